"""What every module of the independent checker shares: reading numbers, verdicts, and three decisions.

Written for reading; it imports the standard library and python-flint only.  Every number of a file is
read as an exact rational from its text; every decision is exact (``Fraction``) or an arb ball enclosure
rounded outward, where a ball that does not decide counts as *not proved*.
"""

from __future__ import annotations

import contextlib
import json
from dataclasses import dataclass, field
from fractions import Fraction
from itertools import combinations

MAX_BYTES = 10_000_000
"""Largest file read (the main reader's limit)."""
MAX_DIGITS = 20_000
"""Most characters of one number, and the largest decimal exponent (beyond, refused: no Fraction grows without bound)."""


class Malformed(Exception):
    """The file is not a certificate this checker can read (then nothing is proved)."""


@dataclass
class Verdict:
    """Per premise: its name and whether it holds (``None``: undecided, which is not proved)."""

    kind: str
    premises: list[tuple[str, bool | None, str]] = field(default_factory=list)

    def add(self, name: str, holds: bool | None, why: str = "") -> bool:
        self.premises.append((name, holds, why))
        return holds is True

    @property
    def proved(self) -> bool:
        return bool(self.premises) and all(h is True for _, h, _ in self.premises)

    @property
    def failing(self) -> list[str]:
        return [name for name, h, _ in self.premises if h is not True]


def load(path: str) -> dict:
    """A JSON object from ``path``: bounded, no duplicate keys, no NaN or Infinity."""

    def pairs(items: list) -> dict:
        out: dict = {}
        for key, value in items:
            if key in out:
                raise Malformed(f"duplicate key {key!r}")
            out[key] = value
        return out

    def bad_constant(name: str) -> None:
        raise Malformed(f"the constant {name} is not JSON a certificate may hold")

    with open(path, "rb") as fh:
        raw = fh.read(MAX_BYTES + 1)
    if len(raw) > MAX_BYTES:
        raise Malformed(f"larger than {MAX_BYTES} bytes")
    try:
        data = json.loads(raw.decode("utf-8"), object_pairs_hook=pairs, parse_constant=bad_constant)
    except (UnicodeDecodeError, ValueError) as exc:
        raise Malformed(f"not JSON: {exc}") from None
    if not isinstance(data, dict):
        raise Malformed("not a JSON object")
    return data


def q(value: object) -> Fraction:
    """An exact rational from a file's number: an integer, or a string such as ``"32/5"`` or ``"1.25e-3"``."""
    if isinstance(value, bool) or not isinstance(value, (int, str)):
        raise Malformed(f"not an exact number: {value!r}")
    if isinstance(value, str) and (len(value) > MAX_DIGITS or not value.strip() or "_" in value):
        raise Malformed(f"not an exact number: {value[:40]!r}")
    if isinstance(value, str) and ("e" in value.lower()) and abs(int(_exponent(value))) > MAX_DIGITS:
        raise Malformed(f"an exponent beyond ±{MAX_DIGITS}: {value[:40]!r}")  # "1e10000000" would take seconds
    import sys

    limit = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)  # a number within MAX_DIGITS may be past Python's 4300-digit default
    try:
        return Fraction(value)
    except (ValueError, ZeroDivisionError):
        raise Malformed(f"not an exact number: {str(value)[:40]!r}") from None
    finally:
        sys.set_int_max_str_digits(limit)


def _exponent(text: str) -> int:
    try:
        return int(text.lower().rsplit("e", 1)[1])
    except ValueError:
        raise Malformed(f"not an exact number: {text[:40]!r}") from None


def shown(x: Fraction) -> str:
    """``x`` for a message: ``str(x)``, which raises past Python's 4300-digit limit, so a longer one by its size."""
    bits = x.numerator.bit_length() + x.denominator.bit_length()
    return str(x) if bits < 14_000 else f"(a rational of {bits} bits)"


