"""Benchmark: what ``check``'s self-check and the hunting files' staleness cost.

Run from the repository root with the package installed::

    python tests/benchmarks/bench_self_check.py             # 5 repetitions
    python tests/benchmarks/bench_self_check.py --repeat 3

It prints, each in a fresh process (imports of sympy, flint and the package
excluded, as ``check`` has made them before this section runs), min and median
over the repetitions (wall time, and CPU time, which a busy machine inflates less) of

1. the self-check: every shipped false certificate verified and the true
   controls proved (:func:`symbolic_friction._certify.self_check.refuse_false_certificates`),
   split by template, and the hunting proof's rigour cases
   (:func:`symbolic_friction._certify.hunting_rigour.rigour_cases`) and the decision procedures' cases
   (:func:`symbolic_friction._obligations._decide_cases.decision_cases`, sympy warmed up first);
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
from symbolic_friction._obligations import all_obligations
from symbolic_friction._obligations._decide_cases import decision_cases
from flint import arb_mat
arb_mat([[1]]).exp()
for ob in all_obligations():
    if ob.id.startswith("lemma2"):
        ob.run()  # sympy warmed up by obligations, as in `check`
out = {}

def timed(name, f):
    c, t = time.process_time(), time.perf_counter()
    value = f()
    out[name] = (time.perf_counter() - t, time.process_time() - c)
    return value

assert timed("self-check: files", self_check.refuse_false_certificates).ok
manifest = json.loads((self_check.DIRECTORY / "manifest.json").read_text())["false_certificates"]
for template in ("stability", "quadratic", "hunting"):
    def part():
        with shared_proofs():
            for entry in manifest:
                if entry["template"] == template:
                    self_check._one(self_check.DIRECTORY / entry["file"], entry)
    timed(f"  of which {template}", part)
assert all(c.ok for c in timed("self-check: rigour cases", rigour_cases))
assert all(c.ok for c in timed("self-check: decision cases", decision_cases))
names = sorted(str(p.relative_to("proofs")) for p in Path("proofs/hunting").glob("*.json"))
timed("hunting files: verify", lambda: [verify_template_file(Path("proofs") / n) for n in names])
assert all(e.ok for e in timed("hunting files: verify + stale", lambda: check_listed_certificates("proofs", names)))
print(json.dumps(out))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    runs = [json.loads(subprocess.run([sys.executable, "-c", _ONE], check=True, capture_output=True, text=True).stdout)
            for _ in range(args.repeat)]
    print(f"{'part':36s} {'wall min':>9s} {'wall median':>12s} {'CPU median':>11s}   ({args.repeat} fresh processes)")
    for key in runs[0]:
        wall = [r[key][0] for r in runs]
        cpu = [r[key][1] for r in runs]
        print(f"{key:36s} {min(wall):9.3f} {statistics.median(wall):12.3f} {statistics.median(cpu):11.3f}")
    parts = ("self-check: files", "self-check: rigour cases", "self-check: decision cases", "hunting files: verify + stale")
    for i, label in ((0, "wall"), (1, "CPU")):
        added = [sum(r[p][i] for p in parts) - r["hunting files: verify"][i] for r in runs]
        print(f"added to check, {label:4s} (min, median)      {min(added):9.3f} {statistics.median(added):12.3f}")

if __name__ == "__main__":
    main()
