"""Tests that close gaps found by mutation-testing the stiff split (ModalScan, the slow scan, the
UNDECIDED code and its Radau fallback, the refusal of explicit integrators).

Each test is cheap (plain-Python kernel on small cases); the closed forms it checks against are
written out independently of the package (mpmath at 40 digits)."""

from __future__ import annotations

import math
from fractions import Fraction as F

import mpmath
import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import SimulationError
from symbolic_friction._simulation import IvpEvents, Status, _kernel, _kernel_flow, simulate
from symbolic_friction._simulation.search import slip_model

# (s + 1000)(s² + s + 1): stiff (|r| = 1000 ≥ 8·max|α ± β| = 8), and a well-damped pair
# (α = -1/2, q = 1), where every term of the μⱼ recursion matters.
DAMPED = Parameters(k_v=1001, k_p=1001, k_i=1000)


def _mp(x) -> mpmath.mpf:
    x = F(x)
    return mpmath.mpf(x.numerator) / x.denominator


def _pair(params: Parameters):
    """(r, α, β²) of s³ + k_v s² + k_p s + k_i, from mpmath at 40 digits (the isolated root: farthest from the others)."""
    roots = mpmath.polyroots([1, _mp(params.k_v), _mp(params.k_p), _mp(params.k_i)], maxsteps=200, extraprec=200)
    iso = max(range(3), key=lambda j: min(abs(roots[j] - roots[k]) for k in range(3) if k != j))
    pair = [roots[j] for j in range(3) if j != iso]
    return mpmath.re(roots[iso]), mpmath.re(pair[0] + pair[1]) / 2, mpmath.re(((pair[0] - pair[1]) / 2) ** 2)


def _cd_derivatives(alpha, beta2, tau, j):
    """C⁽ʲ⁾(τ), D⁽ʲ⁾(τ) for C = (e^{λ₊τ} + e^{λ₋τ})/2, D = (e^{λ₊τ} - e^{λ₋τ})/(2β), λ± = α ± β."""
    beta = mpmath.sqrt(mpmath.mpc(beta2))
    lp, lm = alpha + beta, alpha - beta
    c = (lp**j * mpmath.exp(lp * tau) + lm**j * mpmath.exp(lm * tau)) / 2
    d = (lp**j * mpmath.exp(lp * tau) - lm**j * mpmath.exp(lm * tau)) / (2 * beta)
    return mpmath.re(c), mpmath.re(d)


@pytest.mark.parametrize("params", [DAMPED, Parameters(k_p=F(23, 2500), k_i=F(1000) * F(23, 2500) / F(10026, 10000), k_v=1000)])
def test_mu_is_the_sup_of_the_pair_derivatives_per_unit_energy(params):
    """μⱼ = sup |S⁽ʲ⁾(0)| over q S(0)² + S'(0)² = 1, from the pair's roots (not from the recursion)."""
    modal = slip_model(params).modal
    with mpmath.workdps(40):
        _, alpha, beta2 = _pair(params)
        q = alpha * alpha - beta2
        for j in range(5):
            cj, dj = _cd_derivatives(alpha, beta2, 0, j)
            # S = c₁C + c₂D with c₁ = S(0), c₂ = S'(0) - α S(0):  S⁽ʲ⁾(0) = a S(0) + b S'(0)
            a, b = cj - alpha * dj, dj
            exact = float(mpmath.sqrt(a * a / q + b * b))
            assert exact <= modal.mu[j] <= exact * (1 + 1e-9), (j, modal.mu[j], exact)


