"""Exact decision procedures shared by the proof obligations.

The obligations decide inequalities for *symbolic* gains.  This module keeps
that decision sound and deliberately simple:

* :func:`sign_of` decides the sign of a rational function all of whose free
  symbols are declared positive, by a **sign-definite decomposition**: a
  rational function is written as a reduced fraction of two integer
  polynomials (python-flint ``fmpz_mpoly``; other expressions are split by
  ``together``), and the numerator and the denominator must each have all
  their coefficients of one sign.  A polynomial with only positive coefficients is positive
  wherever its variables are positive, so the answer is correct whenever
  one is given; ``None`` means "not decided" and the obligation then fails
  instead of guessing.
* Regions of the state space are written with fresh positive symbols
  (``c + p``, ``c - p``, ``(a·hi + b·lo)/(a + b)``), each of which covers its
  region exactly, so a sign decided on the parametrisation holds on the whole
  region.
* :func:`decide` turns relations into ``True``/``False``/``None`` with
  :func:`sign_of`; :func:`resolve_piecewise` picks Piecewise branches with it;
  :func:`minimum_on` computes the exact minimum of a differentiable function
  over a finite set or a closed interval (endpoints and interior stationary
  points are the only candidates).

No floating-point number is used anywhere.
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Iterator, Sequence
from typing import Any, NamedTuple

import sympy as sp

from .._model import symbolic as _symbolic
from . import _fastforms as ff
from . import _fastpoly as fp

__all__ = [
    "Undecided",
    "G",
    "pos",
    "sign_of",
    "is_zero",
    "decide",
    "resolve_piecewise",
    "minimum_on",
    "vertices",
    "affine_image",
    "interval_partitions_reals",
    "phi_classes",
    "sign_classes",
    "latex",
    "remembering",
]


class Undecided(Exception):
    """A sign or a branch could not be decided; the obligation must fail."""


@functools.lru_cache(maxsize=None)
def G() -> _symbolic.Gains:
    """The package's canonical symbols (cached)."""
    return _symbolic.gains()


def pos(name: str) -> sp.Symbol:
    """A fresh positive symbol used to parametrise a region."""
    return sp.Symbol(name, positive=True)


_is_rational_function = fp.is_rational_function  # built from symbols and rationals by + - × ÷ and integer powers


def is_zero(expr: Any) -> bool:
    """Exact identity test ``expr == 0``.

    For a rational function, the numerator of its fraction of polynomials
    (:func:`_field_element`) is the zero polynomial exactly when the function
    is zero, which decides the identity; radicals or other
    functions fall back to ``simplify`` (a ``True`` answer is then still an
    identity, a ``False`` one may only mean "not shown").
    """
    expr = sp.sympify(expr)
    if expr == 0:
        return True
    if _is_rational_function(expr):
        # a fraction P/Q of polynomials is the zero function iff P is the zero polynomial
        return _field_element(expr).numer.is_zero()
    # together() writes a rational function as P/Q with polynomials P, Q; it is
    # identically zero iff the expanded P is (no cancellation needed).
    num = sp.expand(sp.fraction(ff.together(expr))[0])
    if num == 0:
        return True
    if _is_rational_function(num) or num.has(sp.Piecewise, sp.Abs, sp.sign, sp.Max, sp.Min):
        return False
    return sp.simplify(num) == 0


class _Fraction(NamedTuple):
    """A rational function as ``numer/denom``, two coprime python-flint ``fmpz_mpoly`` (integer coefficients)."""

    numer: Any
    denom: Any


_REMEMBERED: list[dict[sp.Expr, "_Fraction"]] = []
"""One dict per active :func:`remembering` block (the innermost last): the fractions converted within it."""


@contextlib.contextmanager
def remembering() -> Iterator[None]:
    """Within the block, :func:`_field_element` converts each expression once (``check`` runs its obligations in one:
    they decide many equal expressions, ``2f_c > 0`` alone some fifty times); outside it, every call converts."""
    _REMEMBERED.append({})
    try:
        yield
    finally:
        _REMEMBERED.pop()


def _field_element(expr: sp.Expr) -> _Fraction:
    """``expr`` (a rational function of its free symbols) as a reduced fraction over ``ℤ[symbols]``: the pair of
    :func:`._fastpoly.rational_pair` in the free symbols in sympy's default order (a denominator that is the zero
    polynomial raises :class:`ZeroDivisionError`, anything but a rational function :class:`TypeError`); the same
    pair for an equal expression within a :func:`remembering` block."""
    memo = _REMEMBERED[-1] if _REMEMBERED else None
    if memo is not None and expr in memo:
        return memo[expr]
    symbols = fp.rational_symbols(expr)  # its free symbols, if it is a rational function (remembered)
    element = _Fraction(*fp.rational_pair(expr, _default_order(frozenset(expr.free_symbols) if symbols is None else symbols)))
    if memo is not None:
        memo[expr] = element
    return element


