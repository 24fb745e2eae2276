"""Settings shared by the whole test suite: workers and the order tests are handed out.

The suite runs on every core (``-n auto --dist loadscope`` in ``pyproject.toml``).
``loadscope`` keeps the tests of one module on one worker, so a module-scoped
fixture (a run of ``check``, the extremes matrix, a certificate search, the
reference trajectories of a module) is computed once.  Modules with a test
marked ``slow`` are handed out first, the longest of all (:data:`EARLY`)
before them, so that the longest work starts at once and no worker is left
with a long tail.  Modules that share a session fixture of seconds
(:data:`SHARED`) are handed out together, as one unit, so that it is computed
once, not once per worker.  While the module held to a wall-clock budget
(:data:`TIMED`) runs, the other workers are handed no module that keeps two
processes busy (:data:`BUSY`).

``-m "not slow"`` deselects the long runs for a quick local check; the
default run (``.ci/run``) runs everything.
"""

from __future__ import annotations

import functools
import os
import re
from pathlib import Path

import pytest

# One OpenBLAS thread per process (numpy and scipy read this when first imported; this file is imported before any
# test module, and the commands, notebook kernels and forks the tests start inherit it).  scipy.linalg's expm and
# solve hand even a 3×3 matrix to OpenBLAS's thread pool, whose threads spin waiting for each other: with every core
# already busy (two workers, and `check` forking a second process) each call waits for time slices, about 60× slower
# (measured: 2.9 ms instead of 50 µs per 3×3 expm beside two busy processes), so that tests taking a second alone
# took minutes in the suite (tests/certify/test_reset_contraction.py).  With two workers on two cores a second
# thread has no core to run on anyway.  Nothing compared depends on it (`check` with it finds every committed
# certificate up to date).  A value the caller set is kept.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

EARLY = (
    "tests/test_extremes.py",  # ≈ 40 s (the matrix fixture ≈ 33 s)
    "tests/test_hostile_options.py",  # ≈ 33 s with test_hostile_inputs.py (SHARED); 933 command lines, none slow
    "tests/test_notebooks.py",  # ≈ 30 s
    "tests/test_project_ci.py",  # ≈ 27 s
    "tests/commands/test_check.py",  # ≈ 23 s
    "tests/independent/test_tampered_sup_flow.py",  # ≈ 20 s
    "tests/simulation/test_reset.py",  # ≈ 17 s, no test marked slow
    "tests/test_docs.py",  # ≈ 14 s (the Sphinx build), no test marked slow, collected near the end
)
"""The longest modules, longest first (``-n 0`` on a loaded 2-core machine, ``--junitxml``, per module; the SHARED
group's together): handed out before the other slow ones, which are handed out before the rest.  (A long module
handed out last leaves the other worker idle; ``tests/test_hostile_options.py``, ``tests/test_extremes.py`` and
``tests/test_docs.py`` are collected near the end.)  The next longest, about 10 to 13 s each (``test_mutation``,
``test_box``, ``test_figures``, ``test_hostile_api``, the crosscheck reports), come after these."""

SHARED = {
    "crosscheck reports": ("paper_report", "wrong_report"),  # tests/crosscheck/conftest.py: seeded runs, ≈ 15 s
    "fork server": ("fork_server",),  # below: the warm interpreter of the hostile-input modules, ≈ 5 s to start
}
"""Session fixtures several modules use, by the group those modules form: a module whose source names one of them
is handed out with the others of its group (one xdist unit), so the fixture is computed on one worker only."""

TIMED = "tests/test_extremes.py"
"""The module whose fixture is held to a wall-clock budget (the extremes matrix: under 120 s, about 33 s beside one
other busy process).  It is handed out first (:data:`EARLY`), and while it runs the other workers get no :data:`BUSY`
module, so that on two cores it shares them with one other busy process, never with two."""

BUSY = (
    "tests/test_project_ci.py",  # the CI hook and `check` in a user's project: `check` forks a second process
    "tests/test_mutation.py",  # the mutation runner's `check --json` runs
    "tests/commands/test_check.py",  # `check` as a command
    "tests/crosscheck/test_selftest.py",  # check's cross-check section
    "tests/crosscheck/test_overshoot.py",
    "tests/commands/test_figures.py",  # figures drawn by a pool of two (--jobs 2)
    "tests/simulation/test_event_buffer.py",
)
"""Modules whose tests keep two processes busy at once for much of their time (measured in a whole run: on average
1.2 to 1.8 runnable threads in the worker's process tree, sampled every 0.2 s, where the other modules stay at one,
the worker or a child it waits for)."""

ROOT = Path(__file__).resolve().parents[1]