def det(m: list[list[Fraction]]) -> Fraction:
    """The determinant (Laplace expansion along the first row, skipping its zeros; the matrices here are at most 4×4)."""
    if len(m) == 1:
        return m[0][0]
    return sum((m[0][j] if j % 2 == 0 else -m[0][j]) * det([row[:j] + row[j + 1:] for row in m[1:]])
               for j in range(len(m)) if m[0][j])


def psd(m: list[list[Fraction]]) -> bool:
    """Positive semidefinite, exactly: every principal minor ``≥ 0``."""
    n = len(m)
    return all(det([[m[i][j] for j in idx] for i in idx]) >= 0 for k in range(1, n + 1) for idx in combinations(range(n), k))


def pd(m: list[list[Fraction]]) -> bool:
    """Positive definite, exactly: every leading principal minor ``> 0`` (Sylvester)."""
    return all(det([row[:k] for row in m[:k]]) > 0 for k in range(1, len(m) + 1))


def copositive(m: list[list[Fraction]]) -> bool | None:
    """``yᵀMy ≥ 0`` for every ``y ≥ 0``, for a symmetric ``M`` up to 3×3 (Hadeler's criterion).

    Exact for the 1×1 and 2×2 conditions; the one 3×3 inequality with square roots is decided in arb balls
    at growing precision (``None`` if no precision decides it).
    """
    import flint

    n = len(m)
    if any(m[i][i] < 0 for i in range(n)):
        return False
    for i, j in combinations(range(n), 2):
        if m[i][j] < 0 and m[i][j] ** 2 > m[i][i] * m[j][j]:
            return False
    if n < 3 or all(m[i][j] >= 0 for i in range(3) for j in range(3)) or psd(m):
        return True
    old = flint.ctx.prec
    try:
        for bits in (128, 512, 2048):
            flint.ctx.prec = bits
            a = [[ball(x) for x in row] for row in m]
            r = [a[i][i].sqrt() for i in range(3)]
            bar = [a[0][1] + r[0] * r[1], a[0][2] + r[0] * r[2], a[1][2] + r[1] * r[2]]
            prod = 2 * bar[0] * bar[1] * bar[2]
            # each bar ≥ 0 exactly (the 2×2 test above), so prod ≥ 0; clip a ball that straddles 0 by rounding
            tail = prod.sqrt() if prod > 0 else flint.arb(0).union(flint.arb(prod.upper()).sqrt())
            total = r[0] * r[1] * r[2] + a[0][1] * r[2] + a[0][2] * r[1] + a[1][2] * r[0] + tail
            if total >= 0:
                return True
            if total < 0:
                return False
        return None
    finally:
        flint.ctx.prec = old


def ball(x: Fraction):
    """``x`` as an arb ball (exact when the denominator is a power of two, else an enclosure)."""
    import flint

    return flint.arb(x.numerator) / x.denominator


def lower(b) -> Fraction:
    """The exact lower end of an arb ball, as a Fraction."""
    return _exact(b.lower())


def upper(b) -> Fraction:
    """The exact upper end of an arb ball, as a Fraction."""
    return _exact(b.upper())


def _exact(point) -> Fraction:
    if not point.is_finite():
        raise Malformed("an enclosure is not finite")
    man, exp = (int(v) for v in point.man_exp())
    return Fraction(man) * (Fraction(2) ** exp)


_KEPT: list[dict] = []


@contextlib.contextmanager
def shared():
    """Within the block, premises and searches on numbers seen before (a key holds every number read, the precision
    too) keep their verdicts: ``check`` decides edited copies of files, mostly unchanged; outside it nothing is kept."""
    _KEPT.append({})
    try:
        yield
    finally:
        _KEPT.pop()


def _kept(key: tuple, compute):
    """``compute()``, or within :func:`shared` its value for ``key`` from earlier in the block."""
    if _KEPT and key not in _KEPT[-1]:
        _KEPT[-1][key] = compute()
    return _KEPT[-1][key] if _KEPT else compute()


def _ints(*xs: Fraction) -> tuple[int, ...]:
    """Rationals as exact integers (numerator, denominator): a key hashed far faster than Fractions."""
    return tuple(n for x in xs for n in (x.numerator, x.denominator))
