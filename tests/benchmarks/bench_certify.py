"""Benchmark: time per certificate (search + exact rounding + exact verification).

Run from the repository root with the package installed::

    python tests/benchmarks/bench_certify.py            # full run (about half a minute)
    python tests/benchmarks/bench_certify.py --quick    # fewer repetitions

It prints

1. the wall time of one ``symbolic-friction certify --k-p 3 --k-i 4 --k-v 6.4
   --f-c 1 --out DIR`` subprocess (what a user waits for; dominated by
   importing cvxpy), next to the bare ``import cvxpy`` time;
2. in process: the first certificate (compiles the cvxpy problem) and the
   warm per-certificate time, split into search / rounding / verification;
3. a sweep of 1,000 gain sets spread over many decades: amortised time per
   certificate, serially and with ``ProcessPoolExecutor(2)``.

Target: under 20 ms per certificate amortised over the sweep.
"""

from __future__ import annotations

import argparse
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from fractions import Fraction


def _decimal(x: float) -> Fraction:
    return Fraction(f"{x:.6g}")


def sweep_gains(n: int, seed: int = 1):
    """k_i, k_p log-uniform in [1e-6, 1e6], k_v k_p / k_i in (1, 1e6], f_c in [1e-9, 1e9]."""
    from symbolic_friction import Parameters

    rng = random.Random(seed)
    out = []
    for i in range(n):
        k_i = _decimal(10 ** rng.uniform(-6, 6))
        k_p = _decimal(10 ** rng.uniform(-6, 6))
        rho = 1 + (Fraction(1, 10**9) if i % 10 == 0 else _decimal(10 ** rng.uniform(-9, 6)))
        out.append(Parameters(k_v=rho * k_i / k_p, k_p=k_p, k_i=k_i, f_c=_decimal(10 ** rng.uniform(-9, 9))))
    return out


def _wall(cmd: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    return time.perf_counter() - start


def bench_cli(repeats: int) -> None:
    exe = [sys.executable, "-m", "symbolic_friction"]
    with tempfile.TemporaryDirectory() as tmp:
        cmd = exe + ["certify", "--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--out", tmp]
        times = [_wall(cmd) for _ in range(repeats)]
    imports = [_wall([sys.executable, "-c", "import cvxpy"]) for _ in range(repeats)]
    verify = [_wall(exe + ["verify", "proofs/case_a_tightest.json"]) for _ in range(repeats)] if os.path.exists(
        "proofs/case_a_tightest.json"
    ) else []
    print(f"1. CLI, one gain set ({repeats} runs): `symbolic-friction certify --k-p 3 --k-i 4 --k-v 6.4 --f-c 1 --out DIR`")
    print(f"   wall time  median {statistics.median(times) * 1e3:7.0f} ms   min {min(times) * 1e3:7.0f} ms")
    print(f"   of which `python -c 'import cvxpy'` alone: median {statistics.median(imports) * 1e3:7.0f} ms")
    if verify:
        print(f"   `symbolic-friction verify proofs/case_a_tightest.json`: median {statistics.median(verify) * 1e3:7.0f} ms")


def bench_in_process(repeats: int) -> None:
    from symbolic_friction import Parameters
    from symbolic_friction._certify import certify, verify_certificate
    from symbolic_friction._certify.rounding import to_certificate
    from symbolic_friction._certify.search import find_candidate

    params = Parameters.table_i("a")
    start = time.perf_counter()
    import cvxpy  # noqa: F401

    t_import = time.perf_counter() - start
    start = time.perf_counter()
    certify(params, mode="tightest")
    t_first = time.perf_counter() - start
    search_t, round_t, verify_t, total_t = [], [], [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        cand = find_candidate(params, mode="tightest")
        t1 = time.perf_counter()
        cert = to_certificate(cand)
        t2 = time.perf_counter()
        assert verify_certificate(cert).proved
        t3 = time.perf_counter()
        search_t.append(t1 - t0)
        round_t.append(t2 - t1)
        verify_t.append(t3 - t2)
        t4 = time.perf_counter()
        certify(params, mode="tightest")
        total_t.append(time.perf_counter() - t4)
    ms = lambda xs: statistics.median(xs) * 1e3  # noqa: E731
    print(f"2. In process, Table I case (a), tightest ({repeats} repetitions, medians)")
    print(f"   import cvxpy {t_import * 1e3:.0f} ms; first certificate (compiles the problem) {t_first * 1e3:.1f} ms")
    print(
        f"   warm certify() {ms(total_t):.2f} ms = search {ms(search_t):.2f} ms + rounding {ms(round_t):.2f} ms"
        f" + exact verification {ms(verify_t):.2f} ms"
    )


def bench_sweep(n: int) -> None:
    from symbolic_friction._certify import certify_many

    gains = sweep_gains(n)
    print(f"3. Sweep of {n} gain sets (k_i, k_p in [1e-6, 1e6], 10% at k_v k_p/k_i = 1 + 1e-9), amortised")
    for mode in ("tightest", "feasible"):
        start = time.perf_counter()
        items = certify_many(gains, mode=mode, progress=False)
        serial = time.perf_counter() - start
        bad = sum(not item.ok for item in items)
        start = time.perf_counter()
        with ProcessPoolExecutor(2) as pool:
            items2 = certify_many(gains, mode=mode, executor=pool, chunksize=100, progress=False)
        parallel = time.perf_counter() - start
        bad2 = sum(not item.ok for item in items2)
        print(
            f"   {mode:8s}: serial {serial / n * 1e3:6.2f} ms/certificate ({serial:5.2f} s total, {bad} failed); "
            f"ProcessPoolExecutor(2) {parallel / n * 1e3:6.2f} ms/certificate ({parallel:5.2f} s incl. pool start, "
            f"{bad2} failed)"
        )
    print("   target: < 20 ms per certificate amortised")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    args = parser.parse_args()
    repeats = 3 if args.quick else 5
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} CPUs")
    bench_cli(repeats)
    bench_in_process(50 if args.quick else 200)
    bench_sweep(200 if args.quick else 1000)


if __name__ == "__main__":
    main()
