"""The event search of a slip: the FIRST zero of v, never skipping a crossing."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._simulation import simulate
from symbolic_friction._simulation.search import first_zero, slip_model

from symbolic_friction._reference import Reference

CASE_A = Parameters.table_i("a")


def mp_v(params: Parameters, y0, tau: float) -> mpmath.mpf:
    """v(τ) = e₃ᵀ e^{Aτ} y0 at 40 digits (independent of the package)."""
    with mpmath.workdps(40):
        k_p, k_i, k_v = (mpmath.mpf(q.numerator) / q.denominator for q in (params.k_p, params.k_i, params.k_v))
        A = mpmath.matrix([[0, 0, -k_i], [1, 0, -k_p], [0, 1, -k_v]])
        return (mpmath.expm(A * mpmath.mpf(tau)) * mpmath.matrix([mpmath.mpf(c) for c in y0]))[2]


def double_dip(params: Parameters, tau_a: float, gap: float, size: float = 10.0) -> np.ndarray:
    """An offset y0 (norm ``size``) whose v vanishes near tau_a and tau_a + gap, dipping below 0 between."""
    E = slip_model(params).expm
    rows = [E.w_scalar(tau_a), E.w_scalar(tau_a + gap)]
    # v(τ) = σ w(τ) + p w'(τ) + v0 w''(τ): (σ, p, v0) orthogonal to both rows
    y0 = np.cross(np.array(rows[0]), np.array(rows[1]))
    y0 *= size / np.linalg.norm(y0)
    return y0 if y0[2] > 0 else -y0


def test_a_start_on_row_iii_is_not_mistaken_for_a_zero():
    # y0 = (σ, 0, 0): v = σ w(τ) has a double zero at τ = 0; the event is w's first positive zero
    model = slip_model(CASE_A)
    tau, y = first_zero(model, (1.0, 0.0, 0.0), 1, 50.0)
    assert tau is not None and tau > 0.1
    with mpmath.workdps(40):
        exact = mpmath.findroot(lambda s: mp_v(CASE_A, (1, 0, 0), s), tau)
        assert abs(float(exact) - tau) <= 1e-13
        # and w > 0 before it
        assert all(mp_v(CASE_A, (1, 0, 0), tau * k / 64) > 0 for k in range(1, 64))
    assert y[2] == pytest.approx(0.0, abs=1e-15)


@pytest.mark.parametrize("gap", [1e-2, 1e-3, 1e-4])
def test_a_double_crossing_inside_one_scan_cell_is_found(gap):
    model = slip_model(CASE_A)
    assert gap < model.table.dt  # both zeros lie within one cell of the scan
    y0 = double_dip(CASE_A, 1.3, gap)
    mid = 1.3 + gap / 2
    assert mp_v(CASE_A, y0, mid) < 0  # v really dips below zero between the two zeros
    tau, _ = first_zero(model, tuple(y0), 1, 10.0)
    # the first zero is the dip's left end, not the right one; where exactly within
    # rounding depends on the slope there (≈ v''·gap/2), so check it by its residual
    assert tau is not None and tau < 1.3 + gap / 4
    assert abs(float(mp_v(CASE_A, y0, tau))) <= 1e-14 * np.abs(y0).max()
    with mpmath.workdps(40):
        assert all(mp_v(CASE_A, y0, tau * k / 40) > 0 for k in range(1, 40))


def test_the_double_crossing_agrees_with_the_independent_reference():
    # gap 1e-2 < Δ: inside one cell of the package's scan and one step of the reference's
    y0 = double_dip(CASE_A, 1.3, 1e-2)
    x0 = y0 + np.array([0.0, 1.0, 0.0])  # slip +1 equilibrium (0, f_c, 0), f_c = 1
    z0 = x_to_z(CASE_A, x0)
    sol = simulate(CASE_A, z0, 2.0)
    ref = Reference(CASE_A, tuple(z0), 2.0)
    assert sol.events[0][1:] == ref.event_list()[0][1:]
    assert abs(sol.events[0][0] - ref.event_list()[0][0]) <= 1e-10


def tangent_start(params: Parameters, tau0: float, size: float = 10.0) -> np.ndarray:
    """An offset y0 whose v touches zero at tau0 (v = v' = 0 there) from above."""
    E = slip_model(params).expm
    k_p, k_i, k_v = E.k_p, E.k_i, E.k_v
    w0, w1, w2 = E.w_scalar(tau0)
    w3 = -k_v * w2 - k_p * w1 - k_i * w0
    y0 = np.cross([w0, w1, w2], [w1, w2, w3])
    y0 *= size / np.linalg.norm(y0)
    return y0 if y0[2] > 0 else -y0


@pytest.mark.parametrize("tau0", [0.8, 1.3])
def test_a_tangency_ends_promptly_and_agrees_with_the_reference(tau0):
    """At a double zero of v the certified steps shrink geometrically; the run must not stall."""
    y0 = tangent_start(CASE_A, tau0)
    tau, _ = first_zero(slip_model(CASE_A), tuple(y0), 1, 10.0)
    # either the contact point (v within rounding of 0 there) or a later zero: never before
    assert tau is not None and tau >= tau0 - 1e-6
    z0 = x_to_z(CASE_A, y0 + np.array([0.0, 1.0, 0.0]))
    t = np.linspace(0, 6, 301)
    sol = simulate(CASE_A, z0, 6.0, t_eval=t)
    ref = Reference(CASE_A, tuple(z0), 6.0)
    z_ref, _ = ref.sample(t)
    assert np.max(np.abs(sol.z - np.array(z_ref))) / max(1.0, np.linalg.norm(z0)) <= 1e-10
    # At a tangency the event list is ill-conditioned: v dips to about -3e-15 (exactly, from
    # the rounded x(0) too), below the rounding of v's closed form in double precision
    # (about 1e-14 here), so whether the dip is seen, and where it starts (|v'| ≈ 1e-7
    # there: 1e-14/|v'| ≈ 1e-7 s), is decided by the last bits.  Every event of the
    # reference must be found: at its time to 1e-10 away from the contact, to 1e-6 at it,
    # with the same modes; any other event must come in such a pair, within 1e-6 of the
    # contact.  The states above agree to 1e-10 all the same.
    want = ref.event_list()

    def tol(e):
        return 1e-6 if abs(e[0] - tau0) <= 1e-6 else 1e-10

    def matched(e, among):
        return any(abs(e[0] - w[0]) <= max(tol(e), tol(w)) and e[1:] == w[1:] for w in among)

    assert all(matched(w, sol.events) for w in want)
    extra = [e for e in sol.events if not matched(e, want)]
    assert all(abs(e[0] - tau0) <= 1e-6 for e in extra) and len(extra) % 2 == 0
    assert len(sol.events) - len(extra) == len(want)


@pytest.mark.parametrize("name", ["a", "b", "triple"])
def test_the_slip_that_leaves_a_stick_has_one_length_per_gain_set(name):
    """From y0 = (σ, 0, 0) the search gives the cached length, whatever σ (or no zero, for case (b))."""
    from symbolic_friction._simulation import _kernel as k

    params = Parameters(k_v=3, k_p=3, k_i=1) if name == "triple" else Parameters.table_i(name)
    model = slip_model(params)
    cached, valid = model.K[k.I_STICK_SLIP_T], model.K[k.I_STICK_SLIP_H]
    for sigma in (1e-6, -0.3, 2.0, -7e5):
        tau, _ = first_zero(model, (sigma, 0.0, 0.0), 1 if sigma > 0 else -1, valid)
        if np.isinf(cached):
            assert tau is None
        else:
            assert tau == pytest.approx(cached, rel=1e-13)
    if name == "a":
        assert 4.0 < cached < 4.3 and valid > 300  # w's first zero; 60 time constants of the slowest root
