"""The sup-flow template, version 2 (beyond the paper): the sign split and the friction-drag split of ``R̂``.

Version 2 (``docs/design/sup_flow_v2.md``, :mod:`symbolic_friction._certify.sup_flow_v2`) gives each piece of version 1's
``U = max_i U_i`` (:mod:`.sup_flow`) two forms, ``K⁺`` where ``σv > 0`` and ``K⁻`` where ``σv < 0`` and on ``σ = 0``, with
``K₁₂`` kept (``u_matrix_signed``), and splits ``R̂`` by the friction excess ``f = f_c − φ − |dz φ|``:
``R̂′ = {x ∈ R̂ : f > ℓᵀy}``, ``ℓ ≥ 0``, ``y = (|σ|, |dz φ|, |v|)``.  These obligations mechanise its algebra for symbolic
gains, ``K`` (six entries), ``s = ±1`` and ``ℓ`` from the one model (``A``, ``b``, ``dz``, the minimiser, ``R``, ``|x|²_𝒜``,
:mod:`._model.quadratic`, :mod:`._model.sup_flow`): ``sup_flow_v2.U_rate`` (signed and drag rate forms against the vector
field), ``sup_flow_v2.sign_crossing`` (``σ̇ = −k_iv``: ``σv`` only passes from + to −; ``x ↦ −x``; the coupling block),
``sup_flow_v2.drag_region`` (``x − f_c e₂`` between ``D₀y`` and ``D_ℓy`` on ``R̂ ∖ R̂′``), ``sup_flow_v2.exit`` (the signed
and drag exit forms), ``sup_flow_v2.stability_bound`` (three starting cases); generic Gram matrices in rings over ℚ.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import sympy as sp
from sympy.polys.rings import ring

from .._model import attractor as _attractor
from .._model import lyapunov as _lyapunov
from .._model import quadratic as _quadratic
from .._model import sup_flow as _sup_flow
from . import _sup_flow_points as _pt
from ._base import Obligation, Outcome
from ._decide import G, is_zero, pos, sign_of
from ._inequalities import is_nonneg
from .quadratic import BoundSubject, QuadraticStabilityBound, Step, _y_rate

__all__ = ["URateV2", "SignCrossing", "DragRegion", "ExitV2", "StabilityBoundV2", "stability_chain_v2", "OBLIGATIONS"]

_ENTRIES = ("11", "12", "13", "22", "23", "33")


def _quad(m, u, zero) -> Any:  # uᵀMu for nested lists (sympy or ring elements)
    return sum((u[i] * m[i][j] * u[j] for i in range(len(u)) for j in range(len(u))), zero)


def _apply(d, u, zero) -> list:  # Du for nested lists
    return [sum((d[i][j] * u[j] for j in range(len(u))), zero) for i in range(len(d))]


def _nonzero(gaps) -> list:  # elements of rings over ℚ are compared with 0, sympy expressions decided by is_zero
    return [e for e in gaps if (e != 0 if hasattr(e, "ring") else not is_zero(e))]


def _signed_k(**assumptions: Any) -> tuple[sp.Matrix, tuple[sp.Symbol, ...]]:
    ks = sp.symbols(" ".join("K" + e for e in _ENTRIES), **(assumptions or {"real": True}))
    return sp.Matrix(_quadratic.u_matrix_signed(*ks)), ks


def _model_y(point, fc) -> tuple[sp.Matrix, sp.Expr]:
    """The model's ``y = (|σ|, |dz φ|, |v|)`` and friction excess ``f = f_c − φ − |dz φ|`` at ``point = (σ, φ, v)``."""
    y = sp.Matrix([_pt.exact(sp.Abs(point[0])), _pt.exact(sp.Abs(_pt.exact(_attractor.dz(point[1], fc)))), _pt.exact(sp.Abs(point[2]))])
    return y, sp.expand(fc - point[1] - y[1])


def _gram(g11, g12, g13, g22, g23, g33) -> tuple:
    return ((g11, g12, g13), (g12, g22, g23), (g13, g23, g33))


def _lin(ell, y) -> sp.Expr:
    return sp.expand(sum((e * y[i] for i, e in enumerate(ell)), sp.Integer(0)))


@dataclass(frozen=True)
class RateSign:
    """One sign ``s`` of ``σ`` on ``R̂ ∩ {v > 0}``: every residual (in a ring ℚ[gains, y, K, ℓ]) is 0 when the model is right."""

    s: int
    diagonal: Any  # u_rate_entries(K, B_s)₁₁ − 2sK₁₂
    y_gaps: tuple[sp.Expr, ...]  # the model's y at the parametrised points − (y₁, y₂, y₃) resp. (y₁, 0, y₃)
    flow_gap: tuple[Any, ...]  # ẏ − (B_s y − f e₃) outside the band, f the model's friction excess
    rate: Any  # U̇ + yᵀMy + 2(Ky)₃f
    drag: Any  # U̇ + yᵀDy + 2(Ky)₃(f − ℓᵀy), D = drag_rate_entries
    drag_gap: Any  # yᵀ(D − M)y − 2(Ky)₃ℓᵀy for every y
    band: Any  # U̇ + uᵀ(band form)u + 2(Ky)₃f inside the band, u = (y₁, y₃)
    drag_band: Any  # U̇ + uᵀ(drag band form)u + 2(Ky)₃(f − ℓᵀy) inside the band
    frictions: tuple[sp.Expr, sp.Expr]  # f outside and inside the band: > 0
    third_rows: tuple[sp.Expr, sp.Expr]  # (Ky)₃ outside and inside with K₃ⱼ ≥ 0


