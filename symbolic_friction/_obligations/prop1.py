"""Proposition 1: 𝒜 is globally asymptotically stable.

* ``prop1.invariance`` — item 1 (global attractivity), the invariance step.
* ``prop1.stability_bound`` — item 2 (stability), proved in Section V.

**Item 1.** Proposition 1, item 1 (global attractivity): the invariance step.

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

**Item 2.** Proposition 1, item 2 (stability), proved in Section V: the bound

.. math::

    |x(t)|_{\\mathcal A} \\le \\sqrt{\\tfrac{c_2\\hat c_2}{c_1\\hat c_1}}\\,|x(0)|_{\\mathcal A},
    \\qquad t \\ge 0 \\qquad\\text{(eq. stabState)}

from Lemma 2 and Lemma 3, by the paper's two cases: (i) ``x(t) ∉ R`` for
all ``t``; (ii) a first time ``t₁`` with ``x(t₁) ∈ R``.

The analytic facts (Lemma 2, Lemma 3 at the relevant points, monotonicity of
``V`` and ``V̂`` along solutions) are *premises*, each built by the function
of :mod:`._statements` that the lemma's own obligation checks is what it
proves; every inequality the paper
chains from them is a *step* ``lhs ≤ rhs`` with an explicit certificate

.. math::

    \\mathrm{rhs} - \\mathrm{lhs} = \\sum_i m_i\\,(\\text{gap of a used premise or step}) + r,

with multipliers ``m_i ≥ 0`` and remainder ``r ≥ 0`` proved by a
sign-definite decomposition over positive constants and nonnegative
distances.  Squared distances keep every step polynomial (no square roots,
no division by quantities of unknown sign).  Also checked: ``R`` is closed
(the paper's reason why a *first* time ``t₁`` exists) and the witness points
that give ``c₁ ≤ c₂`` and ``ĉ₁ ≤ ĉ₂``, hence ``κ ≥ 1``.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import sympy as sp

from .._model import symbolic as _symbolic
from . import _fastforms as ff
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, Undecided, decide, is_zero, latex, phi_classes, sign_classes, sign_of
from ._inequalities import is_nonneg
from ._shared import attractor_x, sgn_sets
from ._stability_chain import Ineq, StabilitySubject, _closedness_failures, _subject, _tex_rel, _witness_failures

__all__ = ["Prop1Invariance", "StabilityBound", "OBLIGATIONS"]


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
        if S.ell.has(sigma) or S.ell.has(phi) or ff.solve(S.ell, v) != [0]:
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
        x_t = [sp.expand(ff.simplify(traj[0])), sp.expand(ff.simplify(traj[1])), sp.Integer(0)]
        w_t = sp.expand(fp.cancel((S.A * sp.Matrix(x_t))[2] / S.b[2]))  # 0 = v' = (A x)_3 - b_3 w
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
                verdict = self._classify(S, [e.xreplace(sub) for e in x_t], sp.expand(w_t.xreplace(sub)), t, lo, hi)
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
        x0 = [e.xreplace({t: sp.Integer(0)}) for e in x0_t]  # as subs(t, 0), without its bookkeeping
        forced = (S.A * sp.Matrix(x0))[:2]
        w0 = w.xreplace({t: sp.Integer(0)})
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


class StabilityBound(Obligation):
    """``prop1.stability_bound``: eq. (stabState) by the two-case argument, and κ ≥ 1."""

    id = "prop1.stability_bound"
    paper = "Proposition 1 item 2; proof in Section V, eqs. (stabState), (boundInHatR), (boundInHatRandInR)"
    statement = (
        "From Lemma 2 and Lemma 3: |x(t)|_𝒜 ≤ √(c₂ĉ₂/(c₁ĉ₁))|x(0)|_𝒜 for all t ≥ 0 in case (i) and in case (ii) "
        "(t < t₁, t ≥ t₁, and t₁ = 0), R is closed so t₁ exists, and c₁ ≤ c₂, ĉ₁ ≤ ĉ₂ give κ ≥ 1"
    )
    method = (
        "chain of symbolic implications over positive constants and nonnegative squared distances, each step "
        "certified by nonnegative multipliers and a sign-definite remainder; exhaustive case split for R's closedness"
    )

    def derive(self) -> StabilitySubject:
        return _subject()

    def verify(self, subject: StabilitySubject) -> Outcome:
        s = subject
        failures: list[str] = []
        known: dict[str, Ineq] = {}
        for p in s.premises:
            known[p.name] = p.claim
        rows = []
        for step in s.steps:
            missing = [u for u in step.uses if u not in known]
            if missing:
                failures.append(f"step {step.name!r} uses unknown or later facts {missing}")
                continue
            if len(step.multipliers) != len(step.uses):
                failures.append(f"step {step.name!r} has {len(step.multipliers)} multipliers for {len(step.uses)} facts")
                continue
            bad = [m for m in step.multipliers if not is_nonneg(m)]
            if bad:
                failures.append(f"step {step.name!r}: multipliers {bad} are not shown nonnegative")
                continue
            remainder = fp.expand(
                step.claim.gap - sum(sp.sympify(m) * known[u].gap for m, u in zip(step.multipliers, step.uses))
            )
            if not is_nonneg(remainder):
                failures.append(f"step {step.name!r} ({step.claim.lhs} ≤ {step.claim.rhs}) does not follow: remainder {remainder}")
                continue
            known[step.name] = step.claim
            rows.append(
                (
                    f"\\text{{{step.name}}}",
                    f"{step.claim.latex()} \\quad(\\text{{remainder }} {latex(remainder)})",
                )
            )
        c_prod_hat = s.c1 * s.c1_hat
        c_prod = s.c2 * s.c2_hat
        for goal in s.goals:
            claim = known.get(goal.step)
            want = Ineq(c_prod_hat * goal.distance, c_prod * s.d0)
            if claim is None:
                failures.append(f"case {goal.case}: step {goal.step!r} was not proved")
            elif not is_zero(claim.gap - want.gap):
                failures.append(f"case {goal.case}: step {goal.step!r} proves {claim.lhs} ≤ {claim.rhs}, not {want.lhs} ≤ {want.rhs}")
        # κ² c₁ĉ₁ = c₂ĉ₂, so D_t ≤ κ² D₀ ⇔ c₁ĉ₁ D_t ≤ c₂ĉ₂ D₀; sqrt is monotone on [0, ∞)
        if not (s.kappa.is_positive and is_zero(sp.expand(s.kappa**2 * c_prod_hat) - c_prod)):
            failures.append(f"κ = {s.kappa} does not satisfy κ > 0 and κ²·c₁ĉ₁ = c₂ĉ₂")
        kstep = known.get(s.kappa_step)
        if kstep is None or not is_zero(kstep.gap - (c_prod - c_prod_hat)):
            failures.append(f"κ ≥ 1 needs a proved step c₁ĉ₁ ≤ c₂ĉ₂; {s.kappa_step!r} is not one")
        failures += _closedness_failures(s)
        failures += _witness_failures(s)
        premise_rows = tuple(
            (f"\\text{{premise: {p.name}}}", f"{p.claim.latex()} \\quad \\text{{({p.why})}}") for p in s.premises
        )
        details = premise_rows + tuple(rows) + (
            ("\\kappa", latex(s.kappa)),
            ("R \\text{ (closed)}", r" \cup ".join("\\{" + ",\\ ".join(f"{latex(e)} {_tex_rel(r)} 0" for e, r in part) + "\\}" for part in s.closed_form)),
        )
        if failures:
            return Outcome.fail("; ".join(failures[:6]), details)
        return Outcome(
            True,
            f"{len(s.steps)} steps from {len(s.premises)} premises cover {len(s.goals)} cases; "
            "t₁ = 0 needs ĉ₁ ≤ ĉ₂, which the paper leaves implicit",
            details,
        )


OBLIGATIONS = (Prop1Invariance, StabilityBound)
