"""sympy constructions on expressions that the obligations repeat, done without sympy's general machinery.

Each but :func:`simplify` returns what the sympy call it names returns (the same expression tree: the
printed LaTeX of ``proofs/obligations.md`` and the SMT-LIB queries of ``proofs/smt/`` do not change), for the
forms the obligations meet, and hands any other form to sympy itself (``tests/obligations/test_fastpoly.py``
compares them); :func:`simplify` only promises an equal expression, 0 for a rational function that is 0:

* :func:`poly_terms`, :func:`ex_coefficients`, :func:`degree_in`: the terms, the coefficients and the degree
  of a polynomial in chosen generators, read off its expanded terms instead of building a ``Poly``;
* :func:`together` of a sum of monomials: ``gcd_terms``'s steps on exponent dictionaries; remembered;
* :func:`solve` and :func:`simplify`: without the import of ``sympy.physics.units`` that sympy's own solution
  check and ``simplify`` make (about 0.2 s), each solution checked exactly instead (``check`` finds
  ``proofs/obligations.md`` unchanged, so the obligations print what they printed with sympy's).

Nothing is decided here: the obligations decide the results with :mod:`._decide`.
"""

from __future__ import annotations

import functools
from typing import Any

import sympy as sp
from sympy.core.mul import _keep_coeff

from . import _fastpoly

__all__ = ["poly_terms", "ex_coefficients", "degree_in", "together", "solve", "simplify"]


def _vanishes(expr: sp.Expr) -> bool | None:
    """Whether a rational function is identically 0 (``None``: not a rational function, or undefined)."""

    expr = sp.sympify(expr)
    if expr.is_number:
        return None if not expr.is_Rational else bool(expr == 0)
    if not _fastpoly.is_rational_function(expr):
        return None
    gens = sorted(expr.free_symbols, key=sp.default_sort_key)
    try:
        return bool(_fastpoly.rational_pair(expr, gens)[0].is_zero())
    except Exception:  # noqa: BLE001 - a denominator that vanishes, or python-flint failing: not decided here
        return None


def solve(equations: Any, symbols: Any, **flags: Any) -> list:
    """``sympy.solve(equations, symbols, **flags)``, each solution checked by substitution in exact arithmetic.

    sympy's own check of the solutions (``checksol``) imports ``sympy.physics.units`` (about 0.2 s, once per
    process) to ask whether an expression carries units; here every equation is rational, so each solution is
    checked by substituting it and testing the numerator for the zero polynomial instead.  A solution that
    does not satisfy an equation is dropped (as sympy drops it); an equation or a solution outside rational
    functions (a radical, a denominator that vanishes) is left to sympy's own check.  Only ``dict=True`` with
    a list of symbols, or one symbol without ``dict``, are taken this way.  The solutions are not passed
    through ``sympy.simplify`` (which imports the same module): callers factor or decide them, which
    does not depend on how they are written.
    """
    from sympy.core.assumptions import check_assumptions
    from sympy.solvers.solvers import solve as sympy_solve

    as_dicts = bool(flags.get("dict"))
    # one unknown without dict: sympy answers a list of values only for one equation (for a list, a dict or tuples)
    one = isinstance(symbols, sp.Symbol) and not as_dicts and not isinstance(equations, (list, tuple))
    if not (as_dicts or one) or "check" in flags or "simplify" in flags:
        return sympy_solve(equations, symbols, **flags)
    eqs = list(equations) if isinstance(equations, (list, tuple)) else [equations]
    eqs = [sp.sympify(e) for e in eqs]
    eqs = [e.lhs - e.rhs if isinstance(e, sp.Equality) else e for e in eqs]
    unknowns = [symbols] if isinstance(symbols, sp.Symbol) else list(symbols)
    if any(not isinstance(e, sp.Expr) or (e != 0 and not e.has(*unknowns)) for e in eqs):
        return sympy_solve(equations, symbols, **flags)  # an equation free of the unknowns: sympy has its own rule
    chain = _linear_chain(eqs, list(symbols)) if as_dicts and isinstance(symbols, (list, tuple)) else None
    found = chain if chain is not None else sympy_solve(equations, symbols, check=False, simplify=False, **flags)
    kept = []
    for sol in found:
        mapping = sol if as_dicts else {symbols: sol}
        verdicts = [_vanishes(e.xreplace(mapping)) for e in eqs]
        if None in verdicts or not all(_fastpoly.is_rational_function(v) for v in mapping.values()):
            return sympy_solve(equations, symbols, **flags)  # a radical: sympy's check and its form of the value
        # sympy's check also drops a solution that contradicts an unknown's assumptions (±i·√k_p for a real x)
        if all(verdicts) and all(check_assumptions(v, x) is not False for x, v in mapping.items()):
            kept.append(sol)
    return kept