@functools.lru_cache(maxsize=1024)
def _default_order(symbols: frozenset) -> tuple[sp.Symbol, ...]:
    """``sorted(symbols, key=sp.default_sort_key)``, remembered (the decisions meet the same few sets of symbols)."""
    return tuple(sorted(symbols, key=sp.default_sort_key))


def _coefficient_sign(coefficients: Sequence[Any]) -> int | None:
    """1 or -1 if all the rational coefficients have that sign, 0 if there are none, else ``None``."""
    if not coefficients:
        return 0
    if all(c > 0 for c in coefficients):
        return 1
    if all(c < 0 for c in coefficients):
        return -1
    return None


def _number_sign(x: sp.Expr) -> int | None:
    if x.is_zero:
        return 0
    return 1 if x.is_positive else (-1 if x.is_negative else None)


def _poly_sign(p: sp.Expr) -> int | None:
    """Sign of an expanded polynomial whose rational coefficients all have one sign."""
    if p == 0:
        return 0
    if p.is_number:
        return _number_sign(p)
    try:
        coeffs = sp.Poly(p, *sorted(p.free_symbols, key=sp.default_sort_key)).coeffs()
    except sp.PolynomialError:  # radicals or other non-polynomial parts
        return None
    if not all(c.is_Rational for c in coeffs):
        return None
    if all(c > 0 for c in coeffs):
        return 1
    if all(c < 0 for c in coeffs):
        return -1
    return None


def _has_denominator(expr: sp.Expr) -> bool:
    return any(isinstance(a, sp.Pow) and a.exp.is_negative for a in sp.preorder_traversal(expr))


def sign_of(expr: Any) -> int | None:
    """Sign (1, 0 or -1) of ``expr`` on the positive orthant, or ``None`` if not decided.

    Every free symbol must be declared positive; otherwise ``None``.  A
    rational function is written as a reduced fraction ``P/Q`` of integer
    polynomials (:func:`_field_element`, common factors cancelled: ``P/Q``
    equals ``expr`` wherever ``expr`` is defined); a polynomial whose
    coefficients all share a sign has that sign on the orthant, and ``P = 0``
    means ``expr`` is identically zero.  Other expressions (radicals) are
    decided the same way on the numerator and denominator of ``together``,
    without cancelling.
    """
    expr = sp.sympify(expr)
    if expr.is_number:
        return _number_sign(expr)
    symbols = fp.rational_symbols(expr)  # one pass: its free symbols if it is a rational function, else None
    if any(s.is_positive is not True for s in (expr.free_symbols if symbols is None else symbols)):
        return None
    if symbols is None and expr.has(sp.Piecewise, sp.Abs, sp.sign, sp.Max, sp.Min):
        return None
    if symbols is not None:
        # numerator and denominator of the reduced fraction in Q(symbols): a
        # polynomial whose coefficients share a sign has that sign on the orthant
        element = _field_element(expr)
        sn, sd = (_coefficient_sign(list(p.coeffs())) for p in (element.numer, element.denom))
    elif not _has_denominator(expr):
        return _poly_sign(sp.expand(expr))
    else:
        num, den = sp.fraction(ff.together(expr))
        sn, sd = _poly_sign(sp.expand(num)), _poly_sign(sp.expand(den))
    if sn is None or sd is None or sd == 0:
        return None
    return sn * sd


_REL = {
    sp.StrictGreaterThan: {1: True, 0: False, -1: False},
    sp.GreaterThan: {1: True, 0: True, -1: False},
    sp.StrictLessThan: {1: False, 0: False, -1: True},
    sp.LessThan: {1: False, 0: True, -1: True},
    sp.Equality: {1: False, 0: True, -1: False},
    sp.Unequality: {1: True, 0: False, -1: True},
}


def decide(cond: Any) -> bool | None:
    """Truth value of a relation (or And/Or/Not of relations) via :func:`sign_of`; ``None`` if undecided."""
    if cond is True or cond is sp.true:
        return True
    if cond is False or cond is sp.false:
        return False
    if isinstance(cond, (sp.And, sp.Or)):
        vals = [decide(a) for a in cond.args]
        if isinstance(cond, sp.And):
            return False if False in vals else (None if None in vals else True)
        return True if True in vals else (None if None in vals else False)
    if isinstance(cond, sp.Not):
        val = decide(cond.args[0])
        return None if val is None else not val
    for kind, table in _REL.items():
        if isinstance(cond, kind):
            sg = sign_of(cond.lhs - cond.rhs)
            return None if sg is None else table[sg]
    return None


