"""The exact event-driven method against the independent mpmath reference.

Each case is simulated by the package and by :class:`symbolic_friction._reference.Reference`
(50 digits) and compared at 301 sample times: states within 1e-13 relative
to ``max(1, |z0|)``, the same sequence of events, event times within 1e-12.
"""

from __future__ import annotations

import functools
import os
import subprocess
import sys
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._model.coordinates import z_to_x
from symbolic_friction._model.lyapunov import V
from symbolic_friction._simulation import Status, simulate
from symbolic_friction._simulation.modes import table_row

from ..tolerance import relative_error
from .against_reference import scale_of, simulate_and_reference

TABLE_A = Parameters.table_i("a")
TABLE_B = Parameters.table_i("b")
STIFF = Parameters(k_v="51.1", k_p="5.3525", k_i="12.8775")  # (s² + 0.1 s + 0.2525)(s + 51)
# A large-gain system whose solutions creep: each slip from row (iii) lasts the first zero
# of w, each stick -offset/σ, while σ shrinks ~30× per cycle; f_c makes the start exact.
CREEP = Parameters(k_v=17, k_p=336, k_i=1746, f_c=F(3828, 4096))

TOL = 1e-13  # states, relative to max(1, |z0|)
EVENT_TOL = 1e-12  # event times
N_SAMPLES = 301

# name -> (params, z0, t_end, minimum number of events)
CASES = {
    "table_a": (TABLE_A, (0.0, 5.0, 0.0), 30.0, 10),
    "table_a_generic": (TABLE_A, (-3.0, 3.0, -3.0), 30.0, 10),
    # Three real roots: a slip's v is Σ c_i e^{λ_i t}, with at most 2 real zeros; a slip that
    # starts from a stick (row iii, a double zero at t = 0) never ends, so after the first
    # stick there is no event (the paper: "after a stick phase ... v remains always nonzero").
    # The most a solution shows is reversal, stick, slip: 3 events.
    "table_b": (TABLE_B, (0.0, 5.0, 5.0), 60.0, 3),
    "triple_root": (Parameters(k_v=3, k_p=3, k_i=1), (0.0, 0.0, 5.0), 30.0, 3),
    "double_root": (Parameters(k_v=4, k_p=5, k_i=2), (0.0, 0.0, 5.0), 30.0, 3),
    "routh_margin_1.01": (Parameters(k_p=1, k_i=1, k_v="1.01"), (0.0, 2.0, 0.0), 30.0, 10),
    "stiff": (STIFF, (0.0, 5.0, 0.0), 60.0, 10),
    "f_c_1e-6": (Parameters(k_v="6.4", k_p=3, k_i=4, f_c="1e-6"), (0.0, 1.0, 0.0), 50.0, 10),
    "f_c_1e-6_sticks": (Parameters(k_v="6.4", k_p=3, k_i=4, f_c="1e-6"), (0.0, 1e-4, 0.0), 30.0, 10),
    "f_c_100": (Parameters(k_v="6.4", k_p=3, k_i=4, f_c=100), (0.0, 500.0, 0.0), 30.0, 10),
    "z0_1e6": (TABLE_A, (0.0, 1e6, 0.0), 60.0, 10),
    "z0_1e6_generic": (TABLE_A, (1e6, -1e6, 5e5), 60.0, 10),
    "creep": (CREEP, (-(2.0**-11), -(2.0**-12), 0.0), 4.0, 10),
}

# One start on each row of the appendix's table, for case (a) (σ = -4s, φ = -4e_i - 3s, f_c = 1);
# all exactly representable, so the package and the reference see the same row.
ROWS = {
    "i": (0.0, 0.0, 3.0),
    "ii": (-2.0, 1.0, 0.0),
    "iii": (0.5, -1.0, 0.0),
    "iv": (-0.25, 0.0, 0.0),
    "v": (-1.0, 1.0, 0.0),
    "vi": (-0.25, 0.5, 0.0),
    "vii": (1.0, -1.0, 0.0),
    "viii": (0.25, 0.0, 0.0),
    "ix": (-0.5, 1.0, 0.0),
    "x": (2.0, -1.0, 0.0),
    "xi": (0.0, 0.0, -3.0),
}
for _row, _z0 in ROWS.items():
    CASES[f"row_{_row}"] = (TABLE_A, _z0, 15.0, 0)


