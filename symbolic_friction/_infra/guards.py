"""Guards at the public API's entry: each argument checked before anything is allocated or looped over.

The command line reads every option through :mod:`.options`; a call from Python goes through the
same kind of check here, so that a bad argument ends in the package's own error (a
:class:`~symbolic_friction.SymbolicFrictionError`, which the command line prints as one line), naming
the argument, the value (abbreviated) and the accepted range, never in an ``OverflowError`` from deep
in a kernel, a ``MemoryError`` from numpy's allocator, or a hang:

* :func:`check_count` — an integer in ``[low, high]`` (``bool`` refused; ``10**12`` grid points refused
  before any array exists);
* :func:`check_real` — a finite real in a range, compared *exactly* before it is converted, so that
  ``10**400`` and ``Decimal("1e999999999")`` are refused as out of range, never read as ``inf`` (and
  never expanded: :func:`~.rational.to_rational` bounds digits and exponents first);
* :func:`check_memory` — the bytes an allocation would take (element count × bytes per element),
  against :data:`MAX_BYTES`, before numpy is asked for it;
* :func:`check_path` — a path argument is a ``str`` or an ``os.PathLike`` (``load_scene(3)``).

These run once per call, at the API's entry, never in an inner loop.  Only the standard library is
imported.
"""

from __future__ import annotations

import math
import numbers
import os
from fractions import Fraction
from typing import Any

from .errors import InputFileError, InvalidNumberError, NonFiniteError, ParameterError, SymbolicFrictionError
from .rational import shown, to_rational

__all__ = ["MAX_BYTES", "shown", "check_count", "check_real", "check_memory", "check_path", "nbytes_text"]

MAX_BYTES = 4 * 2**30
"""The most memory (4 GiB) the arrays of one call's result may take: a larger request is refused up front
(naming the argument that sized it), never handed to numpy's allocator.  Larger batches stream through
:func:`~symbolic_friction.simulation.iter_batches` in bounded memory."""


def nbytes_text(n: float) -> str:
    """``n`` bytes in words: ``'44.7 GiB'``."""
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{int(n)} B"


def check_count(value: Any, *, name: str, low: int = 1, high: int, error: type[SymbolicFrictionError] = ParameterError,
                why: str = "a bound on time and memory") -> int:
    """``value`` as an ``int`` in ``[low, high]``; ``bool``, floats and strings refused.

    Raises
    ------
    error
        ``"{name} must be an integer ≥ {low}; got …"`` below the range, or
        ``"{name} must be an integer from {low} to {high} (…); got …"`` above it.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise error(f"{name} must be an integer ≥ {low}; got {shown(value)}")
    value = int(value)
    if value < low:
        raise error(f"{name} must be an integer ≥ {low}; got {shown(value)}")
    if value > high:
        raise error(f"{name} must be an integer from {low} to {high} ({why}); got {shown(value)}")
    return value


def check_real(value: Any, *, name: str, low: float | Fraction | None = 0, high: float | Fraction | None = None,
               low_open: bool = True, error: type[SymbolicFrictionError] = ParameterError, why: str = "") -> float:
    """``value`` as a finite ``float`` above ``low`` (at or above with ``low_open=False``) and at most ``high``.

    A float is checked as it is (the fast path of every simulation call); anything else is read exactly by
    :func:`~.rational.to_rational` (so ``"6.4"``, ``Fraction`` and ``Decimal`` are accepted; ``bool``,
    complex, NaN and ``1e999999999`` are refused) and compared with the range *before* it is converted,
    so that ``10**400`` is refused as too large rather than overflowing.  ``None``: no bound.

    Raises
    ------
    error
        ``"{name} must be finite and > {low}; got …"``, ``"{name} must be at most {high} ({why}); got …"``
        or ``"{name} must be a number; got …"``.
    """
    below = "" if low is None else f" and {'>' if low_open else '≥'} {float(low):g}"
    if type(value) is float:
        q: float | Fraction = value
        if not math.isfinite(value):
            raise error(f"{name} must be finite{below}; got {shown(value)}")
    else:
        try:
            q = to_rational(value, name=name, binary=True)
        except NonFiniteError:
            raise error(f"{name} must be finite{below}; got {shown(value)}") from None
        except InvalidNumberError as exc:
            if "refused" in str(exc) or "accepted" in str(exc):  # too many digits, too large an exponent
                raise error(str(exc)) from None
            raise error(f"{name} must be a number; got {shown(value)}") from None
    if low is not None and (q <= low if low_open else q < low):
        raise error(f"{name} must be finite{below}; got {shown(value)}")
    if high is not None and q > high:
        raise error(f"{name} must be at most {float(high):g}{f' ({why})' if why else ''}; got {shown(value)}")
    try:
        result = float(q)
    except OverflowError:
        result = math.inf
    if math.isinf(result):
        raise error(f"{name} must be at most about 1.8e308 (the range of float64); got {shown(value)}")
    if result == 0.0 and q != 0:
        raise error(f"{name} = {shown(value)} is below what a float64 can hold (about 5e-324)")
    return result


def check_memory(*, name: str, value: Any, count: float, item_bytes: int, what: str,
                 error: type[SymbolicFrictionError] = ParameterError, hint: str = "") -> None:
    """Refuse an allocation of ``count`` elements of ``item_bytes`` bytes beyond :data:`MAX_BYTES`, naming ``name``.

    ``count`` is the product of the dimensions (a Python ``int`` or ``float``, never an overflowing numpy
    integer); ``what`` says what the array holds, e.g. ``"1000 trajectories × 1000000 samples"``.
    """
    need = float(count) * item_bytes
    if need > MAX_BYTES:
        raise error(
            f"{name} = {shown(value)}: {what} would need {nbytes_text(need)}; at most "
            f"{nbytes_text(MAX_BYTES)} are allowed (MAX_BYTES, a bound on memory){': ' + hint if hint else ''}"
        )


def check_path(path: Any, *, name: str = "path", what: str = "file") -> str | os.PathLike:
    """``path`` if it is a ``str`` or an ``os.PathLike`` naming a ``str`` path without NUL bytes.

    Raises
    ------
    InputFileError
        For any other type (``3``, ``None``, ``b"x.json"``) or a NUL byte, naming ``name``.
    """
    if isinstance(path, os.PathLike) and not isinstance(path, (bytes, str)):
        try:
            text = os.fspath(path)
        except TypeError:
            text = None
    else:
        text = path
    if not isinstance(text, str):
        raise InputFileError(f"{name} ({what}) must be a str or a pathlib.Path; got {type(path).__name__} {shown(path)}")
    if "\0" in text:
        raise InputFileError(f"{name} ({what}) contains a NUL byte, which no file name can hold: {shown(text)}")
    return path
