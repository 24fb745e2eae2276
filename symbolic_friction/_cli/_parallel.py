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

Once its sections are done, the child takes work from the *back* of a list
of named functions (``tail``: ``check``'s obligations) that this process works
through from the front, and this process asks for the result of each item
the child took by name when it reaches it (:class:`Inbox`);
each item is claimed under a lock (:class:`Claims`) by whichever process gets
there first, so the split adapts to how fast each core really is (a busy
machine, a slower section) and no item is done twice or left out.

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

__all__ = ["ENV", "parallel_allowed", "run_sections", "Inbox", "Claims"]

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


class Claims:
    """Who does each item of a list: this process claims from the front, the child from the back (under one lock).

    Items named together in ``together`` (work they share, such as one derivation) are claimed as one, by the
    process that reaches any of them first; the other passes over the rest of the group.  The child stops when
    it reaches the item this process is at, so every item is done exactly once.
    """

    CAPACITY = 1024
    """Items a list named only after the fork (:meth:`publish`) may have; a longer one is all this process's."""

    def __init__(self, ctx: Any, names: list[str] | None = None, together: tuple[tuple[str, ...], ...] = ()) -> None:
        self.together = tuple(together)
        self.names: tuple[str, ...] = ()
        self.groups: list[tuple[int, ...]] = []
        self.lock = ctx.Lock()
        self.owner = ctx.RawArray("b", self.CAPACITY if names is None else len(names))  # 0 free, 1 this process, 2 the child
        self.front = ctx.RawValue("i", 0)  # this process has reached the items before it
        self.back = ctx.RawValue("i", 0)  # the child looks at the items before it, last first
        self.count = ctx.RawValue("i", 0)  # the items the child may claim (0 until published)
        self.digest = ctx.RawValue("I", 0)  # of the published names: the child claims only from the same list
        self.published = ctx.Event()
        if names is not None:
            self.publish(names)

    def _name(self, names: tuple[str, ...]) -> None:
        self.names = names
        self.groups = [tuple(names.index(n) for n in group if n in names) for group in self.together]

    def publish(self, names: list[str]) -> None:
        """Name the items (this process, after the fork when the list is costly to build: ``check``'s obligations
        import sympy, which the child's first sections do not need)."""
        names = tuple(names)
        self._name(names)
        with self.lock:
            self.count.value = self.back.value = len(names) if len(names) <= len(self.owner) else 0
            self.digest.value = _digest(names)
        self.published.set()

    def adopt(self, names: list[str], *, timeout: float = 600.0) -> bool:
        """In the child: whether it may claim from ``names``, its own copy of the list, once this process has
        published it: only if it is the same list (same length and digest), else it claims nothing."""
        names = tuple(names)
        if not self.published.wait(timeout) or self.count.value != len(names) or self.digest.value != _digest(names):
            return False
        self._name(names)
        return True

    def _members(self, k: int) -> tuple[int, ...]:
        return next((g for g in self.groups if k in g), (k,))

    def take_front(self, name: str) -> bool:
        """Whether this process is to do ``name`` (False: the child has claimed it; ask the inbox)."""
        k = self.names.index(name)
        if k >= self.count.value:  # not shared (a list too long to share): this process's
            return True
        with self.lock:
            self.front.value = max(self.front.value, k + 1)
            if self.owner[k] == 0:
                for j in self._members(k):
                    self.owner[j] = 1
            return self.owner[k] == 1

    def take_back(self) -> tuple[int, ...] | None:
        """The indices of the last free item (with the items claimed together with it), now the child's; None
        once the child has reached the items this process has reached."""
        with self.lock:
            while self.back.value > self.front.value:
                k = self.back.value - 1
                self.back.value = k
                if self.owner[k] != 0:  # claimed with an item of its group
                    continue
                members = self._members(k)
                for j in members:
                    self.owner[j] = 2
                return members
            return None


def _digest(names: tuple[str, ...]) -> int:
    import zlib

    return zlib.crc32("\0".join(names).encode())


def _send_result(send: Any, key: str, work: Callable[[], Any]) -> None:
    try:
        send.send(("claimed", key, work()))
    except Exception as exc:  # the parent reports the error where it needed the value
        send.send(("claimed", key, exc if _picklable(exc) else RuntimeError(repr(exc))))


def _child(makers: list[Maker], args: argparse.Namespace, send: Any,
           tail: Any = (), claims: Claims | None = None,
           context: Callable[[], Any] | None = None) -> None:
    import contextlib

    from .._infra.output import set_verbosity

    set_verbosity(0)  # no progress bar or note from here: this process's output is the parent's to print
    sections = [(make, _safe(make, args)) for make in makers]
    # the tail before the sections: a large section could fill the pipe, which the parent reads only when it needs
    # a value, and the child would then claim nothing while this process does every item itself
    with context() if context is not None else contextlib.nullcontext():
        if callable(tail):  # built after the fork, in each process (:meth:`Claims.adopt`)
            try:
                tail = tail()
            except Exception:  # this process then does every item (its own error is reported there)
                tail = []
            if claims is not None and not claims.adopt([name for name, _ in tail]):
                claims = None
        while claims is not None and (taken := claims.take_back()) is not None:
            for k in taken:
                _send_result(send, *tail[k])
    for make, section in sections:
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
                 tail: Any = None, together: tuple[tuple[str, ...], ...] = (),
                 context: Callable[[], Any] | None = None) -> Iterator[Section]:
    """Each section of ``makers``, in order (module docstring).

    With the child, ``args.inbox`` is an :class:`Inbox` holding the results of
    the items of ``tail`` the child claimed, and ``args.claims``
    the :class:`Claims` of ``tail`` (both ``None`` when everything runs here: do
    the work yourself).  Items named in one tuple of ``together`` are claimed
    as one; the child works through the tail within ``context()`` if given.
    ``tail`` is a list ``[(name, work)]``, or a function that returns it: each
    process then calls it after the fork (this one before its first section),
    so what building it imports is not waited for before the child starts,
    and is never imported when everything runs here.
    """
    import gc

    if parallel is None:
        parallel = parallel_allowed()
    args.inbox = None
    args.claims = None
    # The sections build hundreds of thousands of short-lived sympy expressions and Fractions and almost no
    # reference cycles, so the cyclic collector's passes (over every object sympy's import made) find little and
    # cost about 7 % of check's CPU (measured: 5.62 -> 5.22 CPU-s, median of 6, for about 16 MB more at the
    # peak); it is off while they run, in both processes (the child inherits it), and on again after.
    collecting = gc.isenabled()
    gc.disable()
    try:
        yield from _run(makers, args, parallel, tail, together, context)
    finally:
        if collecting:
            gc.enable()


def _run(makers: list[Maker], args: argparse.Namespace, parallel: bool, tail: Any,
         together: tuple[tuple[str, ...], ...], context: Callable[[], Any] | None) -> Iterator[Section]:
    if not parallel or len(makers) < 2:
        for make in makers:
            yield _safe(make, args)
        return
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    quiet = copy.copy(args)
    quiet.json = True  # the child streams nothing: this process prints its tables, in order
    lazy = callable(tail)
    if lazy:
        claims: Claims | None = Claims(ctx, together=together)  # named below, once this process has built the list
    else:
        tail = list(tail or [])
        claims = Claims(ctx, [name for name, _ in tail], together) if tail else None
    proc = ctx.Process(target=_child, args=(makers[1:], quiet, send, tail, claims, context),
                       daemon=True)
    proc.start()
    send.close()
    if lazy:
        try:
            names = [name for name, _ in tail()]
        except Exception:  # the first section meets the same error and reports it; the child claims nothing
            names = []
        claims.publish(names)  # type: ignore[union-attr]
    inbox = Inbox(recv, proc)
    args.inbox = inbox
    args.claims = claims
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
        args.claims = None
        recv.close()
        proc.join(timeout=5)
        if proc.is_alive():
            proc.terminate()
