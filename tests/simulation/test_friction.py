"""Perturbed friction laws (Corollary 1, Fig. 4) simulated by ``moreau``."""

import math
from fractions import Fraction

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import ParameterError, SimulationError
from symbolic_friction._simulation import Status, simulate
from symbolic_friction._simulation.friction import Coulomb, InflatedCoulomb, Step, Stribeck

CASE_A = Parameters.table_i("a")
K_P, K_I, K_V, F_C = CASE_A.as_floats()


def random_steps(n, *, seed=0, h=(1e-3, 0.05, 0.3)):
    rng = np.random.default_rng(seed)
    for i in range(n):
        sigma, phi, v = rng.normal(scale=[0.5, 1.5, 0.3])
        if i % 3 == 0:
            v = 0.0
        yield Step(0.0, h[i % len(h)], sigma, phi, v, K_P, K_I, K_V, F_C)


def in_graph(law, w, f, tol=1e-9):
    lo, hi = law.graph(np.array([w]), F_C)
    return lo[0] - tol <= f <= hi[0] + tol


LAWS = [
    Coulomb(),
    InflatedCoulomb("0.2"),
    InflatedCoulomb("0.2", selection=("0.1", "-0.2")),
    InflatedCoulomb(0),
    Stribeck(f_s=2, v_s="0.1"),
    Stribeck(f_s="0.7", v_s="0.3", viscous="0.5"),
]


@pytest.mark.parametrize("law", LAWS, ids=lambda law: law.describe())
def test_solve_step_returns_a_point_of_the_graph_solving_the_step(law):
    for step in random_steps(60):
        law.check_step(step.h, k_p=K_P, k_i=K_I, k_v=K_V, f_c=F_C)
        w, f = law.solve_step(step)
        assert abs(step.D * w + step.h * f - step.r) <= 1e-12 * max(1.0, abs(step.r))
        if isinstance(law, InflatedCoulomb) and isinstance(law.selection, tuple):
            d, e = (float(q) for q in law.selection)
            lo, hi = Coulomb().graph(np.array([w + d]), F_C)  # f ∈ f_c (SGN(w + d) + e)
            assert lo[0] + F_C * e - 1e-9 <= f <= hi[0] + F_C * e + 1e-9
        assert in_graph(law, w, f), (law.describe(), step, w, f)


def test_graphs_match_the_paper():
    v = np.array([-1.0, -0.2, -0.1, 0.0, 0.1, 0.2, 1.0])
    lo, hi = InflatedCoulomb("0.2").graph(v, 2.0)  # eq. (perturbed): SGN_ρ, closed at |v| = ρ
    assert np.allclose(lo, 2.0 * np.array([-1.2, -1.2, -1.2, -1.2, -1.2, -1.2, 0.8]))
    assert np.allclose(hi, 2.0 * np.array([-0.8, 1.2, 1.2, 1.2, 1.2, 1.2, 1.2]))
    lo, hi = Coulomb().graph(v, 2.0)
    assert np.array_equal(lo, [-2, -2, -2, -2, 2, 2, 2]) and np.array_equal(hi, [-2, -2, -2, 2, 2, 2, 2])
    law = Stribeck(f_s=3, v_s="0.5", viscous="0.1")
    lo, hi = law.graph(v, 1.0)
    want = (1.0 + 2.0 * np.exp(-((v / 0.5) ** 2))) * np.sign(v) + 0.1 * v
    assert np.allclose(lo[v != 0], want[v != 0]) and lo[3] == -3.0 and hi[3] == 3.0


def test_zero_perturbation_is_the_paper_law_exactly():
    z0, kw = (0.0, 5.0, 0.0), {"method": "moreau", "h": 1e-3}
    ref = simulate(CASE_A, z0, 20.0, **kw)
    for law in (Coulomb(), InflatedCoulomb(0), InflatedCoulomb("0.3", selection=(0, 0))):
        sol = simulate(CASE_A, z0, 20.0, friction=law, **kw)
        assert np.array_equal(sol.z, ref.z) and sol.events == ref.events, law.describe()


