"""The points where the sup-of-flow obligations (:mod:`.sup_flow`) evaluate the package's model, and their records.

The model pieces are read through their modules at call time (``A`` from
:func:`coordinates.system_matrix_entries`, the minimiser
:func:`lyapunov.friction_selection`, ``sat`` and ``dz``), so a test that
breaks one of them is what the obligations see.  The classes of ``φ`` are
written with fresh positive symbols that cover them exactly; the band
``|φ| < f_c`` polynomially (``f_c = (u + w)/2``, ``φ = (w − u)/2``), so the
model's ``Piecewise`` branches are decided without common denominators.
Where a solution leaves ``R̂`` (Proposition 1's case (ii) at ``t₁``) the
minimiser's ``w`` is compared with the template model's ``exit_map`` in
``y = (|σ|, |dz φ|, |v|)``, and the verifier's ``exit_forms`` and
``tail_gram`` with what they stand for, for a generic Gram matrix and a
generic flow ``M`` (polynomial rings over ℚ: exact, and cheap to multiply out).
Proposition 1's two cases for ``V_∞`` are a chain of inequalities
(:func:`stability_chain`) that ``sup_flow.stability_bound`` decides.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import attractor as _attractor
from .._model import coordinates as _coordinates
from .._model import lyapunov as _lyapunov
from .._model import quadratic as _quadratic
from .._model import sup_flow as _sup_flow
from ._decide import Undecided, pos, resolve_piecewise

__all__ = [
    "E", "system_matrix", "input_vector", "state", "exact", "minimiser_w", "dot",
    "phi_points", "WithFc", "sides", "Between", "RowStep", "LowerPiece", "UpperPiece", "ExitPoint", "matmul", "norm2",
    "stability_chain", "exit_points", "exit_form_gaps", "tail_gram_gap",
]

E = (sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1]))
"""``e₁, e₂, e₃``."""


def system_matrix(g) -> sp.Matrix:
    """``A`` of eq. (xDot) from the one model (:func:`coordinates.system_matrix_entries`)."""
    return sp.Matrix([[sp.sympify(e) for e in row] for row in _coordinates.system_matrix_entries(g.k_p, g.k_i, g.k_v)])


def input_vector(g) -> sp.Matrix:
    """``b`` of eq. (xDot) from the one model."""
    return sp.Matrix([sp.sympify(e) for e in _coordinates.input_vector_entries(g.f_c)])


def state(g) -> sp.Matrix:
    """``x = (σ, φ, v)``."""
    return sp.Matrix([g.sigma, g.phi, g.v])


def exact(expr: Any) -> sp.Expr:
    """A model value at a parametrised point, its ``Piecewise`` branches decided (left as is if undecided: verify then fails)."""
    expr = sp.sympify(expr)
    try:
        return resolve_piecewise(expr)
    except Undecided:
        return expr


def minimiser_w(g, sigma: Any, phi: Any, v: Any) -> sp.Matrix:
    """``x − f e₂`` with the model's minimiser ``f`` of eq. (lyapLikeV) (:func:`lyapunov.friction_selection`)."""
    f = exact(_lyapunov.friction_selection(g, sp.sympify(phi), sp.sympify(v)))
    return sp.Matrix([sigma, phi - f, v])


def dot(u: sp.Matrix, w: sp.Matrix) -> sp.Expr:
    """``uᵀw``, expanded."""
    return sp.expand((u.T * w)[0])


def phi_points(f_c: sp.Symbol) -> list[tuple[str, sp.Expr, sp.Expr]]:
    """The five classes of ``φ`` against ``±f_c`` as ``(label, φ, f_c)`` with fresh positive symbols.

    As :func:`._decide.phi_classes`, but the band ``|φ| < f_c`` is the
    polynomial ``f_c = (u + w)/2``, ``φ = (w − u)/2`` (so the model's
    ``Piecewise`` branches decide without common denominators).
    """
    p, u, w = pos("p_phi"), pos("u_phi"), pos("w_phi")
    return [
        ("φ > f_c", f_c + p, f_c),
        ("φ = f_c", f_c, f_c),
        ("|φ| < f_c", (w - u) / 2, (u + w) / 2),
        ("φ = -f_c", -f_c, f_c),
        ("φ < -f_c", -f_c - p, f_c),
    ]


@dataclass(frozen=True)
class WithFc:
    """The gains object the model's :func:`lyapunov.friction_selection` and ``R_margin`` read, with ``f_c`` given."""

    f_c: Any


