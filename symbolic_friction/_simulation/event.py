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
from .._infra.guards import check_count, check_memory
from .._model.parameters import Parameters
from ._base import MAX_EVENTS, MAX_GRID_POINTS, SimulationMethod, Solution
from ._jit import kernel, plain, spent_in_plain
from ._kernel_layout import BUFFER_FULL, I_DWELL, I_STICK_SLIP_H, I_STICK_SLIP_T, S_SIZE
from ._trajectories import Status, Trajectories
from .search import slip_model

__all__ = ["EventDriven", "run", "preload_compiled"]

# Room for this many events per trajectory on the first pass (reset PID: _first_room).  A trajectory
# with more stops (BUFFER_FULL) with its loop's state saved and goes on from there in a larger buffer
# (_next_room, at most max_events): nothing is computed twice, and the padding the kernel writes stays
# within a few times the events it holds (a buffer of max_events = 100 000 slots per trajectory, which
# the trajectories used to be run again with, cost more than the trajectory itself).
_FIRST_ROOM = 32
# A larger buffer has at least _GROWTH times the room of the last, at most _MAX_GROWTH times.
_GROWTH, _MAX_GROWTH = 4, 64
# reset PID's first pass: room for at most this many events per trajectory (memory)
_RESET_ROOM_CAP = 4096
# the kernel's status codes (T_END, MAX_EVENTS, EQUILIBRIUM, NONFINITE) as names
_STATUS_NAMES = np.array(
    [Status.T_END, Status.MAX_EVENTS, Status.EQUILIBRIUM, Status.NONFINITE, "buffer full", Status.UNDECIDED], dtype=object
)


def _check_positive_int(name: str, value: Any, minimum: int, maximum: int = 10**12) -> None:
    check_count(value, name=name, low=minimum, high=maximum, error=SimulationError)


def _first_room(K, t_end: float, max_events: int) -> int:
    """Event slots per trajectory for the first pass of the kernel.

    :data:`_FIRST_ROOM` for the paper's PID.  With resets (``K[I_DWELL] ≥ 0``)
    a stick ends at once in a slip from ``(σ, ±f_c, 0)``, whose length is the
    same ``τ*`` for every ``σ`` (``K[I_STICK_SLIP_T]``, with ``f_s = f_c``), so
    a trajectory has about three events (a reset, the stick's end, the slip's
    end) per ``τ*``.  Room for that many (up to :data:`_RESET_ROOM_CAP`) spares
    reset PID's trajectories the further passes, each a launch of the kernel,
    that a smaller buffer would take.  The room changes no result.
    """
    room = _FIRST_ROOM
    if K[I_DWELL] >= 0.0 and K[I_STICK_SLIP_T] <= K[I_STICK_SLIP_H]:
        room += int(min(3.0 * t_end / K[I_STICK_SLIP_T], _RESET_ROOM_CAP))
    return int(min(max_events, room))


