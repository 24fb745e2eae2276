"""Benchmark: ``symbolic-friction check`` wall time and time per obligation.

Run from the repository root with the package installed::

    python tests/benchmarks/bench_check.py             # 3 repetitions
    python tests/benchmarks/bench_check.py --repeat 1  # quicker

It prints

1. the wall time of ``symbolic-friction check`` in this checkout as a subprocess
   (what a user waits for, imports included), min and median over the runs,
   and the time until its first obligation row arrives through a pipe (results
   stream line by line; target under 1 s);
2. in a fresh process per repetition: ``derive`` + ``verify`` seconds of each
   obligation (median and max over the repetitions) and their sum.

Target: the whole command under 30 s on a 2-core machine.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

_PER_OBLIGATION = """
import json, time
from symbolic_friction._obligations import all_obligations
start = time.perf_counter()
rows = [(r.id, r.seconds, r.status) for r in (ob.run() for ob in all_obligations())]
print(json.dumps({"rows": rows, "total": time.perf_counter() - start}))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="repetitions (default 3)")
    args = parser.parse_args()

    walls, firsts = [], []
    for _ in range(args.repeat):
        start = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "symbolic_friction", "check"], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        first = None
        lines = []
        for line in proc.stdout:  # type: ignore[union-attr]
            lines.append(line)
            if first is None and line.split(" ", 1)[0] in ("coordinates", "regularization"):
                first = time.perf_counter() - start
        code = proc.wait()
        walls.append(time.perf_counter() - start)
        firsts.append(first if first is not None else float("nan"))
        if code != 0:
            print("".join(lines)[-2000:], proc.stderr.read()[-2000:], sep="\n")  # type: ignore[union-attr]
            raise SystemExit(f"check exited with {code}")
    print(f"symbolic-friction check (subprocess, {args.repeat} runs): min {min(walls):.2f} s, median {statistics.median(walls):.2f} s")
    print(f"first obligation row through a pipe: min {min(firsts):.2f} s, median {statistics.median(firsts):.2f} s")

    per: dict[str, list[float]] = {}
    totals = []
    for _ in range(args.repeat):
        out = subprocess.run([sys.executable, "-c", _PER_OBLIGATION], capture_output=True, text=True, check=True).stdout
        data = json.loads(out)
        totals.append(data["total"])
        for ident, seconds, status in data["rows"]:
            per.setdefault(ident, []).append(seconds)
            if status != "holds":
                print(f"warning: {ident} {status}")
    width = max(len(k) for k in per)
    print(f"\n{'obligation':{width}}  median s  max s")
    for ident, values in per.items():
        print(f"{ident:{width}}  {statistics.median(values):8.3f}  {max(values):5.3f}")
    print(f"{'sum (in process)':{width}}  {statistics.median(totals):8.3f}  {max(totals):5.3f}")
    print(f"\nmachine: {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
