"""What the speed–accuracy study measures: one point per method and knob, the curves, the fitted order and the report (measured against the 50-digit reference, :mod:`symbolic_friction._reference`)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Sequence

import numpy as np

from .._model.parameters import Parameters

__all__ = ["Point", "Curve", "Tradeoff", "CostPoint", "fit_order", "FIT_FLOOR", "LEVELS"]


# below this relative error a knob no longer controls the error (float64 rounding): left out of the order fit
FIT_FLOOR = 1e-11


# the error levels at which the cheapest method is named in the closing note
LEVELS = (1e-2, 1e-4, 1e-6, 1e-8)


@dataclass(frozen=True)
class Point:
    """One configuration of one method, measured.

    Errors are relative to the solution's size (state, final) or in seconds
    (stick); ``refused`` holds the method's reason when it refused or stopped
    early, and then the errors are NaN.
    """

    label: str
    method: str
    knob: str | None
    value: float | None
    config: str
    error_state: float
    error_final: float
    error_stick: float
    sticks: int
    time_median: float
    time_min: float
    time_max: float
    repeats: int
    refused: str | None = None

    @property
    def ok(self) -> bool:
        return self.refused is None

    def as_dict(self) -> dict[str, Any]:
        d = dict(self.__dict__)
        for key in ("error_state", "error_final", "error_stick"):
            d[key] = _json_float(d[key])
        return d


@dataclass(frozen=True)
class Curve:
    """The points of one sweep and the order of accuracy fitted from them."""

    label: str
    knob: str | None
    declared_order: float
    points: tuple[Point, ...]
    fitted_order: float | None
    fit_points: int

    def as_dict(self) -> dict[str, Any]:
        return {
            "label": self.label,
            "knob": self.knob,
            "declared_order": _json_float(self.declared_order),
            "fitted_order": self.fitted_order,
            "fit_points": self.fit_points,
            "points": [p.as_dict() for p in self.points],
        }


def _json_float(x: float) -> float | str | None:
    if x is None:
        return None
    if math.isnan(x):
        return None
    if math.isinf(x):
        return "inf"
    return float(x)


def fit_order(values: Sequence[float], errors: Sequence[float]) -> tuple[float | None, int]:
    """Slope of ``log error`` against ``log knob`` (least squares) over errors above :data:`FIT_FLOOR`.

    Returns ``(order, points used)``; ``None`` with fewer than two points.
    """
    pairs = [(v, e) for v, e in zip(values, errors) if v and v > 0 and math.isfinite(e) and e > FIT_FLOOR]
    if len(pairs) < 2:
        return None, len(pairs)
    x = np.log10([p[0] for p in pairs])
    y = np.log10([p[1] for p in pairs])
    slope = float(np.polyfit(x, y, 1)[0])
    return slope, len(pairs)


@dataclass(frozen=True)
class Tradeoff:
    """The measured trade: the curves, the setting, and what the reference said."""

    params: Parameters
    label: str
    z0s: tuple[tuple[float, float, float], ...]
    t_end: float
    samples: int
    curves: tuple[Curve, ...]
    reference_sticks: tuple[int, ...]
    reference_seconds: float
    cost: tuple[CostPoint, ...] = field(default=())
    kernel: str = ""  # the event kernel the timings used: "numba" (compiled) or "python"

    def __repr__(self) -> str:
        # a summary; the curves are in .curves and in the report
        points = sum(len(c.points) for c in self.curves)
        return (f"Tradeoff({self.label!r}, {len(self.z0s)} initial state(s), t_end = {self.t_end:g}, "
                f"{len(self.curves)} methods, {points} configurations)")

    @property
    def event(self) -> Point:
        return next(c for c in self.curves if c.label == "event").points[0]

    def others(self) -> list[Point]:
        return [p for c in self.curves if c.label != "event" for p in c.points if p.ok]

    def pareto(self) -> dict[str, list[Point]]:
        """Per method, the points not beaten in both time and state error by another point of the same method."""
        front: dict[str, list[Point]] = {}
        for c in self.curves:
            pts = sorted((p for p in c.points if p.ok), key=lambda p: p.time_median)
            keep, best = [], math.inf
            for p in pts:
                if p.error_state < best:
                    keep.append(p)
                    best = p.error_state
            front[c.label] = keep
        return front

    def cheapest_other(self, level: float) -> Point | None:
        """The fastest non-event point whose state error is at most ``level``."""
        cands = [p for p in self.others() if p.error_state <= level]
        return min(cands, key=lambda p: p.time_median) if cands else None

    def equal_error(self) -> dict[str, Any]:
        """The speed ratio of ``event`` against the best other method at equal error.

        The comparison level is the smallest error any other method reached
        (``event`` reaches it too, or the comparison says it does not); the
        ratio is that method's cheapest time at or below the level over the
        event time.  The same at the fixed :data:`LEVELS`.
        """
        ev = self.event
        others = self.others()
        out: dict[str, Any] = {"event_error": ev.error_state, "event_time": ev.time_median, "levels": []}
        if not others or not ev.ok:
            return out
        best = min(p.error_state for p in others)
        levels = [lvl for lvl in LEVELS if lvl > best] + [max(best, ev.error_state)]
        for lvl in levels:
            p = self.cheapest_other(lvl)
            if p is None:
                continue
            out["levels"].append(
                {
                    "level": lvl,
                    "event_reaches": ev.error_state <= lvl,
                    "method": p.label,
                    "config": p.config,
                    "error": p.error_state,
                    "time": p.time_median,
                    "ratio": p.time_median / ev.time_median,
                }
            )
        return out

    # -- output ---------------------------------------------------------------
    def table(self) -> str:
        """The text table: one row per configuration."""
        k_p, k_i, k_v, f_c = (str(q) for q in (self.params.k_p, self.params.k_i, self.params.k_v, self.params.f_c))
        lines = [
            f"{self.label}: k_p = {k_p}, k_i = {k_i}, k_v = {k_v}, f_c = {f_c}; "
            f"{len(self.z0s)} initial state(s) {', '.join(_fmt_state(z) for z in self.z0s)}; "
            f"t in [0, {self.t_end:g}], {self.samples} sample times",
            f"reference: mpmath, 50 digits, stick phases per initial state {list(self.reference_sticks)} "
            f"({self.reference_seconds:.1f} s)",
            "errors relative to max_t |z_ref(t)|; stick: largest shift of a stick start [s] (inf: a stick missed or added)",
            "",
            f"{'method':18s} {'knob':>14s} {'state err':>10s} {'final err':>10s} {'stick err':>10s} "
            f"{'time/traj':>10s} {'spread (min-max)':>19s}",
        ]
        for c in self.curves:
            for p in c.points:
                knob = "(exact)" if p.knob is None else f"{p.knob}={p.value:g}"
                if not p.ok:
                    lines.append(f"{p.label:18s} {knob:>14s}  refused: {p.refused}")
                    continue
                lines.append(
                    f"{p.label:18s} {knob:>14s} {p.error_state:10.2e} {p.error_final:10.2e} {p.error_stick:10.2e} "
                    f"{_fmt_time(p.time_median):>10s} {_fmt_time(p.time_min):>9s}-{_fmt_time(p.time_max):<9s}"
                )
        lines.append("")
        lines.append("fitted order of accuracy (slope of log state error vs log knob) against the declared one:")
        for c in self.curves:
            if c.knob is None:
                lines.append(f"  {c.label:18s} exact (no knob), state error {self.event.error_state:.1e}"
                             + (f", {self.kernel} kernel" if self.kernel else ""))
                continue
            fitted = "n/a" if c.fitted_order is None else f"{c.fitted_order:.2f}"
            lines.append(f"  {c.label:18s} in {c.knob}: fitted {fitted} over {c.fit_points} points, declared {c.declared_order:g}")
        return "\n".join(lines)

    def note(self) -> str:
        """The closing note: Pareto points, fitted orders, the event speed ratio at equal error."""
        lines = ["Pareto points (time per trajectory, state error):"]
        for label, pts in self.pareto().items():
            pts_s = ", ".join(f"({_fmt_time(p.time_median)}, {p.error_state:.1e})" for p in pts)
            lines.append(f"  {label:18s} {pts_s}")
        orders = ", ".join(
            f"{c.label} {c.fitted_order:.2f}" for c in self.curves if c.fitted_order is not None
        )
        lines.append(f"fitted orders: {orders}")
        eq = self.equal_error()
        ev = self.event
        for lvl in eq["levels"]:
            reach = "" if lvl["event_reaches"] else " (event does NOT reach it)"
            lines.append(
                f"at state error <= {lvl['level']:.1e}: fastest other method {lvl['config']} "
                f"{_fmt_time(lvl['time'])} (error {lvl['error']:.1e}); event {_fmt_time(ev.time_median)} "
                f"(error {ev.error_state:.1e}): event is {lvl['ratio']:.3g}x faster{reach}"
            )
        return "\n".join(lines)

    def as_dict(self) -> dict[str, Any]:
        return {
            "label": self.label,
            "params": self.params.as_strings(),
            "z0": [list(z) for z in self.z0s],
            "t_end": self.t_end,
            "samples": self.samples,
            "reference": {"dps": 50, "sticks": list(self.reference_sticks), "seconds": self.reference_seconds},
            "curves": [c.as_dict() for c in self.curves],
            "pareto": {k: [p.config for p in v] for k, v in self.pareto().items()},
            "equal_error": self.equal_error(),
            "cost": [c.__dict__ for c in self.cost],
        }


def _fmt_state(z: Sequence[float]) -> str:
    return "(" + ", ".join(f"{float(c):g}" for c in z) + ")"


def _fmt_time(seconds: float) -> str:
    if seconds >= 1:
        return f"{seconds:.2f} s"
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds * 1e6:.0f} us"


# -------------------------------------------------------------------- cost vs T and N
@dataclass(frozen=True)
class CostPoint:
    """Wall time (median of repeats) of ``n`` trajectories over ``[0, t_end]`` with one configuration."""

    config: str
    axis: str  # "T" or "N"
    t_end: float
    n: int
    seconds: float
    seconds_min: float
    seconds_max: float
    kernel: str = ""  # event only: "python" or "numba", the kernel variant the run used
