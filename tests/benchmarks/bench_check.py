"""Benchmark: ``symbolic-friction check`` wall time and time per obligation.

Run from the repository root with the package installed::

    python tests/benchmarks/bench_check.py             # 3 repetitions
    python tests/benchmarks/bench_check.py --repeat 1  # quicker
    python tests/benchmarks/bench_check.py --against /path/to/old/checkout  # old and new, interleaved
    python tests/benchmarks/bench_check.py --sides [--against DIR]  # CPU before the fork, of each process, critical path

It prints

1. the wall time of ``symbolic-friction check`` in this checkout as a subprocess
   (what a user waits for, imports included), min and median over the runs,
   and the time until its first obligation row arrives through a pipe (results
   stream line by line; target under 1 s);
2. in a fresh process per repetition: ``derive`` + ``verify`` seconds of each
   obligation (median and max over the repetitions) and their sum.

With ``--against DIR`` it also runs ``check`` from another checkout (``PYTHONPATH=DIR``, in ``DIR``), one
run of each in turn, so that a busy machine slows both alike, and prints both with the load average
before and after.  ``check`` uses both cores (``SYMBOLIC_FRICTION_JOBS=1`` runs it on one).

Target: the whole command within 3 s on a quiet 2-core machine.
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


def _wall(cwd: str | None = None, pythonpath: str | None = None) -> tuple[float, float]:
    """Wall and CPU seconds (this process's children: the command and its worker) of one ``check``."""
    env = dict(os.environ)
    if pythonpath:
        env["PYTHONPATH"] = pythonpath
    before = os.times()
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "symbolic_friction", "check"], cwd=cwd, env=env, capture_output=True,
                          text=True)
    wall = time.perf_counter() - start
    after = os.times()
    if proc.returncode != 0:
        print(proc.stdout[-2000:], proc.stderr[-2000:], sep="\n")
        raise SystemExit(f"check in {cwd or '.'} exited with {proc.returncode}")
    return wall, (after.children_user - before.children_user) + (after.children_system - before.children_system)


_SIDES = """
import argparse, contextlib, io, os, resource, sys, time
start = time.perf_counter()
from symbolic_friction._cli import _parallel, check
at_fork = {}
real = _parallel.run_sections
def timed(*a, **k):
    at_fork["cpu"], at_fork["wall"] = time.process_time(), time.perf_counter() - start
    return real(*a, **k)
_parallel.run_sections = timed
args = argparse.Namespace(json=True, write=False, proofs=None, config=None, no_certificates=False, only=None,
                          junit_xml=None)
with contextlib.redirect_stdout(io.StringIO()):
    code = check.run(args)
me, worker = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
main, child = me.ru_utime + me.ru_stime, worker.ru_utime + worker.ru_stime
serial = at_fork["cpu"]
print(f"exit {code}: wall {time.perf_counter() - start:.2f} s; CPU: {serial:.2f} s before the fork, then main process "
      f"{main - serial:.2f} s, worker {child:.2f} s; critical path {serial + max(main - serial, child):.2f} s; "
      f"load {os.getloadavg()[0]:.2f}")
"""


def sides(repeat: int, other: str | None = None) -> None:
    """CPU seconds of ``check``'s serial start (interpreter, imports, until the fork), then of its main process and
    of its worker: on a quiet 2-core machine the wall time is about the serial part plus the larger of the two
    (the critical path), whatever else the machine runs meanwhile.  With ``other``, that checkout's run comes
    before each of this one's."""
    for _ in range(repeat):
        for name, where in ([("old", other)] if other else []) + [("new" if other else "", None)]:
            env = dict(os.environ, PYTHONPATH=where) if where else None
            out = subprocess.run([sys.executable, "-c", _SIDES], capture_output=True, text=True, check=True, cwd=where,
                                 env=env)
            print(f"{name + ': ' if name else ''}{out.stdout.strip()}")


def compare(other: str, repeat: int) -> None:
    """This checkout and ``other``, interleaved (module docstring)."""
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    if sys.flags.dont_write_bytecode or os.environ.get("PYTHONDONTWRITEBYTECODE"):
        print("note: PYTHONDONTWRITEBYTECODE is set: modules without a __pycache__ are compiled on every run")
    new, old = [], []
    for _ in range(repeat):
        old.append(_wall(other, other))
        new.append(_wall())
    for name, runs in (("old (" + other + ")", old), ("new (this checkout)", new)):
        walls, cpus = [w for w, _ in runs], [c for _, c in runs]
        print(f"{name}: wall min {min(walls):.2f} s, median {statistics.median(walls):.2f} s; "
              f"CPU (user + sys, both processes) min {min(cpus):.2f} s, median {statistics.median(cpus):.2f} s")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="repetitions (default 3)")
    parser.add_argument("--against", metavar="DIR", default=None,
                        help="also time `check` from the checkout in DIR, interleaved with this one")
    parser.add_argument("--sides", action="store_true",
                        help="CPU seconds of check's serial start, main process and worker, and the critical path, per run")
    args = parser.parse_args()
    if args.sides:
        sides(args.repeat, args.against)
        return
    if args.against:
        compare(args.against, args.repeat)
        return

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
