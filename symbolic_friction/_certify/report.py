"""The human-readable proof report (Markdown) written beside each certificate.

It is rendered from a :class:`~._certify.verify.VerificationReport`, i.e. from
what the exact verifier actually checked: the gains and constants, every
instantiated inequality of Lemma 2, Lemma 3 and Proposition 1 with its exact
numbers and ✓/✗, and the overshoot bound ``κ`` of eq. (stabState).  The text
is deterministic (no dates, timings or library versions).
"""

from __future__ import annotations

from fractions import Fraction

from .._infra.rational import format_rational
from .certificate import SCHEMA
from .verify import Check, VerificationReport

__all__ = ["render_markdown"]

_SECTIONS: tuple[tuple[str, tuple[str, ...], str], ...] = (
    (
        "Assumption 1 and the friction model",
        ("lemma2.P", "model"),
        "Assumption 1 (k_i > 0, k_p > 0, k_v·k_p > k_i) is what makes P ≻ 0 (obligation `lemma2.P`); "
        "f_c > 0 is the Coulomb level of eq. (xPhDot).",
    ),
    (
        "Lemma 2 (Lyapunov-like function V)",
        ("lemma2.dVdt", "lemma2.lower_bound"),
        "Item 1: c₁|x|²_𝒜 ≤ V(x) for all x, which holds for every 0 < c₁ ≤ λ_min(P). "
        "Item 2: V decreases at rate c v² with c = 2(k_v k_p − k_i).",
    ),
    (
        "Lemma 3 (bounds on R and R̂, and V̂° ≤ 0)",
        ("lemma3.R", "lemma3.hatV_derivative", "lemma3.hatV_bounds"),
        "Eq. (VandR): V ≤ c₂|x|²_𝒜 on R for c₂ ≥ λ_max(P). "
        "Eq. (hatVdot): V̂° ≤ 0 on R̂ under the conditions on k₁…k₄. "
        "Eq. (hatVandHatR): V̂ = ½wᵀKw with w = (|σ|, |dz(φ)|, |v|) ≥ 0 and |w| = |x|_𝒜; "
        "since k₃ ≥ 0 and w ≥ 0, ½wᵀKw ≥ ½min(k₁,k₂,k₄)|w|², so ĉ₁ ≤ k_j/2 (j = 1, 2, 4) suffices, "
        "and ĉ₂I − K/2 ⪰ 0 gives the upper bound.",
    ),
    (
        "Proposition 1, item 2 (stability bound)",
        ("prop1.stability_bound",),
        "Eq. (stabState): |x(t)|_𝒜 ≤ √(c₂ĉ₂/(c₁ĉ₁))·|x(0)|_𝒜 for all t ≥ 0; the constant is ≥ 1.",
    ),
    (
        "What the certificate says about itself",
        ("provenance",),
        "The obligations it lists are ones instantiated above; a label naming Table I carries Table I's gains; "
        "recorded physical parameters normalise to the gains (paper §II-A).",
    ),
)

_ROLES = {
    "k1": "coefficient of ½σ² in V̂",
    "k2": "coefficient of ½dz(φ)² in V̂",
    "k3": "coefficient of \\|σ\\|·\\|v\\| in V̂",
    "k4": "coefficient of ½v² in V̂",
    "c1": "lower bound of V (≤ λ_min(P))",
    "c2": "upper bound of V on R (≥ λ_max(P))",
    "c1_hat": "lower bound of V̂ on R̂",
    "c2_hat": "upper bound of V̂ on R̂",
    "c": "decrease rate, 2(k_v k_p − k_i)",
}


def _approx(q: Fraction) -> str:
    # float formatting is correctly rounded in CPython, hence identical on every machine
    try:
        return f"{float(q):.6g}"
    except OverflowError:  # beyond float range: say so instead of printing inf
        return "beyond 1e308" if q > 0 else "below -1e308"


def _check_line(check: Check) -> str:
    mark = "✓" if check.holds else "✗ **fails**"
    return f"- {mark} `{check.name}` ({check.obligation}): {check.instance}"


