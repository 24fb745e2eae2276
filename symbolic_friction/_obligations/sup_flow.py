"""The sup-of-flow Lyapunov function (beyond the paper): its lemma, its bounds and the stability bound.

With ``g(w) = sup_{t≥0} |e^{At}w|²`` (finite: ``A`` is Hurwitz under
Assumption 1) and ``V_∞(x) = min_{f ∈ f_c SGN(v)} g(x − f e₂)`` (eq.
lyapLikeV with ``|·|²_P`` replaced by ``g``), the new lemma says: ``V_∞`` is
nonincreasing along every solution of eq. (xDot), ``|x|²_𝒜 ≤ V_∞``
everywhere, and ``V_∞ ≤ c₂|x|²_𝒜`` on ``R`` when ``c₂ ≥ sup_t ‖e^{At}‖₂²``.
These obligations mechanise its algebraic steps, for symbolic gains, from the
package's one model (``A`` from ``system_matrix_entries``, the minimiser
``friction_selection``, ``sat``, ``dz``, ``|x|²_𝒜``, ``R``, the paper's ``P``):

* ``sup_flow.slip_flow`` — during a slip ``w = x − f_c sign(v) e₂`` obeys
  ``ẇ = Aw`` (``A e₂ = e₃``), so ``g(w(t)) = sup_{τ≥t}|e^{Aτ}w(0)|² ≤ g(w(0))``.
* ``sup_flow.rest_minimum`` — ``ψ ↦ g(σ, ψ, 0)`` is convex and minimal at
  ``ψ = 0`` (``A e₁ = e₂`` fixes the ψ-slope at every maximising time; the
  quadratic's Taylor form then replaces the Danskin step).
* ``sup_flow.nonincreasing`` — the minimiser at ``v = 0`` is ``sat_{f_c}(φ)``,
  and Claim 1's table row by row for ``V_∞``; lsc and Fact 2 are cited.
* ``sup_flow.bounds`` — ``|x|²_𝒜 ≤ V_∞`` (the ``t = 0`` term) and
  ``V_∞ = g(w)``, ``|w| = |x|_𝒜`` on ``R``.
* ``sup_flow.exit`` — the minimiser's ``w`` where a solution leaves ``R̂`` is
  the template model's ``exit_map`` (:mod:`symbolic_friction._model.sup_flow`),
  the verifier's ``exit_forms`` are ``U − |e^{At}w|²`` there, and its
  ``tail_gram`` is the tail ``|e^{At}w|² ≤ (1/p)|e^{AT}w|²_P``.
* ``sup_flow.stability_bound`` — eq. (stabState) by Proposition 1's two
  cases, with the chain checker of ``quadratic.stability_bound``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import attractor as _attractor
from .._model import coordinates as _coordinates
from .._model import lyapunov as _lyapunov
from .._model import symbolic as _symbolic
from . import _sup_flow_points as _pt
from ._base import Obligation, Outcome
from ._decide import G, is_zero, latex, pos, sign_of
from ._inequalities import is_nonneg

__all__ = [
    "SlipFlow",
    "RestMinimum",
    "Nonincreasing",
    "Bounds",
    "Exit",
    "SupFlowStabilityBound",
    "OBLIGATIONS",
]

_LSC_AND_FACT2 = (
    "cited: V_∞ is lsc as in the paper's proof of Lemma 2 (g is continuous, √g being a norm), "
    "and Fact 2 turns 'V_∞(x(t)) ≤ V_∞(x(τ)) on [τ, τ+T] at every τ' into nonincreasing"
)


# -- slip_flow --------------------------------------------------------------------------------


@dataclass(frozen=True)
class SlipFlowSubject:
    shift: sp.Matrix  # A(x − f e₂) − (Ax − f e₃)
    b_gap: sp.Matrix  # b − f_c e₃
    columns: tuple[sp.Matrix, sp.Matrix]  # A e₁ − e₂, A e₂ − e₃
    slips: tuple[sp.Matrix, ...]  # A w − F_k(x) for w = x − k f_c e₂, k = ±1
    rest_sigma_rate: sp.Expr  # (Ax − b ω)₁ at v = 0, ω a selection of SGN(0)


class SlipFlow(Obligation):
    """``sup_flow.slip_flow``: during a slip ``w = x − f_c sign(v) e₂`` follows the friction-free flow ``ẇ = Aw``."""

    id = "sup_flow.slip_flow"
    paper = "beyond the paper: eqs. (xDot), (subcasesAffine); the flow behind g(w) = sup_t |e^{At}w|²"
    statement = (
        "A(x − f e₂) = Ax − f e₃ for every f, b = f_c e₃, A e₁ = e₂, A e₂ = e₃; along f_{±1} = Ax ∓ b, "
        "w = x ∓ f_c e₂ obeys ẇ = Aw, so g(w(t)) = sup_{τ≥t}|e^{Aτ}w(0)|² ≤ g(w(0)) (semigroup); "
        "at v = 0, σ̇ = 0 for every selection ω of SGN(0)"
    )
    method = "sympy identities"

    def derive(self) -> SlipFlowSubject:
        g = G()
        A, b, x = _pt.system_matrix(g), _pt.input_vector(g), _pt.state(g)
        f, omega = sp.symbols("f omega", real=True)
        e1, e2, e3 = _pt.E
        slips = tuple((A * (x - k * g.f_c * e2) - (A * x - k * b)).applyfunc(sp.expand) for k in (1, -1))
        return SlipFlowSubject(
            shift=(A * (x - f * e2) - (A * x - f * e3)).applyfunc(sp.expand),
            b_gap=(b - g.f_c * e3).applyfunc(sp.expand),
            columns=(A * e1 - e2, A * e2 - e3),
            slips=slips,
            rest_sigma_rate=sp.expand((A * x - b * omega)[0].subs(g.v, 0)),
        )

    def verify(self, s: SlipFlowSubject) -> Outcome:
        if any(not is_zero(e) for e in s.shift):
            return Outcome.fail(f"A(x − f e₂) − (Ax − f e₃) = {list(s.shift)} ≠ 0")
        if any(not is_zero(e) for e in s.b_gap):
            return Outcome.fail(f"b − f_c e₃ = {list(s.b_gap)} ≠ 0")
        for name, gap in zip(("A e₁ − e₂", "A e₂ − e₃"), s.columns):
            if any(not is_zero(e) for e in gap):
                return Outcome.fail(f"{name} = {list(gap)} ≠ 0")
        for k, gap in zip((1, -1), s.slips):
            if any(not is_zero(e) for e in gap):
                return Outcome.fail(f"k = {k}: Aw − (Ax − k b) = {list(gap)} ≠ 0 for w = x − k f_c e₂: the slip is not the flow ẇ = Aw")
        if not is_zero(s.rest_sigma_rate):
            return Outcome.fail(f"at v = 0, σ̇ = {s.rest_sigma_rate} ≠ 0")
        return Outcome(True, "", (("A(x - f e_2) - (Ax - f e_3)", "0"), ("\\dot\\sigma\\big|_{v=0}", "0")))


# -- rest_minimum -----------------------------------------------------------------------------


@dataclass(frozen=True)
class RestMinimumSubject:
    """Polynomials (elements of one ring over ℚ: exact, and cheap to multiply out)."""

    time_rate: Any  # d/dt |Mσe₁|² with M' = MA
    psi_slope: Any  # ∂_ψ |M(σe₁ + ψe₂)|² at ψ = 0
    sigma: Any
    slope_at_identity: Any  # the slope at M = I (t* = 0)
    curvature: Any  # ∂²_ψ |M(σe₁ + ψe₂)|²
    column_two: Any  # |Me₂|²
    taylor_gap: Any  # q(ψ) − (q(0) + ψ q'(0) + ½ψ² q'')


class RestMinimum(Obligation):
    """``sup_flow.rest_minimum``: ``ψ ↦ g(σ, ψ, 0)`` is convex and minimal at ``ψ = 0``."""

    id = "sup_flow.rest_minimum"
    paper = "beyond the paper: eq. (lyapLikeV) with g for |·|²_P, its minimiser at v = 0"
    statement = (
        "for every M with M' = MA (M = e^{At}): d/dt|Mσe₁|² = σ·∂_ψ|M(σe₁+ψe₂)|² at ψ = 0 (A e₁ = e₂), so the "
        "ψ-slope vanishes at an interior maximiser t* of t ↦ |e^{At}σe₁|² (σ ≠ 0), at t* = 0 (M = I) and at σ = 0; "
        "∂²_ψ = 2|Me₂|² ≥ 0 and q is quadratic in ψ, so q_{t*}(ψ) = g(σ,0,0) + ψ²|Me₂|² and g(σ,ψ,0) ≥ g(σ,0,0); "
        "this replaces the Danskin step (cited only: the sup is attained, as e^{At} → 0); a sup of convex "
        "quadratics, ψ ↦ g(σ,ψ,0) is convex, so nondecreasing in |ψ| on each side of 0"
    )
    method = "polynomial identities over ℚ in a generic 3×3 M; sum of squares"

    def derive(self) -> RestMinimumSubject:
        from sympy.polys.rings import ring

        ring_, *gens = ring("m11 m12 m13 m21 m22 m23 m31 m32 m33 sigma psi k_p k_i k_v", sp.QQ)
        m = [gens[0:3], gens[3:6], gens[6:9]]
        sigma, psi, k_p, k_i, k_v = gens[9:]
        a = [[ring_(e) for e in row] for row in _coordinates.system_matrix_entries(k_p, k_i, k_v)]
        ma = _pt.matmul(m, a)
        column = lambda mat, j: [mat[i][j] for i in range(3)]  # noqa: E731
        u = [sigma * m[i][0] + psi * m[i][1] for i in range(3)]  # M(σe₁ + ψe₂)
        q = _pt.norm2(u)
        slope = q.diff(psi).compose(psi, ring_(0))
        curvature = q.diff(psi).diff(psi)
        identity = {g: ring_(int(i == j)) for (i, row) in enumerate(m) for (j, g) in enumerate(row)}
        at_identity = slope.compose(list(identity.items()))
        me1 = [sigma * e for e in column(m, 0)]
        rate = 2 * sum((x * (sigma * y) for x, y in zip(me1, column(ma, 0))), ring_(0))  # M' = MA: (Mσe₁)' = MAσe₁
        return RestMinimumSubject(
            time_rate=rate,
            psi_slope=slope,
            sigma=sigma,
            slope_at_identity=at_identity,
            curvature=curvature,
            column_two=_pt.norm2(column(m, 1)),
            taylor_gap=q - (q.compose(psi, ring_(0)) + psi * slope + psi**2 * curvature * sp.Rational(1, 2)),
        )

    def verify(self, s: RestMinimumSubject) -> Outcome:
        gap = s.time_rate - s.sigma * s.psi_slope
        if gap != 0:
            return Outcome.fail(f"d/dt|Mσe₁|² − σ·∂_ψ|M(σe₁+ψe₂)|² = {gap} ≠ 0: the maximiser does not fix the ψ-slope")
        if s.slope_at_identity != 0:
            return Outcome.fail(f"at t* = 0 (M = I) the ψ-slope is {s.slope_at_identity}, not 0")
        at_rest = s.psi_slope.compose(s.sigma, s.sigma.ring(0))
        if at_rest != 0:
            return Outcome.fail(f"at σ = 0 the ψ-slope is {at_rest}, not 0")
        if s.curvature - 2 * s.column_two != 0:
            return Outcome.fail(f"∂²_ψ|M(σe₁+ψe₂)|² = {s.curvature}, not 2|Me₂|²")
        if not is_nonneg(s.curvature.as_expr()):
            return Outcome.fail(f"∂²_ψ = {s.curvature} is not shown ≥ 0")
        if s.taylor_gap != 0:
            return Outcome.fail(f"|M(σe₁+ψe₂)|² is not its second-order Taylor polynomial in ψ: gap {s.taylor_gap}")
        return Outcome(True, "", (
            ("\\tfrac{d}{dt}|M\\sigma e_1|^2", "2\\sigma^2 (Me_1)^\\top (MAe_1) = \\sigma\\,\\partial_\\psi |M(\\sigma e_1 + \\psi e_2)|^2\\big|_{\\psi=0}"),
            ("\\partial_\\psi^2 |M(\\sigma e_1 + \\psi e_2)|^2", "2|Me_2|^2"),
        ))


# -- nonincreasing ----------------------------------------------------------------------------


@dataclass(frozen=True)
class NonincreasingSubject:
    classes: tuple[_pt.Between, ...]
    rows: tuple[_pt.RowStep, ...]
    stick_rates: tuple[sp.Expr, sp.Expr]  # σ̇ and v̇ along f₀


class Nonincreasing(Obligation):
    """``sup_flow.nonincreasing``: ``V_∞`` cannot increase along a solution, row by row of Claim 1's table."""

    id = "sup_flow.nonincreasing"
    paper = "beyond the paper: Claim 1 and Lemma 2 item 2 for V_∞ (Fact 2, lsc cited)"
    statement = (
        "at v = 0, for every class of φ, dz(φ) lies between 0 and φ − f for f = ±f_c (so for all |f| ≤ f_c) "
        "and |sat φ| ≤ f_c: by sup_flow.rest_minimum the minimiser is sat(φ), V_∞ = g(σ, dz φ, 0), and V_∞ "
        "does not jump up where a slip arrives at v = 0; for Claim 1's rows with k = ±1 the start's argument "
        "is the slip's w(0) = x̄ − k f_c e₂ (slip, crossing at |φ| > f_c, stick exit at φ = ±f_c: "
        "V_∞(x(t)) = g(w(t)) ≤ g(w(0)) = V_∞(x̄) by sup_flow.slip_flow), and with k = 0 dz(φ̄) = 0 and f₀ "
        "keeps σ and v (a stick keeps V_∞ = g(σ̄, 0, 0); claim1.cases keeps |φ| ≤ f_c on [0, T]); "
        + _LSC_AND_FACT2
    )
    method = "exhaustive split over Claim 1's rows and the five classes of φ, each exact; sympy identities"

    def derive(self) -> NonincreasingSubject:
        from .claim1 import table_rows
        from .lemma2 import F0_MATRIX

        g = G()
        e2 = _pt.E[1]
        classes, at_rest = [], {}
        for label, phi, fc in _pt.phi_points(g.f_c):
            d = _pt.exact(_attractor.dz(phi, fc))
            sat = _pt.exact(_attractor.sat(phi, fc))
            between = tuple(sp.expand(d * (phi - f - d)) for f in (fc, -fc))
            rest_w = _pt.minimiser_w(_pt.WithFc(fc), g.sigma, phi, 0)
            classes.append(_pt.Between(label, rest_w, d, (fc - sat, fc + sat), between))
            at_rest[label] = (phi, fc, d, rest_w)
        rows = []
        sigmas = {"> 0": pos("q_s"), "= 0": sp.Integer(0), "< 0": -pos("q_s"), None: g.sigma}
        for row in table_rows(g.f_c):
            sigma = sigmas[row.sigma]
            if row.v == "= 0":
                phi, fc, d, rest_w = at_rest[row.phi]
                start = rest_w.xreplace({g.sigma: sigma})
            else:  # v̄ ≠ 0: any φ̄
                phi, fc, d = g.phi, g.f_c, None
                start = _pt.minimiser_w(g, sigma, phi, pos("q_v") if row.v == "> 0" else -pos("q_v"))
            point = sp.Matrix([sigma, phi, start[2]])
            slip = point - row.k * fc * e2 if row.k else None
            rows.append(_pt.RowStep(f"({row.label})", row.k, start, slip, d if row.k == 0 else None))
        f0 = sp.Matrix(F0_MATRIX) * _pt.state(g)
        return NonincreasingSubject(tuple(classes), tuple(rows), (f0[0], f0[2]))

    def verify(self, s: NonincreasingSubject) -> Outcome:
        for c in s.classes:
            if any(sign_of(e) not in (0, 1) for e in c.sat_room):
                return Outcome.fail(f"{c.label}: |sat(φ)| ≤ f_c is not shown ({list(c.sat_room)})")
            if any(sign_of(e) not in (0, 1) for e in c.between):
                return Outcome.fail(f"{c.label}: dz(φ) does not lie between 0 and φ ∓ f_c: dz·(φ − f − dz) = {list(c.between)}")
            gap = (c.rest_w - sp.Matrix([c.rest_w[0], c.dz, 0])).applyfunc(sp.expand)
            if any(not is_zero(e) for e in gap):
                return Outcome.fail(f"{c.label}: at v = 0 the minimiser's w = {list(c.rest_w)} is not (σ, dz φ, 0)")
        rows = []
        for r in s.rows:
            if r.k:
                gap = (r.start_w - r.slip_w).applyfunc(sp.expand)
                if any(not is_zero(e) for e in gap):
                    return Outcome.fail(f"row {r.label}, k = {r.k}: the minimiser's w = {list(r.start_w)} is not the slip's w(0) = {list(r.slip_w)}")
            else:
                if not is_zero(r.stick_dz):
                    return Outcome.fail(f"row {r.label}, k = 0: dz(φ̄) = {r.stick_dz} ≠ 0 in a stick")
                gap = (r.start_w - sp.Matrix([r.start_w[0], 0, 0])).applyfunc(sp.expand)
                if any(not is_zero(e) for e in gap):
                    return Outcome.fail(f"row {r.label}, k = 0: the minimiser's w = {list(r.start_w)} is not (σ̄, 0, 0)")
            rows.append(f"{r.label}\\;k={r.k}")
        if any(not is_zero(e) for e in s.stick_rates):
            return Outcome.fail(f"along f₀, (σ̇, v̇) = {list(s.stick_rates)} ≠ 0: a stick does not keep g(σ, 0, 0)")
        if (len(s.classes), len(rows)) != (5, 11):
            return Outcome.fail(f"{len(s.classes)} classes of φ and {len(rows)} rows of Claim 1's table checked, not 5 and 11")
        return Outcome(True, "", (("\\text{rows checked}", ",\\ ".join(rows)),))


