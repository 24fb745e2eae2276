"""Start the notebooks' Jupyter kernels cheaply: one warm interpreter forks a kernel per notebook.

A kernel started as its kernel spec says (``python -m ipykernel_launcher -f …``)
spends about 0.7 s of CPU before it runs a cell, nearly all of it importing
ipykernel, IPython, zmq, tornado and debugpy.  :class:`KernelForks` starts one
server process that imports these once and forks a child per kernel; the
child is the kernel as ``ipykernel_launcher`` runs it: the
command's arguments, the environment and working directory jupyter_client
gives it, stdin from ``/dev/null``, its own process group (the kernel
manager signals the group), ``sys.path`` without the launch directory (which
IPython adds back as ``''``).  :class:`ForkedKernelManager` is jupyter_client's
kernel manager with this one launch step replaced; the connection file,
the ports, the messages and the shutdown are jupyter_client's own.

The server imports the kernel's own start-up and the libraries and package
modules the notebooks import (:data:`LIBRARIES`: about 0.7 to 1.3 s of CPU
less per notebook), never running any of their code: an import only defines
things, so a notebook that imports one finds what a fresh import gives it.
Two are left to the kernel, as for a user, because importing them changes
what a notebook does: matplotlib reads ``MPLBACKEND``, which ipykernel sets
when the kernel starts, and once numba is imported the package runs small
simulations with its compiled kernel and ``check`` stops forking.  The
random states seeded on import (Python's, numpy's, sympy's) are seeded
again in each kernel, as a fresh interpreter draws its own.  The one setting
ipykernel reads from the environment when imported (``JPY_PARENT_PID``, the
kernels' parent) is in the server's environment already, and a kernel whose
``PYTHONPATH`` differs from the server's (which would have imported other
modules) is refused; the server never starts a thread and never runs a
kernel itself, so every child starts from the state a fresh interpreter has
after the same imports.  ``tests/test_notebooks.py`` holds a forked kernel to
one started as a subprocess.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import tempfile
import time

from jupyter_client.manager import AsyncKernelManager

try:  # the wire of tests/forkserver.py: a 4-byte length, then a pickle
    from tests.forkserver import _receive, _send
except ImportError:  # the server, started as `import kernel_forks` from this folder
    from forkserver import _receive, _send

PRELOAD = ("ipykernel_launcher", "ipykernel.kernelapp", "ipykernel.ipkernel", "ipykernel.zmqshell")
"""What the server imports once: the kernel's own start-up (measured: 986 modules before the first cell, 0.6 s of CPU)."""

LIBRARIES = (
    "numpy", "scipy.integrate", "scipy.linalg", "scipy.optimize", "sympy", "mpmath", "flint", "jsonschema",
    "symbolic_friction", "symbolic_friction.model", "symbolic_friction.symbolic", "symbolic_friction.studies",
    "symbolic_friction._obligations", "symbolic_friction._certify.templates", "symbolic_friction._crosscheck",
    "symbolic_friction._simulation.event", "symbolic_friction._studies.tradeoff", "symbolic_friction._studies.gainmap_run",
    "symbolic_friction._studies.settling_map", "symbolic_friction._hunting._study",
)
"""What several notebooks import besides matplotlib and numba (module doc), imported once by the server too (measured:
1.2 s of CPU once, 0.4 to 1.0 s less in each notebook's kernel; what a single notebook imports, cvxpy, pandas or
xarray, would only move its cost to the server).  Only saves time: a kernel imports whatever is missing."""

LEFT_TO_THE_KERNEL = ("matplotlib", "numba")
"""Never imported by the server (module doc); :func:`serve` fails if :data:`LIBRARIES` would import one."""


class KernelForks:
    """The client side: a server started on first use, asked to fork a kernel or whether one has ended."""

    def __init__(self) -> None:
        self._proc: subprocess.Popen | None = None

    def _call(self, request: dict):
        if self._proc is not None and self._proc.poll() is not None:  # its kernels' state went with it: no restart
            raise RuntimeError(f"the kernel fork server exited (status {self._proc.returncode})")
        if self._proc is None:
            # the kernels' parent (this process) already in the server's environment: ipykernel reads it when imported
            env = {**os.environ, "JPY_PARENT_PID": str(os.getpid())}
            self._proc = subprocess.Popen(
                [sys.executable, "-c", "import sys; sys.path.insert(0, sys.argv[1]); import kernel_forks; kernel_forks.serve()",
                 os.path.dirname(os.path.abspath(__file__))],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, cwd=tempfile.gettempdir(), env=env,
            )
            assert _receive(self._proc.stdout) == "ready"
        _send(self._proc.stdin, request)
        return _receive(self._proc.stdout)

    def launch(self, cmd: list[str], *, env: dict[str, str], cwd: str) -> ForkedKernel:
        """Fork a kernel for ``cmd`` (``python -m ipykernel_launcher ARGS``)."""
        if cmd[1:3] != ["-m", "ipykernel_launcher"]:
            raise ValueError(f"not an ipykernel command: {cmd}")
        return ForkedKernel(self, self._call({"op": "fork", "args": cmd[3:], "env": env, "cwd": cwd}))

    def close(self) -> None:
        if self._proc is not None and self._proc.poll() is None:
            self._proc.stdin.close()
            self._proc.wait(timeout=10)
        self._proc = None


