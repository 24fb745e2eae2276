"""Every branch of the exact decision procedures, with the answer a wrong branch would give refused.

Each test reaches one branch of :mod:`symbolic_friction._obligations._decide`
with an input on which a mutated procedure (a flipped comparison, a dropped
case, a wrong table entry) would answer differently, and pins the message of
every ``Undecided`` so that a refusal says what could not be decided.
"""

from __future__ import annotations

import pytest
import sympy as sp

from symbolic_friction._obligations import _decide as D
from symbolic_friction._obligations._decide import (
    Undecided,
    affine_image,
    decide,
    interval_partitions_reals,
    is_zero,
    minimum_on,
    phi_classes,
    pos,
    resolve_piecewise,
    sign_classes,
    sign_of,
    vertices,
)

a, b, c = pos("a"), pos("b"), pos("c")
x = sp.Symbol("x", real=True)
n = sp.Symbol("n", nonnegative=True)


def test_pos_and_G():
    s = pos("q")
    assert s.name == "q" and s.is_positive is True
    assert D.G() is D.G()


def test_rational_function_recognition():
    assert D._is_rational_function(a / b + 3 * c**2 - sp.Rational(1, 2))
    assert D._is_rational_function((a + b) ** -2)
    assert not D._is_rational_function(sp.sqrt(a) + 1)
    assert not D._is_rational_function(a ** sp.Rational(1, 3))
    assert not D._is_rational_function(sp.exp(a))
    assert not D._is_rational_function(sp.Float(0.5) * a)


def test_is_zero_every_branch():
    assert is_zero(0) and is_zero(sp.Integer(0))
    assert not is_zero(1) and not is_zero(sp.Rational(1, 3))
    assert is_zero(1 / (a + b) - (a - b) / (a**2 - b**2))  # zero only after together()
    assert is_zero(sp.expand((a + b) ** 2) - (a + b) ** 2)
    assert not is_zero(a - b)
    assert not is_zero(1 / (a + b) - 1 / (a + 2 * b))
    assert is_zero(sp.sin(a) ** 2 + sp.cos(a) ** 2 - 1)  # simplify decides a non-rational identity
    assert not is_zero(sp.Abs(x) - x)  # Abs: not simplified, never called zero
    assert not is_zero(sp.Max(x, 0) - x)
    assert not is_zero(sp.sqrt(a) - 1)


def test_number_sign():
    assert sign_of(sp.Integer(0)) == 0
    assert sign_of(sp.Rational(-1, 2)) == -1 and sign_of(sp.Rational(1, 2)) == 1
    assert sign_of(sp.pi - 3) == 1 and sign_of(3 - sp.pi) == -1
    assert sign_of(sp.nan) is None
    assert D._number_sign(sp.Integer(0)) == 0


def test_poly_sign_every_branch():
    assert D._poly_sign(sp.Integer(0)) == 0
    assert D._poly_sign(sp.Integer(-3)) == -1
    assert D._poly_sign(a**2 + a * b + 1) == 1
    assert D._poly_sign(-(a**2) - 2 * b) == -1
    assert D._poly_sign(a - b) is None
    assert D._poly_sign(a - 1) is None
    assert D._poly_sign(sp.pi * a) is None  # an irrational coefficient is not decided
    assert D._poly_sign(sp.sqrt(a) + 1) is None  # not a polynomial
    assert D._poly_sign(a * b - a * b + 2 * c) == 1


def test_sign_of_every_branch():
    assert sign_of(n + 1) is None  # a nonnegative symbol is not positive
    assert sign_of(x**2 + 1) is None
    assert sign_of(a + n) is None
    for f in (sp.Abs(a - b) + 1, sp.Max(a, b), sp.Min(a, b), sp.sign(a - b) + 2):
        assert sign_of(f) is None
    assert sign_of(sp.Piecewise((a, a > b), (b, True))) is None
    assert sign_of(a * b + 1) == 1 and sign_of(-a - b) == -1
    assert sign_of(a / (b + 1)) == 1
    assert sign_of(a / (-b - 1)) == -1
    assert sign_of(-a / (b + 1)) == -1
    assert sign_of(-a / (-b - 1)) == 1
    assert sign_of((a - b) / (a + b)) is None  # numerator undecided
    assert sign_of(a / (a - b)) is None  # denominator undecided
    assert sign_of((a**2 - a**2 * (1 + b) + a**2 * b) / (a + 1)) == 0
    assert sign_of(1 / a + 1 / b) == 1


