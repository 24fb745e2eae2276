"""Cost of the high-precision reference (``symbolic_friction._reference``) against stiffness.

Prints, at ``dps = 40`` and ``T = 20``:

* the time of one trajectory against ``k_v`` from ``10⁰`` to ``10⁸``, on gains
  ``k_p = k_v``, ``k_i = k_v/2`` whose slow pair stays near the roots of
  ``s² + s + 1/2`` (so the number of events stays small and about the same) and
  whose fast mode is ``≈ -k_v``; next to it the former fixed-grid method
  (``_method="grid"``, cost ``∝ ‖A‖∞ T``) while that takes under a minute;
* the time of one trajectory on random stiff gain sets drawn by
  ``tests/simulation/reference_cases.random_case`` (log-uniform ``k_p, k_i`` in
  ``[10⁻⁴, 10⁴]``, Routh margin ``1 + 10^U``, ``U ∈ [-4, 1]``).

Nothing is asserted; run it on a quiet machine::

    python tests/benchmarks/bench_reference.py [--seeds 10] [--grid-up-to 1000]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from symbolic_friction import Parameters  # noqa: E402
from symbolic_friction._reference import Reference  # noqa: E402
from tests.simulation.reference_cases import random_case  # noqa: E402

DPS = 40
T_END = 20.0
Z0 = (3.0, -2.0, 1.0)


def _timed(params, z0, t_end, **kw):
    t0 = time.perf_counter()
    ref = Reference(params, z0, t_end, dps=DPS, max_events=5000, **kw)
    return time.perf_counter() - t0, ref


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10, help="random gain sets (seeds 0, 1, ...)")
    parser.add_argument("--grid-up-to", type=float, default=1e3, help="largest k_v timed with the fixed grid too")
    args = parser.parse_args()

    print(f"reference at dps = {DPS}, T = {T_END:g}, z0 = {Z0}")
    print(f"{'k_v':>8} {'events':>6} {'steps':>6} {'wp':>4} {'time [s]':>9} {'grid [s]':>9}")
    for e in range(0, 9):
        k_v = Fraction(10) ** e
        params = Parameters(k_p=k_v, k_i=k_v / 2, k_v=k_v)
        seconds, ref = _timed(params, Z0, T_END)
        steps = sum(len(p.grid) for p in ref.pieces if p.grid is not None)
        grid = ""
        if k_v <= args.grid_up_to:
            grid_seconds, grid_ref = _timed(params, Z0, T_END, _method="grid")
            same = [(a, b) for _, a, b in grid_ref.events] == [(a, b) for _, a, b in ref.events]
            grid = f"{grid_seconds:9.3f}" + ("" if same else " (events differ)")
        print(f"{float(k_v):8.0e} {len(ref.events):6d} {steps:6d} {ref.ctx.dps:4d} {seconds:9.3f} {grid}", flush=True)

    print(f"\nrandom stiff gain sets (reference_cases.random_case), T = {T_END:g}")
    print(f"{'seed':>4} {'k_p':>9} {'k_i':>9} {'k_v':>9} {'m-1':>8} {'f_c':>5} {'f_s':>5} {'|z0|':>7} "
          f"{'events':>6} {'time [s]':>9} {'s/event':>8}")
    times = []
    for seed in range(args.seeds):
        params, z0, t_end = random_case(seed)
        seconds, ref = _timed(params, z0, t_end)
        times.append(seconds)
        margin = float(params.k_v * params.k_p / params.k_i - 1)
        per = seconds / max(1, len(ref.events))
        print(f"{seed:4d} {float(params.k_p):9.3g} {float(params.k_i):9.3g} {float(params.k_v):9.3g} {margin:8.2g} "
              f"{float(params.f_c):5.3g} {float(params.f_s):5.3g} {math.hypot(*z0):7.3g} "
              f"{len(ref.events):6d} {seconds:9.3f} {per:8.4f}", flush=True)
    if times:
        print(f"median {sorted(times)[len(times) // 2]:.3f} s, max {max(times):.3f} s per trajectory")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
