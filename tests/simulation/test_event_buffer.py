"""The event buffer of the exact kernel: a trajectory with more events than its buffer holds goes on where it stopped.

The kernel stops with ``BUFFER_FULL`` and its loop's state saved when a turn finds
no free slot; :func:`.event.run` and :func:`.event.run_one` hand it a larger
buffer with the events so far, and it goes on.  The room changes nothing: every
output is the same, bit for bit, as with room for every event from the start, in
both variants of the kernel.
"""

from __future__ import annotations

import dataclasses
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._simulation import _jit, event, simulate
from symbolic_friction._simulation.batch import simulate_batch

from .test_reset import random_gain_sets

CASES = {
    "a": Parameters.table_i("a"),
    "a_reset": dataclasses.replace(Parameters.table_i("a"), reset_dwell=F(1, 100)),
    # a dwell longer than a slip (τ* = 4.136): the timer decides, so the count and time of the last reset go on too
    "a_reset_long_dwell": dataclasses.replace(Parameters.table_i("a"), reset_dwell=F(6)),
    "a_reset_stiction": dataclasses.replace(Parameters.table_i("a"), f_s=F(6, 5), reset_dwell=F(1, 100)),
    # stiff (the split flow of .modal), τ* = 6.59
    "stiff_reset": dataclasses.replace(random_gain_sets(5)[4], reset_dwell=F(1, 100)),
}
FIELDS = ("x", "z", "mode", "event_t", "event_x", "event_before", "event_after", "event_residual", "n_events", "t_stop", "x0")


def starts(n: int) -> np.ndarray:
    z = np.random.default_rng(11).uniform(-5, 5, size=(n, 3))
    z[: n // 3, 2] = 0.0  # at rest
    return z


def tiny_rooms(monkeypatch) -> None:
    """No slot on the first pass, then one more per pass: every event is a stop and a resumption."""
    monkeypatch.setattr(event, "_first_room", lambda K, t_end, max_events: 0)
    monkeypatch.setattr(event, "_next_room", lambda room, n_ev, t_stop, t_end, max_events: min(max_events, room + 1))


def same(a, b) -> None:
    for field in FIELDS:
        assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), field
    assert a.status.tolist() == b.status.tolist()


@pytest.mark.parametrize("variant", ["python", "numba"])
@pytest.mark.parametrize("name", list(CASES))
def test_a_full_buffer_goes_on_where_it_stopped_bit_for_bit(name, variant, monkeypatch):
    monkeypatch.setenv(_jit.ENV, "1" if variant == "numba" else "0")
    params, z0 = CASES[name], starts(6)
    t = np.linspace(0.0, 25.0, 51)
    whole = simulate_batch(params, z0, 25.0, t_eval=t, max_events=300)
    one = simulate(params, z0[0], 25.0, t_eval=t, max_events=300)
    assert whole.n_events.max() >= 8  # many stops and resumptions below
    tiny_rooms(monkeypatch)
    same(simulate_batch(params, z0, 25.0, t_eval=t, max_events=300), whole)
    again = simulate(params, z0[0], 25.0, t_eval=t, max_events=300)
    assert again.events == one.events and np.array_equal(again.z, one.z) and np.array_equal(again.x, one.x)


@pytest.mark.parametrize("variant", ["python", "numba"])
def test_a_resumed_trajectory_stopped_by_the_event_budget_ends_as_before(variant, monkeypatch):
    """Stopped after each of its first events: the samples up to the stop (the grid ends at it) are unchanged.

    The last sample sits at the stop time, where the dense output uses the state the loop carried (and, in a
    slip mode, the numbers of the slip that starts there, computed from it), so this also checks that all of it
    went on.
    """
    monkeypatch.setenv(_jit.ENV, "1" if variant == "numba" else "0")
    for name in ("a", "a_reset"):
        stops = [simulate(CASES[name], (0.0, 3.0, 0.0), 60.0, max_events=k, grid_points=41) for k in range(1, 8)]
        with monkeypatch.context() as m:
            tiny_rooms(m)
            for k, want in enumerate(stops, start=1):
                got = simulate(CASES[name], (0.0, 3.0, 0.0), 60.0, max_events=k, grid_points=41)
                assert got.events == want.events and got.status == want.status == "max_events reached", (name, k)
                assert np.array_equal(got.t, want.t) and np.array_equal(got.x, want.x) and np.array_equal(got.z, want.z)


@pytest.mark.parametrize("variant", ["python", "numba"])
def test_the_event_budget_still_stops_a_resumed_trajectory(variant, monkeypatch):
    monkeypatch.setenv(_jit.ENV, "1" if variant == "numba" else "0")
    params, z0 = CASES["a_reset"], starts(4)
    t = np.linspace(0.0, 25.0, 51)
    whole = simulate_batch(params, z0, 25.0, t_eval=t, max_events=7)
    assert set(whole.status.tolist()) == {"max_events reached"}
    tiny_rooms(monkeypatch)
    same(simulate_batch(params, z0, 25.0, t_eval=t, max_events=7), whole)


def test_reset_pid_fits_its_events_in_the_first_buffer(monkeypatch):
    """About three events per slip of length τ* (a reset, the stick's end, the slip's end): one kernel call."""
    calls = []
    original = event._kernel_call
    monkeypatch.setattr(event, "_kernel_call", lambda *a: calls.append(a[-2].size) or original(*a))
    batch = simulate_batch(CASES["a_reset"], starts(5), 200.0, t_eval=np.linspace(0.0, 200.0, 21), max_events=10_000)
    assert batch.n_events.min() > 100 and calls == [5]
    calls.clear()
    pid = simulate_batch(CASES["a"], starts(5), 200.0, t_eval=np.linspace(0.0, 200.0, 21), max_events=10_000)
    assert calls == [5] and event._first_room(event.slip_model(CASES["a"]).K, 200.0, 10_000) == event._FIRST_ROOM
    assert pid.n_events.max() <= event._FIRST_ROOM


def test_the_next_room_follows_the_event_rate_within_bounds():
    # 32 events by t = 50 of 200: 128 at that rate, a quarter more
    assert event._next_room(32, np.array([32, 20]), np.array([50.0, 50.0]), 200.0, 10_000) == 160
    assert event._next_room(32, np.array([32]), np.array([199.0]), 200.0, 10_000) == 128  # at least 4×
    assert event._next_room(32, np.array([32]), np.array([0.0]), 200.0, 10_000) == 2048  # at most 64×
    assert event._next_room(32, np.array([32]), np.array([1.0]), 200.0, 100) == 100  # at most max_events
