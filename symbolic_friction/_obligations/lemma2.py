"""Lemma 2 (properties of the Lyapunov-like function ``V``, eq. lyapLike).

* ``lemma2.P`` — ``P`` of eq. (lyapLikeP) is positive definite iff
  ``k_v k_p > k_i`` (Sylvester's criterion, no division by an expression of
  unknown sign).
* ``lemma2.lower_bound`` — item 1: ``V = 0`` on 𝒜 and
  ``V(x) ≥ c₁|x|²_𝒜`` with ``c₁ = min{𝔤, 1} = λ_min(P)``.
* ``lemma2.dVdt`` — item 2's engine, eq. (dVdt): along ``f_{±1}``,
  ``d/dt V_{±1} = -2(k_v k_p - k_i) v²``; along ``f_0``, ``d/dt V_0 = 0``.

The Remark after Lemma 2 (``remark.armstrong``) is in :mod:`.remark`; it uses
the pieces of ``V`` defined here.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.lyapunov import V_k, quadratic_form
from . import _fastforms as ff
from . import _fastpoly as fp
from ._base import Erratum, Obligation, Outcome
from ._decide import (
    G,
    Undecided,
    is_zero,
    latex,
    minimum_on,
    phi_classes,
    pos,
    resolve_piecewise,
    sign_classes,
    sign_of,
)
from ._inequalities import extremum
from ._shared import distance_squared, sgn_sets
from ._statements import lemma2_decrease, lemma2_lower_bound, statement_failure

__all__ = [
    "Lemma2P",
    "Lemma2LowerBound",
    "Lemma2dVdt",
    "OBLIGATIONS",
    "F0_MATRIX",
    "affine_fields",
    "lyapunov_pieces",
    "decrease_rate",
    "friction_form",
    "friction_minimum",
    "under_assumption1",
]

F0_MATRIX = ((0, 0, 0), (1, 0, 0), (0, 0, 0))
"""The matrix of the stick dynamics ``f_0`` in eq. (subcasesAffine:f0), as printed."""


def under_assumption1(expr: sp.Expr) -> sp.Expr:
    """Encode ``k_v k_p - k_i = δ > 0`` (Assumption 1) in ``expr``."""
    return fp.factor(sp.sympify(expr).subs(_symbolic.assumption1_substitution(G())))


def affine_fields(g: _symbolic.Gains) -> dict[int, sp.ImmutableMatrix]:
    """The affine fields of eq. (subcasesAffine): ``f_{±1} = A x ∓ b`` and ``f_0 = F0_MATRIX x``."""
    x = sp.Matrix([g.sigma, g.phi, g.v])
    A, b = sp.Matrix(_symbolic.A(g)), sp.Matrix(_symbolic.b(g))
    return {1: sp.ImmutableMatrix(A * x - b), 0: sp.ImmutableMatrix(sp.Matrix(F0_MATRIX) * x), -1: sp.ImmutableMatrix(A * x + b)}


def lyapunov_pieces(g: _symbolic.Gains) -> dict[int, sp.Expr]:
    """The package's ``V_k`` of eq. (subcasesAffine:Vs), expanded, for ``k = 1, 0, -1``."""
    return {k: sp.expand(V_k(g, [g.sigma, g.phi, g.v], k)) for k in (1, 0, -1)}


def decrease_rate(g: _symbolic.Gains) -> sp.Expr:
    """``c = 2(k_v k_p - k_i)`` of eq. (dVdt)."""
    return 2 * (g.k_v * g.k_p - g.k_i)


def friction_form(g: _symbolic.Gains) -> tuple[sp.Expr, sp.Symbol]:
    """The package's quadratic form of ``V`` in ``(σ, y, v)``, ``y = φ - f`` (eq. lyapLike), and ``y``."""
    y = sp.Symbol("y", real=True)
    return quadratic_form(g, g.sigma, y, g.v), y


