"""The quadratic template: ``V`` of eq. (lyapLikeV) with a free ``P`` (``P₁₂ = 0``) and a general ``V̂``.

Beyond the paper.  Lemma 2's argument uses three facts about ``P``:

* at ``v = 0`` the minimiser of eq. (lyapLikeV) is ``f = sat_{f_c}(φ)``, which
  needs ``P₁₂ = 0`` (``P₂₃`` never meets ``v = 0``);
* during a slip ``w = x − f_c sign(v) e₂`` follows ``ẇ = Aw`` (``A e₂ = e₃``),
  so ``d/dt |w|²_P = wᵀQw`` with ``Q = AᵀP + PA``;
* ``Q + c e₃e₃ᵀ ⪯ 0`` for some ``c > 0`` gives eq. (Vdecrease).

``Q₁₁ = 2P₁₂``, so ``Q ⪯ 0`` forces the first row of ``Q`` to vanish:
``P₁₃ = −P₂₂`` and ``P₂₃ = k_i P₁₁ − k_v P₂₂``.  That leaves ``P₁₁, P₂₂, P₃₃``
free (:func:`quadratic_p_entries`); the paper's ``P`` of eq. (lyapLikeP) is
``(k_v/k_i, 1, k_p)``, where ``P₂₃ = 0``.

``V̂`` of eq. (Vhat) becomes ``U = yᵀKy`` with ``y = (|σ|, |dz(φ)|, |v|)`` and
any symmetric ``K`` with ``K₁₂ = 0``.  On ``R̂ ∩ {v > 0}``, with
``s = sign(σ)``, ``ẏ = B_s y − (0, 0, f)`` where ``f = f_c − φ − |dz(φ)| ≥ 0``
(:func:`slip_rate_entries`), so ``U̇ ≤ 0`` there when

* ``−(K B_s + B_sᵀ K)`` is copositive for ``s = ±1`` (outside the band
  ``|φ| ≤ f_c``; ``K₁₂ = 0`` because its diagonal entry is ``±2K₁₂``);
* the 2×2 form of :func:`band_rate_entries` is copositive for ``s = ±1``
  (inside the band, where ``y₂ = 0``);
* ``K₃ⱼ ≥ 0`` (the friction term ``−2(Ky)₃ f``);

and ``R̂ ∩ {v < 0}`` is the mirror image.  The bounds are ``U ≥ |y|²``
(``K − I`` copositive), ``U ≤ γ|y|²`` (``γI − K`` copositive) and, where a
solution leaves ``R̂`` (``v = 0``, or ``φ = ±f_c`` with ``v ≠ 0``), ``U ≥ V``
(:func:`exit_entries`).  With ``P ⪰ I`` and ``c₂I − P ⪰ 0`` Proposition 1's
case analysis then gives ``|x(t)|²_𝒜 ≤ max(c₂, γ)|x(0)|²_𝒜``.

Every function uses plain arithmetic, so the search (floats), the verifier
(Fractions) and the obligations (sympy) share this one definition.
"""

from __future__ import annotations

from typing import Any

from .coordinates import system_matrix_entries

__all__ = [
    "quadratic_p_entries",
    "lyapunov_rate_entries",
    "slip_rate_entries",
    "u_matrix_entries",
    "u_rate_entries",
    "band_rate_entries",
    "exit_entries",
    "u_matrix_signed",
    "drag_rate_entries",
    "drag_band_entries",
]

Matrix = tuple[tuple[Any, ...], ...]


def quadratic_p_entries(k_p: Any, k_i: Any, k_v: Any, p11: Any, p22: Any, p33: Any) -> Matrix:
    """``P`` with ``P₁₂ = 0``, ``P₁₃ = −P₂₂``, ``P₂₃ = k_i P₁₁ − k_v P₂₂`` (the first row of ``AᵀP + PA`` zero)."""
    zero = p22 - p22
    p23 = k_i * p11 - k_v * p22
    return ((p11, zero, -p22), (zero, p22, p23), (-p22, p23, p33))


def _transpose(m: Matrix) -> Matrix:
    return tuple(tuple(m[j][i] for j in range(len(m))) for i in range(len(m[0])))


def _product(a: Matrix, b: Matrix) -> Matrix:
    return tuple(
        tuple(sum((a[i][k] * b[k][j] for k in range(len(b))), a[0][0] * 0) for j in range(len(b[0])))
        for i in range(len(a))
    )


def _symmetric_sum(m: Matrix) -> Matrix:
    """``M + Mᵀ``."""
    t = _transpose(m)
    return tuple(tuple(m[i][j] + t[i][j] for j in range(len(m))) for i in range(len(m)))


def lyapunov_rate_entries(k_p: Any, k_i: Any, k_v: Any, p: Matrix) -> Matrix:
    """``Q = AᵀP + PA`` with ``A`` of eq. (xDot): ``d/dt |w|²_P = wᵀQw`` along ``ẇ = Aw``."""
    a = system_matrix_entries(k_p, k_i, k_v)
    return _symmetric_sum(_product(p, a))


def slip_rate_entries(k_p: Any, k_i: Any, k_v: Any, s: Any) -> Matrix:
    """``B_s``: ``ẏ = B_s y − (0, 0, f)`` for ``y = (|σ|, |dz(φ)|, v)`` on ``R̂ ∩ {v > 0, φ < −f_c}``, ``s = sign(σ)``."""
    zero = k_p - k_p
    return ((zero, zero, -k_i * s), (-s + zero, zero, k_p), (zero, zero - 1, -k_v))


