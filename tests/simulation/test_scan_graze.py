"""The certified scan on a graze inside one cell, and the rounding tolerance of a state at rest.

On lightly damped gains (``k_v ≪ √k_p/8``) ``v`` along a slip is a fast
oscillation on a slow offset, so ``|v''|`` can peak between two points of the
scan's grid, right where ``v`` dips below 0.  A cell is cleared only when both
its ends exceed the interpolation error ``Δ²/8·max|v''|`` on the cell, and
``max|v''|`` there exceeds the larger end by up to ``Δ²/8·max|v⁗|``: without
that fourth-order term the scan clears the cell and the slip runs past its end
(every dip below ``10⁻⁹ f_c`` in the middle of a cell is missed).  The dips here
go down to ``10⁻¹³ f_c``, near the rounding of ``v``.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from symbolic_friction._crosscheck._kernel_check import GRAZE
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._model.parameters import Parameters
from symbolic_friction._simulation.batch import simulate_batch
from symbolic_friction._simulation.modes import select_mode
from symbolic_friction._simulation.slip import first_zero, slip_model

PARAMS = Parameters(**GRAZE)


def _graze(cell: float, depth: float) -> tuple[float, np.ndarray]:
    """``(τ_m, y0)``: the slip from offset ``y0`` has ``v(τ_m) = −depth·f_c``, ``v'(τ_m) = 0``, ``v''(τ_m) ≈ f_c``."""
    model = slip_model(PARAMS)
    f_c = float(PARAMS.f_c)
    tau_m = cell * model.table.dt
    y = f_c * np.array([1.0, -float(PARAMS.k_v) * depth, -depth])
    return tau_m, model.expm.apply(np.array([-tau_m]), y)[0]


@pytest.mark.parametrize("depth", [1e-13, 1e-11, 1e-9, 1e-7])
@pytest.mark.parametrize("cell", [3.5, 10.5, 10.3, 10.7, 127.5, 130.5])
def test_the_scan_finds_a_dip_inside_one_cell(cell, depth):
    """The middle of a cell, off its middle, the last cell of the first window and a cell of the second."""
    tau_m, y0 = _graze(cell, depth)
    model = slip_model(PARAMS)
    assert y0[2] > 0 and model.expm.apply(np.array([tau_m]), y0)[0, 2] < 0
    tau, y = first_zero(model, tuple(y0), 1, 2 * tau_m)
    # v ≈ −δ + (τ − τ_m)²/2 about τ_m: its first zero is √(2δ) before τ_m
    assert tau is not None and tau_m - 2 * np.sqrt(2 * depth) < tau < tau_m, (tau, tau_m)
    assert abs(y[2]) <= 1e-12 * float(PARAMS.f_c)


def test_the_kernel_ends_the_slip_at_the_dip():
    tau_m, y0 = _graze(10.5, 1e-11)
    x0 = y0 + np.array([0.0, float(PARAMS.f_c), 0.0])
    batch = simulate_batch(PARAMS, x_to_z(PARAMS, x0[None, :]), 2 * tau_m, t_eval=np.array([0.0, 2 * tau_m]))
    assert int(batch.n_events[0]) >= 1 and int(batch.event_before[0, 0]) == 1
    assert 0.0 < float(batch.event_t[0, 0]) < tau_m


@pytest.mark.parametrize("ulps", [24, 40, 64, 256])
@pytest.mark.parametrize("sign", [1, -1])
def test_a_state_at_rest_just_beyond_f_c_starts_as_the_exact_table_says(ulps, sign):
    """``φ = ±f_c(1 + m ε)`` exactly with ``σ`` pushing back (``σφ < 0``): the table's row (ii) or (x), a slip,
    whatever ``σ``; the kernel puts on the boundary only what its rounding of ``φ = −k_i e_i − k_p s`` reaches."""
    f_c, k_p, k_i = float(PARAMS.f_c), float(PARAMS.k_p), float(PARAMS.k_i)
    s = sign * 1e-9 * f_c  # σ = −k_i s has the sign −sign
    e_i = -(sign * f_c * (1 + ulps * 2.0**-52) + k_p * s) / k_i
    sigma, phi = -PARAMS.k_i * Fraction(s), -PARAMS.k_i * Fraction(e_i) - PARAMS.k_p * Fraction(s)
    want = select_mode(sigma, phi, 0, PARAMS.f_c)
    assert want == sign and abs(phi) > PARAMS.f_c
    batch = simulate_batch(PARAMS, np.array([[e_i, s, 0.0]]), 1e-3, t_eval=np.array([0.0, 1e-3]))
    assert int(batch.mode[0, 0]) == want
