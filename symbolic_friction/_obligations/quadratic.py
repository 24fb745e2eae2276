"""The quadratic template's proof (beyond the paper): the steps of Lemma 2, Lemma 3 and Proposition 1 it changes.

The template (:mod:`symbolic_friction._model.quadratic`) frees ``P`` (with
``P₁₂ = 0``) and replaces ``V̂`` by ``U = yᵀKy``.  Its verifier
(:mod:`symbolic_friction._certify.quadratic`) decides numbers; these
obligations show, for symbolic gains and symbolic template constants, that
the numbers it decides are the right ones:

* ``quadratic.P_structure`` — ``(AᵀP + PA)₁₁ = 2P₁₂`` for a general symmetric
  ``P`` (so ``Q ⪯ 0`` forces ``P₁₂ = 0`` and a zero first row), the first row
  of ``Q`` vanishes for the template's ``P``, the paper's ``P`` of eq.
  (lyapLikeP) is the template's at ``(k_v/k_i, 1, k_p)``, and at ``v = 0`` the
  form is ``P₁₁σ² + P₂₂(φ − f)²`` (``P₂₃`` never enters), so the minimiser of
  eq. (lyapLikeV) is still ``sat_{f_c}(φ)``.
* ``quadratic.V_decrease`` — eq. (dVdt) for the template: along
  ``f_{±1} = Ax ∓ b``, ``w = x ∓ f_c e₂`` obeys ``ẇ = Aw`` and
  ``d/dt |w|²_P = wᵀQw`` with the verifier's ``Q``; along ``f₀``,
  ``d/dt P₁₁σ² = 0``.  The premise ``−Q − c e₃e₃ᵀ ⪰ 0`` then gives
  eq. (Vdecrease) and Lemma 2 item 2 as in the paper (lsc is unchanged).
* ``quadratic.U_rate`` — eq. (hatVdot) for ``U``: on ``R̂ ∩ {v > 0}``, for both
  signs of ``σ``, outside the band ``U̇ = −yᵀ(−(KB_s + B_sᵀK))y − 4f_c(Ky)₃`` and
  inside it ``U̇ = −(band form) − 2(f_c − φ)(Ky)₃`` with ``f_c − φ ≥ 0``;
  ``K₁₂`` is forced to 0 (the diagonal entry is ``2sK₁₂``); ``F`` is odd and
  ``U``, ``R̂`` even, which covers ``v < 0``.  Where ``U`` is not differentiable
  (``σ = 0``, ``φ = −f_c``) its generalized gradient is the convex hull of the
  one-sided ones, and ``U̇`` is affine in the selection, so the maximum in
  eq. (hatVdot) is one of the forms above (``s = ±1``; band or outside);
  that ``U̇ ≤ 0`` in this sense makes ``U`` nonincreasing is cited, as in the
  paper's proof of Proposition 1 (case (i)).
* ``quadratic.U_exit`` — ``U − V`` where a solution leaves ``R̂``: at ``v = 0``
  it is the verifier's first exit form in ``(|σ|, |dz(φ)|)``; at ``φ = f_c
  sign(v)`` it is the second exit form plus ``2P₂₂(σv + |σ||v|) ≥ 0``.
* ``quadratic.stability_bound`` — eq. (stabState) with ``κ² ≥ max(c₂, γ)``, by
  the two-case argument of Proposition 1 written as a chain of inequalities,
  each step certified by nonnegative multipliers.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import quadratic as model
from .._model import symbolic as _symbolic
from .._model.lyapunov import lyapunov_matrix_entries
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, is_zero, latex, sign_of
from ._inequalities import is_nonneg

__all__ = ["QuadraticPStructure", "QuadraticVDecrease", "QuadraticURate", "QuadraticUExit", "QuadraticStabilityBound", "OBLIGATIONS"]


def _sym(names: str, **assumptions: Any) -> tuple[sp.Symbol, ...]:
    return sp.symbols(names, **assumptions)


def _m(entries) -> sp.Matrix:
    return sp.Matrix([[sp.sympify(e) for e in row] for row in entries])


def _template_p(g) -> tuple[sp.Matrix, tuple[sp.Symbol, ...]]:
    p11, p22, p33 = _sym("P11 P22 P33", positive=True)
    return _m(model.quadratic_p_entries(g.k_p, g.k_i, g.k_v, p11, p22, p33)), (p11, p22, p33)


def _template_k() -> tuple[sp.Matrix, tuple[sp.Symbol, ...]]:
    ks = _sym("K11 K13 K22 K23 K33", real=True)
    return _m(model.u_matrix_entries(*ks)), ks


# -- P's structure -------------------------------------------------------------------------


@dataclass(frozen=True)
class PStructureSubject:
    general_p: sp.Matrix
    general_q: sp.Matrix
    template_p: sp.Matrix
    template_q: sp.Matrix
    at_paper: sp.Matrix
    paper_p: sp.Matrix
    rest_form: sp.Expr
    rest_expected: sp.Expr


class QuadraticPStructure(Obligation):
    """``quadratic.P_structure``: why ``P₁₂ = 0``, ``P₁₃ = −P₂₂``, ``P₂₃ = k_iP₁₁ − k_vP₂₂``, and the paper's ``P`` is one case."""

    id = "quadratic.P_structure"
    paper = "beyond the paper: eqs. (lyapLikeV), (lyapLikeP) with a free P"
    statement = (
        "(AᵀP+PA)₁₁ = 2P₁₂; with P₁₂ = 0, P₁₃ = −P₂₂, P₂₃ = k_iP₁₁ − k_vP₂₂ the first row of AᵀP+PA is 0; "
        "the paper's P is the case (k_v/k_i, 1, k_p); at v = 0 the form is P₁₁σ² + P₂₂(φ−f)²"
    )
    method = "sympy identities"

    def derive(self) -> PStructureSubject:
        g = G()
        a11, a12, a13, a22, a23, a33 = _sym("a11 a12 a13 a22 a23 a33", real=True)
        general = ((a11, a12, a13), (a12, a22, a23), (a13, a23, a33))
        p, (p11, p22, p33) = _template_p(g)
        f = sp.Symbol("f", real=True)
        w = sp.Matrix([g.sigma, g.phi - f, 0])
        return PStructureSubject(
            general_p=_m(general),
            general_q=_m(model.lyapunov_rate_entries(g.k_p, g.k_i, g.k_v, general)),
            template_p=p,
            template_q=_m(model.lyapunov_rate_entries(g.k_p, g.k_i, g.k_v, tuple(tuple(p[i, j] for j in range(3)) for i in range(3)))),
            at_paper=_m(model.quadratic_p_entries(g.k_p, g.k_i, g.k_v, g.k_v / g.k_i, 1, g.k_p)),
            paper_p=_m(lyapunov_matrix_entries(g.k_p, g.k_i, g.k_v)),
            rest_form=sp.expand((w.T * p * w)[0]),
            rest_expected=sp.expand(p11 * g.sigma**2 + p22 * (g.phi - f) ** 2),
        )

    def verify(self, s: PStructureSubject) -> Outcome:
        q11, p12 = s.general_q[0, 0], s.general_p[0, 1]
        if not is_zero(q11 - 2 * p12):
            return Outcome.fail(f"(AᵀP+PA)₁₁ = {q11}, not 2P₁₂ = {2 * p12}")
        row = [sp.expand(s.template_q[0, j]) for j in range(3)]
        if any(not is_zero(e) for e in row):
            return Outcome.fail(f"the first row of AᵀP+PA for the template's P is {row}, not 0")
        if s.template_p != s.template_p.T:
            return Outcome.fail("the template's P is not symmetric")
        diff = (s.at_paper - s.paper_p).applyfunc(fp.cancel)
        if any(not is_zero(e) for e in diff):
            return Outcome.fail(f"the template's P at (k_v/k_i, 1, k_p) differs from eq. (lyapLikeP) by {list(diff)}")
        if not is_zero(s.rest_form - s.rest_expected):
            return Outcome.fail(f"at v = 0 the form is {s.rest_form}, not P₁₁σ² + P₂₂(φ−f)²")
        details = (("(A^\\top P + PA)_{11}", latex(q11)), ("P", latex(s.template_p)), ("Q = A^\\top P + PA", latex(s.template_q.applyfunc(fp.factor))))
        return Outcome(True, "", details)


