"""Text tables and counterexample files of a cross-check run."""

from __future__ import annotations

import json
import math
import re
from fractions import Fraction
from pathlib import Path
from typing import Any

from ._run import SEARCH_MODES, CertificateCheck, CrosscheckReport

__all__ = ["format_report", "format_tightness", "write_counterexamples", "TOLERANCE_NOTE"]

TOLERANCE_NOTE = (
    "margin = smallest relative slack (rhs - lhs)/scale; a failure is a slack below -rtol = {rtol:g}. "
    "The event simulator matches an mpmath reference to ~1e-14 relative (tests hold it to 1e-13), so quadratic "
    "forms err by far less than 1e-12 of their scale: rtol leaves a safety factor of at least 1e4."
)


def _fmt(x: float) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if x == math.inf:
        return "inf"
    return f"{x:+.2e}"


def format_check(check: CertificateCheck) -> str:
    """The table of one certificate."""
    cl = check.claims
    lines = [
        f"{check.label}: k_p={cl.exact['k_p']} k_i={cl.exact['k_i']} k_v={cl.exact['k_v']} f_c={cl.exact['f_c']}, "
        f"kappa={cl.exact['overshoot_bound']}  ({check.source or 'in memory'})"
        + ("" if cl.is_paper else f"; {cl.template_name} template: only its bound kappa is a claim"),
        f"  {check.trajectories} trajectories on [0, {check.horizon:g}] ({check.incomplete} incomplete), "
        f"{check.seconds:.1f} s for this gain set; "
        + {True: "proved exactly before the cross-check", False: "NOT proved", None: "candidate constants (not verified)"}[check.proved],
        f"  {'property':28s} {'paper':40s} {'traj':>6s} {'checked':>9s} {'margin':>10s} {'fail':>6s}",
    ]
    for r in check.results:
        extra = f"  ({r.inconclusive} within tolerance of 0)" if r.id == "remark.stick_sigma" and r.inconclusive else ""
        lines.append(
            f"  {r.id:28s} {r.paper[:40]:40s} {r.trajectories:6d} {r.samples:9d} {_fmt(r.worst_margin):>10s} "
            f"{r.failures:6d}{'  FAIL' if r.failures else ''}{extra}"
        )
    ratios = []
    for r, const, name in (
        ("lemma2.lower_bound", cl.c1, "c1"), ("lemma3.V_upper", cl.c2, "c2"),
        ("lemma3.hatV_lower", cl.c1_hat, "c1_hat"), ("lemma3.hatV_upper", cl.c2_hat, "c2_hat"),
    ):
        res = next((x for x in check.results if x.id == r), None)
        for key, value in (res.details.items() if res else ()):
            ratios.append(f"{key} = {value:.5g} ({name} = {const:.5g})")
    if ratios:
        lines.append("  observed ratios: " + "; ".join(ratios))
    tight = check.tightness
    parts = [f"{mode} {check.max_overshoot[mode]:.4f} ({tight[mode]:.3f})" for mode in SEARCH_MODES if mode in tight]
    lines.append("  overshoot max_t |x(t)|_A/|x(0)|_A (observed/kappa): " + "; ".join(parts))
    if "all" in tight:
        w = check.worst_state
        lines.append(
            f"  tightness ratio {tight['all']:.4f} at x(0) = ({w[0]:.6g}, {w[1]:.6g}, {w[2]:.6g})"
        )
    search = check.overshoot_search
    if search is not None:
        from ._overshoot import linear_limit

        lin, t_lin = linear_limit(cl.params)
        lines.append(f"  adversary (differential evolution with restarts, {search.evaluations} trajectories; peak refined "
                     f"on the closed form): worst found per scale |x(0)|_A/f_c")
        lines.append("    " + "  ".join(f"{s:.3g}: {r:.4f}" for s, r in zip(search.scales, search.ratio)))
        lines.append(f"  {search.describe(cl.kappa)}; friction-free limit sup_t |e^(At)| = {lin:.6f} at t = {t_lin:.4g}")
    att = next((r for r in check.results if r.id == "prop1.attractivity"), None)
    if att is not None and att.details:
        d = att.details
        more = ""
        if d.get("extended"):
            more = (f"; {d['extended']} needed a longer horizon "
                    f"(latest reached theta at t = {d['latest_time_to_theta']:.4g})")
        lines.append(
            f"  attractivity: median |x(T)|_A/|x(0)|_A = {d['median_final_ratio']:.3g}, "
            f"max {d['max_final_ratio']:.3g}{more}"
        )
        if "median |s(T)|" in d:
            lines.append(
                f"  in z at T: median |s| = {d['median |s(T)|']:.3g}, median |v| = {d['median |v(T)|']:.3g}, "
                f"e_i in [-f_c/k_i, f_c/k_i] for {100 * d['share e_i(T) in [-f_c/k_i, f_c/k_i]']:.1f} %"
            )
    return "\n".join(lines)


