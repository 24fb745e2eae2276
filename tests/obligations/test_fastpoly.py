"""The obligations' polynomial arithmetic in python-flint (:mod:`._fastpoly`, :mod:`._fastforms`) is sympy's own.

Each function there claims to return the very expression the sympy call it
names returns (the same tree, so ``proofs/obligations.md`` prints the same
LaTeX and ``proofs/smt/`` holds the same queries), and to hand any other form
to sympy.  Here the claim is checked directly: property tests over random
rational functions in the package's kind of symbols (positive gains as
:func:`._decide.G` and :func:`._decide.pos` make them, real coordinates,
plain symbols, names that sort in tricky ways: ``x``, ``x1``, ``x2``, ``x10``,
``k_v`` after ``v``) compare each result with sympy's by ``==`` and by
``srepr`` (the tree itself), or as the sets of solutions or factors where the
claim is only that.  Each property has a mutant (:data:`MUTANTS`): a copy of
the subject with one step broken, on which the same examples must find a
difference, so that every comparison here can fail.  The differences these
properties found (forms no obligation met) were fixed in the package; each is
kept as a fixed case (:data:`FOUND_DIFFERENCES`).

The examples are derandomized (the same on every run) and few enough that the
module runs in seconds; sympy's side of each comparison is the slow one.
"""

from __future__ import annotations

import functools
import inspect
import textwrap
from collections import Counter

import flint
import pytest
import sympy as sp
from hypothesis import HealthCheck, Phase, assume, given, settings
from hypothesis import strategies as st
from sympy.polys.polyutils import _sort_gens

from symbolic_friction._obligations import _fastforms as ff
from symbolic_friction._obligations import _fastpoly as fp
from symbolic_friction._obligations._decide import G, pos

