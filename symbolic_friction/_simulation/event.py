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
  ``±f_c`` counts as on it, so that ``σ`` decides as rows (iii)/(v)/(vii)/(ix)
  do.  ``φ`` is carried as an exact boundary plus an offset, so a stick after
  a tiny slip gets its exact duration ``-offset/σ``.
  A grazing contact (row (iii)/(ix) again) continues the slip without an
  event.  A slip that decays to within 1e-280 of its equilibrium
  ``(0, ±f_c, 0) ∈ 𝒜`` (where double precision underflows) is put on it:
  an equilibrium.  ``max_events`` caps the number of mode changes
  (:attr:`Status.MAX_EVENTS`; later samples are omitted), so rounding at a
  switching surface can never make the method spin forever.

Only numpy and the standard library are imported (no scipy, no sympy).
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Any, NamedTuple

import numpy as np

from .._coordinates import x_to_z, z_to_x
from .._errors import SimulationError
from .._parameters import Parameters
from ._base import SimulationMethod, Solution, Status
from .modes import mode_after_slip, mode_at_rest
from .search import UNDERFLOW, first_zero, slip_model

__all__ = ["EventDriven", "Segment", "integrate_events", "sample_segments", "initial_state"]

_EPS = 2.220446049250313e-16
# ulps allowed between a computed φ and ±f_c before σ decides (rows iii/v/vii/ix)
_SNAP_ULPS = 8.0


def _check_positive_int(name: str, value: Any, minimum: int) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise SimulationError(f"{name} must be an integer ≥ {minimum}; got {value!r}")


# ---------------------------------------------------------------------------
# The event loop and dense output
# ---------------------------------------------------------------------------
class Segment(NamedTuple):
    """One closed-form piece: mode ``k`` on ``[t0, t1]`` from ``(σ, φ, v)``.

    ``φ = base·f_c + offset`` with ``base ∈ {-1, 0, 1}``: keeping the exact
    boundary apart from the offset preserves ``φ ∓ f_c`` exactly (see
    :func:`.modes.mode_at_rest`).
    """

    t0: float
    t1: float
    mode: int
    sigma: float
    base: int
    offset: float
    v: float


def initial_state(params: Parameters, z0: np.ndarray) -> tuple[float, int, float, float, int]:
    """``(σ, base, offset, v, mode)`` at ``t = 0``; ``φ(0)`` within its rounding of ``±f_c`` counts as on it."""
    k_p, k_i, _, f_c = params.as_floats()
    sigma, phi, v = (float(c) for c in z_to_x(params, z0))
    if v != 0.0:
        return sigma, 0, phi, v, 1 if v > 0 else -1
    # φ = -k_i e_i - k_p s is rounded: a few ulps of its terms
    tol = _SNAP_ULPS * _EPS * (k_i * abs(float(z0[0])) + k_p * abs(float(z0[1])))
    base, offset, mode = mode_at_rest(sigma, 0, phi, f_c, tol)
    return sigma, base, offset, 0.0, mode


def integrate_events(
    params: Parameters, z0: np.ndarray, t_end: float, *, max_events: int
) -> tuple[list[Segment], list[tuple[float, int, int]], str]:
    """Run the event loop from ``z0`` on ``[0, t_end]``.

    Returns the closed-form segments (contiguous, the last one ends at the
    stopping time), the events ``(t, mode_before, mode_after)`` and the status.
    """
    model = slip_model(params)
    f_c = model.f_c
    sigma, base, offset, v, mode = initial_state(params, z0)
    t = 0.0
    segments: list[Segment] = []
    events: list[tuple[float, int, int]] = []
    status = Status.T_END
    # grazing contacts continue a slip without an event; bound the loop anyway
    for _ in range(4 * max_events + 16):
        if mode == 0:
            if sigma == 0.0:
                segments.append(Segment(t, t_end, 0, sigma, base, offset, v))
                status = Status.EQUILIBRIUM
                break
            d = 1 if sigma > 0.0 else -1
            # distance to the exit d·f_c: exactly -offset when leaving where the last slip ended
            gap = -offset if base == d else (d - base) * f_c - offset
            t_next = t + gap / sigma
            segments.append(Segment(t, min(t_next, t_end), 0, sigma, base, offset, v))
            if t_next >= t_end:
                break
            t, base, offset, mode = t_next, d, 0.0, d  # rows (iii)/(ix): slip d
            events.append((t, 0, d))
        else:
            d = mode
            y0 = (sigma, offset if base == d else (base - d) * f_c + offset, v)
            tau, y = first_zero(model, y0, d, t_end - t)
            if tau is None:
                segments.append(Segment(t, t_end, d, sigma, base, offset, v))
                break
            t_next = t + tau
            segments.append(Segment(t, t_next, d, sigma, base, offset, v))
            if max(abs(c) for c in y) <= UNDERFLOW:  # decayed onto x*_k ∈ 𝒜 (see search.UNDERFLOW)
                y = (0.0, 0.0, 0.0)
            tol = _SNAP_ULPS * _EPS * max(abs(c) for c in y0)
            base, offset, new_mode = mode_after_slip(y[0], y[1], d, f_c, tol)
            t, sigma, v = t_next, y[0], 0.0
            if new_mode != d:
                events.append((t, d, new_mode))
                mode = new_mode
            if t >= t_end:
                segments.append(Segment(t, t_end, mode, sigma, base, offset, v))
                break
        if len(events) >= max_events:
            segments.append(Segment(t, t, mode, sigma, base, offset, v))
            status = Status.MAX_EVENTS
            break
    else:
        segments.append(Segment(t, t, mode, sigma, base, offset, v))
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
    seg = np.array([s[:1] + s[3:] for s in segments], dtype=float)  # t0, σ, base, offset, v
    modes = np.array([s.mode for s in segments], dtype=np.int8)
    which = np.clip(np.searchsorted(seg[:, 0], t, side="right") - 1, 0, len(segments) - 1)
    tau = t - seg[which, 0]
    mode = modes[which]
    x = np.empty((t.size, 3))
    stick = mode == 0
    rows = seg[which[stick]]
    x[stick, 0] = rows[:, 1]
    x[stick, 1] = rows[:, 2] * f_c + (rows[:, 3] + rows[:, 1] * tau[stick])
    x[stick, 2] = 0.0
    slip = ~stick
    if slip.any():
        rows = seg[which[slip]]
        d = modes[which[slip]].astype(float)
        # offsets from the slip equilibrium (0, d f_c, 0); exact when base = d
        p_off = np.where(rows[:, 2] == d, rows[:, 3], (rows[:, 2] - d) * f_c + rows[:, 3])
        y0 = np.column_stack([rows[:, 1], p_off, rows[:, 4]])
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
    options = MappingProxyType({"max_events": 10_000, "grid_points": 1001})

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