def _next_room(room: int, n_ev: np.ndarray, t_stop: np.ndarray, t_end: float, max_events: int) -> int:
    """The room of the next pass for trajectories that filled ``room`` slots with ``n_ev`` events by ``t_stop``.

    Their events so far, at the rate they came, extrapolated to ``t_end``
    with a quarter more, within :data:`_GROWTH` and :data:`_MAX_GROWTH` times
    ``room`` and at most ``max_events``: usually one more pass.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.max(n_ev / t_stop)
    want = 1.25 * rate * t_end if np.isfinite(rate) else math.inf
    return int(min(max_events, _MAX_GROWTH * room, max(_GROWTH * room, want)))


_EVENT_BYTES = 8 + 3 * 8 + 2 + 8  # ev_t, ev_x, ev_m, ev_res of one event


def _slip_model(params: Parameters):
    """:func:`.search.slip_model`, with gains whose closed form leaves float64 refused by name."""
    try:
        return slip_model(params)
    except (OverflowError, ZeroDivisionError) as exc:
        raise SimulationError(
            f"the event method's closed form of these gains leaves the range of float64 ({exc}): k_p = "
            f"{float(params.k_p):g}, k_i = {float(params.k_i):g}, k_v = {float(params.k_v):g}; rescale time"
        ) from None


def _event_buffers(n: int, room: int) -> list[np.ndarray]:
    """``ev_t, ev_x, ev_m, ev_res`` for ``n`` trajectories of at most ``room`` events (uninitialised)."""
    return [np.empty((n, room)), np.empty((n, room, 3)), np.empty((n, room, 2), dtype=np.int8), np.empty((n, room))]


def _kernel_call(consts, k, Z0, X0, t_end, max_events, ts, out, state, rows, events):
    """The kernel on the trajectories ``rows``: into ``out = [out_x, out_z, out_mode, status, n_ev, t_stop]`` and
    ``state`` (one row per trajectory) and ``events = [ev_t, ev_x, ev_m, ev_res]`` (one row per entry of ``rows``)."""
    out_x, out_z, out_mode, status, n_ev, t_stop = out
    with np.errstate(over="ignore", invalid="ignore"):  # plain Python on numpy scalars: overflow is a status
        if rows.size == 1:  # no parallel region for one trajectory
            j = int(rows[0])
            status[j], n_ev[j], t_stop[j] = k.trajectory(
                *consts, Z0[j], X0[j], t_end, max_events, ts, out_x[j], out_z[j], out_mode[j],
                *(a[0] for a in events), state[j],
            )
        else:
            k.trajectories(
                *consts, Z0, X0, t_end, max_events, ts, out_x, out_z, out_mode, *events, state, status, n_ev, t_stop, rows
            )


def _fit(a: np.ndarray, width: int, fill) -> np.ndarray:
    """``a`` with its event axis (axis 1) cut or padded with ``fill`` to ``width``."""
    if a.shape[1] > width:
        return a[:, :width]
    if a.shape[1] < width:
        pad = [(0, 0)] * a.ndim
        pad[1] = (0, width - a.shape[1])
        return np.pad(a, pad, constant_values=fill)
    return a


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
    model = _slip_model(params)
    Z0 = np.ascontiguousarray(Z0, dtype=float)
    X0 = np.empty_like(Z0)  # filled by the kernel: T z0
    ts = np.ascontiguousarray(ts, dtype=float)
    k = kernel(work=Z0.shape[0] * (ts.size + 2 * _FIRST_ROOM))
    is_plain = k is plain()
    consts = model.constants(not is_plain)
    start = time.perf_counter()
    n, m = Z0.shape[0], ts.size
    x, z = np.empty((2, n, m, 3))
    out = [x, z, np.empty((n, m), dtype=np.int8), np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64), np.empty(n)]
    state = np.zeros((n, S_SIZE))
    room = _first_room(consts[0], t_end, max_events)
    rows = np.arange(n)
    events = _event_buffers(n, room)
    _kernel_call(consts, k, Z0, X0, t_end, max_events, ts, out, state, rows, events)
    first = events
    resumed = []  # (rows, their event buffers), round by round, of the trajectories that went on
    full = out[3] == BUFFER_FULL  # more events than the buffer had room for
    while full.any() and room < max_events:  # (a buffer of max_events slots is never full)
        # the full rows go on where they stopped, their events so far copied into larger buffers
        rows, events, filled = rows[full], [a[full] for a in events], room
        room = _next_room(room, out[4][rows], out[5][rows], t_end, max_events)
        check_memory(name="max_events", value=max_events, count=float(rows.size) * room, item_bytes=_EVENT_BYTES,
                     what=f"{rows.size} trajectories with more than {filled} events each", error=SimulationError)
        larger = _event_buffers(rows.size, room)
        for new, old in zip(larger, events):
            new[:, : old.shape[1]] = old
        events = larger
        _kernel_call(consts, k, Z0, X0, t_end, max_events, ts, out, state, rows, events)
        resumed.append((rows, events))
        full = out[3][rows] == BUFFER_FULL
    if is_plain:
        spent_in_plain(time.perf_counter() - start)
    n_ev = out[4]
    width = int(n_ev.max())
    fills = (np.nan, np.nan, 0, 0)  # the kernel's padding of ev_t, ev_x, ev_m, ev_res
    # the event axis, cut or padded to the most events of any row; a later round's rows overwrite an earlier one's
    ev = [_fit(a, width, fill) for a, fill in zip(first, fills)]
    for rows, events in resumed:
        for a, b, fill in zip(ev, events, fills):
            a[rows] = _fit(b, width, fill)
    x, z, mode, status, n_ev, t_stop = out
    ev_t, ev_x, ev_m, ev_res = ev
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
    model = _slip_model(params)
    m = ts.size
    k = kernel(work=m + 2 * _FIRST_ROOM)
    is_plain = k is plain()
    consts = model.constants(not is_plain)
    start = time.perf_counter()
    Z0 = np.array(z0, dtype=float).reshape(1, 3)
    X0 = np.empty((1, 3))
    ts = np.ascontiguousarray(ts, dtype=float)
    room = _first_room(consts[0], t_end, max_events)
    x, z = np.empty((2, 1, m, 3))  # one allocation, two C-contiguous halves
    mode = np.empty((1, m), dtype=np.int8)
    ev_t, ev_x, ev_m, ev_res = _event_buffers(1, room)
    state = np.zeros(S_SIZE)
    while True:
        if is_plain:
            with np.errstate(over="ignore", invalid="ignore"):  # overflow is reported as a status
                code, n, t_stop = k.trajectory(
                    *consts, Z0[0], X0[0], t_end, max_events, ts, x[0], z[0], mode[0],
                    ev_t[0], ev_x[0], ev_m[0], ev_res[0], state,
                )
        else:
            code, n, t_stop = k.trajectory(
                *consts, Z0[0], X0[0], t_end, max_events, ts, x[0], z[0], mode[0], ev_t[0], ev_x[0], ev_m[0], ev_res[0], state
            )
        if code != BUFFER_FULL or room >= max_events:  # (a buffer of max_events slots is never full)
            break
        # go on where the kernel stopped, the events so far in a larger buffer (the comment at _FIRST_ROOM)
        room = _next_room(room, np.array([n]), np.array([t_stop]), t_end, max_events)
        larger = _event_buffers(1, room)
        for new, old in zip(larger, (ev_t, ev_x, ev_m, ev_res)):
            new[:, : old.shape[1]] = old
        ev_t, ev_x, ev_m, ev_res = larger
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
        _check_positive_int("max_events", options["max_events"], 1, MAX_EVENTS)
        _check_positive_int("grid_points", options["grid_points"], 2, MAX_GRID_POINTS)

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


_preloaded = False


def preload_compiled() -> None:
    """Make the compiled kernel's first call in this process, if a small call here would run it (:mod:`._jit`).

    numba loads a compiled function's machine code from its on-disk cache at the function's first call, in the
    process that makes it.  A process that simulates only in forked children (the extremes matrix: each run in a
    child, for its time limit) has every child load it again and throw it away: about 0.4 s a child (measured;
    0.02 s once the parent holds it).  One short run of Table I's case (a) makes the first call of the kernel's
    entry point, with the types every run passes; nothing is loaded while small calls get the plain kernel.
    """
    global _preloaded
    if _preloaded or kernel(0.0) is plain():
        return
    method = EventDriven()
    method._solve(Parameters.table_i("a"), np.array([0.0, 1.0, 0.0]), 1.0, np.linspace(0.0, 1.0, 3), method.options)
    _preloaded = True


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
