"""Lemma 2 on trajectories: ``V`` of eq. (lyapLike) is bounded below and decreases.

* item 1: ``c₁|x|²_𝒜 ≤ V(x)`` at every point (both limits at events too);
* item 2 (eq. Vdecrease): ``V(x(t₂)) - V(x(t₁)) ≤ -c ∫_{t₁}^{t₂} v² dt`` for
  all sampled ``t₁ < t₂``, ``V`` taken on *both sides* of every event (``V``
  is discontinuous exactly at mode changes); and its corollary, ``V``
  nonincreasing.

Why consecutive points suffice
------------------------------
With ``S(t) = V(x(t)) + c∫_0^t v²`` the claim for *all* pairs ``t₁ < t₂`` is
"``S`` is nonincreasing on the sampled points"; the integral is additive, so
consecutive inequalities telescope.  Rounding could add up over many steps,
so the slack is computed over all pairs at once with a running minimum
(``min_{t₁<t₂} S(t₁) - S(t₂)``), in ``O(n)`` per trajectory.  On a slip the
identity ``dV_k/dt = -c v²`` makes the inequality an equality: its slack is
``0`` up to rounding there, positive only across the downward jumps of ``V``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._along import along, exact_state
from ._property import Evaluation, Property

__all__ = ["Decrease", "Nonincreasing", "LowerBound"]


def _scale(a: Any, certificate: Any) -> np.ndarray:
    """``coef·L²`` with ``coef`` the largest coefficient of the quadratic forms involved."""
    coef = max(a.lam_P, certificate.c1, certificate.c2) if certificate is not None else a.lam_P
    return (coef * a.Q)[:, None]


def _pair_evaluation(prop: str, a: Any, c: float, scale: np.ndarray) -> Evaluation:
    S = a.V + c * a.cumI
    run_min = np.minimum.accumulate(np.where(a.valid, S, np.inf), axis=1)
    rel = (run_min[:, :-1] - S[:, 1:]) / scale

    def witness(idx: tuple[int, int]) -> Any:
        i, p = idx  # the pair (a*, p+1) with a* = argmin S over [0, p]
        b = p + 1
        before = np.where(a.valid[i, :b], S[i, :b], np.inf)
        # a NaN S (a NaN constant or state) is a failure: name the first point rather than crash on it
        j = int(np.nanargmin(before)) if not np.all(np.isnan(before)) else 0
        integral = float(a.cumI[i, b] - a.cumI[i, j])
        values = {"V_t1": a.V[i, j], "V_t2": a.V[i, b], "integral_v2": integral, "c": c,
                  "lhs": a.V[i, b] - a.V[i, j], "rhs": -c * integral, "scale": float(scale[i, 0])}
        return a.counterexample(prop, i, t=a.ch.t[i, b], t_start=a.ch.t[i, j], x=a.xs[i, b], values=values,
                                rel=(S[i, j] - S[i, b]) / scale[i, 0])

    return Evaluation(rel, a.pair, witness)


class Decrease(Property):
    """Lemma 2, item 2: ``V`` decreases at least at the rate ``c v²`` (eq. Vdecrease)."""

    id = "lemma2.decrease"
    paper = "Lemma 2, item 2 (eq. Vdecrease)"
    statement = "V(x(t2)) - V(x(t1)) <= -c ∫ v² dt, all t1 < t2"

    def check(self, trajectories: Any, certificate: Any) -> Evaluation:
        a = along(trajectories)
        return _pair_evaluation(self.id, a, certificate.c, _scale(a, certificate))


class Nonincreasing(Property):
    """Lemma 2, item 2, its corollary: ``V`` never increases, across events included."""

    id = "lemma2.nonincreasing"
    paper = "Lemma 2, item 2"
    statement = "V(x(t2)) <= V(x(t1)), both sides of every event"

    def check(self, trajectories: Any, certificate: Any) -> Evaluation:
        a = along(trajectories)
        return _pair_evaluation(self.id, a, 0.0, _scale(a, certificate))


class LowerBound(Property):
    """Lemma 2, item 1: ``c₁|x|²_𝒜 ≤ V(x)``; a violation is re-decided in exact arithmetic."""

    id = "lemma2.lower_bound"
    paper = "Lemma 2, item 1"
    statement = "c1 |x|²_A <= V(x)"

    def check(self, trajectories: Any, certificate: Any) -> Evaluation:
        a = along(trajectories)
        c1 = certificate.c1
        rel = (a.V - c1 * a.d2) / _scale(a, certificate)

        def witness(idx: tuple[int, int]) -> Any:
            return a.point_counterexample(self.id, idx, {"V": a.V[idx], "c1": c1, "dist2": a.d2[idx]}, rel[idx],
                                          exact=self.exact_violation(a.params, certificate, a.xs[idx]))

        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = a.V / a.d2
        return Evaluation(rel, a.valid & a.off_A, witness,
                          extremes=(("min V/|x|²", ratio, a.valid & a.far, False),))

    @staticmethod
    def exact_violation(params: Any, certificate: Any, x: Any) -> bool | None:
        """Whether ``c₁|x|²_𝒜 > V(x)`` in exact rational arithmetic at the float state ``x``."""
        from fractions import Fraction

        from .._model.attractor import squared_distance_x
        from .._model.lyapunov import V

        xq = exact_state(x)
        if xq is None:
            return None
        return not (Fraction(certificate.exact["c1"]) * squared_distance_x(params, xq) <= V(params, xq))
