"""simulate_batch: the one event-driven kernel over many initial states."""

from __future__ import annotations


import numpy as np
import pytest

from symbolic_friction.errors import SimulationError
from symbolic_friction._simulation import Status, simulate
from symbolic_friction._simulation import Trajectories
from symbolic_friction._simulation.batch import iter_batches, simulate_batch

from ..tolerance import relative_error
from symbolic_friction._reference import Reference

from .gain_sets import GAIN_SETS

CASES = GAIN_SETS


def starts(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    z = rng.uniform(-5, 5, size=(n, 3)) * rng.choice([1e-3, 1.0, 1e3], size=(n, 1))
    z[: n // 5, 2] = 0.0  # at rest
    # exact boundary and attractor starts for case (a)-like rows: s = 0, v = 0
    z[n // 5 : n // 5 + 4] = [[-0.25, 0.0, 0.0], [0.25, 0.0, 0.0], [0.1, 0.0, 0.0], [0.5, -1.0, 0.0]]
    return z


@pytest.mark.parametrize("name", list(CASES))
def test_batch_and_single_runs_are_identical_bit_for_bit(name):
    params = CASES[name]
    z0 = starts(120, seed=len(name))
    t = np.linspace(0, 20, 201)
    batch = simulate_batch(params, z0, 20.0, t_eval=t)
    for i, zi in enumerate(z0):
        sol = simulate(params, zi, 20.0, t_eval=t)
        assert batch.status[i] == sol.status, i
        assert batch.events(i) == sol.events, i
        assert np.array_equal(batch.z[i], sol.z), i
        assert np.array_equal(batch.x[i], sol.x), i
        assert np.array_equal(batch.mode[i], sol.mode), i
        assert np.array_equal(batch.event_x[i, : len(sol.events)], sol.event_x), i


def test_batch_matches_the_reference():
    params = CASES["a"]
    z0 = np.array([[0.0, 5.0, 0.0], [-3.0, 3.0, -3.0], [0.5, -1.0, 0.0]])
    t = np.linspace(0, 30, 301)
    batch = simulate_batch(params, z0, 30.0, t_eval=t)
    for i, zi in enumerate(z0):
        ref = Reference(params, tuple(zi), 30.0)
        z_ref, _ = ref.sample(t)
        assert relative_error(batch.z[i], z_ref, scale=max(1.0, np.linalg.norm(zi))) <= 1e-10
        want = ref.event_list()
        assert [e[1:] for e in batch.events(i)] == [e[1:] for e in want]
        assert max(abs(a[0] - b[0]) for a, b in zip(batch.events(i), want)) <= 1e-10


def test_shapes_types_and_statuses():
    params = CASES["a"]
    z0 = [[0.0, 5.0, 0.0], [-0.25, 0.0, 0.0], [0.0, 0.0, 3.0]]
    sol = simulate_batch(params, z0, 30.0, t_eval=np.linspace(0, 30, 61))
    assert isinstance(sol, Trajectories)
    assert sol.t.shape == (61,) and sol.z.shape == (3, 61, 3) and sol.mode.shape == (3, 61)
    assert sol.mode.dtype == np.int8 and sol.n_events.dtype.kind == "i"
    assert sol.status.tolist() == [Status.T_END, Status.EQUILIBRIUM, Status.T_END]
    assert np.array_equal(sol.t_stop, [30.0, 30.0, 30.0])
    assert sol.event_t.shape == (3, int(sol.n_events.max()))
    assert np.isnan(sol.event_t[1]).all() and sol.n_events[1] == 0
    assert np.all(sol.z[1] == [-0.25, 0.0, 0.0])
    assert sol.x.shape == (3, 61, 3)
    assert np.array_equal(sol.z[:, 0], np.array(z0))


def test_default_grid():
    sol = simulate_batch(CASES["b"], [[0.0, 5.0, 5.0]], 12.0, grid_points=25)
    assert np.array_equal(sol.t, np.linspace(0, 12, 25))


def test_max_events_stops_each_trajectory_at_its_own_event():
    params = CASES["a"]
    z0 = np.array([[0.0, 5.0, 0.0], [0.0, 0.0, 3.0], [-0.25, 0.0, 0.0]])
    t = np.linspace(0, 30, 301)
    sol = simulate_batch(params, z0, 30.0, t_eval=t, max_events=4)
    for i in range(3):
        one = simulate(params, z0[i], 30.0, t_eval=t, max_events=4)
        assert sol.status[i] == one.status
        assert [e[1:] for e in sol.events(i)] == [e[1:] for e in one.events]
        assert np.allclose([e[0] for e in sol.events(i)], [e[0] for e in one.events], rtol=1e-14)
        back = sol.solution(i)
        assert np.array_equal(back.t, one.t)
        assert relative_error(back.z, one.z) <= 1e-12
        if one.status == Status.MAX_EVENTS:
            assert sol.t_stop[i] == pytest.approx(one.events[-1][0], rel=1e-14)
            assert np.isnan(sol.z[i, t > sol.t_stop[i]]).all()


def test_the_batch_method_rejects_bad_input_with_specific_messages():
    p = CASES["a"]
    with pytest.raises(SimulationError, match=r"Z0 must have shape \(N, 3\) with N ≥ 1; got shape \(3,\)"):
        simulate_batch(p, [0.0, 1.0, 2.0], 1.0)
    with pytest.raises(SimulationError, match=r"got shape \(0, 3\)"):
        simulate_batch(p, np.zeros((0, 3)), 1.0)
    with pytest.raises(SimulationError, match=r"must be finite; 1 row\(s\) are not, first row 1: \[nan, 0.0, 0.0\]"):
        simulate_batch(p, [[0, 0, 0], [np.nan, 0, 0]], 1.0)
    with pytest.raises(SimulationError, match=r"Z0 must be an \(N, 3\) array of numbers"):
        simulate_batch(p, [["a", "b", "c"]], 1.0)
    with pytest.raises(SimulationError, match=r"t_end must be finite and > 0; got -1"):
        simulate_batch(p, [[0, 0, 1]], -1)
    with pytest.raises(SimulationError, match=r"max_events must be an integer ≥ 1; got 0"):
        simulate_batch(p, [[0, 0, 1]], 1.0, max_events=0)
    with pytest.raises(SimulationError, match=r"grid_points must be an integer ≥ 2; got 1"):
        simulate_batch(p, [[0, 0, 1]], 1.0, grid_points=1)
    with pytest.raises(SimulationError, match=r"t_eval must be nondecreasing within \[0, t_end\]"):
        simulate_batch(p, [[0, 0, 1]], 1.0, t_eval=[0.0, 2.0])
    with pytest.raises(SimulationError, match=r"params must be a Parameters instance; got dict"):
        simulate_batch({"k_p": 1}, [[0, 0, 1]], 1.0)


def test_the_simulation_package_exports_the_batch_lazily():
    import symbolic_friction._simulation as sim

    assert sim.simulate_batch is simulate_batch and sim.iter_batches is iter_batches
    with pytest.raises(AttributeError, match=r"'symbolic_friction._simulation' has no attribute 'simulate_fast'"):
        sim.simulate_fast  # noqa: B018


def test_iter_batches_streams_the_same_trajectories_in_chunks():
    params = CASES["a"]
    z0 = starts(50, seed=3)
    t = np.linspace(0, 10, 11)
    whole = simulate_batch(params, z0, 10.0, t_eval=t)
    parts = list(iter_batches(params, z0, 10.0, t_eval=t, chunk=16))
    assert [len(p) for p in parts] == [16, 16, 16, 2]
    joined = Trajectories.concatenate(parts)
    assert np.array_equal(joined.z, whole.z, equal_nan=True)
    assert np.array_equal(joined.event_t, whole.event_t, equal_nan=True)
    with pytest.raises(SimulationError, match=r"chunk must be an integer ≥ 1; got 0"):
        next(iter_batches(params, z0, 10.0, chunk=0))


def test_events_carry_their_states():
    params = CASES["a"]
    batch = simulate_batch(params, [[0.0, 5.0, 0.0]], 30.0, t_eval=np.linspace(0, 30, 31))
    n = int(batch.n_events[0])
    ev = batch.event_x[0, :n]
    assert np.all(ev[:, 2] == 0.0)  # every event is a zero of v
    f_c = float(params.f_c)
    leaving = batch.event_before[0, :n] == 0  # a stick ends on φ = ±f_c exactly
    assert np.all(np.abs(ev[leaving, 1]) == f_c)
    assert np.all(batch.event_residual[0, :n] <= 1e-12)