def resolve_piecewise(expr: Any) -> sp.Expr:
    """Replace every ``Piecewise`` by its first branch whose condition :func:`decide` shows true.

    Raises
    ------
    Undecided
        If a condition met before the chosen branch cannot be decided.
    """

    def pick(*pairs: Any) -> Any:
        for pair in pairs:
            e, c = pair.args
            val = decide(c)
            if val is True:
                return e
            if val is None:
                raise Undecided(f"cannot decide the branch condition {c}")
        raise Undecided("no branch of a Piecewise applies")

    expr = sp.sympify(expr)
    while expr.has(sp.Piecewise):
        expr = expr.replace(sp.Piecewise, pick)
    return expr


def vertices(s: sp.Set) -> list[sp.Expr]:
    """Extreme points of a finite set or a closed bounded interval."""
    if isinstance(s, sp.FiniteSet):
        return list(s.args)
    if isinstance(s, sp.Interval) and not s.left_open and not s.right_open and s.start.is_finite and s.end.is_finite:
        return [s.start, s.end]
    raise Undecided(f"{s} is neither finite nor a closed bounded interval")


def _stationary_points(f: sp.Expr, var: sp.Symbol) -> list[sp.Expr]:
    """Real roots of ``f'`` (exact; polynomial derivatives through ``roots``)."""
    df = ff.together(sp.diff(f, var))
    num = sp.fraction(df)[0]
    if num.is_polynomial(var):
        poly = sp.Poly(num, var)
        if poly.degree() <= 0:
            return []
        if poly.degree() == 1:
            c1, c0 = poly.all_coeffs()
            return [fp.cancel(-c0 / c1)]
        found = sp.roots(poly)
        if sum(found.values()) == poly.degree():
            return [r for r in found if r.is_real is not False]
    return [r for r in sp.solve(df, var, simplify=False) if r.is_real is not False]


def _convex_quadratic_minimum(f: sp.Expr, var: sp.Symbol, s: sp.Interval) -> sp.Expr | None:
    """``min_{var ∈ s} f`` when ``f = α·var² + β·var + γ`` with ``α`` shown positive; ``None`` otherwise.

    A convex quadratic's minimum over a closed interval is at its vertex
    ``-β/(2α)`` clipped to the interval: one decision about where the vertex
    lies replaces the pairwise comparison of every candidate value (the
    costliest step of the obligations that minimise ``V`` over the friction).
    ``None`` (the caller's general method decides) when ``f`` is not such a
    quadratic or the vertex's position is not decided.
    """
    try:
        # coefficients as expressions (those of Poly(f, var, domain=EX)): no polynomial domain of the other
        # symbols to build, and every decision below is on the coefficients' values (sign_of, cancel)
        coeffs = ff.ex_coefficients(f, var)
    except sp.PolynomialError:
        return None
    if len(coeffs) != 3:
        return None
    alpha, beta, _gamma = coeffs
    if sign_of(alpha) != 1:
        return None
    vertex = fp.cancel(-beta / (2 * alpha))
    if decide(sp.LessThan(vertex, s.start)) is True:
        return f.xreplace({var: s.start})  # the value at the end point, as subs gives it
    if decide(sp.GreaterThan(vertex, s.end)) is True:
        return f.xreplace({var: s.end})
    if decide(sp.And(sp.StrictLessThan(s.start, vertex), sp.StrictLessThan(vertex, s.end))) is True:
        return f.xreplace({var: vertex})  # the value at the vertex, as subs gives it, without subs's bookkeeping
    return None


def minimum_on(f: sp.Expr, var: sp.Symbol, s: sp.Set) -> sp.Expr:
    """Exact ``min_{var ∈ s} f`` for a finite set or a closed bounded interval ``s``.

    A continuous function on a compact interval attains its minimum at an
    endpoint or at an interior stationary point; all candidates are compared
    with :func:`sign_of` (a convex quadratic goes straight to its clipped
    vertex, :func:`_convex_quadratic_minimum`).
    """
    candidates = list(vertices(s))
    if isinstance(s, sp.Interval):
        shortcut = _convex_quadratic_minimum(f, var, s)
        if shortcut is not None:
            return shortcut
        for r in _stationary_points(f, var):
            inside = decide(sp.And(sp.StrictLessThan(s.start, r), sp.StrictLessThan(r, s.end)))
            if inside is None:
                raise Undecided(f"cannot decide whether the stationary point {r} lies in {s}")
            if inside:
                candidates.append(r)
    values = [f.xreplace({var: c}) for c in candidates]  # as subs(var, c) gives them, without its bookkeeping
    for v in values:
        if all(sign_of(w - v) in (0, 1) for w in values):
            return v
    raise Undecided(f"cannot order the candidate values {values} of the minimum over {s}")


