"""Exact rational input: the package's single way of turning user numbers into
:class:`fractions.Fraction`.

Standard 5 of the developers' guide: a gain given as ``"6.4"`` is 32/5, and a
Python ``float`` is read through its shortest decimal ``repr`` (so ``0.1`` is
1/10), never through its binary expansion unless ``binary=True`` is asked for.
"""

from __future__ import annotations

import math
import numbers
import re
from decimal import Decimal
from fractions import Fraction

from ._errors import InvalidNumberError, NonFiniteError

__all__ = ["to_rational", "format_rational"]

_NUMBER_RE = re.compile(
    r"""^\s*[+-]?(
        \d+(\.\d*)?([eE][+-]?\d+)?      # 12, 12., 12.5, 1e-6
      | \.\d+([eE][+-]?\d+)?            # .5
      | \d+\s*/\s*\d+                   # 32/5
    )\s*$""",
    re.VERBOSE,
)
_NONFINITE_WORDS = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}


def to_rational(value: object, *, name: str = "value", binary: bool = False) -> Fraction:
    """Convert ``value`` to an exact :class:`~fractions.Fraction`.

    Parameters
    ----------
    value : int, Fraction, sympy Rational, Decimal, str or float
        Integers, fractions and sympy rationals are taken as they are.
        Strings may be decimals (``"6.4"``, ``"1e-6"``) or fractions
        (``"32/5"``).  Floats are read through ``repr`` unless ``binary``.
    name : str, keyword-only
        Name of the quantity, used in error messages.
    binary : bool, keyword-only
        Read a float through its exact binary expansion instead.

    Returns
    -------
    Fraction

    Raises
    ------
    NonFiniteError
        If ``value`` is NaN or infinite.
    InvalidNumberError
        If ``value`` is not a number (booleans included) or the string is not
        a decimal or fraction.

    Examples
    --------
    >>> to_rational("6.4")
    Fraction(32, 5)
    >>> to_rational(0.1)
    Fraction(1, 10)
    >>> to_rational(0.1, binary=True) == Fraction(0.1)
    True
    """
    if isinstance(value, bool):
        raise InvalidNumberError(f"{name} must be a number; got the boolean {value!r}")
    if isinstance(value, Fraction):
        return value
    if isinstance(value, int):
        return Fraction(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise NonFiniteError(f"{name} must be finite; got {value!r}")
        # float(...) first: numpy 2 scalars repr as 'np.float64(0.66)'.
        return Fraction(value) if binary else Fraction(repr(float(value)))
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise NonFiniteError(f"{name} must be finite; got {value!r}")
        return Fraction(value)
    if isinstance(value, str):
        text = value.strip()
        if text.lower() in _NONFINITE_WORDS:
            raise NonFiniteError(f"{name} must be finite; got {value!r}")
        if not _NUMBER_RE.match(text):
            raise InvalidNumberError(
                f"{name} must be a decimal such as '6.4' or a fraction such as '32/5'; got {value!r}"
            )
        num = text.replace(" ", "")
        if "/" in num and int(num.split("/")[1]) == 0:
            raise InvalidNumberError(f"{name} has a zero denominator: {value!r}")
        return Fraction(num)
    # sympy numbers: Rational registers as numbers.Rational; reject Float/oo/nan explicitly.
    if type(value).__module__.startswith("sympy"):
        if getattr(value, "is_Rational", False):
            return Fraction(int(value.p), int(value.q))  # type: ignore[attr-defined]
        if getattr(value, "is_number", False) and not getattr(value, "is_finite", False):
            raise NonFiniteError(f"{name} must be finite; got {value!r}")
        if getattr(value, "is_Float", False):
            return to_rational(float(value), name=name, binary=binary)
        raise InvalidNumberError(f"{name} must be a rational number; got the sympy expression {value!r}")
    if isinstance(value, numbers.Rational):
        return Fraction(value.numerator, value.denominator)
    if isinstance(value, numbers.Real):  # numpy floating scalars and the like
        return to_rational(float(value), name=name, binary=binary)
    raise InvalidNumberError(f"{name} must be a number; got {type(value).__name__} {value!r}")


def format_rational(q: Fraction) -> str:
    """Write a rational as ``"p/q"`` or ``"p"`` (the certificate file format).

    >>> format_rational(Fraction(32, 5)), format_rational(Fraction(4))
    ('32/5', '4')
    """
    q = Fraction(q)
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"