def render_markdown(report: VerificationReport, *, name: str = "certificate.json") -> str:
    """The Markdown proof report for ``report`` (deterministic text, trailing newline).

    Parameters
    ----------
    report : VerificationReport
        Output of :func:`~symbolic_friction.verify_certificate`.
    name : str, keyword-only
        File name of the JSON certificate, quoted in the re-check command.
    """
    cert = report.certificate
    prov = cert.provenance
    title = "Stability certificate"
    if prov is not None and prov.label:
        title += f": {prov.label}"
    if prov is not None:
        title += f" ({prov.mode})"
    verdict = (
        f"**Verdict: PROVED.** All {len(report.checks)} inequalities below hold in exact rational arithmetic."
        if report.proved
        else f"**Verdict: NOT PROVED.** {len(report.failures)} of {len(report.checks)} inequalities fail."
    )
    lines = [
        f"# {title}",
        "",
        "Paper: A. Bisoffi, M. Da Lio, A. R. Teel, L. Zaccarian, *Global asymptotic stability of a PID "
        "control system with Coulomb friction*.",
        "",
        f"Certificate: `{name}` (schema `{SCHEMA}`). Re-check it with `symbolic-friction verify {name}`.",
        "",
        verdict,
        "",
        f"**Overshoot bound (Proposition 1):** |x(t)|_𝒜 ≤ κ·|x(0)|_𝒜 for all t ≥ 0 and every solution, with "
        f"κ = √(c₂ĉ₂/(c₁ĉ₁)) ≤ **{cert.overshoot_bound}** "
        f"(κ² = {format_rational(cert.kappa_squared)} ≈ {_approx(cert.kappa_squared)}).",
        "",
        "## Gains",
        "",
        "| parameter | exact | ≈ |",
        "|---|---|---|",
    ]
    for key, value in cert.parameters.items():
        lines.append(f"| {key} | {format_rational(value)} | {_approx(value)} |")
    if cert.physical is not None:
        lines += ["", "Given as physical parameters (paper §II-A):", "", "| parameter | exact | ≈ |", "|---|---|---|"]
        for key, value in cert.physical.items():
            lines.append(f"| {key} | {format_rational(value)} | {_approx(value)} |")
    lines += ["", "## Constants", "", "| constant | role | exact | ≈ |", "|---|---|---|---|"]
    for key, value in cert.constants.items():
        lines.append(f"| {key} | {_ROLES[key]} | {format_rational(value)} | {_approx(value)} |")
    lines += ["", "## Inequalities (exact)", ""]
    covered: set[int] = set()
    for heading, obligations, explanation in _SECTIONS:
        lines += [f"### {heading}", "", explanation, ""]
        for i, check in enumerate(report.checks):
            if check.obligation in obligations:
                lines.append(_check_line(check))
                covered.add(i)
        lines.append("")
    rest = [check for i, check in enumerate(report.checks) if i not in covered]
    if rest:
        lines += ["### Other", ""] + [_check_line(check) for check in rest] + [""]
    if prov is not None:
        lines += [
            "## Provenance",
            "",
            f"- found by: {prov.package} {prov.package_version}, mode `{prov.mode}`, "
            f"relative margin {format_rational(prov.margin)} on the strict inequalities",
            (f"- numerical search: {prov.solver}, status `{prov.solver_status}` (a candidate only; "
             "the verdict above comes from the exact check)") if prov.search == "sdp" else
            ("- search: the closed form of every gain set (no solver; obligations `closed_form.all_gains` and, "
             "for its k₁ = k₄ variant, `closed_form.balanced` prove it for all gains; the verdict above comes "
             "from the exact check)"),
            f"- proof obligations instantiated: {', '.join(f'`{o}`' for o in prov.obligations)}",
            *([f"- label: {prov.label}"] if prov.label else []),
            "",
        ]
    return "\n".join(lines).rstrip("\n") + "\n"
