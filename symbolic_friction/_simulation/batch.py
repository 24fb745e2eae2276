"""The exact event-driven method vectorised over many initial states.

Same mathematics as :mod:`.event` (closed-form flows of eq. subcasesAffine,
the appendix's mode table, the certified event search of :mod:`.search`),
but every step acts on all unfinished trajectories at once with numpy: the
Python loops run over *event index* (one closed-form segment per trajectory
per round) and over the iterations of the vectorised search, never over
trajectories.  All trajectories share the sample times ``t_eval``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from .._coordinates import z_to_x
from .._errors import SimulationError
from .._parameters import Parameters
from ._base import Solution, Status
from .event import _SNAP_ULPS, _check_positive_int
from .modes import modes_after_slip, modes_at_rest
from .search import UNDERFLOW, first_zeros, slip_model

__all__ = ["BatchSolution", "simulate_batch"]

_EPS = 2.220446049250313e-16


@dataclass(frozen=True, eq=False)
class BatchSolution:
    """Solutions of :func:`simulate_batch` from ``N`` initial states on a common time grid.

    Attributes
    ----------
    params : Parameters
    t : ndarray, shape (m,)
        Sample times (``t_eval``).
    z : ndarray, shape (N, m, 3)
        ``(e_i, s, v)``; NaN after ``t_stop`` (only for status ``MAX_EVENTS``).
    mode : ndarray of int8, shape (N, m)
        ``+1``, ``0``, ``-1`` as in :class:`Solution` (0 after ``t_stop``).
    n_events : ndarray of int, shape (N,)
        Number of mode changes.
    status : ndarray of str, shape (N,)
        One of :class:`Status` per trajectory.
    t_stop : ndarray, shape (N,)
        Where each computation stopped: ``t_end``, or the time of the
        ``max_events``-th event.
    event_times : ndarray, shape (N, K)
        Event times in order, NaN-padded (``K = max(n_events)``).
    event_modes : ndarray of int8, shape (N, K, 2)
        ``(mode_before, mode_after)`` of each event, 0-padded.
    options : dict
    """

    params: Parameters
    t: np.ndarray
    z: np.ndarray
    mode: np.ndarray
    n_events: np.ndarray
    status: np.ndarray
    t_stop: np.ndarray
    event_times: np.ndarray
    event_modes: np.ndarray
    options: dict[str, Any] = field(default_factory=dict)

    @cached_property
    def x(self) -> np.ndarray:
        """States in ``(σ, φ, v)``, shape (N, m, 3)."""
        return z_to_x(self.params, self.z)

    def events(self, i: int) -> tuple[tuple[float, int, int], ...]:
        """The events ``(t, mode_before, mode_after)`` of trajectory ``i``."""
        k = int(self.n_events[i])
        return tuple(
            (float(self.event_times[i, j]), int(self.event_modes[i, j, 0]), int(self.event_modes[i, j, 1]))
            for j in range(k)
        )

    def solution(self, i: int) -> Solution:
        """Trajectory ``i`` as a :class:`Solution` (samples after ``t_stop`` dropped)."""
        keep = self.t <= self.t_stop[i] if self.status[i] == Status.MAX_EVENTS else slice(None)
        return Solution(
            params=self.params,
            method="event",
            t=self.t[keep],
            z=self.z[i][keep],
            mode=self.mode[i][keep],
            events=self.events(i),
            status=str(self.status[i]),
            options=dict(self.options),
        )


def _check_states(Z0: Any) -> np.ndarray:
    try:
        arr = np.asarray(Z0, dtype=float)
    except (TypeError, ValueError):
        raise SimulationError("the initial states Z0 must be an (N, 3) array of numbers (e_i, s, v)") from None
    if arr.ndim != 2 or arr.shape[1] != 3 or arr.shape[0] == 0:
        raise SimulationError(f"the initial states Z0 must have shape (N, 3) with N ≥ 1; got shape {arr.shape}")
    bad = ~np.all(np.isfinite(arr), axis=1)
    if bad.any():
        i = int(np.argmax(bad))
        raise SimulationError(
            f"all initial states Z0 must be finite; {int(bad.sum())} row(s) are not, first row {i}: {arr[i].tolist()}"
        )
    return arr


def _matvec(m: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``y @ m.T`` for y of shape (K, 3), written out (numpy's matmul is slow for 3×3)."""
    return np.column_stack([m[i, 0] * y[:, 0] + m[i, 1] * y[:, 1] + m[i, 2] * y[:, 2] for i in range(3)])


