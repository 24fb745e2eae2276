"""Initial states of the cross-check."""

from __future__ import annotations

import numpy as np

from symbolic_friction import Parameters
from symbolic_friction._crosscheck._initial import grid_states, special_states, sphere_states
from symbolic_friction._crosscheck._run import search_mode


def test_initial_states():
    p = Parameters.table_i("b")
    rng = np.random.default_rng(0)
    s = sphere_states(p, 60, rng, radii=(0.5, 2.0))
    r = np.linalg.norm(s.x, axis=1)
    assert set(np.round(r, 12)) == {0.5, 2.0} and len(s) == 60
    g = grid_states(p, 125)
    assert len(g) == 125 and np.any(np.all(g.x == 0, axis=1))
    sp = special_states(p)
    assert np.any(np.all(np.isclose(sp.x, [0.0, 1.001, 0.0]), axis=1))
    assert search_mode("sphere r=1f_c") == "random spheres" and search_mode("adversarial x") == "adversarial"