def _rel(kind, lhs, rhs):
    return kind(lhs, rhs, evaluate=False)


@pytest.mark.parametrize(
    "kind, want",
    [
        (sp.StrictGreaterThan, {1: True, 0: False, -1: False}),
        (sp.GreaterThan, {1: True, 0: True, -1: False}),
        (sp.StrictLessThan, {1: False, 0: False, -1: True}),
        (sp.LessThan, {1: False, 0: True, -1: True}),
        (sp.Equality, {1: False, 0: True, -1: False}),
        (sp.Unequality, {1: True, 0: False, -1: True}),
    ],
)
def test_decide_every_relation_and_sign(kind, want):
    lhs = {1: a * b + 1, 0: a * b, -1: a * b - a * b - c}
    for sg, expected in want.items():
        assert decide(_rel(kind, lhs[sg], a * b if sg == 0 else 0)) is expected, (kind, sg)
    assert decide(_rel(kind, a, b)) is None


def test_decide_connectives():
    t, f, u = _rel(sp.Gt, a + 1, 0), _rel(sp.Lt, a + 1, 0), _rel(sp.Gt, a, b)
    assert decide(True) is True and decide(sp.true) is True
    assert decide(False) is False and decide(sp.false) is False
    assert decide(sp.And(t, t, evaluate=False)) is True
    assert decide(sp.And(t, u, evaluate=False)) is None  # an undecided conjunct
    assert decide(sp.And(u, f, evaluate=False)) is False  # a false conjunct decides
    assert decide(sp.Or(f, f, evaluate=False)) is False
    assert decide(sp.Or(f, u, evaluate=False)) is None
    assert decide(sp.Or(u, t, evaluate=False)) is True
    assert decide(sp.Not(t, evaluate=False)) is False
    assert decide(sp.Not(f, evaluate=False)) is True
    assert decide(sp.Not(u, evaluate=False)) is None
    assert decide(a) is None  # not a relation


def test_resolve_piecewise():
    pw = sp.Piecewise((a, _rel(sp.Lt, a + 1, 0)), (b, _rel(sp.Gt, a + 1, 0)), (c, True))
    assert resolve_piecewise(pw) == b
    assert resolve_piecewise(pw + sp.Piecewise((c, _rel(sp.Ge, a, 0)), (a, True))) == b + c
    with pytest.raises(Undecided, match=r"^cannot decide the branch condition a > b$"):
        resolve_piecewise(sp.Piecewise((a, _rel(sp.Gt, a, b)), (b, True)))
    with pytest.raises(Undecided, match=r"^no branch of a Piecewise applies$"):
        resolve_piecewise(sp.Piecewise((a, _rel(sp.Lt, a + 1, 0)), (b, _rel(sp.Lt, b + 1, 0)), evaluate=False))
    assert resolve_piecewise(a + b) == a + b
    assert resolve_piecewise(3) == 3


def test_vertices():
    assert vertices(sp.FiniteSet(1, 3)) == [1, 3]
    assert vertices(sp.Interval(0, a)) == [0, a]
    for bad in (sp.Interval.open(0, 1), sp.Interval.Lopen(0, 1), sp.Interval.Ropen(0, 1), sp.Interval(0, sp.oo),
                sp.Interval(-sp.oo, 0)):
        with pytest.raises(Undecided, match="is neither finite nor a closed bounded interval"):
            vertices(bad)


def test_stationary_points():
    assert D._stationary_points(a + 0 * x, x) == []
    assert D._stationary_points(3 * x + 1, x) == []
    assert D._stationary_points(x**2 - 2 * x, x) == [1]
    assert D._stationary_points(a * x**2 - 2 * b * x, x) == [b / a]
    assert sorted(D._stationary_points(x**3 - 3 * x, x)) == [-1, 1]
    assert D._stationary_points(x**3 + 3 * x, x) == []  # complex roots only
    assert D._stationary_points(x + 1 / x, x) in ([-1, 1], [1, -1])  # a rational function: solve()


