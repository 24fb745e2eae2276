"""Initial states for the cross-check, drawn in ``x = (σ, φ, v)`` (eq. CoC):
seeded random draws on spheres of several radii, a tensor grid, and
special directions (the coordinate axes, the eigenvectors of ``P`` of
eq. lyapLikeP, and the ends ``(0, ±f_c, 0)`` of the attractor 𝒜).

Radii are in units of ``f_c``: the dynamics are homogeneous far from 𝒜
(``|x| ≫ f_c``) and near it (``|x - x*_k| ≪ f_c``), so the interesting
radii straddle ``f_c``.

Adversarial initial states: optimisers that try to break the certified
inequalities (scipy's differential evolution, imported lazily, then scipy's Nelder–Mead
step for step with the starts evaluated together).

* **Overshoot** (Proposition 1, eq. stabState): see :mod:`._overshoot`
  (direction and scale of ``x(0)``, peaks refined on the closed form).
* **Pointwise bounds** (Lemma 2 item 1, eqs. VandR and hatVandHatR): the
  ratios ``V/|x|²_𝒜`` (everywhere, and on ``R``) and ``V̂/|x|²_𝒜`` (on
  ``R̂``) are minimised and maximised over states; the extremal states start
  trajectories, so the checks see them at ``t = 0``.
* **Growth of V̂ in R̂** (eq. hatVdot): the rate ``V̂'/V̂`` along the flow
  of eq. (xDot) is maximised over ``R̂``; trajectories from the best states,
  sampled densely at short times, expose any increase of ``V̂``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .._model.parameters import Parameters
from ._claims import Claims

__all__ = ["InitialStates", "default_initial_states", "DEFAULT_RADII", "sphere_states", "grid_states", "special_states", "directions_to_x", "pointwise_extremes", "rate_maximisers", "sampled_rate_maximisers", "hat_V_rate", "LOG_RADIUS"]

DEFAULT_RADII: tuple[float, ...] = (0.1, 0.3, 1.0, 3.0, 10.0, 30.0)
"""Sphere radii in units of ``f_c``."""


@dataclass(frozen=True, eq=False)
class InitialStates:
    """Initial states in ``x`` with a label per state."""

    x: np.ndarray
    source: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "x", np.asarray(self.x, dtype=float).reshape(-1, 3))
        object.__setattr__(self, "source", np.asarray(self.source, dtype=object).reshape(-1))

    def __len__(self) -> int:
        return int(self.x.shape[0])

    @staticmethod
    def concat(parts: "list[InitialStates]") -> "InitialStates":
        if not parts:
            return InitialStates(np.zeros((0, 3)), np.zeros(0, dtype=object))
        return InitialStates(np.concatenate([p.x for p in parts]), np.concatenate([p.source for p in parts]))


def directions_to_x(u: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Spherical angles ``u = (a, b)`` (rows) and radii to points ``r·(cos a, sin a cos b, sin a sin b)``."""
    a, b = u[..., 0], u[..., 1]
    return np.stack([np.cos(a), np.sin(a) * np.cos(b), np.sin(a) * np.sin(b)], axis=-1) * np.asarray(radius)[..., None]


def sphere_states(params: Parameters, n: int, rng: np.random.Generator, *, radii=DEFAULT_RADII) -> InitialStates:
    """``n`` states uniform on the spheres ``|x| = r f_c`` (equal shares per radius)."""
    f_c = float(params.f_c)
    if n <= 0:
        return InitialStates.concat([])
    g = rng.standard_normal((n, 3))
    g /= np.linalg.norm(g, axis=1)[:, None]
    which = np.arange(n) % len(radii)
    r = np.asarray(radii, dtype=float)[which] * f_c
    labels = np.array([f"sphere r={radii[i]:g}f_c" for i in which], dtype=object)
    return InitialStates(g * r[:, None], labels)


def grid_states(params: Parameters, n: int, *, half_width: float = 3.0) -> InitialStates:
    """About ``n`` points of a tensor grid on ``[-w, w]³·f_c`` (odd size: contains the axes)."""
    if n <= 0:
        return InitialStates.concat([])
    g = max(3, int(round(n ** (1 / 3))))
    if g % 2 == 0:
        g -= 1
    axis = np.linspace(-half_width, half_width, g) * float(params.f_c)
    pts = np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), axis=-1).reshape(-1, 3)
    return InitialStates(pts, np.full(len(pts), f"grid {g}^3", dtype=object))


