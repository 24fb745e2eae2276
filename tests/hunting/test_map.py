"""The hunting map P against the exact simulation; the cycles of Table I with f_s = 1.2 f_c."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import Parameters, simulate
from symbolic_friction.errors import ParameterError
from symbolic_friction._hunting import HuntingMap, find_cycles
from symbolic_friction._hunting._map import real_root_escape
from symbolic_friction._hunting._report import simulation_agreement, with_static

A12 = with_static(Parameters.table_i("a"), F(6, 5))
B12 = with_static(Parameters.table_i("b"), F(6, 5))


@pytest.fixture(scope="module")
def cycle_a():
    (c,) = find_cycles(A12)
    return c


@pytest.fixture(scope="module")
def cycle_b():
    (c,) = find_cycles(B12)
    return c


def test_case_a_hunts_with_the_documented_cycle(cycle_a):
    c = cycle_a
    assert c.symmetric and c.slips == 1 and c.stable
    assert abs(c.sigma - 0.10504486800579652) <= 1e-12
    assert abs(c.period - 46.860418567897) <= 1e-9
    assert abs(c.amplitude_s - c.sigma / 4) <= 1e-15  # s is monotone along a slip: max |s| at the sticks
    assert 0 < c.multiplier < 1


def test_one_step_of_the_map_is_the_simulation_between_two_stick_exits(cycle_a):
    """From a stick exit, the simulation's next exit is at P(σ), after the map's slip and stick durations."""
    P = HuntingMap(A12)
    for sigma in (0.05, 0.3, 2.0):
        st = P.step(sigma)
        k_p, k_i = 3.0, 4.0
        s0 = -sigma / k_i
        z0 = ((-1.2 - k_p * s0) / k_i, s0, 0.0)
        t_half = st.slip_time + st.stick
        sol = simulate(A12, z0, t_half * 1.01, t_eval=[0.0, t_half])
        exits = [(t, x) for (t, b, _), x in zip(sol.events, sol.event_x) if b == 0]
        (t_exit, x_exit), = exits[:1]
        assert abs(t_exit - t_half) <= 1e-12 * t_half
        assert abs(x_exit[0] - st.next_sigma) <= 1e-14
        assert abs(abs(x_exit[1]) - 1.2) == 0.0


def test_a_step_with_reversals_is_the_simulation_too():
    """From σ = 100 the slip ends beyond -f_s and reverses twice before the mass sticks."""
    P = HuntingMap(A12)
    st = P.step(100.0)
    assert st.reason == "exit" and [s[0] for s in st.slips] == [1, -1, 1]
    s0 = -100.0 / 4.0
    z0 = ((-1.2 - 3.0 * s0) / 4.0, s0, 0.0)
    t_half = st.slip_time + st.stick
    sol = simulate(A12, z0, t_half * 1.01, t_eval=[0.0, t_half])
    assert [e[1:] for e in sol.events[:4]] == [(1, -1), (-1, 1), (1, 0), (0, -1)]
    for (t, _, _), x, slip in zip(sol.events, sol.event_x, st.slips):
        assert abs(x[0] - slip[2]) <= 1e-13 * 100 and abs(x[1] - slip[3]) <= 1e-13 * 100
    assert abs(sol.events[3][0] - t_half) <= 1e-12 * t_half
    assert abs(sol.event_x[3][0] - st.next_sigma) <= 1e-13 * 100


def test_the_cycle_agrees_with_a_long_simulation_to_1e_9(cycle_a, cycle_b):
    for c in (cycle_a, cycle_b):
        ag = simulation_agreement(c)
        assert ag.holds(1e-9), ag.describe()


def test_the_agreement_check_can_fail(cycle_a):
    """A cycle value moved by 1e-6 is far outside 1e-9."""
    import dataclasses

    wrong = dataclasses.replace(cycle_a, sigma=cycle_a.sigma * (1 + 1e-6))
    assert not simulation_agreement(wrong, periods=12).holds(1e-9)


def test_the_amplitude_grows_linearly_from_zero_with_f_s_minus_f_c(cycle_a):
    """Without reversals P(σ) = Δ h(σ/Δ): σ* is proportional to Δ = f_s - f_c."""
    (half,) = find_cycles(with_static(Parameters.table_i("a"), F(11, 10)), general=False)
    assert abs(half.sigma * 2 - cycle_a.sigma) <= 1e-13


def test_the_map_is_odd():
    P = HuntingMap(A12)
    for s in (0.01, 0.2, 3.0):
        assert P(-s) == -P(s)


def test_the_paper_model_has_no_hunting_map():
    with pytest.raises(ParameterError, match="f_s = f_c = 1"):
        HuntingMap(Parameters.table_i("a"))


# -- case (b): three real roots ---------------------------------------------------------------
def test_case_b_three_real_roots_gives_the_exact_escape_bound():
    esc = real_root_escape(B12)
    assert esc.root_bracket == (F(-1, 5), F(-1, 5))  # χ = (s + 1/5)(s + 1/2)(s + 4/5)
    assert esc.bound == F(1, 5) * F(1, 5)
    assert real_root_escape(A12) is None  # complex pair


@pytest.mark.parametrize("factor, ends", [(0.5, True), (0.99, True), (1.0, False), (1.01, False), (3.0, False)])
def test_case_b_a_slip_from_a_stick_exit_ends_only_below_the_bound(factor, ends):
    P = HuntingMap(B12)
    st = P.step(factor * 0.04)
    assert (st.reason == "exit") == ends
    if ends:
        assert st.next_sigma < 0  # the slip always overshoots
    else:
        assert st.reason == "slips forever"


def test_case_b_from_a_large_start_the_mass_never_sticks_again():
    """z0 = (0, 1, 0): the first stick exits with |σ| = 0.08 = 2·bound, and the slip never ends."""
    sol = simulate(B12, (0.0, 1.0, 0.0), 2000.0, t_eval=[0.0, 2000.0])
    assert [e[1:] for e in sol.events] == [(0, -1)]
    assert abs(sol.event_x[0][0]) == pytest.approx(0.08)
    assert abs(sol.x[-1, 1] + 1.0) < 1e-6  # converging to (0, -f_c, 0) ∈ 𝒜 while slipping


def test_case_b_hunts_below_the_bound(cycle_b):
    c = cycle_b
    assert c.symmetric and c.slips == 1 and c.stable and c.multiplier < 0
    assert c.sigma < float(real_root_escape(B12).bound)
    assert abs(c.sigma - 0.01182905148819867) <= 1e-12
    assert abs(c.period - 380.907022964) <= 1e-6
