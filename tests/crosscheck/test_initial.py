"""Initial states of the cross-check."""

from __future__ import annotations

import numpy as np
import pytest

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


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_lockstep_nelder_mead_is_scipys_step_for_step(seed):
    """``_nelder_mead_many`` (the starts' runs evaluated together) finds what scipy's Nelder–Mead finds from each
    start, bit for bit, on a rough function with plateaus (the objective's 1e9 outside ``R̂``) and a smooth one."""
    from scipy.optimize import minimize

    from symbolic_friction._crosscheck._initial import _nelder_mead_many

    def rough(U):
        U = np.atleast_2d(U)
        r = np.sin(3 * U[:, 0]) * np.cos(2 * U[:, 1]) + 0.1 * U[:, 2] ** 2 + np.abs(U[:, 0] - U[:, 2])
        return np.where(U[:, 1] > 1.5, 1e9, r)

    def smooth(U):
        U = np.atleast_2d(U)
        return (U[:, 0] - 1) ** 2 + 10 * (U[:, 1] - U[:, 0] ** 2) ** 2 + 0.5 * U[:, 2] ** 2

    rng = np.random.default_rng(seed)
    starts = [rng.uniform(-2, 2, size=3) for _ in range(5)]
    options = dict(maxfev=200, xatol=1e-9, fatol=1e-12)
    for func in (rough, smooth):
        ours = _nelder_mead_many(func, starts, **options)
        for (f, u), u0 in zip(ours, starts):
            ref = minimize(lambda x: float(func(x)[0]), u0, method="Nelder-Mead", options=options)
            assert f == ref.fun and np.array_equal(u, ref.x)