def test_the_slow_table_is_c_d_their_second_derivatives_and_the_fast_decay():
    model = slip_model(DAMPED)
    modal = model.modal
    assert modal.stiff
    W, N = model.W, model.N
    slow, noise = W[_kernel.W_SLOW :], N[_kernel.N_SLOW :]
    with mpmath.workdps(40):
        r, alpha, beta2 = _pair(DAMPED)
        grow = modal.dt**2 / 8
        rows = []
        for j in range(modal.cells + 1):
            tau = _mp(modal.dt) * j
            c0, d0 = _cd_derivatives(alpha, beta2, tau, 0)
            c2, d2 = _cd_derivatives(alpha, beta2, tau, 2)
            rows.append([float(c0), float(d0), float(c2), float(d2), float(mpmath.exp(r * tau))])
    rows = np.array(rows).T
    for k in range(4):
        assert np.allclose(slow[k], rows[k], rtol=1e-12, atol=1e-14), k
    assert np.all(slow[4] >= rows[4]) and np.allclose(slow[4], rows[4], rtol=1e-14, atol=0.0)
    top = np.maximum(np.abs(rows[:4, :-1]), np.abs(rows[:4, 1:]))
    assert np.allclose(noise[0], top[0] + grow * top[2], rtol=1e-12)
    assert np.allclose(noise[1], top[1] + grow * top[3], rtol=1e-12)


def test_the_slow_scan_never_clears_a_cell_the_fast_part_can_reach(monkeypatch):
    """A cell is cleared only if the pair's part exceeds, at both ends, the fast part's bound |c| e^{rτⱼ}.

    Called at a_w = 0 with the true |c(0)|: the cells where |c| e^{rτⱼ} is not below the pair's
    part at the cell's ends must be marched, whatever the scaling of y (the scan is homogeneous).
    """
    monkeypatch.setenv("SYMBOLIC_FRICTION_JIT", "0")
    model = slip_model(DAMPED)
    K, W, N = model.constants(False)
    marched = []
    original = _kernel._march

    def spy(K_, q_, d_, a0, *rest):
        marched.append(a0)
        return original(K_, q_, d_, a0, *rest)

    monkeypatch.setattr(_kernel_flow, "_march", spy)
    dt = K[_kernel.I_SDT]
    mf = np.array(K[_kernel.I_MF : _kernel.I_MF + 9]).reshape(3, 3)
    mc = np.array(K[_kernel.I_MC : _kernel.I_MC + 9]).reshape(3, 3)
    A = np.array([[0.0, 0.0, -float(DAMPED.k_i)], [1.0, 0.0, -float(DAMPED.k_p)], [0.0, 1.0, -float(DAMPED.k_v)]])
    basis = [mc[:, 0], mc[:, 1]]
    w = np.linalg.solve(np.array([[b[2], (A @ b)[2]] for b in basis]).T, np.array([1.0, 0.0]))
    y_slow = w[0] * basis[0] + w[1] * basis[1]  # S(0) = 1, S'(0) = 0: S ≈ 1 over cell 0, a small slack
    y_fast = mf[:, 2] / mf[2, 2]  # c = 1
    for scale in (1.0, 2.0**-40, 2.0**40):
        y = scale * (1e3 * y_fast + y_slow)
        c, c1, c2, ac, *_ = _kernel.modal(K, *map(float, y))
        q = _kernel.slip_q(K, *map(float, y))
        marched.clear()
        _kernel._scan_slow(K, W, N, q, 1, 0.0, *map(float, y), 50 * dt, ac)
        # the fast part's bound 1e3 e^{rτⱼ} exceeds |S| ≤ 2 at the start of cell j: it must be marched
        must = [j for j in range(50) if 1e3 * math.exp(-1000.0 * j * dt) > 2.0]
        assert must and all(any(abs(a - j * dt) <= 1e-12 for a in marched) for j in must), (scale, marched)


# -- the Radau fallback: its samples, its events and its stated tolerances -----------------------


@pytest.fixture
def undecided(monkeypatch):
    """The kernel's step budget at 1 (every march runs out), with uncached slip models; the exact solution first."""
    params = Parameters.table_i("a")
    z0 = (1.0, 2.0, -3.0)
    exact = simulate(params, z0, 10.0, t_eval=np.linspace(0.0, 10.0, 41))
    exact_events = simulate(params, z0, 10.0).events
    monkeypatch.setenv("SYMBOLIC_FRICTION_JIT", "0")
    monkeypatch.setattr(_kernel_flow, "MAX_STEPS", 1)
    slip_model.cache_clear()
    monkeypatch.setattr("symbolic_friction._simulation.search.slip_model", slip_model.__wrapped__)
    monkeypatch.setattr("symbolic_friction._simulation.event.slip_model", slip_model.__wrapped__)
    yield params, z0, exact, exact_events
    slip_model.cache_clear()


