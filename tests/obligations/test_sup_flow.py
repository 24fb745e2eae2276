"""The sup-of-flow lemma's obligations hold, and each fails when the model piece or the step it is about is broken."""

from __future__ import annotations

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._model import attractor, coordinates, lyapunov
from symbolic_friction._model import sup_flow as template
from symbolic_friction._obligations import _sup_flow_points as points
from symbolic_friction._obligations import lemma2, obligation_modules, registry
from symbolic_friction._obligations import sup_flow as module
from symbolic_friction._obligations.sup_flow import (
    OBLIGATIONS,
    Bounds,
    Exit,
    Nonincreasing,
    RestMinimum,
    SlipFlow,
    SupFlowStabilityBound,
)

IDS = ("sup_flow.slip_flow", "sup_flow.rest_minimum", "sup_flow.nonincreasing", "sup_flow.bounds", "sup_flow.exit",
       "sup_flow.stability_bound")


@pytest.mark.parametrize("cls", OBLIGATIONS, ids=lambda c: c.id)
def test_holds_and_is_registered(cls):
    result = cls().run()
    assert result.holds, result.reason
    assert cls in registry()


def test_the_ids_the_certificate_cites_run_after_the_quadratic_ones():
    ids = [cls.id for cls in registry()]
    assert tuple(cls.id for cls in OBLIGATIONS) == IDS
    start = ids.index(IDS[0])
    assert ids[start:start + len(IDS)] == list(IDS)  # one block (reset PID's jumps come after it)
    assert ids.index("quadratic.stability_bound") < ids.index(IDS[0])
    assert module in obligation_modules()


def _a_with(entry: tuple[int, int], value):
    real = coordinates.system_matrix_entries

    def wrong(k_p, k_i, k_v):
        a = [list(r) for r in real(k_p, k_i, k_v)]
        a[entry[0]][entry[1]] = value(k_p, k_i, k_v)
        return tuple(map(tuple, a))

    return wrong


# -- slip_flow ------------------------------------------------------------------------------


def test_slip_flow_sees_a_wrong_second_column_of_a(monkeypatch):
    monkeypatch.setattr(coordinates, "system_matrix_entries", _a_with((2, 1), lambda k_p, k_i, k_v: 2))
    result = SlipFlow().run()
    assert not result.holds and "A(x − f e₂)" in result.reason


def test_slip_flow_sees_a_wrong_first_column_of_a(monkeypatch):
    monkeypatch.setattr(coordinates, "system_matrix_entries", _a_with((1, 0), lambda k_p, k_i, k_v: k_p))
    result = SlipFlow().run()
    assert not result.holds and "A e₁ − e₂" in result.reason


def test_slip_flow_sees_a_wrong_b(monkeypatch):
    monkeypatch.setattr(coordinates, "input_vector_entries", lambda f_c: (0, 0, 2 * f_c))
    result = SlipFlow().run()
    assert not result.holds and "b − f_c e₃" in result.reason


def test_slip_flow_sees_a_moving_sigma_at_rest():
    ob = SlipFlow()
    subject = ob.derive()
    result = ob.verify(dataclasses.replace(subject, rest_sigma_rate=sp.Symbol("phi")))
    assert not result.holds and "σ̇" in result.reason


def test_slip_flow_sees_a_slip_that_is_not_the_free_flow():
    ob = SlipFlow()
    subject = ob.derive()
    broken = (subject.slips[0] + sp.Matrix([0, 0, sp.Symbol("f_c", positive=True)]), subject.slips[1])
    result = ob.verify(dataclasses.replace(subject, slips=broken))
    assert not result.holds and "ẇ = Aw" in result.reason


# -- rest_minimum ---------------------------------------------------------------------------


def test_rest_minimum_sees_a_wrong_first_column_of_a(monkeypatch):
    monkeypatch.setattr(coordinates, "system_matrix_entries", _a_with((2, 0), lambda k_p, k_i, k_v: 1))
    result = RestMinimum().run()
    assert not result.holds and "ψ-slope" in result.reason


def _rest_subject():
    ob = RestMinimum()
    subject = ob.derive()
    gens = {str(x): x for x in subject.sigma.ring.gens}
    return ob, subject, gens


@pytest.mark.parametrize(
    ("field", "value", "fragment"),
    [
        ("slope_at_identity", lambda g: g["sigma"], "M = I"),
        ("curvature", lambda g: -g["m12"] ** 2, "2|Me₂|²"),
        ("taylor_gap", lambda g: g["psi"] ** 3, "Taylor"),
    ],
)
def test_rest_minimum_sees_a_forged_step(field, value, fragment):
    ob, subject, gens = _rest_subject()
    result = ob.verify(dataclasses.replace(subject, **{field: value(gens)}))
    assert not result.holds and fragment in result.reason