@dataclass(frozen=True)
class URateV2Subject:
    signs: tuple[RateSign, ...]


class URateV2(Obligation):
    """``sup_flow_v2.U_rate``: the signed rate forms and the drag rate and band forms bound ``U̇`` on ``R̂′``."""

    id = "sup_flow_v2.U_rate"
    paper = "beyond the paper: Lemma 3, eq. (hatVdot) for U = yᵀK^s y with K₁₂ kept and the friction drag"
    statement = (
        "for K = u_matrix_signed (six entries), s = ±1: the (1,1) entry of u_rate_entries(K, B_s) is 2sK₁₂, so its copositivity needs "
        "sK₁₂ ≥ 0; on R̂ ∩ {v > 0, sign σ = s}, y = (|σ|, |dz φ|, |v|) and f = f_c − φ − |dz φ| from the model (2f_c > 0 for φ < −f_c, "
        "f_c − φ > 0 in the band): outside the band ẏ = B_s y − f e₃ (the model's ẋ = Ax − b), U̇ = −yᵀMy − 2(Ky)₃f and "
        "U̇ + yᵀDy = −2(Ky)₃(f − ℓᵀy), D = drag_rate_entries(K, B_s, ℓ) (yᵀ(D − M)y = 2(Ky)₃ℓᵀy); inside (y₂ = 0) "
        "U̇ + (y₁,y₃)·drag_band_entries·(y₁,y₃)ᵀ = −2(Ky)₃(f − ℓᵀy); so with K₃ⱼ ≥ 0 ((Ky)₃ ≥ 0) and f > ℓᵀy (on R̂′) these "
        "forms copositive give U̇ ≤ 0; v < 0 is the mirror (sup_flow_v2.sign_crossing); at φ = −f_c (y not differentiable) the "
        "generalized-gradient argument of quadratic.U_rate is cited"
    )
    method = "polynomial identities over ℚ over the sign of σ and the φ-pieces of R̂ ∩ {v > 0}, the model's field at parametrised points; exact signs"

    def derive(self) -> URateV2Subject:
        g = G()
        field = _pt.system_matrix(g) * _pt.state(g) - _pt.input_vector(g)  # v > 0
        (k, ks), (kn, _), ell = _signed_k(), _signed_k(nonnegative=True), sp.symbols("ell1 ell2 ell3", nonnegative=True)
        third = {ks[2]: kn[0, 2], ks[4]: kn[1, 2], ks[5]: kn[2, 2]}  # K₁₃, K₂₃, K₃₃ ≥ 0
        kt, z = tuple(tuple(k[i, j] for j in range(3)) for i in range(3)), sp.Integer(0)
        y1, y2, y3, u, w = (pos(n) for n in ("y_1", "y_2", "y_3", "u_phi", "w_phi"))
        ring_, *_ = ring((g.k_p, g.k_i, g.k_v, g.f_c, y1, y2, y3, u, w, *ks, *ell), sp.QQ)  # exact and cheap; a non-polynomial model raises
        r = lambda es: [ring_(sp.sympify(e)) for e in es]  # noqa: E731
        kr, (l1, l2, l3), (k_p, k_i, k_v), zr = [r(row) for row in kt], r(ell), r((g.k_p, g.k_i, g.k_v)), ring_(0)
        y, yb, ub = r((y1, y2, y3)), r((y1, 0, y3)), r((y1, y3))
        out = []
        for s in (1, -1):
            b = _quadratic.slip_rate_entries(k_p, k_i, k_v, s)
            m, d = _quadratic.u_rate_entries(kr, b), _quadratic.drag_rate_entries(kr, b, (l1, l2, l3))
            at = {g.sigma: s * y1, g.phi: -g.f_c - y2, g.v: y3}  # outside the band: φ = −f_c − y₂
            (model_y, f), ydot = _model_y([at[g.sigma], at[g.phi], at[g.v]], g.f_c), r(_y_rate(g, field, at, s))
            band_at = {g.sigma: s * y1, g.phi: (w - u) / 2, g.f_c: (u + w) / 2, g.v: y3}  # inside: y₂ ≡ 0, so ẏ₂ = 0
            band_y, f_b = _model_y([band_at[g.sigma], band_at[g.phi], band_at[g.v]], band_at[g.f_c])
            ydot_b, (fr, fbr) = r([(s * field[0]).xreplace(band_at), 0, field[2].xreplace(band_at)]), r((f, f_b))
            ky, kyb = _apply(kr, y, zr), _apply(kr, yb, zr)
            udot, udot_b = 2 * sum((a * e for a, e in zip(ky, ydot)), zr), 2 * sum((a * e for a, e in zip(kyb, ydot_b)), zr)
            band, drag_band = _quadratic.band_rate_entries(k_i, k_v, kr, s), _quadratic.drag_band_entries(k_i, k_v, kr, s, (l1, l2, l3))
            out.append(RateSign(
                s=s,
                diagonal=m[0][0] - 2 * s * ring_(ks[1]),
                y_gaps=tuple(sp.expand(a - b_) for a, b_ in zip(list(model_y) + list(band_y), (y1, y2, y3, y1, 0, y3))),
                flow_gap=tuple(e - q + (fr if i == 2 else zr) for i, (e, q) in enumerate(zip(ydot, _apply(b, y, zr)))),
                rate=udot + _quad(m, y, zr) + 2 * ky[2] * fr,
                drag=udot + _quad(d, y, zr) + 2 * ky[2] * (fr - l1 * y[0] - l2 * y[1] - l3 * y[2]),
                drag_gap=_quad(d, y, zr) - _quad(m, y, zr) - 2 * ky[2] * (l1 * y[0] + l2 * y[1] + l3 * y[2]),
                band=udot_b + _quad(band, ub, zr) + 2 * kyb[2] * fbr,
                drag_band=udot_b + _quad(drag_band, ub, zr) + 2 * kyb[2] * (fbr - l1 * yb[0] - l3 * yb[2]),
                frictions=(f, f_b),
                third_rows=tuple(sp.expand(sum((kt[2][j] * e for j, e in enumerate(v)), z).xreplace(third)) for v in ((y1, y2, y3), (y1, z, y3))),
            ))
        return URateV2Subject(tuple(out))

    def verify(self, subject: URateV2Subject) -> Outcome:
        if sorted(r.s for r in subject.signs) != [-1, 1]:
            return Outcome.fail(f"signs of σ checked: {[r.s for r in subject.signs]}, not ±1")
        for r in subject.signs:
            tag = f"s = {r.s}"
            if _nonzero([r.diagonal]):
                return Outcome.fail(f"{tag}: the (1,1) entry of u_rate_entries(K, B_s) is not 2sK₁₂ (residual {r.diagonal})")
            if _nonzero(r.y_gaps):
                return Outcome.fail(f"{tag}: the model's y = (|σ|, |dz φ|, |v|) is not the parametrisation: gaps {list(r.y_gaps)}")
            if _nonzero(r.flow_gap):
                return Outcome.fail(f"{tag}: the model's ẏ outside the band is not B_s y − f e₃: gap {list(r.flow_gap)}")
            if any(sign_of(f) != 1 for f in r.frictions):
                return Outcome.fail(f"{tag}: the friction excess f = {list(r.frictions)} is not shown > 0 on R̂ ∩ {{v > 0}}")
            for name, residual in (("U̇ + yᵀMy + 2(Ky)₃f", r.rate), ("U̇ + yᵀDy + 2(Ky)₃(f − ℓᵀy) (the drag rate form)", r.drag),
                                   ("yᵀ(D − M)y − 2(Ky)₃ℓᵀy", r.drag_gap), ("inside the band, U̇ + (band form) + 2(Ky)₃f", r.band),
                                   ("inside the band, U̇ + (drag band form) + 2(Ky)₃(f − ℓᵀy)", r.drag_band)):
                if _nonzero([residual]):
                    return Outcome.fail(f"{tag}: {name} = {residual} ≠ 0")
            if not all(is_nonneg(e) for e in r.third_rows):
                return Outcome.fail(f"{tag}: (Ky)₃ = {list(r.third_rows)} is not shown ≥ 0 from K₃ⱼ ≥ 0, y ≥ 0")
        drag = r"-2(Ky)_3\,(f - \ell^\top y),\quad f = f_c - \phi - |\mathrm{dz}\,\phi|"
        return Outcome(True, "", ((r"\bigl(-(KB_s + B_s^\top K)\bigr)_{11}", r"2sK_{12}"), (r"y^\top (D_\ell - M) y", r"2(Ky)_3\,\ell^\top y"),
                                  (r"\dot U + y^\top D_\ell y \text{ on } \hat R \cap \{v>0\}", drag)))