_ON_41: dict = {}


def fallback_on_41(undecided):
    """``simulate(params, z0, 10.0, t_eval=np.linspace(0.0, 10.0, 41))`` under :func:`undecided`: computed once for
    the tests that only read it (a Radau run of about half a second; the run is deterministic)."""
    params, z0, _, _ = undecided
    if "sol" not in _ON_41:
        _ON_41["sol"] = simulate(params, z0, 10.0, t_eval=np.linspace(0.0, 10.0, 41))
    return _ON_41["sol"]


def test_the_fallback_keeps_the_requested_samples_and_the_event_times(undecided):
    params, z0, exact, exact_events = undecided
    t = np.linspace(0.0, 10.0, 41)
    sol = fallback_on_41(undecided)
    assert sol.status == Status.FALLBACK
    assert np.array_equal(sol.t, t)  # the samples asked for, once each (t_end not repeated)
    assert np.abs(sol.z - exact.z).max() <= 1e-9 * 3.0
    assert len(sol.events) == len(exact_events)
    for got, want in zip(sol.events, exact_events):
        assert got[1:] == want[1:] and abs(got[0] - want[0]) <= 1e-8, (got, want)


def test_the_fallback_without_t_eval_merges_the_exact_events(undecided):
    params, z0, exact, exact_events = undecided
    sol = simulate(params, z0, 10.0)
    assert sol.status == Status.FALLBACK
    assert np.all(np.diff(sol.t) > 0) and sol.t[0] == 0.0 and sol.t[-1] == 10.0
    t_from = sol.options["fallback"]["from"]
    kept = [e for e in sol.events if e[0] <= t_from]
    assert kept
    for t_ev, before, after in kept:  # the kernel's own events are among the samples, in the mode after
        k = int(np.searchsorted(sol.t, t_ev))
        assert sol.t[k] == t_ev and sol.mode[k] == after, (t_ev, before, after, sol.mode[k])
    for got, want in zip(sol.events, exact_events):
        assert got[1:] == want[1:] and abs(got[0] - want[0]) <= 1e-8, (got, want)


def test_the_fallback_states_the_tolerances_it_ran_with(undecided, monkeypatch):
    params, z0, _, _ = undecided
    used = []
    original = IvpEvents.__init__

    def record(self, **options):
        used.append(options)
        original(self, **options)

    monkeypatch.setattr(IvpEvents, "__init__", record)
    sol = simulate(params, z0, 10.0, t_eval=np.linspace(0.0, 10.0, 41))
    fb = sol.options["fallback"]
    assert used and used[-1]["atol"] == fb["atol"] and used[-1]["rtol"] == fb["rtol"]
    # absolute tolerance scaled by the state's size at the switch, from the exact solution there
    monkeypatch.undo()
    z_from = simulate(params, z0, 10.0, t_eval=np.array([0.0, fb["from"]])).z[-1]
    assert float(np.abs(z_from).max()) > 1.0
    assert fb["atol"] == fb["rtol"] * max(1.0, float(np.abs(z_from).max()), float(params.f_c / params.k_i))


# -- explicit integrators on stiff gains ----------------------------------------------------------


def test_rk45_is_refused_on_stiff_gains_too(monkeypatch):
    import scipy.integrate

    def never(*args, **kwargs):  # an explicit run here would take ~10⁸ steps: fail at once instead
        raise AssertionError("solve_ivp called on stiff gains with an explicit integrator")

    monkeypatch.setattr(scipy.integrate, "solve_ivp", never)
    stiff = Parameters(k_v=F(10**8) + F(1, 5), k_p=F(2 * 10**7) + 1, k_i=F(10**8))
    with pytest.raises(SimulationError, match="RK45"):
        simulate(stiff, (0.0, 1.0, 0.0), 20.0, method=IvpEvents(integrator="RK45"))


