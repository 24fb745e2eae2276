"""Checks of the test oracle itself (tests/simulation/reference.py)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from symbolic_friction import Parameters

from symbolic_friction._reference import Reference, reference_table_mode


def test_the_taylor_step_matrix_is_expm_to_the_working_precision():
    ref = Reference(Parameters.table_i("a"), (0.0, 0.0, 0.0), 1.0)
    with mpmath.workdps(60):
        A = mpmath.matrix([[0, 0, -4], [1, 0, -3], [0, 1, -mpmath.mpf(32) / 5]])
        E = mpmath.expm(A * ref.h)
        worst = max(abs(E[i, j] - ref.E_h[i][j]) for i in range(3) for j in range(3))
    assert worst < mpmath.mpf(10) ** -45


def test_a_slip_without_event_is_the_affine_flow_around_its_equilibrium():
    # v stays positive on [0, 0.05] from this state: no event, pure slip +1
    p = Parameters.table_i("a")
    z0 = (0.0, 0.0, 5.0)
    ref = Reference(p, z0, 0.05)
    assert ref.events == []
    (sigma, phi, v), mode = ref.x_at(0.05)
    with mpmath.workdps(60):
        A = mpmath.matrix([[0, 0, -4], [1, 0, -3], [0, 1, -mpmath.mpf(32) / 5]])
        y = mpmath.expm(A * mpmath.mpf(0.05)) * mpmath.matrix([0, -1, 5])
        want = [y[0], y[1] + 1, y[2]]
    assert mode == 1
    assert max(abs(a - b) for a, b in zip((sigma, phi, v), want)) < mpmath.mpf(10) ** -40


def test_a_stick_ramps_phi_and_exits_at_f_c_in_closed_form():
    p = Parameters.table_i("a")  # σ = -4 s, φ = -4 e_i - 3 s, f_c = 1
    ref = Reference(p, (-0.25, 0.5, 0.0), 2.0)  # σ = -2, φ = -0.5: row (vi)
    t_exit, before, after = ref.events[0]
    assert (before, after) == (0, -1)
    assert t_exit == mpmath.mpf(1) / 4  # (-f_c - φ)/σ = (-1 + 0.5)/(-2)


def test_the_reference_table_has_the_papers_eleven_rows():
    f_c = 1
    assert [reference_table_mode(*x, f_c) for x in [
        (0, 0, 1), (0, 2, 0), (1, 1, 0), (0, 1, 0), (-1, 1, 0), (0, 0, 0),
        (1, -1, 0), (0, -1, 0), (-1, -1, 0), (0, -2, 0), (0, 0, -1),
    ]] == [1, 1, 1, 0, 0, 0, 0, 0, -1, -1, -1]


def test_too_few_digits_are_refused():
    with pytest.raises(ValueError, match="at least 40 digits"):
        Reference(Parameters.table_i("a"), (0, 0, 0), 1.0, dps=30)


def test_sampling_returns_floats_in_z_coordinates():
    ref = Reference(Parameters.table_i("b"), (1.0, 2.0, 0.0), 3.0)
    zs, modes = ref.sample([0.0, 1.5, 3.0])
    assert np.array(zs).shape == (3, 3)
    assert zs[0] == (1.0, 2.0, 0.0)
    assert set(modes) <= {-1, 0, 1}