@dataclass(frozen=True)
class Mirror:  # x ↦ −x in one class of (φ, v): each gap is 0 when the model is odd resp. even there
    label: str
    dz_gap: sp.Expr  # dz(−φ) + dz(φ)
    margin_gap: sp.Expr  # R-margin(−x) − R-margin(x)
    w_gap: sp.Matrix  # w(−x) + w(x), w the minimiser's x − f e₂


@dataclass(frozen=True)
class SignCrossingSubject:
    sigma_rates: tuple[tuple[int, sp.Expr], ...]  # (h, σ̇ + k_i v) along f_h = Ax − h b
    crossing: tuple[tuple[int, sp.Expr], ...]  # (h, v·σ̇ at v = h q): < 0
    odd: sp.Matrix  # F(−x, −ω) + F(x, ω)
    mirrors: tuple[Mirror, ...]
    sigma_v: sp.Expr  # (−σ)(−v) − σv
    coupling: Any  # U⁺ − U⁻ − (y₂, y₃)·coupling_block·(y₂, y₃)ᵀ at y₁ = 0 (ring)


class SignCrossing(Obligation):
    """``sup_flow_v2.sign_crossing``: ``σv`` only passes from ``+`` to ``−`` in ``R̂``, where ``U`` drops from ``U⁺`` to ``U⁻``."""

    id = "sup_flow_v2.sign_crossing"
    paper = "beyond the paper: eqs. (xDot), (subcasesAffine); the sign split of U on R̂"
    statement = (
        "along the slips f_h = Ax − h b (h = ±1, v ≠ 0) σ̇ = −k_i v, so v·σ̇ = −k_i v² < 0: on R̂ ∩ {hv > 0} F is single valued and "
        "affine (the solution is classical; σ = 0 is no discontinuity of F, so no sliding there) and σ strictly monotone, so σ "
        "crosses 0 at most once, transversally, and sign(σv) only passes from + to −; F(−x, −ω) = −F(x, ω) (friction odd), so "
        "x ↦ −x maps solutions to solutions, and per class of (φ, v) the model's dz is odd, its R-margin even and its minimiser's w "
        "odd, so σv, y = (|σ|, |dz φ|, |v|), R̂ and V_∞ are invariant (g even); at y₁ = 0, U⁺ − U⁻ = (y₂, y₃)·coupling_block(K⁺, K⁻)·"
        "(y₂, y₃)ᵀ, so its copositivity gives U⁻ ≤ U⁺ on σ = 0 (piece by piece: max_i U⁻_i ≤ max_i U⁺_i): U only drops at the crossing"
    )
    method = "sympy identities and exact signs; exhaustive split over the classes of φ and the sign of v; polynomial identity over ℚ"

    def derive(self) -> SignCrossingSubject:
        g = G()
        A, b, x = _pt.system_matrix(g), _pt.input_vector(g), _pt.state(g)
        q, omega = pos("q_v"), sp.Symbol("omega", real=True)
        rates = tuple((h, sp.expand((A * x - h * b)[0] + g.k_i * g.v)) for h in (1, -1))
        crossing = tuple((h, sp.expand(((A * x - h * b)[0] * g.v).xreplace({g.v: h * q}))) for h in (1, -1))
        odd = (A * (-x) - b * (-omega) + (A * x - b * omega)).applyfunc(sp.expand)
        mirrors = []
        for label, phi, fc in _pt.phi_points(g.f_c):
            fcg = _pt.WithFc(fc)
            dz_gap = sp.expand(_pt.exact(_attractor.dz(-phi, fc)) + _pt.exact(_attractor.dz(phi, fc)))
            for v in (sp.Integer(0), q, -q):
                point, image = [g.sigma, phi, v], [-g.sigma, -phi, -v]
                margin_gap = sp.expand(_pt.exact(_lyapunov.R_margin(fcg, image)) - _pt.exact(_lyapunov.R_margin(fcg, point)))
                w_gap = (_pt.minimiser_w(fcg, *image) + _pt.minimiser_w(fcg, *point)).applyfunc(sp.expand)
                mirrors.append(Mirror(f"{label}, v = {v}", dz_gap, margin_gap, w_gap))
        ring_, *gens = ring("P11 P12 P13 P22 P23 P33 M11 M12 M13 M22 M23 M33 y2 y3", sp.QQ)
        kp, km, (y2, y3), zero = _quadratic.u_matrix_signed(*gens[0:6]), _quadratic.u_matrix_signed(*gens[6:12]), gens[12:], ring_(0)
        coupling = _quad(kp, (zero, y2, y3), zero) - _quad(km, (zero, y2, y3), zero) - _quad(_sup_flow.coupling_block(kp, km), (y2, y3), zero)
        return SignCrossingSubject(rates, crossing, odd, tuple(mirrors), sp.expand((-g.sigma) * (-g.v) - g.sigma * g.v), coupling)

    def verify(self, subject: SignCrossingSubject) -> Outcome:
        for h, gap in subject.sigma_rates:
            if not is_zero(gap):
                return Outcome.fail(f"along f_{h}, σ̇ + k_i v = {gap} ≠ 0: σ̇ = −k_i v does not hold on the slips")
        for h, rate in subject.crossing:
            if sign_of(rate) != -1:
                return Outcome.fail(f"at v = {h}·q, v·σ̇ = {rate} is not shown < 0: σv could pass from − to +")
        if sorted(h for h, _ in subject.sigma_rates) != [-1, 1] or sorted(h for h, _ in subject.crossing) != [-1, 1]:
            return Outcome.fail("both signs of v must be checked")
        if _nonzero(subject.odd):
            return Outcome.fail(f"F(−x, −ω) + F(x, ω) = {list(subject.odd)} ≠ 0: x ↦ −x does not map solutions to solutions")
        for m in subject.mirrors:
            if not is_zero(m.dz_gap):
                return Outcome.fail(f"{m.label}: dz(−φ) + dz(φ) = {m.dz_gap} ≠ 0: y is not invariant under x ↦ −x")
            if not is_zero(m.margin_gap):
                return Outcome.fail(f"{m.label}: R-margin(−x) − R-margin(x) = {m.margin_gap} ≠ 0: R̂ is not invariant under x ↦ −x")
            if _nonzero(m.w_gap):
                return Outcome.fail(f"{m.label}: w(−x) + w(x) = {list(m.w_gap)} ≠ 0: V_∞ is not invariant under x ↦ −x")
        if len(subject.mirrors) != 15:
            return Outcome.fail(f"{len(subject.mirrors)} classes of (φ, v) mirrored, not 15")
        if not is_zero(subject.sigma_v):
            return Outcome.fail(f"(−σ)(−v) − σv = {subject.sigma_v} ≠ 0")
        if subject.coupling != 0:
            return Outcome.fail(f"at y₁ = 0, U⁺ − U⁻ − (coupling block form) = {subject.coupling} ≠ 0: the coupling block is not U⁺ − U⁻ on σ = 0")
        return Outcome(True, "", ((r"\dot\sigma \text{ on } \{v \ne 0\}", r"-k_i v,\quad v\dot\sigma = -k_i v^2 < 0"),
                                  (r"U^+ - U^- \text{ at } y_1 = 0", r"(y_2, y_3)\,(K^+ - K^-)_{\{2,3\}}\,(y_2, y_3)^\top")))


