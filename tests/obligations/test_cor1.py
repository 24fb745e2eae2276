"""Corollary 1: cor1.inflation and cor1.distances."""

from __future__ import annotations

import dataclasses
import itertools
from fractions import Fraction as F

import numpy as np
import sympy as sp

from symbolic_friction import Parameters
from symbolic_friction._model import attractor as _attractor
from symbolic_friction._obligations.cor1 import Distances, Inflation, _counterexample, _expand_abs_relations

from ..tolerance import assert_close
from ._helpers import assert_fails, assert_holds, subject_fixture

inflation = subject_fixture(Inflation)
distances = subject_fixture(Distances)


# ------------------------------------------------------------ cor1.inflation


def test_inflation_holds(inflation):
    out = assert_holds(Inflation(), inflation)
    rows = out.details[0][1]
    assert "|\\rho | = 0,\\  v = 0: [-1, 1]" in rows  # ρ = 0 gives SGN
    assert "v = |\\rho |: [- r - 1, r + 1]" in rows  # the boundary |v| = |ρ| is the wide interval


def test_inflation_wrong_friction_level(inflation):
    s = inflation
    wrong = sp.Piecewise((sp.sign(s.v) + s.r, sp.Abs(s.v) > s.r), (sp.Rational(11, 10) + s.r, True))
    assert_fails(Inflation(), dataclasses.replace(s, inflated_hi=wrong), "SGN_ρ(v) = [-r - 1, r + 11/10]")


def test_inflation_wrong_interval_boundary(inflation):
    s = inflation
    lo = sp.Piecewise((sp.sign(s.v) - s.r, sp.Abs(s.v) >= s.r), (-1 - s.r, True))
    hi = sp.Piecewise((sp.sign(s.v) + s.r, sp.Abs(s.v) >= s.r), (1 + s.r, True))
    altered = dataclasses.replace(s, inflated_lo=lo, inflated_hi=hi)
    # ρ = 0: SGN_0(0) would be {0}
    assert_fails(Inflation(), altered, "|ρ| > 0, v = -|ρ|", "|ρ| > 0, v = |ρ|", "|ρ| = 0, v = 0")


def test_inflation_wrong_width(inflation):
    s = inflation
    lo = sp.Piecewise((sp.sign(s.v) - 2 * s.r, sp.Abs(s.v) > s.r), (-1 - s.r, True))
    assert_fails(Inflation(), dataclasses.replace(s, inflated_lo=lo), "v > |ρ|: SGN_ρ(v) = [1 - 2*r, r + 1]")


def test_inflation_wrong_SGN(inflation):
    s = inflation
    assert_fails(Inflation(), dataclasses.replace(s, sgn_lo=sp.sign(s.u)), "|ρ| = 0, v = 0: SGN_ρ(v) = [-1, 1] but")


def test_inflation_checked_against_brute_force():
    """Independent of sympy: the inflation of SGN on a rational grid equals the paper's formula."""

    def sgn(u):
        return (u > 0) - (u < 0)

    def paper(v, r):
        return (sgn(v) - r, sgn(v) + r) if abs(v) > r else (-1 - r, 1 + r)

    def inflated(v, r):
        lo, hi = v - r, v + r
        values = set()
        if lo < 0:
            values.add(-1)
        if hi > 0:
            values.add(1)
        if lo <= 0 <= hi:
            values |= {-1, 1}
        return (min(values) - r, max(values) + r)

    grid = [F(k, 4) for k in range(-12, 13)]
    for v, r in itertools.product(grid, [F(0), F(1, 4), F(1), F(5, 2)]):
        assert paper(v, r) == inflated(v, r), (v, r)


def test_expand_abs_relations():
    y, c = sp.symbols("y c", real=True)
    assert _expand_abs_relations(sp.Abs(y) > c) == sp.Or(y > c, y < -c)
    assert _expand_abs_relations(c >= sp.Abs(y)) == sp.And(y <= c, y >= -c)


# ------------------------------------------------------------ cor1.distances


def test_distances_hold(distances):
    out = assert_holds(Distances(), distances)
    assert out.details[1][1] == "4 D \\beta"


