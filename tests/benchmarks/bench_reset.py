"""Cost of reset PID in the exact event kernel, against the paper's PID on the same states.

Prints, for Table I (a), (b) and 20 random admissible gain sets (the ones of
``tests/simulation/test_reset.py``), the median time per trajectory of
``simulate_batch`` (compiled kernel, warm) over 200 initial states uniform in
[-5, 5]³, t ∈ [0, 200], 201 samples, with and without resets
(``reset_dwell = 1/100``), the ratio, and the events and resets per trajectory.
Nothing is asserted; run it on a quiet machine::

    python tests/benchmarks/bench_reset.py [--states 200] [--repeats 5]
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from symbolic_friction import Parameters  # noqa: E402
from symbolic_friction._simulation import simulate_batch  # noqa: E402
from tests.simulation.test_reset import random_gain_sets  # noqa: E402


def per_trajectory(params, z0, repeats):
    t = np.linspace(0.0, 200.0, 201)
    simulate_batch(params, z0[:2], 200.0, t_eval=t, max_events=100_000)  # compile / warm
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        batch = simulate_batch(params, z0, 200.0, t_eval=t, max_events=100_000)
        times.append((time.perf_counter() - t0) / len(z0))
    resets = int(((batch.event_before == 0) & (batch.event_after == 0) & (batch.event_t == batch.event_t)).sum())
    return statistics.median(times), float(batch.n_events.mean()), resets / len(z0)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--states", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    rng = np.random.default_rng(2026)
    z0 = rng.uniform(-5, 5, size=(args.states, 3))
    sets = {"Table I (a)": Parameters.table_i("a"), "Table I (b)": Parameters.table_i("b")}
    sets.update({f"random {j:02d}": p for j, p in enumerate(random_gain_sets(20))})
    print(f"{'gain set':14s} {'PID µs':>9s} {'reset µs':>9s} {'ratio':>6s} {'events':>8s} {'events(r)':>9s} {'resets':>7s}"
          f" {'µs/event':>9s} {'(reset)':>8s} {'ratio':>6s}")
    ratios, per_event = [], []
    for name, p in sets.items():
        a, ea, _ = per_trajectory(p, z0, args.repeats)
        b, eb, rb = per_trajectory(dataclasses.replace(p, reset_dwell=Fraction(1, 100)), z0, args.repeats)
        ratios.append(b / a)
        pa, pb = a / max(ea, 1.0), b / max(eb, 1.0)
        per_event.append(pb / pa)
        print(f"{name:14s} {a * 1e6:9.1f} {b * 1e6:9.1f} {b / a:6.2f} {ea:8.1f} {eb:9.1f} {rb:7.1f}"
              f" {pa * 1e6:9.2f} {pb * 1e6:8.2f} {pb / pa:6.2f}")
    print(f"per trajectory, reset/PID: median {statistics.median(ratios):.2f}, max {max(ratios):.2f}; "
          f"per event: median {statistics.median(per_event):.2f}, max {max(per_event):.2f} over {len(ratios)} gain sets")


if __name__ == "__main__":
    main()
