"""The test modules' assertions rewritten once for the whole run, by the controller, before the workers start.

pytest rewrites the ``assert`` statements of every test module it imports
and caches the result as a pyc beside it, unless bytecode writing is off
(``PYTHONDONTWRITEBYTECODE``, common in containers and CI images): then each
xdist worker rewrites every module again on its own, about 6 s of CPU a
worker here, before its first test.  :func:`rewrite_before_workers` writes
those pyc files once, on two cores, where pytest itself reads them (a pyc
is read even when bytecode writing is off, and it is keyed on the source's
hash, so an edited file is rewritten again as usual).  It relies on
pytest's own rewrite functions; if they are not there (another pytest) it
does nothing and the workers rewrite as before.
"""

from __future__ import annotations

import fnmatch
import os
import sys
from pathlib import Path


def _targets(config, root: Path) -> list[Path]:
    patterns = list(config.getini("python_files")) + ["conftest.py"]
    return sorted(p for p in root.rglob("*.py")
                  if "__pycache__" not in p.parts and any(fnmatch.fnmatch(p.name, pat) for pat in patterns))


def _rewrite(config, files: list[Path]) -> None:
    from _pytest.assertion.rewrite import PYC_TAIL, _read_pyc, _rewrite_test, _write_pyc, get_cache_dir
    from _pytest.assertion import assertstate_key

    state = config.stash[assertstate_key]
    for fn in files:
        pyc = get_cache_dir(fn) / (fn.name[:-3] + PYC_TAIL)
        if _read_pyc(fn, pyc) is not None:  # already current
            continue
        try:
            pyc.parent.mkdir(exist_ok=True)
            source_hash, co = _rewrite_test(fn, config)
        except (OSError, SyntaxError):  # pytest reports it where it imports the module
            continue
        _write_pyc(state, co, source_hash, pyc)


def rewrite_before_workers(config, root: Path) -> None:
    """In the xdist controller of a run with workers and bytecode writing off: write the rewritten pyc of every test
    module and conftest under ``root``, half in a forked child, half here."""
    if not sys.dont_write_bytecode or config.getoption("assertmode", "rewrite") != "rewrite":
        return
    if hasattr(config, "workerinput") or not getattr(config.option, "numprocesses", None):
        return
    try:
        import _pytest.assertion.rewrite as rewrite
        from _pytest.assertion import assertstate_key

        if assertstate_key not in config.stash or not all(
                hasattr(rewrite, name) for name in ("PYC_TAIL", "_read_pyc", "_rewrite_test", "_write_pyc", "get_cache_dir")):
            return
    except ImportError:
        return
    files = _targets(config, root)
    pid = os.fork() if hasattr(os, "fork") else -1
    if pid == 0:  # the child: every other file, then gone without running any exit handler of pytest's
        try:
            _rewrite(config, files[1::2])
        finally:
            os._exit(0)
    _rewrite(config, files[0::2] if pid > 0 else files)
    if pid > 0:
        os.waitpid(pid, 0)