def test_distances_moved_attractor_bound(distances):
    s = distances
    beta2 = 2 * s.f_c / s.k_i
    dz = sp.Piecewise((s.e_i + beta2, s.e_i < -beta2), (s.e_i - beta2, s.e_i > beta2), (0, True))
    dist2 = s.s**2 + s.v**2 + dz**2
    cases = Distances().derive().cases  # split at the original ±f_c/k_i
    out = assert_fails(Distances(), dataclasses.replace(s, dist2=dist2, bound2=2 * dist2 + 2 * (s.f_c / s.k_i) ** 2, cases=cases))
    assert "cannot decide" in out.reason or "not shown" in out.reason


def test_distances_moved_bound_with_matching_split(distances):
    from symbolic_friction._obligations._inequalities import line_cases

    s = distances
    beta2 = 2 * s.f_c / s.k_i
    dz = sp.Piecewise((s.e_i + beta2, s.e_i < -beta2), (s.e_i - beta2, s.e_i > beta2), (0, True))
    dist2 = s.s**2 + s.v**2 + dz**2
    cases = tuple(line_cases(s.e_i, [-beta2, beta2], name="e_i", beyond="t_e", weights=("p_e", "q_e")))
    moved = dataclasses.replace(s, dist2=dist2, bound2=2 * dist2 + 2 * (s.f_c / s.k_i) ** 2, cases=cases)
    assert_fails(Distances(), moved, "|z|² ≤ 2|z|_𝒜² + 2(f_c/k_i)² not shown")
    assert_fails(Distances(), moved, "it is negative at")


def test_distances_wrong_norm(distances):
    s = distances
    assert_fails(Distances(), dataclasses.replace(s, norm2=s.s**2 + s.v**2), "|z|_𝒜² ≤ |z|² not shown")


def test_distances_wrong_offset(distances):
    s = distances
    assert_fails(Distances(), dataclasses.replace(s, offset=s.f_c / (2 * s.k_i)), "2(|z|_𝒜 + f_c/(2*k_i))²")


def test_distances_on_rational_points_against_the_package():
    """The package's distance_z matches an exact reference, which satisfies both inequalities exactly."""
    p = Parameters.table_i("b")
    beta = p.f_c / p.k_i
    points = list(itertools.product([F(-40), F(-25, 2), F(-1), F(0), F(3), F(25, 2), F(13)], [F(-2), F(0), F(1, 2)], [F(-1), F(0), F(2)]))
    for e_i, s_, v in points:
        d = e_i - beta if e_i > beta else (e_i + beta if e_i < -beta else F(0))
        dist2 = s_**2 + v**2 + d**2
        norm2 = e_i**2 + s_**2 + v**2
        assert dist2 <= norm2 <= 2 * dist2 + 2 * beta**2
        got = _attractor.distance_z(p, np.array([[float(e_i), float(s_), float(v)]]))[0]
        assert_close(got**2, float(dist2), rtol=1e-13, atol=1e-13, what=f"|z|²_𝒜 at {(e_i, s_, v)}")


def test_counterexample_search():
    t, b = sp.symbols("t b", positive=True)
    x = sp.Symbol("x", real=True)
    assert _counterexample(t**2 + x**2) is None
    found = _counterexample(t**2 - 4 * b * t - 2 * b**2)
    assert found is not None and (t**2 - 4 * b * t - 2 * b**2).xreplace(found) < 0


def test_inflation_bounded_input(inflation):
    """A consistent but doubled friction map still inflates correctly, but is not within 1 + |ρ|."""
    s = inflation
    nonzero = sp.Ne(s.u, 0)
    big = sp.Abs(s.v) > s.r
    doubled = dataclasses.replace(
        s,
        sgn_lo=sp.Piecewise((2 * sp.sign(s.u), nonzero), (-2, True)),
        sgn_hi=sp.Piecewise((2 * sp.sign(s.u), nonzero), (2, True)),
        inflated_lo=sp.Piecewise((2 * sp.sign(s.v) - s.r, big), (-2 - s.r, True)),
        inflated_hi=sp.Piecewise((2 * sp.sign(s.v) + s.r, big), (2 + s.r, True)),
    )
    assert_fails(Inflation(), doubled, "is not inside [−1 − |ρ|, 1 + |ρ|]")
    (erratum,) = Inflation.errata
    assert "|m(t)| ≤ 1 + |ρ_v|" in erratum.correct
