"""The sup-flow template's version-2 obligations hold, and each fails when the model piece or the step it is about is broken."""

from __future__ import annotations

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._model import attractor, coordinates, lyapunov
from symbolic_friction._model import quadratic as quad_model
from symbolic_friction._model import sup_flow as template
from symbolic_friction._obligations import obligation_modules, registry
from symbolic_friction._obligations import sup_flow_v2 as module
from symbolic_friction._obligations.sup_flow import Exit
from symbolic_friction._obligations.sup_flow_v2 import (
    OBLIGATIONS,
    DragRegion,
    ExitV2,
    SignCrossing,
    StabilityBoundV2,
    URateV2,
)

from ._helpers import assert_fails, assert_holds, obligation_fixture

IDS = ("sup_flow_v2.U_rate", "sup_flow_v2.sign_crossing", "sup_flow_v2.drag_region", "sup_flow_v2.exit",
       "sup_flow_v2.stability_bound")

u_rate = obligation_fixture(URateV2)
sign_crossing = obligation_fixture(SignCrossing)
drag_region = obligation_fixture(DragRegion)
exit_v2 = obligation_fixture(ExitV2)
bound = obligation_fixture(StabilityBoundV2)


@pytest.mark.parametrize("cls", OBLIGATIONS, ids=lambda c: c.id)
def test_holds_and_is_registered(cls):
    result = cls().run()
    assert result.holds, result.reason
    assert cls in registry()
    assert result.paper.startswith("beyond the paper")


def test_the_ids_run_as_one_block_after_version_1():
    ids = [cls.id for cls in registry()]
    assert tuple(cls.id for cls in OBLIGATIONS) == IDS
    start = ids.index(IDS[0])
    assert ids[start:start + len(IDS)] == list(IDS)
    assert ids.index("sup_flow.stability_bound") < start
    assert module in obligation_modules()


def test_every_obligation_the_v2_certificate_cites_is_one_check_runs():
    from symbolic_friction._certify.sup_flow_v2 import OBLIGATIONS as CITED

    ids = {cls.id for cls in registry()}
    assert set(IDS) <= set(CITED) and set(CITED) <= ids, sorted(set(CITED) - ids)


def test_the_latex_details_are_deterministic(u_rate, drag_region):
    for ob, subject in (u_rate, drag_region):
        assert assert_holds(ob, subject).details == ob.verify(subject).details


# -- U_rate ---------------------------------------------------------------------------------


def test_u_rate_sees_a_drag_rate_without_the_friction_term(monkeypatch):
    monkeypatch.setattr(quad_model, "drag_rate_entries", lambda k, b, ell: quad_model.u_rate_entries(k, b))
    result = URateV2().run()
    assert not result.holds and "drag rate form" in result.reason


def test_u_rate_sees_a_drag_band_block_with_a_wrong_entry(monkeypatch):
    real = quad_model.drag_band_entries

    def wrong(k_i, k_v, k, s, ell):
        m = real(k_i, k_v, k, s, ell)
        return ((m[0][0] - 2 * k[0][2] * ell[0] + 2 * k[0][2] * ell[2], m[0][1]), m[1])  # ℓ₃ for ℓ₁ in the (1,1) entry

    monkeypatch.setattr(quad_model, "drag_band_entries", wrong)
    result = URateV2().run()
    assert not result.holds and "drag band form" in result.reason


def test_u_rate_sees_a_signed_form_that_drops_k12(monkeypatch):
    monkeypatch.setattr(quad_model, "u_matrix_signed", lambda k11, k12, k13, k22, k23, k33: quad_model.u_matrix_entries(k11, k13, k22, k23, k33))
    result = URateV2().run()
    assert not result.holds and "2sK₁₂" in result.reason


def test_u_rate_sees_a_wrong_slip_matrix(monkeypatch):
    real = quad_model.slip_rate_entries
    monkeypatch.setattr(quad_model, "slip_rate_entries", lambda k_p, k_i, k_v, s: tuple(
        tuple(-e if (i, j) == (1, 2) else e for j, e in enumerate(row)) for i, row in enumerate(real(k_p, k_i, k_v, s))))
    result = URateV2().run()
    assert not result.holds and "B_s y − f e₃" in result.reason


