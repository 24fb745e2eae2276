"""A hunting cycle against Corollary 1 (ISS from the inflation ``ρ``).

The stiction law (friction ``f_c sign(v)`` in a slip, anything in
``[-f_s, f_s]`` at rest) has its graph inside ``f_c SGN_ρ`` of eq. (perturbed)
with ``ρ = (f_s - f_c)/f_c``: every solution of the stiction model is a
solution of the perturbed inclusion, and Corollary 1 gives
``|z(t)|_𝒜 ≤ β(|z(0)|_𝒜, t) + γ(ρ)``.  Along a periodic solution the
transient term vanishes as ``t → ∞``, so a proved hunting cycle is a
*lower bound* of the ISS gain: ``γ(ρ) ≥ max over the cycle of |z|_𝒜``.

:func:`iss_comparison` sets this next to the ultimate bounds that the
cross-check measures on the gains without stiction (:func:`.._crosscheck._iss.iss_gain`
for the greedy selection of ``SGN_ρ`` and the Stribeck laws) and the exact
rest point at the edge of ``f_c SGN_ρ(0)``, at distance ``ρ f_c/k_i``
(:func:`.._crosscheck._iss_search.equilibrium_bound`).  Their maximum is the
*worst found* ``γ̂(ρ)`` (found, not proved: a lower estimate of ``γ(ρ)``).  The
cycle should lie within it; if it did not, the cycle would be the sharper
lower estimate of ``γ(ρ)``, and that is reported, not hidden.
"""

from __future__ import annotations

import dataclasses

from dataclasses import dataclass

from ._map import HuntingCycle

__all__ = ["IssComparison", "iss_comparison"]


@dataclass(frozen=True)
class IssComparison:
    """``max |z|_𝒜`` on the cycle against ``γ̂(ρ)``.

    Attributes
    ----------
    rho : float
        ``(f_s - f_c)/f_c``.
    amplitude : float
        ``max |z|_𝒜`` over the cycle (the distance of Corollary 1's proof).
    gamma : dict
        ``law -> γ̂(ρ)`` (``"greedy"``, ``"stribeck"``, ``"rest point"``).
    within : bool
        ``amplitude ≤`` the worst found ``max(gamma.values())``.
    """

    rho: float
    amplitude: float
    gamma: dict

    @property
    def worst_found(self) -> float:
        return max(self.gamma.values())

    @property
    def within(self) -> bool:
        return self.amplitude <= self.worst_found

    def describe(self) -> str:
        g = ", ".join(f"{law} {v:.4g}" for law, v in self.gamma.items())
        verdict = (
            f"within the worst found γ̂(ρ) = {self.worst_found:.4g}"
            if self.within
            else f"ABOVE the worst found γ̂(ρ) = {self.worst_found:.4g}: the cycle is the sharper lower estimate of γ(ρ)"
        )
        return (
            f"Corollary 1 at ρ = (f_s - f_c)/f_c = {self.rho:.6g}: cycle max |z|_𝒜 = {self.amplitude:.6g}; "
            f"empirical γ̂(ρ): {g}; {verdict}"
        )


def iss_comparison(cycle: HuntingCycle, *, horizon: float = 100.0, h: float = 5e-3) -> IssComparison:
    """Measure ``γ̂(ρ)`` at the cycle's ``ρ`` and compare (module docstring)."""
    from .._crosscheck._iss import iss_gain
    from .._crosscheck._iss_search import equilibrium_bound

    p = cycle.params
    coulomb = dataclasses.replace(p, f_s=p.f_c)  # the paper's model: Corollary 1 perturbs it
    est = iss_gain(coulomb, [p.rho], laws=("greedy", "stribeck"), horizon=horizon, h=h)
    gamma = {law: float(est.gamma[law][0]) for law in est.laws}
    gamma["rest point"] = float(equilibrium_bound(coulomb, p.rho))
    return IssComparison(rho=float(p.rho), amplitude=cycle.amplitude_distance, gamma=gamma)
