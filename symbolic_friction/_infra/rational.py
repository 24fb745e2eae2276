"""Exact rational input: the package's single way of turning user numbers into
:class:`fractions.Fraction`.

Exact input stays exact: a gain given as ``"6.4"`` is 32/5, and a
Python ``float`` is read through its shortest decimal ``repr`` (so ``0.1`` is
1/10), never through its binary expansion unless ``binary=True`` is asked for.
"""

from __future__ import annotations

import math
import numbers
import re
from decimal import Decimal
from fractions import Fraction

from .errors import InvalidNumberError, NonFiniteError

__all__ = [
    "to_rational", "format_rational", "short_rational", "shown", "parse_integer", "format_integer", "MAX_INPUT_DIGITS",
    "MAX_EXPONENT",
]

# ASCII digits only (re.ASCII): "٣" or "３" are refused, never read as 3.
_NUMBER_RE = re.compile(
    r"""^\s*[+-]?(
        \d+(\.\d*)?([eE][+-]?\d+)?      # 12, 12., 12.5, 1e-6
      | \.\d+([eE][+-]?\d+)?            # .5
      | \d+\s*/\s*\d+                   # 32/5
    )\s*$""",
    re.VERBOSE | re.ASCII,
)
_EXPONENT_RE = re.compile(r"[eE]([+-]?\d+)", re.ASCII)
MAX_INPUT_DIGITS = 1000
"""A number typed by a user (option, scene file) may have at most this many characters."""
MAX_EXPONENT = 1000
"""... and a decimal exponent of at most this magnitude (``1e999999999`` would be a 10⁹-digit integer)."""
_MAX_BITS = int(MAX_INPUT_DIGITS * 3.3219280948873626) + 1
_CHUNK = 4000  # below Python's int/str conversion limit (4300 digits)


def parse_integer(text: str) -> int:
    """``int(text)`` for a string of ASCII digits of any length, without Python's 4300-digit limit.

    The caller bounds the length; the conversion splits the string so that
    each piece stays below the interpreter's limit.
    """
    sign = 1
    if text[:1] in "+-" and text[:1]:
        sign, text = (-1 if text[0] == "-" else 1), text[1:]
    if not text.isascii() or not text.isdigit():
        raise InvalidNumberError(f"expected ASCII digits; got {text[:40]!r}")
    if len(text) <= _CHUNK:
        return sign * int(text)
    half = len(text) // 2
    return sign * (parse_integer(text[:half]) * 10 ** (len(text) - half) + parse_integer(text[half:]))