def test_u_rate_sees_a_wrong_damping_in_the_model(monkeypatch):
    real = coordinates.system_matrix_entries
    monkeypatch.setattr(coordinates, "system_matrix_entries", lambda k_p, k_i, k_v: real(k_p, k_i, 2 * k_v))
    result = URateV2().run()
    assert not result.holds and "ẏ outside the band" in result.reason


def test_u_rate_sees_a_dead_zone_that_is_not_y2(monkeypatch):
    real = attractor.dz
    monkeypatch.setattr(attractor, "dz", lambda y, c: 2 * real(y, c))
    result = URateV2().run()
    assert not result.holds and "parametrisation" in result.reason


def test_u_rate_sees_a_friction_row_of_unknown_sign(u_rate):
    ob, subject = u_rate
    k13 = sp.Symbol("K13", real=True)
    signs = (dataclasses.replace(subject.signs[0], third_rows=(k13, subject.signs[0].third_rows[1])),) + subject.signs[1:]
    assert_fails(ob, dataclasses.replace(subject, signs=signs), "(Ky)₃")


def test_u_rate_sees_a_missing_sign(u_rate):
    ob, subject = u_rate
    assert_fails(ob, dataclasses.replace(subject, signs=subject.signs[:1]), "±1")


# -- sign_crossing --------------------------------------------------------------------------


def test_sign_crossing_sees_a_reversed_coupling_block(monkeypatch):
    monkeypatch.setattr(template, "coupling_block", lambda kp, km: tuple(tuple(km[i][j] - kp[i][j] for j in (1, 2)) for i in (1, 2)))
    result = SignCrossing().run()
    assert not result.holds and "coupling block" in result.reason


def test_sign_crossing_sees_a_sigma_that_does_not_follow_minus_ki_v(monkeypatch):
    real = coordinates.system_matrix_entries

    def wrong(k_p, k_i, k_v):
        a = [list(r) for r in real(k_p, k_i, k_v)]
        a[0][2] = -k_p
        return tuple(map(tuple, a))

    monkeypatch.setattr(coordinates, "system_matrix_entries", wrong)
    result = SignCrossing().run()
    assert not result.holds and "σ̇ = −k_i v" in result.reason


def test_sign_crossing_sees_a_sigma_that_can_rise_across_zero(sign_crossing):
    ob, subject = sign_crossing
    crossing = ((1, sp.Symbol("q_v", positive=True)),) + subject.crossing[1:]
    assert_fails(ob, dataclasses.replace(subject, crossing=crossing), "from − to +")


def test_sign_crossing_sees_a_friction_that_is_not_odd(monkeypatch):
    real = coordinates.input_vector_entries
    monkeypatch.setattr(coordinates, "input_vector_entries", lambda f_c: (f_c, 0, real(f_c)[2]))
    result = SignCrossing().run()
    assert not result.holds  # b₁ ≠ 0: σ̇ on a slip is no longer −k_i v


def test_sign_crossing_sees_a_minimiser_that_is_not_odd(monkeypatch):
    real = lyapunov.friction_selection
    monkeypatch.setattr(lyapunov, "friction_selection", lambda params, phi, v: real(params, phi, v) if v != 0 else params.f_c + 0 * phi)
    result = SignCrossing().run()
    assert not result.holds and "V_∞ is not invariant" in result.reason


def test_sign_crossing_sees_a_region_that_is_not_even(monkeypatch):
    real = lyapunov.R_margin
    monkeypatch.setattr(lyapunov, "R_margin", lambda params, x: real(params, x) + x[0])
    result = SignCrossing().run()
    assert not result.holds and "R̂ is not invariant" in result.reason


def test_sign_crossing_sees_a_dead_zone_that_is_not_odd(monkeypatch):
    real = attractor.dz
    monkeypatch.setattr(attractor, "dz", lambda y, c: real(y, c) + c)
    result = SignCrossing().run()
    assert not result.holds and "dz(−φ) + dz(φ)" in result.reason


