"""The adversary of Proposition 1 (eq. stabState): the worst overshoot found, as a function of scale.

The ratio ``sup_t |x(t)|_𝒜/|x(0)|_𝒜`` is not scale-invariant: scaling
``x`` by ``λ`` is the same as scaling ``f_c`` by ``1/λ``.  Far from 𝒜
(``|x(0)|_𝒜 ≫ f_c``) friction is negligible and the ratio tends to the
overshoot of the linear flow ``x' = Ax``; close to 𝒜 (``≪ f_c``, i.e.
``|e_i| - f_c/k_i ≪ f_c/k_i`` in ``z``) friction dominates.  The
half-width of 𝒜 is ``f_c`` in ``φ`` (``f_c/k_i`` in ``e_i``), so the scale
is reported as ``|x(0)|_𝒜/f_c``.

For each scale ``r`` on a logarithmic ladder from ``10⁻³`` to ``10³``,
differential evolution (scipy, imported lazily) with restarts maximises the
ratio over the *direction* of ``x(0)`` and its anchor on 𝒜:
``x(0) = (r f_c u₁, w f_c + r f_c u₂, r f_c u₃)``, ``u`` on the unit sphere,
``w ∈ [-1, 1]``.  Every evaluation is a batch of exact simulations that the
checker checks too.  The best state of each scale is then re-simulated and
its peak time refined on the closed-form segment that contains it
(:func:`~symbolic_friction._simulation.affine.slip_flow`,
:func:`~symbolic_friction._simulation.affine.stick_flow`, bounded scalar
maximisation between the neighbouring samples/events), not on the sample
grid.  Everything here is *found*, never proved: the certified κ is the
proof, the search measures how tight it is.

How ``|x(t)|_𝒜 → 0`` (Proposition 1, item 1): exponential or not?

The paper (Section III) explains why convergence is *not* exponential when
solutions keep sticking: during a stick phase starting with ``σ = σ̄``,
``φ`` ramps at rate ``σ̄`` across ``[-f_c, f_c]``, so the phase lasts about
``2f_c/|σ̄|`` while ``|x|_𝒜 = |σ̄|`` stays constant.  Near 𝒜 each slip
maps ``σ̄`` to a fixed multiple of itself (the slip dynamics are linear
around ``x*_k``), so ``|σ̄|`` shrinks geometrically per stick–slip cycle
while the cycle durations grow geometrically: the envelope decays like a
power of ``t``, not like ``e^{-λt}``.  When solutions stop sticking (three
real roots, case (b)), the last slip converges to ``x*_k = (0, ±f_c, 0)``
exponentially.

:func:`decay_fit` measures this: on long exact solutions it takes the
envelope ``D(t) = max_{s ≥ t} |x(s)|_𝒜`` over the tail and fits both
``log D = a - λt`` and ``log D = a - p log t``, reporting which fits better.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from .._model.parameters import Parameters

__all__ = ["OvershootSearch", "search_overshoot", "refine_peak", "linear_limit", "DEFAULT_SCALES", "DecayFit", "decay_fit"]

DEFAULT_SCALES: tuple[float, ...] = tuple(float(s) for s in np.logspace(-3, 3, 13))
"""Scales ``|x(0)|_𝒜/f_c`` searched (two per decade)."""

_BOUNDS = [(0.0, math.pi), (-math.pi, math.pi), (-1.0, 1.0)]


@dataclass(frozen=True)
class OvershootSearch:
    """The worst overshoot found, per scale.

    Attributes
    ----------
    scales : ndarray
        ``|x(0)|_𝒜/f_c`` of the best state at each searched scale.
    ratio : ndarray
        Best ``sup_t |x(t)|_𝒜/|x(0)|_𝒜`` found at that scale (peak refined).
    x0 : ndarray, shape (n, 3)
        The initial states.
    t_peak : ndarray
        Time of the refined peak.
    evaluations : int
        Trajectories the search simulated (all of them checked).
    """

    scales: np.ndarray
    ratio: np.ndarray
    x0: np.ndarray
    t_peak: np.ndarray
    evaluations: int
    x_peak: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]

    @property
    def best(self) -> int:
        return int(np.nanargmax(self.ratio))

    def tightness(self, kappa: float) -> float:
        """Best ratio found / κ (< 1 for a proved certificate)."""
        return float(self.ratio[self.best]) / kappa

    def describe(self, kappa: float) -> str:
        j = self.best
        x = self.x0[j]
        return (f"worst overshoot found {self.ratio[j]:.6f} at |x(0)|_A = {self.scales[j]:.3g} f_c, "
                f"x(0) = ({x[0]:.6g}, {x[1]:.6g}, {x[2]:.6g}), t = {self.t_peak[j]:.6g}; "
                f"tightness {self.tightness(kappa):.4f} of kappa = {kappa:.6g}")


def _states(params: Parameters, U: np.ndarray, r: float) -> np.ndarray:
    a, b, w = U[:, 0], U[:, 1], U[:, 2]
    f_c = float(params.f_c)
    u = np.stack([np.sin(a) * np.cos(b), np.sin(a) * np.sin(b), np.cos(a)], axis=1)
    x = r * f_c * u
    x[:, 1] += w * f_c
    return x


def search_overshoot(params: Parameters, evaluate: Callable[[np.ndarray, str], np.ndarray], *, budget: int,
                     seed: int, scales: tuple[float, ...] = DEFAULT_SCALES, restarts: int = 2,
                     t_eval: np.ndarray | None = None, max_events: int = 10_000) -> OvershootSearch:
    """Maximise the overshoot at every scale (see the module docstring).

    Parameters
    ----------
    params : Parameters
    evaluate : callable
        ``evaluate(X0, label)`` simulates and checks the states ``X0`` (rows,
        in ``x``) and returns their observed overshoots (NaN if incomplete).
    budget : int
        Trajectories the search may use over all scales and restarts.
    seed : int
    scales : tuple of float
    restarts : int
        Independent differential-evolution runs per scale (different seeds).
    t_eval : ndarray, optional
        Sample times of the refinement run (default: the evaluations' own).
    """
    from scipy.optimize import differential_evolution

    popsize = 8
    pop = popsize * len(_BOUNDS)
    if budget < 2 * pop * restarts * len(scales):
        # too small for an optimiser at every scale: a seeded screen of each scale instead
        return _screen(params, evaluate, budget=budget, seed=seed, scales=scales, t_eval=t_eval,
                       max_events=max_events)
    per_run = budget // (len(scales) * restarts)
    maxiter = per_run // pop - 1
    best_x, best_ratio = [], []
    used = 0
    for j, r in enumerate(scales):
        top: tuple[float, Any] = (-math.inf, None)
        for k in range(restarts):
            def obj(U: np.ndarray, r: float = r) -> np.ndarray:
                nonlocal used
                ov = evaluate(_states(params, U.T, r), f"adversarial overshoot r={r:.3g}f_c")
                used += U.shape[1]
                return -np.where(np.isfinite(ov), ov, 0.0)

            res = differential_evolution(obj, _BOUNDS, vectorized=True, updating="deferred", popsize=popsize,
                                         maxiter=maxiter, seed=seed + 101 * j + k, polish=False, tol=0.0)
            if -res.fun > top[0]:
                top = (-float(res.fun), np.asarray(res.x))
        best_ratio.append(top[0])
        best_x.append(_states(params, top[1][None, :], r)[0])
    X = np.array(best_x)
    ratio, t_peak, x_peak, d0 = refine_peak(params, X, t_eval=t_eval, max_events=max_events)
    ratio = np.fmax(ratio, np.array(best_ratio))  # the refinement can only raise the sampled maximum
    return OvershootSearch(scales=d0 / float(params.f_c), ratio=ratio, x0=X, t_peak=t_peak, evaluations=used,
                           x_peak=x_peak)


def _screen(params: Parameters, evaluate: Callable[[np.ndarray, str], np.ndarray], *, budget: int, seed: int,
            scales: tuple[float, ...], t_eval: np.ndarray | None, max_events: int) -> OvershootSearch:
    """Random directions at each scale (``budget`` spread over the scales), best one refined."""
    rng = np.random.default_rng(seed)
    scales = scales[:: max(1, math.ceil(len(scales) / max(1, budget)))]
    each = max(1, budget // len(scales))
    best_x, best_ratio, used = [], [], 0
    for r in scales:
        if used + each > budget:
            break
        U = np.column_stack([rng.uniform(lo, hi, each) for lo, hi in _BOUNDS])
        X = _states(params, U, r)
        ov = evaluate(X, f"adversarial overshoot r={r:.3g}f_c")
        used += each
        j = int(np.argmax(np.where(np.isfinite(ov), ov, 0.0)))
        best_x.append(X[j])
        best_ratio.append(float(ov[j]) if np.isfinite(ov[j]) else 0.0)
    X = np.array(best_x).reshape(-1, 3)
    ratio, t_peak, x_peak, d0 = refine_peak(params, X, t_eval=t_eval, max_events=max_events)
    return OvershootSearch(scales=d0 / float(params.f_c), ratio=np.fmax(ratio, np.array(best_ratio)), x0=X,
                           t_peak=t_peak, evaluations=used, x_peak=x_peak)


def linear_limit(params: Parameters) -> tuple[float, float]:
    """``(sup_t ‖e^{At}‖₂, t)``: the overshoot of the friction-free flow, the limit of the ratio as ``|x(0)|_𝒜/f_c → ∞``."""
    from scipy.optimize import minimize_scalar

    from .._simulation.affine import MatrixExponential
    from ._outcome import default_horizon

    expm = MatrixExponential.from_params(params)
    t = np.linspace(0.0, default_horizon(params), 4001)
    norms = np.linalg.norm(expm(t), ord=2, axis=(-2, -1))
    j = int(np.argmax(norms))
    lo, hi = t[max(0, j - 1)], t[min(len(t) - 1, j + 1)]
    res = minimize_scalar(lambda s: -float(np.linalg.norm(expm(np.array(s)), ord=2)), bounds=(lo, hi),
                          method="bounded", options={"xatol": 1e-12})
    return max(float(norms[j]), -float(res.fun)), float(res.x)


def _flow(expm: Any, f_c: float, xa: np.ndarray, tau: np.ndarray, k: int) -> np.ndarray:
    """The closed-form solution of mode ``k`` from ``xa`` after ``tau`` (:mod:`.._simulation.affine`)."""
    from .._simulation.affine import slip_flow, stick_flow

    return slip_flow(expm, f_c, xa, tau, k) if k else stick_flow(xa, tau)


def refine_peak(params: Parameters, X0: np.ndarray, *, t_eval: np.ndarray | None = None, horizon: float | None = None,
                max_events: int = 10_000) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(ratio, t_peak, x_peak, |x(0)|_𝒜)``: the peak of ``|x(t)|_𝒜`` located on the closed-form segment.

    The trajectory is simulated exactly; between any two consecutive points
    (samples and events merged) the solution is one affine mode
    (Claim 1): each segment is scanned on its closed form (65 points) and the
    best interior point polished by a bounded Brent search on ``-|x(t)|²_𝒜``.
    Slip segments that cannot reach the largest sampled ``|x|²_𝒜`` are not
    scanned (:func:`_scan`), which leaves the result the same.
    """
    from scipy.optimize import minimize_scalar

    from .._model.attractor import squared_distance_x
    from .._model.coordinates import x_to_z
    from .._model.lyapunov import lyapunov_matrix
    from .._simulation.affine import MatrixExponential
    from .._simulation.batch import simulate_batch
    from ._along import along
    from ._outcome import default_horizon, sample_times

    if t_eval is None:
        T = horizon if horizon is not None else default_horizon(params)
        t_eval = sample_times(T, 2001)
    b = simulate_batch(params, x_to_z(params, X0), float(t_eval[-1]), t_eval=t_eval, max_events=max_events)
    a = along(b)
    expm = MatrixExponential.from_params(params)
    f_c = float(params.f_c)
    # λ_min(P) of eq. (lyapLikeP), used only where the float eigenvalue is accurate (P not too ill-conditioned)
    eig = np.linalg.eigvalsh(lyapunov_matrix(params))
    lam = float(eig[0]) if eig[0] > 1e-8 * eig[-1] else 0.0
    n = X0.shape[0]
    ratio, t_peak, x_peak = np.full(n, np.nan), np.full(n, np.nan), np.full((n, 3), np.nan)
    grid = np.linspace(0.0, 1.0, 65)
    for i in range(n):
        if not (a.complete[i] and a.d0[i] > 0):
            continue
        dd = np.where(a.point[i], a.d[i], -np.inf)
        p = int(np.argmax(dd))
        best = (float(dd[p]), float(a.ch.t[i, p]), a.xs[i, p])
        # every segment between consecutive points is one affine mode (Claim 1): scan it on the
        # closed form, then polish the best interior point with a bounded Brent search
        floor = float(dd[p]) ** 2 * (1.0 - 1e-9) if lam > 0.0 else -math.inf
        found = _scan(params, a, i, expm, grid, lam, floor)
        if found is None or not found[0] >= floor:  # nothing reached the samples' maximum: scan every segment
            found = _scan(params, a, i, expm, grid, lam, -math.inf)
        if found is not None:
            _, lo, k, h, j = found
            xa = a.xs[i, lo]
            bracket = (h * grid[max(j - 1, 0)], h * grid[min(j + 1, len(grid) - 1)])
            res = minimize_scalar(lambda tau: -float(squared_distance_x(params, _flow(expm, f_c, xa, np.array(tau), k))),
                                  bounds=bracket, method="bounded", options={"xatol": 1e-13 * max(1.0, h)})
            for tau in (float(res.x), h * grid[j]):
                x = _flow(expm, f_c, xa, np.array(tau), k)
                dv = math.sqrt(max(0.0, float(squared_distance_x(params, x))))
                if dv > best[0]:
                    best = (dv, float(a.ch.t[i, lo]) + tau, x)
        ratio[i] = best[0] / a.d0[i]
        t_peak[i], x_peak[i] = best[1], best[2]
    return ratio, t_peak, x_peak, a.d0


def _scan(params: Parameters, a: Any, i: int, expm: Any, grid: np.ndarray, lam: float,
          floor: float) -> tuple[float, int, int, float, int] | None:
    """``(|x|²_𝒜, segment, mode, length, grid index)`` of the largest scanned point of trajectory ``i``.

    Along a slip of mode ``k``, ``V_k = |x − x*_k|²_P`` does not increase
    (``dV_k/dt = −c v²``, Lemma 2's identity behind eq. dVdt) and ``x*_k`` lies
    in 𝒜, so from a point ``x_a`` on, ``|x|²_𝒜 ≤ |x − x*_k|² ≤ V_k(x_a)/λ_min(P)``.
    A slip segment whose bound, doubled (far beyond the closed form's rounding),
    is below ``floor`` holds only points below it and is not scanned.  When the
    maximum found is at least ``floor``, no segment left out could have held it
    or tied with it: the result is the full scan's (segments in order, the
    first maximum kept).
    """
    from .._model.attractor import squared_distance_x
    from .._model.lyapunov import V_k
    from .._simulation.affine import slip_flow, stick_flow

    f_c, seg = float(params.f_c), np.flatnonzero(a.dt_pos[i])
    found = None
    for k in (-1, 0, 1):
        los = seg[a.k_int[i, seg] == k]
        if k and los.size and floor > -math.inf:
            los = los[2.0 * V_k(params, a.xs[i, los], k) / lam >= floor]
        if los.size == 0:
            continue
        h = a.ch.t[i, los + 1] - a.ch.t[i, los]
        taus = h[:, None] * grid[None, :]
        if k:  # the mode's segments in one call: row m is the flow from xs[i, los[m]] (the same numbers)
            X = slip_flow(expm, f_c, a.xs[i, los][:, None, :], taus, k)
        else:
            X = np.stack([stick_flow(a.xs[i, lo], taus[m]) for m, lo in enumerate(los)])
        d2 = squared_distance_x(params, X)
        m, j = np.unravel_index(int(np.argmax(d2)), d2.shape)
        if found is None or d2[m, j] > found[0]:
            found = (float(d2[m, j]), int(los[m]), k, float(h[m]), int(j))
    return found


@dataclass(frozen=True)
class DecayFit:
    """Tail fits of ``|x(t)|_𝒜`` (medians over the trajectories).

    Attributes
    ----------
    trajectories : int
    horizon : float
    exponential_rate : float
        ``λ`` of ``D ≈ C e^{-λt}``.
    exponential_r2 : float
        Coefficient of determination of that fit (in ``log D``).
    power_exponent : float
        ``p`` of ``D ≈ C t^{-p}``.
    power_r2 : float
    stick_phases : float
        Median number of stick phases per trajectory on the horizon.
    verdict : str
        ``"power law"`` or ``"exponential"``: the better fit.
    """

    trajectories: int
    horizon: float
    exponential_rate: float
    exponential_r2: float
    power_exponent: float
    power_r2: float
    stick_phases: float
    verdict: str

    def describe(self) -> str:
        return (
            f"{self.verdict}: |x|_A tail ~ t^-{self.power_exponent:.3g} (R²={self.power_r2:.4f}) vs "
            f"e^(-{self.exponential_rate:.3g} t) (R²={self.exponential_r2:.4f}); "
            f"median {self.stick_phases:g} stick phases on [0, {self.horizon:g}]"
        )


def _fit(u: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    A = np.stack([np.ones_like(u), u], axis=1)
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    pred = A @ coef
    ss_res = float(np.sum((y - pred) ** 2))
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    return float(coef[1]), 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0


def decay_fit(params: Parameters, *, trajectories: int = 12, horizon: float = 2000.0, seed: int = 0) -> DecayFit:
    """Fit the tail of ``|x(t)|_𝒜`` on ``trajectories`` long exact solutions.

    Initial states are random on the sphere ``|x| = 3 f_c``; samples are
    geometric in ``t`` on ``[1, horizon]``; the tail is ``[horizon/100, horizon]``.
    """
    from .._model.attractor import distance_x
    from .._model.coordinates import x_to_z
    from .._simulation.batch import simulate_batch

    rng = np.random.default_rng(seed)
    g = rng.standard_normal((trajectories, 3))
    X0 = 3.0 * float(params.f_c) * g / np.linalg.norm(g, axis=1)[:, None]
    t = np.concatenate([[0.0], np.geomspace(1.0, horizon, 400)])
    batch = simulate_batch(params, x_to_z(params, X0), float(t[-1]), t_eval=t)
    d = distance_x(params, batch.x)
    env = np.maximum.accumulate(d[:, ::-1], axis=1)[:, ::-1]
    tail = t >= horizon / 100.0
    lam, r2e, p, r2p = [], [], [], []
    for row in env:
        ok = tail & (row > 1e-250)
        if np.count_nonzero(ok) < 10:
            continue
        y = np.log(row[ok])
        s1, q1 = _fit(t[ok], y)
        s2, q2 = _fit(np.log(t[ok]), y)
        lam.append(-s1)
        r2e.append(q1)
        p.append(-s2)
        r2p.append(q2)
    sticks = np.sum((batch.event_after == 0) & np.isfinite(batch.event_t), axis=1) + (batch.mode[:, 0] == 0)
    med = lambda a: float(np.median(a)) if len(a) else float("nan")  # noqa: E731
    verdict = "power law" if med(r2p) > med(r2e) else "exponential"
    return DecayFit(
        trajectories=len(lam),
        horizon=horizon,
        exponential_rate=med(lam),
        exponential_r2=med(r2e),
        power_exponent=med(p),
        power_r2=med(r2p),
        stick_phases=float(np.median(sticks)),
        verdict=verdict,
    )
