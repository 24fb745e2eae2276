"""Which claims an obligation's verdict rests on: the decisions its ``verify`` made, recorded as it runs.

The obligations decide every sign and identity through four procedures:
:func:`.._decide.sign_of`, :func:`.._decide.is_zero`, :func:`.._inequalities.is_nonneg`
(and ``is_nonpos`` through it) and :func:`.._closed_form_cases.frac_sign`.
:func:`recording` replaces each of them, in every loaded module of the package
that imported it, by a wrapper that calls the original and keeps what it
*decided* as a :class:`Claim`, then restores the originals.  Only decisions
count: ``sign_of`` giving ``1``, ``0`` or ``-1``; ``is_zero`` giving ``True``,
or ``False`` for a rational function (then it is a decision too: "not the zero
function"); ``is_nonneg`` giving ``True``; ``frac_sign`` giving a sign.  "Not
decided" answers (``None``, ``False`` from a certificate search) assert
nothing.  A call made from inside another recorded call (``sign_of`` of a
denominator within ``is_nonneg``) is the inner step of a claim already
recorded and is not kept.

A claim is universal over its symbols with their sympy assumptions
(``positive`` symbols range over ``(0, ∞)``, the convention of
:mod:`.._decide`), wherever the expression is defined; ``"nonzero"`` is the
existential "some admissible point where the expression is not 0".  ``frac_sign`` reads the sign of
a fraction of python-flint polynomials from the signs of its numerator and
denominator; each of those is kept as a claim of its own about a
:class:`RawPolynomial` (their product is the sign it returned).
"""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import sympy as sp

__all__ = ["KINDS", "Claim", "RawPolynomial", "declare_claim", "recording"]

KINDS = ("sign", "nonneg", "zero", "nonzero")
"""``sign``: the expression has the sign ``sign`` (1, 0, -1); ``nonneg``: it is ``≥ 0``; ``zero``: it is
identically 0; ``nonzero``: it is not identically 0 (an existential claim)."""


@dataclass(frozen=True)
class RawPolynomial:
    """An integer polynomial in positive generators (the numerator or denominator ``frac_sign`` decided).

    ``terms`` is a tuple of ``(exponents, coefficient)`` over ``gens``.
    """

    gens: tuple[str, ...]
    terms: tuple[tuple[tuple[int, ...], int], ...]


@dataclass(frozen=True)
class Claim:
    """One decision an obligation's verdict rests on.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    expr : sympy expression or RawPolynomial
        What the claim is about.
    sign : int or None
        For ``kind == "sign"``: 1, 0 or -1.
    source : str
        The procedure that decided it (``"sign_of"``, ``"is_zero"``, ``"is_nonneg"``, ``"frac_sign numerator"``,
        ``"frac_sign denominator"``, ``"declared"``).
    """

    kind: str
    expr: Any
    sign: int | None = None
    source: str = "declared"


_ACTIVE: list[list[Claim]] = []
_DEPTH = [0]


def declare_claim(expr: Any, kind: str, sign: int | None = None) -> None:
    """Record a claim directly (for code that decides without the four procedures, and for tests).

    Does nothing outside :func:`recording`.
    """
    if kind not in KINDS:
        raise ValueError(f"unknown claim kind {kind!r}; expected one of {KINDS}")
    if _ACTIVE:
        _ACTIVE[-1].append(Claim(kind, sp.sympify(expr), sign, "declared"))


def _is_rational_function(expr: Any) -> bool:
    """The decision procedures' own test (:func:`.._decide._is_rational_function`), for sympy expressions only."""
    from .._decide import _is_rational_function as rational

    return isinstance(expr, sp.Expr) and rational(expr)


def _entries(expr: Any) -> list[Any]:
    """A matrix's entries (each is a claim of its own), else ``[expr]``."""
    expr = sp.sympify(expr)
    return list(expr) if isinstance(expr, sp.MatrixBase) else [expr]


