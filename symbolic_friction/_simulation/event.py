"""The exact event-driven method (``method="event"``): the reference solution
of the inclusion ``x' ∈ A x - b SGN(v)`` (eq. xDot), unique by Lemma 1.

The solution is a concatenation of the three affine flows of Claim 1
(eq. subcasesAffine), each in closed form (:mod:`.affine`):

* **Mode selection** by the appendix's table (:mod:`.modes`).
* **Stick** (``k = 0``): ``φ(t) = φ̄ + σ̄ t`` reaches ``sign(σ̄) f_c`` at
  ``t = (sign(σ̄) f_c - φ̄)/σ̄`` (closed form), where row (iii) or (ix)
  starts a slip; with ``σ̄ = 0`` the state is an equilibrium in 𝒜 and the
  method stops stepping (:attr:`Status.EQUILIBRIUM`, later samples constant).
* **Slip** (``k = ±1``): the event is the *first* zero of ``v`` after the
  start, bracketed rigorously and refined to machine precision
  (:mod:`.search`: a certified scan plus a certified Taylor march, both
  resting on ``|x - x*_k|_P`` being nonincreasing with the paper's ``P``, and
  on stiff gains on the split of ``v`` into its fast mode and the slow pair,
  so that the cost is set by the events, not by ``k_v``).
* If the search cannot decide where a slip ends (its certified march ran out
  of steps, which no gain set in the tests reaches), the kernel stops at the
  slip's start with :attr:`Status.UNDECIDED`, and :func:`simulate` finishes
  the trajectory from there with ``ivp-events`` (Radau, ``rtol = 1e-12``),
  status :attr:`Status.FALLBACK`, the switch stated in ``options["fallback"]``
  (with static friction, which that method does not model, it stays
  incomplete).
* After a slip, ``v`` is set to exactly 0 and the next mode is selected with
  :func:`._kernel.mode_after_slip`: a tolerance-free clamp (a slip in
  direction ``k`` can only end with ``k·φ ≤ f_c``), then ``φ`` within a few
  ulps of ``±f_c`` counts as on it, so that ``σ`` decides as rows
  (iii)/(v)/(vii)/(ix) do.  ``φ`` is carried as an exact boundary plus an
  offset, so a stick after a tiny slip gets its exact duration ``-offset/σ``.
  A grazing contact (row (iii)/(ix) again) continues the slip without an
  event.  A slip that decays to within 1e-280 of its equilibrium
  ``(0, ±f_c, 0) ∈ 𝒜`` (where double precision underflows) is put on it:
  an equilibrium.  ``max_events`` caps the number of mode changes
  (:attr:`Status.MAX_EVENTS`; later samples are NaN, never made up), so
  rounding at a switching surface can never make the method spin forever.

With static friction above Coulomb (``Parameters(f_s=…)``, ``f_s > f_c``; beyond
the paper) the same loop runs with the stick boundary at ``±f_s``: a stick ends
at ``φ = ±f_s`` and the slip starts from the offset ``(σ, ±(f_s - f_c), 0)``
(a jump of the acceleration), and a slip that ends with ``|φ| ≤ f_s`` sticks.

All of this is one kernel for one trajectory (:mod:`._kernel`), compiled by
numba when it is installed; :func:`run` applies it to one or many initial
states and returns the one result type, :class:`.Trajectories`.

Only numpy and the standard library are imported (no scipy, no sympy).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .._model.coordinates import x_to_z
from .._infra.errors import SimulationError
from .._model.parameters import Parameters
from ._base import SimulationMethod, Solution
from ._jit import kernel, plain, spent_in_plain
from ._trajectories import Status, Trajectories
from .search import slip_model

__all__ = ["EventDriven", "run"]

# Room for this many events per trajectory on the first pass; a trajectory
# with more is run again with room for max_events (its kernel call says so).
_FIRST_ROOM = 32
# the kernel's status codes (T_END, MAX_EVENTS, EQUILIBRIUM, NONFINITE) as names
_STATUS_NAMES = np.array(
    [Status.T_END, Status.MAX_EVENTS, Status.EQUILIBRIUM, Status.NONFINITE, "buffer full", Status.UNDECIDED], dtype=object
)


def _check_positive_int(name: str, value: Any, minimum: int) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise SimulationError(f"{name} must be an integer ≥ {minimum}; got {value!r}")


def _kernel_pass(consts, k, Z0, X0, t_end, max_events, ts, room):
    """One call of the kernel on every row; the buffers it fills (padding included)."""
    n, m = Z0.shape[0], ts.size
    with np.errstate(over="ignore", invalid="ignore"):  # plain Python on numpy scalars: overflow is a status
        return _kernel_call(consts, k, Z0, X0, t_end, max_events, ts, room, n, m)


def _kernel_call(consts, k, Z0, X0, t_end, max_events, ts, room, n, m):
    out_x, out_z = np.empty((2, n, m, 3))
    out_mode = np.empty((n, m), dtype=np.int8)
    ev_t = np.empty((n, room))
    ev_x = np.empty((n, room, 3))
    ev_m = np.empty((n, room, 2), dtype=np.int8)
    ev_res = np.empty((n, room))
    if n == 1:  # no parallel region for one trajectory
        code, n_ev, t_stop = k.trajectory(
            *consts, Z0[0], X0[0], t_end, max_events, ts,
            out_x[0], out_z[0], out_mode[0], ev_t[0], ev_x[0], ev_m[0], ev_res[0],
        )
        status, n_ev, t_stop = np.array([code]), np.array([n_ev]), np.array([t_stop])
    else:
        status = np.empty(n, dtype=np.int64)
        n_ev = np.empty(n, dtype=np.int64)
        t_stop = np.empty(n)
        k.trajectories(
            *consts, Z0, X0, t_end, max_events, ts,
            out_x, out_z, out_mode, ev_t, ev_x, ev_m, ev_res, status, n_ev, t_stop,
        )
    return [out_x, out_z, out_mode, ev_t, ev_x, ev_m, ev_res, status, n_ev, t_stop]


def run(
    params: Parameters,
    Z0: np.ndarray,
    t_end: float,
    ts: np.ndarray,
    *,
    max_events: int,
    source: np.ndarray | None = None,
    options: dict[str, Any] | None = None,
) -> Trajectories:
    """The kernel from every row of ``Z0`` (validated, finite, shape (N, 3)), sampled at sorted ``ts``."""
    model = slip_model(params)
    Z0 = np.ascontiguousarray(Z0, dtype=float)
    X0 = np.empty_like(Z0)  # filled by the kernel: T z0
    ts = np.ascontiguousarray(ts, dtype=float)
    k = kernel(work=Z0.shape[0] * (ts.size + 2 * _FIRST_ROOM))
    is_plain = k is plain()
    consts = model.constants(not is_plain)
    start = time.perf_counter()
    room = int(min(max_events, _FIRST_ROOM))
    out = _kernel_pass(consts, k, Z0, X0, t_end, max_events, ts, room)
    status, n_ev = out[7], out[8]
    again = np.flatnonzero(status == 4)  # BUFFER_FULL: more events than the first pass had room for
    if again.size:
        more = _kernel_pass(consts, k, Z0[again], np.empty((again.size, 3)), t_end, max_events, ts, int(max_events))
        n_ev[again] = more[8]
    if is_plain:
        spent_in_plain(time.perf_counter() - start)
    width = int(n_ev.max())
    for j in (3, 4, 5, 6):  # the event axis, cut or padded to the most events of any row
        a = out[j]
        if a.shape[1] > width:
            out[j] = a[:, :width]
        elif a.shape[1] < width:
            pad = [(0, 0)] * a.ndim
            pad[1] = (0, width - a.shape[1])
            out[j] = np.pad(a, pad, constant_values=np.nan if j in (3, 4) else 0)
    if again.size:
        for j in range(10):
            out[j][again] = more[j][:, :width] if j in (3, 4, 5, 6) else more[j]
    x, z, mode, ev_t, ev_x, ev_m, ev_res, status, n_ev, t_stop = out
    return Trajectories._unchecked(
        params=params,
        method="event",
        t=ts,
        z=z,
        x=x,
        mode=mode,
        event_t=ev_t,
        event_x=ev_x,
        event_before=ev_m[..., 0],
        event_after=ev_m[..., 1],
        event_residual=ev_res,
        n_events=n_ev,
        status=_STATUS_NAMES[status],
        t_stop=t_stop,
        z0=Z0,
        x0=X0,
        source=source,
        options=dict(options or {}),
    )


def run_one(params: Parameters, z0: np.ndarray, t_end: float, ts: np.ndarray, *, max_events: int, options: dict) -> Trajectories:
    """:func:`run` for one initial state, with less Python around the same kernel call."""
    model = slip_model(params)
    m = ts.size
    k = kernel(work=m + 2 * _FIRST_ROOM)
    is_plain = k is plain()
    consts = model.constants(not is_plain)
    start = time.perf_counter()
    Z0 = np.array(z0, dtype=float).reshape(1, 3)
    X0 = np.empty((1, 3))
    ts = np.ascontiguousarray(ts, dtype=float)
    room = int(min(max_events, _FIRST_ROOM))
    while True:
        x, z = np.empty((2, 1, m, 3))  # one allocation, two C-contiguous halves
        mode = np.empty((1, m), dtype=np.int8)
        ev_t, ev_x = np.empty((1, room)), np.empty((1, room, 3))
        ev_m, ev_res = np.empty((1, room, 2), dtype=np.int8), np.empty((1, room))
        if is_plain:
            with np.errstate(over="ignore", invalid="ignore"):  # overflow is reported as a status
                code, n, t_stop = k.trajectory(
                    *consts, Z0[0], X0[0], t_end, max_events, ts, x[0], z[0], mode[0], ev_t[0], ev_x[0], ev_m[0], ev_res[0]
                )
        else:
            code, n, t_stop = k.trajectory(
                *consts, Z0[0], X0[0], t_end, max_events, ts, x[0], z[0], mode[0], ev_t[0], ev_x[0], ev_m[0], ev_res[0]
            )
        if code != 4 or room >= max_events:  # 4: BUFFER_FULL, run again with room for max_events
            break
        room = int(max_events)
    if is_plain:
        spent_in_plain(time.perf_counter() - start)
    return Trajectories._unchecked(
        params=params, method="event", t=ts, z=z, x=x, mode=mode,
        event_t=ev_t[:, :n], event_x=ev_x[:, :n], event_before=ev_m[:, :n, 0], event_after=ev_m[:, :n, 1],
        event_residual=ev_res[:, :n], n_events=np.array([n]), status=_STATUS_NAMES[code : code + 1],
        t_stop=np.array([t_stop]), z0=Z0, x0=X0, options=dict(options),
    )


@dataclass(frozen=True, kw_only=True)
class EventDriven(SimulationMethod):
    """Exact event-driven simulation (closed-form flows, exact mode table).

    Parameters
    ----------
    max_events : int, default 10_000
        Stop (status ``MAX_EVENTS``) after this many mode changes.
    grid_points : int, default 1001
        Without ``t_eval``: number of equally spaced samples on ``[0, t_end]``,
        to which every event time is added.

    Exact: no accuracy knob (``order = inf``); states agree with the 50-digit
    reference to about 1e-14 relative.

    Examples
    --------
    >>> from symbolic_friction import EventDriven, Parameters, simulate
    >>> sol = simulate(Parameters.table_i("b"), (0, 3, 0), 40, method=EventDriven(grid_points=5))
    >>> sol.t.size - len(sol.events), sol.status  # the grid, plus every event time
    (5, 't_end reached')
    """

    max_events: int = 10_000
    grid_points: int = 1001

    name: ClassVar[str] = "event"
    stiction: ClassVar[bool] = True
    resets: ClassVar[bool] = True
    order: ClassVar[float] = math.inf
    knob: ClassVar[str | None] = None

    def _validate(self, options: dict[str, Any]) -> None:
        _check_positive_int("max_events", options["max_events"], 1)
        _check_positive_int("grid_points", options["grid_points"], 2)

    def _solve(
        self, params: Parameters, z0: np.ndarray, t_end: float, t_eval: np.ndarray | None, options: dict[str, Any]
    ) -> Solution:
        max_events = int(options["max_events"])
        if t_eval is not None:
            batch = run_one(params, z0, t_end, t_eval, max_events=max_events, options=options)
            if batch.status[0] == Status.UNDECIDED and not params.stiction:
                return _fallback(batch, params, z0, t_end, max_events, options, event_samples=False)
            return _single(batch)
        grid = np.linspace(0.0, t_end, int(options["grid_points"]))
        batch = run_one(params, z0, t_end, grid, max_events=max_events, options=options)
        if batch.status[0] == Status.UNDECIDED and not params.stiction:
            return _fallback(batch, params, z0, t_end, max_events, options, event_samples=True)
        if batch.status[0] == Status.MAX_EVENTS:
            # the grid covers what was computed: [0, t_stop]
            grid = np.linspace(0.0, float(batch.t_stop[0]), int(options["grid_points"]))
            batch = run_one(params, z0, t_end, grid, max_events=max_events, options=options)
        return _single(_with_events(batch))


# The stiff integrator that finishes a trajectory whose next event the kernel could not decide,
# and its tolerances (relative; absolute ones scaled by the state's size).
FALLBACK_INTEGRATOR = "Radau"
FALLBACK_RTOL = 1e-12


def _fallback(
    batch: Trajectories, params: Parameters, z0: np.ndarray, t_end: float, max_events: int, options: dict,
    *, event_samples: bool,
) -> Solution:
    """Finish ``batch`` (one trajectory, status ``UNDECIDED``) with Radau and events from where it stopped.

    The exact samples and events up to ``t_stop`` (the start of the slip whose
    end the kernel could not decide) are kept; the rest comes from the
    ``ivp-events`` method with ``integrator="Radau"`` at ``rtol = 1e-12``.
    The status says so (:attr:`Status.FALLBACK`), and ``options["fallback"]``
    states from when, with which integrator and tolerances (the residual
    of that part: its local error per step, not the kernel's rounding).
    """
    from .ivp_events import IvpEvents

    t_stop = float(batch.t_stop[0])
    # the exact state where the kernel stopped: its sample at t_stop
    at_stop = run_one(params, z0, t_end, np.array([0.0, t_stop]), max_events=max_events, options=options)
    z_stop = at_stop.z[0, -1]
    n = int(batch.n_events[0])
    keep = batch.t <= t_stop
    later = batch.t[~keep]
    scale = max(1.0, float(np.max(np.abs(z_stop))), float(params.f_c) / float(params.k_i))
    # the rest of the event budget (the kernel's events count), at least one mode change
    radau = IvpEvents(
        integrator=FALLBACK_INTEGRATOR, rtol=FALLBACK_RTOL, atol=FALLBACK_RTOL * scale, max_events=max(max_events - n, 1)
    )
    horizon = t_end - t_stop
    # the requested samples after the stop, and t_end so that Radau runs to the horizon (dropped below)
    rest = radau._solve(params, z_stop, horizon, np.concatenate([later - t_stop, [horizon]]), radau.options)
    end = -1 if rest.t.size and rest.t[-1] == horizon else None  # an incomplete rest keeps its last sample
    rt, rz, rmode = rest.t[:end] + t_stop, rest.z[:end], rest.mode[:end]
    events = tuple((float(batch.event_t[0, j]), int(batch.event_before[0, j]), int(batch.event_after[0, j])) for j in range(n))
    events += tuple((t + t_stop, a, b) for t, a, b in rest.events)
    complete = rest.status in Status.COMPLETE
    fallback = {
        "from": t_stop,
        "integrator": FALLBACK_INTEGRATOR,
        "rtol": FALLBACK_RTOL,
        "atol": FALLBACK_RTOL * scale,
        "status": rest.status,
    }
    t = np.concatenate([batch.t[keep], rt])
    z = np.concatenate([batch.z[0, keep], rz])
    mode = np.concatenate([batch.mode[0, keep], rmode])
    if event_samples:  # as _with_events: the exact event times among the samples
        t_ev = np.array([e[0] for e in events[:n]])
        order = np.argsort(np.concatenate([t, t_ev]), kind="stable")
        ev_z = x_to_z(params, batch.event_x[0, :n])
        t = np.concatenate([t, t_ev])[order]
        z = np.concatenate([z, ev_z])[order]
        mode = np.concatenate([mode, batch.event_after[0, :n]])[order]
        unique = np.concatenate([[True], t[1:] != t[:-1]])
        t, z, mode = t[unique], z[unique], mode[unique]
    return Solution.from_samples(
        params=params, method="event", t=t, z=z, mode=mode, events=events,
        status=Status.FALLBACK if complete else rest.status, options={**options, "fallback": fallback},
    )


def _with_events(batch: Trajectories) -> Trajectories:
    """One trajectory with its event times added to the samples (the state there is the event's)."""
    n = int(batch.n_events[0])
    if n == 0:
        return batch
    t = np.concatenate([batch.t, batch.event_t[0, :n]])
    order = np.argsort(t, kind="stable")  # a grid time equal to an event time comes first
    t = t[order]
    keep = np.concatenate([[True], t[1:] != t[:-1]])
    pick = order[keep]

    def merged(samples: np.ndarray, at_events: np.ndarray) -> np.ndarray:
        return np.concatenate([samples[0], at_events[0, :n]])[pick][None]

    ev_z = x_to_z(batch.params, batch.event_x[:, :n])
    return Trajectories._unchecked(
        params=batch.params,
        method=batch.method,
        t=t[keep],
        z=merged(batch.z, ev_z),
        x=merged(batch.x, batch.event_x),
        mode=merged(batch.mode, batch.event_after),
        event_t=batch.event_t,
        event_x=batch.event_x,
        event_before=batch.event_before,
        event_after=batch.event_after,
        event_residual=batch.event_residual,
        n_events=batch.n_events,
        status=batch.status,
        t_stop=batch.t_stop,
        z0=batch.z0,
        x0=batch.x0,
        source=batch.source,
        options=batch.options,
    )


def _single(batch: Trajectories) -> Solution:
    if batch.status[0] == Status.NONFINITE:
        z0 = ", ".join(f"{c:g}" for c in batch.z0[0])
        raise SimulationError(
            f"the solution from z0 = ({z0}) leaves the range of float64 (about ±1.8e308) at t = {batch.t_stop[0]:g}: "
            "scale the initial state down"
        )
    return batch.solution(0)
