"""Proposition 1 on trajectories: stability with the certified overshoot, and attractivity.

* item 2 (eq. stabState): ``|x(t)|_𝒜 ≤ κ|x(0)|_𝒜`` at every sample and event;
* item 1, in the finite-horizon form ``|x(T)|_𝒜 ≤ θ|x(0)|_𝒜``.  Decay can be
  very slow (a stick phase from ``σ̄`` lasts ``≈ 2f_c/|σ̄|`` with
  ``|x|_𝒜 = |σ̄|`` constant), so a trajectory that has not reached
  ``θ|x(0)|_𝒜`` by ``T`` is *pending*: :func:`resolve_attractivity` follows it
  on windows of doubling length before it may be called a failure.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._along import along
from ._property import DEFAULT_THETA, Evaluation, Property

__all__ = ["Stability", "Attractivity", "resolve_attractivity"]


class Stability(Property):
    """Proposition 1, item 2 (eq. stabState), with the certificate's overshoot bound κ."""

    id = "prop1.stability"
    paper = "Proposition 1, item 2 (eq. stabState)"
    statement = "|x(t)|_A <= kappa |x(0)|_A"
    paper_constants = False  # κ only: every template's bound, trajectory by trajectory

    def check(self, trajectories: Any, certificate: Any) -> Evaluation:
        a = along(trajectories)
        kappa = certificate.kappa
        rel = (kappa * a.d0[:, None] - a.d) / a.L[:, None]

        def witness(idx: tuple[int, int]) -> Any:
            d0 = a.d0[idx[0]]
            values = {"dist": a.d[idx], "dist0": d0, "kappa": kappa,
                      "observed_ratio": a.d[idx] / d0 if d0 > 0 else float("inf")}
            return a.point_counterexample(self.id, idx, values, rel[idx])

        return Evaluation(rel, a.point, witness)


class Attractivity(Property):
    """Proposition 1, item 1: ``|x(T)|_𝒜 ≤ θ|x(0)|_𝒜`` by the horizon, or later (see :func:`resolve_attractivity`).

    Parameters
    ----------
    theta : float, keyword-only
        The factor ``θ ∈ (0, 1]``.
    """

    id = "prop1.attractivity"
    paper = "Proposition 1, item 1"
    statement = "|x(T)|_A <= theta |x(0)|_A at the horizon T"
    uses_certificate = False

    def __init__(self, *, theta: float = DEFAULT_THETA) -> None:
        self.theta = float(theta)

    def slack(self, trajectories: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(rel, conclusive)`` at the horizon, per trajectory."""
        a = along(trajectories)
        d_final = a.d[np.arange(a.N), a.last_sample]
        return (self.theta * a.d0 - d_final) / a.L, (a.d0 > 0) & a.complete

    def check(self, trajectories: Any, certificate: Any = None) -> Evaluation:
        """Instances that reached ``θ|x(0)|_𝒜`` by ``T``; the others are :meth:`pending`, not failures yet."""
        a = along(trajectories)
        rel, conclusive = self.slack(trajectories)
        ok = conclusive & (rel >= 0)

        def witness(idx: tuple[int, int]) -> Any:
            i = idx[0]
            values = {"dist_T": a.d[i, a.last_sample[i]], "dist0": a.d0[i], "theta": self.theta}
            return a.counterexample(self.id, i, t=trajectories.t[-1], t_start=0.0, x=a.xs[i, a.last_sample[i]],
                                    values=values, rel=rel[i])

        return Evaluation(rel[:, None], ok[:, None], witness)

    def pending(self, trajectories: Any) -> np.ndarray:
        """Rows still above ``θ|x(0)|_𝒜`` at ``T`` (to be followed further)."""
        rel, conclusive = self.slack(trajectories)
        return np.flatnonzero(conclusive & ~(rel >= 0))


def resolve_attractivity(params: Any, z: np.ndarray, target: np.ndarray, window: float, *, max_events: int,
                         doublings: int = 60, samples: int = 40) -> list[tuple[bool, float, float, tuple] | None]:
    """Follow trajectories from states ``z`` until ``|x(t)|_𝒜 ≤ target``.

    The solution is a semigroup: each is restarted from its last state on
    windows of doubling length ``window, 2·window, …`` (at most
    ``300/|Re λ|``, λ the slowest root: a slip converging to ``x*_k`` much
    longer underflows to denormals, where the event search crawls).  Near 𝒜
    the stick phases last ``≈ 2f_c/|σ|``, so the time needed grows like
    ``1/|x(0)|_𝒜``.

    Returns
    -------
    list
        Per state ``(reached, time, distance, state)``, or ``None`` if its
        simulation was incomplete (event limit): neither holds nor fails.
    """
    from .._model.attractor import distance_x
    from ._outcome import slowest_root
    from ._simulate import simulate

    n = z.shape[0]
    z = np.array(z, dtype=float)
    cap = max(window, 300.0 / abs(slowest_root(params)))
    start = 0.0
    outcome: list[Any] = [(False, 0.0, float("nan"), (float("nan"),) * 3)] * n
    active = np.arange(n)
    for _ in range(doublings):
        if active.size == 0:
            break
        t = np.concatenate([[0.0], np.geomspace(window / samples, window, samples)])
        b = simulate(params, z[active], float(t[-1]), t_eval=t, max_events=max_events)
        d = distance_x(params, b.x)
        still = []
        for row, k in enumerate(active):
            if not b.complete[row]:
                outcome[k] = None
                continue
            hit = np.nonzero(d[row, 1:] <= target[k])[0]
            if hit.size:
                j = int(hit[0]) + 1
                outcome[k] = (True, start + float(t[j]), float(d[row, j]), tuple(float(q) for q in b.x[row, j]))
            else:
                outcome[k] = (False, start + window, float(d[row, -1]), tuple(float(q) for q in b.x[row, -1]))
                z[k] = b.z[row, -1]
                still.append(k)
        active = np.array(still, dtype=int)
        start += window
        window = min(2.0 * window, cap)
    return outcome
