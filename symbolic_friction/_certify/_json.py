"""One strict JSON reader for every certificate file (stability and hunting): bounded size, no duplicate keys, no ``NaN``/``Infinity``, no huge integers; and the exact value of its decimals (:func:`decimal_value`)."""

from __future__ import annotations

import json
import os
from fractions import Fraction
from typing import Any

from .._infra.errors import CertificateFormatError
from .._infra.rational import parse_integer


MAX_FILE_BYTES = 10_000_000
"""Largest certificate file read."""
MAX_VALUES = 10_000
"""Most JSON values (objects, arrays, strings, numbers) in a certificate: one holds about 40, and
validating 10⁵ array items against the schema would take seconds."""


def _count_values(data: object) -> int:
    """The number of JSON values in ``data``, counted without recursion and stopping past :data:`MAX_VALUES`."""
    count, stack = 0, [data]
    while stack and count <= MAX_VALUES:
        value = stack.pop()
        count += 1
        if isinstance(value, dict):
            stack.extend(value.values())
        elif isinstance(value, list):
            stack.extend(value)
    return count


def _reject_constant(name: str) -> None:
    raise CertificateFormatError(f"not valid JSON: the constant {name} is not allowed in a certificate")


def _no_duplicates(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise CertificateFormatError(f"duplicate key {key!r} in a JSON object")
        out[key] = value
    return out


def parse_json(text: str | bytes, *, source: str = "<string>") -> object:
    """The JSON value of a certificate file's text, read strictly and within bounds.

    Shared by every kind of certificate file (stability certificates here,
    hunting certificates in :mod:`.._hunting._certificate`): UTF-8 only, at
    most :data:`MAX_FILE_BYTES`, no duplicate keys, no ``NaN``/``Infinity``,
    integers within Python's digit limit, nesting within the recursion limit, at most
    :data:`MAX_VALUES` values in all.

    Raises
    ------
    CertificateFormatError
        Naming ``source`` and, for a syntax error, the line and column.
    """
    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise CertificateFormatError(f"{source}: not valid JSON: not UTF-8 ({exc.reason} at byte {exc.start})")
    if len(text) > MAX_FILE_BYTES:
        raise CertificateFormatError(f"{source}: {len(text)} characters; a certificate has at most {MAX_FILE_BYTES}")
    try:
        data = json.loads(
            text, parse_constant=_reject_constant, object_pairs_hook=_no_duplicates,
            parse_int=_json_int,
        )
    except json.JSONDecodeError as exc:
        raise CertificateFormatError(
            f"{source}: not valid JSON: {exc.msg} at line {exc.lineno}, column {exc.colno}"
        ) from None
    except RecursionError:
        raise CertificateFormatError(f"{source}: not a certificate: JSON nested too deeply") from None
    except CertificateFormatError as exc:
        raise CertificateFormatError(f"{source}: {exc}") from None
    if _count_values(data) > MAX_VALUES:
        raise CertificateFormatError(
            f"{source}: more than {MAX_VALUES} JSON values (a certificate holds about 40); not a certificate"
        )
    return data


def read_json(path: str | os.PathLike[str]) -> object:
    """Read a certificate file once, with the package's bounds, and :func:`parse_json` it.

    Raises
    ------
    InputFileError
        If ``path`` is not a readable regular file of at most
        :data:`MAX_FILE_BYTES` bytes (a FIFO, a device, a directory, …).
    CertificateFormatError
        If the content is not strict JSON.
    """
    from .._infra.io import read_limited

    return parse_json(read_limited(path, limit=MAX_FILE_BYTES, what="certificate"), source=str(path))


def _json_int(text: str) -> object:
    """JSON integers are never part of a certificate (exact values are strings); a huge one is not even read."""
    return int(text) if len(text) <= 4000 else float("inf")


def decimal_value(text: str) -> Fraction:
    """The exact value of a plain decimal string of the format (a κ, ``overshoot_bound``), at any length.

    ``Fraction(text)`` refuses more than 4300 digits (Python's limit on ``int(str)``), which the format allows (up
    to 20,000 characters): a κ of 4400 digits crashed every verifier of a κ with a ``ValueError`` (found by the
    tampered corpora, tests/independent/tampered.py).  The digits are read as the exact rationals are.
    """
    whole, _, fraction = text.removeprefix("-").partition(".")
    value = Fraction(parse_integer(whole + fraction), 10 ** len(fraction))
    return -value if text.startswith("-") else value