class _State:
    """The event loop's state of every trajectory (see :class:`.event.Segment`)."""

    def __init__(self, n: int) -> None:
        self.t = np.zeros(n)
        self.sigma = np.zeros(n)
        self.base = np.zeros(n, dtype=np.int8)
        self.offset = np.zeros(n)
        self.v = np.zeros(n)
        self.mode = np.zeros(n, dtype=np.int8)


class _Filler:
    """Writes closed-form segments into the (N, m) sample arrays."""

    def __init__(self, params: Parameters, t_eval: np.ndarray, n: int) -> None:
        model = slip_model(params)
        self.expm, self.f_c = model.expm, model.f_c
        self.t_eval = t_eval
        self.x = np.full((n, t_eval.size, 3), np.nan)
        self.mode = np.zeros((n, t_eval.size), dtype=np.int8)

    def _cells(self, rows: np.ndarray, t0: np.ndarray, t1: np.ndarray, final: bool):
        lo = np.searchsorted(self.t_eval, t0, side="left")
        hi = np.searchsorted(self.t_eval, t1, side="right" if final else "left")
        counts = np.maximum(hi - lo, 0)
        rep = np.repeat(np.arange(rows.size), counts)
        offsets = np.cumsum(counts) - counts
        col = lo[rep] + (np.arange(rep.size) - offsets[rep])
        return rep, col

    def segment(self, st: _State, rows: np.ndarray, t1: np.ndarray, final: bool) -> None:
        """Samples in ``[t, t1)`` (``[t, t1]`` if ``final``) of the rows' current segments."""
        if rows.size == 0:
            return
        t0 = st.t[rows]
        rep, col = self._cells(rows, t0, t1, final)
        if rep.size == 0:
            return
        r = rows[rep]
        tau = self.t_eval[col] - t0[rep]
        f_c = self.f_c
        mode = st.mode[rows]
        sigma, base, offset, v = st.sigma[rows], st.base[rows].astype(float), st.offset[rows], st.v[rows]
        self.mode[r, col] = mode[rep]
        stick = mode[rep] == 0
        if stick.any():
            rs, cs, k = r[stick], col[stick], rep[stick]
            self.x[rs, cs, 0] = sigma[k]
            self.x[rs, cs, 1] = base[k] * f_c + (offset[k] + sigma[k] * tau[stick])
            self.x[rs, cs, 2] = 0.0
        slip = ~stick
        if slip.any():
            d = mode.astype(float)
            # offsets from each row's slip equilibrium (exact when base = d), B1 and B2 per row
            y0 = np.column_stack([sigma, np.where(base == d, offset, (base - d) * f_c + offset), v])
            q1 = _matvec(self.expm.B1, y0)
            q2 = _matvec(self.expm.B2, y0)
            k = rep[slip]
            w0, w1, w2 = self.expm.w(tau[slip])
            dd = d[k]
            rs, cs = r[slip], col[slip]
            for c in range(3):
                comp = w2 * y0[k, c] + w1 * q1[k, c] + w0 * q2[k, c]
                if c == 1:
                    comp = comp + dd * f_c
                elif c == 2:
                    comp = dd * np.maximum(dd * comp, 0.0)  # v keeps the mode's sign (rounding)
                self.x[rs, cs, c] = comp