@dataclass(frozen=True)
class DragClass:
    """One class of ``(sign σ, φ)`` at ``v > 0``: the model's ``R``-margin, ``y``, ``f``, ``w`` and ``D₀y``, ``D_ℓy``."""

    label: str
    s: int
    margin: sp.Expr  # R-margin: < 0 on R̂, ≥ 0 on R
    y: sp.Matrix  # (|σ|, |dz φ|, |v|) from the model
    friction: sp.Expr  # f = f_c − φ − |dz φ|
    w: sp.Matrix  # x − f e₂ with the model's minimiser
    d0y: sp.Matrix  # drag_exit_map(s, 0)·y
    dly: sp.Matrix  # drag_exit_map(s, ℓ)·y
    distance_gap: sp.Expr  # |x|²_𝒜 − |y|²


def _drag_classes(g, ell) -> tuple[DragClass, ...]:
    """Every class of ``φ`` and sign of ``σ`` at ``v > 0``, evaluated with the model (the points of ``sup_flow.exit``'s style)."""
    y1, qv, zero = pos("y_1"), pos("q_v"), sp.Integer(0)
    out = []
    for label, phi, fc in _pt.phi_points(g.f_c):
        fcg = _pt.WithFc(fc)
        for s in (1, -1):
            point = [s * y1, phi, qv]
            (y, f), dist = _model_y(point, fc), _pt.exact(_attractor.squared_distance_x(fcg, point))
            out.append(DragClass(
                f"s = {s}, {label}", s, sp.expand(_pt.exact(_lyapunov.R_margin(fcg, point))), y, f,
                _pt.minimiser_w(fcg, *point), sp.Matrix(_apply(_sup_flow.drag_exit_map(s, (zero, zero, zero)), y, zero)),
                sp.Matrix(_apply(_sup_flow.drag_exit_map(s, ell), y, zero)), sp.expand(dist - _pt.dot(y, y))))
    return tuple(out)