def test_the_refusal_is_on_the_work_rho_times_t_end_not_on_rho():
    # (s + 2·10⁷)(s² + 0.2 s + 1): ρ = 2·10⁷ > 10⁷, but ρ·t_end = 2·10³ over t_end = 1e-4
    k = F(2 * 10**7)
    stiff = Parameters(k_v=k + F(1, 5), k_p=k * F(1, 5) + 1, k_i=k)
    sol = simulate(stiff, (0.0, 1.0, 0.0), 1e-4, method=IvpEvents(integrator="DOP853"))
    assert sol.complete


def test_the_fallback_returns_only_the_requested_samples_when_all_precede_the_switch(undecided):
    params, z0, _, _ = undecided
    t = np.array([0.0, 1.0, 2.0])  # the kernel decides up to 3.2283…, where the march runs out
    sol = simulate(params, z0, 10.0, t_eval=t)
    assert sol.status == Status.FALLBACK and sol.options["fallback"]["from"] > 2.0
    assert np.array_equal(sol.t, t)


# -- the bounds of the split, where they are tight ------------------------------------------------

# (s + 1000)(s² + 2s + 10): stiff, q = 10 > 1 and α = -1, so that neither q nor α drops out of √E
PAIR10 = Parameters(k_v=1002, k_p=2010, k_i=10000)


def _a_matrix(params):
    return mpmath.matrix([[0, 0, -_mp(params.k_i)], [1, 0, -_mp(params.k_p)], [0, 1, -_mp(params.k_v)]])


@pytest.mark.parametrize("j", range(5))
def test_the_modal_bound_holds_in_every_direction_of_the_pair_plane(j):
    """|v⁽ʲ⁾(0)| ≤ |c||r|ʲ + μⱼ√E (:func:`_kernel._modal_bound`) for y on the pair's plane with
    (S(0), S'(0)) = (cos θ, sin θ), θ on a grid: v⁽ʲ⁾(0) = e₃ᵀ Aʲ y exactly (rationals).  The bound is
    attained to a few tens of percent in some direction, so a smaller μⱼ or √E fails it."""
    params = PAIR10
    K = slip_model(params).K.tolist()
    mc = np.array(K[_kernel.I_MC : _kernel.I_MC + 9]).reshape(3, 3)
    A = [[F(0), F(0), -params.k_i], [F(1), F(0), -params.k_p], [F(0), F(1), -params.k_v]]
    Af = np.array([[float(x) for x in row] for row in A])
    basis = [mc[:, 0], mc[:, 1]]
    s01 = np.array([[b[2], (Af @ b)[2]] for b in basis]).T
    worst = 0.0
    for theta in np.linspace(0.0, math.pi, 360, endpoint=False):
        w = np.linalg.solve(s01, np.array([math.cos(theta), math.sin(theta)]))
        y = w[0] * basis[0] + w[1] * basis[1]
        y = y / np.abs(y).max()
        state = [F(float(c)) for c in y]
        for _ in range(j):
            state = [sum(A[i][m] * state[m] for m in range(3)) for i in range(3)]
        exact = abs(float(state[2]))
        bound = _kernel._modal_bound(K, *map(float, y), j, math.inf)
        assert exact <= bound, (theta, exact, bound)
        worst = max(worst, exact / bound)
    assert worst >= 0.7, worst


def test_the_coefficients_of_the_split_come_with_their_rounding():
    """modal(): ac ≥ |c|, |c₁ - ĉ₁| ≤ e₁, |c₂ - ĉ₂| ≤ e₂ for the exact products of K's rows with y,
    on the slow manifold, where c cancels to rounding (and |c| |r|⁴ is not negligible)."""
    K = slip_model(PAIR10).K.tolist()
    rows = [[F(x) for x in K[m + 6 : m + 9]] for m in (_kernel.I_MF, _kernel.I_MC, _kernel.I_MD)]
    mc = np.array(K[_kernel.I_MC : _kernel.I_MC + 9]).reshape(3, 3)
    rng = np.random.default_rng(5)
    short = 0
    for _ in range(200):
        y = mc @ rng.normal(size=3)
        c, c1, c2, ac, e1, e2, _ = _kernel.modal(K, *map(float, y))
        exact = [sum(r * F(float(v)) for r, v in zip(row, y)) for row in rows]
        assert ac >= abs(exact[0])
        assert abs(F(c1) - exact[1]) <= F(e1) and abs(F(c2) - exact[2]) <= F(e2)
        short += abs(c) < abs(exact[0])
    assert short > 0  # the computed c alone falls short of the exact one: the rounding term is needed