def simulate_batch(
    params: Parameters,
    Z0: Any,
    t_end: float,
    *,
    t_eval: Any = None,
    max_events: int = 10_000,
    grid_points: int = 1001,
) -> BatchSolution:
    """Exact event-driven solutions from many initial states, vectorised with numpy.

    Parameters
    ----------
    params : Parameters
    Z0 : array_like, shape (N, 3)
        Initial states ``(e_i, s, v)``; must be finite.
    t_end : float
        Horizon, ``> 0``.
    t_eval : array_like, optional, keyword-only
        Common sample times in ``[0, t_end]`` (nondecreasing); default
        ``grid_points`` equally spaced times.
    max_events : int, keyword-only
        Stop a trajectory after this many mode changes (status ``MAX_EVENTS``).
    grid_points : int, keyword-only
        Number of default sample times when ``t_eval`` is None.

    Returns
    -------
    BatchSolution

    Examples
    --------
    >>> p = Parameters.table_i("a")
    >>> sol = simulate_batch(p, [[0, 5, 0], [0, 0, 3]], 30.0, t_eval=[0.0, 15.0, 30.0])
    >>> sol.z.shape, sol.n_events.tolist()
    ((2, 3, 3), [10, 6])
    """
    from . import _check_horizon, _check_t_eval

    if not isinstance(params, Parameters):
        raise SimulationError(f"params must be a Parameters instance; got {type(params).__name__}")
    _check_positive_int("max_events", max_events, 1)
    _check_positive_int("grid_points", grid_points, 2)
    Z0 = _check_states(Z0)
    t_end = _check_horizon(t_end)
    t_eval = _check_t_eval(t_eval, t_end)
    if t_eval is None:
        t_eval = np.linspace(0.0, t_end, int(grid_points))

    model = slip_model(params)
    f_c = model.f_c
    k_p, k_i, _, _ = params.as_floats()
    n = Z0.shape[0]
    st = _State(n)
    X = z_to_x(params, Z0)
    st.sigma[:], st.offset[:], st.v[:] = X[:, 0], X[:, 1], X[:, 2]
    moving = st.v != 0.0
    st.mode[moving] = np.where(st.v[moving] > 0.0, 1, -1)
    rest = ~moving
    # as initial_state: φ = -k_i e_i - k_p s is rounded, a few ulps of its terms
    tol0 = _SNAP_ULPS * _EPS * (k_i * np.abs(Z0[:, 0]) + k_p * np.abs(Z0[:, 1]))
    st.base[rest], st.offset[rest], st.mode[rest] = modes_at_rest(
        st.sigma[rest], st.base[rest], st.offset[rest], f_c, tol0[rest]
    )

    fill = _Filler(params, t_eval, n)
    end = np.full(n, t_end)
    active = np.ones(n, dtype=bool)
    status = np.full(n, Status.T_END, dtype=object)
    t_stop = np.full(n, t_end)
    n_events = np.zeros(n, dtype=np.int64)
    log: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []

    def record(rows: np.ndarray, times: np.ndarray, before: np.ndarray, after: np.ndarray) -> None:
        log.append((rows, times, before.astype(np.int8), after.astype(np.int8)))
        n_events[rows] += 1

    def cap() -> None:
        capped = np.flatnonzero(active & (n_events >= max_events))
        # the state at the stopping time (an event time) closes the record
        fill.segment(st, capped, st.t[capped], final=True)
        status[capped] = Status.MAX_EVENTS
        t_stop[capped] = st.t[capped]
        active[capped] = False

    for _ in range(4 * max_events + 16):
        if not active.any():
            break
        # -- stick: closed-form exit time ---------------------------------
        rows = np.flatnonzero(active & (st.mode == 0))
        if rows.size:
            sig = st.sigma[rows]
            eq = sig == 0.0
            r = rows[eq]
            fill.segment(st, r, end[r], final=True)
            status[r] = Status.EQUILIBRIUM
            active[r] = False
            rows, sig = rows[~eq], sig[~eq]
            d = np.where(sig > 0.0, 1, -1).astype(np.int8)
            base, offset = st.base[rows], st.offset[rows]
            # exactly -offset when leaving where the last slip ended (see event.integrate_events)
            gap = np.where(base == d, -offset, (d - base.astype(float)) * f_c - offset)
            t_next = st.t[rows] + gap / sig
            ends = t_next >= t_end
            r = rows[ends]
            fill.segment(st, r, end[r], final=True)
            active[r] = False
            go = ~ends
            r, d, t_next = rows[go], d[go], t_next[go]
            fill.segment(st, r, t_next, final=False)
            record(r, t_next, np.zeros(r.size), d)
            st.t[r], st.base[r], st.offset[r], st.mode[r] = t_next, d, 0.0, d
            cap()
        # -- slip (including those that just left a stick): first zero of v --
        rows = np.flatnonzero(active & (st.mode != 0))
        if rows.size:
            d = st.mode[rows]
            base, offset = st.base[rows], st.offset[rows]
            y0 = np.column_stack(
                [st.sigma[rows], np.where(base == d, offset, (base.astype(float) - d) * f_c + offset), st.v[rows]]
            )
            tau, y = first_zeros(model, y0, d, t_end - st.t[rows])
            none = np.isnan(tau)
            r = rows[none]
            fill.segment(st, r, end[r], final=True)
            active[r] = False
            hit = ~none
            r, d, tau, y, y0 = rows[hit], d[hit], tau[hit], y[hit], y0[hit]
            t_next = st.t[r] + tau
            fill.segment(st, r, t_next, final=False)
            y[np.max(np.abs(y), axis=1) <= UNDERFLOW] = 0.0  # decayed onto x*_k ∈ 𝒜 (see search.UNDERFLOW)
            tol = _SNAP_ULPS * _EPS * np.max(np.abs(y0), axis=1)
            new_base, new_offset, new = modes_after_slip(y[:, 0], y[:, 1], d, f_c, tol)
            st.t[r], st.sigma[r], st.base[r], st.offset[r], st.v[r] = t_next, y[:, 0], new_base, new_offset, 0.0
            changed = new != d
            record(r[changed], t_next[changed], d[changed], new[changed])
            st.mode[r] = new
            late = r[t_next >= t_end]
            fill.segment(st, late, end[late], final=True)
            active[late] = False
            cap()
    else:
        r = np.flatnonzero(active)
        status[r] = Status.MAX_EVENTS
        t_stop[r] = st.t[r]

    k = int(n_events.max())
    event_times = np.full((n, k), np.nan)
    event_modes = np.zeros((n, k, 2), dtype=np.int8)
    if log:
        rows_all = np.concatenate([e[0] for e in log])
        order = np.argsort(rows_all, kind="stable")  # each row's events were logged in time order
        rows_all = rows_all[order]
        first = np.searchsorted(rows_all, np.arange(n), side="left")
        slot = np.arange(rows_all.size) - first[rows_all]
        event_times[rows_all, slot] = np.concatenate([e[1] for e in log])[order]
        event_modes[rows_all, slot, 0] = np.concatenate([e[2] for e in log])[order]
        event_modes[rows_all, slot, 1] = np.concatenate([e[3] for e in log])[order]

    # z = T⁻¹ x (eq. CoC inverted), written out per component for speed
    c_e, c_s = k_p / k_i**2, -1.0 / k_i
    z = np.empty_like(fill.x)
    z[..., 0] = c_e * fill.x[..., 0] + c_s * fill.x[..., 1]
    z[..., 1] = c_s * fill.x[..., 0]
    z[..., 2] = fill.x[..., 2]
    z[:, t_eval == 0.0, :] = Z0[:, None, :]  # the given states, not their round trip through x
    return BatchSolution(
        params=params,
        t=t_eval,
        z=z,
        mode=fill.mode,
        n_events=n_events,
        status=status.astype(str),
        t_stop=t_stop,
        event_times=event_times,
        event_modes=event_modes,
        options={"max_events": int(max_events), "grid_points": int(grid_points)},
    )