def format_report(report: CrosscheckReport) -> str:
    """All tables, the decay and ISS summaries, and the verdict."""
    out = [TOLERANCE_NOTE.format(rtol=report.rtol)]
    for check in report.checks:
        out.append("")
        out.append(format_check(check))
    for label, fit in report.decay.items():
        out.append("")
        out.append(f"decay of |x(t)|_A for {label}: {fit.describe()}")
    for label, est in report.iss.items():
        out.append("")
        out.append(f"Corollary 1, empirical ISS gain for {label} "
                   f"(moreau, h={est.h:g}, tail [T/2, T], T={est.horizon:g}):")
        out.append(f"  {'law':11s} {'rho':>8s} {'gamma':>10s} {'from A':>10s} {'tail':>10s} {'tail events':>12s}")
        for law, rho, g, ga, gt, ev in est.rows():
            out.append(f"  {law:11s} {rho:8.3g} {g:10.4g} {ga:10.4g} {gt:10.4g} {ev:12d}")
        for law, slope in est.slope.items():
            out.append(f"  {law}: log-log slope of gamma at small rho = {slope:.3f}")
        for rho, w in sorted(getattr(est, "worst_found", {}).items()):
            stribeck = ", ".join(f"v_s={v}: {b:.4g}" for v, b in w.stribeck.items())
            out.append(f"  rho = {rho:g}: worst found {w.bound:.5g} ({w.law}, z(0) = {w.initial_state}); "
                       f"Stribeck f_s=(1+rho)f_c {stribeck}"
                       + ("" if w.covers_stribeck else "  SEARCH NOT DONE: a Stribeck law goes higher"))
    out.append("")
    out.append(format_tightness(report))
    out.append("")
    if report.incomplete:
        out.append(
            f"INCOMPLETE: {report.incomplete} trajectories hit the event limit before their horizon; "
            "nothing was checked on their unsimulated part and none counts as holding"
        )
    out.append(report.summary())
    return "\n".join(out)


def format_tightness(report: CrosscheckReport) -> str:
    """Per certificate: its template, proven κ, the worst overshoot observed and their ratio (the tightness).

    The worst is over every trajectory of the gain set and the adversary's
    peaks refined on the closed form; the bound ``|x(t)|_𝒜 ≤ κ|x(0)|_𝒜`` was
    checked on each (``prop1.stability``), so ``held`` means no trajectory
    exceeded κ by more than the tolerance.
    """
    lines = [
        f"tightness per certificate = worst observed sup_t |x(t)|_A/|x(0)|_A / proven kappa; |x(t)|_A <= kappa |x(0)|_A "
        f"checked trajectory by trajectory at every sample, event and refined peak (a relative slack below "
        f"-rtol = {report.rtol:g} fails):",
        f"  {'certificate':28s} {'template':10s} {'kappa':>10s} {'worst':>9s} {'tightness':>9s} {'kappa_lin >=':>12s}"
        f" {'kappa/kappa_lin':>15s}  bound",
    ]
    for check in report.checks:
        stability = next((r for r in check.results if r.id == "prop1.stability"), None)
        worst = max(check.max_overshoot.values()) if check.max_overshoot else math.nan
        held = "-" if stability is None else ("held" if stability.passed else f"VIOLATED ({stability.failures})")
        kappa = check.claims.exact["overshoot_bound"]
        floor = _kappa_lin_floor(check.claims.params)
        # a lower end is printed rounded down and κ/κ_lin ≤ κ/(lower end) rounded up, so both stay true as printed
        lin = "-" if floor is None else f"{_decimal(floor, 7, 'down'):>12s}"
        ratio = "-" if floor is None else f"{_decimal(Fraction(kappa) / floor, 5, 'up'):>15s}"
        lines.append(f"  {check.label[:28]:28s} {check.claims.template_name:10s} {kappa:>10s} "
                     f"{worst:9.5f} {check.tightness.get('all', math.nan):9.4f} {lin:>12s} {ratio:>15s}  {held}")
    lines.append("  kappa_lin >= : the proven lower end of sup_t ||e^(At)||_2, below which no certificate's kappa can go "
                 "(friction is negligible for large states), rounded down; kappa/kappa_lin rounded up")
    return "\n".join(lines)


def _decimal(q: Fraction, digits: int, direction: str) -> str:
    """``q`` to ``digits`` significant digits, rounded in ``direction``, as a plain decimal."""
    from .._certify.rounding import round_significant

    # a decimal of at most 15 significant digits prints back exactly from its nearest float
    return f"{float(round_significant(q, digits, direction=direction)):.{digits}g}"


def _kappa_lin_floor(params: Any) -> Fraction | None:
    """The proven lower end of ``κ_lin`` for these gains (:func:`.flow_bound.kappa_lin_lower`: no cover, so stiff
    and slow gains have one too), or None beyond float range."""
    from .._certify.flow_bound import kappa_lin_lower
    from .._infra.errors import ParameterError

    try:
        return kappa_lin_lower(params)
    except ParameterError:
        return None


def _json_safe(value: Any) -> Any:
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    return value


def _slug(label: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", label).strip("_") or "certificate"


def write_counterexamples(report: CrosscheckReport, out_dir: str | Path) -> list[Path]:
    """Write one JSON file per certificate that has counterexamples; return the files.

    Files are written atomically (temporary file + ``os.replace``).
    """
    from .._infra.io import atomic_write_text

    written = []
    for check in report.checks:
        cxs = check.counterexamples()
        if not cxs:
            continue
        data = {
            "certificate": check.label,
            "source": check.source,
            "exact": {k: str(v) for k, v in check.claims.exact.items()},
            "rtol": report.rtol,
            "seed": report.seed,
            "counterexamples": [_json_safe(cx.to_dict()) for cx in cxs],
        }
        path = Path(out_dir) / f"{_slug(check.label)}.counterexamples.json"
        atomic_write_text(path, json.dumps(data, indent=2, ensure_ascii=False, allow_nan=False) + "\n")
        written.append(path)
    return written