def test_rest_minimum_sees_a_slope_that_survives_at_sigma_zero():
    ob, subject, gens = _rest_subject()
    extra = gens["m11"]
    forged = dataclasses.replace(subject, psi_slope=subject.psi_slope + extra, time_rate=subject.time_rate + subject.sigma * extra)
    result = ob.verify(forged)
    assert not result.holds and "σ = 0" in result.reason


def test_rest_minimum_sees_a_curvature_that_is_not_a_sum_of_squares():
    ob, subject, gens = _rest_subject()
    m = gens["m12"]
    result = ob.verify(dataclasses.replace(subject, curvature=-2 * m**2, column_two=-(m**2)))
    assert not result.holds and "≥ 0" in result.reason


# -- nonincreasing --------------------------------------------------------------------------


def test_nonincreasing_sees_a_minimiser_that_is_not_sat(monkeypatch):
    real = lyapunov.friction_selection

    # f = 0 at rest instead of sat(φ)
    monkeypatch.setattr(lyapunov, "friction_selection", lambda params, phi, v: real(params, phi, v) if v != 0 else 0 * phi)
    result = Nonincreasing().run()
    assert not result.holds and "(σ, dz φ, 0)" in result.reason


def test_nonincreasing_sees_a_dead_zone_on_the_wrong_side(monkeypatch):
    real = attractor.dz
    monkeypatch.setattr(attractor, "dz", lambda y, c: -real(y, c))
    result = Nonincreasing().run()
    assert not result.holds and "between 0 and" in result.reason


def test_nonincreasing_sees_a_slip_that_does_not_start_at_the_minimiser(monkeypatch):
    real = lyapunov.friction_selection
    # at v > 0 a selection of −f_c: the slip's w(0) = x̄ − f_c e₂ is no longer V_∞'s argument
    monkeypatch.setattr(lyapunov, "friction_selection", lambda params, phi, v: -real(params, phi, v) if v != 0 else real(params, phi, v))
    result = Nonincreasing().run()
    assert not result.holds and "slip's w(0)" in result.reason


def test_nonincreasing_sees_a_stick_that_moves_sigma(monkeypatch):
    monkeypatch.setattr(lemma2, "F0_MATRIX", ((0, 1, 0), (1, 0, 0), (0, 0, 0)))
    result = Nonincreasing().run()
    assert not result.holds and "f₀" in result.reason


def test_nonincreasing_sees_a_missing_row():
    ob = Nonincreasing()
    subject = ob.derive()
    result = ob.verify(dataclasses.replace(subject, rows=subject.rows[:-1]))
    assert not result.holds and "not 5 and 11" in result.reason


# -- bounds ---------------------------------------------------------------------------------


def test_bounds_sees_a_wrong_distance(monkeypatch):
    real = attractor.squared_distance_x
    monkeypatch.setattr(attractor, "squared_distance_x", lambda params, x: real(params, x) + x[2] ** 2)
    result = Bounds().run()
    assert not result.holds and "|x|²_𝒜" in result.reason


def test_bounds_sees_a_wrong_region(monkeypatch):
    real = lyapunov.R_margin
    monkeypatch.setattr(lyapunov, "R_margin", lambda params, x: -real(params, x))
    result = Bounds().run()
    assert not result.holds and "R-margin" in result.reason


def test_bounds_sees_a_missing_class():
    ob = Bounds()
    subject = ob.derive()
    result = ob.verify(dataclasses.replace(subject, outside=subject.outside[1:]))
    assert not result.holds and "not 15" in result.reason


# -- exit -----------------------------------------------------------------------------------


def test_exit_sees_a_wrong_sign_in_the_rest_exit_map(monkeypatch):
    real = template.exit_map
    monkeypatch.setattr(template, "exit_map", lambda plane, s: ((real(plane, s)[0], (0, 1), real(plane, s)[2]) if plane == "v = 0"
                                                              else real(plane, s)))
    result = Exit().run()
    assert not result.holds and "v = 0" in result.reason and "exit form" in result.reason


def test_exit_sees_a_wrong_sign_of_sigma_on_the_edge(monkeypatch):
    real = template.exit_map
    monkeypatch.setattr(template, "exit_map", lambda plane, s: real(plane, -s) if plane == "φ = f_c" else real(plane, s))
    result = Exit().run()
    assert not result.holds and "φ = h f_c" in result.reason


def test_exit_sees_verifier_forms_that_are_not_u_minus_the_flow(monkeypatch):
    real = template.exit_forms

    def wrong(k, gram, s):
        rest, edge = real(k, gram, s)
        return rest, ((edge[0][0], edge[0][1] + gram[0][2]), (edge[1][0] + gram[0][2], edge[1][1]))  # a dropped sign of the cross term

    monkeypatch.setattr(template, "exit_forms", wrong)
    result = Exit().run()
    assert not result.holds and "φ = f_c" in result.reason and "U − wᵀGw" in result.reason