def test_sign_crossing_sees_a_missing_class(sign_crossing):
    ob, subject = sign_crossing
    assert_fails(ob, dataclasses.replace(subject, mirrors=subject.mirrors[1:]), "not 15")


# -- drag_region ----------------------------------------------------------------------------


def test_drag_region_sees_a_drag_exit_map_with_plus_ell(monkeypatch):
    real = template.drag_exit_map
    monkeypatch.setattr(template, "drag_exit_map", lambda s, ell: real(s, tuple(-e for e in ell)))
    result = DragRegion().run()
    assert not result.holds and "w ≠ (1 − λ)D₀y + λD_ℓy" in result.reason


def test_drag_region_sees_a_wrong_pullback(monkeypatch):
    def wrong(m, gram, d):  # D G Dᵀ instead of Dᵀ G D
        dgd = tuple(tuple(sum(d[i][a] * gram[a][b] * d[j][b] for a in range(3) for b in range(3)) for j in range(3)) for i in range(3))
        return tuple(tuple(m[i][j] - dgd[i][j] for j in range(3)) for i in range(3))

    monkeypatch.setattr(template, "pullback_gap", wrong)
    result = DragRegion().run()
    assert not result.holds and "pullback_gap(c₂I, G, D)" in result.reason


def test_drag_region_sees_a_d0_that_is_not_an_isometry(drag_region):
    ob, subject = drag_region
    broken = (sp.diag(3, 0, 0),) + subject.isometry[1:]
    assert_fails(ob, dataclasses.replace(subject, isometry=broken), "isometry")


def test_drag_region_sees_a_wrong_distance(monkeypatch):
    real = attractor.squared_distance_x
    monkeypatch.setattr(attractor, "squared_distance_x", lambda params, x: real(params, x) + x[2] ** 2)
    result = DragRegion().run()
    assert not result.holds and "|x|²_𝒜 − |y|²" in result.reason


def test_drag_region_sees_a_minimiser_of_the_wrong_sign(monkeypatch):
    real = lyapunov.friction_selection
    monkeypatch.setattr(lyapunov, "friction_selection", lambda params, phi, v: -real(params, phi, v))
    result = DragRegion().run()
    assert not result.holds and "minimiser's w" in result.reason


def test_drag_region_sees_a_friction_excess_of_unknown_sign(monkeypatch):
    real = attractor.dz
    monkeypatch.setattr(attractor, "dz", lambda y, c: 2 * real(y, c))  # f = 2f_c − p for φ = −f_c − p
    result = DragRegion().run()
    assert not result.holds and "friction excess" in result.reason


def test_drag_region_sees_a_wrong_region(monkeypatch):
    real = lyapunov.R_margin
    monkeypatch.setattr(lyapunov, "R_margin", lambda params, x: -real(params, x))
    result = DragRegion().run()
    assert not result.holds and "not (6, 4, 10, 2, 3)" in result.reason


# -- exit -----------------------------------------------------------------------------------


def test_exit_sees_exit_forms_that_assume_k12_zero(monkeypatch):
    real = template.exit_forms

    def without_k12(k, gram, s):
        zero = k[0][1] - k[0][1]
        return real(((k[0][0], zero, k[0][2]), (zero, k[1][1], k[1][2]), k[2]), gram, s)

    monkeypatch.setattr(template, "exit_forms", without_k12)
    result = ExitV2().run()
    assert not result.holds and "K₁₂ kept" in result.reason and "v = 0" in result.reason
    assert Exit().run().holds  # version 1 (K₁₂ = 0) cannot see it


def test_exit_sees_a_drag_exit_map_with_plus_ell(monkeypatch):
    real = template.drag_exit_map
    monkeypatch.setattr(template, "drag_exit_map", lambda s, ell: real(s, tuple(-e for e in ell)))
    result = ExitV2().run()
    assert not result.holds and "not D_ℓy" in result.reason