def sides(h: int) -> tuple[str, ...]:
    """The classes of ``φ`` with ``h·φ ≥ f_c`` (``v`` of sign ``h`` is then in ``R``)."""
    return ("φ > f_c", "φ = f_c") if h == 1 else ("φ < -f_c", "φ = -f_c")


@dataclass(frozen=True)
class Between:
    """At ``v = 0`` in one class of ``φ``: the model's minimiser and ``dz``, and the betweenness at ``f = ±f_c``."""

    label: str
    rest_w: sp.Matrix  # x − f e₂ with the model's minimiser at v = 0
    dz: sp.Expr  # the model's dz(φ)
    sat_room: tuple[sp.Expr, sp.Expr]  # f_c − sat(φ), f_c + sat(φ)
    between: tuple[sp.Expr, sp.Expr]  # dz·(φ − f − dz) at f = f_c, −f_c (affine in f)


@dataclass(frozen=True)
class RowStep:
    """One row of Claim 1's table for ``V_∞``: the argument of ``g`` at the start and what it must equal."""

    label: str
    k: int
    start_w: sp.Matrix  # x̄ − f e₂ with the model's minimiser
    slip_w: sp.Matrix | None  # x̄ − k f_c e₂ (k = ±1)
    stick_dz: sp.Expr | None  # dz(φ̄) (k = 0)


@dataclass(frozen=True)
class LowerPiece:
    """``|x − f e₂|² ≥ |x|²_𝒜`` in one class of ``φ``: an identity and the sign of the cross term."""

    label: str
    residual: sp.Expr  # |x − f e₂|² − |x|²_𝒜 − (φ−f−dz)² − 2dz(φ−f−dz), identically 0 in f
    cross: tuple[sp.Expr, sp.Expr]  # dz(φ−f−dz) at f = ±f_c (affine in f)


@dataclass(frozen=True)
class UpperPiece:
    """One class of ``(v, φ)`` in ``R``: its ``R``-margin and ``|w|² − |x|²_𝒜`` for the minimiser's ``w``."""

    label: str
    margin: sp.Expr  # the model's v(φ − sign(v) f_c): R is where it is ≥ 0
    gap: sp.Expr  # |w|² − |x|²_𝒜 for the minimiser's w


@dataclass(frozen=True)
class ExitPoint:
    """One place where a solution leaves ``R̂``: its ``R``-margin and the minimiser's ``w`` against the exit form."""

    label: str
    margin: sp.Expr  # the model's R-margin there: 0 (the boundary of R̂)
    gap: sp.Matrix  # the minimiser's w − h·(exit form at σ-sign h·s) in the model's y


def matmul(a, b) -> list:
    """``ab`` for 3×3 nested lists (of polynomial-ring elements)."""
    return [[sum((a[i][k] * b[k][j] for k in range(3)), a[0][0] * 0) for j in range(3)] for i in range(3)]


def norm2(u) -> Any:
    """``|u|²`` for a list of polynomial-ring elements."""
    return sum((e * e for e in u), u[0] * 0)