def friction_minimum(form: sp.Expr, y: sp.Symbol, phi: Any, f_c: Any, sgn_set: sp.Set) -> sp.Expr:
    """Exact minimum over ``f ∈ f_c·sgn_set`` of the ``f``-dependent part of ``form`` at ``y = φ - f``.

    ``V`` of eq. (lyapLikeV) is ``form`` at ``y = 0`` plus this minimum; only
    the part that depends on ``f`` is minimised (smaller expressions, same
    minimum).

    Raises
    ------
    Undecided
        From :func:`._decide.minimum_on`.
    """
    w = sp.Symbol("w", real=True)
    # xreplace: a symbol for a value, as subs does it, without subs's bookkeeping
    moving = sp.expand(form.xreplace({y: sp.sympify(phi - f_c * w)}) - form.xreplace({y: sp.Integer(0)}))
    return minimum_on(moving, w, sgn_set)


# --------------------------------------------------------------------------- lemma2.P


@dataclass(frozen=True)
class PSubject:
    """``P`` and the condition claimed equivalent to ``P ≻ 0``."""

    P: sp.ImmutableMatrix
    condition: sp.Expr
    solve_for: sp.Symbol


class Lemma2P(Obligation):
    id = "lemma2.P"
    paper = "eq. (lyapLikeP); Lemma 2, item 1 (proof)"
    statement = "P ≻ 0 ⇔ k_v k_p > k_i (for k_i, k_p > 0)"
    method = "Sylvester's criterion: leading principal minors; (⇐) substitute k_v = (k_i + δ)/k_p, δ > 0, sign-definite decomposition; (⇒) the condition is a positive multiple of a minor"

    def derive(self) -> PSubject:
        g = G()
        return PSubject(P=sp.ImmutableMatrix(_symbolic.P(g)), condition=g.k_v * g.k_p - g.k_i, solve_for=g.k_v)

    def verify(self, subject: PSubject) -> Outcome:
        S = subject
        if not all(is_zero(e) for e in (S.P - S.P.T)):
            return Outcome.fail(f"P is not symmetric: P - Pᵀ = {(S.P - S.P.T).tolist()}")
        minors = [fp.factored_det(S.P[:k, :k]) for k in range(1, S.P.rows + 1)]
        details = [("P", latex(S.P)), ("\\text{leading principal minors}", latex(minors))]
        delta = pos("delta")
        sols = ff.solve(sp.Eq(S.condition, delta), S.solve_for, dict=True)
        if len(sols) != 1:
            return Outcome.fail(f"cannot write the condition {S.condition} = δ as a unique {S.solve_for}")
        under = [fp.factor(m.subs(sols[0])) for m in minors]
        for k, m in enumerate(under, 1):
            if sign_of(m) != 1:
                return Outcome.fail(f"(⇐) fails: with {S.condition} = δ > 0 the minor Δ_{k} = {m} is not shown positive", tuple(details))
        details.append((f"{latex(S.condition)} = \\delta > 0 \\Rightarrow", latex(under)))
        for k, m in enumerate(minors, 1):
            ratio = fp.factor(S.condition / m)
            if sign_of(ratio) == 1:
                details.append(("\\Rightarrow", f"{latex(S.condition)} = {latex(ratio)} \\cdot \\Delta_{k} > 0"))
                return Outcome(True, f"all minors positive iff {S.condition} > 0", tuple(details))
        return Outcome.fail(f"(⇒) fails: {S.condition} is not a positive multiple of any minor {minors}", tuple(details))


# --------------------------------------------------------------------------- lemma2.lower_bound


@dataclass(frozen=True)
class LowerBoundSubject:
    """``P``, the package's quadratic form, 𝔤, ``c₁`` and the distance formula."""

    P: sp.ImmutableMatrix
    form: sp.Expr
    g_min: sp.Expr
    c1: sp.Expr
    dist2: sp.Expr
    sgn: dict
    sigma: sp.Symbol
    phi: sp.Symbol
    v: sp.Symbol
    y: sp.Symbol
    f_c: sp.Symbol
    statement: Any = lemma2_lower_bound
    """The conclusion Proposition 1 uses (:func:`._statements.lemma2_lower_bound`)."""