def _linear_chain(eqs: list[sp.Expr], unknowns: list[sp.Symbol]) -> list[dict] | None:
    """The one solution of a polynomial system that elimination solves one unknown at a time, each from an
    equation of degree 1 in it whose coefficient is free of the unknowns (``None`` for any other system).

    Each step ``c·x + r = 0`` gives ``x = -r/c`` for the generic parameters (``c`` not the zero polynomial), as
    sympy's ``solve`` does, and is an equivalence there, so the solution found is the only one; the values
    are written as :func:`._fastpoly.cancel` writes them (the reduced fraction), which is how sympy writes
    the solutions of the obligations' systems (:func:`solve` checks each by substitution either way).
    """

    left = [sp.fraction(_fastpoly.cancel(e))[0] for e in eqs]
    if not all(_fastpoly.is_rational_function(e) for e in left):
        return None
    steps: list[tuple[sp.Symbol, sp.Expr]] = []
    todo = list(unknowns)
    while todo:
        step = None
        for e in left:
            for x in todo:
                if not e.has(x):
                    continue
                terms = dict(poly_terms(sp.expand(e), (x,)))
                if set(terms) - {(0,), (1,)} or terms[(1,)].has(*todo):
                    continue
                step = (e, x, -terms.get((0,), sp.Integer(0)) / terms[(1,)])
                break
            if step is not None:
                break
        if step is None:
            return None
        e, x, value = step
        todo.remove(x)
        steps.append((x, value))
        left = [sp.fraction(_fastpoly.cancel(f.xreplace({x: value})))[0] for f in left if f is not e]
    if any(f != 0 for f in left):
        return None  # an equation left over: not one generic solution
    solution: dict[sp.Symbol, sp.Expr] = {}
    for x, value in reversed(steps):
        solution[x] = _fastpoly.cancel(value.xreplace(solution))
    return [{x: solution[x] for x in sorted(unknowns, key=sp.default_sort_key)}]  # keyed in sympy's order


def simplify(expr: Any) -> sp.Expr:
    """A rational function that is identically 0 as ``0``, any other rational function unchanged; anything else
    through ``sympy.simplify``.

    The obligations simplify only to tidy an expression they then decide exactly (an interval's end, a
    polynomial whose zero set is solved) or print; on a rational function sympy's ``simplify`` would first
    import ``sympy.physics.units`` (about 0.2 s) and try a dozen rewritings, and a decision on the result is
    the same decision.
    """
    expr = sp.sympify(expr)
    if isinstance(expr, sp.Expr) and (expr.is_Rational or expr.is_Symbol):
        return expr

    zero = _vanishes(expr) if isinstance(expr, sp.Expr) and _fastpoly.is_rational_function(expr) else None
    if zero is None:
        return sp.simplify(expr)
    return sp.Integer(0) if zero else expr


def _looks_expanded(expr: sp.Expr) -> bool:
    """What ``expand`` leaves as it is: a sum of terms, each a rational times integer powers of symbols, or an
    integer times positive powers of symbols over one sum of that form (``expand`` multiplies out a denominator
    of several factors, and expands a power of a sum)."""
    for term in sp.Add.make_args(expr):
        over = [f for f in sp.Mul.make_args(term) if f.is_Pow and f.exp == -1 and f.base.is_Add]
        for factor in sp.Mul.make_args(term):
            if factor.is_Rational:
                if over and factor.q != 1:
                    return False
            elif factor.is_Symbol:
                continue
            elif factor.is_Pow and factor.exp.is_Integer and factor.base.is_Symbol:
                if over and factor.exp < 0:
                    return False
            elif not (len(over) == 1 and factor is over[0] and _looks_expanded(factor.base)):
                return False
    return True