@functools.cache
def shared_group(module: str) -> str | None:
    """The :data:`SHARED` group of ``module`` (a path relative to the checkout), or ``None``."""
    try:
        text = (ROOT / module).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    for group, fixtures in SHARED.items():
        if any(re.search(rf"\b{name}\b", text) for name in fixtures):
            return group
    return None


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """``--dist loadscope`` with the modules of a :data:`SHARED` group as one unit (else one unit per module), and no
    :data:`BUSY` module started beside :data:`TIMED`."""
    if config.getvalue("dist") != "loadscope":
        return None
    from xdist.scheduler import LoadScopeScheduling

    class SharedFixtureScheduling(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            group = shared_group(nodeid.split("::")[0])
            return f"[{group}]" if group else super()._split_scope(nodeid)

        def _assign_work_unit(self, node) -> None:
            """Hand out the next unit, passing over :data:`BUSY` ones while :data:`TIMED` runs on another node."""
            if self._timed_elsewhere(node):
                for scope, unit in self.workqueue.items():
                    if not any(nodeid.split("::")[0] in BUSY for nodeid in unit):
                        self.workqueue.move_to_end(scope, last=False)  # the base class pops the first unit
                        break  # none left: the next BUSY one (a worker is never left idle for this)
            super()._assign_work_unit(node)

        def _timed_elsewhere(self, node) -> bool:
            return any(other is not node and not done and nodeid.split("::")[0] == TIMED
                       for other, units in self.assigned_work.items() for unit in units.values()
                       for nodeid, done in unit.items())

    return SharedFixtureScheduling(config, log)


@pytest.fixture(scope="session")
def fork_server(tmp_path_factory):
    """One warm interpreter (``tests/forkserver.py``) for the hostile-input modules, its numba kernel compiled."""
    from tests.forkserver import ForkServer
    from tests.test_hostile_inputs import warm_jit

    forks = ForkServer()
    warm_jit(forks, tmp_path_factory.mktemp("warm"))  # the kernel's one-time compile is not a case's time
    yield forks
    forks.close()


def pytest_configure(config) -> None:
    """Run every worker with the environment of a plain ``pytest`` run; keep the order below.

    pytest-xdist starts its workers with ``COLUMNS`` set, which would make
    the commands wrap their notes as on a terminal; the tests expect the
    unwrapped lines of a pipe (tests that want a width set ``COLUMNS``
    themselves).
    """
    if os.environ.get("PYTEST_XDIST_WORKER"):
        os.environ.pop("COLUMNS", None)
    # pytest-xdist's loadscope hands out the modules with the most tests first (its --loadscope-reorder, on by
    # default), which puts the few-test long modules (EARLY: one fixture of a minute, five notebooks) last, each
    # then the suite's tail on one worker while the other is idle; the order of
    # pytest_collection_modifyitems below is the one wanted
    if getattr(config.option, "loadscopereorder", False):
        config.option.loadscopereorder = False
    from tests.rewrite_once import compile_before_workers

    compile_before_workers(config, ROOT)


def pytest_collection_modifyitems(config, items: list[pytest.Item]) -> None:
    """Hand out :data:`EARLY`, then the other modules that hold slow tests, first (stable: otherwise the collection
    order).  A :data:`SHARED` group's unit is handed out where its first module is."""
    slow_modules = {item.nodeid.split("::")[0] for item in items if item.get_closest_marker("slow") is not None}

    def rank(item: pytest.Item) -> int:
        module = item.nodeid.split("::")[0]
        return EARLY.index(module) if module in EARLY else len(EARLY) + (module not in slow_modules)

    items.sort(key=rank)


# The trusted base's process-wide memos: what each holds is a value of its key alone, so a run shares them across tests.
# mutmut, though, runs the tests once in its own process and forks each mutant's run from it: inherited full, they
# would answer for a mutated builder, which then never runs (a flow enclosure replaced by ``None`` survived so).
_MEMOS = {
    "symbolic_friction._certify.sup_flow_enclosure": ("_FLOWS", "_SYSTEMS"),
    "symbolic_friction._certify.sup_flow_forms": ("_PLANS", "_SIGNS"),
    "symbolic_friction._obligations._decide": ("_PRINTED",),
    "symbolic_friction._obligations._fastpoly": (),
}


@pytest.fixture(autouse=bool(os.environ.get("MUTANT_UNDER_TEST")))
def _fresh_memos_under_mutmut():
    """Under mutmut (``MUTANT_UNDER_TEST`` set), each test starts with the memos of :data:`_MEMOS` and the
    ``functools`` caches of those modules empty; otherwise this fixture is not used."""
    import importlib
    import sys

    for name, memos in _MEMOS.items():
        module = sys.modules.get(name) or importlib.import_module(name)
        for memo in memos:
            getattr(module, memo).clear()
        for value in list(vars(module).values()):
            if callable(getattr(value, "cache_clear", None)):
                value.cache_clear()
    yield
