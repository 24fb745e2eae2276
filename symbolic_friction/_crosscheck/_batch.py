"""Sampled exact solutions of eq. (xDot) in the form the cross-check reads.

A :class:`TrajectoryBatch` holds, for ``N`` trajectories sampled at common
times ``t``, the states in ``x = (σ, φ, v)`` coordinates (eq. CoC), the mode
of Claim 1 at each sample, and every mode change (event) with the state at
the event.  Events matter because ``V`` (eq. lyapLike) is discontinuous
exactly there: its one-sided limits are read off the state at the event and
the modes on either side.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._errors import SimulationError
from .._parameters import Parameters

__all__ = ["TrajectoryBatch"]


@dataclass(frozen=True, eq=False)
class TrajectoryBatch:
    """``N`` sampled solutions of eq. (xDot) with their events.

    Attributes
    ----------
    params : Parameters
    t : ndarray, shape (n,)
        Common, strictly increasing sample times, ``t[0] = 0``.
    x : ndarray, shape (N, n, 3)
        States ``(σ, φ, v)`` at the samples.
    mode : ndarray of int, shape (N, n)
        Mode at each sample (``+1``, ``0``, ``-1``), right-continuous: the
        mode on the interval that starts at the sample.
    event_t : ndarray, shape (N, E)
        Event (mode change) times, increasing along each row, padded with NaN.
    event_x : ndarray, shape (N, E, 3)
        States at the events (``v = 0`` there).
    event_before, event_after : ndarray of int, shape (N, E)
        Modes before and after each event (0 in the padding).
    x0 : ndarray, shape (N, 3)
        Initial states in ``x``.
    z0 : ndarray, shape (N, 3)
        Initial states in ``z = (e_i, s, v)``.
    source : ndarray of str, shape (N,)
        Where each initial state came from (``"sphere r=1"``, ``"grid"``, …).
    event_residual : ndarray, shape (N, E)
        ``|v|`` that the closed-form flow gives at each event time before
        ``v`` is set to 0 (a check of the event times; 0 if not known).
    complete : ndarray of bool, shape (N,)
        False where the simulation stopped before the last sample (the event
        limit): its samples after the stop are NaN, never made up.
    """

    params: Parameters
    t: np.ndarray
    x: np.ndarray
    mode: np.ndarray
    event_t: np.ndarray
    event_x: np.ndarray
    event_before: np.ndarray
    event_after: np.ndarray
    x0: np.ndarray
    z0: np.ndarray
    source: np.ndarray = field(default=None)  # type: ignore[assignment]
    event_residual: np.ndarray = field(default=None)  # type: ignore[assignment]
    complete: np.ndarray = field(default=None)  # type: ignore[assignment]

    def __post_init__(self) -> None:
        N, n = self.mode.shape
        E = self.event_t.shape[1] if self.event_t.ndim == 2 else -1
        problems = []
        if self.t.shape != (n,):
            problems.append(f"t has shape {self.t.shape}, expected ({n},)")
        if self.x.shape != (N, n, 3):
            problems.append(f"x has shape {self.x.shape}, expected ({N}, {n}, 3)")
        if self.event_t.shape != (N, E) or self.event_x.shape != (N, E, 3):
            problems.append(f"events have shapes {self.event_t.shape} and {self.event_x.shape}, expected ({N}, E)")
        if self.event_before.shape != (N, E) or self.event_after.shape != (N, E):
            problems.append("event_before/event_after must have the shape of event_t")
        if self.x0.shape != (N, 3) or self.z0.shape != (N, 3):
            problems.append(f"x0 and z0 must have shape ({N}, 3)")
        if n and np.any(np.diff(self.t) <= 0):
            problems.append("sample times must be strictly increasing")
        if problems:
            raise SimulationError("malformed trajectory batch: " + "; ".join(problems))
        if self.source is None:
            object.__setattr__(self, "source", np.full(N, "", dtype=object))
        if self.event_residual is None:
            object.__setattr__(self, "event_residual", np.zeros(self.event_t.shape))
        if self.complete is None:
            object.__setattr__(self, "complete", np.ones(N, dtype=bool))

    @property
    def size(self) -> int:
        """Number of trajectories ``N``."""
        return int(self.mode.shape[0])

    def subset(self, index: np.ndarray | slice) -> "TrajectoryBatch":
        """The trajectories ``index`` (a slice or an index array)."""
        return TrajectoryBatch(
            params=self.params,
            t=self.t,
            x=self.x[index],
            mode=self.mode[index],
            event_t=self.event_t[index],
            event_x=self.event_x[index],
            event_before=self.event_before[index],
            event_after=self.event_after[index],
            x0=self.x0[index],
            z0=self.z0[index],
            source=self.source[index],
            event_residual=self.event_residual[index],
            complete=self.complete[index],
        )
