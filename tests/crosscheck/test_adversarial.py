"""The adversary's objective functions."""

from __future__ import annotations

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck._initial import hat_V_rate
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._simulation.batch import simulate_batch
from tests.crosscheck.helpers import _cert


def test_hat_V_rate_matches_a_finite_difference_along_the_flow():
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    x0 = np.array([0.3, -2.0, 0.7])  # v > 0, φ < f_c: in R̂, σ ≠ 0, |φ| ≠ f_c
    t = np.array([0.0, 1e-6])
    b = simulate_batch(p, x_to_z(p, x0[None]), float(t[-1]), t_eval=t)
    from symbolic_friction._model.lyapunov import V_hat

    vh = V_hat(p, b.x[0], cl.k)
    fd = (vh[1] - vh[0]) / 1e-6 / vh[0]
    assert hat_V_rate(p, cl, x0[None])[0] == pytest.approx(fd, rel=1e-4)
    assert np.isnan(hat_V_rate(p, cl, np.array([[0.3, 2.0, 0.7]])))[0]  # in R