@functools.lru_cache(maxsize=None)
def run(name: str):
    params, z0, t_end, _ = CASES[name]
    return simulate_and_reference(params, z0, t_end, N_SAMPLES)


@pytest.mark.parametrize("name", list(CASES))
def test_states_match_the_reference(name):
    sol, _, z_ref, _ = run(name)
    assert np.array_equal(sol.t, np.linspace(0.0, CASES[name][2], N_SAMPLES))
    assert relative_error(sol.z, z_ref, scale=scale_of(CASES[name][1])) <= TOL


@pytest.mark.parametrize("name", list(CASES))
def test_events_match_the_reference(name):
    sol, ref, _, _ = run(name)
    events = ref.event_list()
    assert [e[1:] for e in sol.events] == [e[1:] for e in events]
    times = np.array([e[0] for e in sol.events])
    want = np.array([e[0] for e in events])
    assert np.all(np.abs(times - want) <= EVENT_TOL)


@pytest.mark.parametrize("name", list(CASES))
def test_modes_and_status_match_the_reference(name):
    sol, ref, _, mode_ref = run(name)
    assert sol.status == {"t_end": Status.T_END, "equilibrium": Status.EQUILIBRIUM}[ref.status]
    # a sample within rounding of an event time may fall on either side of it
    near = np.zeros(sol.t.size, dtype=bool)
    for t_event, _, _ in sol.events:
        near |= np.abs(sol.t - t_event) <= 1e-9
    assert np.array_equal(sol.mode[~near], mode_ref[~near])


@pytest.mark.parametrize("name", [n for n in CASES if not n.startswith("row_")])
def test_each_case_shows_its_events(name):
    sol, _, _, _ = run(name)
    minimum = CASES[name][3]
    assert len(sol.events) >= minimum
    if minimum == 3:  # three real roots: exactly reversal, stick, slip
        assert [e[2] for e in sol.events][1] == 0 and len(sol.events) == 3


def test_the_cases_have_the_root_configurations_they_claim():
    def roots(p):
        return np.roots([1, float(p.k_v), float(p.k_p), float(p.k_i)])

    assert np.allclose(np.sort(roots(CASES["triple_root"][0]).real), [-1, -1, -1], atol=1e-4)
    assert np.allclose(np.sort(roots(CASES["double_root"][0]).real), [-2, -1, -1], atol=1e-6)
    assert CASES["routh_margin_1.01"][0].routh_margin == F(101, 100)
    stiff = np.abs(roots(STIFF))
    assert stiff.max() / stiff.min() >= 100
    assert np.all(np.abs(roots(TABLE_B).imag) == 0)
    assert np.sum(np.abs(roots(TABLE_A).imag) > 0) == 2


@pytest.mark.parametrize("row", list(ROWS))
def test_the_row_cases_start_on_their_rows(row):
    x0 = z_to_x(TABLE_A, np.array(ROWS[row]))
    assert table_row(*x0.tolist(), 1.0) == row


@pytest.mark.parametrize("row", ["iv", "viii"])
def test_the_equilibrium_edge_stays_put(row):
    sol, _, _, _ = run(f"row_{row}")
    assert sol.status == Status.EQUILIBRIUM
    assert sol.events == ()
    assert np.all(sol.z == np.array(ROWS[row]))
    assert np.all(sol.mode == 0)


