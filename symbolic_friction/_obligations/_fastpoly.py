"""sympy's ``factor``, ``cancel``, ``factor_list`` and ``expand`` of a rational function (or a determinant), in python-flint.

The obligations call these sympy functions hundreds of times per ``check``
(to write a minor or a condition in factored form, to reduce a quotient
before its sign is decided, to list the factors of a numerator); sympy does
the polynomial arithmetic in pure Python, python-flint in C.  Each function
here returns **the very expression sympy returns** (the same tree, so the
same printed LaTeX in ``proofs/obligations.md`` and the same SMT-LIB queries
in ``proofs/smt/``), because the result is canonical and is rebuilt with
sympy's own constructors:

* ``cancel(f)`` is ``P/Q`` with ``P, Q`` the coprime integer polynomials
  (content included) of ``f = P/Q``, ``Q``'s leading coefficient positive
  in the lexicographic order of sympy's generator order (``_sort_gens``);
* ``factor(f)`` is ``c·∏ fᵢ^eᵢ`` with ``fᵢ`` the irreducible primitive integer
  factors of ``P`` and ``Q`` (leading coefficient positive, ``eᵢ < 0`` for
  ``Q``'s) and ``c`` the rational left over: equal factors of a numerator
  and a denominator cancel in sympy's product too;
* ``factor_list(p)`` of a polynomial is ``(c, [(fᵢ, eᵢ)])`` with the same
  factors (in an order of its own: callers here only multiply them or decide
  each);
* ``expand(f)`` of a rational function whose denominators are powers of symbols is the sum of its terms
  (a rational times powers of the symbols, of any sign), the one form sympy's distributing arrives at;
* ``expanded_det(M)`` and ``factored_det(M)`` are ``expand(M.det())`` and ``factor(M.det())``, the
  determinant computed in python-flint.

Anything else (a radical, ``Abs``, ``Piecewise``, two symbols printed alike, a
number) goes to sympy itself, as does every call if python-flint fails.  The
obligations decide the results with :mod:`._decide`, which reads its
fractions of integer polynomials off :func:`rational_pair` too (the one
conversion of an expression into python-flint, in the trusted base).
"""

from __future__ import annotations

import functools
from typing import Any

import sympy as sp
from sympy.core.function import expand as _sympy_expand
from sympy.core.mul import _keep_coeff
from sympy.polys.polytools import cancel as _sympy_cancel
from sympy.polys.polytools import factor as _sympy_factor
from sympy.polys.polytools import factor_list as _sympy_factor_list

__all__ = ["cancel", "factor", "factor_list", "expand", "expanded_det", "factored_det", "polynomial_gens",
           "is_rational_function", "rational_symbols", "rational_pair"]


def is_rational_function(expr: sp.Expr) -> bool:
    """Whether ``expr`` is built from symbols and rationals by + - × ÷ and integer powers only."""
    return rational_symbols(expr) is not None


def rational_symbols(expr: sp.Expr) -> frozenset[sp.Symbol] | None:
    """The symbols of ``expr`` if it is a rational function (:func:`is_rational_function`), ``None`` otherwise.

    One pass over the tree for both (each shared subexpression once), remembered for the last few thousand
    expressions: a decision asks both of one expression, and the obligations decide many equal ones.
    """
    try:
        return _rational_symbols(expr)
    except TypeError:  # unhashable (a mutable matrix): decided without the memo, with the memo's answer type
        symbols = _symbols_of_rational(expr)
        return None if symbols is None else frozenset(symbols)


@functools.lru_cache(maxsize=4096)
def _rational_symbols(expr: sp.Expr) -> frozenset[sp.Symbol] | None:
    symbols = _symbols_of_rational(expr)
    return None if symbols is None else frozenset(symbols)


def polynomial_gens(expr: sp.Expr) -> tuple[sp.Symbol, ...] | None:
    """sympy's generators of ``expr`` in its order (``_sort_gens``); ``None`` if two symbols print alike or have one
    sort key (``x`` and ``x0``: sympy then orders them by an accident of hashing), or there are none."""
    syms = expr.free_symbols
    if not syms:
        return None
    return _sorted_gens(frozenset(syms))


