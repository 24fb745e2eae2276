"""The reset-PID obligations hold, and each fails when its subject is broken."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import pytest

from symbolic_friction._model import reset as model
from symbolic_friction._obligations import reset as ob


@pytest.mark.parametrize("cls", ob.OBLIGATIONS)
def test_each_reset_obligation_holds(cls):
    result = cls().run()
    assert result.holds, result.reason


def test_v_jump_fails_for_a_jump_map_that_raises_v():
    """A jump past the band (φ⁺ = 2 f_c sign σ) raises V by P₂₂ f_c²."""
    o = ob.ResetVJump()
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (s, 2 * f_c * sg, v))
    out = o.verify(bad)
    assert not out.holds and "not 0" in out.reason


def test_v_jump_fails_for_a_jump_map_that_moves_sigma():
    o = ob.ResetVJump()
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (s / 2, f_c * sg, v))
    assert not o.verify(bad).holds


def test_no_second_jump_fails_without_the_timer_reset():
    """A jump map that would leave τ ≥ τ_d (margins read with τ⁺ = τ_d) allows an immediate second jump."""
    o = ob.ResetNoSecondJump()
    bad = dataclasses.replace(o.derive(), margins=lambda *a: model.jump_set_margins(*a[:-2], a[-1], a[-1]))
    out = o.verify(bad)
    assert not out.holds and "timer" in out.reason


def test_no_second_jump_fails_for_a_law_that_stops_short():
    o = ob.ResetNoSecondJump()
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (s, f_c * sg / 2, v))
    out = o.verify(bad)
    assert not out.holds and "σφ⁺" in out.reason


def test_attractor_fails_for_a_jump_that_leaves_it():
    o = ob.ResetAttractor()
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (s, 2 * f_c, v))
    assert not o.verify(bad).holds
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (s + 1, f_c * sg, v))
    assert not o.verify(bad).holds


def test_basic_conditions_fail_for_an_open_or_discontinuous_jump_set():
    o = ob.ResetBasicConditions()
    import sympy as sp

    step = dataclasses.replace(o.derive(), margins=lambda *a: (*model.jump_set_margins(*a)[:3], sp.Heaviside(a[7] - a[8])))
    assert not o.verify(step).holds
    short = dataclasses.replace(o.derive(), margins=lambda *a: model.jump_set_margins(*a)[:3])
    assert not o.verify(short).holds


def test_basic_conditions_fail_for_a_jump_map_outside_sgn():
    o = ob.ResetBasicConditions()
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (s, f_c * 2 * sg, v))
    assert not o.verify(bad).holds


def test_leaves_stick_fails_for_a_jump_that_keeps_the_mass_stuck():
    o = ob.ResetLeavesStick()
    select_mode, _ = o.derive()
    out = o.verify((select_mode, lambda s, p, v, f_c, sg: (s, f_c * sg / 2, v)))
    assert not out.holds


def test_kernel_binding_fails_against_a_different_law():
    """The kernel is bound to the model: a model that jumps to half the band disagrees with it."""
    o = ob.ResetKernelBinding()
    simulate, params = o.derive()
    original = model.jump_map_x
    try:
        model.jump_map_x = lambda s, p, v, f_c, sg: (s, f_c * sg / 2, v)
        out = o.verify((simulate, params))
    finally:
        model.jump_map_x = original
    assert not out.holds


def test_kernel_binding_fails_for_a_kernel_without_resets():
    o = ob.ResetKernelBinding()
    simulate, params = o.derive()
    out = o.verify((simulate, params.without_reset()))
    assert not out.holds and "does not reset" in out.reason


def test_jump_map_in_z_is_the_jump_map_in_x():
    """e_i⁺ = (f_c sign(s) - k_p s)/k_i is φ⁺ = f_c sign(σ) in eq. (CoC)."""
    from symbolic_friction import Parameters
    from symbolic_friction._model.coordinates import z_to_x
    import numpy as np

    p = Parameters.table_i("a")
    for s in (Fraction(1, 3), Fraction(-5, 2)):
        z = np.array([Fraction(7), s, Fraction(0)], dtype=object)
        sign_s = 1 if s > 0 else -1
        post = np.array(model.jump_map_z(z[0], z[1], z[2], p.k_p, p.k_i, p.f_c, sign_s), dtype=object)
        x = z_to_x(p, post)
        assert x[1] == p.f_c * (-sign_s) and x[0] == -p.k_i * s


def test_same_stick_exits_fails_for_a_jump_that_moves_sigma():
    o = ob.ResetSameStickExits()
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (2 * s, f_c * sg, v))
    out = o.verify(bad)
    assert not out.holds and "changes σ" in out.reason


def test_same_stick_exits_fails_for_a_jump_past_the_exit():
    """φ⁺ = 2 f_c sign(σ) lies beyond the exit sign(σ) f_s when f_s = f_c: the stick would have to run backwards."""
    o = ob.ResetSameStickExits()
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (s, 2 * f_c * sg, v))
    out = o.verify(bad)
    assert not out.holds and "not ≥ 0" in out.reason


def test_same_stick_exits_fails_for_a_jump_that_lengthens_the_stick():
    """φ⁺ = -f_c sign(σ) (the wrong side) keeps the exit but makes the stick longer than without the jump."""
    o = ob.ResetSameStickExits()
    bad = dataclasses.replace(o.derive(), jump_map_x=lambda s, p, v, f_c, sg: (s, -f_c * sg, v))
    out = o.verify(bad)
    assert not out.holds and "lengthens" in out.reason
