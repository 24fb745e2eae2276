"""Benchmark of ``symbolic-friction crosscheck``: wall time for the four
Table I certificates with 100,000 trajectories per gain set (the default),
and the numbers worth quoting: tightness ratios, the overshoot adversary's
worst found per scale of ``x(0)``, worst margins, the empirical ISS gain and
Corollary 1's worst found over selections of ``SGN_ρ`` at ρ = 0.01, 0.1, 1
with the Stribeck family below it.

Run from the repository root::

    python tests/benchmarks/bench_crosscheck.py            # library call + CLI subprocess
    python tests/benchmarks/bench_crosscheck.py --no-cli

This is a script that prints figures, not a timed test.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trajectories", type=int, default=100_000)
    parser.add_argument("--no-cli", action="store_true", help="skip the end-to-end CLI timing")
    parser.add_argument("--rhos", default="0,0.01,0.1,1", help="comma-separated ρ for the ISS table")
    parser.add_argument("--search-rhos", default="0.01,0.1,1", help="comma-separated ρ for the worst found ('' skips)")
    args = parser.parse_args()

    sys.path.insert(0, str(REPO))
    from symbolic_friction import Parameters
    from symbolic_friction._crosscheck import crosscheck, iss_gain

    files = [REPO / "proofs" / f"case_{c}_{m}.json" for c in "ab" for m in ("feasible", "tightest")]
    print(f"machine: {os.cpu_count()} CPU(s); load average {os.getloadavg()[0]:.2f}")
    t0 = time.perf_counter()
    report = crosscheck(files, trajectories=args.trajectories, progress=False)
    wall = time.perf_counter() - t0
    print(f"crosscheck (library), {args.trajectories} trajectories per gain set, 4 certificates: {wall:.1f} s "
          f"({'passed' if report.passed else 'FAILED'})")
    seen = set()
    for c in report.checks:
        if c.claims.params not in seen:
            seen.add(c.claims.params)
            print(f"  gain set of {c.label}: {c.seconds:.1f} s")
    print()
    print(f"{'certificate':18s} {'kappa':>9s} {'max overshoot':>14s} {'tightness':>9s}  per search mode (observed/kappa)")
    for c in report.checks:
        t = c.tightness
        modes = ", ".join(f"{m} {t[m]:.3f}" for m in ("random spheres", "grid", "special", "adversarial") if m in t)
        print(f"{c.label:18s} {c.claims.kappa:9.5f} {max(c.max_overshoot.values()):14.5f} {t['all']:9.4f}  {modes}")
    print()
    seen = set()
    for c in report.checks:
        if c.overshoot_search is None or c.claims.params in seen:
            continue
        seen.add(c.claims.params)
        s = c.overshoot_search
        print(f"overshoot adversary, gain set of {c.label} ({s.evaluations} trajectories):")
        print("  |x(0)|_A/f_c: " + "  ".join(f"{a:.3g}: {b:.5f}" for a, b in zip(s.scales, s.ratio)))
        for cc in report.checks:
            if cc.claims.params == c.claims.params:
                print(f"  {cc.label}: {s.describe(cc.claims.kappa)}")
    print()
    print("worst relative margins (smallest slack/scale; > -rtol passes):")
    ids = [r.id for r in report.checks[0].results]
    print(f"{'property':28s} " + " ".join(f"{c.label:>16s}" for c in report.checks))
    for k, pid in enumerate(ids):
        print(f"{pid:28s} " + " ".join(f"{c.results[k].worst_margin:16.3e}" for c in report.checks))
    print()
    rhos = tuple(args.rhos.split(","))
    for case in "ab":
        t0 = time.perf_counter()
        search = tuple(r for r in args.search_rhos.split(",") if r)
        est = iss_gain(Parameters.table_i(case), rhos, search_rhos=search)
        print(f"Corollary 1, case ({case}), empirical gain gamma(rho) [{time.perf_counter() - t0:.1f} s]:")
        for law in est.laws:
            vals = ", ".join(f"rho={r:g}: {g:.4g}" for r, g in zip(est.rhos, est.gamma[law]))
            print(f"  {law:10s} {vals}  (tail events at largest rho: {est.hunting[law][-1]})")
        for rho, w in sorted(est.worst_found.items()):
            cands = ", ".join(f"{k} {v:.4g}" for k, v in w.candidates.items())
            strib = ", ".join(f"v_s={k}: {v:.4g}" for k, v in w.stribeck.items())
            print(f"  rho={rho:g}: worst found {w.bound:.5g} by {w.law} from z(0)={w.initial_state}")
            print(f"    candidates: {cands}; Stribeck f_s=(1+rho)f_c: {strib}; "
                  f"{'Stribeck family below' if w.covers_stribeck else 'SEARCH NOT DONE'}")
    if not args.no_cli:
        print()
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "symbolic_friction", "crosscheck"], cwd=REPO,
                              capture_output=True, text=True)
        print(f"CLI `symbolic-friction crosscheck` (defaults: 100000 trajectories, every proofs/*.json): "
              f"{time.perf_counter() - t0:.1f} s wall, exit status {proc.returncode}")
        print("  " + proc.stdout.strip().splitlines()[-1])


if __name__ == "__main__":
    main()
