"""Proposition 1, item 1 (global attractivity): the invariance step.

Fact 1 (Ryan's invariance principle) with ``ℓ(x) = v²`` sends every solution
to the largest forward-invariant subset ``ℳ`` of ``Σ = {ℓ = 0} = {v = 0}``;
the proof claims ``ℳ = 𝒜``.  Solutions are unique (Lemma 1), so ``ℳ`` is the
set of points of ``Σ`` whose solution never leaves ``Σ``.

While a solution stays in ``Σ`` it has ``v ≡ 0``, so ``(σ, φ)`` obeys the
linear part of eq. (xDot) with ``v = 0`` (``σ' = 0``, ``φ' = σ``) and
``0 = v' ∈ φ - f_c[-1, 1]`` forces the friction selection
``w(t) = φ(t)/f_c`` to stay in ``[-1, 1]``.  The obligation splits ``Σ``
into 15 classes (sign of σ × five φ-classes) and decides for each: either it
consists of equilibria (then it must lie in 𝒜), or ``w(t)`` leaves
``[-1, 1]`` (then it is not in ``ℳ`` and must miss 𝒜).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import sympy as sp

from .._model import symbolic as _symbolic
from ._base import Obligation, Outcome
from ._decide import G, Undecided, decide, latex, phi_classes, sign_classes, sign_of
from .model import attractor_x, sgn_sets

__all__ = ["Prop1Invariance", "OBLIGATIONS"]


@dataclass(frozen=True)
class InvarianceSubject:
    """The inclusion, 𝒜, the function ℓ of Fact 1 and the SGN map."""

    A: sp.ImmutableMatrix
    b: sp.ImmutableMatrix
    attractor: tuple
    ell: sp.Expr
    sgn: dict
    state: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    f_c: sp.Symbol


class Prop1Invariance(Obligation):
    id = "prop1.invariance"
    paper = "Proposition 1, item 1 (proof); Fact 1"
    statement = "the largest forward-invariant subset of Σ = {x : ℓ(x) = v² = 0} is 𝒜"
    method = "exhaustive case split of Σ (3 signs of σ × 5 classes of φ): equilibrium test, or the explicit in-Σ motion (matrix exponential) whose friction selection w(t) leaves [-1, 1]; sign-definite decomposition"

    def derive(self) -> InvarianceSubject:
        g = G()
        return InvarianceSubject(
            A=sp.ImmutableMatrix(_symbolic.A(g)),
            b=sp.ImmutableMatrix(_symbolic.b(g)),
            attractor=attractor_x(g),
            ell=g.v**2,
            sgn=sgn_sets(),
            state=(g.sigma, g.phi, g.v),
            f_c=g.f_c,
        )

    def verify(self, subject: InvarianceSubject) -> Outcome:
        S = subject
        sigma, phi, v = S.state
        if S.ell.has(sigma) or S.ell.has(phi) or sp.solve(S.ell, v) != [0]:
            return Outcome.fail(f"Σ = {{ℓ = {S.ell} = 0}} is not the plane v = 0")
        if not (isinstance(S.attractor[1], sp.Interval) and S.attractor[2] == 0):
            return Outcome.fail(f"𝒜 = {S.attractor} is not a φ-interval inside v = 0")
        if S.b[0] != 0 or S.b[1] != 0 or sign_of(S.b[2]) != 1:
            return Outcome.fail(f"b = {list(S.b)} is not (0, 0, positive)")
        # Motion inside Σ: v ≡ 0 makes the first two rows forced (b_1 = b_2 = 0): (σ, φ)' = B (σ, φ).
        B = sp.Matrix(S.A).extract([0, 1], [0, 1])
        t = sp.Symbol("t", nonnegative=True)
        sb, pb = sp.symbols("sigmabar phibar", real=True)
        traj = (B * t).exp() * sp.Matrix([sb, pb])
        x_t = [sp.expand(sp.simplify(traj[0])), sp.expand(sp.simplify(traj[1])), sp.Integer(0)]
        w_t = sp.expand(sp.cancel((S.A * sp.Matrix(x_t))[2] / S.b[2]))  # 0 = v' = (A x)_3 - b_3 w
        details = [
            ("(\\sigma, \\phi)(t) \\text{ while } v \\equiv 0", latex(sp.Matrix(x_t[:2]).T)),
            ("w(t) = (Ax)_3 / f_c", latex(w_t)),
        ]
        lo, hi = S.sgn[0].start, S.sgn[0].end
        if not w_t.is_polynomial(t):
            return Outcome.fail(f"the selection w(t) = {w_t} is not polynomial in t")
        for (slab, _ss, sval), (plab, ptex, pval, _reg) in itertools.product(sign_classes("s_sigma"), phi_classes(S.f_c, "_phi")):
            case = f"σ {slab}, {plab}"
            sub = {sb: sval, pb: pval}
            try:
                verdict = self._classify(S, [e.subs(sub) for e in x_t], sp.expand(w_t.subs(sub)), t, lo, hi)
                in_A = self._in_attractor(S, sval, pval)
            except Undecided as exc:
                return Outcome.fail(f"class {case}: {exc}", tuple(details))
            if verdict == "equilibria" and in_A is not True:
                return Outcome.fail(f"class {case} consists of equilibria (forward invariant in Σ) but is not in 𝒜 = {S.attractor}", tuple(details))
            if verdict != "equilibria" and in_A is not False:
                return Outcome.fail(f"class {case} leaves Σ ({verdict}) but meets 𝒜 = {S.attractor}", tuple(details))
            details.append((f"\\sigma {slab},\\ {ptex}", _TEX[verdict.split(" ")[0]]))
        return Outcome(True, "every class of Σ is either equilibria inside 𝒜 or leaves Σ and misses 𝒜", tuple(details))

    @staticmethod
    def _classify(S: InvarianceSubject, x0_t, w, t, lo, hi) -> str:
        """'equilibria', or why the class leaves Σ."""
        x0 = [e.subs(t, 0) for e in x0_t]
        forced = (S.A * sp.Matrix(x0))[:2]
        w0 = w.subs(t, 0)
        in_range = decide(sp.And(sp.Le(lo, w0), sp.Le(w0, hi)))
        if in_range is None:
            raise Undecided(f"cannot decide whether w(0) = {w0} lies in [{lo}, {hi}]")
        moving = [sign_of(e) for e in forced]
        if any(m is None for m in moving):
            raise Undecided(f"cannot decide whether (σ', φ') = {forced} vanishes")
        if all(m == 0 for m in moving) and in_range:
            return "equilibria"
        if not in_range:
            return "w(0) is outside [-1, 1], so v' ≠ 0 at once"
        # w(t) is a polynomial of positive degree in t with a decided leading coefficient: it is unbounded.
        poly = sp.Poly(w, t)
        if poly.degree() >= 1 and sign_of(poly.LC()) in (1, -1):
            return "φ ramps until w(t) leaves [-1, 1]"
        raise Undecided(f"the class moves ((σ', φ') = {forced}) but w(t) = {w} is not shown to leave [{lo}, {hi}]")

    @staticmethod
    def _in_attractor(S: InvarianceSubject, sval, pval) -> bool | None:
        fixed = sign_of(sval - S.attractor[0])
        if fixed is None:
            raise Undecided(f"cannot decide σ = {sval} against 𝒜")
        if fixed != 0:
            return False
        I = S.attractor[1]
        inside = decide(sp.And(sp.Le(I.start, pval), sp.Le(pval, I.end)))
        if inside is None:
            raise Undecided(f"cannot decide whether φ = {pval} lies in {I}")
        return inside


_TEX = {
    "equilibria": "\\text{equilibria, inside } \\mathcal A",
    "w(0)": "w(0) \\notin [-1, 1] \\Rightarrow \\dot v \\neq 0 \\text{ at once: leaves } \\Sigma",
    "φ": "w(t) \\text{ unbounded} \\Rightarrow \\text{leaves } \\Sigma",
}

OBLIGATIONS = (Prop1Invariance,)
