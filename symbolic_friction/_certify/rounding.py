"""From a floating-point :class:`~._certify.search.Candidate` to exact rational
constants (the "found" side; the verifier in :mod:`._certify.verify` shares
none of this code).

Why the bounds on ``V̂`` are valid and tight (Lemma 3, eq. hatVandHatR)
-----------------------------------------------------------------------
``V̂(x) = ½ wᵀKw`` with ``K = [[k₁,0,k₃],[0,k₂,0],[k₃,0,k₄]]`` and the
*nonnegative* vector ``w = (|σ|, |dz(φ)|, |v|)``, whose squared norm is
``|x|²_𝒜`` (eq. distFromA).

* Lower bound.  ``k₃ ≥ 0`` and ``w ≥ 0`` give ``k₃w₁w₃ ≥ 0``, so
  ``½wᵀKw ≥ ½(k₁w₁² + k₂w₂² + k₄w₃²) ≥ ½min(k₁,k₂,k₄)|w|²``, with equality
  at a coordinate vector.  Hence ``ĉ₁ = min(k₁,k₂,k₄)/2`` is the *largest*
  valid lower bound over nonnegative ``w``: larger than ``λ_min(K)/2``, and
  it does not even need ``k₁k₄ > k₃²``.
* Upper bound.  ``½wᵀKw ≤ ½λ_max(K)|w|²`` for every ``w``, and it is attained
  at a Perron eigenvector of the nonnegative matrix ``K``, which can be
  chosen nonnegative; so ``ĉ₂ = λ_max(K)/2`` is the smallest valid upper bound.

Rounding
--------
Certificates must regenerate byte-identically on any machine, so the last
bits of the solver's output must not reach the file.

1. The solver's ``k₁`` is snapped to the shortest decimal (at most
   :data:`SOLVER_DIGITS` significant digits, and ``≥ 2``) whose exactly
   evaluated objective is within :data:`SNAP_TOLERANCE` (relative) of the
   6-digit rounding.  ``k₂ = 2`` (the normalisation bound; every condition
   only gets harder as ``k₂`` grows, so the bound is optimal in both modes).
2. ``k₃`` and ``k₄`` are then the exact smallest values allowed by the
   k-conditions with margin ``μ`` (rounded *up* to :data:`DIGITS` significant
   digits): both objectives are nondecreasing in ``k₃`` and ``k₄`` (the
   largest eigenvalue of a nonnegative matrix is nondecreasing in its
   entries), and every lower bound on ``k₄`` is nondecreasing in ``k₃``, so
   this never does worse than the solver's own ``k₃``, ``k₄``.
3. ``ĉ₁ = min(k₁,k₂,k₄)/2`` exactly; ``ĉ₂``, ``c₁``, ``c₂`` are rounded
   outward to :data:`DIGITS` digits from closed-form eigenvalues (times
   ``(1+μ)^{±1}`` in the ``feasible`` mode), then checked exactly and
   *repaired* (moved outward one unit of the last digit at a time, then by
   halving/doubling) until the exact check passes.
4. The overshoot bound is ``√(c₂ĉ₂/(c₁ĉ₁))`` rounded *up* to
   :data:`KAPPA_DIGITS` significant digits, exactly (integer square root).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Callable

from .._infra.bounds import decimal_exponent, round_significant
from .._infra.errors import CertificateError
from .._model.parameters import Parameters
from .certificate import OBLIGATIONS, Certificate, Provenance
from .search import Candidate

__all__ = [
    "DIGITS",
    "SOLVER_DIGITS",
    "KAPPA_DIGITS",
    "SNAP_TOLERANCE",
    "round_significant",
    "sqrt_decimal_up",
    "to_certificate",
]

DIGITS = 9
"""Significant digits of constants derived exactly or from closed forms."""
SOLVER_DIGITS = 6
"""At most this many significant digits are kept from the solver's ``k₁``."""
KAPPA_DIGITS = 6
"""Significant digits of the decimal overshoot bound (rounded up)."""
SNAP_TOLERANCE = 1e-9
"""Relative loss in the objective accepted when snapping ``k₁`` to a shorter decimal."""

