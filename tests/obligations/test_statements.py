"""The conclusions of Lemma 2 and Lemma 3 that Proposition 1 uses are the ones their obligations prove."""

import dataclasses

from symbolic_friction._obligations._statements import statement_failure
from symbolic_friction._obligations.lemma2 import Lemma2dVdt, Lemma2LowerBound
from symbolic_friction._obligations.lemma3 import HatVBounds, HatVDerivative, LemmaR
from symbolic_friction._obligations.prop1 import StabilityBound

from ._helpers import assert_fails


def test_statement_failure_names_the_difference():
    assert statement_failure(lambda c, d, v: (c * d, v), lambda c, d, v: v - c * d) is None
    why = statement_failure(lambda c, d, v: (c * d / 2, v), lambda c, d, v: v - c * d)
    assert why is not None and "is not what is proved here" in why
    assert "2 inequalities" in statement_failure(lambda a, b: ((a, b), (b, a)), lambda a, b: b - a)


def test_weakened_lemma2_lower_bound_fails():
    ob = Lemma2LowerBound()
    s = dataclasses.replace(ob.derive(), statement=lambda c1, dist2, V: (c1 * dist2 / 2, V))
    assert_fails(ob, s, "Lemma 2 item 1 as Proposition 1 uses it")


def test_reversed_lemma2_decrease_fails():
    ob = Lemma2dVdt()
    s = dataclasses.replace(ob.derive(), statement=lambda later, earlier: (earlier, later))
    assert_fails(ob, s, "Lemma 2 item 2 as Proposition 1 uses it")


def test_weakened_VandR_fails():
    ob = LemmaR()
    s = dataclasses.replace(ob.derive(), statement=lambda c1, c2, d, V: ((c1 * d, V), (V, 2 * c2 * d)))
    assert_fails(ob, s, "eq. (VandR) as Proposition 1 uses it")


def test_weakened_hatV_bounds_fails():
    ob = HatVBounds()
    s = dataclasses.replace(ob.derive(), statement=lambda c1, c2, d, W: ((c1 * d, 2 * W), (W, c2 * d)))
    assert_fails(ob, s, "eq. (hatVandHatR) as Proposition 1 uses it")


def test_reversed_hatV_monotonicity_fails():
    ob = HatVDerivative()
    s = dataclasses.replace(ob.derive(), statement=lambda later, earlier: (earlier, later))
    assert_fails(ob, s, "eq. (hatVdot) as Proposition 1 uses it")


def test_prop1_premises_come_from_the_statements(monkeypatch):
    from symbolic_friction._obligations import _stability_chain

    # a weaker Lemma 3 conclusion (upper bound 2c₂) leaves Proposition 1's chain without the bound it needs
    monkeypatch.setattr(_stability_chain, "lemma3_V_bounds", lambda c1, c2, d, V: ((c1 * d, V), (V, 2 * c2 * d)))
    ob = StabilityBound()
    out = ob.verify(ob.derive())
    assert not out.holds and "does not follow" in out.reason