# -- V's decrease --------------------------------------------------------------------------


@dataclass(frozen=True)
class VDecreaseSubject:
    shifted_flows: tuple[tuple[sp.Matrix, sp.Matrix, sp.Matrix], ...]  # (field, A·w, w)
    rate_residuals: tuple[sp.Expr, ...]  # d/dt wᵀPw − wᵀQw
    stick_rate: sp.Expr


class QuadraticVDecrease(Obligation):
    """``quadratic.V_decrease``: eq. (dVdt) for the template's ``P``: ``d/dt V_{±1} = wᵀQw``, ``d/dt V₀ = 0``."""

    id = "quadratic.V_decrease"
    paper = "beyond the paper: Claim 1 item 2, eq. (dVdt) with a free P"
    statement = "along f_{±1}, w = x ∓ f_c e₂ obeys ẇ = Aw and d/dt wᵀPw = wᵀ(AᵀP+PA)w; along f₀, d/dt P₁₁σ² = 0"
    method = "sympy identities"

    def derive(self) -> VDecreaseSubject:
        from .lemma2 import affine_fields

        g = G()
        fields = affine_fields(g)
        A = _symbolic.A(g)
        p, (p11, _, _) = _template_p(g)
        q = _m(model.lyapunov_rate_entries(g.k_p, g.k_i, g.k_v, tuple(tuple(p[i, j] for j in range(3)) for i in range(3))))
        x = sp.Matrix([g.sigma, g.phi, g.v])
        flows, residuals = [], []
        for k in (1, -1):
            w = x - k * g.f_c * sp.Matrix([0, 1, 0])
            flows.append((sp.Matrix(fields[k]), A * w, w))
            residuals.append(fp.expand(2 * (w.T * p * sp.Matrix(fields[k]))[0] - (w.T * q * w)[0]))
        stick = sp.expand(2 * p11 * g.sigma * fields[0][0])
        return VDecreaseSubject(tuple(flows), tuple(residuals), stick)

    def verify(self, s: VDecreaseSubject) -> Outcome:
        for (field, aw, w), residual in zip(s.shifted_flows, s.rate_residuals):
            gap = (field - aw).applyfunc(sp.expand)
            if any(not is_zero(e) for e in gap):
                return Outcome.fail(f"f = {list(field)} is not A·w for w = {list(w)}: difference {list(gap)}")
            if not is_zero(residual):
                return Outcome.fail(f"d/dt wᵀPw − wᵀQw = {residual} ≠ 0")
        if not is_zero(s.stick_rate):
            return Outcome.fail(f"along f₀, d/dt P₁₁σ² = {s.stick_rate} ≠ 0")
        return Outcome(True, "", (("\\tfrac{d}{dt}|w|_P^2 - w^\\top Q w", "0"),))


