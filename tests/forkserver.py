"""Run the command line many times, cheaply: one warm interpreter forks a child per run.

Starting a fresh ``python -m symbolic_friction`` per hostile input costs an
interpreter start and the imports of numpy, sympy and python-flint every
time (about a quarter of a second of CPU each).  :class:`ForkServer` starts
one server process that imports the command line and the heavy libraries
once, then forks a child per request.  The child is the command line as a
user runs it: its own working directory and environment, stdin from
``/dev/null``, stdout and stderr captured through pipes, an address-space limit
(``RLIMIT_AS``), its own process group, killed (``SIGKILL``, the whole group)
when it outlives the timeout.  Its exit status follows the interpreter's
rules: ``SystemExit`` as Python maps it, an uncaught exception prints its
traceback and exits 1.

What a fork cannot reproduce (an environment read at interpreter start-up,
such as ``PYTHONIOENCODING``) needs :func:`run_fresh`, a real subprocess.

The server is single-threaded (it never starts a thread), so forking it is safe.
"""

from __future__ import annotations

import gc
import io
import os
import pickle
import resource
import select
import signal
import struct
import subprocess
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PRELOAD = (
    "numpy", "sympy", "flint",
    "symbolic_friction._cli.main", "symbolic_friction._certify", "symbolic_friction._certify.templates",
    "symbolic_friction._studies.scenes", "symbolic_friction._crosscheck", "symbolic_friction._hunting._study",
    "symbolic_friction._obligations", "symbolic_friction._studies.tradeoff", "symbolic_friction._extremes",
    "symbolic_friction._infra.junit",
    # what many runs import on their way to refusing the input (measured over the hostile cases: every run imports
    # _infra.output, about a hundred each the certificate templates, gain maps, the independent verifier, the
    # simulators, the configuration reader); imported once here instead of in every child
    "symbolic_friction._infra.output", "symbolic_friction._infra.config", "symbolic_friction._certify.choose",
    "symbolic_friction._studies.gainmap", "symbolic_friction._studies.gainmap_run", "symbolic_friction.independent",
    "symbolic_friction.independent.paper", "symbolic_friction._simulation.friction", "symbolic_friction._simulation.event",
    "symbolic_friction._simulation.moreau", "symbolic_friction._simulation.regularized",
    "symbolic_friction._studies.figures_run", "symbolic_friction._studies.crosscheck_figures",
    "symbolic_friction._studies.gainmap_plot", "numpy.random", "numpy.ma",
    # not scipy.linalg, scipy.optimize, matplotlib.pyplot: of the ~1,050 hostile runs only two import them (the
    # kernel's warm-up and one drawing hunting run), while their 47 MB of the server's 115 cost every fork and exit
    # (about 2 ms a run: 25 -> 23 s for the two hostile modules)
)
"""Imported once by the server; everything else a command needs is imported by the child, as in a real run.

The list only saves time: a child imports whatever is missing, so a command's behaviour does not depend on it
(:func:`tests.test_hostile_options.test_fork_and_fresh_interpreter_agree` holds forks to fresh interpreters)."""


@dataclass(frozen=True)
class Run:
    """One run of the command line: exit status (negative: killed by that signal), output, wall time."""

    returncode: int
    stdout: bytes
    stderr: bytes
    seconds: float
    timed_out: bool = False


def _base_env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO) + os.pathsep + env.get("PYTHONPATH", "")
    env.pop("COLUMNS", None)
    return env


def run_fresh(argv: list[str], *, cwd: str, env: dict[str, str] | None = None, timeout: float, memory: int) -> Run:
    """``python -m symbolic_friction ARGV`` in a new interpreter (for what a fork cannot reproduce)."""
    full = _base_env()
    full.update(env or {})
    start = time.perf_counter()
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "symbolic_friction", *argv], capture_output=True, timeout=timeout, cwd=cwd,
            env=full, stdin=subprocess.DEVNULL,
            preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (memory, memory)),
        )
    except subprocess.TimeoutExpired as exc:
        return Run(-signal.SIGKILL, exc.stdout or b"", exc.stderr or b"", time.perf_counter() - start, True)
    return Run(proc.returncode, proc.stdout, proc.stderr, time.perf_counter() - start)