@dataclass(frozen=True)
class DragRegionSubject:
    ell: tuple[sp.Symbol, ...]
    classes: tuple[DragClass, ...]
    isometry: tuple[sp.Matrix, ...]  # D₀ᵀD₀ − I, s = ±1
    pullbacks: tuple[tuple[str, Any], ...]  # yᵀ·pullback_gap(c₂I, G, D)·y − (c₂|y|² − (Dy)ᵀG(Dy)) (ring)


class DragRegion(Obligation):
    """``sup_flow_v2.drag_region``: on ``R̂ ∖ R̂′``, ``V_∞ ≤ max(g(D₀y), g(D_ℓy)) ≤ c₂|x|²_𝒜``."""

    id = "sup_flow_v2.drag_region"
    paper = "beyond the paper: eq. (VandR) for V_∞ on the part f ≤ ℓᵀy of R̂"
    statement = (
        "at v > 0 the classes of φ with R-margin < 0 (the band, φ = −f_c, φ < −f_c) are R̂, the others R; there, per class and "
        "s = sign σ, with the model's y = (|σ|, |dz φ|, |v|) and f = f_c − φ − |dz φ| > 0, V_∞ = g(w) with the minimiser's "
        "w = x − f_c e₂ = (s y₁, −(y₂ + f), y₃) and (ℓᵀy)(w − D₀y) = f(D_ℓy − D₀y) (D_ℓ = drag_exit_map(s, ℓ), D₀ = "
        "drag_exit_map(s, 0)), so on R̂ ∖ R̂′ (0 < f ≤ ℓᵀy) w = (1 − λ)D₀y + λD_ℓy, λ = f/ℓᵀy ∈ [0, 1]; g is convex and even "
        "(cited: a sup over t of the convex even quadratics |e^{At}w|²), so V_∞ ≤ max(g(D₀y), g(D_ℓy)); D₀ᵀD₀ = I; "
        "yᵀ·pullback_gap(c₂I, G, D)·y = c₂|y|² − (Dy)ᵀG(Dy) for generic symmetric G and D, so the verifier's c₂I − DᵀG(t)D ⪰ 0 "
        "(D = I, D_ℓ(±1), G = e^{At}ᵀe^{At}, t ≥ 0) gives V_∞ ≤ c₂|y|² = c₂|x|²_𝒜 (the model's |x|²_𝒜); v < 0: sup_flow_v2.sign_crossing"
    )
    method = "exhaustive split over the sign of σ and the classes of φ at v > 0; sympy identities and exact signs; polynomial identities over ℚ"

    def derive(self) -> DragRegionSubject:
        g, ell = G(), sp.symbols("ell1 ell2 ell3", nonnegative=True)
        d0s = [sp.Matrix(_sup_flow.drag_exit_map(s, (0, 0, 0))) for s in (1, -1)]
        isometry = [(d0.T * d0 - sp.eye(3)).applyfunc(sp.expand) for d0 in d0s]
        ring_, *gens = ring("c2 G11 G12 G13 G22 G23 G33 l1 l2 l3 y1 y2 y3 d11 d12 d13 d21 d22 d23 d31 d32 d33", sp.QQ)
        c2, l1, l2, l3, y1, y2, y3 = gens[0], *gens[7:13]
        zero, y, gram = ring_(0), (y1, y2, y3), _gram(*gens[1:7])
        c2i = tuple(tuple(c2 if i == j else zero for j in range(3)) for i in range(3))
        maps = [("generic D", (tuple(gens[13:16]), tuple(gens[16:19]), tuple(gens[19:22])))]
        maps += [(f"D_ℓ(s = {s})", _sup_flow.drag_exit_map(ring_(s), (l1, l2, l3))) for s in (1, -1)]
        norm2 = c2 * (y1**2 + y2**2 + y3**2)
        pullbacks = [(name, _quad(_sup_flow.pullback_gap(c2i, gram, d), y, zero) - (norm2 - _quad(gram, _apply(d, y, zero), zero)))
                     for name, d in maps]
        return DragRegionSubject(ell, _drag_classes(g, ell), tuple(isometry), tuple(pullbacks))

    def verify(self, subject: DragRegionSubject) -> Outcome:
        inside = [c for c in subject.classes if sign_of(c.margin) == -1]
        outside = [c for c in subject.classes if sign_of(c.margin) in (0, 1)]
        counts = (len(inside), len(outside), len(subject.classes), len(subject.isometry), min(len(subject.pullbacks), 3))
        if counts != (6, 4, 10, 2, 3):  # the pullback for generic D and D_ℓ(±1), the isometry for s = ±1
            return Outcome.fail(f"(classes in R̂, in R, of all at v > 0, isometries, pullbacks) = {counts}, not (6, 4, 10, 2, 3)")
        for c in inside:
            if sign_of(c.friction) != 1:
                return Outcome.fail(f"{c.label}: the friction excess f = {c.friction} is not shown > 0 on R̂ ∩ {{v > 0}}")
            expected = sp.Matrix([c.s * c.y[0], -(c.y[1] + c.friction), c.y[2]])
            if _nonzero(c.w - expected):
                return Outcome.fail(f"{c.label}: the minimiser's w = {list(c.w)} is not (s y₁, −(y₂ + f), y₃) = {list(expected)}")
            gap = _lin(subject.ell, c.y) * (c.w - c.d0y) - c.friction * (c.dly - c.d0y)
            if _nonzero(gap):
                return Outcome.fail(f"{c.label}: (ℓᵀy)(w − D₀y) − f(D_ℓy − D₀y) = {list(gap.applyfunc(sp.expand))}: w ≠ (1 − λ)D₀y + λD_ℓy")
            if not is_zero(c.distance_gap):
                return Outcome.fail(f"{c.label}: |x|²_𝒜 − |y|² = {c.distance_gap} ≠ 0")
        for m in subject.isometry:
            if _nonzero(m):
                return Outcome.fail(f"D₀ᵀD₀ − I = {list(m)} ≠ 0: D₀ is not an isometry, so c₂ ≥ ‖e^{{At}}‖² does not bound g(D₀y)")
        for name, gap in subject.pullbacks:
            if gap != 0:
                return Outcome.fail(f"{name}: yᵀ·pullback_gap(c₂I, G, D)·y − (c₂|y|² − (Dy)ᵀG(Dy)) = {gap} ≠ 0")
        split = r"(s y_1,\ -(y_2 + f),\ y_3) = (1-\lambda) D_0 y + \lambda D_\ell y,\quad \lambda = f/\ell^\top y"
        return Outcome(True, "", ((r"x - f_c e_2 \text{ on } \hat R \cap \{v>0\}", split), (r"D_0^\top D_0", r"I")))


