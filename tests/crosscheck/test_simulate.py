"""The cross-check's simulations: within a sharing block the same arguments give the same trajectories, once."""

from __future__ import annotations

import numpy as np

from symbolic_friction import Parameters
from symbolic_friction._crosscheck._simulate import shared_simulations, simulate
from symbolic_friction._simulation.batch import simulate_batch

P = Parameters.table_i("a")
Z0 = np.array([[0.0, 5.0, 0.0], [0.0, 0.0, 3.0]])
T = np.array([0.0, 1.0, 2.0])


def test_simulate_is_simulate_batch():
    got, want = simulate(P, Z0, 2.0, t_eval=T, max_events=100), simulate_batch(P, Z0, 2.0, t_eval=T, max_events=100)
    assert np.array_equal(got.x, want.x) and np.array_equal(got.event_t, want.event_t, equal_nan=True)
    assert simulate(P, Z0, 2.0, t_eval=T, max_events=100) is not got  # outside a block nothing is kept


def test_a_block_keeps_each_simulation_by_its_exact_arguments():
    with shared_simulations():
        first = simulate(P, Z0, 2.0, t_eval=T, max_events=100)
        assert simulate(P, Z0.copy(), 2.0, t_eval=T.copy(), max_events=100) is first
        others = [simulate(P, Z0 + [[0.0, 0.0, 1e-12]], 2.0, t_eval=T, max_events=100),
                  simulate(P, Z0, 2.0, t_eval=np.array([0.0, 2.0]), max_events=100),
                  simulate(P, Z0, 2.0, t_eval=T, max_events=2),
                  simulate(P, Z0, 2.0, t_eval=T, max_events=100, source=np.array(["a", "b"], dtype=object)),
                  simulate(Parameters.table_i("b"), Z0, 2.0, t_eval=T, max_events=100)]
        assert all(other is not first for other in others)
        assert list(others[3].source) == ["a", "b"] and list(first.source) == ["", ""]
    assert simulate(P, Z0, 2.0, t_eval=T, max_events=100) is not first  # the block's results end with it
