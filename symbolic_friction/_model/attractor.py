"""The attractor 𝒜 (eqs. Aph and A) and the distance to it (eq. distFromA).

In ``z = (e_i, s, v)``: 𝒜 = {s = 0, v = 0, |e_i| ≤ f_c/k_i}.
In ``x = (sigma, phi, v)``: 𝒜 = {sigma = 0, v = 0, |phi| ≤ f_c}, and

.. math::

    |x|_{\\mathcal A}^2 = \\sigma^2 + v^2 + \\mathrm{dz}_{f_c}(\\phi)^2,
    \\qquad \\mathrm{dz}_c(y) = y - c\\,\\mathrm{sat}(y/c).

Each object is written once (see :mod:`._kinds`): the same body evaluates
exact scalars (Fractions) exactly, float arrays vectorised, and sympy
expressions symbolically, which is what the proof obligations ``distance``,
``cor1.distances`` and ``model.distance_runtime`` check.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .kinds import FLOAT, kind_of
from .parameters import Parameters

__all__ = [
    "sat",
    "dz",
    "state_components",
    "attractor_bound_x",
    "attractor_bound_z",
    "distance_x",
    "squared_distance_x",
    "distance_z",
    "squared_distance_z",
    "in_attractor_x",
]


def sat(y: Any, c: Any) -> Any:
    """``c·sat(y/c)``, the projection of ``y`` on ``[-c, c]`` (Notation, §I), ``c > 0``.

    >>> from fractions import Fraction
    >>> sat(Fraction(5, 2), 1), float(sat(-3.0, 1.0))
    (1, -1.0)
    """
    kind = kind_of(y, c)
    c = kind.scalar(c)
    return kind.clip(y, -c, c)


def dz(y: Any, c: Any) -> Any:
    """Symmetric dead zone ``dz_c(y) = y - c sat(y/c)`` for ``c > 0`` (eq. distFromA).

    >>> from fractions import Fraction
    >>> dz(Fraction(5, 2), 1), float(dz(-3.0, 1.0)), float(dz(0.5, 1.0))
    (Fraction(3, 2), -2.0, 0.0)
    """
    kind = kind_of(y, c)
    return kind.finish(y - sat(y, c))


def state_components(x: Any) -> tuple[Any, Any, Any]:
    """The three components of a state, or of a batch of states of shape ``(..., 3)``.

    A length-3 sequence of exact or sympy numbers is returned as it is (kept
    exact); anything else is read as a float array.
    """
    if isinstance(x, (list, tuple)) and len(x) == 3 and not any(isinstance(c, (float, np.ndarray, np.floating)) for c in x):
        if not all(isinstance(c, int) for c in x):
            return x[0], x[1], x[2]
    arr = np.asarray(x)
    if arr.dtype == object and arr.ndim == 1:
        return arr[0], arr[1], arr[2]
    arr = arr.astype(float)
    return arr[..., 0], arr[..., 1], arr[..., 2]


def attractor_bound_x(params: Parameters) -> Any:
    """Bound on ``|phi|`` inside 𝒜 in ``x`` coordinates: ``f_c`` (eq. A)."""
    return params.f_c


def attractor_bound_z(params: Parameters) -> Any:
    """Bound on ``|e_i|`` inside 𝒜 in ``z`` coordinates: ``f_c / k_i`` (eq. Aph)."""
    return params.f_c / params.k_i


def squared_distance_x(params: Parameters, x: Any) -> Any:
    """``|x|²_𝒜 = σ² + v² + dz_{f_c}(φ)²`` of eq. (distFromA).

    Exact for exact components, vectorised for arrays, symbolic for sympy.
    """
    sigma, phi, v = state_components(x)
    return sigma**2 + v**2 + dz(phi, attractor_bound_x(params)) ** 2


def distance_x(params: Parameters, x: Any) -> Any:
    """``|x|_𝒜`` for ``x = (sigma, phi, v)`` of shape ``(..., 3)`` (floats)."""
    arr = np.asarray(x)
    if arr.dtype == object:
        raise TypeError("distance_x is irrational in general; use squared_distance_x for exact input")
    return np.sqrt(squared_distance_x(params, arr.astype(float)))


def squared_distance_z(params: Parameters, z: Any) -> Any:
    """``|z|²_𝒜 = s² + v² + dz_{f_c/k_i}(e_i)²`` (Corollary 1's proof)."""
    e_i, s, v = state_components(z)
    return s**2 + v**2 + dz(e_i, attractor_bound_z(params)) ** 2


def distance_z(params: Parameters, z: Any) -> Any:
    """``|z|_𝒜`` (Corollary 1's proof), for float states of shape ``(..., 3)``."""
    return np.sqrt(squared_distance_z(params, np.asarray(z, dtype=float)))


def in_attractor_x(params: Parameters, x: Any) -> Any:
    """Whether ``x`` lies in 𝒜 (eq. A): ``σ = 0``, ``v = 0`` and ``dz(φ) = 0``.

    Exact membership for exact input; for float arrays a boolean array.
    """
    sigma, phi, v = state_components(x)
    d = dz(phi, attractor_bound_x(params))
    if kind_of(sigma, phi, v) is FLOAT:
        return (sigma == 0) & (v == 0) & (d == 0)
    return sigma == 0 and v == 0 and d == 0