def test_the_comparison_can_fail():
    """A 1e-8 change of k_v, or of z0, is far outside the tolerance: the comparison has teeth (and at 1e-12 still fails)."""
    _, _, z_ref, _ = run("table_a")
    params, z0, t_end, _ = CASES["table_a"]
    t = np.linspace(0.0, t_end, N_SAMPLES)
    nudged = Parameters(k_v=params.k_v * (1 + F(1, 10**8)), k_p=params.k_p, k_i=params.k_i)
    assert relative_error(simulate(nudged, z0, t_end, t_eval=t).z, z_ref, scale=scale_of(z0)) > TOL
    moved = (z0[0], z0[1] + 1e-8, z0[2])
    assert relative_error(simulate(params, moved, t_end, t_eval=t).z, z_ref, scale=scale_of(z0)) > TOL
    moved = (z0[0], z0[1] + 1e-12, z0[2])
    assert relative_error(simulate(params, moved, t_end, t_eval=t).z, z_ref, scale=scale_of(z0)) > TOL


# ---------------------------------------------------------------------------
# Properties of the solutions (no reference needed)
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("params", [TABLE_A, TABLE_B, STIFF], ids=["a", "b", "stiff"])
def test_V_never_increases_and_stick_phases_are_flat(params):
    """Lemma 2 item 2 along the exact solution; in stick v = 0 and |φ| ≤ f_c."""
    rng = np.random.default_rng(4)
    for z0 in rng.uniform(-5, 5, size=(20, 3)):
        sol = simulate(params, z0, 30.0, t_eval=np.linspace(0, 30, 3001))
        v_lyap = sol.V
        assert np.all(np.diff(v_lyap) <= 1e-12 * max(1.0, v_lyap[0]))
        stick = sol.mode == 0
        assert np.all(sol.x[stick, 2] == 0.0)
        assert np.all(np.abs(sol.x[stick, 1]) <= float(params.f_c) * (1 + 1e-12))
        assert np.all(sol.mode * sol.x[:, 2] >= 0.0)
        # within one stick the position is frozen and the integral error ramps: Δe_i = s Δt
        event_times = np.array([e[0] for e in sol.events])
        same = stick[:-1] & stick[1:]
        same &= np.searchsorted(event_times, sol.t[:-1], "right") == np.searchsorted(event_times, sol.t[1:], "right")
        i = np.flatnonzero(same)
        assert np.all(sol.z[i, 1] == sol.z[i + 1, 1])
        ramp = sol.z[i + 1, 0] - sol.z[i, 0] - sol.z[i, 1] * (sol.t[i + 1] - sol.t[i])
        assert np.all(np.abs(ramp) <= 1e-12 * max(1.0, np.abs(sol.z).max()))


def test_without_t_eval_the_grid_contains_every_event_time():
    sol = simulate(TABLE_A, (0.0, 5.0, 0.0), 30.0, grid_points=101)
    assert sol.t[0] == 0.0 and sol.t[-1] == 30.0
    assert np.all(np.diff(sol.t) > 0)
    assert set(np.linspace(0, 30, 101)) <= set(sol.t)
    for t_event, _, after in sol.events:
        i = int(np.searchsorted(sol.t, t_event))
        assert sol.t[i] == t_event and sol.mode[i] == after


def test_the_first_sample_is_the_given_state():
    z0 = (0.1, 0.2, 0.3)  # not exactly representable after the change of coordinates
    sol = simulate(TABLE_A, z0, 1.0, t_eval=[0.0, 0.5, 1.0])
    assert tuple(sol.z[0]) == z0


def test_a_state_inside_the_attractor_is_an_equilibrium():
    # s = 0, v = 0, |e_i| < f_c/k_i: 𝒜 of eq. (Aph)
    sol = simulate(TABLE_A, (0.1, 0.0, 0.0), 10.0, t_eval=np.linspace(0, 10, 11))
    assert sol.status == Status.EQUILIBRIUM
    assert np.all(sol.z == np.array([0.1, 0.0, 0.0]))


