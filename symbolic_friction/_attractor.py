"""The attractor 𝒜 (eqs. Aph and A) and the distance to it (eq. distFromA).

In ``z = (e_i, s, v)``: 𝒜 = {s = 0, v = 0, |e_i| ≤ f_c/k_i}.
In ``x = (sigma, phi, v)``: 𝒜 = {sigma = 0, v = 0, |phi| ≤ f_c}, and

.. math::

    |x|_{\\mathcal A}^2 = \\sigma^2 + v^2 + \\mathrm{dz}_{f_c}(\\phi)^2,
    \\qquad \\mathrm{dz}_c(y) = y - c\\,\\mathrm{sat}(y/c).

Functions accept floats or numpy arrays (vectorised) and exact scalars
(Fractions), returning the same kind.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._parameters import Parameters

__all__ = ["dz", "attractor_bound_x", "attractor_bound_z", "distance_x", "squared_distance_x", "distance_z", "in_attractor_x"]


def dz(y: Any, c: Any) -> Any:
    """Symmetric dead zone ``dz_c(y) = y - c sat(y/c)`` for ``c > 0``.

    >>> from fractions import Fraction
    >>> dz(Fraction(5, 2), 1), dz(-3.0, 1.0), dz(0.5, 1.0)
    (Fraction(3, 2), -2.0, 0.0)
    """
    if isinstance(y, np.ndarray) or isinstance(c, np.ndarray):
        y = np.asarray(y, dtype=float)
        return y - np.clip(y, -c, c)
    if y > c:
        return y - c
    if y < -c:
        return y + c
    return y - y  # zero of the same type as y


def attractor_bound_x(params: Parameters) -> Any:
    """Bound on ``|phi|`` inside 𝒜 in ``x`` coordinates: ``f_c``."""
    return params.f_c


def attractor_bound_z(params: Parameters) -> Any:
    """Bound on ``|e_i|`` inside 𝒜 in ``z`` coordinates: ``f_c / k_i``."""
    return params.f_c / params.k_i


def distance_x(params: Parameters, x: Any) -> Any:
    """``|x|_𝒜`` for ``x = (sigma, phi, v)`` of shape ``(..., 3)``."""
    arr = np.asarray(x)
    if arr.dtype == object:
        raise TypeError("distance_x is irrational in general; use squared_distance_x for exact input")
    arr = arr.astype(float)
    return np.sqrt(squared_distance_x(params, arr))


def squared_distance_x(params: Parameters, x: Any) -> Any:
    """``|x|_𝒜^2`` (exact for exact scalars, vectorised for arrays)."""
    arr = np.asarray(x)
    if arr.dtype == object and arr.ndim == 1:
        sigma, phi, v = arr
        return sigma**2 + v**2 + dz(phi, params.f_c) ** 2
    arr = arr.astype(float)
    d = dz(arr[..., 1], float(params.f_c))
    return arr[..., 0] ** 2 + arr[..., 2] ** 2 + d**2


def distance_z(params: Parameters, z: Any) -> Any:
    """``|z|_𝒜 = sqrt(s^2 + v^2 + dz_{f_c/k_i}(e_i)^2)`` (Corollary 1's proof)."""
    arr = np.asarray(z, dtype=float)
    d = dz(arr[..., 0], float(params.f_c / params.k_i))
    return np.sqrt(arr[..., 1] ** 2 + arr[..., 2] ** 2 + d**2)


def in_attractor_x(params: Parameters, x: Any) -> Any:
    """Whether ``x`` lies in 𝒜 (exact membership for exact input)."""
    arr = np.asarray(x)
    if arr.dtype == object and arr.ndim == 1:
        sigma, phi, v = arr
        return sigma == 0 and v == 0 and -params.f_c <= phi <= params.f_c
    arr = arr.astype(float)
    f_c = float(params.f_c)
    return (arr[..., 0] == 0) & (arr[..., 2] == 0) & (np.abs(arr[..., 1]) <= f_c)
