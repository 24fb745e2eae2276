"""Speed/accuracy trade-off of the comparison methods (issue 4), printed as a table.

For Table I case (a), f_c = 1, z0 = (0, 1, 0) over t ∈ [0, 30], each method's
wall time per trajectory and its error against the exact ``event`` method at
301 sample times (sup-norm of |z - z_event| relative to max(1, |z0|)), for
several values of its accuracy knob.  Also the perturbed-friction laws run by
``moreau``.

Run:  python tests/benchmarks/bench_methods.py
"""

from __future__ import annotations

import time

import numpy as np

from symbolic_friction import Parameters
from symbolic_friction._simulation import simulate
from symbolic_friction._simulation.friction import InflatedCoulomb, Stribeck

PARAMS = Parameters.table_i("a")
Z0 = (0.0, 1.0, 0.0)
T_END = 30.0
TIMES = np.linspace(0.0, T_END, 301)


def timed(repeat: int, **kw):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        sol = simulate(PARAMS, Z0, T_END, t_eval=TIMES, **kw)
        best = min(best, time.perf_counter() - t0)
    return sol, best


def main() -> None:
    simulate(PARAMS, Z0, 1.0, method="regularized")  # import scipy once, outside the timings
    ref, t_ref = timed(5, method="event")
    scale = max(1.0, max(abs(c) for c in Z0))
    print(f"case (a), z0 = {Z0}, t in [0, {T_END:g}], {len(ref.events)} events; errors vs the event method")
    print(f"{'method':12s} {'knob':22s} {'time/traj [s]':>14s} {'max rel. error':>15s} {'events':>7s}")
    print(f"{'event':12s} {'(exact)':22s} {t_ref:14.4f} {0.0:15.2e} {len(ref.events):7d}")
    runs = [("moreau", {"h": h}, f"h = {h:g}", 1) for h in (1e-2, 1e-3, 1e-4)]
    runs += [("regularized", {"epsilon": e, "rtol": 1e-9, "atol": 1e-11}, f"eps = {e:g} (tanh)", 1) for e in (1e-2, 1e-3, 1e-4)]
    runs += [("regularized", {"epsilon": 1e-3, "law": "sat", "rtol": 1e-9, "atol": 1e-11}, "eps = 0.001 (sat)", 1)]
    runs += [("ivp-events", {"rtol": r, "atol": r * 1e-2}, f"rtol = {r:g}", 3) for r in (1e-6, 1e-8, 1e-10, 1e-12)]
    for method, kw, label, repeat in runs:
        sol, dt = timed(repeat, method=method, **kw)
        err = float(np.max(np.abs(sol.z - ref.z))) / scale
        print(f"{method:12s} {label:22s} {dt:14.4f} {err:15.2e} {len(sol.events):7d}")
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
