"""``check``'s section that checks the trusted base where it runs: known-false certificates must be refused.

It calls :func:`symbolic_friction._certify.self_check.refuse_false_certificates`
(the verifiers on the certificates shipped in the package),
:func:`symbolic_friction._certify.hunting_rigour.rigour_cases` (the hunting
proof's decisions on inputs built to be refused) and
:func:`symbolic_friction._obligations._decide_cases.decision_cases` (the
obligations' decision procedures, likewise), and renders them.  Only the
standard library is imported at module level (fast ``--help``).
"""

from __future__ import annotations

import argparse

from ._sections import Section


def self_check_section(args: argparse.Namespace) -> Section:
    """Every shipped false certificate refused naming its premise, every true one proved, every rigour case decided right."""
    from .._certify.hunting_rigour import rigour_cases
    from .._certify.self_check import refuse_false_certificates
    from .._infra.junit import Case
    from .._obligations._decide_cases import decision_cases

    result = refuse_false_certificates()
    cases = rigour_cases() + decision_cases()
    false = [r for r in result.refusals if r.premise is not None]
    true = [r for r in result.refusals if r.premise is None]
    # one row per group; a file or case that fails gets its own row (all of them are in --json and JUnit)
    groups: dict[str, list[bool]] = {}
    for r in result.refusals:
        groups.setdefault(r.file.split("_")[0], []).append(r.ok)
    rows = [(f"{group} files", f"{len(oks)} ({'true' if group == 'true' else 'false'})",
             "proved" if group == "true" else "refused, naming their premise", "ok" if all(oks) else "FAILED")
            for group, oks in groups.items()]
    rows.append(("rigour cases", str(len(cases)), "decided as built", "ok" if all(c.ok for c in cases) else "FAILED"))
    rows += [(r.file, r.premise or "(true)", ", ".join(r.named) or "proved", "FAILED") for r in result.refusals if not r.ok]
    rows += [(c.name, c.expected, c.got, "FAILED") for c in cases if not c.ok]
    summary = (f"self-check: {sum(r.ok for r in false)} of {len(false)} false certificates refused naming their premise, "
               f"{sum(r.ok for r in true)} of {len(true)} true ones proved, "
               f"{sum(c.ok for c in cases)} of {len(cases)} rigour cases (hunting proof, decision procedures) decided right")
    notes = [summary + f" ({result.seconds:.2f} s)"]
    notes += [f"FAILED self-check {r.describe()}" for r in result.refusals if not r.ok]
    notes += [f"FAILED self-check: no false certificate breaks the premise {name!r}" for name in result.uncovered]
    notes += [f"FAILED self-check {c.name}: expected {c.expected}, got {c.got}" for c in cases if not c.ok]
    junit = [Case(name=r.file, classname="check.self_check", failure=None if r.ok else r.describe()) for r in result.refusals]
    junit += [Case(name=c.name, classname="check.self_check", failure=None if c.ok else f"expected {c.expected}, got {c.got}")
              for c in cases]
    return Section(
        "Self-check (the verifiers refuse known-false certificates)",
        ("files or case", "how many / breaks", "must be / got", "verdict"),
        rows,
        {"self_check": [{"file": r.file, "premise": r.premise, "expected": list(r.expected), "named": list(r.named), "ok": r.ok}
                        for r in result.refusals]
                       + [{"case": c.name, "expected": c.expected, "got": c.got, "ok": c.ok} for c in cases]},
        result.ok and bool(cases) and all(c.ok for c in cases),
        notes,
        summary=summary,
        counts={"self_check_files": len(result.refusals), "self_check_ok": sum(r.ok for r in result.refusals) + sum(c.ok for c in cases),
                "self_check_cases": len(cases)},
        cases=junit,
    )