def _raw(poly: Any) -> tuple[RawPolynomial, int | None]:
    """``poly`` (python-flint ``fmpz_mpoly``) as a :class:`RawPolynomial`, and the sign all its coefficients share."""
    gens = tuple(str(n) for n in poly.context().names())
    terms = tuple((tuple(map(int, m)), int(c)) for m, c in zip(poly.monoms(), poly.coeffs()))
    signs = {(c > 0) - (c < 0) for _, c in terms}
    return RawPolynomial(gens, terms), (0 if not terms else signs.pop() if len(signs) == 1 else None)


def _fraction_claims(frac: Any) -> list[Claim]:
    """``frac_sign`` decides the sign of a numerator and of a denominator (each with coefficients of one sign):
    a claim each, a constant denominator none."""
    out = []
    for which, poly in (("frac_sign numerator", frac.numer), ("frac_sign denominator", frac.denom)):
        raw, sign = _raw(poly)
        if sign is None:  # frac_sign decided nothing (it would have said None)
            return []
        if which.endswith("denominator") and all(not any(m) for m, _ in raw.terms):
            continue
        out.append(Claim("sign", raw, sign, which))
    return out


def _claims_of(source: str, args: tuple, result: Any) -> list[Claim]:
    """The claims one call decided (none when it decided nothing)."""
    if source == "sign_of":
        return [Claim("sign", sp.sympify(args[0]), int(result), source)] if result is not None else []
    if source == "is_zero":
        if result is True:
            return [Claim("zero", e, None, source) for e in _entries(args[0])]
        expr = sp.sympify(args[0])
        return [Claim("nonzero", expr, None, source)] if _is_rational_function(expr) else []
    if source == "is_nonneg":
        return [Claim("nonneg", sp.sympify(args[0]), None, source)] if result is True else []
    if source == "frac_sign":
        return _fraction_claims(args[0]) if result is not None else []
    raise ValueError(source)


def _wrap(source: str, original: Any) -> Any:
    def recorded(*args: Any, **kwargs: Any) -> Any:
        if _DEPTH[0] or not _ACTIVE:
            return original(*args, **kwargs)
        _DEPTH[0] += 1
        try:
            result = original(*args, **kwargs)
        finally:
            _DEPTH[0] -= 1
        _ACTIVE[-1].extend(_claims_of(source, args, result))
        return result

    recorded.__wrapped__ = original  # type: ignore[attr-defined]
    recorded.__name__ = getattr(original, "__name__", source)
    return recorded


def _procedures() -> list[tuple[str, Any]]:
    from .. import _closed_form_cases, _decide, _inequalities, registry

    registry()  # every obligation module is imported, so every binding of a procedure is patched
    return [("sign_of", _decide.sign_of), ("is_zero", _decide.is_zero), ("is_nonneg", _inequalities.is_nonneg),
            ("frac_sign", _closed_form_cases.frac_sign)]


@contextlib.contextmanager
def recording() -> Iterator[list[Claim]]:
    """Within the block, every decision of the four procedures is appended to the yielded list.

    The procedures are patched in every module of the package that holds them (``from ._decide import
    sign_of`` binds a name per module) and restored on exit, also on an exception.  Blocks nest: the
    innermost one receives the claims.
    """
    patched: list[tuple[Any, str, Any]] = []
    claims: list[Claim] = []
    if not _ACTIVE:
        for source, original in _procedures():
            wrapper = _wrap(source, original)
            for module in list(sys.modules.values()):
                if not getattr(module, "__name__", "").startswith("symbolic_friction"):
                    continue
                for attr, value in list(vars(module).items()):
                    if value is original:
                        setattr(module, attr, wrapper)
                        patched.append((module, attr, original))
    _ACTIVE.append(claims)
    try:
        yield claims
    finally:
        _ACTIVE.pop()
        for module, attr, original in reversed(patched):
            setattr(module, attr, original)
