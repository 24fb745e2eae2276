"""Lemma 3's region ``R`` and its case split: membership decided exactly, an undecided piece recorded, never guessed."""

from __future__ import annotations

import sympy as sp

from symbolic_friction._obligations import _region as R
from symbolic_friction._obligations._decide import G, pos
from symbolic_friction._obligations._inequalities import Case


def test_k_symbols_are_positive_and_cached():
    ks = R.k_symbols()
    assert [k.name for k in ks] == ["k_1", "k_2", "k_3", "k_4"] and all(k.is_positive for k in ks)
    assert R.k_symbols() is ks


def test_region_is_the_papers_margin():
    g = G()
    region = R.region_R(g)
    p = pos("p")
    # v > 0: v(φ - f_c); v < 0: v(φ + f_c); v = 0: 0
    assert sp.simplify(R.in_R(region.subs({g.v: p, g.phi: g.f_c + p})) is True)
    assert R.in_R(region.xreplace({g.v: p, g.phi: g.f_c - p})) is False
    assert R.in_R(region.xreplace({g.v: -p, g.phi: -g.f_c - p})) is True
    assert R.in_R(region.xreplace({g.v: -p, g.phi: -g.f_c + p})) is False
    assert R.in_R(region.xreplace({g.v: sp.Integer(0)})) is True
    assert R.in_R(region.xreplace({g.v: p, g.phi: g.f_c})) is True  # on the boundary: R is closed
    assert R.in_R(region.xreplace({g.v: p})) is None  # φ free: undecided, never guessed


def test_vhat_expression_is_the_models():
    g = G()
    k = R.k_symbols()
    e = R.vhat_expression(g, k)
    assert e.free_symbols >= {g.sigma, g.v, *k}
    at = e.xreplace({g.sigma: 0, g.phi: 0, g.v: 0})
    assert sp.simplify(at) == 0


def test_pieces_of_sorts_records_and_never_guesses():
    g = G()
    region = R.region_R(g)
    p, q = pos("p"), pos("q")
    inside = Case("v > 0, φ > f_c", ((g.v, p), (g.phi, g.f_c + q)))
    outside = Case("v > 0, |φ| < f_c", ((g.v, p), (g.phi, g.f_c - q)))
    on = Case("v = 0", ((g.v, sp.Integer(0)),))
    undecided = Case("v > 0, φ free", ((g.v, p),))
    cases = (undecided, inside, outside, on)
    failures: list[str] = []
    assert list(R.pieces_of(cases, region, inside=True, failures=failures)) == [inside, on]
    assert failures == ["cannot decide whether the piece v > 0, φ free lies in R"]
    failures = []
    assert list(R.pieces_of(cases, region, inside=False, failures=failures)) == [outside]
    assert failures == ["cannot decide whether the piece v > 0, φ free lies in R̂"]
    # a region written with a Piecewise whose branch cannot be decided on a piece: recorded with its label
    a, b = pos("a"), pos("b")
    piecewise = sp.Piecewise((g.phi, sp.StrictGreaterThan(g.v, 0)), (-g.phi, True))
    unresolved = Case("v = a - b", ((g.v, a - b), (g.phi, g.f_c)))
    resolved = Case("v = a", ((g.v, a), (g.phi, g.f_c)))
    failures = []
    assert list(R.pieces_of((unresolved, resolved), piecewise, inside=True, failures=failures)) == [resolved]
    assert failures == ["v = a - b: cannot decide the branch condition a - b > 0"]


def test_fmt_failures_keeps_six():
    assert R._fmt_failures([]) == ""
    assert R._fmt_failures(["a", "b"]) == "a; b"
    six = [str(i) for i in range(6)]
    assert R._fmt_failures(six) == "0; 1; 2; 3; 4; 5"
    assert R._fmt_failures(six + ["6", "7"]) == "0; 1; 2; 3; 4; 5 (and 2 more)"
    assert R._fmt_failures(six + ["6"]) == "0; 1; 2; 3; 4; 5 (and 1 more)"
