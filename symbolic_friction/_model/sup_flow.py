"""The sup-flow template: ``V_∞(x) = min_{f ∈ f_c SGN(v)} g(x − f e₂)`` with ``g(w) = sup_{t≥0} |e^{At}w|²``.

Beyond the paper.  ``V_∞`` is eq. (lyapLikeV) with ``|·|²_P`` replaced by ``g``,
the squared peak of the friction-free flow from ``w``.  It is nonincreasing
along every Filippov solution (the obligations ``sup_flow.*``), satisfies
``|x|²_𝒜 ≤ V_∞`` everywhere and ``V_∞ ≤ c₂|x|²_𝒜`` on ``R`` when
``c₂ ≥ sup_t ‖e^{At}‖₂²``, so on ``R`` it is as tight as the friction-free
limit allows.

On ``R̂`` the bound comes from ``U = max_i U_i``, each ``U_i = yᵀK_iy`` of
the quadratic template (:mod:`._model.quadratic`: ``y = (|σ|, |dz(φ)|, |v|)``,
``K₁₂ = 0``, nonincreasing on ``R̂`` under the same copositivity premises),
with time pieces ``I_i`` covering ``[0, ∞)``.  Where a solution leaves
``R̂ ∩ {v > 0}`` it is at ``v = 0`` (``φ < f_c``), where
``x − sat(φ)e₂ = (σ, dz(φ), 0) = (s·y₁, −y₂, 0)``, or at ``φ = f_c``, where
``x − f_c e₂ = (s·y₁, 0, y₃)`` (``s = sign σ``); ``v < 0`` is the mirror image
(``g`` is even).  So ``U ≥ V_∞`` there when, for every piece, every ``t ∈ I_i``
and ``s = ±1``, the 2×2 forms of :func:`exit_forms` with ``G = e^{At}ᵀe^{At}``
are copositive; past the last finite time ``T``,
``|e^{At}w|² ≤ (1/p)|e^{AT}w|²_P`` (the paper's ``P`` of eq. lyapLikeP,
``P − pI ⪰ 0``, ``AᵀP + PA ⪯ 0``) replaces ``G`` by
:func:`tail_gram`.

Every function uses plain arithmetic, so the search (floats), the verifier
(Fractions, arb balls) and the obligations (sympy) share this one definition.
"""

from __future__ import annotations

from typing import Any

__all__ = ["EXIT_PLANES", "exit_map", "exit_forms", "tail_gram", "drag_exit_map", "pullback_gap", "coupling_block"]

Matrix = tuple[tuple[Any, ...], ...]

EXIT_PLANES: tuple[str, ...] = ("v = 0", "φ = f_c")
"""Where a solution leaves ``R̂ ∩ {v > 0}``, in the order of :func:`exit_forms`."""


def exit_map(plane: str, s: Any) -> Matrix:
    """The 3×2 matrix ``D`` with ``x − f e₂ = D·(y_a, y_b)`` on an exit plane (``s = sign σ``).

    ``"v = 0"``: ``(y_a, y_b) = (|σ|, |dz(φ)|)`` and ``dz(φ) ≤ 0`` (``φ < f_c``);
    ``"φ = f_c"``: ``(y_a, y_b) = (|σ|, v)``.
    """
    zero = s - s
    one = zero + 1
    if plane == "v = 0":
        return ((s, zero), (zero, -one), (zero, zero))
    if plane == "φ = f_c":
        return ((s, zero), (zero, zero), (zero, one))
    raise ValueError(f"exit plane must be one of {EXIT_PLANES}; got {plane!r}")


def _block(k: Matrix, plane: str) -> Matrix:
    """``K`` restricted to the coordinates of ``y`` that are free on ``plane``."""
    i, j = (0, 1) if plane == "v = 0" else (0, 2)
    return ((k[i][i], k[i][j]), (k[j][i], k[j][j]))


def exit_forms(k: Matrix, gram: Matrix, s: Any) -> tuple[Matrix, Matrix]:
    """``K|_plane − Dᵀ·G·D`` on both exit planes: ``U(y) − wᵀGw`` in the plane's two free ``y`` coordinates.

    With ``G = e^{At}ᵀe^{At}`` a copositive form says ``U ≥ |e^{At}w|²`` on
    that plane for this ``t`` and this sign ``s`` of ``σ``.
    """
    out = []
    for plane in EXIT_PLANES:
        d = exit_map(plane, s)
        kb = _block(k, plane)
        dgd = tuple(
            tuple(sum((d[m][a] * gram[m][n] * d[n][b] for m in range(3) for n in range(3)), s - s) for b in range(2))
            for a in range(2)
        )
        out.append(tuple(tuple(kb[a][b] - dgd[a][b] for b in range(2)) for a in range(2)))
    return out[0], out[1]


def tail_gram(flow: Matrix, p_matrix: Matrix, p: Any) -> Matrix:
    """``(1/p)·Mᵀ P M`` with ``M = e^{AT}``: it bounds ``|e^{At}w|²`` for every ``t ≥ T`` (module docstring)."""
    pm = tuple(tuple(sum((p_matrix[i][k] * flow[k][j] for k in range(3)), p - p) for j in range(3)) for i in range(3))
    return tuple(tuple(sum((flow[k][i] * pm[k][j] for k in range(3)), p - p) / p for j in range(3)) for i in range(3))



# -- sup-flow/v2: the friction-drag split ---------------------------------------------------------------------


def drag_exit_map(s: Any, ell: tuple[Any, Any, Any]) -> Matrix:
    """The 3×3 ``D_ℓ`` with ``x − f_c e₂ = D_ℓ y`` on ``R̂ ∩ {v > 0}`` where the friction excess ``f = ℓᵀy``.

    On ``R̂ ∩ {v > 0}`` (``φ < f_c``) ``x − f_c e₂ = (s·y₁, −(y₂ + f), y₃)`` with
    ``f = f_c − φ − |dz(φ)| ≥ 0`` (``2f_c`` outside the band, ``f_c − φ`` inside), ``s = sign σ``;
    ``ℓ = 0`` gives ``diag(s, −1, 1)``, an isometry.
    """
    zero = s - s
    one = zero + 1
    return ((s, zero, zero), (-ell[0], -one - ell[1], -ell[2]), (zero, zero, one))


def pullback_gap(m: Matrix, gram: Matrix, d: Matrix) -> Matrix:
    """``M − DᵀGD`` (3×3): ``yᵀMy − |e^{At}Dy|²`` when ``G = e^{At}ᵀe^{At}``.

    With ``M = K`` and ``D = D_ℓ`` (:func:`drag_exit_map`) it says ``U ≥ |e^{At}w|²`` where a solution leaves
    ``{f > ℓᵀy}``; with ``M = c₂I`` that ``c₂|y|² ≥ |e^{At}D_ℓy|²``, the bound of ``V_∞`` on ``{f ≤ ℓᵀy}``.
    """
    zero = gram[0][0] - gram[0][0]
    dgd = tuple(tuple(sum((d[a][i] * gram[a][b] * d[b][j] for a in range(3) for b in range(3)), zero) for j in range(3))
                for i in range(3))
    return tuple(tuple(m[i][j] - dgd[i][j] for j in range(3)) for i in range(3))


def coupling_block(k_plus: Matrix, k_minus: Matrix) -> Matrix:
    """``(K⁺ − K⁻)`` on ``(|dz φ|, |v|)``: copositive, it says ``U⁻ ≤ U⁺`` on ``σ = 0`` (``y₁ = 0``)."""
    return tuple(tuple(k_plus[i][j] - k_minus[i][j] for j in (1, 2)) for i in (1, 2))
