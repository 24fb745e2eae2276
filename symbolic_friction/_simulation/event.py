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
  resting on ``|x - x*_k|_P`` being nonincreasing with the paper's ``P``).
* After a slip, ``v`` is set to exactly 0 and the next mode is selected with
  :func:`.modes.mode_after_slip`: a tolerance-free clamp (a slip in direction
  ``k`` can only end with ``k·φ ≤ f_c``), then ``φ`` within a few ulps of
  ``±f_c`` is snapped so that ``σ`` decides as rows (iii)/(v)/(vii)/(ix) do.
  A grazing contact (row (iii)/(ix) again) continues the slip without an
  event.  ``max_events`` caps the number of mode changes
  (:attr:`Status.MAX_EVENTS`; later samples are omitted), so rounding at a
  switching surface can never make the method spin forever.

Only numpy and the standard library are imported (no scipy, no sympy).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._coordinates import x_to_z, z_to_x
from .._errors import SimulationError
from .._parameters import Parameters
from ._base import SimulationMethod, Solution, Status
from .modes import mode_after_slip, select_mode, snap_to_boundary
from .search import first_zero, slip_model

__all__ = ["EventDriven", "Segment", "integrate_events", "sample_segments", "initial_mode"]

_EPS = 2.220446049250313e-16
# ulps allowed between a computed φ and ±f_c before σ decides (rows iii/v/vii/ix)
_SNAP_ULPS = 8.0


def _check_positive_int(name: str, value: Any, minimum: int) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise SimulationError(f"{name} must be an integer ≥ {minimum}; got {value!r}")


# ---------------------------------------------------------------------------
# The event loop and dense output
# ---------------------------------------------------------------------------
Segment = tuple[float, float, int, tuple[float, float, float]]
"""``(t_start, t_stop, mode, x_start)`` of one closed-form piece."""


def initial_mode(params: Parameters, z0: np.ndarray, x0: np.ndarray) -> tuple[np.ndarray, int]:
    """Snap ``φ(0)`` within rounding of ``±f_c`` (only if ``v(0) = 0``) and select the mode."""
    k_p, k_i, _, f_c = params.as_floats()
    x0 = np.array(x0, dtype=float)
    if x0[2] == 0.0:
        tol = _SNAP_ULPS * _EPS * (f_c + k_i * abs(z0[0]) + k_p * abs(z0[1]))
        x0[1] = snap_to_boundary(float(x0[1]), f_c, tol)
    return x0, select_mode(float(x0[0]), float(x0[1]), float(x0[2]), f_c)


def integrate_events(
    params: Parameters, z0: np.ndarray, t_end: float, *, max_events: int
) -> tuple[list[Segment], list[tuple[float, int, int]], str]:
    """Run the event loop from ``z0`` on ``[0, t_end]``.

    Returns the closed-form segments (contiguous, the last one ends at the
    stopping time), the events ``(t, mode_before, mode_after)`` and the status.
    """
    model = slip_model(params)
    f_c = model.f_c
    x, mode = initial_mode(params, z0, z_to_x(params, z0))
    state = (float(x[0]), float(x[1]), float(x[2]))
    t = 0.0
    segments: list[Segment] = []
    events: list[tuple[float, int, int]] = []
    status = Status.T_END
    # grazing contacts continue a slip without an event; bound the loop anyway
    for _ in range(4 * max_events + 16):
        sigma, phi, v = state
        if mode == 0:
            if sigma == 0.0:
                segments.append((t, t_end, 0, state))
                status = Status.EQUILIBRIUM
                break
            d = 1 if sigma > 0.0 else -1
            t_next = t + (d * f_c - phi) / sigma
            if t_next >= t_end:
                segments.append((t, t_end, 0, state))
                break
            segments.append((t, t_next, 0, state))
            t, state, mode = t_next, (sigma, d * f_c, 0.0), d
            events.append((t, 0, d))
        else:
            d = mode
            star = d * f_c
            y0 = (sigma, phi - star, v)
            tau, y = first_zero(model, y0, d, t_end - t)
            if tau is None:
                segments.append((t, t_end, d, state))
                break
            t_next = t + tau
            segments.append((t, t_next, d, state))
            tol = _SNAP_ULPS * _EPS * (f_c + max(abs(c) for c in y0))
            phi_end, new_mode = mode_after_slip(y[0], y[1] + star, d, f_c, tol)
            t, state = t_next, (y[0], phi_end, 0.0)
            if new_mode != d:
                events.append((t, d, new_mode))
                mode = new_mode
            if t >= t_end:
                segments.append((t, t_end, mode, state))
                break
        if len(events) >= max_events:
            segments.append((t, t, mode, state))
            status = Status.MAX_EVENTS
            break
    else:
        segments.append((t, t, mode, state))
        status = Status.MAX_EVENTS
    return segments, events, status


