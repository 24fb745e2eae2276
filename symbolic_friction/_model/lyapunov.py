"""The Lyapunov-like function ``V`` (eq. lyapLike), its smooth pieces ``V_k``
(eq. subcasesAffine:Vs), the auxiliary ``V̂`` (eq. Vhat) and the regions
``R``, ``R̂`` of Lemma 3.

.. math::

    V(x) = \\min_{f \\in f_c\\,\\mathrm{SGN}(v)}
        (\\sigma, \\phi - f, v)^\\top P\\, (\\sigma, \\phi - f, v),\\qquad
    P = \\begin{bmatrix} k_v/k_i & 0 & -1\\\\ 0 & 1 & 0\\\\ -1 & 0 & k_p\\end{bmatrix}.

The minimum is in closed form: ``f = f_c sign(v)`` when ``v != 0`` and
``f = sat_{f_c}(phi)`` (the projection of ``phi`` on ``[-f_c, f_c]``) when
``v = 0``, because only the middle entry of the quadratic form depends on
``f`` and ``P_22 = 1`` is decoupled from the rest.

``V̂(x) = ½k₁σ² + ½k₂ dz(φ)² + k₃|σ||v| + ½k₄v²`` and
``R = {v(φ - sign(v) f_c) ≥ 0}``, ``R̂ = ℝ³ \\ R``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .attractor import dz, sat, state_components
from .coordinates import input_vector_entries, system_matrix_entries
from .kinds import kind_of
from .parameters import Parameters

__all__ = [
    "lyapunov_matrix_entries",
    "lyapunov_matrix",
    "quadratic_form",
    "V",
    "V_k",
    "V_hat",
    "vhat_matrix_entries",
    "in_R",
    "R_margin",
    "friction_selection",
    "V_hat_rate",
]


def lyapunov_matrix_entries(k_p: Any, k_i: Any, k_v: Any) -> tuple[tuple[Any, ...], ...]:
    """``P`` of eq. (lyapLikeP)."""
    return ((k_v / k_i, 0, -1), (0, 1, 0), (-1, 0, k_p))


def lyapunov_matrix(params: Parameters) -> np.ndarray:
    """``P`` as a float array of shape (3, 3)."""
    k_p, k_i, k_v, _ = params.as_floats()
    return np.array(lyapunov_matrix_entries(k_p, k_i, k_v), dtype=float)


def vhat_matrix_entries(k1: Any, k2: Any, k3: Any, k4: Any) -> tuple[tuple[Any, ...], ...]:
    """The matrix ``K`` with ``V̂ = ½ wᵀ K w``, ``w = (|σ|, |dz(φ)|, |v|)`` (Lemma 3's proof)."""
    return ((k1, 0, k3), (0, k2, 0), (k3, 0, k4))


def quadratic_form(params: Parameters, sigma: Any, y: Any, v: Any) -> Any:
    """``(σ, y, v) P (σ, y, v)ᵀ = (k_v/k_i)σ² - 2σv + k_p v² + y²`` with ``P`` of eq. (lyapLikeP).

    Works for exact scalars, float arrays (vectorised) and sympy expressions."""
    kind = kind_of(sigma, y, v, params.k_p, params.k_i, params.k_v)
    P = lyapunov_matrix_entries(*(kind.scalar(q) for q in (params.k_p, params.k_i, params.k_v)))
    w = (sigma, y, v)
    return sum(P[i][j] * w[i] * w[j] for i in range(3) for j in range(3) if P[i][j] != 0)


def friction_selection(params: Parameters, phi: Any, v: Any) -> Any:
    """The minimiser ``f`` of eq. (lyapLikeV) over ``f ∈ f_c SGN(v)``.

    ``f = f_c sign(v)`` for ``v ≠ 0`` and ``f = f_c sat(φ/f_c)`` (the
    projection of ``φ`` on ``[-f_c, f_c]``) for ``v = 0``: only the middle
    entry of the quadratic form depends on ``f``, and ``P₂₂ = 1`` is decoupled
    from the rest (obligation ``model.V_runtime`` checks this against the
    minimum itself).
    """
    kind = kind_of(phi, v, params.f_c)
    f_c = kind.scalar(params.f_c)
    return kind.where(v > 0, f_c, kind.where(v < 0, -f_c, sat(phi, f_c)))


def V(params: Parameters, x: Any) -> Any:
    """Lyapunov-like function ``V(x)`` of eq. (lyapLike), in closed form.

    Parameters
    ----------
    params : Parameters
    x : array_like, shape (..., 3)
        States ``(sigma, phi, v)``; a length-3 sequence of Fractions is
        evaluated exactly, of sympy expressions symbolically.

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> p = Parameters(k_p=3, k_i=4, k_v="6.4")
    >>> V(p, [F(0), F(0), F(0)]), bool(V(p, [0.0, 0.0, 1e-12]) > 0.99)
    (Fraction(0, 1), True)
    """
    sigma, phi, v = state_components(x)
    f = friction_selection(params, phi, v)
    return kind_of(sigma, phi, v).finish(quadratic_form(params, sigma, phi - f, v))


def V_k(params: Parameters, x: Any, k: int) -> Any:
    """Smooth piece ``V_k`` of eq. (subcasesAffine:Vs), ``k ∈ {-1, 0, 1}``.

    ``V_1 = |(σ, φ - f_c, v)|²_P``, ``V_0 = |(σ, 0, 0)|²_P``,
    ``V_{-1} = |(σ, φ + f_c, v)|²_P``.
    """
    sigma, phi, v = state_components(x)
    f_c = kind_of(sigma, phi, v, params.f_c).scalar(params.f_c)
    if k == 1:
        return quadratic_form(params, sigma, phi - f_c, v)
    if k == -1:
        return quadratic_form(params, sigma, phi + f_c, v)
    if k == 0:
        return quadratic_form(params, sigma, phi * 0, v * 0)
    raise ValueError(f"k must be -1, 0 or 1; got {k!r}")


def V_hat(params: Parameters, x: Any, k: tuple[Any, Any, Any, Any]) -> Any:
    """Auxiliary function ``V̂`` of eq. (Vhat) with constants ``k = (k1, k2, k3, k4)``:

    ``V̂(x) = ½k₁σ² + ½k₂ dz(φ)² + k₃|σ||v| + ½k₄v²``.
    """
    sigma, phi, v = state_components(x)
    kind = kind_of(sigma, phi, v, params.f_c, *k)
    k1, k2, k3, k4 = (kind.scalar(q) for q in k)
    d = dz(phi, kind.scalar(params.f_c))
    value = k1 * sigma**2 / 2 + k2 * d**2 / 2 + k3 * kind.abs(sigma) * kind.abs(v) + k4 * v**2 / 2
    return kind.finish(value)


def R_margin(params: Parameters, x: Any) -> Any:
    """``v(φ - sign(v) f_c)``: ``R`` of Lemma 3 is where this is ``≥ 0``."""
    sigma, phi, v = state_components(x)
    kind = kind_of(sigma, phi, v, params.f_c)
    return v * (phi - kind.sign(v) * kind.scalar(params.f_c))


def in_R(params: Parameters, x: Any) -> Any:
    """Membership in ``R = {v (φ - sign(v) f_c) ≥ 0}`` (Lemma 3); ``R̂`` is the complement.

    A bool for exact input, a boolean array for floats, a relational for sympy.
    """
    return R_margin(params, x) >= 0


def V_hat_rate(params: Parameters, x: Any, k: tuple[Any, Any, Any, Any]) -> Any:
    """``V̂°(x)`` of eq. (hatVdot) for ``x ∈ R̂``, where ``v ≠ 0`` and ``F(x) = Ax - b sign(v)`` is single valued.

    ``V̂° = max_{ζ ∈ SGN(σ)} (k₁σ + k₃ζ|v|)σ' + k₂dz(φ)φ' + (k₃|σ| sign(v) + k₄v)v'``
    with ``(σ', φ', v') = F(x)`` (eq. almostEverywhereDerivatives): at ``σ = 0``
    the maximum over ``ζ ∈ [-1, 1]`` is ``|σ'|``.  Outside ``R̂`` the value is
    not ``V̂°`` (there ``F`` may be set valued); callers mask it with :func:`in_R`.
    """
    sigma, phi, v = state_components(x)
    kind = kind_of(sigma, phi, v, params.f_c, *k)
    gains = (kind.scalar(q) for q in (params.k_p, params.k_i, params.k_v))
    A = system_matrix_entries(*gains)
    b = input_vector_entries(kind.scalar(params.f_c))
    k1, k2, k3, k4 = (kind.scalar(q) for q in k)
    sv = kind.sign(v)
    f = [A[i][0] * sigma + A[i][1] * phi + A[i][2] * v - b[i] * sv for i in range(3)]
    d = dz(phi, kind.scalar(params.f_c))
    # the max over ζ ∈ SGN(σ) of ζσ': sign(σ)σ' for σ ≠ 0, |σ'| at σ = 0
    abs_rate = kind.where(kind.abs(sigma) > 0, kind.sign(sigma) * f[0], kind.abs(f[0]))
    rate = k1 * sigma * f[0] + k2 * d * f[1] + k3 * (abs_rate * kind.abs(v) + kind.abs(sigma) * sv * f[2]) + k4 * v * f[2]
    return kind.finish(rate)
