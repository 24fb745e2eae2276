"""Settings shared by the whole test suite."""

from __future__ import annotations

import os


def pytest_configure(config) -> None:
    """Run every worker with the environment of a plain ``pytest`` run.

    pytest-xdist starts its workers with ``COLUMNS`` set, which would make
    the commands wrap their notes as on a terminal; the tests expect the
    unwrapped lines of a pipe (tests that want a width set ``COLUMNS``
    themselves).
    """
    if os.environ.get("PYTEST_XDIST_WORKER"):
        os.environ.pop("COLUMNS", None)