# -- U's rate ------------------------------------------------------------------------------


@dataclass(frozen=True)
class URateSubject:
    k12_diagonal: tuple[sp.Expr, ...]  # the (1,1) entry of −(KB_s + B_sᵀK) for a general K, s = ±1
    outside: tuple[tuple[sp.Expr, sp.Expr], ...]  # (true ẏ − (B_s y − 2f_c e₃) as a list-expr, U̇ identity residual)
    band: tuple[sp.Expr, ...]  # U̇ identity residual inside the band
    band_friction: sp.Expr  # f_c − φ at the band's ends
    odd: sp.Matrix  # F(−x) + F(x) with sgn as a symbol


def _y_rate(g, field: sp.Matrix, sub: dict, s: int) -> sp.Matrix:
    """``ẏ`` for ``y = (sσ, −φ − f_c, v)`` from the model's field, after the substitution."""
    return sp.Matrix([s * field[0], -field[1], field[2]]).subs(sub)


class QuadraticURate(Obligation):
    """``quadratic.U_rate``: ``U̇ ≤ 0`` on ``R̂`` follows from the verifier's copositive forms and ``K₃ⱼ ≥ 0``."""

    id = "quadratic.U_rate"
    paper = "beyond the paper: Lemma 3, eq. (hatVdot) for U = yᵀKy"
    statement = (
        "on R̂ ∩ {v > 0}, s = ±1: outside the band ẏ = B_s y − 2f_c e₃ and U̇ = −yᵀMy − 4f_c(Ky)₃; inside, "
        "U̇ = −(band form) − 2(f_c − φ)(Ky)₃ with f_c − φ ≥ 0; K₁₂ = 0 is forced; F is odd"
    )
    method = "sympy identities over the sign of σ and the two φ-pieces of R̂ ∩ {v > 0}"

    def derive(self) -> URateSubject:
        from .lemma2 import affine_fields

        g = G()
        field = sp.Matrix(affine_fields(g)[1])  # v > 0
        k, _ = _template_k()
        y1, y2, y3 = _sym("y1 y2 y3", positive=True)
        y = sp.Matrix([y1, y2, y3])
        k12 = sp.Symbol("K12", real=True)
        general_k = ((k[0, 0], k12, k[0, 2]), (k12, k[1, 1], k[1, 2]), (k[0, 2], k[1, 2], k[2, 2]))
        diag, outside, band = [], [], []
        for s in (1, -1):
            b = _m(model.slip_rate_entries(g.k_p, g.k_i, g.k_v, s))
            diag.append(sp.expand(model.u_rate_entries(general_k, model.slip_rate_entries(g.k_p, g.k_i, g.k_v, s))[0][0] - 2 * s * k12))
            m = _m(model.u_rate_entries(tuple(tuple(k[i, j] for j in range(3)) for i in range(3)), model.slip_rate_entries(g.k_p, g.k_i, g.k_v, s)))
            ydot = _y_rate(g, field, {g.sigma: s * y1, g.phi: -y2 - g.f_c, g.v: y3}, s)
            flow_gap = sp.expand(sum((ydot - (b * y - sp.Matrix([0, 0, 2 * g.f_c]))).applyfunc(lambda e: e**2)))
            udot = 2 * (y.T * k * ydot)[0]
            outside.append((flow_gap, fp.expand(udot - (-(y.T * m * y)[0] - 2 * (k * y)[2] * 2 * g.f_c))))
            # inside the band: y₂ = 0, φ free in [−f_c, f_c]
            yb = sp.Matrix([y1, 0, y3])
            ydot_b = sp.Matrix([s * field[0], 0, field[2]]).subs({g.sigma: s * y1, g.v: y3})
            udot_b = 2 * (yb.T * k * ydot_b)[0]
            form = _m(model.band_rate_entries(g.k_i, g.k_v, tuple(tuple(k[i, j] for j in range(3)) for i in range(3)), s))
            u2 = sp.Matrix([y1, y3])
            band.append(fp.expand(udot_b - (-(u2.T * form * u2)[0] - 2 * (k * yb)[2] * (g.f_c - g.phi))))
        sv = sp.Symbol("sgn_v", real=True)
        x = sp.Matrix([g.sigma, g.phi, g.v])
        F = lambda xx, sg: _symbolic.A(g) * xx - _symbolic.b(g) * sg  # noqa: E731
        return URateSubject(tuple(diag), tuple(outside), tuple(band), g.f_c - g.phi, (F(-x, -sv) + F(x, sv)).applyfunc(sp.expand))

    def verify(self, s: URateSubject) -> Outcome:
        g = G()
        if any(not is_zero(e) for e in s.k12_diagonal):
            return Outcome.fail(f"the (1,1) entry of −(KB_s + B_sᵀK) is not 2sK₁₂: residuals {list(s.k12_diagonal)}")
        for sign, (flow_gap, residual) in zip((1, -1), s.outside):
            if not is_zero(flow_gap):
                return Outcome.fail(f"s = {sign}: the model's ẏ outside the band is not B_s y − 2f_c e₃ (squared gap {flow_gap})")
            if not is_zero(residual):
                return Outcome.fail(f"s = {sign}: U̇ − (−yᵀMy − 4f_c(Ky)₃) = {residual} ≠ 0 outside the band")
        for sign, residual in zip((1, -1), s.band):
            if not is_zero(residual):
                return Outcome.fail(f"s = {sign}: inside the band U̇ differs from −(band form) − 2(f_c−φ)(Ky)₃ by {residual}")
        # f_c − φ ≥ 0 on the band [−f_c, f_c]: at its ends it is 2f_c and 0, and it is affine in φ
        ends = [sp.expand(s.band_friction.subs(g.phi, e)) for e in (-g.f_c, g.f_c)]
        if not (sp.Poly(s.band_friction, g.phi).degree() <= 1 and all(sign_of(e) in (0, 1) for e in ends)):
            return Outcome.fail(f"the friction term f_c − φ = {s.band_friction} is not shown ≥ 0 on |φ| ≤ f_c")
        if any(not is_zero(e) for e in s.odd):
            return Outcome.fail(f"F(−x) + F(x) = {list(s.odd)} ≠ 0: the case v < 0 is not the mirror image")
        return Outcome(True, "", (("\\dot U \\text{ outside the band}", "-y^\\top M_s y - 4f_c (Ky)_3"),))