def test_worst_case_selection_is_the_farthest_feasible_next_state():
    rho = 0.15
    law = InflatedCoulomb(rho)
    for step in random_steps(40, seed=5):
        w, _ = law.solve_step(step)

        def dist2(w_):
            # on the whole grid at once (next_x is plain arithmetic), not 20,001 Python calls a step; numpy squares
            # by x·x, where a float64 scalar's ** 2 calls pow: up to an ulp apart, far inside the 1e-12 below
            s_, p_, _ = step.next_x(w_)
            return s_**2 + np.maximum(np.abs(p_) - F_C, 0.0) ** 2 + w_**2

        # brute force: every w on a fine grid whose λ = (r - D w)/(h f_c) lies in SGN_ρ(w)
        a = step.h * F_C
        grid = np.linspace((step.r - a * (1 + rho)) / step.D, (step.r + a * (1 + rho)) / step.D, 20001)
        lam = (step.r - step.D * grid) / a
        lo, hi = law.graph(grid, 1.0)
        feasible = grid[(lam >= lo - 1e-12) & (lam <= hi + 1e-12)]
        assert feasible.size > 0
        assert dist2(w) >= dist2(feasible).max() - 1e-12


def test_worst_case_creeps_out_of_the_attractor_and_stays_bounded():
    # From a point of 𝒜 (an equilibrium without perturbation), the worst case pushes the mass
    # along at |v| = ρ: an ultimate bound that grows with ρ and shrinks to 0 with it (ISS).
    assert simulate(CASE_A, (0.0, 0.0, 0.0), 30.0, method="moreau", h=1e-3).status == Status.EQUILIBRIUM
    bounds = []
    for rho in ("0.0001", "0.001", "0.01", "0.1"):
        sol = simulate(CASE_A, (0.0, 0.0, 0.0), 30.0, method="moreau", h=1e-3, friction=InflatedCoulomb(rho))
        assert np.max(np.abs(sol.z[:, 2])) >= float(rho) * 0.99
        bounds.append(float(sol.distance.max()))
    assert bounds == sorted(bounds)
    assert bounds[0] < 0.02 and bounds[-1] < 2.0


def test_constant_selection_offsets_stick_velocity():
    # f_c (SGN(v + d) + e): a stick of the offset law is a drift at v = -d, held while the
    # friction needed, phi - k_v v, stays within f_c (here phi grows to 0.25 by t = 1).
    law = InflatedCoulomb("0.1", selection=("0.05", 0))
    sol = simulate(CASE_A, (0.0, 0.0, -0.05), 1.0, method="moreau", h=1e-3, friction=law)
    assert np.all(sol.z[:, 2] == -0.05)
    assert np.allclose(sol.z[:, 1], -0.05 * sol.t, rtol=0, atol=1e-12)
    coulomb = simulate(CASE_A, (0.0, 0.0, -0.05), 1.0, method="moreau", h=1e-3)
    assert coulomb.z[-1, 2] == 0.0  # without the offset the mass sticks at v = 0


def test_callable_selection_is_checked_against_rho():
    law = InflatedCoulomb("0.1", selection=lambda t, x: (0.0, -0.1 * math.cos(t)))
    sol = simulate(CASE_A, (0.0, 1.0, 0.0), 5.0, method="moreau", h=1e-3, friction=law)
    assert sol.t[-1] == 5.0
    bad = InflatedCoulomb("0.1", selection=lambda t, x: (0.0, 0.5))
    with pytest.raises(SimulationError, match=r"selection returned \(d, e\) = \(0\.0, 0\.5\) at t = 0; both must be within rho = 0\.1"):
        simulate(CASE_A, (0.0, 1.0, 0.0), 1.0, method="moreau", friction=bad)
    junk = InflatedCoulomb("0.1", selection=lambda t, x: "no")
    with pytest.raises(SimulationError, match=r"selection must return a pair \(d, e\) of numbers; got 'no'"):
        simulate(CASE_A, (0.0, 1.0, 0.0), 1.0, method="moreau", friction=junk)


def test_stribeck_hunting_limit_cycle():
    # f_s = 2 f_c: persistent stick–slip with a regular period and |x|_𝒜 bounded away from 0.
    hunting = simulate(CASE_A, (0.0, 1.0, 0.0), 200.0, method="moreau", h=1e-3, friction=Stribeck(2, "0.1"))
    late = [te for te, before, after in hunting.events if te > 100 and before == 0]
    assert len(late) >= 8
    gaps = np.diff(late)
    assert np.ptp(gaps) < 0.05 * np.mean(gaps)  # periodic
    for a in range(100, 200, 25):
        window = (hunting.t >= a) & (hunting.t < a + 25)
        assert hunting.distance[window].max() > 1.0
    # the same gains with f_s = f_c (Coulomb) converge: stick phases grow, no late hunting
    coulomb = simulate(CASE_A, (0.0, 1.0, 0.0), 200.0, method="moreau", h=1e-3, friction=Stribeck(1, "0.1"))
    assert sum(te > 100 for te, _, _ in coulomb.events) <= 2
    assert coulomb.distance[coulomb.t > 150].max() < 0.05


