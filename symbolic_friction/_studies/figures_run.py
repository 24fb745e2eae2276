"""The figures in parallel: every figure, and every task of a split figure, is one unit of work for a pool of
processes; a split figure is drawn in the calling process once its tasks are done.

The units start longest first (their ``cost``), so that the slow computations (the search for the worst
ISS selection, the extremes matrix) overlap with everything else.  Each unit computes what the sequential
run computes, with the same arguments and seeds, so the files are the same; only the order in which they
are written changes.  Processes are forked (the parent's imports, and the compiled kernel, are inherited);
where fork is not available the figures run one after the other.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Sequence

from .figures_registry import FigureSpec, Task

__all__ = ["Unit", "units", "run_parallel", "can_fork", "HEARTBEAT"]

HEARTBEAT = 1.0
"""Seconds between two redraws of the progress display while units run (so no long gap is silent)."""


@dataclass(frozen=True)
class Unit:
    """One unit of work: a whole figure (``index`` is ``None``) or task ``index`` of a split figure."""

    figure: str
    index: int | None
    label: str
    cost: float
    task: Task | None = None


def units(specs: Sequence[FigureSpec]) -> list[Unit]:
    """The units of ``specs``, longest first (stable: equal costs keep the registry's order)."""
    out: list[Unit] = []
    for spec in specs:
        if spec.tasks is None:
            out.append(Unit(spec.name, None, spec.name, spec.cost))
        else:
            out += [Unit(spec.name, i, t.label, t.cost, t) for i, t in enumerate(spec.tasks())]
    return sorted(out, key=lambda u: -u.cost)


def can_fork() -> bool:
    """Whether this platform forks processes (the parallel run needs it)."""
    import multiprocessing as mp

    try:
        mp.get_context("fork")
    except ValueError:
        return False
    return True


def _run_task(task: Task) -> Any:
    return task.run()


def _warm_up() -> None:
    """Import in the parent what every child needs, so that each forked child does not import it again."""
    import matplotlib

    from .._simulation import _jit, event

    matplotlib.use("Agg")
    import matplotlib.pyplot  # noqa: F401
    if _jit.jit_enabled():
        _jit.compiled()  # numba and the kernel's modules, imported once and inherited
        # numba loads the machine code at a function's first call, in the process that makes it: made here, not
        # again in each forked child (0.4 s a child)
        event.preload_compiled()


def run_parallel(
    out: Path,
    specs: Sequence[FigureSpec],
    formats: tuple[str, ...],
    *,
    jobs: int,
    drawn: Callable[..., list[Path]],
    draw_whole: Callable[[str, Path, tuple[str, ...]], list[Path]],
    on_written: Callable[[Path], Any] | None = None,
    progress: Any = None,
) -> list[Path]:
    """Run the units of ``specs`` in ``jobs`` forked processes; return the files, figure by figure in ``specs``' order.

    ``drawn(out, spec, formats, results)`` draws a split figure here from its tasks' results;
    ``draw_whole(name, out, formats)`` (a module-level function: the pool sends it by name) draws a whole
    figure in a child.  ``progress`` (a :class:`~symbolic_friction._infra.progress.Progress` over
    ``len(units(specs))``) is advanced per unit and redrawn every :data:`HEARTBEAT` seconds with the units
    still running.  Raises ``ValueError`` where processes cannot be forked.
    """
    import multiprocessing as mp
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    ctx = mp.get_context("fork")
    by_name = {s.name: s for s in specs}
    todo = units(specs)
    results: dict[str, list[Any]] = {s.name: [None] * len(s.tasks()) for s in specs if s.tasks is not None}
    left = {name: len(r) for name, r in results.items()}
    files: dict[str, list[Path]] = {}
    _warm_up()
    started: dict[Any, float] = {}
    with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
        futures = {}
        for u in todo:
            f = pool.submit(draw_whole, u.figure, out, formats) if u.task is None else pool.submit(_run_task, u.task)
            futures[f] = u
        pending = set(futures)
        try:
            while pending:
                done, pending = wait(pending, timeout=HEARTBEAT, return_when=FIRST_COMPLETED)
                now = time.perf_counter()
                for f in done:
                    u = futures[f]
                    value = f.result()  # a unit's error is the run's error
                    new: list[Path] = []
                    if u.task is None:
                        new = files[u.figure] = value
                    else:
                        results[u.figure][u.index] = value
                        left[u.figure] -= 1
                        if left[u.figure] == 0:  # every task of the figure is done: draw it here
                            new = files[u.figure] = drawn(out, by_name[u.figure], formats, results.pop(u.figure))
                    if on_written is not None:
                        for path in new:
                            on_written(path)
                    if progress is not None:
                        progress.update()
                if progress is not None:
                    running = [f for f in pending if f.running()]
                    for f in running:
                        started.setdefault(f, now)
                    shown = ", ".join(f"{futures[f].label} {now - started[f]:.0f} s" for f in running)
                    progress.note(f"running {shown}" if shown else "")
        except BaseException:
            for f in pending:
                f.cancel()
            raise
    return [path for s in specs for path in files.get(s.name, [])]