# --- the wire: a 4-byte length, then a pickle -------------------------------------------------------------

def _send(stream, obj) -> None:
    data = pickle.dumps(obj)
    stream.write(struct.pack("!I", len(data)) + data)
    stream.flush()


def _receive(stream):
    head = stream.read(4)
    if len(head) < 4:
        raise EOFError("fork server closed its pipe")
    (size,) = struct.unpack("!I", head)
    return pickle.loads(stream.read(size))


class ForkServer:
    """A warm interpreter that runs ``symbolic-friction ARGV`` in a forked child per :meth:`run`."""

    def __init__(self) -> None:
        self._proc: subprocess.Popen | None = None

    def _start(self) -> subprocess.Popen:
        if self._proc is None or self._proc.poll() is not None:
            self._proc = subprocess.Popen(
                [sys.executable, "-c", "import sys; sys.path.insert(0, sys.argv[1]); import forkserver; forkserver.serve()",
                 str(Path(__file__).parent)],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=_base_env(), cwd=tempfile.gettempdir(),
            )
            assert _receive(self._proc.stdout) == "ready"
        return self._proc

    def run(self, argv: list[str], *, cwd: str, env: dict[str, str] | None = None, timeout: float, memory: int) -> Run:
        proc = self._start()
        _send(proc.stdin, {"argv": list(argv), "cwd": cwd, "env": dict(env or {}), "timeout": timeout, "memory": memory})
        return Run(**_receive(proc.stdout))  # a plain dict on the wire: the server imports this file by another name

    def close(self) -> None:
        if self._proc is not None and self._proc.poll() is None:
            self._proc.stdin.close()
            try:
                self._proc.wait(timeout=10)
            except subprocess.TimeoutExpired:  # pragma: no cover
                self._proc.kill()
                self._proc.wait()
        self._proc = None


# --- the server side ---------------------------------------------------------------------------------------

def serve() -> None:  # pragma: no cover - runs in the server process
    """Import once, then answer requests on stdin/stdout until stdin closes."""
    import importlib

    wire_in = os.fdopen(os.dup(0), "rb")
    wire_out = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # a stray print of the server must not corrupt the wire
    for name in PRELOAD:
        importlib.import_module(name)
    from symbolic_friction._certify._schema import _validator
    from symbolic_friction._certify.templates import builtin_templates
    from symbolic_friction._cli.main import shared_parser
    from symbolic_friction._obligations import all_obligations

    all_obligations()  # the registry imports every obligation module: check's --only and --config cases need it
    shared_parser()  # every command module, and the parser each child's main() parses with (built once, here)
    _validator()  # jsonschema and the certificate schema
    builtin_templates()  # every certificate template's module: verify and certify read them all
    gc.collect()
    gc.freeze()  # the children's collector leaves the server's objects alone: fewer pages copied after each fork
    _send(wire_out, "ready")
    while True:
        try:
            request = _receive(wire_in)
        except EOFError:
            return
        _send(wire_out, _run_one(**request).__dict__)


def _run_one(*, argv: list[str], cwd: str, env: dict[str, str], timeout: float, memory: int) -> Run:  # pragma: no cover
    # pipes, not temporary files: two files created, written, rewound and closed per run cost more than the run
    out_r, out_w = os.pipe()
    err_r, err_w = os.pipe()
    sys.stdout.flush()
    sys.stderr.flush()
    start = time.perf_counter()
    pid = os.fork()
    if pid == 0:
        os.close(out_r)
        os.close(err_r)
        _child(argv, cwd, env, memory, out_w, err_w)
    os.close(out_w)
    os.close(err_w)
    chunks: dict[int, list[bytes]] = {out_r: [], err_r: []}
    try:
        timed_out = _wait(pid, timeout, chunks)
        _, status = os.waitpid(pid, 0)
        seconds = time.perf_counter() - start
        try:
            os.killpg(pid, signal.SIGKILL)  # anything the child started goes with it
        except (ProcessLookupError, PermissionError):
            pass
        for fd in chunks:  # what is left in the pipes: written before the child (and its group) ended
            os.set_blocking(fd, False)
            _read_into(fd, chunks[fd], until_empty=True)
    finally:
        os.close(out_r)
        os.close(err_r)
    code = os.waitstatus_to_exitcode(status)
    return Run(code, b"".join(chunks[out_r]), b"".join(chunks[err_r]), seconds, timed_out)


