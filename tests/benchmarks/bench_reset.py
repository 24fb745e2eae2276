"""Cost of reset PID in the exact event kernel, against the paper's PID on the same states.

Prints, for Table I (a), (b) and 20 random admissible gain sets (the ones of
``tests/simulation/test_reset.py``), the median time per trajectory of
``simulate_batch`` (compiled kernel, warm) over 200 initial states uniform in
[-5, 5]³, t ∈ [0, 200], 201 samples, with and without resets
(``reset_dwell = 1/100``), the ratio, and the events and resets per trajectory.
Both runs use the same states, sample times and ``max_events``.

The kernel is the compiled one (``SYMBOLIC_FRICTION_JIT=1`` unless set otherwise):
under the default ``auto`` a process runs the plain-Python kernel until it has spent
a few seconds in it, so the first gain sets would be timed in another variant than
the rest.  The header says which variant ran.

Besides the time per trajectory it prints the time per event and the time per unit
of work, ``events + slip-phase samples`` (a sample during a slip is the closed form
of ``e^{Aτ}``, a sample during a stick a line; reset PID keeps slipping, PID mostly
sticks), with their ratios, and the time of the same batch sampled at t = 0 and
200 only (``ev-only``), so that the samples' share of the time shows.  The four
batches of a gain set take turns, repeat after repeat, so that a change in the
machine's load falls on all of them.  Nothing is asserted; run it on a quiet
machine (on a shared one, ``--stat min`` and ``NUMBA_NUM_THREADS=1`` are steadier)::

    python tests/benchmarks/bench_reset.py [--states 200] [--repeats 5] [--stat median|min]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

import numpy as np

os.environ.setdefault("SYMBOLIC_FRICTION_JIT", "1")
sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from symbolic_friction import Parameters  # noqa: E402
from symbolic_friction._simulation import simulate_batch  # noqa: E402
from symbolic_friction._simulation._jit import variant  # noqa: E402
from tests.simulation.test_reset import random_gain_sets  # noqa: E402

T_END = 200.0
MAX_EVENTS = 100_000


def timed(runs, z0, repeats, stat):
    """``stat`` of the seconds per trajectory of each ``(params, t)`` in ``runs``, the runs taking turns.

    Returns the times and the batch of each run's last repeat.
    """
    for params, t in runs:  # compile / warm
        simulate_batch(params, z0[:2], T_END, t_eval=t, max_events=MAX_EVENTS)
    times = [[] for _ in runs]
    batches = [None] * len(runs)
    for _ in range(repeats):
        for j, (params, t) in enumerate(runs):
            t0 = time.perf_counter()
            batches[j] = simulate_batch(params, z0, T_END, t_eval=t, max_events=MAX_EVENTS)
            times[j].append((time.perf_counter() - t0) / len(z0))
    return [stat(x) for x in times], batches


def counts(batch):
    """Mean events, resets and slip-phase samples per trajectory."""
    resets = int(((batch.event_before == 0) & (batch.event_after == 0) & (batch.event_t == batch.event_t)).sum())
    return float(batch.n_events.mean()), resets / batch.size, float((batch.mode != 0).sum(axis=1).mean())


def main() -> None:
    global T_END  # noqa: PLW0603 - one horizon for every batch of the run
    ap = argparse.ArgumentParser()
    ap.add_argument("--states", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--stat", choices=("median", "min"), default="median")
    ap.add_argument("--t-end", type=float, default=T_END,
                    help="horizon (default 200; the accuracy tests against the reference use T = 20)")
    args = ap.parse_args()
    T_END = args.t_end
    stat = statistics.median if args.stat == "median" else min
    rng = np.random.default_rng(2026)
    z0 = rng.uniform(-5, 5, size=(args.states, 3))
    t = np.linspace(0.0, T_END, 201)
    ends = np.array([0.0, T_END])
    sets = {"Table I (a)": Parameters.table_i("a"), "Table I (b)": Parameters.table_i("b")}
    sets.update({f"random {j:02d}": p for j, p in enumerate(random_gain_sets(20))})
    print(f"kernel: {variant()}; {args.states} states, t ≤ {T_END:g}, {t.size} samples, max_events {MAX_EVENTS}; "
          f"{args.stat} of {args.repeats}")
    print(f"{'gain set':14s} {'PID µs':>9s} {'reset µs':>9s} {'ratio':>6s} {'events':>8s} {'events(r)':>9s} {'resets':>7s}"
          f" {'µs/event':>9s} {'(reset)':>8s} {'ratio':>6s} {'slip smp':>8s} {'(reset)':>7s} {'µs/work':>8s} {'(reset)':>7s}"
          f" {'ratio':>6s} {'ev-only':>8s} {'(reset)':>7s}")
    ratios, per_event, per_work = [], [], []
    for name, p in sets.items():
        r = dataclasses.replace(p, reset_dwell=Fraction(1, 100))
        (a, b, a0, b0), batches = timed([(p, t), (r, t), (p, ends), (r, ends)], z0, args.repeats, stat)
        (ea, _, sa), (eb, rb, sb) = counts(batches[0]), counts(batches[1])
        ratios.append(b / a)
        pa, pb = a / max(ea, 1.0), b / max(eb, 1.0)
        per_event.append(pb / pa)
        wa, wb = a / (ea + sa), b / (eb + sb)  # per event or slip-phase sample
        per_work.append(wb / wa)
        print(f"{name:14s} {a * 1e6:9.1f} {b * 1e6:9.1f} {b / a:6.2f} {ea:8.1f} {eb:9.1f} {rb:7.1f}"
              f" {pa * 1e6:9.2f} {pb * 1e6:8.2f} {pb / pa:6.2f} {sa:8.1f} {sb:7.1f} {wa * 1e6:8.3f} {wb * 1e6:7.3f}"
              f" {wb / wa:6.2f} {a0 * 1e6:8.1f} {b0 * 1e6:7.1f}")
    print(f"per trajectory, reset/PID: median {statistics.median(ratios):.2f}, max {max(ratios):.2f}; "
          f"per event: median {statistics.median(per_event):.2f}, max {max(per_event):.2f}; "
          f"per event or slip-phase sample: median {statistics.median(per_work):.2f}, max {max(per_work):.2f} "
          f"over {len(ratios)} gain sets")


if __name__ == "__main__":
    main()