def test_exit_sees_a_pullback_without_the_form(monkeypatch):
    real = template.pullback_gap
    monkeypatch.setattr(template, "pullback_gap", lambda m, gram, d: real(tuple(tuple(0 * e for e in row) for row in m), gram, d))
    result = ExitV2().run()
    assert not result.holds and "pullback_gap(K, G, D_ℓ)" in result.reason


def test_exit_sees_exit_maps_that_disagree_at_sigma_zero(monkeypatch):
    real = template.exit_map
    monkeypatch.setattr(template, "exit_map", lambda plane, s: real(plane, s) if s == 1 or plane == "φ = f_c"
                        else (real(plane, s)[0], (0, 1), real(plane, s)[2]))
    result = ExitV2().run()
    assert not result.holds and "σ = 0" in result.reason


def test_exit_sees_a_missing_drag_form(exit_v2):
    ob, subject = exit_v2
    assert_fails(ob, dataclasses.replace(subject, drag_gaps=subject.drag_gaps[:1]), "not 4 and 2")


# -- stability_bound ------------------------------------------------------------------------


def _without_step(subject, name):
    b = subject.bound
    return dataclasses.replace(subject, bound=dataclasses.replace(
        b, steps=tuple(s for s in b.steps if s.name != name), goals=tuple(g for g in b.goals if g[0] != name)))


@pytest.mark.parametrize("case", StabilityBoundV2.CASES)
def test_stability_bound_sees_a_chain_missing_a_case(bound, case):
    ob, subject = bound
    assert_fails(ob, _without_step(subject, case), "misses a case", case)


def test_stability_bound_sees_a_reversed_fact(bound):
    ob, subject = bound
    facts = dict(subject.bound.facts)
    name = next(n for n in facts if n.startswith("V_∞ ≤ c₂|x|²_𝒜 on R̂ ∖ R̂′"))
    lo, hi = facts[name]
    facts[name] = (hi, lo)
    assert_fails(ob, dataclasses.replace(subject, bound=dataclasses.replace(subject.bound, facts=facts)), "does not follow", "R̂ ∖ R̂′")


def test_stability_bound_sees_a_cited_obligation_that_check_does_not_run(bound):
    ob, subject = bound
    registered = tuple(i for i in subject.registered if i != "sup_flow_v2.drag_region")
    assert_fails(ob, dataclasses.replace(subject, registered=registered), "sup_flow_v2.drag_region", "check does not run")


def test_stability_bound_sees_a_fact_that_rests_on_nothing(bound):
    ob, subject = bound
    facts = dict(subject.bound.facts)
    facts["U ≤ 0 on R̂′"] = (sp.Symbol("U_t", nonnegative=True), sp.Integer(0))
    assert_fails(ob, dataclasses.replace(subject, bound=dataclasses.replace(subject.bound, facts=facts)), "cite no obligation")


def test_stability_bound_sees_an_unused_lemma_step(bound):
    ob, subject = bound
    rename = {n: n.replace("sup_flow_v2.sign_crossing", "σ crosses once") for n in subject.bound.facts}
    facts = {rename[n]: v for n, v in subject.bound.facts.items()}
    steps = tuple(dataclasses.replace(s, uses=tuple((rename.get(n, n), m) for n, m in s.uses)) for s in subject.bound.steps)
    forged = dataclasses.replace(subject, bound=dataclasses.replace(subject.bound, facts=facts, steps=steps))
    assert_fails(ob, forged, "sup_flow_v2.sign_crossing", "unused")


def test_stability_bound_sees_kappa_below_c2_in_the_drag_case(bound):
    ob, subject = bound
    b = subject.bound
    steps = tuple(dataclasses.replace(s, uses=tuple(u for u in s.uses if not u[0].startswith("κ² ≥ c₂"))) if s.name == "x(0) ∈ R̂ ∖ R̂′" else s
                  for s in b.steps)
    assert_fails(ob, dataclasses.replace(subject, bound=dataclasses.replace(b, steps=steps)), "does not follow")
