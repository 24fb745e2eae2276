"""``max_events`` stops a trajectory at its last event: the sample at the stop time is the state there.

The kernel writes one last sample at ``t_stop``, the time of the event that
used up the budget, with the mode and the state the loop carries after it.
When that event starts a slip (a stick's end, rows iii/ix, or a slip that
reverses at ``v = 0``), the sample is the new slip's state at its start, so it
must be computed from the new slip's numbers, not from the slip before (which
gave ``x = (-12, -7, 0)`` for the state ``(6.405, 1, 0)`` of Table I (a)).

For every stop after each of the first six events, in both variants of the
kernel:

* the sample at ``t_stop`` is the state at the last event: the event's state,
  or, after a reset of reset PID (an event with modes ``(0, 0)``), the state
  after the jump, ``(σ, sign(σ) f_c, 0)`` (a sample at an event time belongs
  to the segment that starts there);
* it agrees with the 40-digit reference stopped by the same budget, at its
  last event (after a reset's jump too);
* the samples before ``t_stop`` are those of the trajectory that is not
  stopped, bit for bit, and so is the one at ``t_stop`` when no other event
  falls at that time (a stop changes no sample it computes);
* the compiled and the plain kernel agree bit for bit.
"""

from __future__ import annotations

import dataclasses
import functools
import os
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._reference import Reference
from symbolic_friction._simulation import _jit, simulate
from symbolic_friction._simulation._trajectories import Status

from .gain_sets import GAIN_SETS

A = Parameters.table_i("a")
DWELL = F(1, 100)
CASES = {
    "a": A,
    "b": Parameters.table_i("b"),
    "a_stiction": dataclasses.replace(A, f_s=F(6, 5)),
    "stiff": GAIN_SETS["stiff"],  # the split flow of .modal
    "a_reset": dataclasses.replace(A, reset_dwell=DWELL),
    "a_reset_stiction": dataclasses.replace(A, f_s=F(6, 5), reset_dwell=DWELL),
    "stiff_reset": dataclasses.replace(GAIN_SETS["stiff"], reset_dwell=DWELL),
}
# at rest (a stick first); a fast start (slips that reverse at v = 0, rows ii/x); one in between
STARTS = [(0.0, 3.0, 0.0), (0.0, 0.0, -40.0), (-5.0, 0.3, 1.2)]
T_END = 60.0
MOST = 6  # stops after each of the first MOST events
TOL = 1e-12  # relative to the state's size: the kernel's states agree with the reference to about 1e-14
ULPS = 8 * np.finfo(float).eps  # the kernel's own event state: the same numbers, up to the split flow's rounding


def _variant(monkeypatch, variant: str) -> None:
    monkeypatch.setenv(_jit.ENV, "1" if variant == "numba" else "0")


@functools.cache
def _reference(name: str, start: int, n: int) -> Reference:
    """The 40-digit reference stopped by the same budget, after ``n`` events."""
    return Reference(CASES[name], STARTS[start], T_END, dps=40, max_events=n)


def _after(params: Parameters, event, x_event: np.ndarray) -> np.ndarray:
    """The state at an event that the next segment starts from: after a reset's jump, ``φ⁺ = sign(σ) f_c``."""
    _, before, after = event
    if before == 0 and after == 0:
        return np.array([x_event[0], np.sign(x_event[0]) * float(params.f_c), 0.0])
    return x_event


def _stops(name: str, start: int) -> tuple:
    """``(n, stopped after n events)`` for every ``n ≤ MOST`` at which the trajectory is stopped by the budget, with
    the kernel the environment chooses (:func:`_variant`)."""
    return _stops_with(name, start, os.environ.get(_jit.ENV))


@functools.cache
def _stops_with(name: str, start: int, variant: str | None) -> tuple:
    """:func:`_stops`, run once per kernel variant (``variant``, the environment's choice, is the key): three tests
    read the same stops of each case, and nothing changes them."""
    params, z0 = CASES[name], STARTS[start]
    out = []
    for n in range(1, MOST + 1):
        sol = simulate(params, z0, T_END, max_events=n)
        if sol.status != Status.MAX_EVENTS:
            assert len(sol.events) < n
            break
        out.append((n, sol))
    return tuple(out)


