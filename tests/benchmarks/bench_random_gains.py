"""The event method on random admissible gain sets, against the independent 40-digit reference.

Draws ``N`` gain sets with :func:`tests.simulation.reference_cases.random_case` (``k_p``,
``k_i`` log-uniform over 10⁻⁴..10⁴, Routh margin ``1 + 10^U`` with ``U`` uniform in
``[-4, 1]``, ``|z₀|`` log-uniform over 0.1..100, ``T = 20``, one in four with
``f_c ≠ 1``, one in four with ``f_s > f_c``), simulates each with default options
(compiled kernel, warm: the first call is made and thrown away) and prints

* how many completed, and the statuses of those that did not;
* the time per trajectory (median, 99th percentile, maximum);
* the error of ``z(T)`` against ``Reference(dps=40)``, relative to ``max|z_ref(T)|``
  (median, maximum, the five worst with their gains), and whether the modes of the
  events agree.

Nothing is asserted; run it on a quiet machine::

    python tests/benchmarks/bench_random_gains.py [--n 400] [--seed 0]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("SYMBOLIC_FRICTION_JIT", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from symbolic_friction import Parameters  # noqa: E402
from symbolic_friction._reference import Reference  # noqa: E402
from symbolic_friction._simulation import Status, simulate  # noqa: E402
from tests.simulation.reference_cases import random_case  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=400)
    parser.add_argument("--seed", type=int, default=0, help="first seed; seeds seed .. seed + n - 1")
    args = parser.parse_args()
    simulate(Parameters.table_i("a"), (1.0, 2.0, 3.0), 20.0)  # warm: load the compiled kernel
    times, errors, incomplete, modes_differ = [], [], [], 0
    for seed in range(args.seed, args.seed + args.n):
        params, z0, t_end = random_case(seed)
        simulate(params, z0, t_end)  # warm: this gain set's slip model
        start = time.perf_counter()
        sol = simulate(params, z0, t_end)
        times.append(time.perf_counter() - start)
        if sol.status not in Status.COMPLETE:
            incomplete.append((seed, sol.status))
            continue
        ref = Reference(params, z0, t_end, dps=40, max_events=100_000)
        z_ref = np.array(ref.z_at(t_end)[0])
        errors.append((float(np.abs(sol.z[-1] - z_ref).max() / np.abs(z_ref).max()), seed, len(sol.events), params))
        modes_differ += [e[1:] for e in sol.events] != [e[1:] for e in ref.event_list()]
    t = sorted(times)
    print(f"{args.n} random admissible gain sets (seeds {args.seed}..{args.seed + args.n - 1}), T = 20, default options")
    print(f"completed: {args.n - len(incomplete)}; incomplete: {incomplete or 'none'}")
    print(
        f"time per trajectory (compiled, warm): median {statistics.median(t) * 1e3:.2f} ms, "
        f"99th percentile {t[int(0.99 * (len(t) - 1))] * 1e3:.1f} ms, max {t[-1] * 1e3:.1f} ms"
    )
    rel = sorted(errors, key=lambda e: e[0], reverse=True)
    print(
        f"z(T) against the 40-digit reference, relative to max|z_ref(T)|: median "
        f"{statistics.median(e[0] for e in rel):.1e}, max {rel[0][0]:.1e}; event modes differ in {modes_differ}"
    )
    for err, seed, n_ev, params in rel[:5]:
        ratio = float(params.k_p / params.k_i)
        print(f"  seed {seed}: {err:.1e}, {n_ev} events, k_p/k_i = {ratio:.1e}, {params}")


if __name__ == "__main__":
    main()