def _smallest_eigenvalue_2x2(M: sp.Matrix) -> sp.Expr:
    tr, det = M.trace(), M.det()
    return (tr - sp.sqrt(sp.expand(tr**2 - 4 * det))) / 2


class Lemma2LowerBound(Obligation):
    id = "lemma2.lower_bound"
    paper = "Lemma 2, item 1"
    statement = "V = 0 on 𝒜 and V(x) ≥ c₁|x|²_𝒜 for all x, with c₁ = min{𝔤, 1} = λ_min(P), 𝔤 = λ_min of the (σ, v) block"
    method = "sympy identities (quadratic form = P-form, det(λI - P) = (λ - 1)·det(λI - P_σv), 𝔤 is the smaller root); exact minimum over f ∈ f_c SGN(v) in 15 (sign v, φ-class) cases, sign-definite decomposition"

    def derive(self) -> LowerBoundSubject:
        g = G()
        P = sp.ImmutableMatrix(_symbolic.P(g))
        form, y = friction_form(g)
        g_min = _smallest_eigenvalue_2x2(sp.Matrix(P).extract([0, 2], [0, 2]))
        return LowerBoundSubject(
            P=P,
            form=form,
            g_min=g_min,
            c1=extremum(sp.Min, g_min, sp.Integer(1)),  # sp.Min(g_min, 1), built once (see extremum)
            dist2=distance_squared(g),
            sgn=sgn_sets(),
            sigma=g.sigma,
            phi=g.phi,
            v=g.v,
            y=y,
            f_c=g.f_c,
        )

    def verify(self, subject: LowerBoundSubject) -> Outcome:
        S = subject
        problem = statement_failure(S.statement, lambda c1, dist2, V: V - c1 * dist2)
        if problem:
            return Outcome.fail(f"Lemma 2 item 1 as Proposition 1 uses it: {problem}")
        X = sp.Matrix([S.sigma, S.y, S.v])
        if not is_zero(S.form - (X.T * S.P * X)[0]):
            return Outcome.fail(f"the quadratic form {S.form} is not (σ, y, v) P (σ, y, v)ᵀ")
        if list(S.P[1, :]) != [0, 1, 0] or list(S.P[:, 1]) != [0, 1, 0]:
            return Outcome.fail(f"the φ row of P is {list(S.P[1, :])}, not (0, 1, 0): the friction term is not decoupled")
        M2 = sp.Matrix(S.P).extract([0, 2], [0, 2])
        lam = sp.Symbol("lambda")
        cp_P = fp.expanded_det(lam * sp.eye(3) - S.P)
        cp_2 = fp.expanded_det(lam * sp.eye(2) - M2)
        if not is_zero(cp_P - (lam - 1) * cp_2):
            return Outcome.fail(f"det(λI - P) = {fp.factor(cp_P)} is not (λ - 1)·det(λI - P_σv)")
        details = [("\\det(\\lambda I - P)", f"(\\lambda - 1)\\left({latex(sp.collect(cp_2, lam))}\\right)")]
        tr, det = M2.trace(), M2.det()
        disc = sp.expand(tr**2 - 4 * det)
        if not is_zero(disc - sp.expand((M2[0, 0] - M2[1, 1]) ** 2 + 4 * M2[0, 1] ** 2)):
            return Outcome.fail(f"the discriminant {disc} is not a sum of squares")
        if not is_zero(fp.expanded_det(S.g_min * sp.eye(2) - M2)):
            return Outcome.fail(f"𝔤 = {S.g_min} is not an eigenvalue of the (σ, v) block")
        if not is_zero(sp.expand(tr - 2 * S.g_min - sp.sqrt(disc))):
            return Outcome.fail(f"𝔤 = {S.g_min} is not the smaller eigenvalue (tr - 2𝔤 ≠ √disc ≥ 0)")
        details.append(("\\mathfrak g = \\lambda_{\\min}(P_{\\sigma v})", latex(S.g_min)))
        # Both roots are positive: their product det and their sum tr are, under Assumption 1.
        if sign_of(under_assumption1(det)) != 1 or sign_of(under_assumption1(tr)) != 1:
            return Outcome.fail(f"under Assumption 1, det = {under_assumption1(det)} or trace = {under_assumption1(tr)} of P_σv is not shown positive")
        details.append(("\\det P_{\\sigma v},\\ \\operatorname{tr} P_{\\sigma v}", latex([under_assumption1(det), under_assumption1(tr)])))
        if S.c1 != extremum(sp.Min, S.g_min, sp.Integer(1)):
            return Outcome.fail(f"c₁ = {S.c1} is not min{{𝔤, 1}} = λ_min(P)")
        details.append(("c_1 = \\min\\{\\mathfrak g, 1\\} = \\lambda_{\\min}(P)", latex(S.c1)))
        # Distance formula: σ² + v² + (a term in φ only).
        dz2 = sp.expand(S.dist2 - S.sigma**2 - S.v**2)
        if dz2.has(S.sigma) or dz2.has(S.v):
            return Outcome.fail(f"|x|²_𝒜 - σ² - v² = {dz2} depends on σ or v")
        # The form is the homogeneous quadratic of P, so it vanishes at σ = v = 0, φ - f = 0.
        # Friction term: min over f ∈ f_c SGN(v) of (φ - f)² ≥ dz(φ)², and = 0 on 𝒜.
        for (vlabel, sv, vval), (plabel, ptex, pval, _reg) in itertools.product(sign_classes("q_v"), phi_classes(S.f_c, "_phi")):
            try:
                m = friction_minimum(S.form, S.y, pval, S.f_c, S.sgn[sv])
                d = resolve_piecewise(dz2.xreplace({S.phi: pval}))  # as subs(S.phi, pval), without its bookkeeping
            except Undecided as exc:
                return Outcome.fail(f"case v {vlabel}, {plabel}: {exc}", tuple(details))
            if sign_of(m - d) not in (0, 1):
                return Outcome.fail(f"case v {vlabel}, {plabel}: min (φ - f)² = {m} is not shown ≥ dz(φ)² = {d}", tuple(details))
            if sv == 0 and plabel in ("φ = f_c", "|φ| < f_c", "φ = -f_c") and not is_zero(m):
                return Outcome.fail(f"V ≠ 0 on 𝒜: at v = 0, {plabel} the friction term is {m}", tuple(details))
            details.append((f"v {vlabel},\\ {ptex}", f"\\min_f(\\phi-f)^2 - \\mathrm{{dz}}(\\phi)^2 = {latex(fp.factor(m - d))} \\ge 0"))
        details.append(
            ("V - c_1|x|^2_{\\mathcal A}", "\\ge (\\mathfrak g - c_1)(\\sigma^2+v^2) + (1-c_1)\\,\\mathrm{dz}(\\phi)^2 \\ge 0")
        )
        return Outcome(True, "c₁ = min{𝔤, 1} = λ_min(P) > 0 and the bound holds in all 15 cases", tuple(details))


