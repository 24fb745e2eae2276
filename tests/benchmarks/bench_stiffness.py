"""Cost of the exact event-driven method against stiffness, at a fixed number of events.

The family ``k_p = 23/2500``, ``k_v`` from 10⁰ to 10⁸, ``k_i = k_v k_p / m`` with
the Routh margin ``m = k_v k_p / k_i = 1.0026``: as ``k_v`` grows the fast root
``≈ -k_v`` separates from a pair ``s² + (k_p/k_v) s + k_p/m`` whose frequency
stays ``√(k_p/m)``, so the solutions from the same ``z₀`` have the same few events
on ``[0, 20]`` while ``‖A‖`` grows a hundred million times.  For each ``k_v`` it
prints the events, the median time per trajectory (``simulate``, default options,
compiled kernel warm, and the plain-Python kernel), and the ratio of the slowest
to the fastest time over ``k_v ≤ 10⁶`` (the curve should be flat, within 10×).

Nothing is asserted; run it on a quiet machine::

    python tests/benchmarks/bench_stiffness.py [--repeats 50]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

K_P = Fraction(23, 2500)
MARGIN = Fraction(10026, 10000)
Z0 = (3.0, -5.0, 7.0)
T_END = 20.0
EXPONENTS = range(0, 9)


def measure(repeats: int) -> list[tuple[int, int, float, str]]:
    """``(exponent, events, median seconds, status)`` for each ``k_v = 10^exponent``, in this process."""
    from symbolic_friction import Parameters
    from symbolic_friction._simulation import simulate

    rows = []
    for e in EXPONENTS:
        k_v = Fraction(10) ** e
        params = Parameters(k_p=K_P, k_i=k_v * K_P / MARGIN, k_v=k_v)
        sol = simulate(params, Z0, T_END)  # warm: the slip model of the gain set and the kernel
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            simulate(params, Z0, T_END)
            times.append(time.perf_counter() - start)
        rows.append((e, len(sol.events), statistics.median(times), sol.status))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=50)
    parser.add_argument("--variant", choices=("numba", "python"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.variant:  # the child: one kernel variant, rows printed as Python literals
        print(repr(measure(args.repeats)))
        return
    results = {}
    for variant, env in (("numba", "1"), ("python", "0")):
        out = subprocess.run(
            [sys.executable, __file__, "--repeats", str(args.repeats), "--variant", variant],
            env={**os.environ, "SYMBOLIC_FRICTION_JIT": env}, capture_output=True, text=True, check=True,
        ).stdout
        results[variant] = eval(out.strip().splitlines()[-1])  # noqa: S307 - our own child's repr
    print(f"k_p = {K_P}, k_v k_p / k_i = {float(MARGIN)}, z0 = {Z0}, T = {T_END}, 1001 samples (default)")
    print(f"{'k_v':>8} {'events':>6} {'compiled µs':>12} {'plain µs':>10}  status")
    for (e, n, t_c, status), (_, _, t_p, _) in zip(results["numba"], results["python"]):
        print(f"{'1e%d' % e:>8} {n:>6} {t_c * 1e6:>12.1f} {t_p * 1e6:>10.1f}  {status}")
    for variant in ("numba", "python"):
        upto6 = [t for e, _, t, _ in results[variant] if e <= 6]
        print(f"{variant}: slowest / fastest over k_v ≤ 1e6 = {max(upto6) / min(upto6):.2f}")


if __name__ == "__main__":
    main()
