"""The one kernel: compiled by numba and run as plain Python, the results are identical bit for bit."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._simulation import _jit, simulate, simulate_batch

from .gain_sets import GAIN_SETS

numba = pytest.importorskip("numba")

CASES = {
    **GAIN_SETS,
    # static friction above Coulomb: stick exits at ±f_s, slips that start with v' ≠ 0
    "a_stiction": Parameters(k_v="6.4", k_p=3, k_i=4, f_s="1.2"),
    "b_stiction": Parameters(k_v="1.5", k_p="0.66", k_i="0.08", f_s="1.5"),
    # reset PID: resets are events of the same loop
    "a_reset": Parameters(k_v="6.4", k_p=3, k_i=4, reset_dwell="1/100"),
    "b_reset_stiction": Parameters(k_v="1.5", k_p="0.66", k_i="0.08", f_s="1.2", reset_dwell="1/2"),
}


def starts(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    z = rng.uniform(-5, 5, size=(n, 3)) * rng.choice([1e-6, 1e-3, 1.0, 1e3, 1e6], size=(n, 1))
    z[: n // 4, 2] = 0.0  # at rest: the mode table decides
    z[n // 4 : n // 4 + 4] = [[-0.25, 0.0, 0.0], [0.25, 0.0, 0.0], [0.0, 0.0, 0.0], [0.5, -1.0, 0.0]]
    return z


def run_with(monkeypatch, variant: str, params, z0, t):
    monkeypatch.setenv(_jit.ENV, "1" if variant == "numba" else "0")
    assert _jit.variant() == variant
    return simulate_batch(params, z0, float(t[-1]), t_eval=t, max_events=200)


@pytest.mark.parametrize("name", list(CASES))
def test_compiled_and_plain_kernels_agree_bit_for_bit(name, monkeypatch):
    params = CASES[name]
    z0 = starts(60, seed=len(name))
    t = np.linspace(0.0, 20.0, 81)
    a = run_with(monkeypatch, "numba", params, z0, t)
    b = run_with(monkeypatch, "python", params, z0, t)
    for field in ("x", "z", "mode", "event_t", "event_x", "event_before", "event_after", "event_residual", "n_events", "t_stop", "x0"):
        assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), field
    assert a.status.tolist() == b.status.tolist()
    assert a.n_events.sum() >= 40  # not a vacuous comparison: many events were computed


def test_the_scalar_search_and_w_agree_bit_for_bit():
    from symbolic_friction._simulation.search import slip_model

    model = slip_model(CASES["a"])
    plain, fast = _jit.plain(), _jit.compiled()
    assert fast is not None and fast is not plain
    rng = np.random.default_rng(5)
    for tau in rng.uniform(0, 40, 200):
        assert plain.w3(model.K, tau) == fast.w3(model.K, tau)
    for y in rng.normal(size=(100, 3)) * 3:
        d = 1 if y[2] >= 0 else -1
        args = (model.K, model.W, model.N, *map(float, y), d, 30.0)
        assert plain.first_zero(*args) == fast.first_zero(*args)


def test_the_environment_variable_selects_the_plain_kernel(monkeypatch):
    for off in ("0", "false", "No", "off"):
        monkeypatch.setenv(_jit.ENV, off)
        assert _jit.variant() == "python"
    monkeypatch.setenv(_jit.ENV, "1")
    assert _jit.variant() == "numba"


def test_without_numba_the_plain_kernel_runs_and_gives_the_same_solution():
    code = (
        "import sys\n"
        "sys.modules['numba'] = None  # as if numba were not installed\n"
        "from symbolic_friction import Parameters\n"
        "from symbolic_friction._simulation import simulate, _jit\n"
        "sol = simulate(Parameters.table_i('a'), (0, 5, 0), 30.0, t_eval=[0.0, 7.5, 30.0])\n"
        "print(_jit.variant(), sol.z.tobytes().hex(), sol.events)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=dict(os.environ))
    variant, z_hex, events = out.stdout.strip().split(" ", 2)
    assert variant == "python"
    sol = simulate(CASES["a"], (0, 5, 0), 30.0, t_eval=[0.0, 7.5, 30.0])
    assert z_hex == sol.z.tobytes().hex() and events == str(sol.events)