def affine_image(expr: sp.Expr, var: sp.Symbol, s: sp.Interval) -> sp.Interval:
    """Image of a closed interval under ``var ↦ expr`` when ``expr`` is affine in ``var``."""
    if sp.degree(sp.expand(expr), var) > 1:
        raise Undecided(f"{expr} is not affine in {var}")
    slope = sp.diff(expr, var)
    a, b = expr.subs(var, s.start), expr.subs(var, s.end)
    sg = sign_of(slope)
    if sg is None:
        raise Undecided(f"cannot decide the sign of the slope {slope}")
    if sg == 0:
        return sp.FiniteSet(ff.simplify(a))
    lo, hi = (a, b) if sg > 0 else (b, a)
    return sp.Interval(ff.simplify(lo), ff.simplify(hi), s.left_open if sg > 0 else s.right_open, s.right_open if sg > 0 else s.left_open)


def interval_partitions_reals(intervals: Sequence[sp.Interval]) -> tuple[bool, str]:
    """Whether the intervals partition the real line (in any order).

    Starting from the interval that begins at -oo, the chain is followed:
    the next interval must begin where the current one ends, and exactly one
    of the two must contain that point; the chain must use every interval
    once and end at +oo.
    """
    left = list(intervals)
    firsts = [i for i in left if i.start == -sp.oo]
    if len(firsts) != 1:
        return False, f"{len(firsts)} intervals start at -oo (expected exactly one)"
    current = firsts[0]
    left.remove(current)
    while current.end != sp.oo:
        nxt = [i for i in left if decide(sp.Eq(i.start, current.end)) is True]
        if len(nxt) != 1:
            return False, f"{len(nxt)} intervals start where {current} ends (expected exactly one)"
        if current.right_open == nxt[0].left_open:
            what = "both miss" if current.right_open else "both contain"
            return False, f"{current} and {nxt[0]} {what} the point {current.end}"
        current = nxt[0]
        left.remove(current)
    if left:
        return False, f"the intervals {left} overlap the others"
    return True, ""


def phi_classes(c: sp.Expr, tag: str = "") -> list[tuple[str, str, sp.Expr, sp.Set]]:
    """The five classes of a real number relative to ``±c`` (``c > 0``), parametrised exactly.

    Returns ``(label, tex, value, region)``: ``value`` covers ``region``
    exactly as its positive symbols range over ``(0, ∞)``; ``tex`` is the
    class in LaTeX, relative to the symbol ``\\phi``.
    """
    p, a, b = pos(f"p{tag}"), pos(f"a{tag}"), pos(f"b{tag}")
    return [
        ("φ > f_c", "\\phi > f_c", c + p, sp.Interval.open(c, sp.oo)),
        ("φ = f_c", "\\phi = f_c", c, sp.FiniteSet(c)),
        ("|φ| < f_c", "|\\phi| < f_c", (a * c - b * c) / (a + b), sp.Interval.open(-c, c)),
        ("φ = -f_c", "\\phi = -f_c", -c, sp.FiniteSet(-c)),
        ("φ < -f_c", "\\phi < -f_c", -c - p, sp.Interval.open(-sp.oo, -c)),
    ]


def sign_classes(tag: str) -> list[tuple[str, int, sp.Expr]]:
    """The three sign classes ``> 0``, ``= 0``, ``< 0`` with a positive symbol."""
    q = pos(tag)
    return [("> 0", 1, q), ("= 0", 0, sp.Integer(0)), ("< 0", -1, -q)]


_PRINTED: dict[Any, str] = {}
"""LaTeX already printed, by ``(type, expression)``: the printed form is a function of the (immutable) expression,
and the obligations print many equal ones (the type too: ``True`` and ``1`` are equal keys that print differently)."""


def latex(expr: Any) -> str:
    """Deterministic LaTeX of a sympy object (lists and tuples become tuples)."""
    if isinstance(expr, (list, tuple)):
        expr = sp.Tuple(*expr)
    try:
        key = (type(expr), expr)
        text = _PRINTED.get(key)
    except TypeError:  # unhashable (a mutable matrix): printed each time
        return sp.latex(expr, order="lex")
    if text is None:
        if len(_PRINTED) > 4096:
            _PRINTED.clear()
        text = _PRINTED[key] = sp.latex(expr, order="lex")
    return text