def test_max_events_stops_at_the_last_event_and_drops_later_samples():
    full = simulate(TABLE_A, (0.0, 5.0, 0.0), 30.0, t_eval=np.linspace(0, 30, 301))
    capped = simulate(TABLE_A, (0.0, 5.0, 0.0), 30.0, t_eval=np.linspace(0, 30, 301), max_events=3)
    assert capped.status == Status.MAX_EVENTS
    assert capped.events == full.events[:3]
    t_stop = capped.events[-1][0]
    assert capped.t[-1] <= t_stop < capped.t[-1] + 0.1 + 1e-12
    assert np.array_equal(capped.z, full.z[: capped.t.size])


@pytest.mark.parametrize("ulps", [-4, -1, 1, 4])
@pytest.mark.parametrize("s", [-1.0, 1.0])  # σ = -4 s: s = -1 is row (iii), s = 1 row (v)
def test_a_start_within_ulps_of_the_boundary_does_not_spin(ulps, s):
    """φ(0) = f_c ± a few ulps: decided as on the boundary, no spurious event, continuous."""
    exact = ((-1.0 - 3.0 * s) / 4.0, s, 0.0)  # φ = -4 e_i - 3 s = 1 exactly
    e_i = exact[0]
    for _ in range(abs(ulps)):
        e_i = np.nextafter(e_i, np.inf if ulps > 0 else -np.inf)
    near = (e_i, s, 0.0)
    t = np.linspace(0, 15, 151)
    a = simulate(TABLE_A, exact, 15.0, t_eval=t)
    b = simulate(TABLE_A, near, 15.0, t_eval=t)
    assert [e[1:] for e in b.events] == [e[1:] for e in a.events]
    assert relative_error(b.z, a.z) <= 1e-13


def test_a_creeping_solution_keeps_exact_stick_durations():
    """Stick after a tiny slip lasts -offset/σ exactly: the durations stay constant."""
    sol, _, _, _ = run("creep")
    sticks = [b[0] - a[0] for a, b in zip(sol.events, sol.events[1:]) if a[2] == 0]
    assert len(sticks) >= 5
    assert max(sticks) - min(sticks) <= 1e-12


@pytest.mark.parametrize("jit", ["0", "1"])
def test_an_event_driven_simulation_imports_neither_scipy_integrate_nor_sympy_nor_cvxpy(jit):
    code = (
        "import sys\n"
        "from symbolic_friction import Parameters\n"
        "from symbolic_friction._simulation import simulate\n"
        "from symbolic_friction._simulation.batch import simulate_batch\n"
        "p = Parameters.table_i('a')\n"
        "simulate(p, (0, 5, 0), 30.0, t_eval=[0.0, 30.0])\n"
        "simulate_batch(p, [[0, 5, 0]], 30.0)\n"
        "heavy = ('scipy.integrate', 'scipy.optimize', 'sympy', 'cvxpy', 'matplotlib')\n"
        "bad = sorted(m for m in sys.modules if m.startswith(heavy))\n"
        "if 'numba' not in sys.modules:  # numba itself loads scipy.linalg for its BLAS bindings\n"
        "    bad += sorted(m for m in sys.modules if m.split('.')[0] == 'scipy')\n"
        "print(','.join(bad))\n"
    )
    env = dict(os.environ, SYMBOLIC_FRICTION_JIT=jit)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    assert out.stdout.strip() == ""


def test_repeated_runs_give_identical_results():
    a = simulate(TABLE_A, (1.0, -2.0, 0.5), 20.0)
    b = simulate(TABLE_A, (1.0, -2.0, 0.5), 20.0)
    assert a.events == b.events and np.array_equal(a.z, b.z)


def test_solution_extras_are_consistent():
    sol = simulate(TABLE_A, (0.0, 5.0, 0.0), 30.0, t_eval=np.linspace(0, 30, 31))
    assert sol.x.shape == (31, 3) and sol.V.shape == (31,) and sol.distance.shape == (31,)
    assert np.allclose(sol.x, z_to_x(TABLE_A, sol.z))
    assert np.allclose(sol.V, V(TABLE_A, sol.x))
    assert sol.V_hat((1, 1, 2, 10)).shape == (31,)
    assert sol.method == "event" and sol.options == {"max_events": 10_000, "grid_points": 1001}
