"""Checks of the test oracle itself (symbolic_friction/_reference.py).

The adaptive flow is checked against the former fixed-grid one (non-stiff
gains), against ``mpmath.expm`` at 60 digits from the start of every slip
(stiff gains, the regression cases of ``reference_cases.py`` and random stiff
gain sets), against its own recorded data, for its cost, and broken on purpose
with a step longer than its rule allows.
"""

from __future__ import annotations

import functools
import math
import time
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._reference import Reference, reference_table_mode

from .reference_cases import CASES, EXPECTED, random_case


def test_the_taylor_step_matrix_is_expm_to_the_working_precision():
    ref = Reference(Parameters.table_i("a"), (0.0, 0.0, 0.0), 1.0)
    with mpmath.workdps(60):
        A = mpmath.matrix([[0, 0, -4], [1, 0, -3], [0, 1, -mpmath.mpf(32) / 5]])
        E = mpmath.expm(A * ref.h)
        worst = max(abs(E[i, j] - ref.E_h[i][j]) for i in range(3) for j in range(3))
    assert worst < mpmath.mpf(10) ** -45


def test_a_slip_without_event_is_the_affine_flow_around_its_equilibrium():
    # v stays positive on [0, 0.05] from this state: no event, pure slip +1
    p = Parameters.table_i("a")
    z0 = (0.0, 0.0, 5.0)
    ref = Reference(p, z0, 0.05)
    assert ref.events == []
    (sigma, phi, v), mode = ref.x_at(0.05)
    with mpmath.workdps(60):
        A = mpmath.matrix([[0, 0, -4], [1, 0, -3], [0, 1, -mpmath.mpf(32) / 5]])
        y = mpmath.expm(A * mpmath.mpf(0.05)) * mpmath.matrix([0, -1, 5])
        want = [y[0], y[1] + 1, y[2]]
    assert mode == 1
    assert max(abs(a - b) for a, b in zip((sigma, phi, v), want)) < mpmath.mpf(10) ** -40


def test_a_stick_ramps_phi_and_exits_at_f_c_in_closed_form():
    p = Parameters.table_i("a")  # σ = -4 s, φ = -4 e_i - 3 s, f_c = 1
    ref = Reference(p, (-0.25, 0.5, 0.0), 2.0)  # σ = -2, φ = -0.5: row (vi)
    t_exit, before, after = ref.events[0]
    assert (before, after) == (0, -1)
    assert t_exit == mpmath.mpf(1) / 4  # (-f_c - φ)/σ = (-1 + 0.5)/(-2)


def test_the_reference_table_has_the_papers_eleven_rows():
    f_c = 1
    assert [reference_table_mode(*x, f_c) for x in [
        (0, 0, 1), (0, 2, 0), (1, 1, 0), (0, 1, 0), (-1, 1, 0), (0, 0, 0),
        (1, -1, 0), (0, -1, 0), (-1, -1, 0), (0, -2, 0), (0, 0, -1),
    ]] == [1, 1, 1, 0, 0, 0, 0, 0, -1, -1, -1]


def test_too_few_digits_are_refused():
    with pytest.raises(ValueError, match="at least 40 digits"):
        Reference(Parameters.table_i("a"), (0, 0, 0), 1.0, dps=30)


def test_sampling_returns_floats_in_z_coordinates():
    ref = Reference(Parameters.table_i("b"), (1.0, 2.0, 0.0), 3.0)
    zs, modes = ref.sample([0.0, 1.5, 3.0])
    assert np.array(zs).shape == (3, 3)
    assert zs[0] == (1.0, 2.0, 0.0)
    assert set(modes) <= {-1, 0, 1}


# -- the adaptive flow (stiff gains) ------------------------------------------------------

NON_STIFF = {
    "a": (Parameters.table_i("a"), (0.0, 1.0, 0.0), 10.0),
    "b": (Parameters.table_i("b"), (0.0, 0.0, 3.0), 10.0),
    "a_stiction": (Parameters(k_p=3, k_i=4, k_v=Fraction(32, 5), f_s=Fraction(6, 5)), (1.0, 2.0, 0.0), 8.0),
}


def _A60(params):
    q = lambda x: mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator  # noqa: E731
    return mpmath.matrix([[0, 0, -q(params.k_i)], [1, 0, -q(params.k_p)], [0, 1, -q(params.k_v)]])


