"""Settings shared by the whole test suite: workers and the order tests are handed out.

The suite runs on every core (``-n auto --dist loadscope`` in ``pyproject.toml``).
``loadscope`` keeps the tests of one module on one worker, so a module-scoped
fixture (a run of ``check``, the extremes matrix, a certificate search, the
reference trajectories of a module) is computed once.  Modules with a test
marked ``slow`` are handed out first, the longest of all (:data:`EARLY`)
before them, so that the longest work starts at once and no worker is left
with a long tail.

``-m "not slow"`` deselects the long runs for a quick local check; the
default run (``.ci/run``) runs everything.
"""

from __future__ import annotations

import os

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
    "tests/test_extremes.py",  # ≈ 75 s alone (the matrix fixture)
    "tests/independent/test_tampered_sup_flow.py",  # ≈ 45 s
    "tests/test_notebooks.py",  # ≈ 45 s
    "tests/test_hostile_options.py",  # ≈ 40 s (933 command lines; none of its tests is slow)
    "tests/test_project_ci.py",  # ≈ 35 s
)
"""The longest modules, longest first: handed out before the other slow ones, which are handed out before the rest.
(A long module handed out last leaves the other worker idle; ``tests/test_hostile_options.py`` and
``tests/test_extremes.py`` are collected near the end.)"""


def pytest_configure(config) -> None:
    """Run every worker with the environment of a plain ``pytest`` run.

    pytest-xdist starts its workers with ``COLUMNS`` set, which would make
    the commands wrap their notes as on a terminal; the tests expect the
    unwrapped lines of a pipe (tests that want a width set ``COLUMNS``
    themselves).
    """
    if os.environ.get("PYTEST_XDIST_WORKER"):
        os.environ.pop("COLUMNS", None)


def pytest_collection_modifyitems(config, items: list[pytest.Item]) -> None:
    """Hand out :data:`EARLY`, then the other modules that hold slow tests, first (stable: otherwise the collection
    order)."""
    slow_modules = {item.nodeid.split("::")[0] for item in items if item.get_closest_marker("slow") is not None}

    def rank(item: pytest.Item) -> int:
        module = item.nodeid.split("::")[0]
        return EARLY.index(module) if module in EARLY else len(EARLY) + (module not in slow_modules)

    items.sort(key=rank)