@pytest.mark.parametrize("scale", [1.0, 2.0**-30, 2.0**30])
def test_the_search_is_homogeneous_where_the_fast_part_ends_the_slip(scale):
    """v(0) = c + S(0) > 0 with the fast part c > 0 and S(0) < 0: v crosses zero within a few 1/|r|.

    The search is homogeneous in y (powers of two scale exactly): the zero is the same at every
    scale, and is mpmath's first zero of e₃ᵀ e^{Aτ} y."""
    model = slip_model(PAIR10)
    K, W, N = model.constants(False)
    mf = np.array(K[_kernel.I_MF : _kernel.I_MF + 9]).reshape(3, 3)
    mc = np.array(K[_kernel.I_MC : _kernel.I_MC + 9]).reshape(3, 3)
    y_fast = mf[:, 2] / mf[2, 2]  # v = 1
    y_slow = mc[:, 1] / mc[2, 1]  # v = 1
    y = 1.0 * y_fast - 0.01 * y_slow
    y = y / np.abs(y).max() * scale
    code, tau, *_ = _kernel.first_zero(K, W, N, *map(float, y), 1, 1.0)
    assert code == _kernel.FOUND
    with mpmath.workdps(40):
        Am = _a_matrix(PAIR10)
        ym = mpmath.matrix([mpmath.mpf(float(c)) for c in y])
        v = lambda t: (mpmath.expm(Am * t) * ym)[2]  # noqa: E731
        root = mpmath.findroot(v, (mpmath.mpf(0.001), mpmath.mpf(0.01)), solver="anderson")
    assert abs(tau - float(root)) <= 1e-12, (tau, float(root))


# -- the bounds each search step relies on, at the state it starts from --------------------------


def _fast_dominated_state(K):
    """A state of PAIR10 whose v is mostly the fast mode (c = 1, S(0) = -0.01): |v⁽ʲ⁾| ≈ |r|ʲ."""
    mf = np.array(K[_kernel.I_MF : _kernel.I_MF + 9]).reshape(3, 3)
    mc = np.array(K[_kernel.I_MC : _kernel.I_MC + 9]).reshape(3, 3)
    y = mf[:, 2] / mf[2, 2] - 0.01 * mc[:, 1] / mc[2, 1]
    return [float(c) for c in y / np.abs(y).max()]


def _v_derivative(params, y, j):
    """e₃ᵀ Aʲ y, exactly."""
    A = [[F(0), F(0), -params.k_i], [F(1), F(0), -params.k_p], [F(0), F(1), -params.k_v]]
    state = [F(c) for c in y]
    for _ in range(j):
        state = [sum(A[i][m] * state[m] for m in range(3)) for i in range(3)]
    return abs(float(state[2]))


@pytest.fixture
def bound_calls(monkeypatch):
    monkeypatch.setenv("SYMBOLIC_FRICTION_JIT", "0")
    calls = []
    original = _kernel._modal_bound

    def spy(K, s, p, v, j, fast):
        out = original(K, s, p, v, j, fast)
        calls.append(((s, p, v), out))
        return out

    monkeypatch.setattr(_kernel_flow, "_modal_bound", spy)
    return calls


def test_the_fast_scan_bounds_v4_by_the_split(bound_calls):
    """The scan's curvature allowance uses a bound on |v⁗| (m₄|y|_P or the split's): it must exceed |v⁗(0)|."""
    model = slip_model(PAIR10)
    K, W, N = model.constants(False)
    y = _fast_dominated_state(K)
    q = _kernel.slip_q(K, *y)
    fast0 = _kernel.modal(K, *y)[3]
    _kernel._scan_fast(K, W, N, q, 1, 0.0, *y, 1.0, fast0)
    (state, bound) = bound_calls[0]
    r_p = _kernel.p_norm(*y, K[_kernel.I_KVKI], K[_kernel.I_KP])
    assert min(K[_kernel.I_M4] * r_p, bound) >= _v_derivative(PAIR10, y, 4)


