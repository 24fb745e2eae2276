"""Run the exact event-driven method (issue 4) on many initial states and
collect a :class:`~._batch.TrajectoryBatch`.

The samples come from the simulator's dense output; the events and the
states at the events come from its closed-form segments (each event starts a
new segment, whose initial state is the state at the event).
"""

from __future__ import annotations

import numpy as np

from .._coordinates import x_to_z, z_to_x
from .._parameters import Parameters
from ._batch import TrajectoryBatch

__all__ = ["simulate_trajectories"]


def simulate_trajectories(
    params: Parameters,
    Z0: np.ndarray,
    t: np.ndarray,
    *,
    max_events: int = 10_000,
    source: np.ndarray | None = None,
) -> TrajectoryBatch:
    """Simulate from every row of ``Z0`` (``z = (e_i, s, v)``) and sample at ``t``.

    Parameters
    ----------
    params : Parameters
    Z0 : ndarray, shape (N, 3)
    t : ndarray, shape (n,)
        Strictly increasing sample times with ``t[0] = 0``.
    max_events : int, keyword-only
        Cap on mode changes per trajectory.
    source : ndarray of str, optional, keyword-only
        Label of each initial state.
    """
    from .._simulation.event import integrate_events, sample_segments

    Z0 = np.asarray(Z0, dtype=float).reshape(-1, 3)
    t = np.asarray(t, dtype=float)
    N, n = Z0.shape[0], t.size
    t_end = float(t[-1])
    xs = np.empty((N, n, 3))
    modes = np.empty((N, n), dtype=np.int8)
    ev_lists = []
    for i in range(N):
        segments, events, _status = integrate_events(params, Z0[i], t_end, max_events=max_events)
        x, mode = sample_segments(params, segments, t)
        stop = segments[-1][1]
        if stop < t_end:  # max_events reached: hold the last state (never happens with the defaults)
            late = t > stop
            x[late] = segments[-1][3]
            mode[late] = segments[-1][2]
        xs[i] = x
        modes[i] = mode
        starts = {}
        for seg in segments:
            starts.setdefault(seg[0], seg[3])
        ev_lists.append([(te, b, a, starts.get(te)) for te, b, a in events])
    E = max((len(e) for e in ev_lists), default=0)
    ev_t = np.full((N, E), np.nan)
    ev_x = np.zeros((N, E, 3))
    ev_b = np.zeros((N, E), dtype=np.int8)
    ev_a = np.zeros((N, E), dtype=np.int8)
    for i, evs in enumerate(ev_lists):
        for j, (te, b, a, xe) in enumerate(evs):
            ev_t[i, j] = te
            ev_b[i, j] = b
            ev_a[i, j] = a
            ev_x[i, j] = xe if xe is not None else np.nan
    return TrajectoryBatch(
        params=params,
        t=t,
        x=xs,
        mode=modes,
        event_t=ev_t,
        event_x=ev_x,
        event_before=ev_b,
        event_after=ev_a,
        x0=z_to_x(params, Z0),
        z0=Z0,
        source=np.asarray(source, dtype=object) if source is not None else None,  # type: ignore[arg-type]
    )


def x0_to_z0(params: Parameters, X0: np.ndarray) -> np.ndarray:
    """Initial states given in ``x`` mapped to ``z`` (eq. CoC inverted)."""
    return x_to_z(params, np.asarray(X0, dtype=float))