@dataclass(frozen=True)
class ExitV2Subject:
    ell: tuple[sp.Symbol, ...]
    classes: tuple[DragClass, ...]
    form_gaps: tuple[tuple[str, Any], ...]  # signed exit_forms − (U − wᵀGw), both planes, s = ±1 (ring)
    drag_gaps: tuple[tuple[str, Any], ...]  # yᵀ·pullback_gap(K, G, D_ℓ(s))·y − (yᵀKy − (D_ℓy)ᵀG(D_ℓy)) (ring)
    at_sigma_zero: tuple[tuple[str, Any], ...]  # the exit maps of s = +1 and −1 at y₁ = 0: equal (ring)


class ExitV2(Obligation):
    """``sup_flow_v2.exit``: ``U^s ≥ V_∞`` where a solution leaves ``R̂′``, by the signed exit forms and the drag exit form."""

    id = "sup_flow_v2.exit"
    paper = "beyond the paper: Proposition 1's case (ii) at t₁, with U^± for V̂ and the exit f = ℓᵀy"
    statement = (
        "for K = u_matrix_signed (K₁₂ kept), both planes: exit_forms(K, G, ±1) = U − wᵀGw, w = exit_map(plane, ±1)·y (generic "
        "symmetric G), so the v = 0 and φ = f_c exits of sup_flow.exit (w = h·exit_map(plane, h·s)·y, h·s = sign σv) hold for each "
        "form K^{s'} with its own s' = sign σv; where a solution leaves R̂′ inside R̂ (v > 0; f = ℓᵀy there, f and y being "
        "continuous) per class of φ and s = sign σ the minimiser's w − D_ℓy = −(f − ℓᵀy)e₂ = 0, so V_∞ = g(D_ℓy), and "
        "yᵀ·pullback_gap(K, G, D_ℓ)·y = yᵀKy − (D_ℓy)ᵀG(D_ℓy): copositive for G = e^{At}ᵀe^{At}, t ∈ I_i (past T sup_flow.exit's "
        "tail_gram), it gives U ≥ g(D_ℓy) = V_∞ there (v < 0: the mirror, g even); at σ = 0 (y₁ = 0) the maps of s = ±1 give the "
        "same w, so K⁻, used there, meets the same exit point"
    )
    method = "polynomial identities over ℚ in a generic Gram matrix; exhaustive split over the sign of σ and the classes of φ at v > 0"

    def derive(self) -> ExitV2Subject:
        g, ell = G(), sp.symbols("ell1 ell2 ell3", nonnegative=True)
        ring_, *gens = ring("K11 K12 K13 K22 K23 K33 G11 G12 G13 G22 G23 G33 l1 l2 l3 y1 y2 y3 ya yb", sp.QQ)
        k, gram, (l1, l2, l3, y1, y2, y3, ya, yb) = _quadratic.u_matrix_signed(*gens[0:6]), _gram(*gens[6:12]), gens[12:]
        zero, y, lr = ring_(0), (y1, y2, y3), (l1, l2, l3)
        form_gaps, drag_gaps = [], []
        for s in (1, -1):
            for plane, form in zip(_sup_flow.EXIT_PLANES, _sup_flow.exit_forms(k, gram, ring_(s))):
                yp = (ya, yb, zero) if plane == "v = 0" else (ya, zero, yb)
                w = _apply(_sup_flow.exit_map(plane, ring_(s)), (ya, yb), zero)
                form_gaps.append((f"{plane}, s = {s}", _quad(form, (ya, yb), zero) - (_quad(k, yp, zero) - _quad(gram, w, zero))))
            d = _sup_flow.drag_exit_map(ring_(s), lr)
            gap = _quad(_sup_flow.pullback_gap(k, gram, d), y, zero) - (_quad(k, y, zero) - _quad(gram, _apply(d, y, zero), zero))
            drag_gaps.append((f"f = ℓᵀy, s = {s}", gap))
        pairs = [(plane, [_apply(_sup_flow.exit_map(plane, ring_(s)), (zero, yb), zero) for s in (1, -1)]) for plane in _sup_flow.EXIT_PLANES]
        pairs.append(("f = ℓᵀy", [_apply(_sup_flow.drag_exit_map(ring_(s), lr), (zero, y2, y3), zero) for s in (1, -1)]))
        at_zero = tuple((name, next((a - b for a, b in zip(*m) if a != b), zero)) for name, m in pairs)
        return ExitV2Subject(ell, _drag_classes(g, ell), tuple(form_gaps), tuple(drag_gaps), at_zero)

    def verify(self, subject: ExitV2Subject) -> Outcome:
        if (len(subject.form_gaps), len(subject.drag_gaps)) != (4, 2):
            return Outcome.fail(f"{len(subject.form_gaps)} signed exit forms and {len(subject.drag_gaps)} drag exit forms checked, not 4 and 2")
        for label, gap in subject.form_gaps:
            if gap != 0:
                return Outcome.fail(f"{label}: the signed exit form is not U − wᵀGw (K₁₂ kept); they differ by {gap}")
        inside = [c for c in subject.classes if sign_of(c.margin) == -1]
        if len(inside) != 6:
            return Outcome.fail(f"{len(inside)} classes of (sign σ, φ) in R̂ ∩ {{v > 0}}, not 6")
        for c in inside:
            gap = c.w - c.dly + (c.friction - _lin(subject.ell, c.y)) * sp.Matrix([0, 1, 0])
            if _nonzero(gap):
                return Outcome.fail(f"{c.label}: at f = ℓᵀy the minimiser's w is not D_ℓy: w − D_ℓy + (f − ℓᵀy)e₂ = {list(gap.applyfunc(sp.expand))}")
        for label, gap in subject.drag_gaps:
            if gap != 0:
                return Outcome.fail(f"{label}: yᵀ·pullback_gap(K, G, D_ℓ)·y is not U − |G^{{1/2}}D_ℓy|²; they differ by {gap}")
        for plane, gap in subject.at_sigma_zero:
            if gap != 0:
                return Outcome.fail(f"{plane}: at σ = 0 the exit maps of s = +1 and s = −1 give different w (difference {gap})")
        return Outcome(True, "", ((r"w \text{ at } f = \ell^\top y", r"D_\ell\, y"),
                                  (r"y^\top \mathrm{pullback\_gap}(K, G, D_\ell)\, y", r"y^\top K y - (D_\ell y)^\top G (D_\ell y)")))