@pytest.mark.parametrize("name", NON_STIFF)
def test_the_adaptive_flow_agrees_with_the_fixed_grid(name):
    params, z0, t_end = NON_STIFF[name]
    new = Reference(params, z0, t_end)
    old = Reference(params, z0, t_end, _method="grid")
    assert new.status == old.status
    assert [(a, b) for _, a, b in new.events] == [(a, b) for _, a, b in old.events]
    assert len(new.events) >= 2
    for (t_new, _, _), (t_old, _, _) in zip(new.events, old.events):
        assert abs(t_new - t_old) <= 1e-25 * max(1, abs(t_old))
    times = [t_end * k / 10 for k in range(11)]
    scale = max(max(abs(c) for c in old.x_at(t)[0]) for t in times)
    for t in times:
        (x_new, m_new), (x_old, m_old) = new.x_at(t), old.x_at(t)
        assert m_new == m_old
        assert max(abs(a - b) for a, b in zip(x_new, x_old)) <= 1e-25 * scale, t


def _check_against_expm(ref, params, interior=4, max_slips=None):
    """Each slip (the first ``max_slips``) against ``e^{Aτ}`` at 60 digits from its start:
    states, the zero of ``v`` at its end, and ``k v > 0`` inside."""
    with mpmath.workdps(60):
        A = _A60(params)
        f_c = mpmath.mpf(Fraction(params.f_c).numerator) / Fraction(params.f_c).denominator
        slips = [piece for piece in ref.pieces if piece.mode != 0]
        for piece in slips[:max_slips]:
            d = piece.mode
            y0 = mpmath.matrix([piece.x0[0], piece.x0[1] - d * f_c, piece.x0[2]])
            size = max(abs(c) for c in y0) or mpmath.mpf(1)
            span = piece.t1 - piece.t0
            for k in range(1, interior + 2):
                tau = span * k / (interior + 1)
                y = mpmath.expm(A * tau) * y0
                x, mode = ref.x_at(piece.t0 + tau)
                got = [x[0], x[1] - d * f_c, x[2]]
                assert max(abs(got[i] - y[i]) for i in range(3)) <= 1e-32 * size, (piece.t0, tau)
                if k <= interior:
                    assert d * y[2] > 0, f"v has a zero inside the slip at t = {piece.t0 + tau}"
            if piece.t1 < ref.t_end:
                assert abs(y[2]) <= 1e-32 * size  # the slip ends at a zero of v


@functools.cache
def recorded(name: str) -> Reference:
    """The reference of the regression case ``name`` at 40 digits: computed once for the tests that only read it (a
    solution is fixed at construction; reading it samples, never changes it)."""
    params, z0, t_end = CASES[name]
    return Reference(params, z0, t_end, dps=40)


def test_a_remembered_flow_has_the_bits_of_a_new_one():
    """``e^{Aτ}`` is remembered across the references of a process, keyed by all it is formed from: a reference
    made again finds every one, and its events and states are those made with nothing remembered."""
    from symbolic_friction._reference import slip

    params, z0, t_end = Parameters.table_i("a"), (-1.0, 2.0, -0.5), 6.0
    times = [t_end * k / 16 for k in range(17)]
    slip._EXPM_CACHE.clear()
    fresh = Reference(params, z0, t_end)
    want = [fresh.x_at(t) for t in times]
    remembered = len(slip._EXPM_CACHE)
    again = Reference(params, z0, t_end)
    assert [again.x_at(t) for t in times] == want and again.events == fresh.events and len(fresh.events) >= 2
    assert len(slip._EXPM_CACHE) == remembered  # nothing formed again
    finer = Reference(params, z0, t_end, dps=60)  # another precision: formed anew, not found
    assert len(slip._EXPM_CACHE) > remembered
    assert abs(finer.events[-1][0] - fresh.events[-1][0]) <= 1e-45