SETTINGS = settings(deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
"""Derandomized (stable in CI), no example database written into the checkout, no deadline (sympy's time varies)."""

GAINS = G()
POSITIVE = (GAINS.k_p, GAINS.k_i, GAINS.k_v, GAINS.f_c, GAINS.delta, pos("q_v"), pos("y_1"))
REAL = (GAINS.sigma, GAINS.phi, GAINS.v, GAINS.e_i, GAINS.s,
        *(sp.Symbol(name, real=True) for name in ("x", "x1", "x2", "x10")))
PLAIN = (sp.Symbol("y"), sp.Symbol("w"), sp.Symbol("a"))
SYMBOLS = POSITIVE + REAL + PLAIN
ALIKE = (sp.Symbol("s"), GAINS.s)  # two symbols printing alike, one real: sympy orders them by hashing
# Names with equal sort keys (``x`` and ``x0``, ``x1`` and ``x01``) are left out of the random draws: for them sympy's
# own generator order depends on the hash seed, so the fast path hands them to sympy (:data:`FOUND_DIFFERENCES`).

rationals = st.fractions(min_value=-4, max_value=4, max_denominator=3).map(lambda q: sp.Rational(q.numerator,
                                                                                                 q.denominator))
nonzero = rationals.filter(lambda q: q != 0)
symbols = st.sampled_from(SYMBOLS)


def _monomial(draw_from=symbols, max_power: int = 2, min_power: int = 1):
    return st.tuples(nonzero, st.lists(st.tuples(draw_from, st.integers(min_power, max_power)), max_size=3)).map(
        lambda t: sp.Mul(t[0], *(s**k for s, k in t[1] if k)))


def polynomials(draw_from=symbols, max_terms: int = 4):
    """A sum of up to ``max_terms`` monomials with rational coefficients (expanded)."""
    return st.lists(_monomial(draw_from), min_size=1, max_size=max_terms).map(lambda ts: sp.Add(*ts))


def rational_functions(leaves=None, min_power: int = -2, max_leaves: int = 7):
    """Sums, products and integer powers (negative too, down to ``min_power``) of symbols and rationals, unexpanded
    (``1/0`` left out: not a rational function; :data:`FOUND_DIFFERENCES` has its one difference)."""
    leaves = st.one_of(symbols, symbols, rationals) if leaves is None else leaves

    def grow(children):
        return st.one_of(st.lists(children, min_size=2, max_size=3).map(lambda a: sp.Add(*a)),
                         st.lists(children, min_size=2, max_size=3).map(lambda a: sp.Mul(*a)),
                         st.tuples(children, st.integers(min_power, 3)).map(lambda t: sp.Pow(*t)))

    return st.recursive(leaves, grow, max_leaves=max_leaves).filter(lambda e: not e.has(sp.zoo, sp.nan))


_POLYNOMIALS_3, _POLYNOMIALS_2 = polynomials(max_terms=3), polynomials(max_terms=2)
"""Built once: hypothesis validates a strategy the first time it draws from it, so one built inside a composite
is validated again at every example (the same draws either way)."""


@st.composite
def reducible_fractions(draw):
    """``p·r / (±q·r)`` expanded: a fraction whose numerator and denominator share a factor, the denominator's
    leading coefficient of either sign."""
    p, q, r = draw(_POLYNOMIALS_3), draw(_POLYNOMIALS_3), draw(_POLYNOMIALS_2)
    sign = draw(st.sampled_from((1, -1)))
    return sp.expand(p * r) / sp.expand(sign * q * r)


# a rational function whose denominators are powers of symbols (expand's fast form)
laurent = rational_functions(st.one_of(symbols, rationals, st.tuples(symbols, st.integers(-3, -1)).map(
    lambda t: sp.Pow(*t))), min_power=0)
fractions_ = st.one_of(rational_functions(), reducible_fractions())
# a polynomial over a sum, expanded (terms each over the same sum): a form expand leaves as it is
quotients = st.tuples(polynomials(), polynomials(max_terms=2)).map(lambda t: sp.expand(t[0] / t[1]))
sizes = st.sampled_from((2, 3, 2, 3, 1))
# the entries' strategies built once, not inside the flatmap (hypothesis validates a new strategy at its first draw,
# which here was every matrix drawn; the same draws either way)
_ENTRIES = rational_functions(max_leaves=3)
_LAURENT_ENTRIES = rational_functions(st.one_of(symbols, rationals, symbols.map(lambda s: 1 / s)), min_power=0,
                                      max_leaves=3)
matrices = sizes.flatmap(lambda n: st.lists(
    st.lists(_ENTRIES, min_size=n, max_size=n), min_size=n, max_size=n)).map(sp.Matrix)
laurent_matrices = sizes.flatmap(lambda n: st.lists(st.lists(
    _LAURENT_ENTRIES, min_size=n, max_size=n), min_size=n, max_size=n)).map(sp.Matrix)
outside = st.tuples(rational_functions(max_leaves=4), st.sampled_from((
    sp.sqrt(GAINS.k_p), sp.sqrt(2), sp.Abs(GAINS.sigma), sp.Float("0.5"), sp.exp(GAINS.k_i),
    sp.Piecewise((GAINS.v, GAINS.v > 0), (-GAINS.v, True)), GAINS.k_p ** sp.Rational(1, 3),
    sp.Integer(3), sp.Rational(-2, 7), sp.pi, *ALIKE))).map(lambda t: (t[0] + 1) * (t[1] + GAINS.k_p) + t[1] ** 2)
"""Forms python-flint does not take: a radical, ``Abs``, ``Piecewise``, a float, a function, a number, two symbols
printed alike, each built into a rational function."""


def _outcome(call, *args):
    """``("value", srepr, value)`` of a call, or ``("raises", exception type)``."""
    try:
        value = call(*args)
    except Exception as exc:  # noqa: BLE001 - a raise is an outcome to compare as well
        return ("raises", type(exc))
    return ("value", _srepr(value), value)


def _srepr(value):
    return [_srepr(v) for v in value] if isinstance(value, (list, tuple)) else sp.srepr(value)


_SYMPYS: dict = {}
"""sympy's side of the comparisons, by call and arguments: each mutant's examples are its property's own (derandomized,
the same draws), and sympy's answer does not depend on the fast path a mutant breaks, so it is computed once."""


def _tree(value):
    """A key for arguments: equal exactly when they are the same trees (sympy's ``==`` compares trees; a matrix by
    its class, shape and entries; lists, tuples and dicts item by item)."""
    if isinstance(value, (list, tuple)):
        return type(value), tuple(_tree(v) for v in value)
    if isinstance(value, dict):
        return dict, tuple((_tree(k), _tree(v)) for k, v in value.items())
    if isinstance(value, sp.MatrixBase):
        return type(value), value.shape, tuple(value)
    return type(value), value


def _once(key, compute):
    if key not in _SYMPYS:
        _SYMPYS[key] = compute()
    return _SYMPYS[key]


def _sympys(call, *args):
    """``_outcome(call, *args)`` for one of sympy's own calls (or a lambda around them without free variables: a
    new function object per check, keyed by its code), computed once per arguments."""
    code = getattr(call, "__code__", None)
    return _once((_outcome, code if code is not None and not call.__closure__ else call, _tree(args)),
                 lambda: _outcome(call, *args))


def _same(fast, reference, *args):
    """``fast(*args)`` is ``reference(*args)``: the same tree (``==`` and ``srepr``), or the same exception type."""
    got, want = _outcome(fast, *args), _sympys(reference, *args)
    assert got[:2] == want[:2], (args, got, want)
    if want[0] == "value":
        assert got[2] == want[2], (args, got[2], want[2])


# ---------------------------------------------------------------------------- the properties, one check each


def check_cancel(e):
    _same(fp.cancel, sp.cancel, e)


def check_factor(e):
    _same(fp.factor, sp.factor, e)


def check_expand(e):
    _same(fp.expand, sp.expand, e)


def _factor_multiset(call, e):
    if call is sp.factor_list:  # sympy's side: once per expression (:data:`_SYMPYS`)
        return _once((_factor_multiset, _tree(e)), lambda: _factor_multiset_of(call, e))
    return _factor_multiset_of(call, e)


def _factor_multiset_of(call, e):
    try:
        c, factors = call(e)
    except Exception as exc:  # noqa: BLE001 - sympy refuses a rational function: so must the fast path
        return type(exc)
    return c, Counter((sp.srepr(f), k) for f, k in factors)


def check_factor_list(e):
    """The same constant and the same multiset of (factor, multiplicity); the order is the fast path's own."""
    assert _factor_multiset(fp.factor_list, e) == _factor_multiset(sp.factor_list, e), e


def check_expanded_det(m):
    _same(fp.expanded_det, lambda a: sp.expand(a.det()), m)


def check_factored_det(m):
    _same(fp.factored_det, lambda a: sp.factor(a.det()), m)


def check_rational_pair(e):
    """``rational_pair`` is sympy's reduced fraction up to a constant factor (in sympy's generators, or in any order
    of the symbols: python-flint's variables are positional)."""
    free = sorted(e.free_symbols, key=sp.default_sort_key)
    if not free or not fp.is_rational_function(e):
        return
    try:
        want_n, want_d = sp.fraction(sp.cancel(e))
    except Exception:  # noqa: BLE001 - sympy cannot reduce it (a denominator that vanishes): neither can the pair
        with pytest.raises(ZeroDivisionError):
            fp.rational_pair(e, free)
        return
    if want_d.has(sp.zoo, sp.nan) or want_n.has(sp.zoo, sp.nan):
        return
    for gens in (free, free[::-1]):
        n, d = fp.rational_pair(e, gens)
        got_n, got_d = (sp.Poly.from_dict({m: int(c) for m, c in zip(p.monoms(), p.coeffs())} or {(0,) * len(gens): 0},
                                          *gens).as_expr() for p in (n, d))
        scale = sp.cancel(got_d / want_d)
        assert scale.is_Rational and scale != 0, (e, gens, got_d, want_d)
        assert sp.expand(got_n - scale * want_n) == 0, (e, gens, got_n, want_n, scale)


def check_polynomial_gens(e):
    free = e.free_symbols
    assert fp.polynomial_gens(e) == (_sort_gens(free) if free else None), e


def _gen_case(strategy):
    """An expression with one or two of its symbols as generators (an expression without symbols: a real one)."""
    return strategy.flatmap(lambda e: st.tuples(st.just(e), st.lists(
        st.sampled_from(sorted(e.free_symbols, key=sp.default_sort_key) or [GAINS.v]), min_size=1, max_size=2,
        unique=True).map(tuple)))


def check_poly_terms(case):
    expr, gens = case
    _same(ff.poly_terms, lambda a, b: sp.Poly(a, *b).terms(), expr, gens)


def check_ex_coefficients(case):
    expr, (var, *_) = case
    _same(ff.ex_coefficients, lambda a, b: sp.Poly(a, b, domain=sp.EX).all_coeffs(), expr, var)


def check_degree_in(case):
    expr, (gen, *_) = case
    _same(ff.degree_in, sp.degree, expr, gen)


def check_together(e):
    _same(ff.together, sp.together, e)


def _solution_list(solutions, unknowns):
    """Solutions (a list of dicts, of values of one unknown or of tuples of values, or one dict) as a list of tuples of
    values, a rational function written as ``cancel`` writes it (the fast path does not simplify them; sympy does)."""
    if isinstance(solutions, dict):
        solutions = [solutions]

    def values(s):
        return [s.get(u, u) for u in unknowns] if isinstance(s, dict) else list(s) if isinstance(s, tuple) else [s]

    return [tuple(sp.cancel(v) if fp.is_rational_function(v) else v for v in values(s)) for s in solutions]


def _equal_values(got, want) -> bool:
    """Equal tuples of values: a rational function as ``cancel`` writes it, a radical up to ``simplify`` (the fast
    path keeps a radical solution as sympy's solver writes it before simplifying, when its check is exact)."""
    return all(g == w or (not fp.is_rational_function(g) and sp.simplify(g - w) == 0) for g, w in zip(got, want))


def check_solve(case):
    """The same set of solutions, or the same refusal."""
    equations, unknowns, flags = case
    found = []
    for call in (ff.solve, sp.solve):
        try:
            found.append(_solution_list(call(equations, unknowns, **flags),
                                        unknowns if isinstance(unknowns, tuple) else (unknowns,)))
        except Exception as exc:  # noqa: BLE001 - the same refusal
            found.append(type(exc))
    got, want = found
    if isinstance(want, type) or isinstance(got, type):
        assert got == want, (equations, unknowns, found)
        return
    assert len(got) == len(set(got)) and len(set(want)) == len(want) == len(got), (equations, unknowns, found)
    assert all(any(_equal_values(g, w) for w in want) for g in got), (equations, unknowns, found)


UNKNOWNS = (sp.Symbol("e_x", real=True), sp.Symbol("t", real=True), sp.Symbol("u", real=True))
PARAMETERS = st.sampled_from(POSITIVE[:4] + REAL[:2])


_COEFFICIENTS = {flag: st.one_of(rationals, polynomials(PARAMETERS, max_terms=2 if flag else 1)) for flag in (True, False)}
"""A system's coefficients: polynomials of up to two terms in two unknowns or one, of one term in three (built once)."""


@st.composite
def systems(draw):
    """The forms the obligations solve: ``A·u = b`` in two or three unknowns, ``A`` and ``b`` polynomial in the gains
    (solved one unknown at a time), as a list with ``dict=True``; one polynomial equation of degree ≤ 2 in one
    unknown, alone (a list of values) or as an ``Eq`` with ``dict=True``."""
    n = draw(st.integers(1, 3))
    unknowns = UNKNOWNS[:n]
    coefficient = _COEFFICIENTS[n < 3]
    if n == 1:
        a, b, c, d = (draw(coefficient) for _ in range(4))
        q = draw(st.sampled_from(POSITIVE[:3] + (sp.Rational(1, 3), sp.Integer(2))))
        x = unknowns[0]
        # roots that are rational functions (the fast path checks them), or real radicals (see
        # test_roots_that_are_not_real_are_dropped_as_sympy_drops_them for the others)
        lhs, rhs = draw(st.sampled_from([(a * x * (c * x - d), b * x), (a * x + b, d), (q * x**2, GAINS.k_p + c**2)]))
        if draw(st.booleans()):
            return sp.expand(lhs - rhs), x, {}
        return sp.Eq(lhs, rhs), x, {"dict": True}
    rows = [[draw(coefficient) for _ in range(n)] for _ in range(n)]
    equations = [sp.Add(*(a * u for a, u in zip(row, unknowns))) - draw(coefficient) for row in rows]
    assume(all(e.has(*unknowns) for e in equations))  # an equation without unknowns: FOUND_DIFFERENCES
    return equations, unknowns, {"dict": True}


# ---------------------------------------------------------------------------------------- the property tests

def check_other_forms(e):
    for check in (check_cancel, check_factor, check_expand, check_factor_list, check_together):
        check(e)


PROPERTIES = {
    "cancel": (check_cancel, fractions_, 25),
    "factor": (check_factor, fractions_, 25),
    "expand": (check_expand, st.one_of(laurent, rational_functions(max_leaves=5)), 25),
    "factor_list": (check_factor_list, st.one_of(polynomials(), rational_functions(min_power=0),
                                                 reducible_fractions()), 25),
    "expanded_det": (check_expanded_det, st.one_of(laurent_matrices, matrices), 12),
    "factored_det": (check_factored_det, st.one_of(laurent_matrices, matrices), 12),
    "rational_pair": (check_rational_pair, fractions_, 20),
    "polynomial_gens": (check_polynomial_gens, rational_functions(), 20),
    "poly_terms": (check_poly_terms, _gen_case(st.one_of(rational_functions(min_power=0), polynomials(), laurent,
                                                         quotients)), 25),
    "ex_coefficients": (check_ex_coefficients, _gen_case(st.one_of(rational_functions(min_power=0), polynomials(),
                                                                   rational_functions(max_leaves=5), quotients)), 25),
    "degree_in": (check_degree_in, _gen_case(st.one_of(rational_functions(min_power=0), polynomials(), laurent,
                                                       quotients)), 25),
    "together": (check_together, st.one_of(polynomials(max_terms=5), rational_functions(max_leaves=5), st.tuples(
        _monomial(), polynomials(st.sampled_from(SYMBOLS[:3]))).map(lambda t: sp.expand(t[0] * t[1]))), 25),
    "solve": (check_solve, systems(), 8),
    "other forms": (check_other_forms, st.one_of(outside, rational_functions(
        st.one_of(st.sampled_from(ALIKE), rationals), max_leaves=5).filter(lambda e: len(e.free_symbols) == 2)), 15),
}
"""Each property: its check, its examples' strategy and how many (the mutants below are run on the same ones)."""


def _property(name: str, phases=tuple(Phase)):
    """The property test of :data:`PROPERTIES`'s ``name`` (derandomized: the examples depend on the check)."""
    check, strategy, count = PROPERTIES[name]
    return settings(SETTINGS, max_examples=count, phases=phases)(given(strategy)(check))


test_cancel_is_sympys = _property("cancel")
test_factor_is_sympys = _property("factor")
test_expand_is_sympys = _property("expand")
test_factor_list_is_sympys = _property("factor_list")
test_expanded_det_is_sympys = _property("expanded_det")
test_factored_det_is_sympys = _property("factored_det")
test_rational_pair_is_sympys_reduced_fraction = _property("rational_pair")
test_polynomial_gens_are_sympys = _property("polynomial_gens")
test_poly_terms_are_sympys = _property("poly_terms")
test_ex_coefficients_are_sympys = _property("ex_coefficients")
test_degree_in_is_sympys = _property("degree_in")
test_together_is_sympys = _property("together")
test_solve_finds_sympys_solutions = _property("solve")
test_other_forms_go_to_sympy = _property("other forms")


def test_two_symbols_printed_alike_go_to_sympy():
    alike, real = ALIKE
    assert fp.polynomial_gens(alike + real) is None
    for e in ((alike - real) / (real + 1), (alike**2 - real**2) / (alike - real), alike * real - real):
        check_cancel(e)
        check_factor(e)
        check_factor_list(e)
    check_expand((alike + real) ** 2 / alike)
    check_factored_det(sp.Matrix([[alike, real], [1, alike]]))
    check_expanded_det(sp.Matrix([[alike, real], [1, alike]]))


def _refuse(*args, **kwargs):
    """python-flint broken: every polynomial context asked for raises."""
    raise RuntimeError("python-flint unavailable")


FLINT_SAMPLES = [
    (GAINS.k_p**2 - GAINS.k_i**2) / (GAINS.k_i - GAINS.k_p),
    GAINS.sigma / (1 - GAINS.phi) + sp.Rational(1, 3),
    (GAINS.k_v + 1 / GAINS.k_p) ** 2 * GAINS.f_c,
    3 * GAINS.v**2 * GAINS.e_i - 6 * GAINS.v,
]


def test_a_failing_python_flint_gives_sympys_results(monkeypatch):
    monkeypatch.setattr(flint.fmpz_mpoly_ctx, "get", staticmethod(_refuse))
    with pytest.raises(RuntimeError, match="unavailable"):
        fp.rational_pair(GAINS.k_p, [GAINS.k_p])  # the fast path does fail
    for e in FLINT_SAMPLES:
        check_cancel(e)
        check_factor(e)
        check_expand(e)
        check_factor_list(e)
    m = sp.Matrix([[GAINS.k_p, 1 / GAINS.k_i], [GAINS.sigma, GAINS.k_v]])
    check_expanded_det(m)
    check_factored_det(m)


def check_goes_to_sympy(e):
    assert fp.polynomial_gens(e) is None, e


X, X0, X1, X01 = (sp.Symbol(name, real=True) for name in ("x", "x0", "x1", "x01"))
FOUND_DIFFERENCES = {
    # Forms on which the fast path once differed from sympy (found by the properties above, none met by an
    # obligation), each now sympy's: solve([equation], x), one symbol without dict: sympy answers {x: value}
    # (linear) or [(value,), ...]; the fast path read that dict's keys as solutions or substituted a tuple
    "solve: a list, one unknown, linear": (check_solve, ([GAINS.k_p * UNKNOWNS[0] - 1], UNKNOWNS[0], {})),
    "solve: a list, one unknown, quadratic": (check_solve, ([UNKNOWNS[0] ** 2 - GAINS.k_i], UNKNOWNS[0], {})),
    # a real unknown: the fast path checked a solution by substituting it, not against the unknown's assumptions
    "solve: +-i*sqrt(k_p) for a real unknown": (check_solve, (-UNKNOWNS[0] ** 2 - GAINS.k_p, UNKNOWNS[0], {})),
    "solve: 0 and +-i for a real unknown": (check_solve, (UNKNOWNS[0] * (UNKNOWNS[0] ** 2 + 1), UNKNOWNS[0], {})),
    # ex_coefficients filed zoo and nan as numbers; sympy's Poly(..., domain=EX) refuses them (CoercionFailed)
    "ex_coefficients: zoo": (check_ex_coefficients, (sp.zoo, (GAINS.v,))),
    "ex_coefficients: zoo*v": (check_ex_coefficients, (sp.zoo * GAINS.v, (GAINS.v,))),
    # an equation without unknowns that is not 0 (-k_p = 0): sympy answers {u: 0}, the fast path found none
    "solve: an equation free of the unknowns": (check_solve, ([0, UNKNOWNS[2], -GAINS.k_p], UNKNOWNS, {"dict": True})),
    # names with one sort key (x and x0, x1 and x01): sympy orders them by hashing, the fast path by its own set's
    # order (a denominator's sign then differed under some PYTHONHASHSEED: cancel(1/(x - x0**2)))
    "polynomial_gens: x and x0": (check_goes_to_sympy, X - X0**2),
    "polynomial_gens: x1 and x01": (check_goes_to_sympy, X1 - X01**2),
}


@pytest.mark.parametrize("difference", FOUND_DIFFERENCES)
def test_differences_found_from_sympy_are_gone(difference):
    """Each form on which the fast path once differed from sympy gives sympy's result now."""
    check, case = FOUND_DIFFERENCES[difference]
    check(case)


# ------------------------------------------------------------------------------- every comparison can fail

GUARDED = ("cancel", "factor", "factor_list", "expand", "expanded_det", "factored_det")


def _mutate(monkeypatch, module, name: str, old: str, new: str) -> None:
    """Replace ``module.name`` by a copy of its source with ``old`` (which occurs once) replaced by ``new``, and
    rebuild :mod:`._fastpoly`'s guarded functions so that they call the module's (possibly mutated) fast paths."""
    source = textwrap.dedent(inspect.getsource(getattr(module, name)))
    assert source.count(old) == 1, (name, old)
    namespace = dict(vars(module))
    exec(compile(source.replace(old, new), inspect.getsourcefile(module), "exec"), namespace)  # noqa: S102
    monkeypatch.setattr(module, name, namespace[name])
    rebuilt = {}
    for public in GUARDED:
        run = getattr(fp, public)
        cells = dict(zip(run.__code__.co_freevars, (c.cell_contents for c in run.__closure__)))
        rebuilt[public] = fp._guarded(getattr(fp, cells["fast"].__name__), cells["reference"])
    for public, run in rebuilt.items():
        monkeypatch.setattr(fp, public, run)


def _finds_a_difference(test) -> None:
    """The test fails on the mutated subject (a property test on its own examples, not shrinking)."""
    if isinstance(test, str):
        test = _property(test, phases=(Phase.explicit, Phase.generate))
    with pytest.raises(AssertionError):
        test()


MUTANTS = {
    "cancel: no sign normalisation": ("cancel", fp, "_fast_cancel", "if d.leading_coefficient() < 0:", "if False:"),
    "cancel: a term dropped": ("cancel", fp, "_to_expr", "return sp.Add(*terms)", "return sp.Add(*terms[1:])"),
    "factor: a numerator's factor dropped": ("factor", fp, "_factored", "for f, k in fn]", "for f, k in fn[1:]]"),
    "factor: denominators' factors as numerators'": (
        "factor", fp, "_factored", "** -int(k) for f, k in fd]", "** int(k) for f, k in fd]"),
    "expand: a term dropped": ("expand", fp, "_laurent_expr", "return sp.Add(*terms)", "return sp.Add(*terms[1:])"),
    "expand: the denominator's exponents ignored": ("expand", fp, "_laurent_expr", "int(m) - int(k)", "int(m)"),
    "factor_list: a factor dropped": ("factor_list", fp, "_fast_factor_list", "for f, k in fn]", "for f, k in fn[1:]]"),
    "factor_list: the denominator left out of the constant": (
        "factor_list", fp, "_fast_factor_list", "int(d.leading_coefficient())", "1"),
    "expanded_det: the cofactors' signs": ("expanded_det", fp, "_det_pair", "if j % 2 == 0", "if j % 2 == 1"),
    "factored_det: the cofactors' signs": ("factored_det", fp, "_det_pair", "if j % 2 == 0", "if j % 2 == 1"),
    "factored_det: a factor dropped": ("factored_det", fp, "_factored", "for f, k in fn]", "for f, k in fn[1:]]"),
    "rational_pair: a sum's terms subtracted": (
        "rational_pair", fp, "rational_pair", "+ an * (d / g)", "- an * (d / g)"),
    "polynomial_gens: sympy's rank of one-letter names ignored": (
        "polynomial_gens", fp, "_sorted_gens", "_gens_order.get(name, _max_order)", "0"),
    "poly_terms: increasing order": (
        "poly_terms", ff, "poly_terms", "sorted(grouped, reverse=True)", "sorted(grouped)"),
    "ex_coefficients: lowest power first": (
        "ex_coefficients", ff, "ex_coefficients", "range(degree, -1, -1)", "range(degree + 1)"),
    "degree_in: degrees above 1 read as 1": (
        "degree_in", ff, "degree_in", "top = max(top, power[1])", "top = max(top, 1)"),
    "together: common powers of symbols left in": ("together", ff, "_together_polynomial", "min(e, exps[x])", "0"),
    "solve: a linear step's sign": (
        "solve", ff, "_linear_chain", "-terms.get((0,), sp.Integer(0))",
        "terms.get((0,), sp.Integer(0))"),
    "solve: the failing solutions kept": ("solve", ff, "solve", "if all(verdicts) and", "if not all(verdicts) and"),
    "other forms: cancel returns them as they are": (
        "other forms", fp, "_fast_cancel", "return _sympy_cancel(expr)", "return expr"),
    "other forms: factor returns them as they are": (
        "other forms", fp, "_fast_factor", "return _sympy_factor(expr)", "return expr"),
    "other forms: expand returns them as they are": (
        "other forms", fp, "_fast_expand", "_monomial_denominators(expr):\n        return _sympy_expand(expr)",
        "_monomial_denominators(expr):\n        return expr"),
    "other forms: together returns them as they are": (
        "other forms", ff, "together", "sp.together(expr) if", "expr if"),
    "symbols printed alike: taken apart by name": (
        test_two_symbols_printed_alike_go_to_sympy, fp, "_sorted_gens", "!= len(syms)", "< 0"),
    "python-flint failing: the failure passed on": (
        test_a_failing_python_flint_gives_sympys_results, fp, "_guarded", "return reference(expr)", "raise"),
}


@pytest.mark.parametrize("mutant", MUTANTS)
def test_each_comparison_finds_its_mutant(mutant, monkeypatch):
    test, module, name, old, new = MUTANTS[mutant]
    ff.together.cache_clear()  # remembered results of the unmutated subject
    try:
        _mutate(monkeypatch, module, name, old, new)
        if test is test_a_failing_python_flint_gives_sympys_results:
            test = functools.partial(test, monkeypatch)
        _finds_a_difference(test)
    finally:
        ff.together.cache_clear()


def test_rational_symbols_of_an_unhashable_expression_is_decided_without_the_memo():
    """A mutable matrix cannot key the memo: it is decided directly (not a rational function's expression), never
    a ``TypeError``; its entries, hashable, are decided through the memo."""
    x, y = sp.symbols("x y", positive=True)
    m = sp.Matrix([[x / y]])
    assert fp.rational_symbols(m) is None
    assert fp.rational_symbols(m[0, 0]) == frozenset({x, y})
    assert fp.rational_symbols(sp.sqrt(x)) is None