def test_the_march_bounds_v2_and_v3_by_the_split(bound_calls):
    """A march step bounds |u''| and |u'''| after a (P-norm or split): at its start those bounds exceed |v''(a)|, |v'''(a)|."""
    model = slip_model(PAIR10)
    K = model.K.tolist()
    y = _fast_dominated_state(K)
    q = _kernel.slip_q(K, *y)
    fast0 = _kernel.modal(K, *y)[3]
    _kernel._march(K, q, 1, 0.0, *y, 1.0, fast0)
    assert len(bound_calls) >= 2
    (sn, b1), (_, b2) = bound_calls[0], bound_calls[1]
    # normalised state of the step: both bounds serve it, the larger must cover |v'''|, the smaller |v''|
    assert max(b1, b2) >= _v_derivative(PAIR10, sn, 3)
    assert min(b1, b2) >= _v_derivative(PAIR10, sn, 2)


def test_a_slip_without_zero_costs_windows_of_the_pair(monkeypatch):
    """(s + 1000)(s + 1)(s + 2): v = e^{-τ} on the pair, no zero; over τ ≤ 60 the scan runs
    ~ 60·ρ_pair/16 slow windows after 40/|r|, not ~ 60·|r|/16 fast ones."""
    monkeypatch.setenv("SYMBOLIC_FRICTION_JIT", "0")
    params = Parameters(k_v=1003, k_p=3002, k_i=2000)
    model = slip_model(params)
    assert model.modal.stiff
    K, W, N = model.constants(False)
    mc = np.array(K[_kernel.I_MC : _kernel.I_MC + 9]).reshape(3, 3)
    A = np.array([[0.0, 0.0, -2000.0], [1.0, 0.0, -3002.0], [0.0, 1.0, -1003.0]])
    basis = [mc[:, 0], mc[:, 1]]
    w = np.linalg.solve(np.array([[b[2], (A @ b)[2]] for b in basis]).T, np.array([1.0, -1.0]))
    y = [float(c) for c in w[0] * basis[0] + w[1] * basis[1]]  # S(0) = 1, S'(0) = -1: S = e^{-τ}
    calls = []
    for name in ("_scan_fast", "_scan_slow"):
        original = getattr(_kernel_flow, name)

        def counted(*args, _original=original):
            calls.append(args[5])
            return _original(*args)

        monkeypatch.setattr(_kernel_flow, name, counted)
    code, tau, *_ = _kernel.first_zero(K, W, N, *y, 1, 60.0)
    assert code == _kernel.NONE and tau == 60.0
    assert len(calls) <= 20, len(calls)


def test_stiff_samples_on_a_uniform_grid_are_the_closed_form_ones():
    """On stiff gains every sample of a slip is the split's closed form (no stepping with the
    Cayley–Hamilton propagator, whose terms are |y| where v is |y|/k_v): a uniform grid and a
    jittered one that contains it give the same samples."""
    params = Parameters(k_p=F(23, 2500), k_i=F(10**4) * F(23, 2500) / F(10026, 10000), k_v=10**4)
    z0 = (3.0, -5.0, 7.0)
    t = np.linspace(0.0, 20.0, 401)
    uniform = simulate(params, z0, 20.0, t_eval=t)
    jitter = np.random.default_rng(0).uniform(0.1, 0.9, size=400) * (t[1] - t[0])
    mixed = simulate(params, z0, 20.0, t_eval=np.sort(np.concatenate([t, t[:-1] + jitter])))
    z = mixed.z[np.isin(mixed.t, t)]
    assert z.shape == uniform.z.shape
    assert np.all(np.abs(uniform.z - z) <= 1e-13 * np.abs(z)), np.max(np.abs(uniform.z - z) / np.abs(z))