def test_stribeck_required_rho_is_exact_and_tight():
    law = Stribeck(f_s="1.3", v_s="0.1")
    rho = law.required_rho(1)
    assert rho == Fraction(3, 10)
    v = np.concatenate([np.linspace(-2, 2, 40001), [0.0, 0.3, -0.3]])
    lo, hi = law.graph(v, 1.0)
    band_lo, band_hi = InflatedCoulomb(rho).graph(v, 1.0)
    assert np.all(lo >= band_lo - 1e-15) and np.all(hi <= band_hi + 1e-15)
    tighter_lo, tighter_hi = InflatedCoulomb(rho - Fraction(1, 1000)).graph(np.array([0.0]), 1.0)
    assert hi[v == 0].max() > tighter_hi[0]


def test_stribeck_step_size_limit():
    law = Stribeck(f_s=5, v_s="0.01")
    h_max = law.max_step(k_v=K_V, f_c=F_C)
    assert 0 < h_max < 0.01
    law.check_step(0.5 * h_max, k_p=K_P, k_i=K_I, k_v=K_V, f_c=F_C)
    with pytest.raises(SimulationError, match=r"h = 0\.01 is too large for the Stribeck law \(f_s = 5, v_s = 0\.01\): the implicit step is unique only for h < 0\.00296"):
        simulate(CASE_A, (0.0, 1.0, 0.0), 1.0, method="moreau", h=0.01, friction=law)
    # slope bound |f_s - f_c| sqrt(2/e)/v_s = 4.29 < k_v = 6.4: every h is fine
    assert Stribeck(f_s="1.5", v_s="0.1").max_step(k_v=K_V, f_c=F_C) == math.inf


@pytest.mark.parametrize(
    "build, match",
    [
        (lambda: InflatedCoulomb(-1), r"rho must be ≥ 0; got rho = -1"),
        (lambda: InflatedCoulomb("0.1", selection="best"), r"selection must be 'worst-case', a pair \(d, e\) or a callable .*; got 'best'"),
        (lambda: InflatedCoulomb("0.1", selection=(0, 0, 0)), r"a constant selection is a pair \(d, e\); got 3 values"),
        (lambda: InflatedCoulomb("0.1", selection=("0.2", 0)), r"selection d must satisfy \|d\| ≤ rho = 1/10; got d = 1/5"),
        (lambda: InflatedCoulomb("0.1", selection=(0, "-0.3")), r"selection e must satisfy \|e\| ≤ rho = 1/10; got e = -3/10"),
        (lambda: InflatedCoulomb("0.1", selection=3), r"selection must be .*; got int"),
        (lambda: Stribeck(f_s=0, v_s=1), r"f_s must be > 0; got f_s = 0"),
        (lambda: Stribeck(f_s=1, v_s="-0.1"), r"v_s must be > 0; got v_s = -1/10"),
        (lambda: Stribeck(f_s=1, v_s=1, viscous=-1), r"viscous must be ≥ 0; got viscous = -1"),
        (lambda: Stribeck(f_s=2, v_s=1, viscous=1).required_rho(1), r"viscous = 1 > 0 leaves every band"),
        (lambda: Stribeck(f_s="0.5", v_s=1).required_rho(1), r"required_rho covers f_s ≥ f_c; got f_s = 1/2 < f_c = 1"),
        (lambda: Stribeck(f_s=2, v_s=1).required_rho(0), r"f_c must be > 0; got f_c = 0"),
    ],
)
def test_bad_laws(build, match):
    with pytest.raises(ParameterError, match=match):
        build()


def test_time_varying_selection_is_never_taken_for_an_equilibrium():
    # (d, e) = (0, 0) until t = 1, then a force error e = 0.3: at e_i = 0.2, phi = -0.8 leaves
    # the stick set f_c [-1 + e, 1 + e] = [-0.7, 1.3], so the point of 𝒜 is left at t = 1.
    law = InflatedCoulomb("0.3", selection=lambda t, x: (0.0, 0.0 if t < 1 else 0.3))
    assert not law.time_invariant and InflatedCoulomb("0.3").time_invariant
    sol = simulate(CASE_A, (0.2, 0.0, 0.0), 3.0, method="moreau", h=1e-3, friction=law)
    assert sol.status == Status.T_END
    assert np.all(sol.z[sol.t < 1.0] == [0.2, 0.0, 0.0])
    assert sol.events and abs(sol.events[0][0] - 1.0) <= 1e-3 and sol.events[0][1:] == (0, -1)
    assert sol.z[-1, 1] < 0.0
