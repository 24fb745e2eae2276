"""Benchmark: what ``check``'s self-check and the hunting files' staleness cost.

Run from the repository root with the package installed::

    python tests/benchmarks/bench_self_check.py             # 5 repetitions
    python tests/benchmarks/bench_self_check.py --repeat 3

It prints, each in a fresh process (imports of sympy, flint and the package
excluded, as ``check`` has made them before this section runs), min and median
over the repetitions (wall time; the CPU time of the whole self-check too, which a busy machine inflates less) of

1. the self-check: every shipped false certificate verified and the true
   controls proved (:func:`symbolic_friction._certify.self_check.refuse_false_certificates`),
   split by template, and the hunting proof's rigour cases
   (:func:`symbolic_friction._certify.hunting_rigour.rigour_cases`);
2. the five committed hunting files: verification alone, and verification
   plus staleness (regenerating each from its own box), as ``check`` runs them.

Budget: the self-check and the staleness together under 0.3 s on a quiet 2-core machine.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys

_ONE = r"""
import json, time
from pathlib import Path
from symbolic_friction._certify import self_check
from symbolic_friction._certify.hunting import shared_proofs
from symbolic_friction._certify.hunting_rigour import rigour_cases
from symbolic_friction._certify.templates import check_listed_certificates, verify_template_file
import symbolic_friction._obligations  # sympy, as `check` has imported it by then
from flint import arb_mat
arb_mat([[1]]).exp()
out = {}
c = time.process_time()
t = time.perf_counter(); result = self_check.refuse_false_certificates(); out["self-check: files"] = time.perf_counter() - t
out["self-check: files, CPU time"] = time.process_time() - c
assert result.ok
manifest = json.loads((self_check.DIRECTORY / "manifest.json").read_text())["false_certificates"]
for template in ("stability", "quadratic", "hunting"):
    t = time.perf_counter()
    with shared_proofs():
        for entry in manifest:
            if entry["template"] == template:
                self_check._one(self_check.DIRECTORY / entry["file"], entry)
    out[f"  of which {template}"] = time.perf_counter() - t
t = time.perf_counter(); assert all(c.ok for c in rigour_cases()); out["self-check: rigour cases"] = time.perf_counter() - t
names = sorted(str(p.relative_to("proofs")) for p in Path("proofs/hunting").glob("*.json"))
t = time.perf_counter()
for n in names:
    verify_template_file(Path("proofs") / n)
out["hunting files: verify"] = time.perf_counter() - t
t = time.perf_counter(); entries = check_listed_certificates("proofs", names); out["hunting files: verify + stale"] = time.perf_counter() - t
assert all(e.ok for e in entries)
print(json.dumps(out))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    runs = [json.loads(subprocess.run([sys.executable, "-c", _ONE], check=True, capture_output=True, text=True).stdout)
            for _ in range(args.repeat)]
    print(f"{'part':36s} {'min s':>8s} {'median s':>9s}   ({args.repeat} fresh processes)")
    for key in runs[0]:
        values = [r[key] for r in runs]
        print(f"{key:36s} {min(values):8.3f} {statistics.median(values):9.3f}")
    added = [r["self-check: files"] + r["self-check: rigour cases"] + r["hunting files: verify + stale"] - r["hunting files: verify"]
             for r in runs]
    print(f"{'added to check (self-check + stale)':36s} {min(added):8.3f} {statistics.median(added):9.3f}")


if __name__ == "__main__":
    main()