def _expanded(expr: sp.Expr) -> sp.Expr:
    """``expr.expand()``, which sympy's ``Poly`` applies first: ``expr`` itself when it is in expanded form already
    (:func:`_looks_expanded`; the obligations pass expressions they have just expanded), saving a second pass."""
    return expr if _looks_expanded(expr) else expr.expand()


def ex_coefficients(f: sp.Expr, var: sp.Symbol) -> list[sp.Expr]:
    """``sympy.Poly(f, var, domain=sympy.EX).all_coeffs()`` (the same expressions), without building the Poly.

    sympy expands ``f``, files each term's factors other than powers of ``var`` as its coefficient, adds the
    coefficients of equal powers as expressions and strips leading coefficients that are zero (``is_zero``);
    this does the same.  Raises ``sympy.PolynomialError`` as sympy does when ``var`` occurs otherwise than in
    a nonnegative integer power (through sympy itself, for any form this does not take).
    """
    if f.has(sp.zoo, sp.nan, sp.oo, -sp.oo):  # not an element of EX: sympy refuses it (CoercionFailed)
        return sp.Poly(f, var, domain=sp.EX).all_coeffs()
    expanded = _expanded(f)
    by_power: dict[int, list[sp.Expr]] = {}
    for term in sp.Add.make_args(expanded):
        coeff, power = [], 0
        for factor in sp.Mul.make_args(term):
            if factor.is_Number:
                coeff.append(factor)
            elif factor == var:
                power = 1
            elif factor.is_Pow and factor.base == var and factor.exp.is_Integer and factor.exp > 0:
                power = int(factor.exp)
            elif factor.is_Add or factor.has_free(var) or (factor.is_Pow and factor.base.is_Add and factor.exp.is_positive):
                return sp.Poly(f, var, domain=sp.EX).all_coeffs()  # a form sympy expands further, or an error
            else:
                coeff.append(factor)  # a reciprocal of a sum too: sympy files it in the coefficient
        by_power.setdefault(power, []).append(sp.Mul(*coeff))
    # sympy adds each power's coefficients one at a time; their sum is the same expression built at once
    sums = {k: sp.Add(*parts) for k, parts in by_power.items()}
    degree = max(sums, default=0)
    while degree > 0 and (degree not in sums or sums[degree].is_zero):
        degree -= 1
    return [sums.get(k, sp.Integer(0)) for k in range(degree, -1, -1)]


def _power_of(factor: sp.Expr, gens: dict[sp.Symbol, int]) -> tuple[int, int] | None:
    """``(index of the generator, exponent)`` if ``factor`` is a generator to a positive integer power."""
    if factor in gens:
        return gens[factor], 1
    if factor.is_Pow and factor.base in gens and factor.exp.is_Integer and factor.exp > 0:
        return gens[factor.base], int(factor.exp)
    return None


def _plain(factor: sp.Expr) -> bool:
    """A symbol or a symbol to a positive integer power: a factor sympy files into a polynomial coefficient as is."""
    return factor.is_Symbol or (factor.is_Pow and factor.base.is_Symbol and factor.exp.is_Integer and factor.exp > 0)


def poly_terms(expr: sp.Expr, gens: tuple[sp.Symbol, ...]) -> list[tuple[tuple[int, ...], sp.Expr]]:
    """``sympy.Poly(expr, *gens).terms()``: the same monomials, coefficients (as expressions) and order.

    sympy expands ``expr``, files each term under the exponents of ``gens`` with the rest as a polynomial
    coefficient in the other symbols, and lists the terms in decreasing lexicographic order; the
    coefficient sympy returns is the sum of those rests (a polynomial's canonical sum of monomials), which
    this builds directly.  Any other form (a generator inside a function, a negative power, a rest that is
    not a monomial) goes through ``sympy.Poly`` itself.
    """
    expanded = _expanded(expr)
    index = {g: i for i, g in enumerate(gens)}
    grouped: dict[tuple[int, ...], list[sp.Expr]] = {}
    for term in sp.Add.make_args(expanded):
        monom = [0] * len(gens)
        rest = []
        for factor in sp.Mul.make_args(term):
            power = _power_of(factor, index)
            if power is not None:
                monom[power[0]] = power[1]
            elif factor.is_Rational or _plain(factor):
                rest.append(factor)
            else:
                return sp.Poly(expr, *gens).terms()
        grouped.setdefault(tuple(monom), []).append(sp.Mul(*rest))
    if list(grouped) == [tuple([0] * len(gens))] and grouped[tuple([0] * len(gens))] == [sp.Integer(0)]:
        return sp.Poly(expr, *gens).terms()  # the zero polynomial: sympy's own convention
    return [(m, sp.Add(*grouped[m])) for m in sorted(grouped, reverse=True)]