_MAX_REPAIRS = 200


# One exact rounding for the whole package: the printed bounds use it too (:mod:`.._infra.bounds`).
_decimal_exponent = decimal_exponent


def _ulp(q: Fraction, digits: int) -> Fraction:
    """One unit in the last of ``digits`` significant digits of ``q``."""
    return Fraction(10) ** (_decimal_exponent(q) - digits + 1)


def sqrt_decimal_up(q: Fraction, digits: int = KAPPA_DIGITS) -> str:
    """The decimal string ``d`` with ``digits`` significant digits, ``d² ≥ q``, smallest such.

    Exact (integer square root); the string keeps trailing zeros, e.g. ``"1.00000"``.

    Examples
    --------
    >>> sqrt_decimal_up(Fraction(2), 6)
    '1.41422'
    >>> sqrt_decimal_up(Fraction(4), 3)
    '2.00'
    """
    q = Fraction(q)
    if not q > 0:
        raise ValueError(f"sqrt_decimal_up needs q > 0; got {q}")
    # √q has decimal exponent floor(e_q/2); rounding up may carry into one more digit.
    exponent = _decimal_exponent(q) // 2
    while True:
        shift = digits - 1 - exponent
        target = q * Fraction(10) ** (2 * shift)  # smallest integer n with n² ≥ target
        t = math.ceil(target)
        n = math.isqrt(t - 1) + 1
        if len(str(n)) <= digits:
            break
        exponent += 1
    if shift <= 0:
        return str(n * 10 ** (-shift))
    text = str(n).rjust(shift + 1, "0")
    return f"{text[:-shift]}.{text[-shift:]}"


def _repair(value: Fraction, ok: Callable[[Fraction], bool], *, outward: int, what: str, params: Parameters) -> Fraction:
    """Move ``value`` outward (``-1`` down, ``+1`` up) until ``ok`` holds, deterministically."""
    for attempt in range(_MAX_REPAIRS):
        if ok(value):
            return value
        if attempt < 10:
            value = value + outward * _ulp(value, DIGITS)
        else:
            value = value / 2 if outward < 0 else value * 2
    raise CertificateError(f"could not repair {what} for {params} after {_MAX_REPAIRS} attempts")


# -- exact sufficient tests used for the repair (block form; the verifier uses its own) --
def _p_minus_c_psd(params: Parameters, c1: Fraction) -> bool:
    a = params.k_v / params.k_i
    return c1 <= 1 and c1 <= a and c1 <= params.k_p and (a - c1) * (params.k_p - c1) >= 1


def _c_minus_p_psd(params: Parameters, c2: Fraction) -> bool:
    a = params.k_v / params.k_i
    return c2 >= 1 and c2 >= a and c2 >= params.k_p and (c2 - a) * (c2 - params.k_p) >= 1


def _c_minus_half_k_psd(k: tuple[Fraction, ...], c2_hat: Fraction) -> bool:
    k1, k2, k3, k4 = k
    d1, d4 = c2_hat - k1 / 2, c2_hat - k4 / 2
    return 2 * c2_hat >= k2 and d1 >= 0 and d4 >= 0 and d1 * d4 >= k3 * k3 / 4


def _complete_k(k1: Fraction, params: Parameters, m: Fraction) -> tuple[Fraction, Fraction, Fraction, Fraction]:
    """``k₂ = 2`` and the smallest ``k₃``, ``k₄`` meeting the conditions with margin, rounded up."""
    r = params.k_i / params.k_v
    k2 = Fraction(2)
    k3 = round_significant(m * max(r * k1, k2), DIGITS, direction="up")
    k4 = round_significant(m * max(r * k3, params.k_p * k2, k3 * k3 / k1, Fraction(2)), DIGITS, direction="up")
    return k1, k2, k3, k4