class ForkedKernel:
    """What jupyter_client's local provisioner uses of a ``Popen``, for a kernel forked by the server."""

    stdin = stdout = stderr = None

    def __init__(self, forks: KernelForks, pid: int) -> None:
        self._forks, self.pid, self.returncode = forks, pid, None

    def poll(self) -> int | None:
        if self.returncode is None:
            self.returncode = self._forks._call({"op": "poll", "pid": self.pid})
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        end = None if timeout is None else time.monotonic() + timeout
        while self.poll() is None:
            if end is not None and time.monotonic() > end:
                raise subprocess.TimeoutExpired(f"kernel {self.pid}", timeout)
            time.sleep(0.01)
        return self.returncode

    def send_signal(self, signum: int) -> None:
        if self.poll() is None:
            os.kill(self.pid, signum)

    def kill(self) -> None:
        self.send_signal(signal.SIGKILL)

    def terminate(self) -> None:
        self.send_signal(signal.SIGTERM)


class ForkedKernelManager(AsyncKernelManager):
    """jupyter_client's kernel manager, launching through :attr:`forks` (set before use) instead of ``Popen``."""

    forks: KernelForks | None = None

    async def _async_launch_kernel(self, kernel_cmd: list[str], **kw) -> None:
        provisioner = self.provisioner
        assert provisioner is not None and self.forks is not None
        cwd = str(kw.get("cwd") or os.getcwd())
        env = dict(kw.get("env") or os.environ)
        env["JPY_PARENT_PID"] = str(os.getpid())  # as jupyter_client's launch_kernel sets it (the kernel's parent poller)
        process = self.forks.launch(kernel_cmd, env=env, cwd=cwd)
        # what LocalProvisioner.launch_kernel records of the process it starts (the child leads its own group)
        provisioner.process, provisioner.pid, provisioner.pgid, provisioner.cwd = process, process.pid, process.pid, cwd
        self._reconcile_connection_info(provisioner.connection_info)


# --- the server side ---------------------------------------------------------------------------------------

def serve() -> None:  # pragma: no cover - runs in the server process
    """Import :data:`PRELOAD`, then answer requests on stdin/stdout until stdin closes."""
    import gc
    import importlib
    import threading

    wire_in = os.fdopen(os.dup(0), "rb")
    wire_out = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # a stray print (of the server or a kernel) must not corrupt the wire
    del sys.path[:2]  # '' (python -c) and this folder: a kernel's sys.path is the interpreter's, as the launcher leaves it
    for name in PRELOAD + LIBRARIES:
        importlib.import_module(name)
    from symbolic_friction._obligations import obligation_modules

    obligation_modules()  # imported by name at run time: every notebook that runs an obligation imports them all
    imported = sorted({name.split(".")[0] for name in sys.modules} & set(LEFT_TO_THE_KERNEL))
    assert not imported, f"the kernel fork server must leave {imported} to the kernels (module doc)"
    assert threading.active_count() == 1, "the kernel fork server must not start threads (they would not survive a fork)"
    python_path = os.environ.get("PYTHONPATH")
    gc.collect()
    gc.freeze()  # the kernels' collector leaves the server's objects alone: fewer pages copied after each fork
    _send(wire_out, "ready")
    children: dict[int, int | None] = {}
    while True:
        try:
            request = _receive(wire_in)
        except EOFError:
            return
        if request["op"] == "fork":
            pid = os.fork()
            if pid == 0:
                wire_in.close()
                wire_out.close()
                _kernel(request["args"], request["env"], request["cwd"], python_path)
            try:
                os.setpgid(pid, pid)  # also done by the child: whichever runs first, the group exists before the reply
            except OSError:
                pass
            children[pid] = None
            _send(wire_out, pid)
        else:
            pid = request["pid"]
            if children.get(pid) is None:
                done, status = os.waitpid(pid, os.WNOHANG)
                if done:
                    children[pid] = os.waitstatus_to_exitcode(status)
            _send(wire_out, children[pid])


def _kernel(args: list[str], env: dict[str, str], cwd: str, python_path: str | None) -> None:  # pragma: no cover
    """Become ``python -m ipykernel_launcher ARGS`` in ``cwd`` with ``env``, in a forked child; never returns.

    ``python_path``: the server's ``PYTHONPATH``, which its imports were found with.
    """
    code = 1
    try:
        if env.get("PYTHONPATH") != python_path:
            raise RuntimeError(f"a kernel with PYTHONPATH={env.get('PYTHONPATH')!r} cannot be forked from a server that "
                               f"imported its modules with PYTHONPATH={python_path!r}")
        os.setpgid(0, 0)
        null = os.open(os.devnull, os.O_RDONLY)
        os.dup2(null, 0)
        os.close(null)
        os.chdir(cwd)
        os.environ.clear()
        os.environ.update(env)
        import random

        random.seed()  # not the server's state: each kernel draws its own, as a fresh interpreter does
        for name in ("numpy.random", "sympy.core.random"):  # the global states those libraries seed when imported
            if name in sys.modules:
                sys.modules[name].seed()
        import ipykernel_launcher

        sys.argv = [ipykernel_launcher.__file__, *args]
        from ipykernel import kernelapp

        kernelapp.launch_new_instance()
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else 1
    except Exception:  # reported as an uncaught exception is: its traceback on stderr, exit status 1
        import traceback

        traceback.print_exc()
    finally:
        os._exit(code)
