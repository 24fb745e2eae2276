"""The exact decision procedures used by the obligations (sign-definite
decomposition, Piecewise resolution, exact minimisation over intervals)."""

import pytest
import sympy as sp

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
    sign_of,
    vertices,
)

a, b, c = pos("a"), pos("b"), pos("c")
x = sp.Symbol("x", real=True)


def test_sign_of_decides_sign_definite_rational_functions():
    assert sign_of(a + b * c) == 1
    assert sign_of(-(a**2) - 3 * b / c) == -1
    assert sign_of((a - b) ** 2 - (a**2 - 2 * a * b + b**2)) == 0
    assert sign_of(4 * b**2 / (a + b) ** 2) == 1
    assert sign_of(a * b + 2) == 1
    assert sign_of(-a / (b + 1)) == -1
    assert sign_of(a - a) == 0


def test_sign_of_refuses_what_it_cannot_prove():
    assert sign_of(a - b) is None  # indefinite
    assert sign_of(x**2 + 1) is None  # x is not declared positive
    assert sign_of(x**2) is None
    assert sign_of(sp.sqrt(a) - 1) is None  # radicals are not decided
    assert sign_of(sp.Abs(a - b)) is None


def test_sign_of_cancels_symbols_that_drop_out():
    assert sign_of((x**2 + a) - x**2) == 1


def test_is_zero_on_rational_functions_and_radicals():
    assert is_zero((a**2 - b**2) / (a - b) - (a + b))
    assert not is_zero(a - b)
    assert is_zero(sp.sqrt(a) ** 2 - a)
    assert not is_zero(sp.Piecewise((1, x > 0), (0, True)))


def test_decide_relations():
    assert decide(sp.Gt(a + b, a)) is True
    assert decide(sp.Le(a + b, a)) is False
    assert decide(sp.Eq(a, a)) is True
    assert decide(sp.Ne(a + 1, a)) is True
    assert decide(sp.And(sp.Gt(a, 0), sp.Lt(-b, 0))) is True
    assert decide(sp.Or(sp.Lt(a, 0), sp.Gt(b, 0))) is True
    assert decide(sp.Not(sp.Gt(a, 0))) is False
    assert decide(sp.Gt(a, b)) is None
    assert decide(sp.And(a > 0, b + a > b)) is True
    assert decide(sp.Or(a < 0, sp.Eq(a, a + 1))) is False
    assert decide(sp.Not(a < b)) is None


def test_resolve_piecewise_picks_the_decided_branch():
    f = sp.Piecewise((x + 1, x < -1), (x - 1, x > 1), (0, True))
    assert resolve_piecewise(f.subs(x, 1 + a)) == a
    assert resolve_piecewise(f.subs(x, (a - b) / (a + b))) == 0
    pw = sp.Piecewise((1, a < -b), (2, a > b), (3, True))
    assert resolve_piecewise(pw.xreplace({a: b + c})) == 2


def test_resolve_piecewise_raises_when_undecided():
    f = sp.Piecewise((1, x > 1), (0, True))
    with pytest.raises(Undecided, match="cannot decide the branch condition"):
        resolve_piecewise(f.subs(x, a))
    with pytest.raises(Undecided, match="cannot decide the branch condition"):
        resolve_piecewise(sp.Piecewise((1, a < -b), (2, a > b), (3, True)))


def test_resolve_piecewise_raises_without_applicable_branch():
    f = sp.Piecewise((1, x > 1), (2, x < -1))
    with pytest.raises(Undecided, match="no branch of a Piecewise applies"):
        resolve_piecewise(f.subs(x, (a - b) / (a + b)))
    with pytest.raises(Undecided, match="no branch of a Piecewise applies"):
        resolve_piecewise(sp.Piecewise((1, a < 0), (2, sp.Eq(a, 0)), evaluate=False))


def test_minimum_on_interval_uses_interior_stationary_points():
    y = sp.Symbol("y", real=True)
    assert minimum_on((y - a / (a + b)) ** 2, y, sp.Interval(0, 1)) == 0
    assert sp.simplify(minimum_on((y - 1 - a) ** 2, y, sp.Interval(-1, 1)) - a**2) == 0
    assert minimum_on(-y, y, sp.FiniteSet(1, 2, 3)) == -3


def test_minimum_on_raises_when_the_stationary_point_is_unplaced():
    y = sp.Symbol("y", real=True)
    with pytest.raises(Undecided, match="cannot decide whether the stationary point"):
        minimum_on((y - a) ** 2, y, sp.Interval(0, b))


def test_minimum_on_raises_when_values_cannot_be_ordered():
    y = sp.Symbol("y", real=True)
    with pytest.raises(Undecided, match="cannot order the candidate values"):
        minimum_on(a * y, y, sp.FiniteSet(1, b))


def test_vertices_needs_a_compact_set():
    assert vertices(sp.Interval(-1, 1)) == [-1, 1]
    with pytest.raises(Undecided, match="neither finite nor a closed bounded interval"):
        vertices(sp.Interval.open(-1, 1))


def test_affine_image():
    w = sp.Symbol("w", real=True)
    assert affine_image(-a * w, w, sp.Interval(-1, 1)) == sp.Interval(-a, a)
    assert affine_image(0 * w + 2, w, sp.Interval(-1, 1)) == sp.FiniteSet(2)
    with pytest.raises(Undecided, match="is not affine"):
        affine_image(w**2, w, sp.Interval(-1, 1))
    with pytest.raises(Undecided, match="cannot decide the sign of the slope"):
        affine_image((a - b) * w, w, sp.Interval(-1, 1))


def test_interval_partitions_reals():
    ok, _ = interval_partitions_reals([sp.Interval(a, sp.oo), sp.Interval.open(-a, a), sp.Interval(-sp.oo, -a)])
    assert ok
    ok, why = interval_partitions_reals([sp.Interval(a, sp.oo), sp.Interval(-a, a), sp.Interval(-sp.oo, -a)])
    assert not ok and "both contain" in why
    ok, why = interval_partitions_reals([sp.Interval(a, sp.oo), sp.Interval(-sp.oo, -a)])
    assert not ok and "0 intervals start where" in why
    ok, why = interval_partitions_reals([sp.Interval(0, sp.oo)])
    assert not ok and "start at -oo" in why
    ok, why = interval_partitions_reals([sp.Interval(-sp.oo, 0), sp.Interval.Lopen(0, sp.oo), sp.Interval(5, 6)])
    assert not ok and "overlap" in why


def test_phi_classes_cover_their_regions():
    f_c = pos("f_c")
    for label, tex, value, region in phi_classes(f_c, "_t"):
        assert all(sym.is_positive for sym in sp.sympify(value).free_symbols)
        if isinstance(region, sp.FiniteSet):
            assert value in region
        else:
            lo_ok = region.start == -sp.oo or decide(sp.Gt(value, region.start))
            hi_ok = region.end == sp.oo or decide(sp.Lt(value, region.end))
            assert lo_ok and hi_ok, label
