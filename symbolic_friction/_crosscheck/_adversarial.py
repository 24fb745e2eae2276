"""Adversarial initial states: optimisers that try to break the certified
inequalities (scipy.optimize, imported lazily).

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
from typing import Callable

import numpy as np

from .._model.parameters import Parameters
from ._claims import Claims
from ._initial import InitialStates, directions_to_x

__all__ = ["pointwise_extremes", "rate_maximisers", "hat_V_rate", "LOG_RADIUS"]

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


def rate_maximisers(params: Parameters, claim: Claims, *, seed: int, count: int = 16, maxiter: int = 60) -> np.ndarray:
    """Several local maximisers of ``V̂'/V̂`` on ``R̂`` (multistart Nelder–Mead from DE's best)."""
    from scipy.optimize import minimize

    def obj(U: np.ndarray) -> np.ndarray:
        r = hat_V_rate(params, claim, _to_x(params, U))
        return np.where(np.isnan(r), 1e9, -r)

    best, _ = _de(obj, seed=seed, maxiter=maxiter, popsize=20)
    rng = np.random.default_rng(seed)
    starts = [best] + [np.array([rng.uniform(*b) for b in _BOUNDS]) for _ in range(count - 1)]
    found = []
    for u0 in starts:
        res = minimize(lambda u: float(obj(u[None, :])[0]), u0, method="Nelder-Mead",
                       options={"maxfev": 200, "xatol": 1e-9, "fatol": 1e-12})
        found.append((float(res.fun), res.x))
    found.sort(key=lambda q: q[0])
    return _to_x(params, np.array([u for _, u in found]))