def test_minimum_on():
    f = (x - 1) ** 2
    assert minimum_on(f, x, sp.Interval(0, 3)) == 0  # interior stationary point
    assert minimum_on(f, x, sp.Interval(2, 3)) == 1  # at an end, the stationary point outside
    assert minimum_on(-f, x, sp.Interval(0, 3)) == -4
    assert minimum_on(x**2, x, sp.FiniteSet(-2, 1, 3)) == 1
    assert minimum_on((x - a) ** 2, x, sp.Interval(0, a + b)) == 0
    with pytest.raises(Undecided, match=r"^cannot decide whether the stationary point a lies in Interval\(0, b\)$"):
        minimum_on((x - a) ** 2, x, sp.Interval(0, b))
    with pytest.raises(Undecided, match=r"^cannot order the candidate values \[a, b\] of the minimum over \{a, b\}$"):
        minimum_on(x, x, sp.FiniteSet(a, b))


def test_affine_image():
    assert affine_image(2 * x + 1, x, sp.Interval(0, 1)) == sp.Interval(1, 3)
    assert affine_image(-2 * x + 1, x, sp.Interval(0, 1)) == sp.Interval(-1, 1)
    assert affine_image(2 * x, x, sp.Interval.Ropen(0, 1)) == sp.Interval.Ropen(0, 2)
    assert affine_image(-2 * x, x, sp.Interval.Ropen(0, 1)) == sp.Interval.Lopen(-2, 0)
    assert affine_image(-2 * x, x, sp.Interval.Lopen(0, 1)) == sp.Interval.Ropen(-2, 0)
    assert affine_image(a + 0 * x, x, sp.Interval(0, 1)) == sp.FiniteSet(a)
    with pytest.raises(Undecided, match=r"^x\*\*2 is not affine in x$"):
        affine_image(x**2, x, sp.Interval(0, 1))
    with pytest.raises(Undecided, match=r"^cannot decide the sign of the slope a - b$"):
        affine_image((a - b) * x, x, sp.Interval(0, 1))


def test_interval_partitions_reals():
    I = sp.Interval
    ok, why = interval_partitions_reals([I.open(0, sp.oo), I(-sp.oo, 0)])
    assert ok and why == ""
    assert interval_partitions_reals([I.open(-sp.oo, 0), I.Ropen(0, 1), I(1, sp.oo)]) == (True, "")
    assert interval_partitions_reals([I(1, sp.oo), I.open(-sp.oo, 0), I(0, 1)]) == (
        False, "Interval(0, 1) and Interval(1, oo) both contain the point 1")
    assert interval_partitions_reals([I.open(-sp.oo, 0), I.open(0, sp.oo)]) == (
        False, "Interval.open(-oo, 0) and Interval.open(0, oo) both miss the point 0")
    assert interval_partitions_reals([I.open(0, sp.oo)]) == (False, "0 intervals start at -oo (expected exactly one)")
    assert interval_partitions_reals([I.open(-sp.oo, 0), I(-sp.oo, 1), I.open(1, sp.oo)]) == (
        False, "2 intervals start at -oo (expected exactly one)")
    assert interval_partitions_reals([I.open(-sp.oo, 0), I(1, sp.oo)]) == (
        False, "0 intervals start where Interval.open(-oo, 0) ends (expected exactly one)")
    assert interval_partitions_reals([I.open(-sp.oo, 0), I(0, sp.oo), I(0, 1)]) == (
        False, "2 intervals start where Interval.open(-oo, 0) ends (expected exactly one)")
    assert interval_partitions_reals([I(-sp.oo, sp.oo), I(0, 1)]) == (False, "the intervals [Interval(0, 1)] overlap the others")
    assert interval_partitions_reals([I(-sp.oo, sp.oo)]) == (True, "")


def test_phi_classes_are_exact_and_cover_their_regions():
    classes = phi_classes(c, "t")
    assert [lab for lab, *_ in classes] == ["φ > f_c", "φ = f_c", "|φ| < f_c", "φ = -f_c", "φ < -f_c"]
    assert [tex for _, tex, *_ in classes] == ["\\phi > f_c", "\\phi = f_c", "|\\phi| < f_c", "\\phi = -f_c", "\\phi < -f_c"]
    p, aa, bb = pos("pt"), pos("at"), pos("bt")
    assert classes[0][2] == c + p and classes[4][2] == -c - p
    assert classes[1][2] == c and classes[3][2] == -c
    assert sp.simplify(classes[2][2] - (aa * c - bb * c) / (aa + bb)) == 0
    assert classes[0][3] == sp.Interval.open(c, sp.oo) and classes[4][3] == sp.Interval.open(-sp.oo, c * -1)
    assert classes[1][3] == sp.FiniteSet(c) and classes[3][3] == sp.FiniteSet(-c)
    assert classes[2][3] == sp.Interval.open(-c, c)
    assert phi_classes(c)[0][2] == c + pos("p")