def _objective(k: tuple[Fraction, ...], mode: str) -> float:
    """``ĉ₂/ĉ₁`` (tightest) or ``(trace K)/(2ĉ₁)`` (feasible) in floats, from exact ``k``."""
    k1, k2, k3, k4 = (float(v) for v in k)
    low = min(k1, k2, k4)
    if mode == "tightest":
        return max(k2, (k1 + k4 + math.hypot(k1 - k4, 2.0 * k3)) / 2.0) / low
    return (k1 + k2 + k4) / low


def _snap_k1(candidate: Candidate, m: Fraction) -> tuple[Fraction, Fraction, Fraction, Fraction]:
    params, mode = candidate.params, candidate.mode
    k1_float = max(candidate.k[0], 2.0)
    reference = _complete_k(max(round_significant(k1_float, SOLVER_DIGITS, direction="nearest"), Fraction(2)), params, m)
    bound = _objective(reference, mode) * (1.0 + SNAP_TOLERANCE)
    choices = [Fraction(2)] + [
        max(round_significant(k1_float, d, direction="nearest"), Fraction(2)) for d in range(1, SOLVER_DIGITS)
    ]
    for k1 in choices:
        k = _complete_k(k1, params, m)
        if _objective(k, mode) <= bound:
            return k
    return reference


def to_certificate(candidate: Candidate, *, label: str = "") -> Certificate:
    """Round ``candidate`` to exact constants and repair them (see the module docstring).

    The result is *not* yet proved: pass it to
    :func:`~symbolic_friction.verify_certificate`.

    Parameters
    ----------
    candidate : Candidate
        Output of :func:`~._certify.search.find_candidate`.
    label : str, keyword-only
        Free text stored in the provenance (e.g. ``"Table I, case (a)"``).
    """
    from .. import __version__

    params, mode, mu = candidate.params, candidate.mode, candidate.margin
    m = 1 + mu
    k = _snap_k1(candidate, m)
    k1, k2, k3, k4 = k
    c1_hat = min(k1, k2, k4) / 2

    lam_k = max(float(k2), (float(k1 + k4) + math.hypot(float(k1 - k4), 2.0 * float(k3))) / 2.0)
    c2_hat = _repair(
        round_significant(lam_k / 2, DIGITS, direction="up"),
        lambda v: _c_minus_half_k_psd(k, v),
        outward=+1,
        what="c2_hat",
        params=params,
    )
    lam_min = Fraction(candidate.lambda_min_P)
    lam_max = Fraction(candidate.lambda_max_P)
    if mode == "feasible":
        lam_min, lam_max = lam_min / m, lam_max * m
    c1 = _repair(
        round_significant(lam_min, DIGITS, direction="down"),
        lambda v: _p_minus_c_psd(params, v),
        outward=-1,
        what="c1",
        params=params,
    )
    c2 = _repair(
        round_significant(lam_max, DIGITS, direction="up"),
        lambda v: _c_minus_p_psd(params, v),
        outward=+1,
        what="c2",
        params=params,
    )
    c = 2 * (params.k_v * params.k_p - params.k_i)
    overshoot = sqrt_decimal_up((c2 * c2_hat) / (c1 * c1_hat), KAPPA_DIGITS)
    provenance = Provenance(
        mode=mode,
        margin=mu,
        solver=candidate.solver,
        solver_status=candidate.status,
        package_version=__version__,
        obligations=OBLIGATIONS,
        label=label,
    )
    return Certificate(
        k_p=params.k_p,
        k_i=params.k_i,
        k_v=params.k_v,
        f_c=params.f_c,
        k1=k1,
        k2=k2,
        k3=k3,
        k4=k4,
        c1=c1,
        c2=c2,
        c1_hat=c1_hat,
        c2_hat=c2_hat,
        c=c,
        overshoot_bound=overshoot,
        provenance=provenance,
    )
