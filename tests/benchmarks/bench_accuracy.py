"""Accuracy of the exact event-driven method against the independent mpmath reference.

For every case of ``tests/simulation/test_event.py`` (Table I, double and
triple roots, stiff gains, the Routh margin 1.01, f_c from 1e-6 to 100, |z0|
up to 1e6, a creeping solution and a start on each row of the appendix's
table), prints the largest state error at 301 samples relative to
``max(1, |z0|)``, the largest event-time error, and whether the batch path
gives the same numbers bit for bit; then the worst of each over all cases.

Nothing is asserted (the tests hold the bounds 1e-13 and 1e-12)::

    python tests/benchmarks/bench_accuracy.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from symbolic_friction import simulate_batch  # noqa: E402
from tests.simulation.test_event import CASES, N_SAMPLES, run, scale_of  # noqa: E402
from tests.tolerance import relative_error  # noqa: E402


def main() -> int:
    worst_state = worst_event = 0.0
    all_identical = True
    print(f"{'case':<22} {'events':>6} {'state error':>12} {'event-time error':>17}  batch = single")
    for name, (params, z0, t_end, _) in CASES.items():
        sol, ref, z_ref, _ = run(name)
        state = relative_error(sol.z, z_ref, scale=scale_of(z0))
        times = np.array([e[0] for e in sol.events])
        want = np.array([e[0] for e in ref.event_list()])
        event = float(np.max(np.abs(times - want))) if times.size and times.size == want.size else 0.0
        if times.size != want.size:
            event = float("inf")
        batch = simulate_batch(params, np.array([z0]), t_end, t_eval=np.linspace(0.0, t_end, N_SAMPLES))
        same = np.array_equal(batch.z[0], sol.z) and np.array_equal(batch.x[0], sol.x)
        all_identical &= same
        worst_state, worst_event = max(worst_state, state), max(worst_event, event)
        print(f"{name:<22} {len(sol.events):>6} {state:>12.2e} {event:>17.2e}  {'yes' if same else 'NO'}")
    print(f"\nworst over {len(CASES)} cases: state {worst_state:.2e} (relative to max(1, |z0|)), "
          f"event time {worst_event:.2e}; batch and single identical bit for bit: {'yes' if all_identical else 'NO'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