def test_sign_classes():
    q = pos("s")
    assert sign_classes("s") == [("> 0", 1, q), ("= 0", 0, sp.Integer(0)), ("< 0", -1, -q)]


def test_undecided_is_an_exception():
    assert issubclass(Undecided, Exception)


# -- is_zero: simplify() is never asked about a non-smooth function nor a rational one --------------------------------

_PYTHAGORAS = sp.sin(x) ** 2 + sp.cos(x) ** 2  # 1, but only simplify() sees it


@pytest.mark.parametrize("expr", [
    sp.Piecewise((_PYTHAGORAS, x > 1), (1, True)) - 1,
    sp.Abs(_PYTHAGORAS - 2) - 1,
    sp.sign(_PYTHAGORAS - 2) + 1,
    sp.Max(_PYTHAGORAS, sp.Rational(1, 2)) - 1,
    sp.Min(_PYTHAGORAS, 2) - 1,
], ids=["Piecewise", "Abs", "sign", "Max", "Min"])
def test_is_zero_leaves_non_smooth_identities_to_case_splits(expr):
    """Each is 0, and simplify() shows it; is_zero still answers "not shown".

    A Piecewise, |·|, sign, max or min is resolved by the obligations' explicit case splits
    (:func:`resolve_piecewise` with decided branch conditions), never by simplify()'s heuristics: each of the
    five is listed in the guard, and removing any one of them changes the answer on its input here.
    """
    num = sp.expand(sp.fraction(sp.together(expr))[0])
    assert sp.simplify(num) == 0  # the heuristic would have called it zero
    assert is_zero(expr) is False


def test_is_zero_decides_rational_functions_by_expansion_alone():
    """A rational function is zero iff its expanded numerator is: the polynomial identity, not the symbols' assumptions.

    ``z`` declared zero is still the non-zero polynomial ``z`` (simplify() would replace it by 0), so a
    rational function never reaches simplify().
    """
    z = sp.Symbol("z", zero=True)
    assert sp.simplify(z) == 0
    assert is_zero(z) is False and is_zero(a * z + z / b) is False
    assert is_zero(z - z) is True


# -- _stationary_points: the exact-root shortcuts and the solve() fallback -------------------------------------------

def test_stationary_points_of_a_quintic_that_roots_cannot_solve():
    """x⁵ − x − 1 has one real root that roots() does not find (it returns {}): solve() must give it (as a CRootOf).

    Returning what roots() found would drop the stationary point, and minimum_on would answer the value at an
    end, -4/3, above the true minimum ≈ -1.4265 of x⁶/6 − x²/2 − x on [1, 2].
    """
    f = x**6 / 6 - x**2 / 2 - x
    assert sp.roots(sp.Poly(sp.diff(f, x), x)) == {}
    (r,) = D._stationary_points(f, x)
    assert isinstance(r, sp.CRootOf) and r.poly == sp.Poly(x**5 - x - 1, x)
    m = minimum_on(f, x, sp.Interval(1, 2))
    assert m == f.subs(x, r)
    assert sign_of(sp.Rational(-4, 3) - m) == 1  # strictly below the value at the end 1
    assert sign_of(m - sp.Rational(-143, 100)) == 1 and sign_of(sp.Rational(-142, 100) - m) == 1


def test_stationary_points_of_a_transcendental_function():
    """exp(x) − √6·x: f' = exp(x) − √6 is not a polynomial; solve() gives log(√6), kept as found (not simplified)."""
    f = sp.exp(x) - sp.sqrt(6) * x
    found = D._stationary_points(f, x)
    assert found == [sp.log(sp.sqrt(6))] and found[0].args == (sp.sqrt(6),)  # simplify would give log(6)/2
    assert D._stationary_points(a * f, x) == found  # another symbol in f': solve() is told which is the variable
    m = minimum_on(f, x, sp.Interval(0, 2))
    assert m == sp.sqrt(6) - sp.sqrt(6) * sp.log(sp.sqrt(6))
    assert D._stationary_points(-f, x) == found
    # solve() also returns the complex roots ±2πi/3 of exp(3y) = 1 for a symbol y not declared real: dropped
    y = sp.Symbol("y")
    assert D._stationary_points(sp.exp(3 * y) / 3 - y, y) == [0]


