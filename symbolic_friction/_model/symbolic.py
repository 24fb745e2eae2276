"""The paper's model in sympy, for symbolic (all-gain) parameters.

Everything here is built from the same ``*_entries`` functions that the
numerical code uses (:mod:`._coordinates`, :mod:`._lyapunov`), and ``dz``
and ``sat`` are the package's own (:mod:`._attractor`, evaluated in the sympy
kind of :mod:`._kinds`), so a proof obligation checks the package's model
and not a second copy of it.

The gains are positive symbols; Assumption 1's third inequality
``k_v k_p > k_i`` is *not* encoded in the symbols, so every use of it in a
proof is explicit (e.g. by substituting ``k_v = (k_i + δ)/k_p`` with
``δ > 0``).  This module imports sympy: import it lazily.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .coordinates import (
    coc_entries,
    coc_inverse_entries,
    input_vector_entries,
    system_matrix_entries,
    z_system_matrix_entries,
)
from .attractor import dz, sat
from .lyapunov import lyapunov_matrix_entries, vhat_matrix_entries

__all__ = ["Gains", "gains", "A", "A_z", "b", "P", "T", "T_inv", "K_hat", "dz", "sat", "assumption1_substitution"]


@dataclass(frozen=True)
class Gains:
    """Positive sympy symbols for ``k_p, k_i, k_v, f_c`` and state symbols."""

    k_p: sp.Symbol
    k_i: sp.Symbol
    k_v: sp.Symbol
    f_c: sp.Symbol
    sigma: sp.Symbol
    phi: sp.Symbol
    v: sp.Symbol
    e_i: sp.Symbol
    s: sp.Symbol
    delta: sp.Symbol  # k_v k_p - k_i > 0 under Assumption 1


def gains() -> Gains:
    """The canonical symbols (cached by sympy, so calls are cheap)."""
    k_p, k_i, k_v, f_c, delta = sp.symbols("k_p k_i k_v f_c delta", positive=True)
    sigma, phi, v, e_i, s = sp.symbols("sigma phi v e_i s", real=True)
    return Gains(k_p, k_i, k_v, f_c, sigma, phi, v, e_i, s, delta)


def _mat(entries) -> sp.Matrix:
    return sp.Matrix([[sp.sympify(e) for e in row] for row in entries])


def A(g: Gains | None = None) -> sp.Matrix:
    """``A`` of eq. (xDot)."""
    g = g or gains()
    return _mat(system_matrix_entries(g.k_p, g.k_i, g.k_v))


def A_z(g: Gains | None = None) -> sp.Matrix:
    """``A_delta`` (linear part in ``z``) of Lemma 1's proof."""
    g = g or gains()
    return _mat(z_system_matrix_entries(g.k_p, g.k_i, g.k_v))


def b(g: Gains | None = None) -> sp.Matrix:
    """``b = (0, 0, f_c)``."""
    g = g or gains()
    return sp.Matrix([sp.sympify(e) for e in input_vector_entries(g.f_c)])


def P(g: Gains | None = None) -> sp.Matrix:
    """``P`` of eq. (lyapLikeP)."""
    g = g or gains()
    return _mat(lyapunov_matrix_entries(g.k_p, g.k_i, g.k_v))


def T(g: Gains | None = None) -> sp.Matrix:
    """``T`` with ``x = T z`` (eq. CoC)."""
    g = g or gains()
    return _mat(coc_entries(g.k_p, g.k_i))


def T_inv(g: Gains | None = None) -> sp.Matrix:
    """The package's inverse coordinate map."""
    g = g or gains()
    return _mat(coc_inverse_entries(g.k_p, g.k_i))


def K_hat(k1, k2, k3, k4) -> sp.Matrix:
    """``K`` with ``V̂ = ½ wᵀKw``, ``w = (|σ|, |dz(φ)|, |v|)``."""
    return _mat(vhat_matrix_entries(k1, k2, k3, k4))


def assumption1_substitution(g: Gains | None = None) -> dict:
    """``{k_v: (k_i + δ)/k_p}``: encodes ``k_v k_p - k_i = δ > 0`` with positive symbols."""
    g = g or gains()
    return {g.k_v: (g.k_i + g.delta) / g.k_p}
