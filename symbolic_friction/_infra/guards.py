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
* :func:`check_path` — a path argument is a ``str`` or an ``os.PathLike`` (``load_scene(3)``);
* :func:`check_instance` — an argument of a given type (``prove_cycle(params, "x")``), refused with a
  :class:`ParameterTypeError`, which is a ``TypeError`` too;
* :func:`check_items` — a list argument: a list, tuple or other iterable of at most ``high`` items (or one
  item taken as a list of one), never ``None`` or a string read character by character;
* :func:`check_states` — a list of initial states, each three finite numbers, as floats.

These run once per call, at the API's entry, never in an inner loop.  Only the standard library is
imported.
"""

from __future__ import annotations

import itertools
import math
import numbers
import os
from collections.abc import Callable, Iterable, Mapping
from fractions import Fraction
from typing import Any

from .errors import InputFileError, InvalidNumberError, NonFiniteError, ParameterError, SymbolicFrictionError
from .rational import shown, to_rational

__all__ = ["MAX_BYTES", "shown", "check_count", "check_real", "check_memory", "check_path", "nbytes_text", "ParameterTypeError",
           "check_instance", "check_items", "check_states"]


class ParameterTypeError(ParameterError, TypeError):
    """An argument of the Python API is not of the type it must be (``verify_certificate("x")``).

    A :class:`~symbolic_friction.SymbolicFrictionError` (one line on the command line) and a ``TypeError``, as
    Python's own refusal of a wrong type would be, so that ``except TypeError`` keeps working.
    """

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


def _got(value: Any) -> str:
    """``"str 'x'"``: the type and the abbreviated value, for a message."""
    return f"{type(value).__name__} {shown(value)}"


def check_instance(value: Any, kinds: type | tuple[type, ...], *, name: str, what: str,
                   error: type[SymbolicFrictionError] = ParameterTypeError) -> Any:
    """``value`` if it is an instance of ``kinds``.

    Raises
    ------
    error
        ``"{name} must be {what}; got {type} {value}"`` (by default a :class:`ParameterTypeError`).
    """
    if not isinstance(value, kinds):
        raise error(f"{name} must be {what}; got {_got(value)}")
    return value


def check_items(value: Any, *, name: str, what: str, high: int, kind: type | tuple[type, ...] | None = None,
                single: type | tuple[type, ...] = (), each: Callable[[Any], Any] | None = None,
                why: str = "a bound on time", error: type[SymbolicFrictionError] = ParameterError) -> list:
    """``value`` as a list of at most ``high`` items (each an instance of ``kind`` if given, and read by ``each``).

    A list, a tuple or any other iterable (a generator, ``Path.glob(...)``) is read up to ``high + 1`` items
    (an endless generator is refused, not exhausted); a value of a ``single`` type is one item (a list of one).
    ``None``, a number, a ``str`` or ``bytes`` (which would be read character by character) and a mapping are
    refused.  ``each`` converts (and checks) one item; the package's error it raises is raised again with the
    item's place in front (``"methods[1]: …"``).  Without ``kind`` or ``each`` the items are the caller's to check.

    Raises
    ------
    ParameterTypeError
        ``"{name} must be {what}; got …"`` for a value that is not a list of items, or
        ``"{name}[i] must be a {kind}; got …"`` for an item that is not a ``kind``.
    error
        ``"{name} has more than {high} items; at most {high} are accepted ({why})"``.
    SymbolicFrictionError
        ``"{name}[i]: …"``, of the class ``each`` raised.
    """
    if single and isinstance(value, single):
        items = [value]
    elif isinstance(value, (str, bytes, bytearray, Mapping)) or not isinstance(value, Iterable):
        raise ParameterTypeError(f"{name} must be {what}; got {_got(value)}")
    else:
        items = list(itertools.islice(value, high + 1))
    if len(items) > high:
        raise error(f"{name} has more than {high} items; at most {high} are accepted ({why})")
    if kind is not None:
        kinds = kind if isinstance(kind, tuple) else (kind,)
        for i, item in enumerate(items):
            check_instance(item, kinds, name=f"{name}[{i}]", what="a " + " or a ".join(k.__name__ for k in kinds))
    for i, item in enumerate(items if each is not None else ()):
        try:
            items[i] = each(item)  # type: ignore[misc]
        except SymbolicFrictionError as exc:
            raise type(exc)(f"{name}[{i}]: {exc}") from None
    return items


def check_states(value: Any, *, name: str, high: int, bound: float | None = None, labels: str = "(e_i, s, v)",
                 error: type[SymbolicFrictionError] = ParameterError) -> tuple[tuple[float, float, float], ...]:
    """``value``, a non-empty list of at most ``high`` states of three finite numbers, as floats.

    Each number is read as :func:`check_real` reads it (exactly compared before it is converted, so ``10**400``
    is refused, never read as ``inf``), and is at most ``bound`` in size if given.

    Raises
    ------
    ParameterTypeError
        If ``value`` is not a list of states (``"x"``, ``None``).
    error
        ``"{name} must hold at least one initial state …"``, ``"{name} has more than {high} items …"`` or
        ``"{name}[i] must be three finite numbers (e_i, s, v) …; got …"``.
    """
    rows = check_items(value, name=name, what=f"a list of initial states {labels}", high=high, error=error)
    if not rows:
        raise error(f"{name} must hold at least one initial state {labels}; got none")
    size = "" if bound is None else f", each at most {bound:g} in size"
    low = None if bound is None else -bound
    out = []
    for i, row in enumerate(rows):
        try:
            triple = not isinstance(row, (str, bytes, Mapping)) and len(row) == 3
        except TypeError:  # no length: a number, a 0-d array
            triple = False
        if not triple:
            raise error(f"{name}[{i}] must be three finite numbers {labels}{size}; got {_got(row)}")
        try:
            out.append(tuple(check_real(c, name=f"{name}[{i}]", low=low, low_open=False, high=bound, error=error)
                             for c in row))
        except SymbolicFrictionError:
            raise error(f"{name}[{i}] must be three finite numbers {labels}{size}; got {_got(row)}") from None
    return tuple(out)  # type: ignore[return-value]
