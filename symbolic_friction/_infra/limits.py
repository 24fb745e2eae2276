"""Bounds on the work one run may ask for: one definition each, read by the library and by the command line.

The library checks them before anything is simulated or allocated; the command line's options check the
same numbers while parsing, and say them in ``--help``.  This module imports nothing, so a command's
``--help`` stays fast.
"""

from __future__ import annotations

# ``crosscheck`` (_crosscheck/_run.py, _cli/crosscheck.py)
CROSSCHECK_MAX_TRAJECTORIES = 1_000_000
CROSSCHECK_MAX_SAMPLES = 100_000
CROSSCHECK_MAX_TOTAL_SAMPLES = 20_000_000  # twice the default run (10⁵ trajectories × 101 samples); 10⁸ did not finish
CROSSCHECK_MAX_HORIZON = 1e6

# ``measure_tradeoff`` (_studies/tradeoff.py, _cli/tradeoff.py): the horizon, the sample count and the timed
# repeats of one run, the size of a state
TRADEOFF_MAX_T_END = 1e3  # T = 1e4 took minutes even with --quick
TRADEOFF_MAX_SAMPLES = 100_000
TRADEOFF_MAX_REPEATS = 1000
TRADEOFF_MAX_STATE = 1e12