# -- bounds -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class BoundsSubject:
    lower: tuple[_pt.LowerPiece, ...]
    upper: tuple[_pt.UpperPiece, ...]
    outside: tuple[tuple[str, sp.Expr], ...]  # (class, R-margin) of R̂'s classes: must be < 0


class Bounds(Obligation):
    """``sup_flow.bounds``: ``|x|²_𝒜 ≤ V_∞`` everywhere and ``V_∞ = g(w)`` with ``|w| = |x|_𝒜`` on ``R``."""

    id = "sup_flow.bounds"
    paper = "beyond the paper: Lemma 2 item 1 and eq. (VandR) for V_∞"
    statement = (
        "g(w) ≥ |w|² (the t = 0 term) and |x − f e₂|² − |x|²_𝒜 = (φ−f−dz)² + 2dz(φ−f−dz) ≥ 0 for |f| ≤ f_c, "
        "so |x|²_𝒜 ≤ V_∞ everywhere; on R (the model's v(φ − sign(v)f_c) ≥ 0, every class of φ and v) the "
        "minimiser's w has |w|² = |x|²_𝒜, so V_∞ = g(w) ≤ sup_t‖e^{At}‖₂²|w|² ≤ c₂|x|²_𝒜 when "
        "c₂ ≥ sup_t‖e^{At}‖₂² (operator norm); the other classes have margin < 0 (they are R̂)"
    )
    method = "exhaustive split over the signs of v and the five classes of φ; sympy identities and exact signs"

    def derive(self) -> BoundsSubject:
        g = G()
        f = sp.Symbol("f", real=True)
        qv = pos("q_v")
        lower, upper, outside = [], [], []
        for label, phi, fc in _pt.phi_points(g.f_c):
            d = _pt.exact(_attractor.dz(phi, fc))
            fcg = _pt.WithFc(fc)
            dist = _pt.exact(_attractor.squared_distance_x(fcg, [g.sigma, phi, g.v]))  # every v at once
            residual = sp.expand(g.sigma**2 + (phi - f) ** 2 + g.v**2 - dist - (phi - f - d) ** 2 - 2 * d * (phi - f - d))
            lower.append(_pt.LowerPiece(label, residual, tuple(sp.expand(d * (phi - ff - d)) for ff in (fc, -fc))))
            for h, v in ((0, sp.Integer(0)), (1, qv), (-1, -qv)):
                point = [g.sigma, phi, v]
                margin = sp.expand(_pt.exact(_lyapunov.R_margin(fcg, point)))
                where = f"v {'=' if h == 0 else ('>' if h > 0 else '<')} 0, {label}"
                if h == 0 or label in _pt.sides(h):
                    w = _pt.minimiser_w(fcg, *point)
                    upper.append(_pt.UpperPiece(where, margin, sp.expand(_pt.dot(w, w) - dist.xreplace({g.v: v}))))
                else:
                    outside.append((where, margin))
        return BoundsSubject(tuple(lower), tuple(upper), tuple(outside))

    def verify(self, s: BoundsSubject) -> Outcome:
        for piece in s.lower:
            if not is_zero(piece.residual):
                return Outcome.fail(f"{piece.label}: |x − f e₂|² − |x|²_𝒜 − (φ−f−dz)² − 2dz(φ−f−dz) = {piece.residual} ≠ 0")
            if any(sign_of(e) not in (0, 1) for e in piece.cross):
                return Outcome.fail(f"{piece.label}: dz(φ−f−dz) at f = ±f_c is {list(piece.cross)}, not shown ≥ 0")
        for piece in s.upper:
            if sign_of(piece.margin) not in (0, 1):
                return Outcome.fail(f"{piece.label}: the R-margin {piece.margin} is not shown ≥ 0, so this class is not in R")
            if not is_zero(piece.gap):
                return Outcome.fail(f"{piece.label} (in R): |w|² − |x|²_𝒜 = {piece.gap} ≠ 0 for the minimiser's w")
        for where, margin in s.outside:
            if sign_of(margin) != -1:
                return Outcome.fail(f"{where}: the R-margin {margin} is not shown < 0, so R has a class the bound misses")
        if len(s.upper) + len(s.outside) != 15:
            return Outcome.fail(f"{len(s.upper) + len(s.outside)} classes of (v, φ) checked, not 15")
        return Outcome(True, "", (("|x - fe_2|^2 - |x|_{\\mathcal A}^2", "(\\phi - f - \\mathrm{dz}\\,\\phi)^2 + 2\\,\\mathrm{dz}\\,\\phi\\,(\\phi - f - \\mathrm{dz}\\,\\phi)"),))