def _read_into(fd: int, into: list[bytes], *, until_empty: bool = False) -> bool:  # pragma: no cover
    """Read what ``fd`` has (all of it with ``until_empty``, ``fd`` non-blocking); False at end of file."""
    while True:
        try:
            data = os.read(fd, 1 << 16)
        except BlockingIOError:
            return True
        if not data:
            return False
        into.append(data)
        if not until_empty:
            return True


def _wait(pid: int, timeout: float, chunks: dict[int, list[bytes]]) -> bool:  # pragma: no cover
    """Wait for the child at most ``timeout`` seconds, reading its output pipes meanwhile (a full pipe would stall
    it); kill its process group after that.  True if killed.

    The child is not reaped here (the caller's ``waitpid`` does): a pidfd says when it exits, or, where there
    is none (macOS), ``waitid`` with ``WNOWAIT`` is polled.
    """
    deadline = time.monotonic() + timeout
    pidfd = os.pidfd_open(pid) if hasattr(os, "pidfd_open") else None
    reading = list(chunks)
    try:
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                break
            waiting = reading if pidfd is None else [*reading, pidfd]
            ready, _, _ = select.select(waiting, [], [], left if pidfd is not None else min(left, 0.005))
            for fd in ready:
                if fd != pidfd and not _read_into(fd, chunks[fd]):
                    reading.remove(fd)  # end of file: the child closed it (or exited)
            if pidfd is not None:
                exited = pidfd in ready
            else:  # pragma: no cover - platforms without pidfd
                exited = os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None
            if exited:
                return False
    finally:
        if pidfd is not None:
            os.close(pidfd)
    try:
        os.killpg(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    return True


def _child(argv, cwd, env, memory, out_fd, err_fd) -> None:  # pragma: no cover - the forked child
    def run() -> int:
        os.setpgid(0, 0)
        null = os.open(os.devnull, os.O_RDONLY)
        os.dup2(null, 0)
        os.dup2(out_fd, 1)
        os.dup2(err_fd, 2)
        encoding, errors = sys.stdout.encoding, sys.stdout.errors
        sys.stdin = io.TextIOWrapper(io.FileIO(0, "r", closefd=False))
        sys.stdout = io.TextIOWrapper(io.FileIO(1, "w", closefd=False), encoding=encoding, errors=errors)
        sys.stderr = io.TextIOWrapper(io.FileIO(2, "w", closefd=False), encoding=encoding, errors="backslashreplace",
                                      line_buffering=True)
        os.environ.update(env)
        os.chdir(cwd)
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
        from symbolic_friction._cli.main import main

        return main(argv)

    end_as_interpreter(run)


def end_as_interpreter(run) -> None:  # pragma: no cover - a forked child
    """``run()`` in a forked child, ended with the status the interpreter would give: ``run``'s value, ``SystemExit``
    mapped as the interpreter maps it, an uncaught exception printed with its traceback and 1; both streams
    flushed, then ``os._exit`` (a fork of a server must not run the server's clean-up)."""
    code = 1
    try:
        code = run()
    except SystemExit as exc:  # as the interpreter maps it
        if exc.code is None:
            code = 0
        elif isinstance(exc.code, int):
            code = exc.code
        else:
            print(exc.code, file=sys.stderr)
            code = 1
    except BaseException:  # an uncaught exception: a traceback and status 1, as the interpreter does
        traceback.print_exc()
        code = 1
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except BaseException:
                pass
        os._exit(code if isinstance(code, int) and 0 <= code < 256 else 1)
