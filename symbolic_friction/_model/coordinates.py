"""The coordinate change (eq. CoC) and the inclusion's data ``A`` and ``b``
(eq. xDot).

.. math::

    \\sigma = -k_i s,\\qquad \\phi = -k_i e_i - k_p s,\\qquad v = v,

maps the plant-controller state ``z = (e_i, s, v)`` of eq. (xPhDot) to
``x = (\\sigma, \\phi, v)``, in which the inclusion reads
``x' ∈ A x - b SGN(v)`` with

.. math::

    A = \\begin{bmatrix} 0 & 0 & -k_i\\\\ 1 & 0 & -k_p\\\\ 0 & 1 & -k_v\\end{bmatrix},
    \\qquad b = (0, 0, f_c).

The ``*_entries`` functions are written once, with plain arithmetic, so the
same definition serves exact rationals, sympy symbols (the proof
obligations) and floats (the simulators).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # annotations only: _model/python_control.py, which Parameters calls, reads A from here
    from .parameters import Parameters

__all__ = [
    "coc_entries",
    "coc_inverse_entries",
    "system_matrix_entries",
    "z_system_matrix_entries",
    "input_vector_entries",
    "z_to_x",
    "x_to_z",
    "system_matrix",
    "input_vector",
]

Matrix = tuple[tuple[Any, Any, Any], tuple[Any, Any, Any], tuple[Any, Any, Any]]


def coc_entries(k_p: Any, k_i: Any) -> Matrix:
    """Matrix ``T`` with ``x = T z`` (eq. CoC)."""
    return ((0, -k_i, 0), (-k_i, -k_p, 0), (0, 0, 1))


def coc_inverse_entries(k_p: Any, k_i: Any) -> Matrix:
    """Matrix ``T^{-1}`` with ``z = T^{-1} x``; needs ``k_i != 0``.

    From ``sigma = -k_i s`` and ``phi = -k_i e_i - k_p s``:
    ``s = -sigma/k_i`` and ``e_i = (k_p sigma / k_i - phi)/k_i``.
    """
    return ((k_p / k_i**2, -1 / k_i, 0), (-1 / k_i, 0, 0), (0, 0, 1))


def system_matrix_entries(k_p: Any, k_i: Any, k_v: Any) -> Matrix:
    """``A`` of eq. (xDot), in ``x = (sigma, phi, v)`` coordinates."""
    return ((0, 0, -k_i), (1, 0, -k_p), (0, 1, -k_v))


def z_system_matrix_entries(k_p: Any, k_i: Any, k_v: Any) -> Matrix:
    """``A_delta`` of Lemma 1's proof: the linear part of eq. (xPhDot) in ``z``."""
    return ((0, 1, 0), (0, 0, 1), (-k_i, -k_p, -k_v))


def input_vector_entries(f_c: Any) -> tuple[Any, Any, Any]:
    """``b = (0, 0, f_c)`` of eq. (xDot); the same vector multiplies SGN(v) in ``z``."""
    return (0, 0, f_c)


def system_matrix(params: Parameters) -> np.ndarray:
    """``A`` as a float array of shape (3, 3)."""
    k_p, k_i, k_v, _ = params.as_floats()
    return np.array(system_matrix_entries(k_p, k_i, k_v), dtype=float)


def input_vector(params: Parameters) -> np.ndarray:
    """``b`` as a float array of shape (3,)."""
    return np.array(input_vector_entries(float(params.f_c)), dtype=float)


def _apply(matrix: Matrix, state: Any) -> Any:
    arr = np.asarray(state)
    if arr.dtype == object:
        # Exact path: Fractions or sympy numbers, keep them exact.
        rows = [[sum(matrix[i][j] * arr[..., j] for j in range(3))] for i in range(3)]
        return np.stack([r[0] for r in rows], axis=-1)
    m = np.array(matrix, dtype=float)
    return arr.astype(float) @ m.T


def z_to_x(params: Parameters, z: Any) -> np.ndarray:
    """Map states ``z = (e_i, s, v)`` (shape ``(..., 3)``) to ``x = (sigma, phi, v)``.

    Float input gives float output; an object array of Fractions stays exact.

    Examples
    --------
    >>> from symbolic_friction import Parameters
    >>> p = Parameters(k_p=3, k_i=4, k_v="6.4")
    >>> z_to_x(p, [1.0, 2.0, 3.0])
    array([ -8., -10.,   3.])
    """
    if np.asarray(z).dtype == object:
        T = coc_entries(params.k_p, params.k_i)
    else:
        T = coc_entries(float(params.k_p), float(params.k_i))
    return _apply(T, z)


def x_to_z(params: Parameters, x: Any) -> np.ndarray:
    """Inverse of :func:`z_to_x` (nonsingular because ``k_i > 0``)."""
    if np.asarray(x).dtype == object:
        T = coc_inverse_entries(params.k_p, params.k_i)
    else:
        T = coc_inverse_entries(float(params.k_p), float(params.k_i))
    return _apply(T, x)
