"""The points where the sup-of-flow obligations (:mod:`.sup_flow`) evaluate the package's model, and their records.

The model pieces are read through their modules at call time (``A`` from
:func:`coordinates.system_matrix_entries`, the minimiser
:func:`lyapunov.friction_selection`, ``sat`` and ``dz``), so a test that
breaks one of them is what the obligations see.  The classes of ``φ`` are
written with fresh positive symbols that cover them exactly; the band
``|φ| < f_c`` polynomially (``f_c = (u + w)/2``, ``φ = (w − u)/2``), so the
model's ``Piecewise`` branches are decided without common denominators.
The exit forms are those where a solution leaves ``R̂ ∩ {v > 0}``
(Proposition 1's case (ii) at ``t₁``), in ``y = (|σ|, |dz φ|, |v|)``.
Proposition 1's two cases for ``V_∞`` are a chain of inequalities
(:func:`stability_chain`) that ``sup_flow.stability_bound`` decides.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import coordinates as _coordinates
from .._model import lyapunov as _lyapunov
from ._decide import Undecided, pos, resolve_piecewise

__all__ = [
    "E", "system_matrix", "input_vector", "state", "exact", "minimiser_w", "rest_exit_form", "edge_exit_form", "dot",
    "phi_points", "WithFc", "sides", "Between", "RowStep", "LowerPiece", "UpperPiece", "ExitPoint", "matmul", "norm2",
    "stability_chain",
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


def rest_exit_form(s: Any, y1: Any, y2: Any) -> sp.Matrix:
    """``w = (s·y₁, −y₂, 0)``: the exit of ``R̂ ∩ {v > 0}`` at ``v = 0`` in ``y = (|σ|, |dz φ|, |v|)``, ``s = sign σ``."""
    return sp.Matrix([s * y1, -y2, 0])


def edge_exit_form(s: Any, y1: Any, y3: Any) -> sp.Matrix:
    """``w = (s·y₁, 0, y₃)``: the exit of ``R̂ ∩ {v > 0}`` at ``φ = f_c``."""
    return sp.Matrix([s * y1, 0, y3])


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