# -- U ≥ V at the exit of R̂ -----------------------------------------------------------------


@dataclass(frozen=True)
class UExitSubject:
    rest_residual: sp.Expr
    edge_remainders: tuple[sp.Expr, ...]  # (U − V) − edge form, one per sign class of (σ, v)


class QuadraticUExit(Obligation):
    """``quadratic.U_exit``: ``U − V`` at the exit of ``R̂`` is at least the verifier's two exit forms."""

    id = "quadratic.U_exit"
    paper = "beyond the paper: Proposition 1's case (ii) at t₁, with U for V̂"
    statement = (
        "at v = 0, U − V = [|σ|,|dz|]·(exit form 1)·[|σ|,|dz|]ᵀ; at φ = f_c sign(v), v ≠ 0, "
        "U − V − [|σ|,|v|]·(exit form 2)·[|σ|,|v|]ᵀ = 2P₂₂(σv + |σ||v|) ≥ 0"
    )
    method = "sympy identities; exhaustive split over the signs of σ and v, remainders shown nonnegative"

    def derive(self) -> UExitSubject:
        g = G()
        p, (p11, p22, _) = _template_p(g)
        k, _ = _template_k()
        kt = tuple(tuple(k[i, j] for j in range(3)) for i in range(3))
        pt = tuple(tuple(p[i, j] for j in range(3)) for i in range(3))
        at_rest, at_edge = (_m(e) for e in model.exit_entries(kt, pt))
        a, d = _sym("a d", nonnegative=True)  # |σ| and |dz(φ)| at v = 0
        yr = sp.Matrix([a, 0, 0]) + sp.Matrix([0, d, 0])
        v_rest = p11 * a**2 + p22 * d**2  # quadratic.P_structure: the form at v = 0, minimised at f = sat(φ)
        rest = sp.expand((yr.T * k * yr)[0] - v_rest - (sp.Matrix([a, d]).T * at_rest * sp.Matrix([a, d]))[0])
        remainders = []
        m, n = _sym("m n", positive=True)
        for s_sigma, s_v in itertools.product((1, -1), (1, -1)):
            sigma, v = s_sigma * m, s_v * n
            w = sp.Matrix([sigma, 0, v])  # φ − f_c sign(v) = 0
            u = sp.Matrix([m, 0, n])
            diff = (u.T * k * u)[0] - (w.T * p * w)[0] - (sp.Matrix([m, n]).T * at_edge * sp.Matrix([m, n]))[0]
            remainders.append(fp.expand(diff))
        return UExitSubject(rest, tuple(remainders))

    def verify(self, s: UExitSubject) -> Outcome:
        if not is_zero(s.rest_residual):
            return Outcome.fail(f"at v = 0, U − V − (exit form 1) = {s.rest_residual} ≠ 0")
        for r in s.edge_remainders:
            if not is_nonneg(r):
                return Outcome.fail(f"at φ = f_c sign(v), U − V − (exit form 2) = {r} is not shown ≥ 0")
        return Outcome(True, "", tuple((f"\\text{{remainder {i + 1}}}", latex(r)) for i, r in enumerate(s.edge_remainders)))


