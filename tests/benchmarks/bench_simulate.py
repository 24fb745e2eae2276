"""Speed and accuracy of the simulation methods for Table I case (a), t ∈ [0, 30].

Prints, for initial states drawn uniformly from [-5, 5]³ (fixed seed):

* ``event`` (exact, one trajectory at a time): time per trajectory;
* ``simulate_batch`` on 10,000 initial states: total time and time per
  trajectory, and its largest deviation from ``event``;
* ``ivp-events`` at rtol 1e-10 (scipy ``solve_ivp`` with terminal events):
  time per trajectory and its error against ``event``;
* the error of ``event`` itself against the independent 50-digit mpmath
  reference of the test suite, on a few trajectories.

Errors are ``max |z - z_ref| / max(1, |z0|)`` over the 301 sample times.
Nothing is asserted; run it on a quiet machine::

    python tests/benchmarks/bench_simulate.py [--batch 10000] [--scalar 300] [--ivp 50] [--reference 3]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from symbolic_friction import Parameters, SimulationError  # noqa: E402
from symbolic_friction._simulation import simulate  # noqa: E402
from symbolic_friction._simulation.batch import simulate_batch  # noqa: E402

T_END = 30.0
T_EVAL = np.linspace(0.0, T_END, 301)


def error(z: np.ndarray, z_ref: np.ndarray, z0: np.ndarray) -> float:
    return float(np.max(np.abs(z - z_ref)) / max(1.0, float(np.linalg.norm(z0))))


def import_time() -> float:
    code = (
        "import time; t = time.perf_counter(); import symbolic_friction._simulation.event; "
        "print(time.perf_counter() - t)"
    )
    return float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout)


def bench_ivp(params: Parameters, Z0: np.ndarray, scalar: list, per_event: float, per_batch: float) -> None:
    """Time ``ivp-events`` at rtol 1e-10 and measure its error against ``event``."""
    try:
        simulate(params, Z0[0], T_END, method="ivp-events", t_eval=T_EVAL, rtol=1e-10)
    except (ImportError, SimulationError) as exc:  # the method may not be installed yet
        print(f"\nivp-events: not available ({exc})")
        return
    start = time.perf_counter()
    ivp = [simulate(params, z0, T_END, method="ivp-events", t_eval=T_EVAL, rtol=1e-10) for z0 in Z0]
    per_ivp = (time.perf_counter() - start) / len(Z0)
    errs = [error(s.z, scalar[i].z, Z0[i]) for i, s in enumerate(ivp) if s.z.shape == scalar[i].z.shape]
    print(f"\nivp-events (rtol 1e-10), {len(Z0)} trajectories: {1e3 * per_ivp:.2f} ms per trajectory")
    print(f"  error vs event: max {max(errs):.1e}, median {np.median(errs):.1e}")
    print(f"  event is {per_ivp / per_event:.0f}x faster, batch {per_ivp / per_batch:.0f}x faster")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--batch", type=int, default=10_000, help="initial states in the batch")
    parser.add_argument("--scalar", type=int, default=300, help="trajectories timed one by one with 'event'")
    parser.add_argument("--ivp", type=int, default=50, help="trajectories timed with 'ivp-events'")
    parser.add_argument("--reference", type=int, default=3, help="trajectories checked against mpmath")
    parser.add_argument("--seed", type=int, default=2024)
    args = parser.parse_args()

    params = Parameters.table_i("a")
    rng = np.random.default_rng(args.seed)
    Z0 = rng.uniform(-5.0, 5.0, size=(max(args.batch, args.scalar, args.ivp, args.reference), 3))
    print(f"Table I case (a) {params}, t in [0, {T_END:g}], {T_EVAL.size} sample times")
    print(f"import of the event method: {1e3 * import_time():.0f} ms (numpy only; no scipy, sympy, cvxpy)")

    # warm-up: builds and caches the closed form and the scan table
    simulate(params, Z0[0], T_END, t_eval=T_EVAL)

    n = args.scalar
    start = time.perf_counter()
    scalar = [simulate(params, z0, T_END, t_eval=T_EVAL) for z0 in Z0[:n]]
    per_event = (time.perf_counter() - start) / n
    events = np.array([len(s.events) for s in scalar])
    print(f"\nevent (one at a time), {n} trajectories: {1e3 * per_event:.3f} ms per trajectory")
    print(f"  events per trajectory: mean {events.mean():.1f}, max {events.max()}")

    nb = args.batch
    start = time.perf_counter()
    batch = simulate_batch(params, Z0[:nb], T_END, t_eval=T_EVAL)
    total = time.perf_counter() - start
    dev = max(error(batch.z[i], scalar[i].z, Z0[i]) for i in range(min(n, nb)))
    print(f"\nsimulate_batch, {nb} trajectories: {total:.2f} s total, {1e3 * total / nb:.3f} ms per trajectory")
    print(f"  speed-up per trajectory over event: {per_event / (total / nb):.1f}x")
    print(f"  max deviation from event (first {min(n, nb)}): {dev:.1e}")

    if args.ivp:
        bench_ivp(params, Z0[: args.ivp], scalar, per_event, total / nb)

    nr = args.reference
    if nr:
        from tests.simulation.reference import Reference

        errs, t_errs = [], []
        for i in range(nr):
            ref = Reference(params, tuple(Z0[i]), T_END)
            z_ref, _ = ref.sample(T_EVAL)
            errs.append(error(scalar[i].z, np.array(z_ref), Z0[i]))
            t_errs.extend(abs(a[0] - b[0]) for a, b in zip(scalar[i].events, ref.event_list()))
        print(f"\nevent vs the 50-digit mpmath reference, {nr} trajectories:")
        print(f"  state error max {max(errs):.1e}, event-time error max {max(t_errs, default=0.0):.1e}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
