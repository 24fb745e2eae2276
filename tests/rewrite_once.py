"""The checkout's bytecode written once for the whole run, by the controller, before the workers start.

pytest rewrites the ``assert`` statements of every test module it imports
and caches the result as a pyc beside it, and Python caches each module it
compiles, unless bytecode writing is off (``PYTHONDONTWRITEBYTECODE``, common
in containers and CI images).  Then each xdist worker rewrites every test
module again on its own (about 6 s of CPU a worker here) and every process
the suite starts from the checkout compiles the package's modules again
(about 0.2 s each).  :func:`compile_before_workers` writes those files once,
on two cores, where pytest and Python read them (a pyc is read even when
writing is off; pytest's is keyed on the source's hash, Python's on its
modification time and size, so an edited file is compiled again as usual).
The rewriting relies on pytest's own functions; if they are not there
(another pytest) the test modules are left to the workers as before.
"""

from __future__ import annotations

import fnmatch
import os
import sys
from pathlib import Path


def _rewritten(config, root: Path) -> list[Path]:
    """The test modules and conftest files under ``root``, if pytest's rewrite functions are there to write them."""
    if config.getoption("assertmode", "rewrite") != "rewrite":
        return []
    try:
        import _pytest.assertion.rewrite as rewrite
        from _pytest.assertion import assertstate_key
    except ImportError:
        return []
    if assertstate_key not in config.stash or not all(
            hasattr(rewrite, name) for name in ("PYC_TAIL", "_read_pyc", "_rewrite_test", "_write_pyc", "get_cache_dir")):
        return []
    patterns = list(config.getini("python_files")) + ["conftest.py"]
    return sorted(p for p in root.rglob("*.py")
                  if "__pycache__" not in p.parts and any(fnmatch.fnmatch(p.name, pat) for pat in patterns))


def _rewrite(config, fn: Path) -> None:
    from _pytest.assertion import assertstate_key
    from _pytest.assertion.rewrite import PYC_TAIL, _read_pyc, _rewrite_test, _write_pyc, get_cache_dir

    pyc = get_cache_dir(fn) / (fn.name[:-3] + PYC_TAIL)
    if _read_pyc(fn, pyc) is not None:  # already current
        return
    try:
        pyc.parent.mkdir(exist_ok=True)
        source_hash, co = _rewrite_test(fn, config)
    except (OSError, SyntaxError):  # pytest reports it where it imports the module
        return
    _write_pyc(config.stash[assertstate_key], co, source_hash, pyc)


def _work(config, items: list[tuple[str, Path]]) -> None:
    import compileall

    for kind, fn in items:
        if kind == "rewrite":
            _rewrite(config, fn)
        else:  # skipped when its pyc is current; an error is Python's to report where the module is imported
            compileall.compile_file(str(fn), quiet=2)


def compile_before_workers(config, root: Path) -> None:
    """In the xdist controller of a run with workers and bytecode writing off: rewrite every test module and conftest
    under ``root / "tests"`` and compile every module of ``root / "symbolic_friction"``, half in a forked child,
    half here."""
    if not sys.dont_write_bytecode or hasattr(config, "workerinput") or not getattr(config.option, "numprocesses", None):
        return
    items = [("rewrite", p) for p in _rewritten(config, root / "tests")]
    items += [("compile", p) for p in sorted((root / "symbolic_friction").rglob("*.py")) if "__pycache__" not in p.parts]
    pid = os.fork() if hasattr(os, "fork") else -1
    if pid == 0:  # the child: every other file, then gone without running any exit handler of pytest's
        try:
            _work(config, items[1::2])
        finally:
            os._exit(0)
    _work(config, items[0::2] if pid > 0 else items)
    if pid > 0:
        os.waitpid(pid, 0)