@pytest.mark.parametrize("variant", ["python", "numba"])
@pytest.mark.parametrize("start", range(len(STARTS)))
@pytest.mark.parametrize("name", list(CASES))
def test_the_sample_at_the_stop_is_the_state_at_the_last_event(name, start, variant, monkeypatch):
    _variant(monkeypatch, variant)
    params = CASES[name]
    stops = 0
    for n, sol in _stops(name, start):
        stops += 1
        assert len(sol.events) == n
        t_stop = sol.events[-1][0]
        assert sol.t[-1] == t_stop, (n, sol.t[-1], t_stop)  # the grid ends at the stop, the event time among it
        want = _after(params, sol.events[-1], sol.event_x[-1])
        scale = max(1.0, float(np.max(np.abs(want))))
        got = sol.x[-1]
        assert np.all(np.abs(got - want) <= ULPS * scale), (n, sol.events[-1], got.tolist(), want.tolist())
        assert sol.mode[-1] == sol.events[-1][2], n
        # the reference stopped at the same event: its state there (before a reset's jump, as its event's)
        ref = _reference(name, start, n)
        assert ref.status == "max_events" and len(ref.events) == n, n
        assert [e[1:] for e in ref.events] == [e[1:] for e in sol.events], n
        t_ref = ref.events[-1][0]
        assert abs(float(t_ref) - t_stop) <= TOL * T_END, n
        x_ref = _after(params, sol.events[-1], np.array([float(c) for c in ref.x_at(t_ref)[0]]))
        assert np.all(np.abs(got - x_ref) <= TOL * scale), (n, got.tolist(), x_ref.tolist())
    # a stop after each event, up to MOST (Table I (b) from rest has no event at all)
    assert stops == min(MOST, len(simulate(params, STARTS[start], T_END).events))


@pytest.mark.parametrize("variant", ["python", "numba"])
@pytest.mark.parametrize("start", range(len(STARTS)))
@pytest.mark.parametrize("name", list(CASES))
def test_a_stop_changes_no_sample_it_computes(name, start, variant, monkeypatch):
    """On the stopped run's own times (a grid on ``[0, t_stop]`` and the events): the run that goes on gives the same."""
    _variant(monkeypatch, variant)
    params, z0 = CASES[name], STARTS[start]
    for n, sol in _stops(name, start):
        t_stop = sol.events[-1][0]
        stopped = simulate(params, z0, T_END, t_eval=sol.t, max_events=n)
        on = simulate(params, z0, T_END, t_eval=sol.t, max_events=10_000)
        assert stopped.events == on.events[:n]
        before = sol.t < t_stop
        assert np.array_equal(stopped.x[before], on.x[before]), n
        assert np.array_equal(stopped.z[before], on.z[before]), n
        later = [t for t, *_ in on.events[n:]]
        if not later or later[0] > t_stop:  # the sample at t_stop is after the last event there
            assert np.array_equal(stopped.x[-1], on.x[-1]), (n, stopped.x[-1].tolist(), on.x[-1].tolist())
            assert np.array_equal(stopped.z[-1], on.z[-1]), n
            assert stopped.mode[-1] == on.mode[-1], n


@pytest.mark.parametrize("start", range(len(STARTS)))
@pytest.mark.parametrize("name", list(CASES))
def test_both_variants_stop_alike_bit_for_bit(name, start, monkeypatch):
    runs = {}
    for variant in ("python", "numba"):
        _variant(monkeypatch, variant)
        runs[variant] = list(_stops(name, start))
    assert [n for n, _ in runs["python"]] == [n for n, _ in runs["numba"]]
    for (n, a), (_, b) in zip(runs["python"], runs["numba"]):
        assert a.events == b.events, n
        for field in ("t", "x", "z", "mode", "event_x"):
            assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), (n, field)


def test_table_i_a_stopped_at_its_second_event_ends_on_it():
    """The case that was found: stopped at the stick's end (0 → 1) at t = 3.594, the state (6.405, 1, 0)."""
    sol = simulate(A, (0, 3, 0), T_END, max_events=2)
    assert sol.events[-1][1:] == (0, 1)
    assert np.array_equal(sol.x[-1], sol.event_x[-1])
    assert sol.x[-1][1] == 1.0 and sol.x[-1][2] == 0.0


@pytest.mark.parametrize("variant", ["python", "numba"])
def test_a_slip_that_reverses_exactly_at_t_end_ends_on_its_event_state(variant, monkeypatch):
    """The same last sample when the horizon ends the trajectory at an event that starts a slip.

    Table I (b) from ``(0, 0, 5)``: the first slip reverses at ``t₁`` (row x); with ``t_end = t₁`` the event
    is found at ``t_end`` itself, and the sample there is the reversed slip's start (it was ``(0, -2, 0)``,
    the first slip's start, before).
    """
    _variant(monkeypatch, variant)
    p = Parameters.table_i("b")
    t1 = simulate(p, (0.0, 0.0, 5.0), 30.0).events[0][0]
    sol = simulate(p, (0.0, 0.0, 5.0), t1, t_eval=np.array([0.0, t1]))
    assert sol.status == Status.T_END and sol.events == ((t1, 1, -1),)  # the case: the reversal found at t_end
    want = sol.event_x[-1]
    assert np.all(np.abs(sol.x[-1] - want) <= ULPS * max(1.0, float(np.max(np.abs(want))))), sol.x[-1].tolist()
    assert sol.mode[-1] == -1