def stability_chain(step_type: type) -> tuple[dict, tuple, tuple, sp.Expr]:
    """Proposition 1's two cases for ``V_∞`` and ``U = max_i U_i``: the facts (each naming where it is proved), the steps, the goals, ``κ²``.

    ``step_type`` is the step record of ``quadratic.stability_bound``'s chain checker.
    """
    c2, gamma, kappa = sp.symbols("c_2 gamma_j kappa", positive=True)
    D0, Dt, U0, Ut, U1, Uj0, W0, W1, Wt, G1, E, Ui1 = sp.symbols(
        "D_0 D_t U_0 U_t U_t1 U_j0 V_0 V_t1 V_t g_t1 E_t U_it1", nonnegative=True)
    facts = {
        "|x|²_𝒜 ≤ V_∞ (sup_flow.bounds)": (Dt, Wt),
        "V_∞ ≤ c₂|x|²_𝒜 on R, x(0) ∈ R (sup_flow.bounds)": (W0, c2 * D0),
        "V_∞ nonincreasing, t ≥ t₁ (sup_flow.nonincreasing)": (Wt, W1),
        "V_∞ nonincreasing, x(0) ∈ R (sup_flow.nonincreasing)": (Wt, W0),
        "V_∞ = g(w) at t₁ (sup_flow.exit)": (W1, G1),
        "|e^{At}w|² ≤ U_i(t₁) for t ∈ I_i (sup_flow.exit; verifier premise)": (E, Ui1),
        "U_i ≤ U = max_i U_i": (Ui1, U1),
        "g(w) = sup_t |e^{At}w|² ≤ U at t₁ (step 'every t ≥ 0', the I_i cover [0, ∞))": (G1, U1),
        "U ≥ |y|² = |x|²_𝒜 on R̂ (K₀ − I copositive)": (Dt, Ut),
        "U nonincreasing on R̂ (each U_i: quadratic.U_rate)": (Ut, U0),
        "U nonincreasing on R̂ up to t₁ (quadratic.U_rate)": (U1, U0),
        "U(x(0)) = U_j(x(0)), j the maximising piece": (U0, Uj0),
        "U_j ≤ γ_j|y|² (γ_jI − K_j copositive)": (Uj0, gamma * D0),
        "κ² ≥ c₂": (c2, kappa**2),
        "κ² ≥ γ_j (κ² ≥ max_i γ_i)": (gamma, kappa**2),
    }
    uses_hat = (("U nonincreasing on R̂ (each U_i: quadratic.U_rate)", 1), ("U(x(0)) = U_j(x(0)), j the maximising piece", 1),
                ("U_j ≤ γ_j|y|² (γ_jI − K_j copositive)", 1), ("κ² ≥ γ_j (κ² ≥ max_i γ_i)", D0))
    steps = (
        step_type("every t ≥ 0", E, U1, (("|e^{At}w|² ≤ U_i(t₁) for t ∈ I_i (sup_flow.exit; verifier premise)", 1), ("U_i ≤ U = max_i U_i", 1))),
        step_type("case (i) / t < t₁", Dt, kappa**2 * D0, (("U ≥ |y|² = |x|²_𝒜 on R̂ (K₀ − I copositive)", 1),) + uses_hat),
        step_type("case (ii), t ≥ t₁", Dt, kappa**2 * D0, (
            ("|x|²_𝒜 ≤ V_∞ (sup_flow.bounds)", 1), ("V_∞ nonincreasing, t ≥ t₁ (sup_flow.nonincreasing)", 1),
            ("V_∞ = g(w) at t₁ (sup_flow.exit)", 1), ("g(w) = sup_t |e^{At}w|² ≤ U at t₁ (step 'every t ≥ 0', the I_i cover [0, ∞))", 1),
            ("U nonincreasing on R̂ up to t₁ (quadratic.U_rate)", 1)) + uses_hat[1:]),
        step_type("case (ii), t₁ = 0", Dt, kappa**2 * D0, (
            ("|x|²_𝒜 ≤ V_∞ (sup_flow.bounds)", 1), ("V_∞ nonincreasing, x(0) ∈ R (sup_flow.nonincreasing)", 1),
            ("V_∞ ≤ c₂|x|²_𝒜 on R, x(0) ∈ R (sup_flow.bounds)", 1), ("κ² ≥ c₂", D0))),
    )
    goals = tuple((step.name, Dt, D0) for step in steps[1:])
    return facts, steps, goals, kappa**2


def exit_points(g: Any) -> tuple[ExitPoint, ...]:
    """Where a solution leaves ``R̂ ∩ {hv > 0}``, ``h = ±1``, for both signs ``s`` of ``σ``: the minimiser's ``w`` against ``h·D·y``.

    ``D = exit_map(plane, h·s)`` of the template model: ``g`` is even and
    ``F`` odd, so the half ``v < 0`` is the half ``v > 0`` at ``−x``.  At
    ``v = 0`` every class of ``φ`` with ``hφ ≤ f_c``; on the edge ``φ = h f_c``,
    ``hv > 0``.  The model's ``R``-margin must be ``0`` at each.
    """
    y1, n = pos("y_1"), pos("y_3")
    rest = {}  # per class of φ at v = 0: the minimiser's w, |dz φ| and the R-margin (σ enters only w)
    for label, phi, fc in phi_points(g.f_c):
        fcg = WithFc(fc)
        rest[label] = (minimiser_w(fcg, g.sigma, phi, sp.Integer(0)), exact(sp.Abs(exact(_attractor.dz(phi, fc)))),
                       sp.expand(exact(_lyapunov.R_margin(fcg, [g.sigma, phi, 0]))))
    out = []
    for h in (1, -1):
        edge = [g.sigma, h * g.f_c, h * n]
        w_edge, margin_edge = minimiser_w(g, *edge), sp.expand(exact(_lyapunov.R_margin(g, edge)))
        dz_edge = exact(sp.Abs(exact(_attractor.dz(edge[1], g.f_c))))
        for s in (1, -1):
            at = {g.sigma: s * y1}
            for label, (w, abs_dz, margin) in rest.items():
                if label in sides(h) and label not in ("φ = f_c", "φ = -f_c"):
                    continue  # h·φ > f_c at v = 0: not on the closure of R̂ ∩ {hv > 0}
                d = sp.Matrix(_sup_flow.exit_map("v = 0", h * s))
                gap = (w.xreplace(at) - h * d * sp.Matrix([exact(sp.Abs(s * y1)), abs_dz])).applyfunc(sp.expand)
                out.append(ExitPoint(f"h = {h}, s = {s}, v = 0, {label}", margin.xreplace(at), gap))
            d = sp.Matrix(_sup_flow.exit_map("φ = f_c", h * s))
            gap = (w_edge.xreplace(at) - h * d * sp.Matrix([exact(sp.Abs(s * y1)), exact(sp.Abs(edge[2]))])).applyfunc(sp.expand)
            out.append(ExitPoint(f"h = {h}, s = {s}, φ = h f_c, hv > 0", margin_edge.xreplace(at), gap.col_join(sp.Matrix([dz_edge]))))
    return tuple(out)