_CITED_ID = re.compile(r"\b((?:sup_flow_v2|sup_flow|quadratic|lemma2|claim1)\.\w+)")
_UNCITED = ("verifier premise", "(definition")


def stability_chain_v2(step_type: type) -> tuple[dict, tuple, tuple, sp.Expr]:
    """The three starting cases for ``V_∞`` and ``U = max_i U^±_i``: facts (each naming where it is proved), steps, goals, ``κ²``."""
    c2, gamma, kappa = sp.symbols("c_2 gamma_j kappa", positive=True)
    D0, Dt, U0, Ut, U1, Uj0, W0, W1, Wt, G1, E, Ui1 = sp.symbols(
        "D_0 D_t U_0 U_t U_t1 U_j0 V_0 V_t1 V_t g_t1 E_t U_it1", nonnegative=True)
    lower, in_r, in_drag = "|x|²_𝒜 ≤ V_∞ (sup_flow.bounds)", "V_∞ ≤ c₂|x|²_𝒜 on R, x(0) ∈ R (sup_flow.bounds)", (
        "V_∞ ≤ c₂|x|²_𝒜 on R̂ ∖ R̂′, x(0) ∈ R̂ ∖ R̂′ (sup_flow_v2.drag_region; c₂I − DᵀG(t)D ⪰ 0 verifier premise)")
    decay0, decay1 = "V_∞ nonincreasing, from x(0) (sup_flow.nonincreasing)", "V_∞ nonincreasing, t ≥ t₁ (sup_flow.nonincreasing)"
    at_exit = "V_∞ = g(w) at the first exit t₁ from R̂′ (sup_flow.exit at v = 0, φ = f_c; sup_flow_v2.exit at f = ℓᵀy)"
    flow = "|e^{At}w|² ≤ U_i(t₁) for t ∈ I_i, form of sign σv (sup_flow_v2.exit; verifier premise)"
    cover = "g(w) = sup_t |e^{At}w|² ≤ U at t₁ (definition of g; step 'every t ≥ 0', the I_i cover [0, ∞): verifier premise)"
    below = "U ≥ |y|² = |x|²_𝒜 on R̂′ (K^±₁ − I copositive, verifier premise; |y|² = |x|²_𝒜: sup_flow_v2.drag_region)"
    why = "(each U^±_i: sup_flow_v2.U_rate; U⁻ ≤ U⁺ where σ crosses 0, once: sup_flow_v2.sign_crossing)"
    decay_u, decay_u1 = f"U nonincreasing on R̂′ before t₁ {why}", f"U(t₁) ≤ U(0), U nonincreasing on R̂′ up to t₁ {why}"
    at_start, above = "U(x(0)) = U_j(x(0)), j the maximising piece (definition)", "U_j ≤ γ_j|y|² (γ_jI − K^±_j copositive, verifier premise)"
    k_c2, k_gamma = "κ² ≥ c₂ (verifier premise)", "κ² ≥ γ_j (κ² ≥ max_i γ_i, verifier premise)"
    facts = {
        lower: (Dt, Wt), in_r: (W0, c2 * D0), in_drag: (W0, c2 * D0), decay0: (Wt, W0), decay1: (Wt, W1), at_exit: (W1, G1),
        flow: (E, Ui1), "U_i ≤ U = max_i U_i (definition)": (Ui1, U1), cover: (G1, U1), below: (Dt, Ut),
        decay_u: (Ut, U0), decay_u1: (U1, U0), at_start: (U0, Uj0), above: (Uj0, gamma * D0),
        k_c2: (c2, kappa**2), k_gamma: (gamma, kappa**2),
    }
    hat = ((at_start, 1), (above, 1), (k_gamma, D0))
    steps = (
        step_type("every t ≥ 0", E, U1, ((flow, 1), ("U_i ≤ U = max_i U_i (definition)", 1))),
        step_type("x(0) ∈ R̂′, t < t₁", Dt, kappa**2 * D0, ((below, 1), (decay_u, 1)) + hat),
        step_type("x(0) ∈ R̂′, t ≥ t₁", Dt, kappa**2 * D0,
                  ((lower, 1), (decay1, 1), (at_exit, 1), (cover, 1), (decay_u1, 1)) + hat),
        step_type("x(0) ∈ R", Dt, kappa**2 * D0, ((lower, 1), (decay0, 1), (in_r, 1), (k_c2, D0))),
        step_type("x(0) ∈ R̂ ∖ R̂′", Dt, kappa**2 * D0, ((lower, 1), (decay0, 1), (in_drag, 1), (k_c2, D0))),
    )
    return facts, steps, tuple((step.name, Dt, D0) for step in steps[1:]), kappa**2


