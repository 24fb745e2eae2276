"""Speed/accuracy trade-off of the simulation methods, printed as a table.

The measurement itself is the package's (``symbolic-friction tradeoff``,
:mod:`symbolic_friction._studies.tradeoff`): for Table I case (a), z0 = (0, 1, 0)
over t ∈ [0, 30], every method across its knob against the 50-digit mpmath
reference, with the median time of repeats.  Also the perturbed-friction
laws run by ``moreau``.

Run:  python tests/benchmarks/bench_methods.py
"""

from __future__ import annotations

import time

from symbolic_friction import Parameters
from symbolic_friction._simulation import simulate
from symbolic_friction._simulation.friction import InflatedCoulomb, Stribeck
from symbolic_friction._studies.tradeoff import measure_tradeoff

PARAMS = Parameters.table_i("a")
Z0 = (0.0, 1.0, 0.0)
T_END = 30.0


def main() -> None:
    result = measure_tradeoff(PARAMS, [Z0], T_END, label="Table I case (a)")
    print(result.table())
    print()
    print(result.note())
    print()
    print("perturbed friction (moreau, h = 1e-3), z0 = (0, 0, 0) for SGN_rho, (0, 1, 0) for Stribeck, t in [0, 30]:")
    for label, law, z0 in [
        ("SGN_rho worst case, rho = 0.01", InflatedCoulomb("0.01"), (0.0, 0.0, 0.0)),
        ("SGN_rho worst case, rho = 0.1", InflatedCoulomb("0.1"), (0.0, 0.0, 0.0)),
        ("Stribeck f_s = 2, v_s = 0.1", Stribeck(2, "0.1"), Z0),
    ]:
        t0 = time.perf_counter()
        sol = simulate(PARAMS, z0, T_END, method="moreau", h=1e-3, friction=law)
        dt = time.perf_counter() - t0
        print(f"  {label:32s} {dt:8.3f} s   max |x|_A = {sol.distance.max():.4f}   {len(sol.events)} events")


if __name__ == "__main__":
    main()