def test_a_state_between_grid_points_is_the_enclosure_or_the_mpmath_flow(monkeypatch):
    """Between grid points a state is the midpoint of an arb enclosure of ``e^{Ar} y(jh)``, agreeing with the mpmath
    flow far beyond the digits asked for; when the enclosure is not tight enough, the mpmath flow itself."""
    from symbolic_friction._reference import sample

    ref = Reference(Parameters.table_i("a"), (-1.0, 2.0, -0.5), 6.0)
    times, inside = [], []
    for t in (0.37 * k for k in range(1, 17)):
        piece = [p for p in ref.pieces if p.t0 <= t][-1]
        if piece.mode != 0:
            tau = ref.ctx.mpf(t) - piece.t0
            j = max(0, min(int(tau / piece.h), len(piece.grid) - 1))
            times.append(t)
            inside.append((piece, j, tau - j * piece.h))
    got = [ref._offset_at(t)[0] for t in times]
    flows = [ref._flow(p.grid[j], r) for p, j, r in inside]
    for a, b in zip(got, flows):  # both well inside the guard digits above the 50 asked for
        assert max(abs(u - v) for u, v in zip(a, b)) <= ref.ctx.mpf(10) ** -58 * max(abs(v) for v in b)
    assert sum(a != b for a, b in zip(got, flows)) >= 4  # the enclosure is used, not the flow
    monkeypatch.setattr(sample, "_SLACK_BITS", -64)  # no ball is that tight: every state from the mpmath flow
    assert [ref._offset_at(t)[0] for t in times] == flows


@pytest.mark.parametrize("name", CASES)
def test_the_regression_cases_agree_with_expm_from_each_event(name):
    params, z0, t_end = CASES[name]
    ref = recorded(name)
    _check_against_expm(ref, params)
    assert ref.guard_v_hits == 0


@pytest.mark.parametrize("name", CASES)
def test_the_regression_cases_reproduce_their_recorded_data(name):
    params, z0, t_end = CASES[name]
    ref = recorded(name)
    want = EXPECTED[name]
    assert ref.status == want["status"]
    assert [(a, b) for _, a, b in ref.events] == [(a, b) for _, a, b in want["events"]]
    for (t, _, _), (t_want, _, _) in zip(ref.events, want["events"]):
        assert abs(t - ref.ctx.mpf(t_want)) <= 1e-24 * max(1, abs(ref.ctx.mpf(t_want)))
    z, _ = ref.z_mpf_at(t_end)
    z_want = [ref.ctx.mpf(c) for c in want["z_end"]]
    scale = max(abs(c) for c in z_want)
    assert max(abs(a - b) for a, b in zip(z, z_want)) <= 1e-23 * scale


def test_the_recorded_cases_are_what_their_names_say():
    # creep: slip(-1), stick, then one slip(-1) to the horizon with φ falling at σ ≈ -0.1185
    creep = EXPECTED["creep"]["events"]
    assert [(a, b) for _, a, b in creep] == [(-1, 0), (0, -1)]
    assert abs(float(creep[0][0]) - 0.20893) < 1e-5 and abs(float(creep[1][0]) - 6.50758) < 1e-5
    ref = recorded("creep")
    assert abs(float(ref.x_at(4.0)[0][0]) + 0.1185) < 1e-3
    # stiff_stall: slip, slip, a stick, one slip(-1) to the horizon
    assert [(a, b) for _, a, b in EXPECTED["stiff_stall"]["events"]] == [(-1, 1), (1, 0), (0, -1)]
    assert EXPECTED["stiff_cost"]["events"] == []
    assert 1e5 < CASES["kv2e5"][0].k_v < 1e6 and 1e7 < CASES["kv1e8"][0].k_v < 1e9
    stiction = CASES["stiction"][0]
    assert stiction.f_c == 2 and stiction.f_s == Fraction(6, 5) * stiction.f_c


def test_a_stiff_trajectory_costs_what_a_mild_one_does():
    # the fixed grid would take ‖A‖∞ T / (1/4) ≈ 6·10⁶ steps on stiff_cost
    for name in ("stiff_cost", "kv1e8"):
        t0 = time.perf_counter()
        ref = Reference(*CASES[name], dps=40)
        assert time.perf_counter() - t0 < 5.0, name
        assert ref.status == "t_end"
        assert len(ref.pieces[-1].grid) <= 3  # one step of h = min(π/(2β), T) or two