def special_states(params: Parameters, *, radii=DEFAULT_RADII) -> InitialStates:
    """Axes, eigenvectors of ``P`` and the ends of 𝒜, at every radius (and just outside 𝒜's ends)."""
    from .._model.lyapunov import lyapunov_matrix

    f_c = float(params.f_c)
    _, vecs = np.linalg.eigh(lyapunov_matrix(params))
    dirs = np.concatenate([np.eye(3), vecs.T])
    dirs = np.concatenate([dirs, -dirs])
    pts = [r * f_c * dirs for r in radii]
    ends = []
    for sgn in (1.0, -1.0):
        for eps in (1e-3, 1e-1, 1.0):
            # just outside an end of 𝒜: stick exits (σ ≠ 0) and slips starting on its boundary
            ends.append([0.0, sgn * (1 + eps) * f_c, 0.0])
            ends.append([eps * f_c, sgn * f_c, 0.0])
            ends.append([-eps * f_c, sgn * f_c, 0.0])
            ends.append([0.0, sgn * f_c, eps * f_c])
            ends.append([0.0, sgn * f_c, -eps * f_c])
    x = np.concatenate(pts + [np.array(ends)])
    return InitialStates(x, np.full(len(x), "special", dtype=object))


def default_initial_states(params: Parameters) -> np.ndarray:
    """Corollary 1's initial states: the two ends and the centre of 𝒜, and three states outside 𝒜 with ``|z(0)|_𝒜`` between 0.5 and 1."""
    from .._model.attractor import attractor_bound_z

    e = float(attractor_bound_z(params))
    return np.array([[e, 0.0, 0.0], [0.0, 0.0, 0.0], [-e, 0.0, 0.0], [e, 0.0, 0.5], [0.0, 0.5, 0.0], [-e, -0.5, 0.5]])


LOG_RADIUS = (-2.0, 2.0)
"""Range of ``log₁₀(|x(0)|/f_c)`` searched."""


_BOUNDS = [(0.0, math.pi), (-math.pi, math.pi), LOG_RADIUS]


def _to_x(params: Parameters, U: np.ndarray) -> np.ndarray:
    """Rows ``(a, b, log₁₀ r)`` to states ``x``."""
    U = np.atleast_2d(U)
    # Nelder–Mead is unbounded: keep the radius in the searched range
    return directions_to_x(U[:, :2], 10.0 ** np.clip(U[:, 2], *LOG_RADIUS) * float(params.f_c))


