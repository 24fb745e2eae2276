"""``model.modes_runtime`` on every f_c, with and without static friction: the real mode code, mutated, fails it.

Each test changes the simulators' mode selection the way a slip of the pen
would (monkeypatching :mod:`symbolic_friction._simulation.modes` or handing
the obligation a wrapped function) and asserts the obligation fails and names
the place; the band it allows is pinned from both sides.
"""

from __future__ import annotations

import dataclasses

import pytest

from symbolic_friction._obligations import _modes_binding
from symbolic_friction._obligations.model import ModesRuntime
from symbolic_friction._simulation import modes

from ._helpers import assert_fails, assert_holds, obligation_fixture

modes_runtime = obligation_fixture(ModesRuntime)


def test_holds_on_every_f_c_and_with_stiction(modes_runtime):
    out = assert_holds(*modes_runtime)
    assert "1e-06" in out.reason and "1000000.0" in out.reason and "1.2" in out.reason


def test_the_named_band_is_four_ulps():
    assert _modes_binding.SNAP_ULPS == 4.0 and _modes_binding.EPS == 2.0**-52
    assert set(_modes_binding.F_CS) == {1.0, 2.0, 1e-6, 1e6}
    assert _modes_binding.band(0, 1, 1.0, 0.0, 0.0) == 4 * _modes_binding.Fraction(2) ** -52


@pytest.mark.parametrize("factor", [2.0**40, 4.0, 0.25])
def test_a_band_wider_or_narrower_than_named_fails(modes_runtime, monkeypatch, factor):
    """The band is pinned: the real mode_at_rest with its ε scaled (2⁴⁰ looser, or just 4× either way) fails."""
    monkeypatch.setattr(modes, "_EPS", modes._EPS * factor)
    assert_fails(*modes_runtime, "mode_at_rest", "φ = ")


def test_ignoring_the_callers_tol_fails(modes_runtime):
    ob, s = modes_runtime

    def mode_at_rest(sigma, base, offset, f_c, tol, excess=0.0):
        return s.mode_at_rest(sigma, base, offset, f_c, 0.0, excess)

    assert_fails(ob, dataclasses.replace(s, mode_at_rest=mode_at_rest), "mode_at_rest", "tol = ")


def test_ignoring_static_friction_at_rest_fails(modes_runtime):
    ob, s = modes_runtime

    def mode_at_rest(sigma, base, offset, f_c, tol, excess=0.0):
        return s.mode_at_rest(sigma, base, offset, f_c, tol, 0.0)

    assert_fails(ob, dataclasses.replace(s, mode_at_rest=mode_at_rest), "mode_at_rest", "f_s = f_c + ")


def test_a_sign_slip_in_the_stiction_boundary_fails(modes_runtime):
    ob, s = modes_runtime

    def mode_at_rest(sigma, base, offset, f_c, tol, excess=0.0):  # the lower boundary at -f_c + excess
        b, o, k = s.mode_at_rest(sigma, base, offset, f_c, tol, excess)
        return (b, -o, k) if b == -1 and o == -excess and excess else (b, o, k)

    assert_fails(ob, dataclasses.replace(s, mode_at_rest=mode_at_rest), "keeps φ as -1·f_c")


def test_mode_after_slip_ignoring_stiction_fails(modes_runtime):
    ob, s = modes_runtime

    def mode_after_slip(sigma, offset, direction, f_c, tol, excess=0.0):
        return s.mode_after_slip(sigma, offset, direction, f_c, tol, 0.0)

    assert_fails(ob, dataclasses.replace(s, mode_after_slip=mode_after_slip), "after a slip d = ")


def test_mode_after_slip_without_the_clamp_fails(modes_runtime):
    ob, s = modes_runtime

    def mode_after_slip(sigma, offset, direction, f_c, tol, excess=0.0):  # the rounding side taken at face value
        return s.mode_at_rest(sigma, direction, offset, f_c, tol, excess)

    assert_fails(ob, dataclasses.replace(s, mode_after_slip=mode_after_slip), "after a slip d = ")


def test_a_row_swapped_at_one_f_c_only_fails(modes_runtime, monkeypatch):
    """table_row right at f_c = 2 but row (vii) read as (viii) at f_c = 1e-6: the scaled points catch it."""
    ob, s = modes_runtime

    def table_row(sigma, phi, v, f_c, f_s=None):
        row = s.table_row(sigma, phi, v, f_c, f_s)
        return "viii" if row == "vii" and f_c < 1e-3 else row

    assert_fails(ob, dataclasses.replace(s, table_row=table_row), "table_row gives row (viii)")


def test_table_row_without_f_s_fails(modes_runtime):
    ob, s = modes_runtime

    def table_row(sigma, phi, v, f_c, f_s=None):
        return s.table_row(sigma, phi, v, f_c)

    assert_fails(ob, dataclasses.replace(s, table_row=table_row), "f_s = ", "table_row gives")


def test_a_row_never_reached_from_one_base_fails(modes_runtime, monkeypatch):
    """Offsets that never leave the boundaries leave rows (ii) and (x) unreached: vacuous, so it fails."""
    ob, s = modes_runtime
    real = _modes_binding._offsets
    monkeypatch.setattr(_modes_binding, "_offsets", lambda base, f_c, excess, bands: [o for o in real(base, f_c, excess, bands)
                                                                                      if abs(o + base * f_c) <= 1.1 * f_c])
    assert_fails(ob, s, "never reached")
