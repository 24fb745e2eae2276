"""Speed of the exact event-driven method, Table I case (a), t ∈ [0, 30], 301 samples.

Prints, in one run (initial states uniform in [-5, 5]³, fixed seed):

* ``event``, one trajectory per ``simulate`` call, in-process, with the
  compiled kernel (``SYMBOLIC_FRICTION_JIT=1``, after a warm-up) and with the
  plain-Python kernel: median time per trajectory over repeats;
* the DOP853 mode-switching baseline (``ivp-events``, rtol 1e-12) on the same
  states, and the ratio of the two medians taken in this run;
* ``simulate_batch`` on 10⁴ initial states: median total time over repeats;
* ``iter_batches`` streaming 10⁶ initial states in a fresh process, each chunk
  reduced to its largest ``|x|_𝒜``: total time and peak resident memory;
* ``symbolic-friction simulate paper-a`` from a fresh process: the default
  (``auto``), the compiled kernel with its cache warm, and with an empty
  numba cache (cold: every function compiled).

Nothing is asserted; run it on a quiet machine::

    python tests/benchmarks/bench_simulate.py [--scalar 2000] [--ivp 20] [--batch 10000] [--stream 1000000]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("SYMBOLIC_FRICTION_JIT", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from symbolic_friction import Parameters  # noqa: E402
from symbolic_friction._simulation import _jit, simulate  # noqa: E402
from symbolic_friction._simulation.batch import simulate_batch  # noqa: E402

T_END = 30.0
T_EVAL = np.linspace(0.0, T_END, 301)
PARAMS = Parameters.table_i("a")


# the same gains with static friction 1.2 f_c: every stick exit starts a slip with v' ≠ 0 (no cached length)
STICTION = Parameters(k_p=PARAMS.k_p, k_i=PARAMS.k_i, k_v=PARAMS.k_v, f_c=PARAMS.f_c, f_s="1.2")


def per_call(Z0: np.ndarray, repeats: int, params: Parameters = PARAMS, **kw) -> tuple[float, float, float]:
    """Median, min and max over ``repeats`` of the mean time per ``simulate`` call over ``Z0``."""
    rounds = []
    for _ in range(repeats):
        start = time.perf_counter()
        for z0 in Z0:
            simulate(params, z0, T_END, t_eval=T_EVAL, **kw)
        rounds.append((time.perf_counter() - start) / len(Z0))
    return statistics.median(rounds), min(rounds), max(rounds)


def fresh(cmd: list[str], env: dict[str, str], repeats: int) -> tuple[float, float]:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run(cmd, env=env, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times)


STREAM = """
import resource, sys, time
import numpy as np
from symbolic_friction import Parameters
from symbolic_friction._model.attractor import distance_x
from symbolic_friction._simulation.batch import iter_batches
n = int(sys.argv[1])
rng = np.random.default_rng(1)
Z0 = rng.uniform(-5.0, 5.0, size=(n, 3))
t = np.linspace(0.0, 30.0, 301)
start = time.perf_counter()
worst, done, incomplete = 0.0, 0, 0
for b in iter_batches(Parameters.table_i("a"), Z0, 30.0, t_eval=t):
    worst = max(worst, float(np.nanmax(distance_x(b.params, b.x))))
    done += len(b)
    incomplete += int((~b.complete).sum())