def test_exit_sees_a_tail_gram_without_its_factor(monkeypatch):
    real = template.tail_gram
    monkeypatch.setattr(template, "tail_gram", lambda flow, p_matrix, p: tuple(tuple(e * p for e in row) for row in real(flow, p_matrix, p)))
    result = Exit().run()
    assert not result.holds and "tail Gram" in result.reason


def test_exit_sees_a_dropped_tail_factor():
    ob = Exit()
    subject = ob.derive()
    result = ob.verify(dataclasses.replace(subject, tail_bound=subject.tail_bound * subject.p))
    assert not result.holds and "tail bound" in result.reason


def test_exit_sees_a_p_whose_flow_can_grow(monkeypatch):
    real = lyapunov.lyapunov_matrix_entries

    def wrong(k_p, k_i, k_v):
        p = [list(r) for r in real(k_p, k_i, k_v)]
        p[0][1] = p[1][0] = 1  # (AᵀP + PA)₁₁ = 2P₁₂ > 0
        return tuple(map(tuple, p))

    monkeypatch.setattr(lyapunov, "lyapunov_matrix_entries", wrong)
    result = Exit().run()
    assert not result.holds and "AᵀP + PA ⪯ 0" in result.reason


def test_exit_sees_a_verifier_rate_that_is_not_the_derivative_along_the_flow(monkeypatch):
    """The verifier decides −(AᵀP + PA) ⪰ 0 for a file's own tail ``P``: a wrong ``AᵀP + PA`` (here ``AᵀP + PAᵀ``)
    would prove a tail that the flow can break."""
    from symbolic_friction._model import quadratic as quad_model

    def wrong(k_p, k_i, k_v, p):
        a = [[0, 0, -k_i], [1, 0, -k_p], [0, 1, -k_v]]
        return tuple(tuple(sum(a[k][i] * p[k][j] + p[i][k] * a[j][k] for k in range(3)) for j in range(3)) for i in range(3))

    monkeypatch.setattr(quad_model, "lyapunov_rate_entries", wrong)
    result = Exit().run()
    assert not result.holds and "not d/dt|z|²_P ≤ 0" in result.reason


def test_exit_sees_a_tail_premise_that_is_not_p_minus_p_identity(monkeypatch):
    from symbolic_friction._certify import quadratic as quad_certify

    monkeypatch.setattr(quad_certify, "_scaled_identity", lambda n, scale: tuple(
        tuple(scale / 2 if i == j else scale - scale for j in range(n)) for i in range(n)))
    result = Exit().run()
    assert not result.holds and "tail bound does not follow" in result.reason


def test_exit_sees_a_point_off_the_boundary():
    ob = Exit()
    subject = ob.derive()
    moved = (dataclasses.replace(subject.points[0], margin=sp.Symbol("q", positive=True)),) + subject.points[1:]
    result = ob.verify(dataclasses.replace(subject, points=moved))
    assert not result.holds and "R-margin" in result.reason


# -- stability_bound ------------------------------------------------------------------------


def _bound_subject():
    ob = SupFlowStabilityBound()
    return ob, ob.derive()


def test_stability_bound_sees_a_missing_fact():
    ob, subject = _bound_subject()
    facts = dict(subject.bound.facts)
    del facts["κ² ≥ c₂"]
    result = ob.verify(dataclasses.replace(subject, bound=dataclasses.replace(subject.bound, facts=facts)))
    assert not result.holds and "unknown facts" in result.reason


def test_stability_bound_sees_a_reversed_fact():
    ob, subject = _bound_subject()
    facts = dict(subject.bound.facts)
    name = "V_∞ = g(w) at t₁ (sup_flow.exit)"
    lo, hi = facts[name]
    facts[name] = (hi, lo)
    result = ob.verify(dataclasses.replace(subject, bound=dataclasses.replace(subject.bound, facts=facts)))
    assert not result.holds and "does not follow" in result.reason


def test_stability_bound_sees_a_cited_obligation_that_check_does_not_run():
    ob, subject = _bound_subject()
    result = ob.verify(dataclasses.replace(subject, registered=tuple(i for i in subject.registered if i != "sup_flow.exit")))
    assert not result.holds and "sup_flow.exit" in result.reason


def test_stability_bound_sees_a_goal_that_is_not_the_bound():
    ob, subject = _bound_subject()
    name, dt, d0 = subject.bound.goals[0]
    goals = ((name, dt, 2 * d0),) + subject.bound.goals[1:]
    result = ob.verify(dataclasses.replace(subject, bound=dataclasses.replace(subject.bound, goals=goals)))
    assert not result.holds and "κ² D_0" in result.reason


def test_every_obligation_the_sup_flow_certificate_cites_is_one_check_runs():
    from symbolic_friction._certify.sup_flow import OBLIGATIONS as CITED

    ids = {cls.id for cls in registry()}
    assert set(IDS) <= set(CITED) and set(CITED) <= ids, sorted(set(CITED) - ids)
