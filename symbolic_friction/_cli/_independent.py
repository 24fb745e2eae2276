"""``check``'s section that runs the independent checker (:mod:`symbolic_friction.independent`) beside the main one.

Every configured certificate must be proved by it too, every shipped known-false certificate refused and
every true control proved: a file is proved only if both verifiers prove it.  Only the standard library is
imported at module level (fast ``--help``).
"""

from __future__ import annotations

import argparse
import time

from ._sections import Section


def independent_section(args: argparse.Namespace) -> Section:
    """The independent checker on the configured certificates and on the self-check's files."""
    import json

    from .._certify.self_check import DIRECTORY
    from .._infra.junit import Case
    from ..independent import Malformed, check_file, shared
    from ._sections import resolve_target

    start = time.perf_counter()
    files: list[tuple[str, object, bool]] = []  # (path, shown as, must be proved)
    if not getattr(args, "no_certificates", False):
        where = resolve_target(args)
        files += [(str(where.proofs / name), str(where.proofs / name), True) for name in (where.certificates or ())]
    manifest = json.loads((DIRECTORY / "manifest.json").read_text(encoding="utf-8"))["false_certificates"]
    files += [(str(DIRECTORY / entry["file"]), entry["file"], entry["premise"] is None) for entry in manifest]
    results = []
    with shared():  # the known-false files are edited copies of true ones: what they share is decided once
        for path, shown, must_prove in files:
            try:
                verdict = check_file(path)
                proved, why = verdict.proved, "; ".join(verdict.failing[:4])
            except Malformed as exc:
                proved, why = False, f"not readable: {exc}"
            except Exception as exc:  # noqa: BLE001 - a crash of the second checker is its failure, shown, never a traceback
                proved, why = False, f"crashed: {type(exc).__name__}: {exc}"
            results.append((shown, must_prove, proved, why))
    seconds = time.perf_counter() - start
    groups = {"configured certificates": [r for r in results[: len(results) - len(manifest)]],
              "true controls": [r for r in results[len(results) - len(manifest):] if r[1]],
              "false certificates": [r for r in results[len(results) - len(manifest):] if not r[1]]}
    ok_of = lambda r: r[1] == r[2]  # noqa: E731 - proved exactly when it must be
    rows = [(name, str(len(rs)), "refused" if name.startswith("false") else "proved", "ok" if all(map(ok_of, rs)) else "FAILED")
            for name, rs in groups.items() if rs]
    rows += [(str(r[0]), "must be proved" if r[1] else "must be refused", r[3] or "proved", "FAILED")
             for r in results if not ok_of(r)]
    counts = {name: (sum(map(ok_of, rs)), len(rs)) for name, rs in groups.items()}
    summary = ("independent checker: " + ", ".join(
        f"{ok} of {n} {name} {'refused' if name.startswith('false') else 'proved'}" for name, (ok, n) in counts.items() if n))
    notes = [summary + f" ({seconds:.2f} s)"]
    notes += [f"FAILED independent checker: {r[0]} {'is not proved' if r[1] else 'is proved although false'}"
              + (f" ({r[3]})" if r[3] else "") for r in results if not ok_of(r)]
    return Section(
        "Independent checker (a second verifier of every certificate kind)",
        ("files", "how many / must be", "must be / got", "verdict"),
        rows,
        {"independent": [{"file": str(r[0]), "must_prove": r[1], "proved": r[2], "failing": r[3]} for r in results]},
        all(map(ok_of, results)) and bool(results),
        notes,
        summary=summary,
        counts={"independent_files": len(results), "independent_ok": sum(map(ok_of, results))},
        cases=[Case(name=str(r[0]), classname="check.independent", failure=None if ok_of(r) else r[3] or "proved although false")
               for r in results],
    )
