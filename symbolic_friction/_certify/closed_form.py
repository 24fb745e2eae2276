"""A closed-form certificate of Proposition 1 for every gain set, and for boxes of gains.

Lemma 3 needs ``k₁ … k₄`` satisfying the strict conditions of eq. (hatVdot)
and ``K ≻ 0``; the paper argues they exist.  Here they are written down.  With
``r = k_i/k_v``, ``a = k_v/k_i = 1/r``, ``ρ = max(r, 1)`` and a rational
``μ > 0``:

* ``k₁ = k₂ = 2``, ``k₃ = 2(1+μ)ρ``, ``k₄ = (1+μ)·max(2k_p, k₃²/2)``, so
  ``ĉ₁ = min(k₁, k₂, k₄)/2 = 1``;
* ``P`` of eq. (lyapLikeP) is ``[[a, 0, −1], [0, 1, 0], [−1, 0, k_p]]``: its
  eigenvalues are ``1`` and those of the 2×2 block, so
  ``c₂ = (a + k_p + S)/2`` with a rational ``S ≥ 0``, ``S² ≥ (a − k_p)² + 4``,
  bounds ``λ_max(P)``, and ``c₁ = min(1, (a·k_p − 1)/c₂)`` (the block's
  determinant over a bound of its larger eigenvalue), rounded down, bounds
  ``λ_min(P)``;
* ``K/2`` has eigenvalues ``1`` and ``(1 + k₄/2 ± √((k₄/2 − 1)² + k₃²))/2``,
  so ``ĉ₂ = (1 + k₄/2 + S′)/2`` with ``S′² ≥ (k₄/2 − 1)² + k₃²``;
* ``κ = √(c₂ĉ₂/(c₁ĉ₁))``, rounded up to a decimal.

Every premise of :func:`~._certify.verify.premises` depends on the gains only
through ``a`` and ``k_p``, each monotonically, so constants built from the
worst corner of a box ``[a_lo, a_hi] × [kp_lo, kp_hi]`` satisfy them on the
whole box: ``c₁`` from ``(a_lo, kp_lo)``, ``c₂`` from ``(a_hi, kp_hi)``, ``ρ``
from ``a_lo`` and ``k₄`` from ``kp_hi``.  A point is the box with equal ends.

This is *search*: nothing here is called proved.  The verifier
(:mod:`._certify.verify`) decides the result, as for any other certificate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

__all__ = ["ClosedFormConstants", "closed_form_constants", "sqrt_up", "DEFAULT_MU", "SQRT_DIGITS"]

DEFAULT_MU = Fraction(1, 10**6)
"""The relative margin ``μ`` of the strict k-conditions (the SDP's tightest margin)."""
SQRT_DIGITS = 12
"""Significant digits of the rational upper bounds ``S`` and ``S′`` of the square roots."""


def sqrt_up(q: Fraction, digits: int = SQRT_DIGITS) -> Fraction:
    """A rational ``s ≥ 0`` with ``s² ≥ q`` and ``s ≤ √q·(1 + 10^(1−digits))``, exactly.

    Examples
    --------
    >>> sqrt_up(Fraction(4))
    Fraction(2, 1)
    >>> s = sqrt_up(Fraction(2), 6); s * s >= 2, float(s)
    (True, 1.414214)
    """
    q = Fraction(q)
    if q < 0:
        raise ValueError(f"sqrt_up needs q ≥ 0; got {q}")
    if q == 0:
        return Fraction(0)
    # scale so that √(q·10^(2e)) has about `digits` integer digits
    magnitude = (len(str(q.numerator)) - len(str(q.denominator))) // 2
    e = digits - magnitude
    scale = Fraction(10) ** (2 * e)
    target = q * scale
    n = math.isqrt(math.ceil(target))
    if n * n < target:
        n += 1
    return Fraction(n) / Fraction(10) ** e


def _round_down(q: Fraction, digits: int) -> Fraction:
    """``q > 0`` rounded down to ``digits`` significant digits (exact)."""
    from .rounding import round_significant

    return round_significant(q, digits, direction="down")


@dataclass(frozen=True)
class ClosedFormConstants:
    """The constants of the closed form for a box ``[a_lo, a_hi] × [kp_lo, kp_hi]`` (a point when the ends agree).

    Attributes
    ----------
    k1, k2, k3, k4, c1, c2, c1_hat, c2_hat : Fraction
        As in eqs. (VandR), (hatVandHatR), (hatVdot).
    mu : Fraction
        The margin ``μ`` they were built with.
    kappa_squared : Fraction
        ``c₂ĉ₂/(c₁ĉ₁)``.
    """

    k1: Fraction
    k2: Fraction
    k3: Fraction
    k4: Fraction
    c1: Fraction
    c2: Fraction
    c1_hat: Fraction
    c2_hat: Fraction
    mu: Fraction

    @property
    def kappa_squared(self) -> Fraction:
        return (self.c2 * self.c2_hat) / (self.c1 * self.c1_hat)


def closed_form_constants(
    a_lo: Fraction, a_hi: Fraction, kp_lo: Fraction, kp_hi: Fraction, *, mu: Fraction = DEFAULT_MU,
    digits: int = SQRT_DIGITS,
) -> ClosedFormConstants:
    """The closed-form constants for every ``(a, k_p)`` with ``a_lo ≤ a ≤ a_hi``, ``kp_lo ≤ k_p ≤ kp_hi``.

    Parameters
    ----------
    a_lo, a_hi : Fraction
        Range of ``a = k_v/k_i``.
    kp_lo, kp_hi : Fraction
        Range of ``k_p``.
    mu : Fraction, keyword-only
        Margin ``μ > 0`` of the strict conditions.
    digits : int, keyword-only
        Significant digits of the square-root bounds and of ``c₁``.

    Raises
    ------
    ValueError
        If a range is empty or not positive, ``μ ≤ 0``, or ``a_lo·kp_lo ≤ 1``
        (Assumption 1 fails at that corner).
    """
    a_lo, a_hi, kp_lo, kp_hi, mu = (Fraction(q) for q in (a_lo, a_hi, kp_lo, kp_hi, mu))
    if not (0 < a_lo <= a_hi and 0 < kp_lo <= kp_hi):
        raise ValueError(f"need 0 < a_lo ≤ a_hi and 0 < kp_lo ≤ kp_hi; got a ∈ [{a_lo}, {a_hi}], k_p ∈ [{kp_lo}, {kp_hi}]")
    if not mu > 0:
        raise ValueError(f"the margin μ must be positive (with μ = 0 the strict conditions hold with equality); got {mu}")
    if not a_lo * kp_lo > 1:
        raise ValueError(f"Assumption 1 needs k_v·k_p > k_i, i.e. a·k_p > 1; got {a_lo}·{kp_lo} ≤ 1")
    one = Fraction(1)
    rho = max(1 / a_lo, one)
    k1 = k2 = Fraction(2)
    k3 = 2 * (1 + mu) * rho
    k4 = (1 + mu) * max(2 * kp_hi, k3 * k3 / 2)
    c2 = (a_hi + kp_hi + sqrt_up((a_hi - kp_hi) ** 2 + 4, digits)) / 2
    c2_lo = (a_lo + kp_lo + sqrt_up((a_lo - kp_lo) ** 2 + 4, digits)) / 2
    c1 = min(one, _round_down((a_lo * kp_lo - 1) / c2_lo, digits))
    c1_hat = min(k1, k2, k4) / 2
    c2_hat = (1 + k4 / 2 + sqrt_up((k4 / 2 - 1) ** 2 + k3 * k3, digits)) / 2
    return ClosedFormConstants(k1, k2, k3, k4, c1, c2, c1_hat, c2_hat, mu)
