"""Corollary 1, the adversary: the largest ultimate bound *found* over admissible selections of ``SGN_ρ``.

Solutions of the perturbed inclusion (eq. perturbed) are not unique: any
measurable selection ``m(t) ∈ SGN_ρ(v(t))`` is a solution, and Corollary 1's
gain ``γ(ρ)`` must cover all of them.  A single selection (the greedy one of
:class:`~.._simulation.friction.InflatedCoulomb`) is therefore only a lower
estimate; this module searches for a larger one.  Every candidate is the
package's law ``InflatedCoulomb(ρ, selection=(t, x) ↦ (d, e))``, i.e.
friction ``f_c(SGN(v + d) + e)`` with ``|d|, |e| ≤ ρ`` (``SGN_ρ(v) =
SGN(v + ρ𝔹) + ρ𝔹``), simulated by the Moreau method; admissibility is
enforced by the law itself (it raises on ``|d|`` or ``|e| > ρ``).  Families:

``velocity-shaped``
    A friction characteristic of ``v``: static level ``(1 + a₀ρ) f_c``
    while stuck (``e = a₀ρ sign φ`` at ``v = 0``), ``(1 + c_j ρ) f_c sign v``
    on four bins of ``|v|`` (edges ``0.01, 0.1, 1``), and for
    ``0 < |v| < qρ`` a push *along* the motion with ``(1 + ρ) f_c`` (the
    greedy selection's creep).  Stribeck friction with ``f_s ≤ (1 + ρ) f_c``
    is (up to the bins) a member, and it seeds the search.
``bang-bang``
    ``e = ρ sign(α·(σ, φ, v) + α₀)`` while slipping (a switching surface
    through state space), the static level as above.
``periodic``
    A piecewise-constant selection in time: ``e = ρ c_j`` on four equal
    parts of a period ``P`` (optimised too), ``d = 0``.

Each family's parameters are optimised by differential evolution (scipy,
imported lazily) on a shorter, coarser simulation; the best of every family,
and the greedy selection, are then re-simulated at the reference horizon and
step from every initial state, and the largest ultimate bound
``max sup_{t ∈ [T/2, T]} |z(t)|_𝒜`` is the **worst found**.  One candidate
needs no simulation: the rest point at the edge of ``f_c SGN_ρ(0)``, at
distance exactly ``ρ f_c/k_i`` from 𝒜 (:func:`equilibrium_bound`, decided in
rationals), a proved *lower* bound of ``γ(ρ)``.  It is not a
proved upper bound, so it is never called the worst case.  The Stribeck
family (``f_s = (1 + ρ) f_c``, several ``v_s``) is simulated alongside: it
must lie below the worst found, or the search is not done
(:attr:`WorstFound.covers_stribeck`).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Callable

import numpy as np

from .._model.parameters import Parameters

__all__ = ["WorstFound", "worst_found", "equilibrium_bound", "FAMILIES", "STRIBECK_VELOCITIES"]

FAMILIES = ("velocity-shaped", "bang-bang", "periodic")
STRIBECK_VELOCITIES: tuple[str, ...] = ("0.01", "0.1", "1")
"""Stribeck velocities ``v_s`` of the comparison family (``f_s = (1 + ρ) f_c``)."""

_EDGES = np.array([0.01, 0.1, 1.0])
_BOUNDS = {
    "velocity-shaped": [(-1.0, 1.0)] * 5 + [(0.0, 1.0)],  # a0, c1..c4, q
    "bang-bang": [(-1.0, 1.0)] * 6,  # a0, alpha0, alpha (3), unused
    "periodic": [(0.0, 2.0)] + [(-1.0, 1.0)] * 4,  # log10 P, c1..c4
}


def _sign(y: float) -> float:
    return 1.0 if y > 0 else -1.0 if y < 0 else 0.0


def selection(family: str, theta: np.ndarray, rho: float) -> Callable[[float, tuple], tuple[float, float]]:
    """The selection ``(t, x) ↦ (d, e)`` of ``family`` with parameters ``theta`` (|d|, |e| ≤ ρ by construction)."""
    th = [float(q) for q in np.clip(theta, -1.0, max(1.0, float(np.max(np.abs(theta)))))]

    if family == "velocity-shaped":
        a0, c, q = th[0], th[1:5], th[5]
        edges = _EDGES.tolist()

        def law(t: float, x: tuple) -> tuple[float, float]:
            _, phi, v = x
            if v == 0.0:
                return 0.0, rho * a0 * _sign(phi)
            s = _sign(v)
            if abs(v) < q * rho:
                return -rho * s, -rho * s  # SGN(v + d) flips: a push along the motion, (1 + ρ) f_c
            return 0.0, rho * c[bisect.bisect_left(edges, abs(v))] * s  # np.searchsorted's bin, without a numpy call per step
    elif family == "bang-bang":
        a0, alpha0, alpha = th[0], th[1], th[2:5]

        def law(t: float, x: tuple) -> tuple[float, float]:
            sigma, phi, v = x
            if v == 0.0:
                return 0.0, rho * a0 * _sign(phi)
            return 0.0, rho * _sign(alpha[0] * sigma + alpha[1] * phi + alpha[2] * v + alpha0)
    elif family == "periodic":
        period, c = 10.0 ** th[0], th[1:5]

        def law(t: float, x: tuple) -> tuple[float, float]:
            j = min(3, int(4.0 * ((t / period) % 1.0)))
            return 0.0, rho * c[j]
    else:
        raise ValueError(f"unknown family {family!r}; expected one of {FAMILIES}")
    law.__name__ = f"{family} selection"
    return law


def equilibrium_bound(params: Parameters, rho: Fraction) -> Fraction:
    """``|z|_𝒜`` of a rest point of eq. (perturbed) at the edge of ``f_c SGN_ρ(0)``, exactly: ``ρ f_c/k_i``.

    ``z = (-(1 + ρ) f_c/k_i, 0, 0)``, i.e. ``x = (0, (1 + ρ) f_c, 0)``: with
    the selection ``λ = 1 + ρ ∈ SGN_ρ(0)`` the right-hand side ``A x - b λ``
    vanishes, so the constant function is a solution and ``γ(ρ)`` can be no
    smaller than its distance to 𝒜.  Decided in rational arithmetic on the
    package's ``A``, ``b``, ``T`` and ``|z|²_𝒜``; raises if it were not a rest point.
    """
    from .._model.attractor import squared_distance_z
    from .._model.coordinates import input_vector_entries, system_matrix_entries, z_to_x

    rho = Fraction(rho)
    z = np.array([-(1 + rho) * params.f_c / params.k_i, Fraction(0), Fraction(0)], dtype=object)
    x = z_to_x(params, z)
    lam = 1 + rho  # in SGN_ρ(0) = [-(1 + ρ), 1 + ρ]
    A = system_matrix_entries(params.k_p, params.k_i, params.k_v)
    b = input_vector_entries(params.f_c)
    rate = [sum(A[i][j] * x[j] for j in range(3)) - b[i] * lam for i in range(3)]
    if any(r != 0 for r in rate):
        raise AssertionError(f"not a rest point of eq. (perturbed): x' = {rate}")
    d2 = Fraction(squared_distance_z(params, z))
    bound = rho * params.f_c / params.k_i
    if bound * bound != d2:
        raise AssertionError(f"|z|²_A = {d2}, expected ({bound})²")
    return bound


def ultimate_bound(params: Parameters, law: Any, Z0: np.ndarray, *, horizon: float, h: float) -> tuple[float, int]:
    """``(max over Z0 of sup_{t ∈ [T/2, T]} |z(t)|_𝒜, index of the maximising state)`` under ``law``."""
    from .._model.attractor import distance_z
    from .._simulation import simulate

    best, arg = -math.inf, 0
    for j, z0 in enumerate(Z0):
        sol = simulate(params, z0, horizon, method="moreau", h=h, friction=law)
        tail = float(distance_z(params, sol.z)[sol.t >= horizon / 2].max())
        if tail > best:
            best, arg = tail, j
    return best, arg


@dataclass(frozen=True)
class WorstFound:
    """The largest ultimate bound found at one ``ρ`` (a lower estimate of ``γ(ρ)``, not an upper bound).

    Attributes
    ----------
    rho : float
    bound : float
        The worst found: ``max sup_{t ∈ [T/2, T]} |z(t)|_𝒜`` over the initial states.
    law : str
        Which selection attains it (family and parameters).
    initial_state : tuple of float
        The ``z(0)`` that attains it.
    candidates : dict
        Family (and ``"greedy"``) -> its ultimate bound at the reference horizon and step;
        ``"equilibrium"`` -> :func:`equilibrium_bound` (exact, a proved lower bound of ``γ(ρ)``).
    stribeck : dict
        ``v_s`` -> ultimate bound of Stribeck friction ``f_s = (1 + ρ) f_c``.
    evaluations : int
        Simulations the search ran.
    """

    rho: float
    bound: float
    law: str
    initial_state: tuple[float, float, float]
    candidates: dict = field(default_factory=dict)
    stribeck: dict = field(default_factory=dict)
    evaluations: int = 0

    @property
    def covers_stribeck(self) -> bool:
        """Every Stribeck law of the family lies at or below the worst found."""
        return all(v <= self.bound * (1 + 1e-9) for v in self.stribeck.values())


def _seeds(family: str, rho: float) -> list[list[float]]:
    """Known points of a family: Stribeck-like (static 1 + ρ, kinetic decaying to 1) and 'stick high, slip low'."""
    if family == "velocity-shaped":
        return [[1.0, 1.0, 0.6, 0.0, 0.0, 0.0], [1.0, -1.0, -1.0, -1.0, -1.0, 0.0], [1.0, 1.0, 1.0, 0.0, 0.0, 0.0]]
    if family == "bang-bang":
        return [[1.0, -1.0, 0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0, -1.0, 0.0]]
    return [[1.0, 1.0, 1.0, -1.0, -1.0]]


def worst_found(params: Parameters, rho: object, *, initial_states: Any = None, horizon: float = 100.0,
                h: float = 5e-3, search_horizon: float = 60.0, search_h: float = 1e-2, maxiter: int = 6,
                popsize: int = 4, seed: int = 0, families: tuple[str, ...] = FAMILIES,
                stribeck_velocities: tuple[str, ...] = STRIBECK_VELOCITIES) -> WorstFound:
    """Search the admissible selections of ``SGN_ρ`` for the largest ultimate bound (module docstring).

    Parameters
    ----------
    params : Parameters
    rho : number
        Inflation ``ρ > 0`` (kept exact when given as a string).
    initial_states : array_like, shape (m, 3), optional, keyword-only
        ``z(0)`` rows (default: those of :func:`~._iss.iss_gain`).
    horizon, h : float, keyword-only
        Reference horizon (tail ``[T/2, T]``) and Moreau step of the final numbers.
    search_horizon, search_h : float, keyword-only
        The cheaper simulation the optimiser runs.
    maxiter, popsize, seed : int, keyword-only
        Differential evolution per family.
    """
    from scipy.optimize import differential_evolution

    from .._infra.errors import ParameterError
    from .._infra.rational import to_rational
    from .._simulation.friction import InflatedCoulomb, Stribeck
    from ._initial import default_initial_states

    rq = to_rational(rho, name="rho")
    if rq <= 0:
        raise ParameterError(f"rho must be > 0 for a search over SGN_rho; got rho = {rq}")
    r = float(rq)
    Z0 = default_initial_states(params) if initial_states is None else np.asarray(initial_states, float).reshape(-1, 3)
    # the optimiser looks at the states the greedy selection drives farthest: one outside 𝒜, one inside
    search_states = Z0[[0, int(np.argmax(np.linalg.norm(Z0, axis=1)))]]
    evaluations = 0
    candidates: dict[str, float] = {}
    where: dict[str, tuple[str, tuple]] = {}
    for fi, family in enumerate(families):
        bounds = _BOUNDS[family]

        def objective(theta: np.ndarray, family: str = family) -> float:
            nonlocal evaluations
            evaluations += len(search_states)
            law = InflatedCoulomb(rq, selection=selection(family, theta, r))
            return -ultimate_bound(params, law, search_states, horizon=search_horizon, h=search_h)[0]

        rng = np.random.default_rng(seed + fi)
        n = popsize * len(bounds)
        init = np.array([[rng.uniform(lo, hi) for lo, hi in bounds] for _ in range(n)])
        for k, s in enumerate(_seeds(family, r)):
            init[k] = s
        res = differential_evolution(objective, bounds, init=init, maxiter=maxiter, seed=seed + fi, polish=False,
                                     tol=0.0)
        law = InflatedCoulomb(rq, selection=selection(family, res.x, r))
        candidates[family], j = ultimate_bound(params, law, Z0, horizon=horizon, h=h)
        evaluations += len(Z0)
        where[family] = (f"{family} {np.round(res.x, 4).tolist()}", tuple(float(q) for q in Z0[j]))
    candidates["greedy"], j = ultimate_bound(params, InflatedCoulomb(rq), Z0, horizon=horizon, h=h)
    where["greedy"] = ("greedy selection (InflatedCoulomb default)", tuple(float(q) for q in Z0[j]))
    evaluations += len(Z0)
    stribeck: dict[str, float] = {}
    f_s = (1 + rq) * params.f_c
    for v_s in stribeck_velocities:
        law = Stribeck(f_s=f_s, v_s=to_rational(v_s, name="v_s"))
        if law.required_rho(params.f_c) > rq:
            continue  # not inside f_c SGN_rho: not a member of the family at this rho
        stribeck[v_s] = ultimate_bound(params, law, Z0, horizon=horizon, h=h)[0]
        evaluations += len(Z0)
    eq = equilibrium_bound(params, rq)
    candidates["equilibrium"] = float(eq)
    where["equilibrium"] = (f"rest at the edge of f_c SGN_rho(0) (exact: rho f_c/k_i = {eq})",
                            (float(-(1 + rq) * params.f_c / params.k_i), 0.0, 0.0))
    top = max(candidates, key=candidates.get)
    return WorstFound(rho=r, bound=candidates[top], law=where[top][0], initial_state=where[top][1],
                      candidates=candidates, stribeck=stribeck, evaluations=evaluations)
