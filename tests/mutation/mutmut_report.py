"""The report of mutmut's run over the trusted base: ``tests/mutation/mutmut-report.md``.

Usage (from the repository root, after ``pip install -e '.[test,mutation]'``)::

    mutmut run --max-children 1             # configured in pyproject.toml, [tool.mutmut]
    python tests/mutation/mutmut_report.py --out tests/mutation/mutmut-report.md

It reads ``mutmut results --all true`` and counts, per module of the
trusted base, the mutants and how each ended (killed, survived, timeout,
no tests, …).  Every survivor must be listed in :data:`EQUIVALENT` with a
one-line argument that it cannot change a result, or the report says
``OPEN`` and the exit status is 1.  ``--scope`` restricts the count to
the functions that decide (the rest of a module, e.g. its table layout, is
reported separately as out of scope).
"""

from __future__ import annotations

import argparse
import fnmatch
import re
import subprocess
import sys
from collections import Counter, defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from tests.mutation.mutmut_equivalent import EQUIVALENT, PENDING, SCOPE  # noqa: E402

_LINE = re.compile(r"^\s*(?P<name>\S+): (?P<status>.+?)\s*$")


def results() -> dict[str, str]:
    out = subprocess.run(["mutmut", "results", "--all", "true"], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    found = {}
    for line in out.splitlines():
        m = _LINE.match(line)
        if m and "__mutmut_" in m["name"]:
            found[m["name"]] = m["status"]
    return found


def module_of(name: str) -> str:
    return name.split(".x_")[0].split(".xǁ")[0]


def function_of(name: str) -> str:
    tail = name[len(module_of(name)) + 1:]
    return tail.split("__mutmut_")[0].replace("xǁ", "").replace("ǁ", ".").removeprefix("x_")


def in_scope(name: str) -> bool:
    return any(fnmatch.fnmatchcase(name, pattern) for pattern in SCOPE)


def pending(name: str, status: str) -> bool:
    """In scope but not run yet (:data:`PENDING`): counted, listed apart, never called killed or equivalent."""
    return status == "not checked" and any(fnmatch.fnmatchcase(name, pattern) for pattern in PENDING)


def render(found: dict[str, str]) -> tuple[str, bool]:
    per: dict[str, Counter] = defaultdict(Counter)
    out_of_scope: dict[str, Counter] = defaultdict(Counter)
    not_run: dict[str, Counter] = defaultdict(Counter)
    survivors = []
    for name, status in sorted(found.items()):
        target = per if in_scope(name) else out_of_scope
        target[module_of(name)][status] += 1
        if in_scope(name) and pending(name, status):
            not_run[module_of(name)][function_of(name)] += 1
        # a timeout is a mutant whose tests did not finish: it did not pass them
        elif in_scope(name) and status not in ("killed", "timeout"):
            survivors.append((name, status))
    statuses = ["killed", "survived", "timeout", "no tests", "suspicious", "segfault", "skipped", "not checked"]
    rows = ["| module | mutants | " + " | ".join(statuses) + " |", "|---|---:|" + "---:|" * len(statuses)]
    for mod in sorted(per):
        c = per[mod]
        rows.append(f"| `{mod}` | {sum(c.values())} | " + " | ".join(str(c.get(s, 0)) for s in statuses) + " |")
    total = Counter()
    for c in per.values():
        total.update(c)
    rows.append(f"| **all in scope** | {sum(total.values())} | " + " | ".join(str(total.get(s, 0)) for s in statuses) + " |")
    ok = True
    lines = ["", "## Every mutant in scope that was not killed", ""]
    if not survivors:
        lines.append("None.")
    for name, status in survivors:
        why = EQUIVALENT.get(name)
        if why is None:
            ok = False
            why = "OPEN (neither killed nor argued equivalent yet)"
        lines.append(f"- `{name}` ({status}): {why}")
    if not_run:
        lines += ["", "## In scope, not run yet (`not checked`: neither killed nor argued)", ""]
        for mod in sorted(not_run):
            lines.append(f"- `{mod}`: " + ", ".join(f"{fn} {n}" for fn, n in sorted(not_run[mod].items())))
    oos = ["", "## Out of scope (counted, not required to be killed)", ""]
    for mod in sorted(out_of_scope):
        c = out_of_scope[mod]
        oos.append(f"- `{mod}`: {sum(c.values())} mutants (" + ", ".join(f"{k} {v}" for k, v in sorted(c.items())) + ")")
    return "\n".join(rows + lines + oos), ok


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", metavar="FILE")
    parser.add_argument("--header", metavar="FILE", help="prepend this file's text (the hand-written part)")
    args = parser.parse_args(argv)
    body, ok = render(results())
    text = (Path(args.header).read_text(encoding="utf-8") if args.header else "") + body + "\n"
    print(text)
    if args.out:
        from symbolic_friction._infra.io import atomic_write_text

        atomic_write_text(Path(args.out), text)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