def u_matrix_entries(k11: Any, k13: Any, k22: Any, k23: Any, k33: Any) -> Matrix:
    """``K`` of ``U = yᵀKy`` (``K₁₂ = 0``)."""
    zero = k11 - k11
    return ((k11, zero, k13), (zero, k22, k23), (k13, k23, k33))


def u_rate_entries(k: Matrix, b: Matrix) -> Matrix:
    """``−(K B + Bᵀ K)``: ``U̇ = −yᵀ(this)y − 2(Ky)₃ f`` where ``ẏ = By − (0, 0, f)``."""
    kb = _product(k, b)
    s = _symmetric_sum(kb)
    return tuple(tuple(-e for e in row) for row in s)


def band_rate_entries(k_i: Any, k_v: Any, k: Matrix, s: Any) -> Matrix:
    """The 2×2 form in ``(|σ|, v)`` with ``U̇ ≤ −(this form) − 2(Ky)₃ f`` inside the band ``|φ| ≤ f_c``.

    There ``y₂ = 0`` and ``ẏ₁ = −k_i s v``, ``v̇ = −k_v v − f``, so
    ``U̇ = 2(K₁₁y₁ + K₁₃v)(−k_i s v) + 2(K₁₃y₁ + K₃₃v)(−k_v v) − 2(Ky)₃ f``.
    """
    off = k_i * s * k[0][0] + k_v * k[0][2]
    return ((k[0][0] - k[0][0], off), (off, 2 * k_i * s * k[0][2] + 2 * k_v * k[2][2]))


def exit_entries(k: Matrix, p: Matrix) -> tuple[Matrix, Matrix]:
    """The 2×2 forms that make ``U ≥ V`` where a solution leaves ``R̂``.

    At ``v = 0``: ``U − V`` in ``(|σ|, |dz(φ)|)`` (``V = P₁₁σ² + P₂₂dz(φ)²`` there, as ``P₁₂ = 0``).
    At ``φ = ±f_c``, ``v ≠ 0``: ``U − V`` in ``(|σ|, |v|)`` at the worst sign of ``σv``
    (``V = P₁₁σ² + 2P₁₃σv + P₃₃v²``, ``P₁₃ = −P₂₂ ≤ 0``, so the worst case has the term ``−2P₂₂|σ||v|``).
    """
    at_rest = ((k[0][0] - p[0][0], k[0][1]), (k[0][1], k[1][1] - p[1][1]))
    cross = k[0][2] - p[1][1]
    at_edge = ((k[0][0] - p[0][0], cross), (cross, k[2][2] - p[2][2]))
    return at_rest, at_edge


# -- sup-flow/v2: one form per sign of σv (K₁₂ kept) and the friction-drag split ----------------------------


def u_matrix_signed(k11: Any, k12: Any, k13: Any, k22: Any, k23: Any, k33: Any) -> Matrix:
    """``K`` of ``U = yᵀKy`` with ``K₁₂`` kept: the sup-flow/v2 form of one sign ``s`` of ``σv``.

    The rate form's ``(1, 1)`` entry is ``2sK₁₂`` (:func:`u_rate_entries` with ``B_s``), so a form used only
    where ``sign(σv) = s`` may have ``sK₁₂ ≥ 0`` instead of ``K₁₂ = 0``.
    """
    return ((k11, k12, k13), (k12, k22, k23), (k13, k23, k33))


def drag_rate_entries(k: Matrix, b: Matrix, ell: tuple[Any, Any, Any]) -> Matrix:
    """``−(K B + Bᵀ K) + K e₃ℓᵀ + ℓ e₃ᵀK``: ``U̇ ≤ −yᵀ(this)y`` where the friction excess ``f > ℓᵀy``.

    ``U̇ = −yᵀ(−(KB + BᵀK))y − 2(Ky)₃ f`` (:func:`u_rate_entries`) and ``(Ky)₃ ≥ 0``, so
    ``f > ℓᵀy`` gives ``−2(Ky)₃ f ≤ −2(Ky)₃ ℓᵀy = −yᵀ(K e₃ℓᵀ + ℓ e₃ᵀK)y``.  ``ℓ = 0`` is :func:`u_rate_entries`.
    """
    rate = u_rate_entries(k, b)
    return tuple(tuple(rate[i][j] + k[i][2] * ell[j] + ell[i] * k[j][2] for j in range(3)) for i in range(3))


def drag_band_entries(k_i: Any, k_v: Any, k: Matrix, s: Any, ell: tuple[Any, Any, Any]) -> Matrix:
    """:func:`band_rate_entries` plus the band's part of ``K e₃ℓᵀ + ℓ e₃ᵀK`` (rows and columns ``|σ|``, ``v``).

    Inside the band ``y₂ = 0``, so the drag adds ``[[2K₁₃ℓ₁, K₁₃ℓ₃ + K₃₃ℓ₁], [·, 2K₃₃ℓ₃]]``; its
    ``(1, 1)`` entry fills the band form's zero diagonal entry.
    """
    band = band_rate_entries(k_i, k_v, k, s)
    l1, l3 = ell[0], ell[2]
    drag = ((2 * k[0][2] * l1, k[0][2] * l3 + k[2][2] * l1), (k[0][2] * l3 + k[2][2] * l1, 2 * k[2][2] * l3))
    return tuple(tuple(band[i][j] + drag[i][j] for j in range(2)) for i in range(2))