def test_or_and_of_distinct_decided_relations():
    """Or(f, f) collapses to f when built: two *different* false disjuncts reach the Or branch (and so for And)."""
    f1, f2 = _rel(sp.Lt, a + 1, 0), _rel(sp.Lt, b + 1, 0)
    t1, t2 = _rel(sp.Gt, a + 1, 0), _rel(sp.Gt, b + 1, 0)
    assert isinstance(sp.Or(f1, f2, evaluate=False), sp.Or) and isinstance(sp.And(t1, t2, evaluate=False), sp.And)
    assert decide(sp.Or(f1, f2, evaluate=False)) is False
    assert decide(sp.Or(f1, t2, evaluate=False)) is True
    assert decide(sp.And(t1, t2, evaluate=False)) is True
    assert decide(sp.And(t1, f2, evaluate=False)) is False


def test_poly_sign_of_mixed_coefficients_below_one():
    """½a − b has coefficients ½ and −1, both below 1 but of both signs: undecided, not negative."""
    assert D._poly_sign(sp.expand(a / 2 - b)) is None
    assert sign_of(a / 2 - b) is None and sign_of(sp.Rational(1, 3) * a - sp.Rational(1, 2) * b) is None
    assert sign_of(-a / 2 - b) == -1


def test_sign_of_is_an_int_never_a_float():
    """The module uses no float: the sign of a quotient is the product of the two signs (an int), not their ratio."""
    for expr, want in ((a / (b + 1), 1), (a / (-b - 1), -1), (-a / (b + 1), -1), (-a / (-b - 1), 1),
                       ((a * (b + 1) - a * b - a) / (a + b), 0)):
        got = sign_of(expr)
        assert got == want and type(got) is int, (expr, got)


@pytest.mark.parametrize("f", [
    sp.Piecewise((a, a > b), (b, True)), sp.Abs(a - b), sp.sign(a - b), sp.Max(a, b), sp.Min(a, b),
], ids=["Piecewise", "Abs", "sign", "Max", "Min"])
def test_sign_of_refuses_a_non_smooth_function_even_when_it_cancels(f):
    """c·(F + 1) − c·F is c > 0 once expanded, but sign_of decides rational functions only: it refuses it whole.

    Any Piecewise, |·|, sign, max or min is to be resolved by :func:`resolve_piecewise` with its branch
    conditions decided; each of the five is listed in the guard, and removing any one of them lets the
    expansion decide its input here.
    """
    expr = c * (f + 1) - c * f
    assert sp.expand(expr) == c  # what the polynomial test would decide without the guard
    assert sign_of(expr) is None
    assert sign_of(c * (f + 1) / (a + b) - c * f / (a + b)) is None  # and with a denominator


# -- the rational-function field, the radical path, and the convex-quadratic shortcut ---------------------------------

_ONE = (1 + sp.sqrt(2)) * (sp.sqrt(2) - 1)  # 1 once expanded, but a radical until then: not a rational function


def test_sign_of_cancels_common_factors_in_the_field():
    """(a² − b²)/(a − b) is a + b wherever it is defined: positive, though a² − b² and a − b have no sign."""
    assert sign_of((a**2 - b**2) / (a - b)) == 1
    assert sign_of((b**2 - a**2) / (a - b)) == -1


def test_sign_of_a_radical_with_a_denominator_is_decided_on_together():
    """a·(1+√2)(√2−1) + 1/a is (a² + 1)/a after together(): positive, though the expansion a + 1/a is no polynomial."""
    expr = a * _ONE + 1 / a
    assert not D._is_rational_function(expr) and D._has_denominator(expr)
    assert sign_of(expr) == 1 and sign_of(-expr) == -1
    assert sign_of(a * _ONE - 1 / a) is None  # (a² − 1)/a: mixed
    # without a denominator the expansion itself is the polynomial: here the constant 1
    assert sign_of((a + sp.sqrt(2)) * (a - sp.sqrt(2)) - a**2 + 3) == 1


def test_is_zero_of_a_radical_expression_by_its_expanded_numerator():
    """a·(1+√2)(√2−1) − a expands to 0 (an identity); adding 1 gives the non-zero constant 1 without simplify()."""
    assert is_zero(a * _ONE - a) is True
    assert is_zero(a * _ONE - a + 1) is False
    assert is_zero(a * _ONE / b - a / b) is True


