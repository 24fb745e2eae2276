"""The Krawczyk proof of a hunting cycle: it proves the cycles found, and each of its checks can fail."""

from __future__ import annotations

import dataclasses
from fractions import Fraction as F

import pytest

from symbolic_friction import Parameters
from symbolic_friction._hunting import Box, box_around, find_cycles, prove_cycle
from symbolic_friction._certify import hunting_proof as _proof
from symbolic_friction._hunting._report import with_static

GAINS = {
    "a": with_static(Parameters.table_i("a"), F(6, 5)),
    "b": with_static(Parameters.table_i("b"), F(6, 5)),
    "triple": Parameters(k_v=3, k_p=3, k_i=1, f_s="1.2"),
    "stiff": Parameters(k_v="51.1", k_p="5.3525", k_i="12.8775", f_s="1.2"),
    "k10": Parameters(k_p=10, k_i=30, k_v=5, f_c=3, f_s="3.6"),
}


@pytest.fixture(scope="module")
def boxes():
    out = {}
    for name, p in GAINS.items():
        (c,) = [c for c in find_cycles(p, general=False) if c.symmetric]
        out[name] = (c, box_around(c.sigma, c.slip_time))
    return out


@pytest.mark.parametrize("name", list(GAINS))
def test_the_found_cycle_is_proved(name, boxes):
    c, box = boxes[name]
    proof = prove_cycle(GAINS[name], box)
    assert proof.proved, [str(ch) for ch in proof.checks]
    lo, hi = proof.multiplier
    assert lo <= c.multiplier <= hi and proof.stable is True


def failing(proof):
    return [ch.name for ch in proof.checks if not ch.holds]


def test_a_box_that_contains_no_fixed_point_fails(boxes):
    _, box = boxes["a"]
    lo, hi = box.sigma
    w = hi - lo
    shifted = dataclasses.replace(box, sigma=(lo + 2 * w, hi + 2 * w))
    proof = prove_cycle(GAINS["a"], shifted)
    assert not proof.proved and failing(proof) == ["krawczyk"]


def test_changed_gains_fail(boxes):
    _, box = boxes["a"]
    p = GAINS["a"]
    for q in (
        Parameters(k_p=p.k_p, k_i=p.k_i, k_v=p.k_v + F(1, 10**6), f_s=p.f_s),
        Parameters(k_p=p.k_p, k_i=p.k_i, k_v=p.k_v, f_s=p.f_s + F(1, 10**6)),
    ):
        assert "krawczyk" in failing(prove_cycle(q, box))


def test_a_malformed_box_fails_the_box_check(boxes):
    _, box = boxes["a"]
    bad = dataclasses.replace(box, monotone_from=box.tau[1])
    assert failing(prove_cycle(GAINS["a"], bad)) == ["box"]
    assert failing(prove_cycle(Parameters.table_i("a"), box)) == ["box"]  # f_s = f_c: nothing to prove


def test_the_first_zero_check_fails_when_v_has_an_earlier_zero(boxes, monkeypatch):
    """A v that dips below 0 early in the slip (a mutant of the closed form) is caught."""
    _, box = boxes["a"]
    real = _proof._Arb.state

    def dipping(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        if self.ball(F(1, 2), F(1)).overlaps(tau):
            y = [y[0], y[1], y[2] - 1]
        return E, y, dy

    monkeypatch.setattr(_proof._Arb, "state", dipping)
    assert "first_zero.positive" in failing(prove_cycle(GAINS["a"], box))


def test_the_stick_check_fails_when_the_slip_ends_outside_the_stick_band(boxes, monkeypatch):
    _, box = boxes["a"]
    real = _proof._Arb.__init__

    def narrow(self, params):
        real(self, params)
        self.f_s = self.q(F(9, 10))  # the slip ends at φ = 0.98 > 0.9: a reversal, not a stick

    monkeypatch.setattr(_proof._Arb, "__init__", narrow)
    assert "stick" in failing(prove_cycle(GAINS["a"], box))


def test_the_decreasing_check_fails_on_a_wide_tau_range(boxes):
    c, box = boxes["a"]
    wide = dataclasses.replace(box, monotone_from=F(1, 10))  # v increases early in the slip
    assert "first_zero.decreasing" in failing(prove_cycle(GAINS["a"], wide))


def test_the_proof_restores_the_arb_precision(boxes):
    from flint import ctx

    before = ctx.prec
    prove_cycle(GAINS["a"], boxes["a"][1], precision=200)
    assert ctx.prec == before


def test_box_around_is_exact_and_contains_the_value():
    box = box_around(0.1, 2.5)
    assert isinstance(box.sigma[0], F) and box.sigma[0] < F(1, 10) < box.sigma[1]
    assert box.monotone_from < box.tau[0] < F(5, 2) < box.tau[1]
