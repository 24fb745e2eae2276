"""Static friction above Coulomb (``f_s > f_c``): the event-driven kernel against the mpmath reference.

The model is eq. (basic) with a static level: at rest the mass sticks while
``|φ| ≤ f_s``, it leaves ``φ = ±f_s`` with a jump of the acceleration to
``±(f_s - f_c)`` and slips with kinetic friction ``f_c``; a slip that ends with
``|φ| ≤ f_s`` sticks, otherwise it reverses.  Two transitions cannot happen when
``f_s = f_c`` and are tested on purpose: the stick exit with ``v'(0⁺) ≠ 0`` and
a slip that ends with ``|φ|`` in ``(f_c, f_s]`` and sticks.
"""

from __future__ import annotations

import dataclasses

import functools
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import SimulationError
from symbolic_friction._model.coordinates import z_to_x
from symbolic_friction._simulation import simulate
from symbolic_friction._simulation._kernel import mode_after_slip
from symbolic_friction._simulation.modes import mode_at_rest, select_mode, table_row

from ..tolerance import relative_error
from symbolic_friction._reference import reference_table_mode
from .against_reference import scale_of, simulate_and_reference

TOL = 1e-13
EVENT_TOL = 1e-12
N_SAMPLES = 301


def with_fs(p: Parameters, f_s) -> Parameters:
    return dataclasses.replace(p, f_s=f_s)


A12 = with_fs(Parameters.table_i("a"), F(6, 5))
A15 = with_fs(Parameters.table_i("a"), F(3, 2))
B12 = with_fs(Parameters.table_i("b"), F(6, 5))
B15 = with_fs(Parameters.table_i("b"), F(3, 2))

# name -> (params, z0, t_end, minimum number of events)
CASES = {
    "a_fs1.2": (A12, (0.0, 1.0, 0.0), 60.0, 10),
    "a_fs1.5": (A15, (0.0, 5.0, 0.0), 40.0, 8),
    "a_fs1.5_generic": (A15, (-3.0, 3.0, -3.0), 40.0, 8),
    # three real roots: the slip ends at φ = -1.4396 ∈ (-f_s, -f_c) and sticks (it would reverse at f_s = f_c)
    "b_fs1.5_band": (B15, (0.0, 0.0, 5.0), 60.0, 2),
    # three real roots, near the hunting cycle (σ small enough that slips from a stick exit end)
    "b_fs1.2_hunting": (B12, (1.2375, -0.15, 0.0), 900.0, 8),
    "triple_root_fs2": (Parameters(k_v=3, k_p=3, k_i=1, f_s=2), (0.0, 0.0, 5.0), 30.0, 2),
    "f_c_1e-3_fs": (Parameters(k_v="6.4", k_p=3, k_i=4, f_c="1e-3", f_s="1.3e-3"), (0.0, 1e-2, 0.0), 60.0, 6),
}
# Starts at rest around the stick boundary of case (a) with f_s = 3/2 (σ = -4s, φ = -4e_i - 3s), all exact.
REST = {
    "band_sticks": ((-0.125, -0.25, 0.0), "vi"),  # σ = 1, φ = 5/4 ∈ (f_c, f_s): stick (a slip at f_s = f_c)
    "on_fs_outward": ((-0.1875, -0.25, 0.0), "iii"),  # σ = 1, φ = f_s: slip at once
    "on_fs_inward": ((-0.5625, 0.25, 0.0), "v"),  # σ = -1, φ = f_s: stick
    "above_fs": ((-0.6875, 0.25, 0.0), "ii"),  # σ = -1, φ = 2 > f_s: slip
}
for _name, (_z0, _row) in REST.items():
    CASES[f"rest_{_name}"] = (A15, _z0, 15.0, 1)


@functools.lru_cache(maxsize=None)
def run(name: str):
    params, z0, t_end, _ = CASES[name]
    return simulate_and_reference(params, z0, t_end, N_SAMPLES)


@pytest.mark.parametrize("name", list(CASES))
def test_states_match_the_reference(name):
    sol, _, z_ref, _ = run(name)
    assert relative_error(sol.z, z_ref, scale=scale_of(CASES[name][1])) <= TOL


@pytest.mark.parametrize("name", list(CASES))
def test_events_match_the_reference(name):
    sol, ref, _, _ = run(name)
    events = ref.event_list()
    assert [e[1:] for e in sol.events] == [e[1:] for e in events]
    assert len(events) >= CASES[name][3]
    times = np.array([e[0] for e in sol.events])
    want = np.array([e[0] for e in events])
    assert np.all(np.abs(times - want) <= EVENT_TOL * np.maximum(1.0, np.abs(want)))


@pytest.mark.parametrize("name", list(CASES))
def test_modes_match_the_reference(name):
    sol, _, _, mode_ref = run(name)
    near = np.zeros(sol.t.size, dtype=bool)
    for t_event, _, _ in sol.events:
        near |= np.abs(sol.t - t_event) <= 1e-9
    assert np.array_equal(sol.mode[~near], mode_ref[~near])


@pytest.mark.parametrize("name", ["a_fs1.2", "a_fs1.5", "b_fs1.5_band", "b_fs1.2_hunting"])
def test_a_stick_ends_at_f_s_with_a_jump_in_acceleration(name):
    """At a stick exit φ = ±f_s and v'(0⁺) = ±(f_s - f_c) ≠ 0 (impossible at f_s = f_c, where v'(0⁺) = 0)."""
    params = CASES[name][0]
    sol, ref, _, _ = run(name)
    exits = [(t, d, x) for (t, b, d), x in zip(sol.events, sol.event_x) if b == 0]
    assert exits
    jump = float(params.f_s - params.f_c)
    for t, d, x in exits:
        assert x[1] == d * float(params.f_s)
        h = 1e-7
        (_, _, v_ref), mode = ref.x_at(ref.ctx.mpf(t) + h)
        assert mode == d
        assert abs(float(v_ref) / h - d * jump) <= 1e-5  # v = ±(f_s - f_c) h + O(h²)
        late = simulate(params, CASES[name][1], t + h, t_eval=[t + h])
        assert abs(late.x[0, 2] - float(v_ref)) <= 1e-13 * scale_of(CASES[name][1])