# -- exit -------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ExitSubject:
    points: tuple[_pt.ExitPoint, ...]
    form_gaps: tuple[tuple[str, Any], ...]  # the verifier's exit forms − (U − wᵀGw), generic G
    gram_gap: Any  # tail_gram(M, pQ, p) − MᵀQM, generic M and symmetric Q
    rate: Any  # d/dt |z|²_P along ż = Az with the paper's P (in ℚ(z, k, p), as the next four)
    decrease: Any  # c z₃², c = 2(k_v k_p − k_i) of eq. (dVdt)
    own_rate: Any  # 2zᵀP(Az) − zᵀ(the verifier's AᵀP + PA)z for a generic symmetric P (0 when right)
    tail_bound: Any  # the bound on |z|² the verifier uses for t ≥ T, generic symmetric P
    norm: Any  # |z|²
    premise: Any  # zᵀ(P − pI)z as the verifier builds P − pI, ≥ 0 by the certificate's premise P − pI ⪰ 0
    p: Any
    c: sp.Expr  # c with k_v = (k_i + δ)/k_p (Assumption 1), positive symbols


class Exit(Obligation):
    """``sup_flow.exit``: ``V_∞ = g(w)`` where a solution leaves ``R̂``, ``w`` in the verifier's exit forms, and its tail."""

    id = "sup_flow.exit"
    paper = "beyond the paper: Proposition 1's case (ii) at t₁, eqs. (lyapLikeP), (dVdt) for the tail"
    statement = (
        "where a solution leaves R̂ ∩ {v ≷ 0} (h = ±1: at v = 0 with hφ ≤ f_c, or at φ = h f_c with hv > 0; R-margin 0), "
        "for both signs s of σ the minimiser's w is h·D·y with D = exit_map(plane, h·s) of the template model, (h·s·y₁, −y₂, 0) resp. "
        "(h·s·y₁, 0, y₃), y = (|σ|, |dz φ|, |v|) from the model; the verifier's exit_forms are yᵀKy − wᵀGw there (generic "
        "symmetric G), so (g even) these copositive for G = e^{At}ᵀe^{At}, both signs and t ∈ I_i give U = max_i U_i ≥ "
        "g(w) = V_∞ there; tail: for any symmetric P, d/dt|z|²_P = zᵀ(AᵀP+PA)z along ż = Az, with AᵀP+PA as the verifier "
        "builds it, so ≤ 0 when the file's premise −(AᵀP+PA) ⪰ 0 holds (for the paper's P it is −c z₃², c = 2(k_v k_p − k_i) > 0 "
        "by Assumption 1, as in lemma2.dVdt) and (1/p)|z|²_P − |z|² = (1/p)zᵀ(P − pI)z ≥ 0 when P − pI ⪰ 0, so for t ≥ T ≥ 0 "
        "|e^{At}w|² ≤ (1/p)|e^{At}w|²_P ≤ (1/p)|e^{AT}w|²_P = wᵀ·tail_gram(e^{AT}, P, p)·w (tail_gram = (1/p)MᵀPM for generic M, P)"
    )
    method = ("exhaustive split over the half of R̂, the sign of σ and the class of φ; sympy identities; polynomial identities "
              "over ℚ for the verifier's forms; sign-definite decomposition")

    def derive(self) -> ExitSubject:
        from sympy.polys.fields import field

        from .lemma2 import decrease_rate

        g = G()
        # the tail in the field ℚ(z, k, p): exact, and cheap to multiply out
        from .._certify.quadratic import _scaled_identity, _sub
        from .._model.quadratic import lyapunov_rate_entries

        _, z1, z2, z3, k_p, k_i, k_v, p, q11, q12, q13, q22, q23, q33 = field(
            "z1 z2 z3 k_p k_i k_v p q11 q12 q13 q22 q23 q33", sp.QQ)
        z = (z1, z2, z3)
        a = _coordinates.system_matrix_entries(k_p, k_i, k_v)
        pm = _lyapunov.lyapunov_matrix_entries(k_p, k_i, k_v)
        q = ((q11, q12, q13), (q12, q22, q23), (q13, q23, q33))  # the tail's P: the file's own, or the paper's
        form = lambda m, u, v: sum((u[i] * m[i][j] * v[j] for i in range(3) for j in range(3)), p - p)  # noqa: E731
        az = [sum((a[i][j] * z[j] for j in range(3)), p - p) for i in range(3)]
        return ExitSubject(
            points=_pt.exit_points(g),
            form_gaps=_pt.exit_form_gaps(),
            gram_gap=_pt.tail_gram_gap(),
            rate=2 * form(pm, z, az),
            decrease=decrease_rate(_FieldGains(k_p, k_i, k_v)) * z3**2,
            c=decrease_rate(g).xreplace(_symbolic.assumption1_substitution(g)),
            own_rate=2 * form(q, z, az) - form(lyapunov_rate_entries(k_p, k_i, k_v, q), z, z),
            tail_bound=form(q, z, z) / p,
            norm=z1**2 + z2**2 + z3**2,
            premise=form(_sub(q, _scaled_identity(3, p)), z, z),
            p=p,
        )

    def verify(self, s: ExitSubject) -> Outcome:
        for pt in s.points:
            if not is_zero(pt.margin):
                return Outcome.fail(f"{pt.label}: the R-margin is {pt.margin}, not 0: not where a solution leaves R̂")
            if any(not is_zero(e) for e in pt.gap):
                return Outcome.fail(f"{pt.label}: the minimiser's w differs from the exit form by {list(pt.gap)}")
        if len(s.points) != 20:
            return Outcome.fail(f"{len(s.points)} exit points checked, not 20")
        for label, gap in s.form_gaps:
            if gap != 0:
                return Outcome.fail(f"{label}: the verifier's exit form is not U − wᵀGw at the exit; they differ by {gap}")
        if len(s.form_gaps) != 4:
            return Outcome.fail(f"{len(s.form_gaps)} exit forms checked, not 4")
        if s.gram_gap != 0:
            return Outcome.fail(f"tail_gram(M, P, p) − (1/p)MᵀPM ≠ 0 ({s.gram_gap}): the verifier's tail Gram is not the tail bound")
        if s.rate + s.decrease != 0:
            return Outcome.fail(f"d/dt |z|²_P = {s.rate} along ż = Az is not −c z₃² = {-s.decrease}: AᵀP + PA ⪯ 0 is not shown")
        if sign_of(s.c) != 1:
            return Outcome.fail(f"c = {s.c} under Assumption 1 is not shown > 0: AᵀP + PA ⪯ 0 is not shown")
        if s.own_rate != 0:
            return Outcome.fail(f"2zᵀP(Az) − zᵀ(AᵀP + PA)z = {s.own_rate} ≠ 0: the verifier's −(AᵀP + PA) ⪰ 0 is not d/dt|z|²_P ≤ 0")
        residual = s.p * s.tail_bound - s.p * s.norm - s.premise  # p > 0 is the certificate's premise
        if residual != 0:
            return Outcome.fail(f"p·(the tail bound − |z|²) − zᵀ(P − pI)z = {residual} ≠ 0: the tail bound does not follow from P − pI ⪰ 0")
        return Outcome(True, "", (
            ("\\tfrac{d}{dt}|z|_P^2 \\text{ along } \\dot z = Az", f"-c\\,z_3^2,\\quad c = {latex(s.c)} > 0"),
            ("\\tfrac1p|z|_P^2 - |z|^2", "\\tfrac1p z^\\top (P - pI) z"),
        ))


