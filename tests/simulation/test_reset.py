"""Reset PID (``Parameters.reset_dwell``): the event kernel against the mpmath reference, and plain PID untouched.

The law (the package's own, :mod:`symbolic_friction._model.reset`): during a stick with ``φ`` short of
``sign(σ) f_c`` and at least ``reset_dwell`` after the last reset, ``e_i`` jumps so that
``φ⁺ = sign(σ) f_c``.  Both the kernel and the reference implement it, each from that definition.
"""

from __future__ import annotations

import dataclasses
import functools
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import AssumptionError, SimulationError
from symbolic_friction._model.coordinates import z_to_x
from symbolic_friction._simulation import simulate

from ..tolerance import relative_error
from .against_reference import scale_of, simulate_and_reference

TOL = 1e-10
T_END = 20.0
DWELL = F(1, 100)


def with_reset(p: Parameters, dwell=DWELL) -> Parameters:
    return dataclasses.replace(p, reset_dwell=dwell)


def random_gain_sets(n: int, seed: int = 32) -> list[Parameters]:
    """Admissible gain sets, log-uniform k_p, k_i in 10^-1..10^1, Routh margin 1.1..100, rationals with 3 digits."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        k_p = F(round(10 ** rng.uniform(-1, 1), 3)).limit_denominator(1000)
        k_i = F(round(10 ** rng.uniform(-1, 1), 3)).limit_denominator(1000)
        margin = F(round(10 ** rng.uniform(np.log10(1.1), 2), 3)).limit_denominator(1000)
        if k_p > 0 and k_i > 0 and margin > 1:
            out.append(Parameters(k_p=k_p, k_i=k_i, k_v=margin * k_i / k_p))
    return out


CASES = {
    "a_rest": (with_reset(Parameters.table_i("a")), (0.0, 3.0, 0.0)),
    "a_moving": (with_reset(Parameters.table_i("a")), (-1.0, 2.0, -0.5)),
    "b_rest": (with_reset(Parameters.table_i("b")), (0.0, 3.0, 0.0)),
    "b_stick": (with_reset(Parameters.table_i("b")), (-5.0, 0.3, 1.2)),
    # a dwell longer than a slip: the timer, not the law, decides when the next reset comes
    "a_long_dwell": (with_reset(Parameters.table_i("a"), F(6)), (0.0, 3.0, 0.0)),  # longer than a slip (4.136)
    "a_stiction": (with_reset(dataclasses.replace(Parameters.table_i("a"), f_s=F(6, 5))), (0.0, 1.0, 0.0)),
}
for _j, _p in enumerate(random_gain_sets(20)):
    CASES[f"random_{_j:02d}"] = (with_reset(_p), (0.0, 2.0, 0.0) if _j % 2 else (1.0, -1.5, 0.25))


@functools.lru_cache(maxsize=None)
def _run(name):
    params, z0 = CASES[name]
    return simulate_and_reference(params, z0, T_END, 401)


@pytest.mark.parametrize("name", list(CASES))
def test_reset_trajectories_match_the_reference(name):
    sol, ref, z_ref, _ = _run(name)
    assert relative_error(sol.z, z_ref, scale=scale_of(CASES[name][1])) <= TOL
    events = ref.event_list()
    assert [e[1:] for e in sol.events] == [e[1:] for e in events]
    times = np.array([e[0] for e in sol.events])
    want = np.array([e[0] for e in events])
    assert np.all(np.abs(times - want) <= TOL * np.maximum(1.0, np.abs(want)))


def test_the_cases_do_reset():
    """Nothing passes vacuously: the Table I cases and most random ones reset at least once."""
    resets = {name: sum(1 for e in _run(name)[0].events if e[1:] == (0, 0)) for name in CASES}
    assert resets["a_rest"] >= 5 and resets["b_stick"] >= 1 and resets["a_long_dwell"] >= 1
    assert sum(1 for n, r in resets.items() if n.startswith("random") and r > 0) >= 10


def test_a_reset_puts_phi_at_sign_sigma_f_c_and_keeps_sigma():
    params, z0 = CASES["a_rest"]
    sol = simulate(params, z0, T_END)
    resets = [(t, x) for (t, a, b), x in zip(sol.events, sol.event_x) if (a, b) == (0, 0)]
    assert resets
    for t, x in resets:
        after = simulate(params, z0, t + 1e-9, t_eval=[t + 1e-9])
        sigma = x[0]
        assert abs(after.x[0, 0] - sigma) <= 1e-12 * max(1.0, abs(sigma))
        # just after the jump the mass slips toward the setpoint from φ = sign(σ) f_c
        assert after.mode[0] == np.sign(sigma)


def test_the_dwell_time_separates_resets():
    params, z0 = CASES["a_long_dwell"]
    sol = simulate(params, z0, 60.0)
    times = [t for t, a, b in sol.events if (a, b) == (0, 0)]
    assert len(times) >= 2
    assert min(np.diff(times)) >= 6 - 1e-12


def test_plain_pid_is_unchanged_by_the_reset_option():
    """Reset off is the paper's PID bit for bit; a huge dwell resets once and then behaves like PID."""
    p = Parameters.table_i("a")
    t = np.linspace(0, 40, 401)
    plain = simulate(p, (0, 3, 0), 40.0, t_eval=t)
    assert dataclasses.replace(p, reset_dwell=None) == p and hash(dataclasses.replace(p, reset_dwell=None)) == hash(p)
    once = simulate(with_reset(p, F(10) ** 400), (0, 3, 0), 40.0, t_eval=t)
    assert sum(1 for e in once.events if e[1:] == (0, 0)) == 1
    assert not np.array_equal(plain.z, once.z)