def test_a_slip_that_ends_between_f_c_and_f_s_sticks():
    """Case (b) with f_s = 3/2: the slip ends at |φ| ∈ (f_c, f_s] and the mass sticks; with f_s = f_c it reverses."""
    sol, ref, _, _ = run("b_fs1.5_band")
    band = [(e, x) for e, x in zip(sol.events, sol.event_x) if e[1] != 0 and e[2] == 0 and 1.0 < abs(x[1]) <= 1.5]
    assert band
    (t, d, _), x = band[0]
    coulomb = simulate(Parameters.table_i("b"), (0.0, 0.0, 5.0), t + 1.0)
    after = [e for e in coulomb.events if abs(e[0] - t) < 1e-9]
    assert after and after[0][1:] == (d, -d)  # the paper's model: a reversal at the same instant


@pytest.mark.parametrize("name", list(REST))
def test_the_rest_starts_are_on_the_rows_they_claim(name):
    z0, row = REST[name]
    x0 = z_to_x(A15, np.array(z0))
    assert table_row(*(F(c) for c in x0.tolist()), F(1), F(3, 2)) == row


def test_the_table_with_f_s_moves_only_the_stick_boundary():
    f_c, f_s = F(1), F(3, 2)
    # the stick band: sticks with f_s, slips in the paper's model
    assert select_mode(F(1), F(5, 4), F(0), f_c, f_s) == 0 and select_mode(F(1), F(5, 4), F(0), f_c) == 1
    assert select_mode(F(-1), -F(5, 4), F(0), f_c, f_s) == 0 and select_mode(F(-1), -F(5, 4), F(0), f_c) == -1
    assert select_mode(F(1), f_s, F(0), f_c, f_s) == 1 and select_mode(F(-1), f_s, F(0), f_c, f_s) == 0
    assert select_mode(F(0), f_s, F(0), f_c, f_s) == 0  # an equilibrium on the boundary


# Every class and boundary at rest: σ ∈ {<0, 0, >0} × φ around ±f_c and ±f_s.
_SIGMAS = (-1.0, 0.0, 1.0)
_PHIS = (-3.0, -1.5, -1.25, -1.0, -0.5, 0.0, 0.5, 1.0, 1.25, 1.5, 3.0)


@pytest.mark.parametrize("f_s", [1.0, 1.5])
def test_mode_at_rest_and_after_slip_are_the_table_with_f_s(f_s):
    """The kernel's rules (tolerance 0) against the table written independently in the reference."""
    f_c, excess = 1.0, f_s - 1.0
    for sigma in _SIGMAS:
        for phi in _PHIS:
            want = reference_table_mode(F(sigma), F(phi), F(0), F(f_c), F(f_s))
            for base in (-1, 0, 1):
                _, _, k = mode_at_rest(sigma, base, phi - base * f_c, f_c, 0.0, excess)
                assert k == want, (sigma, phi, base)
            for d in (-1, 1):
                offset = phi - d * f_c
                if d * offset <= 0.0:  # a slip in direction d can only end with d·φ ≤ f_c
                    _, _, k = mode_after_slip(sigma, offset, d, f_c, 0.0, excess)
                    assert k == want, (sigma, phi, d)


def test_the_rule_check_can_fail():
    """Deciding with f_c instead of f_s (the Coulomb table) gets the band wrong."""
    want = reference_table_mode(F(1), F(5, 4), F(0), F(1), F(3, 2))
    assert mode_at_rest(1.0, 0, 1.25, 1.0, 0.0)[2] != want
    assert mode_after_slip(1.0, 2.25, -1, 1.0, 0.0)[2] != want  # φ = -f_c + 2.25 = 5/4 after a slip d = -1


def test_the_reference_comparison_can_fail():
    """A change of f_s by 1e-9 moves the solution far outside the tolerance."""
    params, z0, t_end, _ = CASES["a_fs1.2"]
    _, _, z_ref, _ = run("a_fs1.2")
    t = np.linspace(0.0, t_end, N_SAMPLES)
    nudged = with_fs(params, params.f_s + F(1, 10**9))
    assert relative_error(simulate(nudged, z0, t_end, t_eval=t).z, z_ref, scale=scale_of(z0)) > TOL


def test_other_methods_and_the_certificate_refuse_stiction():
    with pytest.raises(SimulationError, match="f_s = 6/5 > f_c = 1"):
        simulate(A12, (0.0, 1.0, 0.0), 1.0, method="moreau", h=1e-3)
    from symbolic_friction import certify
    from symbolic_friction.errors import ParameterError

    with pytest.raises(ParameterError, match="f_s = 6/5 > f_c = 1"):
        certify(A12)


def test_f_s_equal_to_f_c_is_the_paper_model():
    p = Parameters.table_i("a")
    q = with_fs(p, p.f_c)
    assert q == p and hash(q) == hash(p) and str(q) == str(p) and not q.stiction
    t = np.linspace(0, 30, 301)
    a, b = simulate(p, (0, 5, 0), 30.0, t_eval=t), simulate(q, (0, 5, 0), 30.0, t_eval=t)
    assert a.events == b.events and a.z.tobytes() == b.z.tobytes()
