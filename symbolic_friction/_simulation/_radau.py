"""scipy's Radau IIA integrator (order 5) for the three states ``z = (e_i, s, v)`` of eq. (xPhDot), with its linear
solves made directly by LAPACK.

Each Newton iteration of scipy's ``Radau`` solves one real and one complex 3×3 system with the LU factors of
``μ/h I - J``, through :func:`scipy.linalg.lu_solve`; for three states that function spends about 20 µs in
argument checks and dispatch around a LAPACK ``getrs`` of well under one, which made it the larger part of a
``regularized`` run (and of ``ivp-events`` with ``integrator="Radau"``, the event method's fallback).
:class:`Radau` is scipy's class with only that solve replaced: the same ``getrs`` (``dgetrs`` or ``zgetrs``, as
``lu_solve`` chooses them) on the same factors and right-hand sides, with the same refusal of a right-hand side
that is not finite, so every step, every event and every sample is the same number, bit for bit
(``tests/simulation/test_radau.py`` compares the two on the package's methods, and a broken solve fails it).
When scipy's class does not have the dense ``solve_lu`` this relies on, scipy's own solve is kept.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.integrate import Radau as _ScipyRadau
from scipy.linalg import get_lapack_funcs

__all__ = ["Radau", "integrator"]

_ZEROS = (np.zeros((1, 1)), np.zeros((1, 1), dtype=complex))
# lu_solve's choice for float64 and complex128 factors (get_lapack_funcs picks by the arrays' common type)
_GETRS = {a.dtype.char: get_lapack_funcs(("getrs",), (a,))[0] for a in _ZEROS}


def solve_lu(lu_and_piv: tuple[np.ndarray, np.ndarray], b: np.ndarray) -> np.ndarray:
    """``lu_solve(lu_and_piv, b, overwrite_b=True)`` for one right-hand side of the factors' type."""
    lu, piv = lu_and_piv
    if not np.isfinite(b).all():  # lu_solve's check_finite, with its error
        raise ValueError("array must not contain infs or NaNs")
    getrs = _GETRS.get(np.result_type(lu, b).char)
    if getrs is None or b.ndim != 1:  # not a solve Radau makes: scipy's, unchanged
        from scipy.linalg import lu_solve

        return lu_solve(lu_and_piv, b, overwrite_b=True)
    x, info = getrs(lu, piv, b, overwrite_b=True)
    if info != 0:
        raise ValueError(f"illegal value in {-info}th argument of internal gesv|posv")
    return x


class Radau(_ScipyRadau):
    """scipy's ``Radau`` with :func:`solve_lu` for its dense linear solves (see the module docstring)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        if isinstance(getattr(self, "J", None), np.ndarray) and callable(getattr(self, "solve_lu", None)):
            self.solve_lu = solve_lu


def integrator(name: str) -> Any:
    """What to hand ``solve_ivp`` as ``method`` for the integrator ``name``: :class:`Radau` for ``"Radau"``."""
    return Radau if name == "Radau" else name
