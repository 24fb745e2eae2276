"""Gain maps: the cost of one point, a large κ map, and dask throughput.

Prints

* the closed-form certificate of one gain set: building it
  (:func:`~symbolic_friction._certify.closed_form.closed_form_certificate`) and
  verifying it exactly (:func:`~symbolic_friction._certify.verify.verify_certificate`),
  warm, median and mean over ``--per-point`` random gain sets (log-uniform
  ``k_p``, ``k_i``, ``k_v`` over 10⁻³..10³, inside Assumption 1);
* a ``--points`` κ map (default 10⁶: a 1000 × 1000 log grid, ``k_p`` over
  10⁻¹..10² and ``k_i`` over 10⁻²..10¹ at ``k_v = 2``, about 16 % of it outside Assumption 1) on a process pool of ``--workers``
  processes, chunks of ``--chunk`` points, with its wall time, points/s and
  peak resident memory (this process and the largest worker, from
  ``resource.getrusage``);
* the throughput of a ``--cluster-points`` map on a dask.distributed
  ``LocalCluster`` with 1 and with 2 worker processes (one thread each).

Nothing is asserted; the machine load (``os.getloadavg``) is printed with
the figures.  Run it on a quiet machine::

    python tests/benchmarks/bench_gainmap.py [--points 1000000] [--workers 2] [--skip-map] [--skip-cluster]
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from symbolic_friction._certify.verify import verify_certificate  # noqa: E402
from symbolic_friction._studies.gainmap import map_spec  # noqa: E402
from symbolic_friction import Parameters  # noqa: E402
from symbolic_friction._certify.closed_form import DEFAULT_MU, closed_form_certificate  # noqa: E402
from symbolic_friction._studies.gainmap_run import run_map  # noqa: E402


def _load() -> str:
    return "load average " + ", ".join(f"{x:.2f}" for x in os.getloadavg())


def per_point(n: int, seed: int = 0) -> None:
    rng = np.random.default_rng(seed)
    gains = []
    while len(gains) < n:
        k_p, k_i, k_v = (Fraction(f"{x:.6g}") for x in 10 ** rng.uniform(-3, 3, 3))
        if k_v * k_p > k_i:
            gains.append(Parameters(k_p=k_p, k_i=k_i, k_v=k_v))
    for g in gains[:50]:  # warm
        verify_certificate(closed_form_certificate(g, mode="tightest", margin=DEFAULT_MU))
    build, verify, proved = [], [], 0
    for g in gains:
        t0 = time.perf_counter()
        cert = closed_form_certificate(g, mode="tightest", margin=DEFAULT_MU)
        t1 = time.perf_counter()
        proved += verify_certificate(cert).proved
        t2 = time.perf_counter()
        build.append(t1 - t0)
        verify.append(t2 - t1)
    total = [b + v for b, v in zip(build, verify)]
    print(f"per point ({n} random gain sets, warm; {_load()}): {proved}/{n} proved")
    for name, xs in (("build", build), ("verify", verify), ("build + verify", total)):
        print(f"  {name:15s} median {statistics.median(xs) * 1e3:.3f} ms, mean {statistics.fmean(xs) * 1e3:.3f} ms")


def big_map(points: int, workers: int, chunk: int) -> None:
    side = int(round(points ** 0.5))
    spec = map_spec({"k_p": f"0.1:100:{side}:log", "k_i": f"0.01:10:{side}:log", "k_v": "2"}, chunk=chunk)
    print(f"map of {spec.points} points ({side} x {side} log grid of (k_p, k_i) at k_v = 2, chunks of {chunk}) on {workers} processes; {_load()}")
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        with ProcessPoolExecutor(workers) as pool:
            run = run_map(spec, Path(tmp) / "map", executor=pool, progress=None)
        wall = time.perf_counter() - start
        sizes = {p.name: p.stat().st_size for p in run.files}
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    child = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    print(f"  {wall:.1f} s wall ({run.seconds:.1f} s computing, the rest assembling map.csv and map.nc): "
          f"{spec.points / wall:.0f} points/s")
    print(f"  counts {run.counts}; κ from {run.kappa_min:.6g} to {run.kappa_max:.6g}")
    print(f"  peak resident memory: this process {own:.0f} MiB, largest worker {child:.0f} MiB; files "
          + ", ".join(f"{k} {v / 2**20:.0f} MiB" for k, v in sizes.items()))
    print(f"  after: {_load()}")


def cluster(points: int, chunk: int) -> None:
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        print("dask.distributed not installed: no LocalCluster figures (pip install 'symbolic-friction[dask]')")
        return
    side = int(round(points ** 0.5))
    spec = map_spec({"k_p": f"0.1:100:{side}:log", "k_i": f"0.01:10:{side}:log", "k_v": "2"}, chunk=chunk)
    for n in (1, 2):
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None) as lc, \
                Client(lc) as client, tempfile.TemporaryDirectory() as tmp:
            client.submit(sum, [1]).result()  # workers up
            start = time.perf_counter()
            run = run_map(spec, Path(tmp) / "map", executor=client.get_executor(), formats=(), progress=False)
            wall = time.perf_counter() - start
        print(f"LocalCluster, {n} worker process(es): {spec.points} points in {wall:.1f} s = {spec.points / wall:.0f} "
              f"points/s ({run.counts['proved']} proved); {_load()}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per-point", type=int, default=2000)
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--chunk", type=int, default=10_000)
    parser.add_argument("--cluster-points", type=int, default=40_000)
    parser.add_argument("--skip-map", action="store_true")
    parser.add_argument("--skip-cluster", action="store_true")
    args = parser.parse_args()
    per_point(args.per_point)
    if not args.skip_cluster:
        cluster(args.cluster_points, min(args.chunk, max(1, args.cluster_points // 20)))
    if not args.skip_map:
        big_map(args.points, args.workers, args.chunk)


if __name__ == "__main__":
    main()
