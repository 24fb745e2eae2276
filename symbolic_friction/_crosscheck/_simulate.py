"""Run the exact event-driven method (issue 4), vectorised over many initial
states, and collect a :class:`~._batch.TrajectoryBatch`.

:func:`~.._simulation.batch.simulate_batch` returns the samples, the event
times and the modes on either side of each event.  The state *at* an event
is needed too (``V`` jumps there), and is recovered in closed form: from the
last sample before the event (or the previous event, if it is later), the
affine flow of the mode in force (Claim 1, eq. subcasesAffine) is applied
over the elapsed time, exactly as the simulator's own dense output does.
Every event is a zero of ``v``, so ``v`` is set to 0 there; a stick ends at
``φ = ±f_c`` (closed form), which is set exactly.  The ``v`` found before
zeroing is kept as :attr:`TrajectoryBatch.event_residual`, a check of the
simulator's event times.
"""

from __future__ import annotations

import numpy as np

from .._coordinates import x_to_z, z_to_x
from .._parameters import Parameters
from ._batch import TrajectoryBatch

__all__ = ["simulate_trajectories", "x0_to_z0", "event_states"]


def event_states(
    params: Parameters,
    t: np.ndarray,
    x: np.ndarray,
    event_t: np.ndarray,
    before: np.ndarray,
    after: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """States at the events (``v = 0``) and the residual ``|v|`` the flow gave there.

    Parameters
    ----------
    params : Parameters
    t : ndarray, shape (n,)
        Sample times.
    x : ndarray, shape (N, n, 3)
        Sampled states in ``x`` coordinates.
    event_t, before, after : ndarray, shape (N, E)
        Event times (NaN-padded) and the modes before and after.
    """
    from .._simulation.affine import MatrixExponential

    expm = MatrixExponential.from_params(params)
    f_c = float(params.f_c)
    N, E = event_t.shape
    ev_x = np.full((N, E, 3), np.nan)
    resid = np.zeros((N, E))
    prev_t = np.full(N, -np.inf)
    prev_x = np.zeros((N, 3))
    for k in range(E):
        rows = np.flatnonzero(np.isfinite(event_t[:, k]))
        if rows.size == 0:
            break
        te = event_t[rows, k]
        # last sample strictly before the event (a sample at the event belongs to the next mode)
        j = np.clip(np.searchsorted(t, te, side="left") - 1, 0, t.size - 1)
        from_prev = prev_t[rows] >= t[j]
        t0 = np.where(from_prev, prev_t[rows], t[j])
        x0 = np.where(from_prev[:, None], prev_x[rows], x[rows, j])
        tau = np.maximum(te - t0, 0.0)
        m = before[rows, k].astype(int)
        out = np.empty((rows.size, 3))
        stick = m == 0
        out[stick, 0] = x0[stick, 0]
        out[stick, 1] = x0[stick, 1] + x0[stick, 0] * tau[stick]
        out[stick, 2] = 0.0
        slip = ~stick
        if np.any(slip):
            star = np.zeros((int(slip.sum()), 3))
            star[:, 1] = m[slip] * f_c
            out[slip] = star + expm.apply(tau[slip], x0[slip] - star)
        resid[rows, k] = np.abs(out[:, 2])
        out[:, 2] = 0.0
        # a stick ends exactly where φ reaches the sign of σ times f_c (closed form)
        leaving = stick & (after[rows, k] != 0)
        out[leaving, 1] = after[rows, k][leaving] * f_c
        ev_x[rows, k] = out
        prev_t[rows] = te
        prev_x[rows] = out
    return ev_x, resid


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
        Cap on mode changes per trajectory; a trajectory that reaches it is
        *incomplete* (``batch.complete`` is False): its samples after the stop
        stay NaN and no property is checked on them.
    source : ndarray of str, optional, keyword-only
        Label of each initial state.
    """
    from .._simulation.batch import simulate_batch

    Z0 = np.asarray(Z0, dtype=float).reshape(-1, 3)
    t = np.asarray(t, dtype=float)
    sol = simulate_batch(params, Z0, float(t[-1]), t_eval=t, max_events=max_events)
    from .._simulation._base import Status

    x = sol.x.copy()
    mode = sol.mode.copy()
    complete = np.asarray(sol.status) != Status.MAX_EVENTS
    ev_t = sol.event_times
    before = sol.event_modes[..., 0]
    after = sol.event_modes[..., 1]
    ev_x, resid = event_states(params, t, x, ev_t, before, after)
    return TrajectoryBatch(
        params=params,
        t=t,
        x=x,
        mode=mode,
        event_t=ev_t,
        event_x=ev_x,
        event_before=before,
        event_after=after,
        x0=z_to_x(params, Z0),
        z0=Z0,
        source=np.asarray(source, dtype=object) if source is not None else None,  # type: ignore[arg-type]
        event_residual=resid,
        complete=complete,
    )


def x0_to_z0(params: Parameters, X0: np.ndarray) -> np.ndarray:
    """Initial states given in ``x`` mapped to ``z`` (eq. CoC inverted)."""
    return x_to_z(params, np.asarray(X0, dtype=float))