@pytest.mark.parametrize(
    "gains, stiff, pair_radius",
    [
        ((1101, 101100, 100000), True, 100.0),  # (s + 1000)(s + 1)(s + 100): a real pair, radius 100, 8·100 ≤ 1000
        ((1301, 301300, 300000), False, 300.0),  # (s + 1000)(s + 1)(s + 300): 8·300 > 1000
        ((1001, 1001, 1000), True, 1.0),  # (s + 1000)(s² + s + 1): |α ± β| = 1
    ],
)
def test_the_stiff_criterion_and_the_slow_cells_follow_the_pair_radius(gains, stiff, pair_radius):
    """Stiff iff |r| ≥ 8·max|α ± β|; then Δ = 1/(8·max|α ± β|) and the fast part is dropped after 40/|r|."""
    k_v, k_p, k_i = gains
    modal = slip_model(Parameters(k_v=k_v, k_p=k_p, k_i=k_i)).modal
    assert modal.stiff is stiff
    if stiff:
        assert modal.dt == pytest.approx(1.0 / (8.0 * pair_radius), rel=1e-12)
        assert modal.t_fast == pytest.approx(40.0 / 1000.0, rel=1e-12)
    else:
        assert modal.dt == 0.0 and modal.t_fast == math.inf


@pytest.mark.parametrize(
    "gains, slowest",
    [((1101, 101100, 100000), 1.0), ((1001, 1001, 1000), 0.5), ((F(1001, 1000), F(1001, 1000), F(1, 1000)), F(1, 1000))],
)
def test_the_slowest_rate_is_min_re_lambda(gains, slowest):
    """(s + 1000)(s + 1)(s + 100) → 1 (the slow root of a real pair); (s + 1000)(s² + s + 1) → 1/2;
    (s + 1/1000)(s² + s + 1) → 1/1000 (the isolated root)."""
    from symbolic_friction._simulation.affine import MatrixExponential

    k_v, k_p, k_i = gains
    rate = MatrixExponential.from_params(Parameters(k_v=k_v, k_p=k_p, k_i=k_i)).slowest_rate
    assert rate == pytest.approx(float(slowest), rel=1e-12)


@pytest.mark.parametrize(
    "params",
    [
        Parameters(k_p=F(1, 1000), k_i=F(1), k_v=F(1001)),  # reference_cases "stiff_stall"
        Parameters(k_p=F(23, 2500), k_i=F(10**4) * F(23, 2500) / F(10026, 10000), k_v=10**4),
    ],
)
def test_the_slip_after_a_stick_is_cached_on_stiff_gains(params):
    """The first zero of w (the slip from y0 = e₁) is searched once per gain set, over the slow
    table's windows on stiff gains (the fast table's 16/|r| would leave it to every stick exit)."""
    from symbolic_friction._simulation.search import first_zero

    model = slip_model(params)
    assert model.modal.stiff
    tau, _ = first_zero(model, (1.0, 0.0, 0.0), 1, 1e3)
    assert tau is not None and model.K[_kernel.I_STICK_SLIP_T] == tau


def test_a_sample_at_the_switch_is_the_kernels(undecided):
    """A requested sample at exactly the time the kernel stopped is the kernel's (exact) one, once."""
    params, z0, _, _ = undecided
    t_from = fallback_on_41(undecided).options["fallback"]["from"]
    t = np.sort(np.concatenate([np.linspace(0.0, 10.0, 41), [t_from]]))
    sol = simulate(params, z0, 10.0, t_eval=t)
    assert np.array_equal(sol.t, t)
    k = int(np.searchsorted(t, t_from))
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(_kernel_flow, "MAX_STEPS", 2000)
        exact = simulate(params, z0, 10.0, t_eval=t)
    assert np.array_equal(sol.z[k], exact.z[k]) and sol.mode[k] == exact.mode[k], (sol.z[k], exact.z[k], sol.mode[k], exact.mode[k])


def test_an_undecided_trajectory_makes_up_no_samples_after_the_stop(undecided):
    """With static friction there is no fallback: the kernel's samples after the stop are NaN."""
    from symbolic_friction._simulation.event import EventDriven, run_one

    params, z0, _, _ = undecided
    stick = Parameters(k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_s="1.2")
    t = np.linspace(0.0, 10.0, 41)
    batch = run_one(stick, z0, 10.0, t, max_events=100, options=EventDriven().options)
    assert batch.status[0] == Status.UNDECIDED
    after = t > batch.t_stop[0]
    assert after.any() and np.all(np.isnan(batch.z[0, after]))
