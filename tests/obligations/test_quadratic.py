"""The quadratic template's obligations hold, and each fails when the model function it is about is broken."""

from __future__ import annotations

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._model import quadratic as model
from symbolic_friction._obligations import registry
from symbolic_friction._obligations.quadratic import (
    OBLIGATIONS,
    QuadraticPStructure,
    QuadraticStabilityBound,
    QuadraticUExit,
    QuadraticURate,
    QuadraticVDecrease,
)


@pytest.mark.parametrize("cls", OBLIGATIONS, ids=lambda c: c.id)
def test_holds_and_is_registered(cls):
    result = cls().run()
    assert result.holds, result.reason
    assert cls in registry()


def _broken_p(k_p, k_i, k_v, p11, p22, p33):
    zero = p22 - p22
    p23 = k_i * p11 + k_v * p22  # sign slip
    return ((p11, zero, -p22), (zero, p22, p23), (-p22, p23, p33))


def test_p_structure_sees_a_wrong_p23(monkeypatch):
    monkeypatch.setattr(model, "quadratic_p_entries", _broken_p)
    result = QuadraticPStructure().run()
    assert not result.holds and "first row" in result.reason


def test_p_structure_sees_a_p_that_is_not_the_paper_s(monkeypatch):
    real = model.quadratic_p_entries
    monkeypatch.setattr(model, "quadratic_p_entries", lambda k_p, k_i, k_v, p11, p22, p33: real(k_p, k_i, k_v, p11, p22, 2 * p33))
    result = QuadraticPStructure().run()
    assert not result.holds and "lyapLikeP" in result.reason


def test_v_decrease_sees_a_wrong_q(monkeypatch):
    real = model.lyapunov_rate_entries

    def wrong(k_p, k_i, k_v, p):
        q = [list(r) for r in real(k_p, k_i, k_v, p)]
        q[2][2] = q[2][2] + k_v  # a rate that is not AᵀP + PA
        return tuple(map(tuple, q))

    monkeypatch.setattr(model, "lyapunov_rate_entries", wrong)
    assert not QuadraticVDecrease().run().holds


def test_u_rate_sees_a_wrong_slip_matrix(monkeypatch):
    real = model.slip_rate_entries
    monkeypatch.setattr(model, "slip_rate_entries", lambda k_p, k_i, k_v, s: tuple(
        tuple(-e if (i, j) == (1, 2) else e for j, e in enumerate(row)) for i, row in enumerate(real(k_p, k_i, k_v, s))))
    result = QuadraticURate().run()
    assert not result.holds and "B_s" in result.reason


def test_u_rate_sees_a_wrong_band_form(monkeypatch):
    real = model.band_rate_entries
    monkeypatch.setattr(model, "band_rate_entries", lambda k_i, k_v, k, s: ((real(k_i, k_v, k, s)[0][0], real(k_i, k_v, k, s)[0][1] / 2),
                                                                          (real(k_i, k_v, k, s)[1][0] / 2, real(k_i, k_v, k, s)[1][1])))
    result = QuadraticURate().run()
    assert not result.holds and "band" in result.reason


def test_u_rate_sees_a_wrong_rate_form(monkeypatch):
    real = model.u_rate_entries
    monkeypatch.setattr(model, "u_rate_entries", lambda k, b: tuple(tuple(e / 2 for e in row) for row in real(k, b)))
    assert not QuadraticURate().run().holds


def test_u_exit_sees_a_wrong_edge_form(monkeypatch):
    real = model.exit_entries

    def wrong(k, p):
        rest, edge = real(k, p)
        cross = k[0][2] + p[1][1]  # the sign of P₁₃ forgotten
        return rest, ((edge[0][0], cross), (cross, edge[1][1]))

    monkeypatch.setattr(model, "exit_entries", wrong)
    result = QuadraticUExit().run()
    assert not result.holds and "exit form 2" in result.reason


def test_u_exit_sees_a_wrong_rest_form(monkeypatch):
    real = model.exit_entries
    monkeypatch.setattr(model, "exit_entries", lambda k, p: (((real(k, p)[0][0][0] + 1, 0), (0, real(k, p)[0][1][1])), real(k, p)[1]))
    result = QuadraticUExit().run()
    assert not result.holds and "exit form 1" in result.reason


def test_stability_bound_sees_a_missing_fact():
    ob = QuadraticStabilityBound()
    subject = ob.derive()
    facts = dict(subject.facts)
    del facts["κ² ≥ γ"]
    assert not ob.verify(dataclasses.replace(subject, facts=facts)).holds


def test_stability_bound_sees_a_reversed_fact():
    ob = QuadraticStabilityBound()
    subject = ob.derive()
    facts = dict(subject.facts)
    lo, hi = facts["U ≥ V at t₁"]
    facts["U ≥ V at t₁"] = (hi, lo)
    result = ob.verify(dataclasses.replace(subject, facts=facts))
    assert not result.holds and "does not follow" in result.reason


def test_stability_bound_sees_a_wrong_goal():
    ob = QuadraticStabilityBound()
    subject = ob.derive()
    assert not ob.verify(dataclasses.replace(subject, kappa_squared=sp.Symbol("c_2", positive=True))).holds