@functools.lru_cache(maxsize=1024)
def _sorted_gens(syms: frozenset) -> tuple[sp.Symbol, ...] | None:
    """``sympy.polys.polyutils._sort_gens(syms)`` without options (its key, without building sympy's Options object
    on every call): by the rank sympy gives a one-letter name, then the name, then a trailing index."""
    from sympy.polys.polyutils import _gens_order, _max_order, _re_gen

    names = {s: s.name if type(s) is sp.Symbol else str(s) for s in syms}  # a plain symbol prints as its name

    def key(gen: sp.Symbol) -> tuple[int, str, int]:
        name, index = _re_gen.match(names[gen]).groups()
        return (_gens_order.get(name, _max_order), name, int(index) if index else 0)

    keys = {s: key(s) for s in syms}
    if len(set(keys.values())) != len(syms):  # printed alike, or x and x0: sympy orders them by an accident of hashing
        return None
    return tuple(sorted(syms, key=keys.__getitem__))


def rational_pair(expr: sp.Expr, gens: list[sp.Symbol]) -> tuple[Any, Any]:
    """``expr`` (a rational function of ``gens``) as a reduced fraction ``(numerator, denominator)`` over ``ℤ[gens]``.

    Each node of the expression tree becomes a pair of python-flint integer
    polynomials in ``gens`` (lex, ``gens[0]`` first; sparse, exact; a rational
    constant ``p/q`` is ``(p, q)``); sums bring their terms to a common
    denominator, and one ``gcd`` at the end cancels the common factors, so
    ``numerator/denominator`` is the reduced fraction of ``Q(gens)`` up to a
    constant factor and equals ``expr`` wherever ``expr`` is defined.  A
    denominator that is the zero polynomial raises :class:`ZeroDivisionError`,
    anything but a rational function (:func:`is_rational_function`)
    :class:`TypeError`.  The generators get positional names: two symbols with
    one name (different assumptions) stay two variables.
    """
    import flint

    ctx = flint.fmpz_mpoly_ctx.get(("x", len(gens)), "lex")
    one = ctx.constant(1)
    index = {s: (g, one) for s, g in zip(gens, ctx.gens())}
    memo: dict[sp.Expr, tuple[Any, Any]] = {}

    def pair(e: sp.Expr) -> tuple[Any, Any]:
        if e in index:
            return index[e]
        if e in memo:
            return memo[e]
        if e.is_Rational:
            out = (ctx.constant(int(e.p)), ctx.constant(int(e.q)))
        elif e.is_Add:
            n, d = ctx.constant(0), one
            for a in e.args:
                an, ad = pair(a)
                if ad == d:
                    n = n + an
                else:
                    g = d.gcd(ad)
                    n, d = n * (ad / g) + an * (d / g), d * (ad / g)
            out = (n, d)
        elif e.is_Mul:
            n, d = one, one
            for a in e.args:
                an, ad = pair(a)
                n, d = n * an, d * ad
            out = (n, d)
        elif e.is_Pow and e.exp.is_Integer:
            bn, bd = pair(e.base)
            k = int(e.exp)
            if k < 0 and bn.is_zero():
                raise ZeroDivisionError(f"{e.base} is identically zero in {e}")
            out = (bn ** k, bd ** k) if k >= 0 else (bd ** -k, bn ** -k)
        else:  # is_rational_function admits nothing else
            raise TypeError(f"{e} is not a rational function of its symbols")
        memo[e] = out
        return out

    numer, denom = pair(expr)
    g = numer.gcd(denom)
    return numer / g, denom / g



def _to_expr(p: Any, gens: list[sp.Symbol]) -> sp.Expr:
    """An integer polynomial as sympy writes a polynomial (``expr_from_dict``: a sum of coefficient × powers)."""
    terms = []
    for monom, c in zip(p.monoms(), p.coeffs()):
        term = [sp.Integer(int(c))]
        for g, m in zip(gens, monom):
            if m:
                term.append(sp.Pow(g, m))
        terms.append(sp.Mul(*term))
    return sp.Add(*terms)


def _guarded(fast: Any, reference: Any) -> Any:
    """``fast``, or sympy's ``reference`` if ``fast`` raises (python-flint missing or not behaving as documented:
    then sympy's own answer, never a wrong one)."""

    def run(expr: Any) -> Any:
        try:
            return fast(expr)
        except Exception:  # noqa: BLE001 - any failure of the fast path: sympy decides what to return
            return reference(expr)

    run.__name__, run.__doc__ = fast.__name__.removeprefix("_fast_"), fast.__doc__
    return run


