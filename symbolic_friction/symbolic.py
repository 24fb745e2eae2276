"""The sympy model for symbolic gains: the paper's objects with ``k_p, k_i, k_v, f_c`` as positive symbols.

``A``, ``A_z``, ``b``, ``P``, ``T``, ``T⁻¹`` (eqs. xDot, CoC, lyapLikeP), ``K̂`` (Lemma 3), ``dz`` and ``sat``
(eq. distFromA) and Assumption 1's encoding ``k_v = (k_i + δ)/k_p``: the expressions the obligations of
``symbolic-friction check`` re-derive.  ``import symbolic_friction.symbolic`` imports sympy (the rest of
the package does not until it needs it).

Examples
--------
>>> from symbolic_friction.symbolic import A, gains
>>> g = gains()
>>> A(g)
Matrix([
[0, 0, -k_i],
[1, 0, -k_p],
[0, 1, -k_v]])
"""

from __future__ import annotations

from ._model.symbolic import (
    A,
    A_z,
    K_hat,
    P,
    T,
    T_inv,
    Gains,
    assumption1_substitution,
    b,
    dz,
    gains,
    sat,
)

__all__ = ["Gains", "gains", "A", "A_z", "b", "P", "T", "T_inv", "K_hat", "dz", "sat", "assumption1_substitution"]
