"""Printed bounds round in their safe direction: an upper bound up, a lower bound down, exactly.

Every number the package prints as proven (κ, κ/κ_lin, ρ, a settling time, an escape bound) is an upper
bound, and the proven lower end of ``κ_lin`` is a lower bound.  Formatting such a number with ``:.6g`` rounds
to nearest, which half the time prints a claim stronger than what was proved (``κ_lin ≥ 1.373268`` where
the proven end is ``1.3732677…``).  :func:`round_significant` rounds a rational exactly in a given direction
and :func:`bound_text` prints the result, so a printed upper bound is never below the proven one and a
printed lower bound never above it.  Only the standard library is used.
"""

from __future__ import annotations

import math
from decimal import Decimal, localcontext
from fractions import Fraction

__all__ = ["bound_text", "decimal_exponent", "round_significant"]


def decimal_exponent(q: Fraction) -> int:
    """The integer ``e`` with ``10**e ≤ q < 10**(e+1)``, for ``q > 0``, exactly."""
    e = len(str(q.numerator)) - len(str(q.denominator))
    while Fraction(10) ** e > q:
        e -= 1
    while Fraction(10) ** (e + 1) <= q:
        e += 1
    return e


def round_significant(q: Fraction | float, digits: int, *, direction: str) -> Fraction:
    """Round ``q > 0`` to ``digits`` significant decimal digits, exactly.

    Parameters
    ----------
    q : Fraction or float
        A float is taken through its exact binary value.
    digits : int
    direction : {"down", "up", "nearest"}, keyword-only

    Examples
    --------
    >>> round_significant(Fraction(2, 3), 3, direction="down")
    Fraction(333, 500)
    >>> round_significant(Fraction(2, 3), 3, direction="up")
    Fraction(667, 1000)
    """
    q = Fraction(q)
    if not q > 0:
        raise ValueError(f"round_significant needs q > 0; got {q}")
    shift = digits - 1 - decimal_exponent(q)
    scale = Fraction(10) ** shift
    x = q * scale
    if direction == "down":
        n = math.floor(x)
    elif direction == "up":
        n = math.ceil(x)
    elif direction == "nearest":
        n = math.floor(x + Fraction(1, 2))
    else:
        raise ValueError(f"direction must be 'down', 'up' or 'nearest'; got {direction!r}")
    return n / scale


def bound_text(q: Fraction | int | str, digits: int = 6, *, direction: str) -> str:
    """``q`` printed with at most ``digits`` significant digits, rounded ``"up"`` or ``"down"``, exactly.

    The printed decimal ``d`` is the nearest one of ``digits`` digits on the safe side: ``d ≥ q`` for ``"up"``
    (an upper bound such as κ or ρ), ``d ≤ q`` for ``"down"`` (a lower bound such as ``κ_lin``'s).  Negative
    values round in the same direction on the real line.  Trailing zeros are dropped as ``:g`` does.

    Parameters
    ----------
    q : Fraction, int or str
        The exact value (a string is read by :class:`fractions.Fraction`, e.g. ``"2/3"`` or ``"1.5"``).
        Floats are refused: their own rounding has already happened.
    digits : int
        Significant digits, 1 to 40.
    direction : {"up", "down"}, keyword-only

    Examples
    --------
    >>> bound_text(Fraction(13732677, 10000000), 6, direction="down")
    '1.37326'
    >>> bound_text(Fraction(13732677, 10000000), 6, direction="up")
    '1.37327'
    >>> bound_text(Fraction(-2, 3), 3, direction="up")
    '-0.666'
    >>> bound_text(Fraction(1, 3 * 10**9), 2, direction="up")
    '3.4e-10'
    >>> bound_text(0, direction="down")
    '0'
    """
    if isinstance(q, float):
        raise TypeError("bound_text takes an exact value (Fraction, int or str), not a float")
    if direction not in ("up", "down"):
        raise ValueError(f"direction must be 'up' or 'down'; got {direction!r}")
    if isinstance(digits, bool) or not isinstance(digits, int) or not 1 <= digits <= 40:
        raise ValueError(f"digits must be an integer in [1, 40]; got {digits!r}")
    q = Fraction(q)
    if q == 0:
        return "0"
    magnitude_direction = direction if q > 0 else ("down" if direction == "up" else "up")
    r = round_significant(abs(q), digits, direction=magnitude_direction)
    if digits <= 15 and Fraction(10) ** -300 < r < Fraction(10) ** 300:
        # r has at most 15 significant digits, so its nearest float prints back exactly as r
        text = f"{float(r):.{digits}g}"
    else:
        with localcontext() as ctx:
            ctx.prec = digits + 2
            text = format((Decimal(r.numerator) / Decimal(r.denominator)).normalize(), "g")  # exact: ≤ digits digits
    return text if q > 0 else "-" + text