def _symbols_of_rational(expr: sp.Expr) -> set[sp.Symbol] | None:
    """The symbols of a rational function (as :func:`is_rational_function` accepts it), ``None`` for anything else: one pass
    over the tree for both (each shared subexpression once)."""
    symbols: set[sp.Symbol] = set()
    stack, seen = [expr], set()
    while stack:
        node = stack.pop()
        if isinstance(node, sp.Symbol):
            symbols.add(node)
        elif isinstance(node, sp.Rational):
            continue
        elif isinstance(node, (sp.Add, sp.Mul)) or (isinstance(node, sp.Pow) and node.exp.is_Integer):
            if node not in seen:
                seen.add(node)
                stack.extend(node.args)
        else:
            return None
    return symbols


def _eligible(expr: Any) -> tuple[sp.Expr, tuple[sp.Symbol, ...] | None]:
    expr = sp.sympify(expr)
    if not isinstance(expr, sp.Expr) or expr.is_number:
        return expr, None
    symbols = rational_symbols(expr)
    return expr, (None if not symbols else _sorted_gens(symbols))


def _fast_cancel(expr: Any) -> sp.Expr:
    """``sympy.cancel(expr)`` (same expression), through python-flint for a rational function."""
    expr, gens = _eligible(expr)
    if gens is None:
        return _sympy_cancel(expr)
    n, d = rational_pair(expr, gens)
    if d.leading_coefficient() < 0:  # sympy's canonical unit: the denominator's leading coefficient is positive
        n, d = -n, -d
    return 1 * (_to_expr(n, gens) / _to_expr(d, gens))


def _factored(n: Any, d: Any, gens: list[sp.Symbol]) -> sp.Expr:
    """``n/d`` (coprime, ``n`` not zero) as sympy's ``factor`` writes it: ``c·∏ fᵢ^eᵢ`` over the irreducible primitive
    factors of ``n`` (``eᵢ > 0``) and of ``d`` (``eᵢ < 0``)."""
    cn, fn = n.factor()
    cd, fd = d.factor()
    product = sp.Mul(*([_to_expr(f, gens) ** int(k) for f, k in fn] + [_to_expr(f, gens) ** -int(k) for f, k in fd]))
    return _keep_coeff(sp.Rational(int(cn), int(cd)), product)


def _fast_factor(expr: Any) -> sp.Expr:
    """``sympy.factor(expr)`` (same expression), through python-flint for a rational function."""
    expr, gens = _eligible(expr)
    if gens is None:
        return _sympy_factor(expr)
    n, d = rational_pair(expr, gens)
    if n.is_zero():
        return sp.Integer(0)
    return _factored(n, d, gens)


def _fast_factor_list(expr: Any) -> tuple[sp.Rational, list[tuple[sp.Expr, int]]]:
    """``sympy.factor_list(expr)`` of a polynomial: the same constant and factors (in an order of its own)."""
    expr, gens = _eligible(expr)
    if gens is None or any(isinstance(a, sp.Pow) and a.exp.is_negative for a in sp.preorder_traversal(expr)):
        return _sympy_factor_list(expr)
    n, d = rational_pair(expr, gens)
    if not d.is_constant():
        return _sympy_factor_list(expr)
    if n.is_zero():
        return sp.Integer(0), []
    cn, fn = n.factor()
    return sp.Rational(int(cn), int(d.leading_coefficient())), [(_to_expr(f, gens), int(k)) for f, k in fn]


def _monomial_denominators(expr: sp.Expr) -> bool:
    """Every negative power in ``expr`` is a power of a symbol (its denominators are monomials)."""
    return all(a.base.is_Symbol for a in sp.preorder_traversal(expr) if isinstance(a, sp.Pow) and a.exp.is_negative)