def exit_form_gaps() -> tuple[tuple[str, Any], ...]:
    """``(y_a, y_b)·F·(y_a, y_b)ᵀ − (U(y) − wᵀGw)`` for the verifier's ``exit_forms`` ``F``, both planes, ``s = ±1``.

    ``U = yᵀKy`` with the quadratic template's ``K``, ``G`` a generic symmetric
    matrix (the verifier's ``e^{At}ᵀe^{At}``), ``w = D·(y_a, y_b)`` with the
    model's ``exit_map`` and ``y`` the exit point's ``(|σ|, |dz φ|, |v|)``.
    """
    from sympy.polys.rings import ring

    ring_, *gens = ring("K11 K13 K22 K23 K33 G11 G12 G13 G22 G23 G33 ya yb", sp.QQ)
    k = _quadratic.u_matrix_entries(*gens[:5])
    g11, g12, g13, g22, g23, g33, ya, yb = gens[5:]
    gram = ((g11, g12, g13), (g12, g22, g23), (g13, g23, g33))
    out = []
    for s in (1, -1):
        forms = _sup_flow.exit_forms(k, gram, ring_(s))
        for plane, form in zip(_sup_flow.EXIT_PLANES, forms):
            y = (ya, yb, ring_(0)) if plane == "v = 0" else (ya, ring_(0), yb)
            d = _sup_flow.exit_map(plane, ring_(s))
            w = [d[i][0] * ya + d[i][1] * yb for i in range(3)]
            quad = lambda m, u: sum((u[i] * m[i][j] * u[j] for i in range(len(u)) for j in range(len(u))), ring_(0))  # noqa: E731
            out.append((f"{plane}, s = {s}", quad(form, (ya, yb)) - (quad(k, y) - quad(gram, w))))
    return tuple(out)


def tail_gram_gap() -> Any:
    """``tail_gram(M, pQ, p) − MᵀQM`` for a generic flow ``M``, a generic symmetric ``Q`` and a symbol ``p`` (0 when right).

    ``tail_gram(M, P, p)`` must be ``(1/p)MᵀPM`` for every symmetric ``P``;
    as ``Q ↦ pQ`` is onto the symmetric matrices for ``p ≠ 0``, the identity
    above (in a polynomial ring over ℚ, no fractions) is the same claim.  A
    quotient that is not exact is a failure, returned as its message.
    """
    from sympy.polys.polyerrors import ExactQuotientFailed
    from sympy.polys.rings import ring

    ring_, *gens = ring("m11 m12 m13 m21 m22 m23 m31 m32 m33 Q11 Q12 Q13 Q22 Q23 Q33 p", sp.QQ)
    m = (tuple(gens[0:3]), tuple(gens[3:6]), tuple(gens[6:9]))
    q11, q12, q13, q22, q23, q33, p = gens[9:]
    q = ((q11, q12, q13), (q12, q22, q23), (q13, q23, q33))
    try:
        tail = _sup_flow.tail_gram(m, tuple(tuple(p * e for e in row) for row in q), p)
    except ExactQuotientFailed as exc:
        return f"not (1/p)·MᵀPM: {exc}"
    gaps = [tail[i][j] - sum((m[k][i] * q[k][l] * m[l][j] for k in range(3) for l in range(3)), ring_(0)) for i in range(3) for j in range(3)]
    return next((gap for gap in gaps if gap != 0), ring_(0))