def sample_segments(
    params: Parameters, segments: list[Segment], t: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """States ``x`` (shape (n, 3)) and modes at sorted times ``t`` within the segments.

    A time equal to an event time belongs to the segment that starts there.
    All slip samples share one evaluation of ``w, w', w''`` (the closed form
    of :mod:`.affine`), whatever segment they fall in.
    """
    model = slip_model(params)
    expm, f_c = model.expm, model.f_c
    starts = np.array([seg[0] for seg in segments])
    modes = np.array([seg[2] for seg in segments], dtype=np.int8)
    x_start = np.array([seg[3] for seg in segments], dtype=float).reshape(-1, 3)
    which = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(segments) - 1)
    tau = t - starts[which]
    mode = modes[which]
    x = np.empty((t.size, 3))
    stick = mode == 0
    xs = x_start[which[stick]]
    x[stick, 0] = xs[:, 0]
    x[stick, 1] = xs[:, 1] + xs[:, 0] * tau[stick]
    x[stick, 2] = 0.0
    slip = ~stick
    if slip.any():
        seg = which[slip]
        d = modes[seg].astype(float)
        y0 = x_start[seg].copy()
        y0[:, 1] -= d * f_c
        w0, w1, w2 = expm.w(tau[slip])
        b1, b2 = expm.B1, expm.B2
        for k in range(3):
            comp = w2 * y0[:, k]
            comp += w1 * (b1[k, 0] * y0[:, 0] + b1[k, 1] * y0[:, 1] + b1[k, 2] * y0[:, 2])
            comp += w0 * (b2[k, 0] * y0[:, 0] + b2[k, 1] * y0[:, 1] + b2[k, 2] * y0[:, 2])
            if k == 1:
                comp += d * f_c
            elif k == 2:
                # the closed form keeps v's sign up to rounding; the mode fixes it
                comp = d * np.maximum(d * comp, 0.0)
            x[slip, k] = comp
    return x, mode


class EventDriven(SimulationMethod):
    """Exact event-driven simulation (closed-form flows, exact mode table).

    Options
    -------
    max_events : int, default 10_000
        Stop (status ``MAX_EVENTS``) after this many mode changes.
    grid_points : int, default 1001
        Without ``t_eval``: number of equally spaced samples on ``[0, t_end]``,
        to which every event time is added.
    """

    name = "event"
    options = {"max_events": 10_000, "grid_points": 1001}

    def _validate(self, options: dict[str, Any]) -> None:
        _check_positive_int("max_events", options["max_events"], 1)
        _check_positive_int("grid_points", options["grid_points"], 2)

    def _solve(
        self, params: Parameters, z0: np.ndarray, t_end: float, t_eval: np.ndarray | None, options: dict[str, Any]
    ) -> Solution:
        segments, events, status = integrate_events(params, z0, t_end, max_events=int(options["max_events"]))
        t_stop = segments[-1][1]
        if t_eval is None:
            grid = np.linspace(0.0, t_stop, int(options["grid_points"]))
            t = np.unique(np.concatenate([grid, [e[0] for e in events]]))
        else:
            t = t_eval[t_eval <= t_stop] if status == Status.MAX_EVENTS else t_eval
        x, mode = sample_segments(params, segments, t)
        z = x_to_z(params, x)
        z[t == 0.0] = z0  # the given state, not its round trip through x
        return Solution(
            params=params,
            method=self.name,
            t=t,
            z=z,
            mode=mode,
            events=tuple(events),
            status=status,
            options=dict(options),
        )