# --------------------------------------------------------------------------- lemma2.dVdt


@dataclass(frozen=True)
class DVdtSubject:
    """``V_k`` (package), the affine fields ``f_k`` and the rate ``c``."""

    V: dict
    f: dict
    c: sp.Expr
    V0_corrected: sp.Expr
    state: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    A: sp.ImmutableMatrix
    P: sp.ImmutableMatrix
    statement: Any = lemma2_decrease
    """The conclusion Proposition 1 uses (:func:`._statements.lemma2_decrease`)."""


class Lemma2dVdt(Obligation):
    id = "lemma2.dVdt"
    paper = "Claim 1, eq. (dVdt); appendix (last paragraph); Lemma 2, item 2"
    statement = "d/dt V_{±1} along f_{±1} ≡ -2(k_v k_p - k_i) v², d/dt V_0 along f_0 ≡ 0 with V_0 = (k_v/k_i)σ² and v' ≡ 0, and c = 2(k_v k_p - k_i) > 0"
    method = "sympy identity (expand(∇V_k · f_k + c v²) == 0); Lyapunov equation AᵀP + PA = -c e₃e₃ᵀ; sign-definite decomposition of c under Assumption 1"
    errata = (
        Erratum(
            where="Appendix (proof of Claim 1), last paragraph",
            paper_says="for k = 0, V_0(ξ(t)) = (k_v/k_i) ξ_v(t)², so d/dt V_0(ξ(t)) = 2(k_v/k_i) ξ_σ ξ'_σ = 0 ≤ 0 = c ξ_v(t)²",
            correct="V_0(ξ) = (k_v/k_i) ξ_σ² (eq. subcasesAffine:Vs), so d/dt V_0 = 2(k_v/k_i) ξ_σ ξ'_σ = 0 ≤ 0 = -c ξ_v² (ξ_v ≡ 0 along f_0 from ξ_v(0) = 0)",
            checked_by="lemma2.dVdt, claim1.cases",
        ),
    )

    def derive(self) -> DVdtSubject:
        g = G()
        return DVdtSubject(
            V=lyapunov_pieces(g),
            f=affine_fields(g),
            c=decrease_rate(g),
            V0_corrected=g.k_v / g.k_i * g.sigma**2,
            state=(g.sigma, g.phi, g.v),
            A=sp.ImmutableMatrix(_symbolic.A(g)),
            P=sp.ImmutableMatrix(_symbolic.P(g)),
        )

    def verify(self, subject: DVdtSubject) -> Outcome:
        S = subject
        # dV_k/dt = -c v² ≤ 0 on every piece gives V(t₂) ≤ V(t₁) (eq. Vdecrease without c∫v² ≥ 0)
        problem = statement_failure(S.statement, lambda later, earlier: earlier - later)
        if problem:
            return Outcome.fail(f"Lemma 2 item 2 as Proposition 1 uses it: {problem}")
        sigma, phi, v = S.state
        details = [("A^T P + P A", latex((S.A.T * S.P + S.P * S.A).applyfunc(fp.factor)))]
        if sign_of(under_assumption1(S.c)) != 1:
            return Outcome.fail(f"c = {S.c} is not shown positive under Assumption 1 (c = {under_assumption1(S.c)} with δ = k_v k_p - k_i)")
        for k in (1, -1, 0):
            grad = sp.Matrix([sp.diff(S.V[k], s) for s in S.state])
            rate = sp.expand((grad.T * S.f[k])[0])
            target = sp.Integer(0) if k == 0 else -S.c * v**2
            if not is_zero(rate - target):
                return Outcome.fail(f"d/dt V_{k} along f_{k} = {fp.factor(rate)}, not {fp.factor(target)}", tuple(details))
            details.append((f"\\tfrac{{d}}{{dt}} V_{{{k}}} \\text{{ along }} f_{{{k}}}", latex(fp.factor(rate))))
        if not is_zero(S.f[0][2]):
            return Outcome.fail(f"f_0 moves v (v' = {S.f[0][2]}), so v ≡ 0 along f_0 fails")
        if not is_zero(S.V[0] - S.V0_corrected):
            return Outcome.fail(f"V_0 = {S.V[0]} differs from (k_v/k_i)σ² = {S.V0_corrected}", tuple(details))
        details.append(("V_0", latex(S.V[0])))
        details.append(("c", f"{latex(S.c)} = 2\\delta > 0"))
        return Outcome(True, "all three identities hold", tuple(details))


# --------------------------------------------------------------------------- remark.armstrong


OBLIGATIONS = (Lemma2P, Lemma2LowerBound, Lemma2dVdt)