def test_the_step_follows_the_slow_pair():
    params, z0, t_end = CASES["kv1e8"]
    ref = recorded("kv1e8")
    with mpmath.workdps(80):
        roots = mpmath.polyroots([1, params.k_v, mpmath.mpf(params.k_p.numerator) / params.k_p.denominator, params.k_i],
                                 maxsteps=200, extraprec=200)
        beta = max(abs(mpmath.im(r)) for r in roots)
        assert any(abs(r - ref.lambda_r) <= 1e-40 * abs(r) for r in roots if mpmath.im(r) == 0)
    # β only sets the step, π/(2β), so it is kept as a float
    assert abs(ref.beta - beta) <= 1e-14 * beta
    assert abs(ref.step - min(mpmath.pi / (2 * beta), 20)) <= 1e-12 * ref.step


def test_a_step_longer_than_the_slow_period_skips_a_zero_of_v():
    # Table I (a): slow pair -0.2 ± 0.79i; a step of one full period 2π/β puts both ends
    # of the step at the same phase, so the guard cannot see the crossing in between
    params, z0, t_end = NON_STIFF["a"]
    right = Reference(params, z0, t_end)
    assert right.step < mpmath.pi / right.beta
    wrong = Reference(params, z0, t_end, _max_step=2 * math.pi / float(right.beta))
    assert len(right.events) == 3 and wrong.events == []
    with pytest.raises(AssertionError, match="zero inside the slip"):
        _check_against_expm(wrong, params)


def test_a_creeping_slip_keeps_its_offset_exact():
    # the stick of "creep" ends at φ = -f_c exactly: the new slip starts at y = (σ, 0, 0)
    ref = recorded("creep")
    slip = ref.pieces[-1]
    assert slip.mode == -1 and slip.grid[0][1] == 0 and slip.grid[0][2] == 0
    # v stays tiny and negative for the whole slip: one piece to the horizon
    assert ref.status == "t_end" and len(ref.pieces) == 3


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4))
def test_random_stiff_gain_sets_agree_with_expm(seed):
    params, z0, t_end = random_case(seed + 100)
    t0 = time.perf_counter()
    ref = Reference(params, z0, t_end, dps=40, max_events=2000)
    assert time.perf_counter() - t0 < 20.0
    _check_against_expm(ref, params, interior=1, max_slips=60)
    assert ref.guard_v_hits == 0


def test_the_random_cases_are_admissible_and_exact():
    for seed in range(20):
        params, z0, t_end = random_case(seed)
        assert isinstance(params.k_v, Fraction) and params.k_v * params.k_p > params.k_i
        assert 1e-4 <= params.k_p <= 1.0001e4 and 1e-4 <= params.k_i <= 1.0001e4
        assert 1 < params.k_v * params.k_p / params.k_i <= 11.01
        assert 0.099 <= math.sqrt(sum(c * c for c in z0)) <= 100.1 and t_end == 20.0
    assert random_case(3) == random_case(3)


def test_creeping_stick_slip_cycles_keep_exact_stick_durations():
    # σ shrinks ~30× per cycle and each stick lasts -offset/σ: carried as offsets, the
    # durations agree to the working precision (with φ carried absolutely they drifted
    # by 5e-33 at dps = 40)
    creep = Parameters(k_v=17, k_p=336, k_i=1746, f_c=Fraction(3828, 4096))
    ref = Reference(creep, (-(2.0**-11), -(2.0**-12), 0.0), 4.0, dps=40)
    sticks = [b[0] - a[0] for a, b in zip(ref.events, ref.events[1:]) if a[2] == 0]
    assert len(sticks) >= 6
    assert max(sticks) - min(sticks) <= 1e-45


def test_an_enclosed_state_is_never_read_from_an_infinity_or_a_nan():
    """``flow_enclosed`` reads each mpf's raw mantissa and exponent; an infinity's or a NaN's mantissa is 0, which
    would be the state 0: such an input gets ``None`` (the caller's mpmath flow), a finite one a state."""
    import mpmath

    from symbolic_friction._reference.sample import flow_enclosed

    ctx = mpmath.mp.clone()
    ctx.prec = 180
    gains = ((3, 1), (4, 1), (32, 5))
    y, tau = [ctx.mpf(1), ctx.mpf(-2), ctx.mpf("0.5")], ctx.mpf("0.25")
    assert flow_enclosed(ctx, gains, y, tau) is not None
    for bad in (ctx.inf, -ctx.inf, ctx.nan):
        assert flow_enclosed(ctx, gains, [bad, y[1], y[2]], tau) is None
        assert flow_enclosed(ctx, gains, y, bad) is None