elapsed = time.perf_counter() - start
print(done, incomplete, elapsed, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, worst)
"""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scalar", type=int, default=2000, help="trajectories timed one simulate call each")
    parser.add_argument("--ivp", type=int, default=20, help="trajectories timed with the DOP853 baseline")
    parser.add_argument("--batch", type=int, default=10_000, help="initial states in the batch")
    parser.add_argument("--stream", type=int, default=1_000_000, help="initial states streamed (0: skip)")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--seed", type=int, default=2024)
    args = parser.parse_args()

    rng = np.random.default_rng(args.seed)
    Z0 = rng.uniform(-5.0, 5.0, size=(max(args.scalar, args.batch, args.ivp), 3))
    print(f"Table I case (a) {PARAMS}, t in [0, {T_END:g}], {T_EVAL.size} samples; "
          f"{os.cpu_count()} cores, kernel: {_jit.variant()}")

    simulate(PARAMS, Z0[0], T_END, t_eval=T_EVAL)  # warm-up: compile or load the cache, build the tables
    med, lo, hi = per_call(Z0[: args.scalar], args.repeats)
    events = np.mean([len(simulate(PARAMS, z, T_END, t_eval=T_EVAL).events) for z in Z0[:200]])
    print(f"\nevent, one simulate() call per trajectory, {args.scalar} trajectories × {args.repeats}:")
    print(f"  compiled kernel: {1e6 * med:.1f} µs per trajectory (min {1e6 * lo:.1f}, max {1e6 * hi:.1f}); "
          f"{events:.1f} events per trajectory")

    s_med, s_lo, s_hi = per_call(Z0[: args.scalar], args.repeats, params=STICTION)
    s_events = np.mean([len(simulate(STICTION, z, T_END, t_eval=T_EVAL).events) for z in Z0[:200]])
    print(f"  compiled kernel, static friction f_s = 1.2 f_c: {1e6 * s_med:.1f} µs per trajectory "
          f"(min {1e6 * s_lo:.1f}, max {1e6 * s_hi:.1f}); {s_events:.1f} events per trajectory")

    os.environ["SYMBOLIC_FRICTION_JIT"] = "0"
    p_med, _, _ = per_call(Z0[:100], 3)
    os.environ["SYMBOLIC_FRICTION_JIT"] = "1"
    print(f"  plain-Python kernel (SYMBOLIC_FRICTION_JIT=0): {1e3 * p_med:.2f} ms per trajectory")

    ivp_opts = dict(method="ivp-events", rtol=1e-12, atol=1e-14, integrator="DOP853")
    simulate(PARAMS, Z0[0], T_END, t_eval=T_EVAL, **ivp_opts)
    i_med, i_lo, i_hi = per_call(Z0[: args.ivp], 3, **ivp_opts)
    print(f"\nDOP853 mode switching (ivp-events, rtol 1e-12, atol 1e-14), {args.ivp} trajectories × 3:")
    print(f"  {1e3 * i_med:.2f} ms per trajectory (min {1e3 * i_lo:.2f}, max {1e3 * i_hi:.2f})")
    print(f"  event is {i_med / med:.0f}x faster (medians of this run)")

    nb = args.batch
    simulate_batch(PARAMS, Z0[:100], T_END, t_eval=T_EVAL)
    times = []
    for _ in range(args.repeats):
        start = time.perf_counter()
        batch = simulate_batch(PARAMS, Z0[:nb], T_END, t_eval=T_EVAL)
        times.append(time.perf_counter() - start)
    print(f"\nsimulate_batch, {nb} trajectories × {args.repeats}: median {statistics.median(times):.3f} s "
          f"(min {min(times):.3f}, max {max(times):.3f}); {int((~batch.complete).sum())} incomplete")

    if args.stream:
        out = subprocess.run([sys.executable, "-c", STREAM, str(args.stream)], capture_output=True, text=True,
                             check=True, env=dict(os.environ, PYTHONPATH=str(ROOT)))
        done, incomplete, elapsed, rss, worst = out.stdout.split()
        print(f"\niter_batches, {int(done)} trajectories streamed in a fresh process: {float(elapsed):.1f} s, "
              f"peak RSS {float(rss):.0f} MB, {incomplete} incomplete, largest |x|_A {float(worst):.3f}")

    cmd = [sys.executable, "-m", "symbolic_friction", "simulate", "paper-a", "--out", tempfile.mkdtemp()]
    base = dict(os.environ, PYTHONPATH=str(ROOT))
    auto = fresh(cmd, {**base, "SYMBOLIC_FRICTION_JIT": "auto"}, args.repeats)
    fresh(cmd, {**base, "SYMBOLIC_FRICTION_JIT": "1"}, 1)
    warm = fresh(cmd, {**base, "SYMBOLIC_FRICTION_JIT": "1"}, args.repeats)
    with tempfile.TemporaryDirectory() as cache:
        cold = fresh(cmd, {**base, "SYMBOLIC_FRICTION_JIT": "1", "NUMBA_CACHE_DIR": cache}, 1)
    print("\nsymbolic-friction simulate paper-a, fresh process (median, min):")
    print(f"  default (auto: plain kernel for a small scene): {auto[0]:.2f} s, {auto[1]:.2f} s")
    print(f"  compiled kernel, numba cache warm: {warm[0]:.2f} s, {warm[1]:.2f} s")
    print(f"  compiled kernel, empty numba cache (first run): {cold[0]:.2f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