def test_is_zero_decides_in_the_field_without_together_or_simplify(monkeypatch):
    """A rational function is decided in Q(symbols), and a radical one whose numerator expands to a polynomial by
    that expansion: neither needs simplify(), and the rational function not even together()."""
    def boom(*args, **kwargs):
        raise AssertionError("not needed here")

    monkeypatch.setattr(sp, "simplify", boom)
    assert is_zero(a * _ONE - a + 1) is False  # numerator 1: a polynomial, decided without simplify()
    monkeypatch.setattr(sp, "together", boom)
    assert is_zero((a + b) ** 2 - a**2 - 2 * a * b - b**2) is True
    assert is_zero((a**2 - b**2) / (a - b) - a - b) is True
    assert is_zero((a + b) ** 2 - a**2 - b**2) is False


def test_minimum_of_a_convex_quadratic_is_its_clipped_vertex(monkeypatch):
    """Vertex below, above and inside the interval: the value there, where comparing the candidates decides nothing.

    (x − a − b − c)² on [a, b]: the vertex a + b + c ≥ b, so the minimum is (a + c)² at b, but f(b) − f(a) expands to
    a² − b² + 2ac − 2bc (no sign); likewise (x − a + c)² on [a, b] (vertex a − c ≤ a, minimum c²), and
    (a³ + 1)(x − 1/(a + 1))² on [0, 1] (vertex inside, minimum 0, though f(0) = (a² − a + 1)/(a + 1) has no decided sign).
    """
    for f, s, want in (((x - a - b - c) ** 2, sp.Interval(a, b), (a + c) ** 2),
                       ((x - a + c) ** 2, sp.Interval(a, b), c**2),
                       ((a**3 + 1) * (x - 1 / (a + 1)) ** 2, sp.Interval(0, 1), 0)):
        assert is_zero(minimum_on(f, x, s) - want), (f, s)
        with monkeypatch.context() as m:  # the general method alone cannot order the candidates
            m.setattr(D, "_convex_quadratic_minimum", lambda *args: None)
            with pytest.raises(Undecided, match="cannot order the candidate values"):
                minimum_on(f, x, s)
    # the vertex is −β/(2α), not −β·α/2: 2(x − 1)² on [0, 3] has its minimum 0 at 1 (the other point, 4, is outside)
    assert minimum_on(2 * (x - 1) ** 2, x, sp.Interval(0, 3)) == 0
    # a vertex not decided inside is no minimum: c may lie left of a
    with pytest.raises(Undecided, match=r"cannot decide whether the stationary point c lies in Interval\(a, b \+ c\)"):
        minimum_on((x - c) ** 2, x, sp.Interval(a, b + c))


def test_minimum_on_drops_stationary_points_outside_the_interval():
    """x⁴ − 2x² has its stationary points −1, 0, 1 left of [2, 3]: the minimum is f(2) = 8, not f(±1) = −1; a cubic
    (no quadratic) is minimised by the general method."""
    assert minimum_on(x**4 - 2 * x**2, x, sp.Interval(2, 3)) == 8
    assert minimum_on(x**3 - 3 * x, x, sp.Interval(2, 3)) == 2
    assert minimum_on(x**3 - 3 * x, x, sp.Interval(0, 3)) == -2


# -- the fraction of integer polynomials (python-flint) ---------------------------------------------


def test_the_fraction_refuses_a_negative_power_of_a_zero_polynomial_naming_it():
    base = (a + 1) ** 2 - a**2 - 2 * a - 1  # the zero polynomial, not zero as a tree
    with pytest.raises(ZeroDivisionError, match=r"is identically zero in"):
        D._field_element(base**-1)


def test_the_fraction_refuses_what_is_not_a_rational_function():
    with pytest.raises(TypeError, match="sqrt\\(a\\) is not a rational function of its symbols"):
        D._field_element(sp.sqrt(a))


def test_negative_powers_invert_numerator_and_denominator_each_to_the_power():
    assert is_zero((a + 1) ** -2 - 1 / (a**2 + 2 * a + 1))  # a polynomial base: (1, (a + 1)²)
    assert is_zero((1 + 1 / a) ** -2 - a**2 / (a + 1) ** 2)  # a fraction base: (a², (a + 1)²)
    assert sign_of((1 + 1 / a) ** -2 - 1) == -1


def test_sums_bring_each_term_to_the_common_denominator_it_shares():
    # the first two denominators share the factor a: the common one is a·b·c, not a²·b·c
    assert is_zero(1 / a + 1 / (a * b) + 1 / (a * c) - (b * c + b + c) / (a * b * c))
    assert not is_zero(1 / a + 1 / (a * b) + 1 / (a * c) - (b * c + b + c) / (a * b * c) - 1 / (a * b * c))