def _V_d2(params: Parameters, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    from .._model.attractor import squared_distance_x
    from .._model.lyapunov import V, in_R

    return V(params, x), squared_distance_x(params, x), in_R(params, x)


def hat_V_rate(params: Parameters, claim: Claims, x: np.ndarray) -> np.ndarray:
    """``V̂°(x)/V̂(x)`` along eq. (xDot) at states ``x`` in ``R̂`` (NaN elsewhere).

    ``V̂°`` is the package's :func:`~symbolic_friction._model.lyapunov.V_hat_rate`
    (eq. hatVdot, the Clarke ``max`` at ``σ = 0``), ``R̂`` its
    :func:`~symbolic_friction._model.lyapunov.in_R` complement.
    """
    from .._model.lyapunov import V_hat, V_hat_rate, in_R

    rate = V_hat_rate(params, x, claim.k)
    Vh = V_hat(params, x, claim.k)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(~in_R(params, x) & (Vh > 0), rate / Vh, np.nan)


def _de(func: Callable[[np.ndarray], np.ndarray], *, seed: int, maxiter: int, popsize: int) -> tuple[np.ndarray, float]:
    from scipy.optimize import differential_evolution

    res = differential_evolution(
        lambda U: func(U.T),
        _BOUNDS,
        vectorized=True,
        updating="deferred",
        popsize=popsize,
        maxiter=maxiter,
        seed=seed,
        polish=False,
        tol=0.0,
    )
    return np.asarray(res.x), float(res.fun)


def sampled_rate_maximisers(params: Parameters, claim: Claims, *, seed: int, count: int = 8, first: int = 2000,
                            rounds: int = 12, per_point: int = 64) -> np.ndarray:
    """``count`` states of large ``V̂'/V̂`` on ``R̂``, found with numpy alone (``check``'s self-test).

    ``first`` uniform samples of the searched box (angles and log-radius),
    then ``rounds`` of ``per_point`` Gaussian samples around each of the
    ``count`` best so far, the width halved each round; every evaluation is
    vectorised.  The cross-check itself uses :func:`rate_maximisers`
    (scipy's differential evolution and Nelder–Mead); ``check`` avoids importing scipy.optimize and
    scipy.linalg (about 0.45 s) for what this finds as well: the wrong ``k₄``
    of the self-test was caught from these starts for each of 24 seeds.
    """
    rng = np.random.default_rng(seed)
    lo = np.array([b[0] for b in _BOUNDS])
    hi = np.array([b[1] for b in _BOUNDS])

    def rate(U: np.ndarray) -> np.ndarray:
        r = hat_V_rate(params, claim, _to_x(params, U))
        return np.where(np.isnan(r), -np.inf, r)

    U = lo + (hi - lo) * rng.random((first, 3))
    f = rate(U)
    width = (hi - lo) / 4
    for _ in range(rounds):
        best = U[np.argsort(-f, kind="stable")[:count]]
        around = np.repeat(best, per_point, axis=0) + rng.normal(size=(count * per_point, 3)) * width
        U = np.vstack([best, np.clip(around, lo, hi)])
        f = rate(U)
        width = width / 2
    return _to_x(params, U[np.argsort(-f, kind="stable")[:count]])


def pointwise_extremes(params: Parameters, claims: list[Claims], *, seed: int, maxiter: int = 60) -> InitialStates:
    """States that extremise the pointwise ratios behind ``c₁, c₂, ĉ₁, ĉ₂`` and ``V̂'``.

    No simulation is needed to find them; they are returned as initial states.
    """
    out: list[np.ndarray] = []
    labels: list[str] = []
    big = 1e9  # penalty outside the region (finite: DE takes the std of the energies)

    def add(U: np.ndarray, label: str) -> None:
        out.append(_to_x(params, U)[0])
        labels.append(label)

    def ratio_V(U: np.ndarray, sign: float, region: str) -> np.ndarray:
        x = _to_x(params, U)
        V, d2, inR = _V_d2(params, x)
        ok = d2 > 0 if region == "all" else (d2 > 0) & inR
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(ok, sign * V / d2, big)

    add(_de(lambda U: ratio_V(U, 1.0, "all"), seed=seed, maxiter=maxiter, popsize=20)[0], "adversarial min V/|x|²")
    add(_de(lambda U: ratio_V(U, -1.0, "R"), seed=seed + 1, maxiter=maxiter, popsize=20)[0],
        "adversarial max V/|x|² on R")
    for j, cl in enumerate(claims):
        if not cl.is_paper:  # V̂ is the paper's: another template claims none of its bounds
            continue

        def ratio_H(U: np.ndarray, sign: float, cl: Claims = cl) -> np.ndarray:
            from .._model.attractor import squared_distance_x
            from .._model.lyapunov import V_hat, in_R

            x = _to_x(params, U)
            d2 = squared_distance_x(params, x)
            ok = (d2 > 0) & ~in_R(params, x)
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.where(ok, sign * V_hat(params, x, cl.k) / d2, big)

        def rate_H(U: np.ndarray, cl: Claims = cl) -> np.ndarray:
            r = hat_V_rate(params, cl, _to_x(params, U))
            return np.where(np.isnan(r), big, -r)

        add(_de(lambda U: ratio_H(U, 1.0), seed=seed + 10 + j, maxiter=maxiter, popsize=20)[0],
            f"adversarial min V̂/|x|² on R̂ [{cl.label}]")
        add(_de(lambda U: ratio_H(U, -1.0), seed=seed + 20 + j, maxiter=maxiter, popsize=20)[0],
            f"adversarial max V̂/|x|² on R̂ [{cl.label}]")
        add(_de(rate_H, seed=seed + 30 + j, maxiter=maxiter, popsize=20)[0],
            f"adversarial max V̂'/V̂ on R̂ [{cl.label}]")
    return InitialStates(np.array(out), np.array(labels, dtype=object))


class _Spent(Exception):
    """A Nelder–Mead run asked for an evaluation beyond its budget."""


def _nelder_mead(u0: np.ndarray, *, maxfev: int, xatol: float, fatol: float):
    """scipy's Nelder–Mead (``scipy.optimize.minimize(method="Nelder-Mead")``: its coefficients 1, 2, ½, ½, its
    initial simplex, its stopping tests and its count of evaluations), unbounded, as a generator: it yields each
    point it needs the objective at, is sent the value, and returns ``(f, u)``, its best vertex.

    Written as a generator so that :func:`_nelder_mead_many` can evaluate the points of many runs in one vectorised
    call, where scipy's loop calls the objective on one point at a time; the iterates are scipy's.
    """
    n = len(u0)
    sim = np.empty((n + 1, n))
    sim[0] = u0
    for k in range(n):
        y = np.array(u0, dtype=float)
        y[k] = (1 + 0.05) * y[k] if y[k] != 0 else 0.00025
        sim[k + 1] = y
    fsim = np.full(n + 1, np.inf)
    calls = [0]

    def value(u: np.ndarray):
        if calls[0] >= maxfev:
            raise _Spent
        calls[0] += 1
        return (yield np.copy(u))

    try:
        for k in range(n + 1):
            fsim[k] = yield from value(sim[k])
    except _Spent:
        pass
    order = np.argsort(fsim)
    sim, fsim = np.take(sim, order, 0), np.take(fsim, order, 0)
    while calls[0] < maxfev:
        try:
            if np.max(np.abs(sim[1:] - sim[0])) <= xatol and np.max(np.abs(fsim[0] - fsim[1:])) <= fatol:
                break
            xbar = np.add.reduce(sim[:-1], 0) / n
            xr = 2 * xbar - sim[-1]
            fxr = yield from value(xr)
            if fxr < fsim[0]:  # expand
                xe = 3 * xbar - 2 * sim[-1]
                fxe = yield from value(xe)
                sim[-1], fsim[-1] = (xe, fxe) if fxe < fxr else (xr, fxr)
            elif fxr < fsim[-2]:  # reflect
                sim[-1], fsim[-1] = xr, fxr
            else:  # contract outside, or inside, else shrink towards the best vertex
                outside = fxr < fsim[-1]
                xc = 1.5 * xbar - 0.5 * sim[-1] if outside else 0.5 * xbar + 0.5 * sim[-1]
                fxc = yield from value(xc)
                if (fxc <= fxr) if outside else (fxc < fsim[-1]):
                    sim[-1], fsim[-1] = xc, fxc
                else:
                    for j in range(1, n + 1):
                        sim[j] = sim[0] + 0.5 * (sim[j] - sim[0])
                        fsim[j] = yield from value(sim[j])
        except _Spent:
            pass
        order = np.argsort(fsim)
        sim, fsim = np.take(sim, order, 0), np.take(fsim, order, 0)
    return float(np.min(fsim)), sim[0]


def _nelder_mead_many(func: Callable[[np.ndarray], np.ndarray], starts: list[np.ndarray], **options: float) -> list:
    """:func:`_nelder_mead` from every start, the runs in lockstep: each round evaluates the next point of every
    unfinished run in one call of the vectorised ``func`` (rows in, values out).  Returns each run's ``(f, u)``."""
    runs = [_nelder_mead(np.asarray(u0, dtype=float), **options) for u0 in starts]
    asked = [next(run) for run in runs]
    found: list = [None] * len(runs)
    active = list(range(len(runs)))
    while active:
        values = func(np.array([asked[i] for i in active]))
        still = []
        for i, f in zip(active, values):
            try:
                asked[i] = runs[i].send(float(f))
                still.append(i)
            except StopIteration as stop:
                found[i] = stop.value
        active = still
    return found


def rate_maximisers(params: Parameters, claim: Claims, *, seed: int, count: int = 16, maxiter: int = 60) -> np.ndarray:
    """Several local maximisers of ``V̂'/V̂`` on ``R̂`` (multistart Nelder–Mead from DE's best, the starts' runs
    evaluated together: :func:`_nelder_mead_many`)."""

    def obj(U: np.ndarray) -> np.ndarray:
        r = hat_V_rate(params, claim, _to_x(params, U))
        return np.where(np.isnan(r), 1e9, -r)

    best, _ = _de(obj, seed=seed, maxiter=maxiter, popsize=20)
    rng = np.random.default_rng(seed)
    starts = [best] + [np.array([rng.uniform(*b) for b in _BOUNDS]) for _ in range(count - 1)]
    found = _nelder_mead_many(obj, starts, maxfev=200, xatol=1e-9, fatol=1e-12)
    found.sort(key=lambda q: q[0])
    return _to_x(params, np.array([u for _, u in found]))
