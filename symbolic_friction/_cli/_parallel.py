"""``check``'s sections on both cores: the first in this process, the others meanwhile in a forked one.

The obligations (sympy) and the certificates and cross-check self-test
(cvxpy, numpy) share nothing but their inputs, so on a machine with two
cores the later sections run in a child process (``fork``: it inherits the
arguments, the configuration and any test's patches) while this process
decides and streams the obligations; their results come back through a pipe,
in order, and are printed exactly as a sequential run would print them after
its streamed rows.  Nothing is decided differently: each section is the same
function on the same arguments.  If the child dies without answering, this
process decides what it left undone itself (so a section is never lost, and
never passes unless decided).

The child can also take work *ahead* of its sections (``ahead``: named
functions, e.g. the costliest obligation) so that both cores stay busy; this
process asks for each result by name when it reaches it (:class:`Inbox`).

``SYMBOLIC_FRICTION_JOBS=1`` (or one core, or a platform other than Linux,
where ``fork`` is unavailable or unsafe with system libraries, or a process
that already runs other threads, whose locks a forked child would inherit
held, or that has loaded numba, whose threading layers do not survive a fork)
runs them one after the other in this process.
"""

from __future__ import annotations

import argparse
import copy
import os
from collections.abc import Callable, Iterator
from typing import Any

from ._sections import Section, _crashed

__all__ = ["ENV", "parallel_allowed", "run_sections", "Inbox"]

ENV = "SYMBOLIC_FRICTION_JOBS"

Maker = Callable[[argparse.Namespace], Section]


def parallel_allowed() -> bool:
    """Two cores, Linux (``fork``), one thread, and not switched off by ``SYMBOLIC_FRICTION_JOBS=1``."""
    import multiprocessing
    import sys
    import threading

    if os.environ.get(ENV, "").strip() == "1" or not sys.platform.startswith("linux"):
        return False
    if threading.active_count() > 1 or "numba" in sys.modules:
        return False
    return (os.cpu_count() or 1) >= 2 and "fork" in multiprocessing.get_all_start_methods()


def _safe(make: Maker, args: argparse.Namespace) -> Section:
    try:
        return make(args)
    except Exception as exc:  # a crashing section fails loudly, it never passes
        return _crashed(make, exc)


def _child(makers: list[Maker], args: argparse.Namespace, send: Any, ahead: dict[str, Callable[[], Any]]) -> None:
    from .._infra.output import set_verbosity

    set_verbosity(0)  # no progress bar or note from here: this process's output is the parent's to print
    for key, work in ahead.items():
        try:
            send.send(("ahead", key, work()))
        except Exception as exc:  # the parent reports the error where it needed the value
            send.send(("ahead", key, exc if _picklable(exc) else RuntimeError(repr(exc))))
    for make in makers:
        section = _safe(make, args)
        try:
            send.send(("section", make.__name__, section))
        except Exception as exc:  # an unpicklable result: report it, do not hang the parent
            send.send(("section", make.__name__, _crashed(make, exc)))
    send.close()


def _picklable(value: Any) -> bool:
    import pickle

    try:
        pickle.dumps(value)
    except Exception:
        return False
    return True


class Inbox:
    """The child's messages, read in order and kept until asked for by ``(kind, name)``."""

    def __init__(self, recv: Any, proc: Any) -> None:
        self.recv, self.proc = recv, proc
        self.kept: dict[tuple[str, str], Any] = {}

    def get(self, kind: str, name: str) -> Any:
        """The value sent for ``(kind, name)``; raises :class:`RuntimeError` if the child ended without it."""
        while (kind, name) not in self.kept:
            try:
                got_kind, got_name, value = self.recv.recv()
            except (EOFError, OSError):
                raise RuntimeError(f"the worker process ended (exit code {self.proc.exitcode}) without a result") from None
            self.kept[got_kind, got_name] = value
        value = self.kept.pop((kind, name))
        if isinstance(value, BaseException):
            raise value
        return value


def run_sections(makers: list[Maker], args: argparse.Namespace, *, parallel: bool | None = None,
                 ahead: dict[str, Callable[[], Any]] | None = None) -> Iterator[Section]:
    """Each section of ``makers``, in order (module docstring).

    With the child, ``args.inbox`` is an :class:`Inbox` holding the results of
    ``ahead`` (``None`` when everything runs here: do the work yourself).
    """
    if parallel is None:
        parallel = parallel_allowed()
    args.inbox = None
    if not parallel or len(makers) < 2:
        for make in makers:
            yield _safe(make, args)
        return
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    quiet = copy.copy(args)
    quiet.json = True  # the child streams nothing: this process prints its tables, in order
    proc = ctx.Process(target=_child, args=(makers[1:], quiet, send, dict(ahead or {})), daemon=True)
    proc.start()
    send.close()
    inbox = Inbox(recv, proc)
    args.inbox = inbox
    try:
        yield _safe(makers[0], args)
        for make in makers[1:]:
            try:
                section = inbox.get("section", make.__name__)
            except RuntimeError as exc:  # the worker is gone: decide it here
                section = _safe(make, args)
                section.notes.append(f"note: decided in the main process ({exc})")
            yield section
    finally:
        args.inbox = None
        recv.close()
        proc.join(timeout=5)
        if proc.is_alive():
            proc.terminate()