def _laurent_expr(n: Any, d: Any, gens: list[sp.Symbol]) -> sp.Expr | None:
    """``n/d`` with ``d`` a monomial, as the sum of its terms ``c·∏ gᵉ`` (exponents of any sign); ``None`` otherwise."""
    if len(d.monoms()) != 1:
        return None
    (dm,), (dc,) = d.monoms(), d.coeffs()
    terms = []
    for monom, c in zip(n.monoms(), n.coeffs()):
        term = [sp.Rational(int(c), int(dc))]
        for g, m, k in zip(gens, monom, dm):
            if m != k:
                term.append(sp.Pow(g, int(m) - int(k)))
        terms.append(sp.Mul(*term))
    return sp.Add(*terms)


def _fast_expand(expr: Any) -> sp.Expr:
    """``sympy.expand(expr)`` of a rational function whose denominators are monomials (a polynomial, or one over
    powers of symbols): the sum of its terms, each a rational times powers of the symbols, which is the one form
    sympy's distributing of every product over every sum arrives at."""
    expr, gens = _eligible(expr)
    if gens is None or not _monomial_denominators(expr):
        return _sympy_expand(expr)
    n, d = rational_pair(expr, gens)
    out = _laurent_expr(n, d, gens)
    return _sympy_expand(expr) if out is None else out


cancel = _guarded(_fast_cancel, _sympy_cancel)
factor = _guarded(_fast_factor, _sympy_factor)
factor_list = _guarded(_fast_factor_list, _sympy_factor_list)
expand = _guarded(_fast_expand, _sympy_expand)


def _det_pair(entries: list[list[sp.Expr]], gens: list[sp.Symbol]) -> tuple[Any, Any]:
    """The determinant of a square matrix of rational functions as a reduced ``(numerator, denominator)`` pair.

    Laplace expansion along the first row (the matrices here are at most 3×3), in python-flint fractions.
    """
    pairs = [[rational_pair(e, gens) for e in row] for row in entries]

    def det(rows: list[int], cols: list[int]) -> tuple[Any, Any]:
        if len(rows) == 1:
            return pairs[rows[0]][cols[0]]
        num, den = None, None
        for j, c in enumerate(cols):
            an, ad = pairs[rows[0]][c]
            if an.is_zero():
                continue
            mn, md = det(rows[1:], cols[:j] + cols[j + 1:])
            tn, td = (an * mn, ad * md) if j % 2 == 0 else (-(an * mn), ad * md)
            num, den = (tn, td) if num is None else (num * td + tn * den, den * td)
        if num is None:
            one = pairs[0][0][1] / pairs[0][0][1]
            return one - one, one
        return num, den

    n, d = det(list(range(len(entries))), list(range(len(entries))))
    g = n.gcd(d)
    return n / g, d / g


def _matrix_gens(M: Any) -> list[sp.Symbol] | None:
    entries = [sp.sympify(e) for e in M]
    if not all(isinstance(e, sp.Expr) and is_rational_function(e) for e in entries):
        return None
    syms = set().union(*(e.free_symbols for e in entries))
    if not syms:
        return None
    return polynomial_gens(sp.Add(*syms))


def _fast_expanded_det(M: Any) -> sp.Expr:
    """``sympy.expand(M.det())`` (the same expression) for a matrix of rational functions whose determinant has a
    monomial denominator: its terms, computed in python-flint (:func:`expand`'s canonical form)."""
    M = sp.Matrix(M)
    gens = _matrix_gens(M)
    if gens is None or not M.is_square or M.rows > 3 or not all(_monomial_denominators(e) for e in M):
        return _sympy_expand(M.det())
    n, d = _det_pair(M.tolist(), gens)
    out = _laurent_expr(n, d, gens)
    return _sympy_expand(M.det()) if out is None else out


def _fast_factored_det(M: Any) -> sp.Expr:
    """``sympy.factor(M.det())`` (the same expression) for a matrix of rational functions: :func:`factor` of the
    determinant computed in python-flint."""
    M = sp.Matrix(M)
    gens = _matrix_gens(M)
    if gens is None or not M.is_square or M.rows > 3:
        return _sympy_factor(M.det())
    n, d = _det_pair(M.tolist(), gens)
    if n.is_zero():
        return sp.Integer(0)
    return _factored(n, d, gens)


expanded_det = _guarded(_fast_expanded_det, lambda M: _sympy_expand(sp.Matrix(M).det()))
factored_det = _guarded(_fast_factored_det, lambda M: _sympy_factor(sp.Matrix(M).det()))
