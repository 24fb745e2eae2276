"""The cross-check's view of trajectories at ``f_c ≠ 1`` and ``f_s > f_c``, where ``f_c = 1`` hides a dropped factor.

* ``∫v²`` by the Gramian (``Along.cumI``) equals a fine quadrature of the
  sampled ``v²`` at ``f_c = 2`` and ``f_c = 1/4`` (the slip's equilibrium is
  ``(0, k f_c, 0)``, not ``(0, k, 0)``);
* ``∫v²`` scales as ``f_c²`` (exact scaling by powers of two);
* the mode table holds on exact solutions at ``f_c = 2`` and ``f_c = 1/4``,
  sticks with ``|φ|`` up to ``f_c`` included.
"""

from __future__ import annotations

import dataclasses
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._crosscheck._along import along
from symbolic_friction._crosscheck.mode_table import Modes
from symbolic_friction._crosscheck._property import DEFAULT_RTOL
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._simulation.batch import simulate_batch

A = Parameters.table_i("a")
X0 = np.array([[0.5, 3.0, 2.0], [-1.0, -2.5, 0.0], [0.25, 0.5, -3.0]])
T_END = 20.0
T = np.linspace(0.0, T_END, 40001)


def _batch(p, scale):
    return simulate_batch(p, x_to_z(p, X0 * scale), T_END, t_eval=T)


@pytest.mark.parametrize("f_c", [F(2), F(1, 4)])
def test_the_gramian_integral_is_the_integral_of_v_squared(f_c):
    p = dataclasses.replace(A, f_c=f_c, f_s=f_c)
    b = _batch(p, float(f_c))
    a = along(b)
    v2 = b.x[..., 2] ** 2
    quad = np.concatenate([np.zeros((v2.shape[0], 1)), np.cumsum((v2[:, 1:] + v2[:, :-1]) / 2 * np.diff(T), axis=1)], axis=1)
    last = a.last_sample
    got = a.cumI[np.arange(a.N), last]
    assert np.all(got > 0.1 * float(f_c) ** 2)
    np.testing.assert_allclose(got, quad[:, -1], rtol=1e-5)


def test_the_integral_scales_with_f_c_squared():
    base = along(_batch(A, 1.0))
    p = dataclasses.replace(A, f_c=F(4), f_s=F(4))
    big = along(_batch(p, 4.0))
    np.testing.assert_allclose(big.cumI[:, -1], 16 * base.cumI[:, -1], rtol=1e-10)


@pytest.mark.parametrize("f_c", [F(2), F(1, 4)])
def test_the_mode_table_holds_on_exact_solutions(f_c):
    p = dataclasses.replace(A, f_c=f_c, f_s=f_c)
    b = _batch(p, float(f_c))
    ev = Modes().check(b)
    a = along(b)
    stick = a.valid & a.is_sample & (a.ch.piece == 0)
    phi = np.abs(a.xs[..., 1])
    assert np.count_nonzero(stick & (phi > 0.5 * float(f_c))) > 100  # sticks well inside and near the band edge
    assert ev.failures(DEFAULT_RTOL) == 0