def test_reset_is_never_slower_than_pid_on_table_i():
    """Resets only shorten sticks (σ is constant in a stick), so |s| reaches a level no later than with PID."""
    for case, z0 in (("a", (0, 3, 0)), ("b", (0, 3, 0)), ("b", (-5, 0.3, 1.2))):
        p = Parameters.table_i(case)
        t = np.linspace(0, 200, 20001)
        pid = np.abs(simulate(p, z0, 200.0, t_eval=t).z[:, 1])
        rst = np.abs(simulate(with_reset(p), z0, 200.0, t_eval=t).z[:, 1])
        for level in (1e-1, 1e-2, 1e-3):
            first = lambda s: t[np.argmax(s <= level * 3)] if np.any(s <= level * 3) else np.inf  # noqa: E731
            assert first(rst) <= first(pid)


def test_reset_parameters_are_refused_where_they_are_not_modelled():
    p = with_reset(Parameters.table_i("a"))
    with pytest.raises(SimulationError, match="reset PID"):
        simulate(p, (0, 1, 0), 1.0, method="moreau")
    with pytest.raises(AssumptionError, match="reset_dwell > 0"):
        Parameters(k_p=3, k_i=4, k_v="6.4", reset_dwell=0)
    with pytest.raises(AssumptionError, match="reset_dwell > 0"):
        Parameters(k_p=3, k_i=4, k_v="6.4", reset_dwell="-1/2")
    from symbolic_friction.errors import ParameterError
    from symbolic_friction._certify.pipeline import certify

    with pytest.raises(ParameterError, match="reset PID"):
        certify(p)


def test_a_reset_at_t_0_keeps_the_given_state_as_the_first_sample():
    """x and z at t = 0 are both the state before the jump (the jump is the first event, at t = 0)."""
    p = with_reset(Parameters.table_i("a"))
    sol = simulate(p, (-2.375, 3.0, 0.0), 1.0, t_eval=[0.0, 0.5])  # σ = -12, φ = 1/2: a stick, reset at once
    assert sol.events[0] == (0.0, 0, 0)
    np.testing.assert_array_equal(sol.x[0], z_to_x(p, np.array([-2.375, 3.0, 0.0])))
    assert sol.z[0].tolist() == [-2.375, 3.0, 0.0]
