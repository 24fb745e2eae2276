"""Benchmark of ``symbolic-friction figures``: the wall time of every registered figure, end to end (a CLI
subprocess from the repository root, so that the Table I certificates come from ``proofs/``), with the
machine's load before and after, and the CPU time of the processes that drew them.

Run from the repository root::

    python tests/benchmarks/bench_figures.py                    # this tree, --jobs = the number of cores
    python tests/benchmarks/bench_figures.py --jobs 1           # one figure after the other
    python tests/benchmarks/bench_figures.py --tree /other/checkout --no-jobs   # another tree (one without --jobs)

The machine may be shared: compare trees in one session, side by side, and quote the load averages
(``os.getloadavg``, as ``uptime`` prints them) with the times.  This is a script that prints figures, not a
timed test.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def _load() -> str:
    return ", ".join(f"{x:.2f}" for x in os.getloadavg())


def run(tree: Path, *, jobs: int | None, only: list[str] | None) -> tuple[float, float, int]:
    """Wall and CPU seconds of one ``figures`` run from ``tree``, and the number of files it wrote."""
    with tempfile.TemporaryDirectory() as out:
        cmd = [sys.executable, "-m", "symbolic_friction", "figures", "--out", out]
        if jobs is not None:
            cmd += ["--jobs", str(jobs)]
        if only:
            cmd += ["--only", *only]
        env = dict(os.environ, PYTHONPATH=str(tree))
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if proc.returncode != 0:
            sys.exit(f"figures failed in {tree} (exit {proc.returncode}):\n{proc.stderr}")
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        return wall, cpu, len(list(Path(out).iterdir()))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tree", type=Path, default=REPO, help="the checkout to time (default: this one)")
    parser.add_argument("--jobs", type=int, default=None, help="--jobs of the run (default: the command's default)")
    parser.add_argument("--no-jobs", action="store_true", help="pass no --jobs (a tree from before the option)")
    parser.add_argument("--only", nargs="+", default=None, metavar="NAME", help="time only these figures")
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()

    print(f"tree {args.tree}, {os.cpu_count()} cores")
    for i in range(args.repeats):
        load = _load()
        wall, cpu, n = run(args.tree, jobs=None if args.no_jobs else args.jobs, only=args.only)
        print(f"run {i + 1}: wall {wall:.1f} s, CPU {cpu:.1f} s (all processes), {n} files; "
              f"load average before {load}, after {_load()}")


if __name__ == "__main__":
    main()
