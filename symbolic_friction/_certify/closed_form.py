"""A closed-form certificate of Proposition 1 for every gain set, and for boxes of gains.

Lemma 3 needs ``k₁ … k₄`` satisfying the strict conditions of eq. (hatVdot)
and ``K ≻ 0``; the paper argues they exist.  Here they are written down.  With
``r = k_i/k_v``, ``a = k_v/k_i = 1/r``, ``ρ = max(r, 1)`` and a rational
``μ > 0``:

* ``k₁ = k₂ = 2``, ``k₃ = 2(1+μ)ρ``, ``k₄ = (1+μ)·max(2k_p, k₃²/2)``, so
  ``ĉ₁ = min(k₁, k₂, k₄)/2 = k₁/2 = 1`` (``k₄ > k₃²/2 ≥ 2``);
* ``P`` of eq. (lyapLikeP) is ``[[a, 0, −1], [0, 1, 0], [−1, 0, k_p]]``: its
  eigenvalues are ``1`` and those of the 2×2 block ``B``, so
  ``c₂ = (a + k_p + S)/2`` with a rational ``S ≥ 0``, ``S² ≥ (a − k_p)² + 4``,
  bounds ``λ_max(P)``, and ``c₁ = min(1, (a·k_p − 1)/c₂)`` (``det B`` over a
  bound of its larger eigenvalue, hence ``≤ λ_min(B)``), rounded down, bounds
  ``λ_min(P)``;
* ``K/2`` has eigenvalues ``1`` and ``(1 + k₄/2 ± √((k₄/2 − 1)² + k₃²))/2``,
  so ``ĉ₂ = (1 + k₄/2 + S′)/2`` with ``S′ ≥ 0``, ``S′² ≥ (k₄/2 − 1)² + k₃²``;
* ``κ = √(c₂ĉ₂/(c₁ĉ₁))``, rounded up to a decimal.

The obligation ``closed_form.all_gains`` proves, for symbolic gains, ``μ``,
``S`` and ``S′``, that these constants satisfy every premise of the exact
verifier; it runs :func:`closed_form_formulas` itself with symbolic
operations, so it checks this code and not a copy of it.

Every premise depends on the gains only through ``a`` and ``k_p``, each
monotonically (obligation ``closed_form.monotone``), so constants built from
the worst corner of a box ``[a_lo, a_hi] × [kp_lo, kp_hi]`` satisfy them on
the whole box: ``c₁`` from ``(a_lo, kp_lo)``, ``c₂`` from ``(a_hi, kp_hi)``,
``ρ`` from ``a_lo`` and ``k₄`` from ``kp_hi``.  A point is the box with equal
ends.

For a single gain set, :func:`balanced` then trades ``k₁ = 2`` for
``k₁ = k₄ ≈ √(1+μ)·k₃`` where that is allowed (small ``k_p`` and ``k_i/k_v``)
and lowers ``ĉ₂``: the point the SDP's ``feasible`` search finds there.

This is *search*: nothing here is called proved.  The verifier
(:mod:`._certify.verify`) decides the result, as for any other certificate.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

__all__ = [
    "ClosedFormConstants",
    "ExactOps",
    "closed_form_formulas",
    "closed_form_constants",
    "closed_form_certificate",
    "balanced",
    "balanced_conditions",
    "balanced_formulas",
    "balanced_radicand",
    "sqrt_up",
    "DEFAULT_MU",
    "SQRT_DIGITS",
    "SEARCH",
]

SEARCH = "closed-form"
"""The provenance's name of this search."""
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
    num, den = q.numerator, q.denominator
    # scale so that √(q·10^(2e)) has about `digits` integer digits; the target num/den·10^(2e) in integers
    e = digits - (len(str(num)) - len(str(den))) // 2
    if e >= 0:
        num *= 10 ** (2 * e)
    else:
        den *= 10 ** (-2 * e)
    n = math.isqrt(-(-num // den))  # ⌊√⌈target⌉⌋
    if n * n * den < num:
        n += 1
    return Fraction(n, 10**e) if e >= 0 else Fraction(n * 10 ** (-e))


class ExactOps:
    """The choices of :func:`closed_form_formulas` made in exact rationals.

    The arithmetic is the arguments' own: :class:`~fractions.Fraction`, or
    python-flint's ``fmpq`` (the same exact values, several times faster),
    which :func:`closed_form_constants` uses; square roots and rounding are
    taken through ``Fraction`` and returned in the arguments' type.

    The symbolic proof (obligation ``closed_form.all_gains``) passes its own
    operations instead: a case of its split decides which argument of each
    ``max``/``min`` wins, and ``sqrt_up``/``round_down`` become symbols
    constrained by their defining inequalities.
    """

    def __init__(self, digits: int = SQRT_DIGITS) -> None:
        self.digits = digits

    def max(self, name: str, x: Any, y: Any) -> Any:
        return max(x, y)

    def min(self, name: str, x: Any, y: Any) -> Any:
        return min(x, y)

    def sqrt_up(self, name: str, q: Any) -> Any:
        return _like(q, sqrt_up(_as_fraction(q), self.digits))

    def round_down(self, name: str, q: Any) -> Any:
        from .rounding import round_significant

        return _like(q, round_significant(_as_fraction(q), self.digits, direction="down"))


def _as_fraction(q: Any) -> Fraction:
    """An exact rational (``Fraction``, ``fmpq`` or int) as a ``Fraction``."""
    return q if type(q) is Fraction else Fraction(int(q.numerator), int(q.denominator))


def _like(model: Any, q: Fraction) -> Any:
    """``q`` in the type of ``model``: ``fmpq`` if ``model`` is one, else ``Fraction``."""
    from flint import fmpq

    return fmpq(q.numerator, q.denominator) if type(model) is fmpq else q


def closed_form_formulas(a_lo: Any, a_hi: Any, kp_lo: Any, kp_hi: Any, mu: Any, ops: Any) -> dict[str, Any]:
    """The closed form, written once, in the arithmetic of its arguments and the choices of ``ops``.

    Returns ``{"k1", "k2", "k3", "k4", "c1", "c2", "c1_hat", "c2_hat"}``.
    ``ops`` provides ``max(name, x, y)``, ``min(name, x, y)``,
    ``sqrt_up(name, q)`` (a number ``S ≥ 0`` with ``S² ≥ q``) and
    ``round_down(name, q)`` (a number in ``(0, q]``); the names are
    ``"rho"``, ``"k4"``, ``"c1"``, ``"S"``, ``"S_lo"``, ``"S_hat"``.
    """
    one = mu - mu + 1
    k1 = k2 = 2 * one
    rho = ops.max("rho", 1 / a_lo, one)
    k3 = 2 * (1 + mu) * rho
    k4 = (1 + mu) * ops.max("k4", 2 * kp_hi, k3 * k3 / 2)
    c2 = (a_hi + kp_hi + ops.sqrt_up("S", (a_hi - kp_hi) ** 2 + 4)) / 2
    c2_lo = (a_lo + kp_lo + ops.sqrt_up("S_lo", (a_lo - kp_lo) ** 2 + 4)) / 2
    c1 = ops.round_down("c1", ops.min("c1", one, (a_lo * kp_lo - 1) / c2_lo))
    c1_hat = k1 / 2  # = min(k1, k2, k4)/2: k1 = k2 and k4 > k3²/2 ≥ 2 (premises c1_hat ≤ k_j/2)
    c2_hat = (1 + k4 / 2 + ops.sqrt_up("S_hat", (k4 / 2 - 1) ** 2 + k3 * k3)) / 2
    return {"k1": k1, "k2": k2, "k3": k3, "k4": k4, "c1": c1, "c2": c2, "c1_hat": c1_hat, "c2_hat": c2_hat}


@dataclass(frozen=True)
class ClosedFormConstants:
    """The constants of the closed form for a box ``[a_lo, a_hi] × [kp_lo, kp_hi]`` (a point when the ends agree).

    Attributes
    ----------
    k1, k2, k3, k4, c1, c2, c1_hat, c2_hat : Fraction
        As in eqs. (VandR), (hatVandHatR), (hatVdot).
    mu : Fraction
        The margin ``μ`` they were built with.
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
        """``c₂ĉ₂/(c₁ĉ₁)``."""
        return (self.c2 * self.c2_hat) / (self.c1 * self.c1_hat)


def closed_form_constants(
    a_lo: Fraction, a_hi: Fraction, kp_lo: Fraction, kp_hi: Fraction, *, mu: Fraction = DEFAULT_MU,
    digits: int = SQRT_DIGITS, loose: bool = False,
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
    loose : bool, keyword-only
        Also move ``c₁`` and ``c₂`` outward by the factor ``1 + μ`` (the
        ``feasible`` mode: a margin on every inequality, not only the strict ones).

    Raises
    ------
    ValueError
        If a range is empty or not positive, ``μ ≤ 0``, or ``a_lo·kp_lo ≤ 1``
        (Assumption 1 fails at that corner).

    Examples
    --------
    >>> c = closed_form_constants(Fraction(8, 5), Fraction(8, 5), Fraction(3), Fraction(3))
    >>> c.k3, c.c1, round(float(c.kappa_squared), 4)
    (Fraction(1000001, 500000), Fraction(1, 1), 12.0203)
    """
    a_lo, a_hi, kp_lo, kp_hi, mu = (Fraction(q) for q in (a_lo, a_hi, kp_lo, kp_hi, mu))
    if not (0 < a_lo <= a_hi and 0 < kp_lo <= kp_hi):
        raise ValueError(f"need 0 < a_lo ≤ a_hi and 0 < kp_lo ≤ kp_hi; got a ∈ [{a_lo}, {a_hi}], k_p ∈ [{kp_lo}, {kp_hi}]")
    if not mu > 0:
        raise ValueError(f"the margin μ must be positive (with μ = 0 the strict conditions hold with equality); got {mu}")
    if not a_lo * kp_lo > 1:
        raise ValueError(f"Assumption 1 needs k_v·k_p > k_i, i.e. a·k_p > 1; got {a_lo}·{kp_lo} ≤ 1")
    from flint import fmpq

    ops = ExactOps(digits)
    # in FLINT's exact rationals (the same values as Fraction's, a gain map builds one set per point)
    q = [fmpq(x.numerator, x.denominator) for x in (a_lo, a_hi, kp_lo, kp_hi, mu)]
    c = closed_form_formulas(*q, ops)
    if loose:
        c["c1"] = ops.round_down("c1", c["c1"] / (1 + q[4]))
        c["c2"] = c["c2"] * (1 + q[4])
    return ClosedFormConstants(mu=mu, **{name: _as_fraction(value) for name, value in c.items()})


def balanced_radicand(k3: Any, mu: Any) -> Any:
    """``(1+μ)k₃²``: the number whose rational upper root ``T`` is ``k₁ = k₄`` of :func:`balanced`."""
    return (1 + mu) * k3 * k3


def balanced_conditions(a: Any, k_p: Any, k3: Any, mu: Any, T: Any) -> tuple[tuple[str, Any], ...]:
    """Where :func:`balanced` applies: ``(name, m)`` with the condition ``m ≥ 0``, in any arithmetic."""
    return (("T ≥ (1+μ)·2k_p", T - (1 + mu) * 2 * k_p), ("(1+μ)·T ≤ k₃·a", k3 * a - (1 + mu) * T))


def balanced_formulas(k3: Any, T: Any) -> dict[str, Any]:
    """The constants :func:`balanced` changes: ``k₁ = k₄ = T`` and ``ĉ₂ = λ_max(K)/2 = (T + k₃)/2``."""
    return {"k1": T, "k4": T, "c2_hat": (T + k3) / 2}


def balanced(c: ClosedFormConstants, a: Fraction, k_p: Fraction, *, digits: int = SQRT_DIGITS) -> ClosedFormConstants | None:
    """The closed form with ``k₁ = k₄ = T`` instead of ``k₁ = 2``, where that is allowed and lowers ``ĉ₂``; else None.

    With ``k₂ = 2`` and ``k₃`` as in the closed form, ``k₁k₄ ≥ (1+μ)k₃²`` at the
    smallest ``λ_max(K)`` is met by ``k₁ = k₄``: ``T`` is a rational with
    ``T² ≥ (1+μ)k₃²`` (``T ≈ √(1+μ)·k₃``), and then ``λ_max(K)/2 = (T + k₃)/2``
    exactly, so ``ĉ₂ = (T + k₃)/2`` needs no square root.  The other
    k-conditions hold where ``T ≥ (1+μ)·2k_p`` and ``(1+μ)·T ≤ k₃·a``
    (:func:`balanced_conditions`; small ``k_p`` and ``k_i/k_v``, e.g. Table I
    case (b)).  ``P``'s constants are unchanged.  Obligation
    ``closed_form.balanced`` proves, for all gains, that these constants
    satisfy every premise of the verifier wherever the conditions hold.
    This is the point that the SDP's ``feasible`` search finds (its margins,
    its trace objective), which the ``k₁ = 2`` family cannot reach: in Table I
    case (b) at ``μ = 1/100`` it gives κ ≤ 8.01380 where ``k₁ = 2`` gives 8.01425.
    """
    # k₃ ≤ T ≤ 2(1+μ)k₃ (T is √(1+μ)·k₃ rounded up by far less than a factor 2), so the conditions need
    # k_p ≤ k₃ and a ≥ 1 + μ: most gain sets are turned away here, before the square root
    if k_p > c.k3 or a < 1 + c.mu:
        return None
    T = sqrt_up(balanced_radicand(c.k3, c.mu), digits)
    if any(m < 0 for _, m in balanced_conditions(a, k_p, c.k3, c.mu, T)):
        return None
    changed = balanced_formulas(c.k3, T)
    if not changed["c2_hat"] < c.c2_hat:
        return None
    return dataclasses.replace(c, **changed)


def closed_form_certificate(params: Any, *, mode: str, margin: Fraction, label: str = "") -> Any:
    """The closed-form certificate of one gain set (not yet verified: pass it to the verifier).

    ``mode`` ``"tightest"`` uses ``margin`` on the strict k-conditions only;
    ``"feasible"`` also moves ``c₁``, ``c₂`` outward by ``1 + margin``.
    Where :func:`balanced` applies, its constants are used (a smaller ``ĉ₂``).
    """
    from .. import __version__
    from .certificate import OBLIGATIONS, Certificate, Provenance
    from .rounding import KAPPA_DIGITS, sqrt_decimal_up

    a = params.k_v / params.k_i
    c = closed_form_constants(a, a, params.k_p, params.k_p, mu=margin, loose=mode == "feasible")
    c = balanced(c, a, params.k_p) or c
    provenance = Provenance(
        mode=mode, margin=margin, solver="none", solver_status="exact", package_version=__version__,
        obligations=OBLIGATIONS, label=label, search=SEARCH,
    )
    return Certificate(
        k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_c=params.f_c,
        k1=c.k1, k2=c.k2, k3=c.k3, k4=c.k4, c1=c.c1, c2=c.c2, c1_hat=c.c1_hat, c2_hat=c.c2_hat,
        c=2 * (params.k_v * params.k_p - params.k_i),
        overshoot_bound=sqrt_decimal_up(c.kappa_squared, KAPPA_DIGITS),
        provenance=provenance,
    )
