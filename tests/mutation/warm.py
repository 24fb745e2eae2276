"""One warm interpreter for the quick mutation runs: the libraries imported once, a forked child per run.

Each quick run of :mod:`tests.mutation.run` is ``python -m symbolic_friction check …`` on a fresh copy of the
package, in an interpreter of its own that starts and imports numpy, sympy, mpmath, python-flint and jsonschema
before any of the package (about 0.9 CPU-s), the same for every copy.  :class:`Warm` starts one server that imports
those libraries and nothing of the package, then forks a child per run.  The child is the run as
:func:`tests.mutation.run._run` starts it: the copy as working directory, first on ``sys.path`` and in
``PYTHONPATH``, so the package (the mutant included) is imported from the copy, never from the checkout (the
child checks it before it runs anything); ``python -m`` or ``python -c`` as the command says; stdin from
``/dev/null``; the exit status the interpreter would give (``SystemExit`` mapped, an uncaught exception printed
with its traceback and exit 1); killed with its process group after the timeout.  What an interpreter fixes when
it starts (hash seed, flags) is the server's, started with the runs' environment.

The server never starts a thread, so forking it is safe (and ``check`` still forks its own second process).
"""

from __future__ import annotations

import io
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

try:  # the ending of tests/forkserver.py's children: the status the interpreter would give
    from tests.forkserver import end_as_interpreter
except ImportError:  # the server, started as `import warm` from this folder (tests/ for a moment on sys.path)
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    try:
        from forkserver import end_as_interpreter
    finally:
        del sys.path[0]

PRELOAD = ("numpy", "sympy", "mpmath", "flint", "jsonschema")
"""What every ``check`` run imports before it decides anything (measured: the third-party packages in
``sys.modules`` after ``check --json --no-certificates``, scipy and numba not among them)."""


class Warm:
    """The client: :meth:`run` is :func:`subprocess.run` of ``python COMMAND`` in ``cwd``, output as text."""

    def __init__(self) -> None:
        self._proc: subprocess.Popen | None = None

    def __enter__(self) -> Warm:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def run(self, command: list[str], *, cwd: Path, timeout: float) -> subprocess.CompletedProcess:
        if self._proc is None:
            env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
            env.pop("PYTHONPATH", None)  # each child puts its copy first; the server imports nothing of the package
            self._proc = subprocess.Popen(
                [sys.executable, "-c", "import sys; sys.path.insert(0, sys.argv[1]); import warm; warm.serve()",
                 str(Path(__file__).parent)],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env, cwd=tempfile.gettempdir())
            assert self._proc.stdout.readline() == b"ready\n"
        with tempfile.TemporaryDirectory(prefix="sf-warm-") as tmp:
            out, err = Path(tmp, "out"), Path(tmp, "err")
            request = {"command": command, "cwd": str(cwd), "out": str(out), "err": str(err), "timeout": timeout}
            self._proc.stdin.write(json.dumps(request).encode() + b"\n")
            self._proc.stdin.flush()
            reply = json.loads(self._proc.stdout.readline())
            if reply["timed_out"]:
                raise subprocess.TimeoutExpired([sys.executable, *command], timeout)
            text = [io.TextIOWrapper(io.BytesIO(path.read_bytes())).read() for path in (out, err)]  # as text=True
        return subprocess.CompletedProcess([sys.executable, *command], reply["returncode"], *text)

    def close(self) -> None:
        if self._proc is not None:
            self._proc.stdin.close()
            self._proc.wait(timeout=30)
            self._proc.stdout.close()
            self._proc = None


def serve() -> None:  # pragma: no cover - the server process
    """Import :data:`PRELOAD`, then answer one request per line of stdin until it closes."""
    import importlib

    wire_in, wire_out = os.fdopen(os.dup(0), "rb"), os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # a stray print must not corrupt the wire
    for name in PRELOAD:
        importlib.import_module(name)
    assert not any(name.split(".")[0] == "symbolic_friction" for name in sys.modules)
    wire_out.write(b"ready\n")
    wire_out.flush()
    for line in wire_in:
        request = json.loads(line)
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            wire_in.close()
            wire_out.close()
            _child(request["command"], request["cwd"], request["out"], request["err"])
        timed_out = _wait(pid, request["timeout"])
        _, status = os.waitpid(pid, 0)
        try:
            os.killpg(pid, signal.SIGKILL)  # whatever the child started goes with it
        except (ProcessLookupError, PermissionError):
            pass
        reply = {"returncode": os.waitstatus_to_exitcode(status), "timed_out": timed_out}
        wire_out.write(json.dumps(reply).encode() + b"\n")
        wire_out.flush()


def _wait(pid: int, timeout: float) -> bool:  # pragma: no cover - the server process
    """Wait until the child exits (not reaping it) or ``timeout`` passes; then kill its group.  True if killed."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None:
            return False
        time.sleep(0.02)
    os.killpg(pid, signal.SIGKILL)
    return True


def _child(command: list[str], cwd: str, out: str, err: str) -> None:  # pragma: no cover - the forked child
    def run() -> int:
        os.setpgid(0, 0)
        for fd, path, flags in ((0, os.devnull, os.O_RDONLY), (1, out, os.O_WRONLY | os.O_CREAT | os.O_TRUNC),
                                (2, err, os.O_WRONLY | os.O_CREAT | os.O_TRUNC)):
            opened = os.open(path, flags, 0o600)
            os.dup2(opened, fd)
            os.close(opened)
        os.environ["PYTHONPATH"] = cwd
        os.chdir(cwd)
        here = str(Path(__file__).parent)
        sys.path[:] = [cwd, cwd, *(p for p in sys.path if p not in ("", here))]  # as `python -m` with PYTHONPATH
        import symbolic_friction

        if Path(symbolic_friction.__file__).resolve().parents[1] != Path(cwd).resolve():
            raise ImportError(f"symbolic_friction imported from {symbolic_friction.__file__}, not from {cwd}")
        option, target, *args = command
        if option == "-m":
            import runpy

            sys.argv = [target, *args]  # run_module puts the module's path first, as `python -m` does
            runpy.run_module(target, run_name="__main__", alter_sys=True)
        elif option == "-c":
            sys.argv = ["-c", *args]
            exec(compile(target, "<string>", "exec"), {"__name__": "__main__", "__builtins__": __builtins__})
        else:
            raise ValueError(f"unsupported command {command!r}")
        return 0

    end_as_interpreter(run)
