"""Mode selection at a state, following the table of the proof of Claim 1
(appendix, rows (i)–(xi)).

For an initial condition ``(σ̄, φ̄, v̄)`` the table names the affine system
``k ∈ {1, 0, -1}`` of eq. (subcasesAffine) whose solution is the solution of
the inclusion (eq. xDot) on some ``[0, T]``, ``T > 0``:

====== ==================================================== ====
row    initial condition                                    k
====== ==================================================== ====
(i)    ``v̄ > 0``                                            1
(ii)   ``v̄ = 0, φ̄ > f_c``                                   1
(iii)  ``v̄ = 0, φ̄ = f_c, σ̄ > 0``                            1
(iv)   ``v̄ = 0, φ̄ = f_c, σ̄ = 0``                            0
(v)    ``v̄ = 0, φ̄ = f_c, σ̄ < 0``                            0
(vi)   ``v̄ = 0, |φ̄| < f_c``                                 0
(vii)  ``v̄ = 0, φ̄ = -f_c, σ̄ > 0``                           0
(viii) ``v̄ = 0, φ̄ = -f_c, σ̄ = 0``                           0
(ix)   ``v̄ = 0, φ̄ = -f_c, σ̄ < 0``                           -1
(x)    ``v̄ = 0, φ̄ < -f_c``                                  -1
(xi)   ``v̄ < 0``                                            -1
====== ==================================================== ====

The comparisons are exact: with :class:`~fractions.Fraction` input the
boundaries ``φ = ±f_c`` and the edge ``σ = 0`` (rows (iv), (viii): points of
the attractor 𝒜, i.e. equilibria) are decided exactly.  Floating-point
callers that reach ``v = 0`` by computation use :func:`snap_to_boundary`
first, so that rounding within a few ulps of ``±f_c`` is decided by ``σ`` as
rows (iii)/(v)/(vii)/(ix) do, instead of by the sign of a rounding error.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = [
    "TABLE",
    "table_row",
    "select_mode",
    "select_modes",
    "snap_to_boundary",
    "mode_after_slip",
    "modes_after_slip",
]

TABLE: tuple[tuple[str, str, int], ...] = (
    ("i", "v > 0", 1),
    ("ii", "v = 0, phi > f_c", 1),
    ("iii", "v = 0, phi = f_c, sigma > 0", 1),
    ("iv", "v = 0, phi = f_c, sigma = 0", 0),
    ("v", "v = 0, phi = f_c, sigma < 0", 0),
    ("vi", "v = 0, |phi| < f_c", 0),
    ("vii", "v = 0, phi = -f_c, sigma > 0", 0),
    ("viii", "v = 0, phi = -f_c, sigma = 0", 0),
    ("ix", "v = 0, phi = -f_c, sigma < 0", -1),
    ("x", "v = 0, phi < -f_c", -1),
    ("xi", "v < 0", -1),
)
"""The appendix's table: ``(row, condition, k)``."""

_MODE_OF_ROW = {row: k for row, _, k in TABLE}


def table_row(sigma: Any, phi: Any, v: Any, f_c: Any) -> str:
    """The row (``"i"`` … ``"xi"``) of the appendix's table that contains the state.

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> table_row(F(0), F(1), F(0), F(1)), table_row(-1, 1, 0, 1), table_row(0, 0.5, 0, 1)
    ('iv', 'v', 'vi')
    """
    if v > 0:
        return "i"
    if v < 0:
        return "xi"
    if phi > f_c:
        return "ii"
    if phi < -f_c:
        return "x"
    if phi == f_c:
        return "iii" if sigma > 0 else "iv" if sigma == 0 else "v"
    if phi == -f_c:
        return "vii" if sigma > 0 else "viii" if sigma == 0 else "ix"
    return "vi"


def select_mode(sigma: Any, phi: Any, v: Any, f_c: Any) -> int:
    """The mode ``k ∈ {1, 0, -1}`` that the table assigns to ``(σ, φ, v)``.

    ``1`` is slip with ``v > 0`` (``x' = Ax - b``), ``0`` is stick
    (``σ' = 0, φ' = σ, v' = 0``), ``-1`` is slip with ``v < 0``
    (``x' = Ax + b``).  Exact for exact (``Fraction``/``int``) input.

    Examples
    --------
    >>> select_mode(1, 1, 0, 1), select_mode(-1, 1, 0, 1), select_mode(-1, -1, 0, 1)
    (1, 0, -1)
    """
    return _MODE_OF_ROW[table_row(sigma, phi, v, f_c)]


def select_modes(sigma: Any, phi: Any, v: Any, f_c: float) -> np.ndarray:
    """Vectorised :func:`select_mode` for float arrays (broadcast), as ``int8``."""
    sigma, phi, v = np.broadcast_arrays(np.asarray(sigma, float), np.asarray(phi, float), np.asarray(v, float))
    on_zero = v == 0
    at_plus = on_zero & (phi == f_c)
    at_minus = on_zero & (phi == -f_c)
    plus = (v > 0) | (on_zero & (phi > f_c)) | (at_plus & (sigma > 0))
    minus = (v < 0) | (on_zero & (phi < -f_c)) | (at_minus & (sigma < 0))
    return plus.astype(np.int8) - minus.astype(np.int8)


def snap_to_boundary(phi: float, f_c: float, tol: float) -> float:
    """``±f_c`` if ``phi`` is within ``tol`` of it, else ``phi`` unchanged.

    Used only at ``v = 0`` on computed (rounded) states, with ``tol`` a few
    ulps of the magnitudes that produced ``phi``; the table then decides by
    the sign of ``σ`` (rows (iii)–(v), (vii)–(ix)).
    """
    if abs(phi - f_c) <= tol:
        return f_c
    if abs(phi + f_c) <= tol:
        return -f_c
    return phi


def mode_after_slip(sigma: float, phi: float, direction: int, f_c: float, tol: float) -> tuple[float, int]:
    """``(φ, k)`` at the end of a slip in ``direction`` (``v`` has just reached 0).

    A solution can only leave the slip ``v > 0`` (resp. ``v < 0``) through
    ``v = 0`` with ``v' = φ - f_c ≤ 0`` (resp. ``φ + f_c ≥ 0``), i.e. with
    ``direction·φ ≤ f_c``; a computed ``φ`` on the wrong side of ``±f_c`` is a
    rounding error and is clamped (a tolerance-free rule).  Then ``φ`` within
    ``tol`` of ``±f_c`` is snapped (:func:`snap_to_boundary`) and the table
    decides.  The mode may equal ``direction`` (a grazing contact, row (iii)
    or (ix)): the slip then simply goes on.
    """
    if direction * phi > f_c:
        phi = direction * f_c
    phi = snap_to_boundary(phi, f_c, tol)
    return phi, select_mode(sigma, phi, 0.0, f_c)


def modes_after_slip(
    sigma: np.ndarray, phi: np.ndarray, direction: np.ndarray, f_c: float, tol: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised :func:`mode_after_slip`: ``(φ, k)`` arrays."""
    d = np.asarray(direction, dtype=float)
    phi = np.where(d * phi > f_c, d * f_c, phi)
    phi = np.where(np.abs(phi - f_c) <= tol, f_c, np.where(np.abs(phi + f_c) <= tol, -f_c, phi))
    return phi, select_modes(sigma, phi, 0.0, f_c)