# -- the bound -----------------------------------------------------------------------------


@dataclass(frozen=True)
class Step:
    name: str
    lhs: sp.Expr
    rhs: sp.Expr
    uses: tuple[tuple[str, sp.Expr], ...]  # (earlier fact, nonnegative multiplier)


@dataclass(frozen=True)
class BoundSubject:
    facts: dict[str, tuple[sp.Expr, sp.Expr]]
    steps: tuple[Step, ...]
    goals: tuple[tuple[str, sp.Expr, sp.Expr], ...]  # (step, D_t, D_0) that must read D_t ≤ κ² D_0
    kappa_squared: sp.Expr


class QuadraticStabilityBound(Obligation):
    """``quadratic.stability_bound``: eq. (stabState) with ``κ² ≥ max(c₂, γ)`` by Proposition 1's two cases."""

    id = "quadratic.stability_bound"
    paper = "beyond the paper: Proposition 1 item 2, eqs. (stabState), (boundInHatR), (boundInHatRandInR) with U for V̂"
    statement = (
        "|x(t)|²_𝒜 ≤ κ²|x(0)|²_𝒜 when x stays in R̂ (U), after its first time t₁ in R (U at t₁, then V), "
        "and when x(0) ∈ R (V), from P ⪰ I, V ≤ c₂|x|² on R, |y|² ≤ U ≤ γ|y|² on R̂, U ≥ V at t₁, κ² ≥ c₂, κ² ≥ γ"
    )
    method = "chain of inequalities, each step certified by nonnegative multipliers and a nonnegative remainder"

    def derive(self) -> BoundSubject:
        c2, gamma, kappa = _sym("c_2 gamma kappa", positive=True)
        D0, Dt, U0, Ut, U1, V0, V1, Vt = _sym("D_0 D_t U_0 U_t U_t1 V_0 V_t1 V_t", nonnegative=True)
        facts = {
            "P ⪰ I": (Dt, Vt),
            "V ≤ c₂|x|² on R (x(0) ∈ R)": (V0, c2 * D0),
            "V nonincreasing (t ≥ t₁)": (Vt, V1),
            "V nonincreasing (x(0) ∈ R)": (Vt, V0),
            "U ≥ |y|² on R̂": (Dt, Ut),
            "U nonincreasing on R̂": (Ut, U0),
            "U nonincreasing on R̂ up to t₁": (U1, U0),
            "U ≤ γ|y|² on R̂": (U0, gamma * D0),
            "U ≥ V at t₁": (V1, U1),
            "κ² ≥ c₂": (c2, kappa**2),
            "κ² ≥ γ": (gamma, kappa**2),
        }
        steps = (
            Step("case (i) / t < t₁", Dt, kappa**2 * D0, (("U ≥ |y|² on R̂", 1), ("U nonincreasing on R̂", 1), ("U ≤ γ|y|² on R̂", 1), ("κ² ≥ γ", D0))),
            Step("case (ii), t ≥ t₁", Dt, kappa**2 * D0, (("P ⪰ I", 1), ("V nonincreasing (t ≥ t₁)", 1), ("U ≥ V at t₁", 1),
                                                           ("U nonincreasing on R̂ up to t₁", 1), ("U ≤ γ|y|² on R̂", 1), ("κ² ≥ γ", D0))),
            Step("case (ii), t₁ = 0", Dt, kappa**2 * D0, (("P ⪰ I", 1), ("V nonincreasing (x(0) ∈ R)", 1), ("V ≤ c₂|x|² on R (x(0) ∈ R)", 1), ("κ² ≥ c₂", D0))),
        )
        goals = tuple((step.name, Dt, D0) for step in steps)
        return BoundSubject(facts, steps, goals, kappa**2)

    def verify(self, s: BoundSubject) -> Outcome:
        rows = []
        proved = {}
        for step in s.steps:
            missing = [name for name, _ in step.uses if name not in s.facts]
            if missing:
                return Outcome.fail(f"step {step.name!r} uses unknown facts {missing}")
            if any(not is_nonneg(mult) for _, mult in step.uses):
                return Outcome.fail(f"step {step.name!r} has a multiplier not shown ≥ 0")
            remainder = sp.expand((step.rhs - step.lhs) - sum(mult * (s.facts[name][1] - s.facts[name][0]) for name, mult in step.uses))
            if not is_nonneg(remainder):
                return Outcome.fail(f"step {step.name!r} ({step.lhs} ≤ {step.rhs}) does not follow: remainder {remainder}")
            proved[step.name] = (step.lhs, step.rhs)
            rows.append((f"\\text{{{step.name}}}", f"{latex(step.lhs)} \\le {latex(step.rhs)}"))
        for name, dt, d0 in s.goals:
            lhs, rhs = proved.get(name, (None, None))
            if lhs is None or not is_zero(lhs - dt) or not is_zero(rhs - s.kappa_squared * d0):
                return Outcome.fail(f"case {name!r} does not end in D_t ≤ κ² D_0")
        return Outcome(True, "", tuple(rows))


OBLIGATIONS = (QuadraticPStructure, QuadraticVDecrease, QuadraticURate, QuadraticUExit, QuadraticStabilityBound)