@dataclass(frozen=True)
class BoundV2Subject:
    bound: Any  # quadratic.BoundSubject: facts, steps, goals, κ²
    registered: tuple[str, ...]  # the obligation ids check runs


class StabilityBoundV2(Obligation):
    """``sup_flow_v2.stability_bound``: ``κ² ≥ max(c₂, γ_i)`` by the three starting cases ``R``, ``R̂ ∖ R̂′``, ``R̂′``."""

    id = "sup_flow_v2.stability_bound"
    paper = "beyond the paper: Proposition 1 item 2, eq. (stabState) with V_∞ for V, U = max_i U^±_i for V̂ and the drag split"
    statement = (
        "|x(t)|²_𝒜 ≤ κ²|x(0)|²_𝒜 for x(0) ∈ R and x(0) ∈ R̂ ∖ R̂′ (V_∞ ≤ c₂|x|²_𝒜 there, V_∞ nonincreasing, |x|²_𝒜 ≤ V_∞) and "
        "x(0) ∈ R̂′ (|x|²_𝒜 = |y|² ≤ U ≤ γ_j|y|², U nonincreasing up to the first exit t₁ from R̂′ — at v = 0, φ = f_c or "
        "f = ℓᵀy — where U ≥ V_∞, then V_∞ nonincreasing), with κ² ≥ c₂ and κ² ≥ γ_j; every fact cites an obligation check runs "
        "or is a verifier premise or a definition, and the four lemma obligations of sup_flow_v2 are all cited"
    )
    method = "chain of inequalities, each step certified by nonnegative multipliers (the checker of quadratic.stability_bound)"
    CASES = ("x(0) ∈ R̂′, t < t₁", "x(0) ∈ R̂′, t ≥ t₁", "x(0) ∈ R", "x(0) ∈ R̂ ∖ R̂′")
    LEMMA = ("sup_flow_v2.U_rate", "sup_flow_v2.sign_crossing", "sup_flow_v2.drag_region", "sup_flow_v2.exit")

    def derive(self) -> BoundV2Subject:
        from . import registry

        facts, steps, goals, kappa_squared = stability_chain_v2(Step)
        return BoundV2Subject(BoundSubject(facts, steps, goals, kappa_squared), tuple(cls.id for cls in registry()))

    def verify(self, subject: BoundV2Subject) -> Outcome:
        bare = [name for name in subject.bound.facts if not _CITED_ID.search(name) and not any(t in name for t in _UNCITED)]
        if bare:
            return Outcome.fail(f"the facts {bare} cite no obligation and are no verifier premise or definition")
        missing = sorted({m for name in subject.bound.facts for m in _CITED_ID.findall(name)} - set(subject.registered))
        if missing:
            return Outcome.fail(f"the facts cite {missing}, which check does not run")
        used = {m for step in subject.bound.steps for name, _ in step.uses for m in _CITED_ID.findall(name)}
        unused = [c for c in self.LEMMA if c not in used]
        if unused:
            return Outcome.fail(f"the chain's steps do not cite {unused}: a step of the version-2 lemma is unused")
        goals = {name for name, _, _ in subject.bound.goals}
        absent = [c for c in self.CASES if c not in goals]
        if absent:
            return Outcome.fail(f"the starting cases {absent} have no goal D_t ≤ κ² D_0: the chain misses a case")
        return QuadraticStabilityBound().verify(subject.bound)


OBLIGATIONS = (URateV2, SignCrossing, DragRegion, ExitV2, StabilityBoundV2)