@dataclass(frozen=True)
class _FieldGains:
    """The gains :func:`lemma2.decrease_rate` reads, as elements of a field."""

    k_p: Any
    k_i: Any
    k_v: Any


# -- the bound --------------------------------------------------------------------------------

_CITED_ID = re.compile(r"\b((?:sup_flow|quadratic|lemma2|claim1)\.\w+)")


@dataclass(frozen=True)
class SupFlowBoundSubject:
    bound: Any  # quadratic.BoundSubject: facts, steps, goals, κ²
    registered: tuple[str, ...]  # the obligation ids check runs


class SupFlowStabilityBound(Obligation):
    """``sup_flow.stability_bound``: eq. (stabState) with ``κ² ≥ c₂`` and ``κ² ≥ γ_i`` by Proposition 1's two cases."""

    id = "sup_flow.stability_bound"
    paper = "beyond the paper: Proposition 1 item 2, eqs. (stabState), (boundInHatR), (boundInHatRandInR) with V_∞ for V and U = max_i U_i for V̂"
    statement = (
        "|x(t)|²_𝒜 ≤ κ²|x(0)|²_𝒜 when x stays in R̂ (U), after its first time t₁ in R (U at t₁, then V_∞) and when "
        "x(0) ∈ R (V_∞), from |x|²_𝒜 ≤ V_∞, V_∞ nonincreasing, V_∞ ≤ c₂|x|²_𝒜 on R, V_∞ = g(w) ≤ U at t₁ "
        "(the pieces I_i cover [0, ∞)), U ≥ U₀ ≥ |y|² (K₀ − I copositive), each U_i nonincreasing on R̂ "
        "(quadratic.U_rate), U_j ≤ γ_j|y|² (γ_jI − K_j copositive), κ² ≥ c₂, κ² ≥ γ_j; every cited obligation is one check runs"
    )
    method = "chain of inequalities, each step certified by nonnegative multipliers (the checker of quadratic.stability_bound)"

    def derive(self) -> SupFlowBoundSubject:
        from . import registry
        from .quadratic import BoundSubject, Step

        facts, steps, goals, kappa_squared = _pt.stability_chain(Step)
        return SupFlowBoundSubject(BoundSubject(facts, steps, goals, kappa_squared), tuple(cls.id for cls in registry()))

    def verify(self, s: SupFlowBoundSubject) -> Outcome:
        from .quadratic import QuadraticStabilityBound

        cited = sorted({m for name in s.bound.facts for m in _CITED_ID.findall(name)})
        missing = [c for c in cited if c not in s.registered]
        if missing:
            return Outcome.fail(f"the facts cite {missing}, which check does not run")
        if not cited:
            return Outcome.fail("no fact cites an obligation: the chain rests on nothing check runs")
        return QuadraticStabilityBound().verify(s.bound)


OBLIGATIONS = (SlipFlow, RestMinimum, Nonincreasing, Bounds, Exit, SupFlowStabilityBound)
