"""Settings shared by the whole test suite: workers and the order tests are handed out.

The suite runs on every core (``-n auto --dist loadscope`` in ``pyproject.toml``).
``loadscope`` keeps the tests of one module on one worker, so a module-scoped
fixture (a run of ``check``, the extremes matrix, a certificate search, the
reference trajectories of a module) is computed once.  Modules with a test
marked ``slow`` are handed out first, so that the longest work starts at once
and no worker is left with a long tail.

``-m "not slow"`` deselects the long runs for a quick local check; the
default run (``.ci/run``) runs everything.
"""

from __future__ import annotations

import os

import pytest

# One OpenBLAS thread per process (numpy/scipy read this when first imported; this file is imported before any test
# module, and the commands the tests start inherit it).  scipy.linalg's expm and solve hand even a 3×3 matrix to
# OpenBLAS's thread pool, whose threads spin waiting for each other: with every core already busy (two workers, and
# `check` forking a second process) each call then waits for a time slice, about 60× slower (measured: 2.9 ms instead
# of 50 µs per 3×3 expm beside two busy processes), which made tests of a second alone take minutes in the suite.
# The results do not depend on it (3×3 products are never split between threads); a value set by the caller is kept.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


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
    """Hand out the modules that hold slow tests first (stable: otherwise the collection order)."""
    slow_modules = {item.nodeid.split("::")[0] for item in items if item.get_closest_marker("slow") is not None}
    items.sort(key=lambda item: item.nodeid.split("::")[0] not in slow_modules)
