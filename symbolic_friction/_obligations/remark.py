"""The Remark after Lemma 2 (eq. armstrongRes).

* ``remark.armstrong`` — at a stick ``V = (k_v/k_i) σ²``, and ``V`` strictly
  decreases over a slip phase of positive length, so ``|σ|`` at successive
  stick starts decreases strictly.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, Undecided, is_zero, latex, phi_classes, pos, sign_of
from ._shared import sgn_sets
from .lemma2 import decrease_rate, friction_form, friction_minimum, under_assumption1

__all__ = ["RemarkArmstrong", "OBLIGATIONS"]


@dataclass(frozen=True)
class ArmstrongSubject:
    """The quadratic form of ``V``, the SGN map, the stick value and ``c``."""

    form: sp.Expr
    sgn: dict
    stick_value: sp.Expr
    c: sp.Expr
    sigma: sp.Symbol
    y: sp.Symbol
    v: sp.Symbol
    f_c: sp.Symbol


class RemarkArmstrong(Obligation):
    id = "remark.armstrong"
    paper = "Remark after Lemma 2, eq. (armstrongRes)"
    statement = "at stick (v = 0, |φ| ≤ f_c) V = (k_v/k_i)σ²; V strictly decreases over a slip phase of positive length (c > 0, ∫v² > 0), hence |σ(t_{i+1})| < |σ(t_i)|"
    method = "exact minimum over f ∈ f_c SGN(0) on the stick set (3 φ-classes); sign-definite decomposition of (σ_{i+1}² - σ_i²) = (V_{i+1} - V_i)/(k_v/k_i) ≤ -c∫v²/(k_v/k_i) < 0"

    def derive(self) -> ArmstrongSubject:
        g = G()
        form, y = friction_form(g)
        return ArmstrongSubject(
            form=form,
            sgn=sgn_sets(),
            stick_value=g.k_v / g.k_i * g.sigma**2,
            c=decrease_rate(g),
            sigma=g.sigma,
            y=y,
            v=g.v,
            f_c=g.f_c,
        )

    def verify(self, subject: ArmstrongSubject) -> Outcome:
        S = subject
        details = []
        stick = S.form.subs(S.v, 0)
        for label, tex, phi, region in phi_classes(S.f_c, "_phi"):
            if label not in ("φ = f_c", "|φ| < f_c", "φ = -f_c"):
                continue
            try:
                V = stick.subs(S.y, 0) + friction_minimum(stick, S.y, phi, S.f_c, S.sgn[0])
            except Undecided as exc:
                return Outcome.fail(f"stick with {label}: {exc}")
            if not is_zero(V - S.stick_value):
                return Outcome.fail(f"stick with {label}: V = {fp.factor(V)}, not {S.stick_value}", tuple(details))
            details.append((f"v = 0,\\ {tex}", f"V = {latex(fp.factor(V))}"))
        poly = sp.Poly(S.stick_value, S.sigma)
        if poly.monoms() != [(2,)]:
            return Outcome.fail(f"the stick value {S.stick_value} is not a multiple of σ² alone")
        kappa = poly.coeffs()[0]
        if kappa.has(S.y) or sign_of(kappa) != 1:
            return Outcome.fail(f"the stick value's coefficient {kappa} is not shown positive")
        integral = pos("I_v")  # ∫_{t_i}^{t_{i+1}} v² dt > 0 over a slip phase of positive length
        bound = fp.factor(under_assumption1(S.c) * integral / kappa)
        if sign_of(bound) != 1:
            return Outcome.fail(f"c·∫v²/κ = {bound} is not shown positive, so the decrease of V is not strict")
        details.append(
            ("\\sigma(t_{i+1})^2 - \\sigma(t_i)^2", f"= \\frac{{V(t_{{i+1}}) - V(t_i)}}{{{latex(kappa)}}} \\le -{latex(bound)} < 0")
        )
        return Outcome(True, "V = (k_v/k_i)σ² at stick and the decrease is strict", tuple(details))


OBLIGATIONS = (RemarkArmstrong,)
