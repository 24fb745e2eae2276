"""``check``'s sections on both cores: the first in this process, the others meanwhile in a forked one.

The obligations (sympy) and the certificates and cross-check self-test
(cvxpy, numpy) share nothing but their inputs, so on a machine with two
cores the later sections run in a child process (``fork``: it inherits the
arguments, the configuration and any test's patches) while this process
decides and streams the obligations; their results come back through a pipe,
in order, and are printed exactly as a sequential run would print them after
its streamed rows.  Nothing is decided differently: each section is the same
function on the same arguments.  A child that dies without answering makes
its sections fail (never pass).

``SYMBOLIC_FRICTION_JOBS=1`` (or one core, or no ``fork``) runs them one
after the other in this process.
"""

from __future__ import annotations

import argparse
import copy
import os
from collections.abc import Callable, Iterator
from typing import Any

from ._sections import Section, _crashed

__all__ = ["ENV", "parallel_allowed", "run_sections"]

ENV = "SYMBOLIC_FRICTION_JOBS"

Maker = Callable[[argparse.Namespace], Section]


def parallel_allowed() -> bool:
    """Two cores, ``fork`` available, and not switched off by ``SYMBOLIC_FRICTION_JOBS=1``."""
    import multiprocessing

    if os.environ.get(ENV, "").strip() == "1":
        return False
    return (os.cpu_count() or 1) >= 2 and "fork" in multiprocessing.get_all_start_methods()


def _safe(make: Maker, args: argparse.Namespace) -> Section:
    try:
        return make(args)
    except Exception as exc:  # a crashing section fails loudly, it never passes
        return _crashed(make, exc)


def _child(makers: list[Maker], args: argparse.Namespace, send: Any) -> None:
    for make in makers:
        section = _safe(make, args)
        try:
            send.send(section)
        except Exception as exc:  # an unpicklable result: report it, do not hang the parent
            send.send(_crashed(make, exc))
    send.close()


def run_sections(makers: list[Maker], args: argparse.Namespace, *, parallel: bool | None = None) -> Iterator[Section]:
    """Each section of ``makers``, in order (module docstring)."""
    if parallel is None:
        parallel = parallel_allowed()
    if not parallel or len(makers) < 2:
        for make in makers:
            yield _safe(make, args)
        return
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    quiet = copy.copy(args)
    quiet.json = True  # the child streams nothing: this process prints its tables, in order
    proc = ctx.Process(target=_child, args=(makers[1:], quiet, send), daemon=True)
    proc.start()
    send.close()
    try:
        yield _safe(makers[0], args)
        for make in makers[1:]:
            try:
                section = recv.recv()
            except (EOFError, OSError):
                section = _crashed(make, RuntimeError(f"the worker process ended (exit code {proc.exitcode}) without a result"))
            yield section
    finally:
        recv.close()
        proc.join(timeout=5)
        if proc.is_alive():
            proc.terminate()
