"""What a property check produces: counterexamples, per-property results and
the running tally that folds chunks of trajectories into them."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

__all__ = ["Counterexample", "PropertyResult", "Tally"]


@dataclass(frozen=True)
class Counterexample:
    """A violated inequality on one trajectory.

    Attributes
    ----------
    property, certificate : str
        Property id and certificate label.
    trajectory : int
        Index of the trajectory in the cross-check run.
    source : str
        Where its initial state came from.
    z0, x0 : tuple of float
        Initial state in ``z = (e_i, s, v)`` and in ``x = (σ, φ, v)``.
    t : float
        Time of the violation (``t₂`` for a two-time inequality).
    t_start : float or None
        ``t₁`` for a two-time inequality.
    x : tuple of float
        State at ``t``.
    values : dict
        The two sides, the slack, the tolerance and any other number used
        (numbers or short lists of numbers).
    relative_slack : float
        ``(rhs - lhs)/scale`` (below ``-rtol`` for a violation).
    exact : bool or None
        For a pointwise inequality: whether it also fails in exact rational
        arithmetic at the (float) state ``x``; ``None`` when not applicable.
    paper, inequality : str
        The property's paper reference and statement (filled by the tally).
    """

    property: str
    certificate: str
    trajectory: int
    source: str
    z0: tuple[float, float, float]
    x0: tuple[float, float, float]
    t: float
    t_start: float | None
    x: tuple[float, float, float]
    values: dict[str, Any]
    relative_slack: float
    exact: bool | None = None
    paper: str = ""
    inequality: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready mapping (floats written with full precision)."""
        return {
            "property": self.property,
            "paper": self.paper,
            "inequality": self.inequality,
            "certificate": self.certificate,
            "trajectory": self.trajectory,
            "source": self.source,
            "z0": list(self.z0),
            "x0": list(self.x0),
            "t": self.t,
            "t_start": self.t_start,
            "x": list(self.x),
            "values": dict(self.values),
            "relative_slack": self.relative_slack,
            "confirmed_in_exact_arithmetic": self.exact,
        }


@dataclass(frozen=True)
class PropertyResult:
    """Outcome of one property on one certificate.

    Attributes
    ----------
    id, paper, inequality : str
    trajectories : int
        Trajectories on which the inequality was checked at least once.
    samples : int
        Instances of the inequality checked (sampled points or pairs).
    worst_margin : float
        Smallest relative slack seen (``nan`` if nothing was checked).
    failures : int
        Instances with relative slack below ``-rtol``.
    counterexample : Counterexample or None
        The worst violation, if any.
    inconclusive : int
        Instances that can neither pass nor fail on this horizon (e.g. a
        trajectory still in its first stick phase at ``T``).
    details : dict
        Extra statistics (e.g. the largest observed overshoot).
    """

    id: str
    paper: str
    inequality: str
    trajectories: int
    samples: int
    worst_margin: float
    failures: int
    counterexample: Counterexample | None = None
    inconclusive: int = 0
    details: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        return self.failures == 0


class Tally:
    """Running minimum, counts and worst counterexample of one property on one certificate.

    Parameters
    ----------
    prop : Property
        Supplies ``id``, ``paper`` and ``statement``.
    certificate : str
        Label written into counterexamples.
    rtol : float
        A violation is a relative slack below ``-rtol``.
    """

    def __init__(self, prop: Any, certificate: str, rtol: float) -> None:
        self.prop = prop
        self.certificate = certificate
        self.rtol = rtol
        self.trajectories = 0
        self.samples = 0
        self.failures = 0
        self.inconclusive = 0
        self.worst = math.inf
        self.counterexample: Counterexample | None = None
        self.details: dict[str, Any] = {}

    def add(self, rel: np.ndarray, mask: np.ndarray, make: Any, *, offset: int = 0,
            count_trajectories: bool = True) -> None:
        """Fold in relative slacks ``rel`` where ``mask`` (first axis = trajectory).

        ``make(index)`` builds the counterexample at the worst instance (only
        called for a violation); its ``trajectory`` is shifted by ``offset``.
        ``count_trajectories=False`` for a second call on the same trajectories.
        """
        if not np.any(mask):
            return
        self.samples += int(np.count_nonzero(mask))
        if count_trajectories:
            per_traj = mask.reshape(mask.shape[0], -1).any(axis=1)
            self.trajectories += int(np.count_nonzero(per_traj))
        r = np.where(mask, rel, np.inf)
        # NaN slack (should not happen) counts as a failure rather than being hidden
        r = np.where(np.isnan(r) & mask, -np.inf, r)
        self.failures += int(np.count_nonzero(r < -self.rtol))
        idx = np.unravel_index(int(np.argmin(r)), r.shape)
        low = float(r[idx])
        if low < self.worst:
            self.worst = low
            if low < -self.rtol:
                self.counterexample = self.stamp(make(tuple(int(i) for i in idx)), offset)

    def stamp(self, cx: Counterexample, offset: int) -> Counterexample:
        """``cx`` with this tally's certificate, the paper reference and the run-wide trajectory index."""
        values = dict(cx.values)
        values.setdefault("tolerance_relative", self.rtol)
        return replace(cx, certificate=self.certificate, trajectory=cx.trajectory + offset, values=values,
                       paper=self.prop.paper, inequality=self.prop.statement)

    def extreme(self, key: str, values: np.ndarray, mask: np.ndarray, *, largest: bool) -> None:
        """Track the smallest (or largest) of ``values`` where ``mask`` in ``details[key]``."""
        if not np.any(mask):
            return
        v = float(np.max(values[mask]) if largest else np.min(values[mask]))
        old = self.details.get(key)
        if old is None or (v > old if largest else v < old):
            self.details[key] = v

    def result(self) -> PropertyResult:
        return PropertyResult(
            id=self.prop.id,
            paper=self.prop.paper,
            inequality=self.prop.statement,
            trajectories=self.trajectories,
            samples=self.samples,
            worst_margin=self.worst if self.samples else math.nan,
            failures=self.failures,
            counterexample=self.counterexample,
            inconclusive=self.inconclusive,
            details=dict(self.details),
        )