def degree_in(expr: sp.Expr, gen: sp.Symbol) -> Any:
    """``sympy.degree(expr, gen)`` (an ``int``; sympy's ``-oo`` for 0 through sympy), without building the Poly."""
    expanded = _expanded(expr)
    if expanded == 0:
        return sp.degree(expr, gen)
    top = 0
    for term in sp.Add.make_args(expanded):
        for factor in sp.Mul.make_args(term):
            power = _power_of(factor, {gen: 0})
            if power is not None:
                top = max(top, power[1])
            elif factor.is_Add or factor.has_free(gen) or (factor.is_Pow and factor.base.is_Add and factor.exp.is_positive):
                return sp.degree(expr, gen)  # a form sympy expands further, or gen inside a function: its error
    return sp.Integer(top)


def _monomial_exponents(term: sp.Expr) -> tuple[sp.Rational, dict[sp.Symbol, int]] | None:
    """``(coefficient, {symbol: exponent})`` of a rational times positive powers of symbols, else ``None``."""
    coeff, rest = term.as_coeff_Mul()
    if not coeff.is_Rational:
        return None
    exps: dict[sp.Symbol, int] = {}
    for factor in sp.Mul.make_args(rest):
        if factor.is_Symbol:
            exps[factor] = exps.get(factor, 0) + 1
        elif factor.is_Pow and factor.base.is_Symbol and factor.exp.is_Integer and factor.exp > 0:
            exps[factor.base] = exps.get(factor.base, 0) + int(factor.exp)
        elif factor is not sp.S.One:
            return None
    return coeff, exps


def _together_polynomial(expr: sp.Expr) -> sp.Expr | None:
    """``sympy.together(expr)`` of a sum of monomials (``None`` for anything else): sympy's ``gcd_terms`` step by step.

    ``together`` rebuilds each monomial unchanged and hands the list to ``gcd_terms``, which takes out the
    terms' common content (the gcd of the coefficients, and each symbol common to all terms to its smallest
    power), divides each term by it, sums the quotients, takes out the sum's primitive content and returns
    ``coefficient·(common monomial·sum)``; the same steps, on exponent dictionaries instead of sympy's
    ``Factors``, with sympy's own constructors for every expression returned.
    """
    if not expr.is_Add:
        return None
    parts = [_monomial_exponents(t) for t in expr.args]
    if any(p is None for p in parts):
        return None
    g = parts[0][0]
    common = dict(parts[0][1])
    for c, exps in parts[1:]:
        g = g.gcd(c)
        common = {x: min(e, exps[x]) for x, e in common.items() if x in exps}
    numers = []
    for c, exps in parts:
        rest = sp.Mul(*[x**(e - common.get(x, 0)) for x, e in exps.items() if e != common.get(x, 0)])
        numers.append((c / g) * rest)
    cont = g * sp.Mul(*[x**e for x, e in common.items()])
    numer = sp.Add(*numers)
    if numer.is_Add:
        content, numer = numer.primitive()
        cont *= content
    coeff, factors = cont.as_coeff_Mul()
    return _keep_coeff(coeff, factors * numer / sp.Integer(1), clear=True)


@functools.lru_cache(maxsize=4096)
def together(expr: sp.Expr) -> sp.Expr:
    """``sympy.together(expr)`` (the same expression), remembered: a pure function of the expression that the
    obligations apply to many equal expressions (the same coefficient in several pieces, one condition from
    several obligations); a sum of monomials is done without sympy's general machinery (:func:`_together_polynomial`)."""
    fast = _together_polynomial(expr) if isinstance(expr, sp.Expr) else None
    return sp.together(expr) if fast is None else fast
