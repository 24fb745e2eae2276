"""Corollary 1 (ISS from ρ) on simulations: an empirical gain ``γ(ρ)``.

Corollary 1 states ``|z(t)|_𝒜 ≤ β(|z(0)|_𝒜, t) + γ(|ρ|)`` for every
solution of the perturbed inclusion (eq. perturbed), whose friction lies in
``f_c SGN_ρ(v)``.  Two lower estimates of ``γ(ρ)`` are measured:

* from initial states **in** 𝒜, where ``β(0, t) = 0``: the largest
  ``|z(t)|_𝒜`` over the whole horizon is a lower bound of ``γ(ρ)``;
* from initial states **outside** 𝒜, the *ultimate bound*
  ``max sup_{t ∈ [T/2, T]} |z(t)|_𝒜``, which also contains what is left of
  the transient ``β`` at ``T/2`` (measured by the same number at ``ρ = 0``,
  reported as the baseline).

``γ̂(ρ)`` is the larger of the two.  Two families are simulated with the ``moreau`` method
(implicit Euler, :mod:`.._simulation.moreau`), as :mod:`.._simulation.friction`
prescribes for perturbed laws:

* ``"greedy"``: the inflated law ``SGN_ρ`` with the greedy adversarial
  selection of :class:`~.._simulation.friction.InflatedCoulomb` (the mass
  creeps at ``|v| = ρ`` instead of sticking).  One selection among many, so
  a lower estimate only: Stribeck friction inside ``SGN_ρ`` goes higher;
  :mod:`._iss_search` searches the admissible selections for the *worst
  found* (``search_rhos``);
* ``"stribeck"``: Stribeck friction with static level ``f_s = (1 + ρ) f_c``
  and Stribeck velocity ``v_s``, whose graph lies inside ``f_c SGN_ρ``
  (Fig. 4; :meth:`~.._simulation.friction.Stribeck.required_rho`); with
  ``f_s > f_c`` it *hunts* (a stick–slip limit cycle), which is counted.

The distance is ``|z|_𝒜 = sqrt(s² + v² + dz_{f_c/k_i}(e_i)²)`` of the proof
of Corollary 1.  Corollary 1 predicts ``γ̂(ρ) → 0`` as ``ρ → 0`` and a
bounded ``γ̂`` for large ``ρ``; :class:`IssEstimate` records the measured
curve and its log–log slope at small ``ρ``.  Nothing here is an upper
bound: no curve is called a worst case.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from .._model.parameters import Parameters
from ._initial import default_initial_states

__all__ = ["IssEstimate", "DEFAULT_RHOS", "iss_gain"]

DEFAULT_RHOS: tuple[str, ...] = ("0.001", "0.01", "0.1", "0.3", "1")
"""Inflations ``ρ`` (exact decimal strings) of the default sweep."""


@dataclass(frozen=True)
class IssEstimate:
    """Empirical ISS gain of Corollary 1 for one gain set.

    Attributes
    ----------
    params : Parameters
    rhos : tuple of float
    laws : tuple of str
        ``"greedy"`` and/or ``"stribeck"``.
    gamma : dict
        ``law -> array`` of ``γ̂(ρ)`` (one value per ``ρ``).
    gamma_from_attractor, gamma_tail : dict
        ``law -> array``: the two estimates of the module docstring.
    hunting : dict
        ``law -> array`` of the largest number of stick–slip events in the
        tail window among the solutions (``> 0``: a persistent cycle).
    slope : dict
        ``law ->`` log–log slope of ``γ̂`` between the two smallest ``ρ``.
    horizon, h : float
        Simulation horizon and Moreau step.
    v_s : float
        Stribeck velocity used.
    initial_states : ndarray, shape (m, 3)
        The ``z(0)`` used.
    """

    params: Parameters
    rhos: tuple[float, ...]
    laws: tuple[str, ...]
    gamma: dict = field(default_factory=dict)
    gamma_from_attractor: dict = field(default_factory=dict)
    gamma_tail: dict = field(default_factory=dict)
    hunting: dict = field(default_factory=dict)
    slope: dict = field(default_factory=dict)
    horizon: float = 0.0
    h: float = 0.0
    v_s: float = 0.0
    initial_states: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    worst_found: dict = field(default_factory=dict)
    """``ρ ->`` :class:`~._iss_search.WorstFound` at the searched inflations (``search_rhos``)."""

    def rows(self) -> list[tuple[str, float, float, float, float, int]]:
        """``(law, ρ, γ̂, from 𝒜, tail, tail events)`` for every law and ρ."""
        return [
            (law, rho, float(self.gamma[law][j]), float(self.gamma_from_attractor[law][j]),
             float(self.gamma_tail[law][j]), int(self.hunting[law][j]))
            for law in self.laws
            for j, rho in enumerate(self.rhos)
        ]


def iss_gain(
    params: Parameters,
    rhos=DEFAULT_RHOS,
    *,
    laws: tuple[str, ...] = ("greedy", "stribeck"),
    initial_states=None,
    horizon: float = 100.0,
    h: float = 5e-3,
    v_s: object = "0.1",
    search_rhos=(),
) -> IssEstimate:
    """Estimate ``γ(ρ)`` of Corollary 1 by simulation (see the module docstring).

    Parameters
    ----------
    params : Parameters
    rhos : sequence of numbers
        Inflations ``ρ ≥ 0`` (kept exact when given as strings).
    laws : tuple of {"greedy", "stribeck"}, keyword-only
    initial_states : array_like, shape (m, 3), optional, keyword-only
        ``z(0)`` rows; default: the two ends and the centre of 𝒜, and three
        states outside 𝒜 with ``|z(0)|_𝒜`` between 0.5 and 1.
    horizon, h : float, keyword-only
        Horizon ``T`` (the tail is ``[T/2, T]``) and the Moreau step.
    v_s : number, keyword-only
        Stribeck velocity.
    search_rhos : sequence of numbers, keyword-only
        Inflations at which to search the selections of ``SGN_ρ`` for the
        worst found (:func:`~._iss_search.worst_found`, tens of seconds each).

    Raises
    ------
    ParameterError
        If an unknown law is named or a ``ρ`` is negative.
    """
    from .._model.attractor import distance_z
    from .._infra.errors import ParameterError
    from .._infra.rational import to_rational
    from .._simulation import simulate
    from .._simulation.friction import InflatedCoulomb, Stribeck

    unknown = [law for law in laws if law not in ("greedy", "stribeck")]
    if unknown:
        raise ParameterError(f"unknown friction law(s) {unknown!r}; expected 'greedy' and/or 'stribeck'")
    rq = [to_rational(r, name="rho") for r in rhos]
    for r in rq:
        if r < 0:
            raise ParameterError(f"rho must be ≥ 0; got rho = {r}")
    if initial_states is None:
        initial_states = default_initial_states(params)
    Z0 = np.asarray(initial_states, dtype=float).reshape(-1, 3)
    f_c_q = params.f_c
    gamma: dict[str, np.ndarray] = {}
    g_att: dict[str, np.ndarray] = {}
    g_tail: dict[str, np.ndarray] = {}
    d0 = distance_z(params, Z0)
    hunting: dict[str, np.ndarray] = {}
    slope: dict[str, float] = {}
    for law_name in laws:
        ga = np.zeros(len(rq))
        gt = np.zeros(len(rq))
        hunt = np.zeros(len(rq), dtype=int)
        for j, rho in enumerate(rq):
            if law_name == "greedy":
                law = InflatedCoulomb(rho)
            else:
                law = Stribeck(f_s=(1 + rho) * f_c_q, v_s=to_rational(v_s, name="v_s"))
            for z0, dist0 in zip(Z0, d0):
                sol = simulate(params, z0, horizon, method="moreau", h=h, friction=law)
                d = distance_z(params, sol.z)
                if dist0 == 0:
                    ga[j] = max(ga[j], float(d.max()))
                else:
                    gt[j] = max(gt[j], float(d[sol.t >= horizon / 2].max()))
                hunt[j] = max(hunt[j], sum(1 for e in sol.events if e[0] >= horizon / 2))
        g = np.maximum(ga, gt)
        gamma[law_name] = g
        g_att[law_name] = ga
        g_tail[law_name] = gt
        hunting[law_name] = hunt
        pos = [(float(r), v) for r, v in zip(rq, g) if r > 0 and v > 0]
        if len(pos) >= 2:
            (r0, g0), (r1, g1) = pos[0], pos[1]
            slope[law_name] = float(np.log(g1 / g0) / np.log(r1 / r0))
    found = {}
    if search_rhos:
        from ._iss_search import worst_found

        for r in search_rhos:
            w = worst_found(params, r, initial_states=Z0, horizon=horizon, h=h)
            found[w.rho] = w
    return IssEstimate(
        params=params,
        rhos=tuple(float(r) for r in rq),
        laws=tuple(laws),
        gamma=gamma,
        gamma_from_attractor=g_att,
        gamma_tail=g_tail,
        hunting=hunting,
        slope=slope,
        horizon=float(horizon),
        h=float(h),
        v_s=float(Fraction(to_rational(v_s, name="v_s"))),
        initial_states=Z0,
        worst_found=found,
    )
