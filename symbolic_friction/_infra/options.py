"""Readers of numeric command-line options: counts, horizons and tolerances, each bounded before any work.

Every count (``--samples``, ``--trajectories``, ``--repeats`` …) and every
real option (``--t-end``, ``--horizon``, ``--rtol`` …) is read here, as an
``argparse`` type, so that a bad value is a usage error (one line, exit 2)
before anything is allocated or looped over:

* ASCII digits only (``"٣"``, ``"３"`` and ``"1_000"``, which :func:`int` and
  :func:`float` would accept, are refused);
* reals go through :func:`~symbolic_friction._infra.rational.to_rational`,
  the package's one reader of numbers, so ``nan``, ``inf``, ``1e999999999``
  and ``1e-999999999`` are refused with its messages;
* each value is compared with its floor and its ceiling exactly, before it
  is converted (``1e999`` is refused as above the ceiling, never read as
  ``inf``).

The ceilings live next to the options that use them (the command modules)
and are printed in their help text.  Only the standard library is imported.
"""

from __future__ import annotations

import argparse
import re
from collections.abc import Callable
from fractions import Fraction

from .errors import SymbolicFrictionError
from .rational import to_rational

__all__ = ["read_count", "read_real", "count_option", "real_option", "read_reals"]

_INTEGER_RE = re.compile(r"^\s*\+?\d{1,40}\s*$", re.ASCII)


def _shown(text: str) -> str:
    return repr(text if len(text) <= 40 else text[:40] + "…")


def read_count(text: str, *, name: str, high: int, low: int = 1) -> int:
    """An integer in ``[low, high]`` written with ASCII digits.

    Raises
    ------
    argparse.ArgumentTypeError
        Naming the option, the accepted range and what was given.
    """
    if not _INTEGER_RE.match(text):
        raise argparse.ArgumentTypeError(
            f"{name} must be an integer from {low} to {high} (ASCII digits); got {_shown(text)}"
        )
    value = int(text)
    if not low <= value <= high:
        raise argparse.ArgumentTypeError(
            f"{name} must be an integer from {low} to {high} (a bound on time and memory); got {_shown(text.strip())}"
        )
    return value


def read_real(text: str, *, name: str, high: float | Fraction, low: float | Fraction = 0, low_open: bool = True,
              high_open: bool = False) -> float:
    """A finite real in ``(low, high]`` (or the closed/open variant asked for), read exactly, returned as a float.

    Raises
    ------
    argparse.ArgumentTypeError
        Naming the option, the accepted range and what was given.
    """
    try:
        q = to_rational(text, name=name)
    except SymbolicFrictionError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    lo, hi = Fraction(low), Fraction(high)
    if (q <= lo if low_open else q < lo) or (q >= hi if high_open else q > hi):
        interval = f"{'(' if low_open else '['}{float(lo):g}, {float(hi):g}{')' if high_open else ']'}"
        raise argparse.ArgumentTypeError(f"{name} must lie in {interval}; got {_shown(text.strip())}")
    value = float(q)
    if value == 0 and q != 0:
        raise argparse.ArgumentTypeError(f"{name} = {_shown(text.strip())} is below what a float64 can hold")
    return value


def count_option(name: str, *, high: int, low: int = 1) -> Callable[[str], int]:
    """``type=`` for an ``argparse`` option: :func:`read_count` with this name and range."""

    def parse(text: str) -> int:
        return read_count(text, name=name, high=high, low=low)

    parse.__name__ = "count"
    return parse


def real_option(name: str, *, high: float | Fraction, low: float | Fraction = 0, low_open: bool = True,
                high_open: bool = False) -> Callable[[str], float]:
    """``type=`` for an ``argparse`` option: :func:`read_real` with this name and range."""

    def parse(text: str) -> float:
        return read_real(text, name=name, high=high, low=low, low_open=low_open, high_open=high_open)

    parse.__name__ = "real"
    return parse


def read_reals(text: str, *, name: str, size: int, bound: float | Fraction) -> tuple[float, ...]:
    """``size`` comma-separated reals, each in ``[-bound, bound]`` (an initial state ``e_i,s,v``).

    Raises
    ------
    argparse.ArgumentTypeError
        If the count is wrong or a part is not a number in range.
    """
    parts = text.split(",")
    if len(parts) != size:
        count = {1: "one", 2: "two", 3: "three"}.get(size, str(size))
        raise argparse.ArgumentTypeError(f"{name} takes {count} numbers, comma-separated; got {len(parts)} in {_shown(text)}")
    return tuple(read_real(p, name=name, low=-Fraction(bound), high=bound, low_open=False) for p in parts)