def format_integer(n: int) -> str:
    """``str(n)`` for an integer of any size, without Python's 4300-digit limit."""
    if n < 0:
        return "-" + format_integer(-n)
    try:
        return str(n)
    except ValueError:
        pass
    k = max(1, int(n.bit_length() * 0.30103) // 2)
    hi, lo = divmod(n, 10**k)
    return format_integer(hi) + format_integer(lo).rjust(k, "0")


def shown(value: object, limit: int = 40) -> str:
    """``repr(value)`` for a message, at most ``limit`` characters (a 10⁵-digit integer is described, not printed).

    >>> shown(10**400)
    'an integer of 401 digits'
    >>> shown("x" * 100)
    "'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx…"
    """
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 4 * limit:
        return f"an integer of {len(format_integer(abs(value)))} digits" if value.bit_length() < 40_000 else (
            f"an integer of about {int(value.bit_length() * 0.30103) + 1} digits")
    if isinstance(value, Fraction) and max(value.numerator.bit_length(), value.denominator.bit_length()) > 4 * limit:
        return f"Fraction {short_rational(value)}"
    if isinstance(value, (list, tuple, dict, set)) and len(value) > limit:
        return f"a {type(value).__name__} of {len(value)} items"
    try:
        text = repr(value)
    except Exception:  # noqa: BLE001 - a repr that fails (Python's 4300-digit limit) must not hide the error
        text = f"<{type(value).__name__}>"
    return text if len(text) <= limit else text[: limit - 1] + "…"


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
        if value.bit_length() > _MAX_BITS:
            raise InvalidNumberError(f"{name} has more than {MAX_INPUT_DIGITS} digits; such numbers are refused")
        return Fraction(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise NonFiniteError(f"{name} must be finite; got {value!r}")
        # float(...) first: numpy 2 scalars repr as 'np.float64(0.66)'.
        return Fraction(value) if binary else Fraction(repr(float(value)))
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise NonFiniteError(f"{name} must be finite; got {value!r}")
        if not value:
            return Fraction(0)  # Decimal("0E+999999999") too
        # bounded as a string is, before the conversion expands 10**exponent: Decimal("1e999999999") would hang
        digits = len(value.as_tuple().digits)
        if digits > MAX_INPUT_DIGITS:
            raise InvalidNumberError(f"{name} has {digits} digits; at most {MAX_INPUT_DIGITS} are accepted")
        if abs(value.adjusted()) > MAX_EXPONENT:
            raise InvalidNumberError(
                f"{name} has the exponent {value.adjusted()}; exponents beyond ±{MAX_EXPONENT} are refused"
            )
        return Fraction(value)
    if isinstance(value, str):
        text = value.strip()
        if text.lower() in _NONFINITE_WORDS:
            raise NonFiniteError(f"{name} must be finite; got {value!r}")
        if len(text) > MAX_INPUT_DIGITS:
            raise InvalidNumberError(
                f"{name} has {len(text)} characters; at most {MAX_INPUT_DIGITS} are accepted"
            )
        if not _NUMBER_RE.match(text):
            abbreviated = value if len(value) <= 40 else value[:40] + "…"
            hint = " (ASCII digits only)" if any(ch.isdigit() and not ch.isascii() for ch in text) else ""
            raise InvalidNumberError(
                f"{name} must be a decimal such as '6.4' or a fraction such as '32/5'{hint}; got {abbreviated!r}"
            )
        exponent = _EXPONENT_RE.search(text)
        if exponent is not None and abs(int(exponent.group(1))) > MAX_EXPONENT:
            raise InvalidNumberError(
                f"{name} has the exponent {exponent.group(1)}; exponents beyond ±{MAX_EXPONENT} are refused"
            )
        num = "".join(text.split())  # white space around the slash (tabs, newlines too) is not part of the number
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
        raise InvalidNumberError(f"{name} must be a rational number; got the sympy expression {shown(value)}")
    if isinstance(value, numbers.Integral):  # numpy integers: a Python int, never an np.int64 numerator
        return to_rational(int(value), name=name, binary=binary)
    if isinstance(value, numbers.Rational):
        return Fraction(int(value.numerator), int(value.denominator))
    if isinstance(value, numbers.Real):  # numpy floating scalars and the like
        return to_rational(float(value), name=name, binary=binary)
    raise InvalidNumberError(f"{name} must be a number; got {type(value).__name__} {shown(value)}")


def format_rational(q: Fraction) -> str:
    """Write a rational as ``"p/q"`` or ``"p"`` (the certificate file format).

    Examples
    --------
    >>> format_rational(Fraction(32, 5)), format_rational(Fraction(4))
    ('32/5', '4')
    """
    if not isinstance(q, Fraction):  # an int, a float (its exact binary value), "32/5", a Decimal: read with the bounds
        q = to_rational(q, name="q", binary=True)
    num = format_integer(q.numerator)
    return num if q.denominator == 1 else f"{num}/{format_integer(q.denominator)}"


def short_rational(q: Fraction, *, limit: int = 40) -> str:
    """``format_rational(q)`` for messages: exact when short, else ``≈1e-300 (exact: a 301-digit denominator)``.

    >>> short_rational(Fraction(32, 5))
    '32/5'
    >>> short_rational(Fraction(1, 10**300))
    '≈1e-300 (exact: a 301-digit denominator)'
    """
    q = Fraction(q)
    num, den = abs(q.numerator), q.denominator
    num_digits = len(format_integer(num)) if num.bit_length() < 40_000 else int(num.bit_length() * 0.30103) + 1
    den_digits = len(format_integer(den)) if den.bit_length() < 40_000 else int(den.bit_length() * 0.30103) + 1
    if num_digits + den_digits + 1 <= limit:
        return format_rational(q)
    try:
        approx = f"{float(q):.6g}"
    except OverflowError:
        approx = f"{'-' if q < 0 else ''}1e+{num_digits - den_digits}"
    if approx in ("0", "-0"):
        approx = f"1e-{den_digits - num_digits}"
    parts = []
    if num_digits > 20:
        parts.append(f"a {num_digits}-digit numerator")
    if den_digits > 20:
        parts.append(f"a {den_digits}-digit denominator")
    return f"≈{approx} (exact: {' and '.join(parts) or 'long'})"
