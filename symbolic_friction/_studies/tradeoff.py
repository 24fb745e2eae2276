"""The speed/accuracy trade of the simulation methods, measured against the
independent 50-digit reference (:mod:`._reference`) of the inclusion
``x' ∈ A x - b SGN(v)`` (eq. xDot, unique by Lemma 1).

For one gain set and a few initial states, every method runs across its
accuracy knob (:attr:`~._simulation.SimulationMethod.knob`: the Moreau step
``h``, the regularisation width ``ε`` for both laws, the ``solve_ivp``
tolerance ``rtol``; the exact ``event`` method has none).  Each
configuration gets

* three errors against the reference, relative to the solution's size
  ``max_t |z_ref(t)|∞``: the sup over the sample times of ``|z - z_ref|∞``
  (*state*), the same at ``t_end`` (*final*), and the largest shift of the
  stick start times of Claim 1 (*stick*, in seconds; ``inf`` when the method
  finds a different number of stick phases);
* the wall time per trajectory: the median of ``repeats`` runs, with the
  fastest and slowest;
* per method, the order of accuracy fitted from the data (least squares of
  ``log error`` against ``log knob``), next to the declared
  :attr:`~._simulation.SimulationMethod.order`.

:func:`measure_cost` adds how the cost grows with the horizon ``T`` and the
batch size ``N``.  :func:`tradeoff_figures` draws the Pareto front (error
against time, log–log, one curve per method) and the cost figure.  A method
that refuses (``SimulationError``) or stops early is reported as such, never
as a number.
"""

from __future__ import annotations

import math
import statistics
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from .._infra.errors import SimulationError, UsageError
from .._model.parameters import Parameters

__all__ = [
    "Sweep",
    "Point",
    "Curve",
    "Tradeoff",
    "CostPoint",
    "default_sweeps",
    "measure_tradeoff",
    "measure_cost",
    "tradeoff_figures",
    "FIGURE_FORMATS",
]

FIGURE_FORMATS = ("png", "pdf", "svg")
# below this relative error a knob no longer controls the error (float64 rounding): left out of the order fit
FIT_FLOOR = 1e-11
# the error levels at which the cheapest method is named in the closing note
LEVELS = (1e-2, 1e-4, 1e-6, 1e-8)


@dataclass(frozen=True)
class Sweep:
    """One method's curve: a label and the configured methods along its knob (coarse to fine)."""

    label: str
    methods: tuple[Any, ...]


def default_sweeps(scale: float = 1.0, *, quick: bool = False) -> list[Sweep]:
    """The knobs swept by ``symbolic-friction tradeoff``.

    ``scale`` (the size of the initial states) sets the absolute tolerances,
    so that the relative tolerance decides.  The regularised ODE is solved
    with tight tolerances so that ``ε`` alone sets its error.
    """
    from .._simulation import EventDriven, IvpEvents, Moreau, Regularized

    hs = (1e-1, 1e-2, 1e-3) if quick else (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4)
    eps = (1e-1, 1e-2, 1e-3) if quick else (1e-1, 1e-2, 1e-3, 1e-4, 1e-5)
    rtols = (1e-4, 1e-7, 1e-10) if quick else (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)
    atol = 1e-12 * scale
    return [
        Sweep("event", (EventDriven(),)),
        Sweep("moreau", tuple(Moreau(h=h) for h in hs)),
        Sweep("regularized tanh", tuple(Regularized(epsilon=e, law="tanh", rtol=1e-10, atol=atol) for e in eps)),
        Sweep("regularized sat", tuple(Regularized(epsilon=e, law="sat", rtol=1e-10, atol=atol) for e in eps)),
        Sweep("ivp-events", tuple(IvpEvents(rtol=r, atol=r * 1e-3 * scale) for r in rtols)),
    ]


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
    cost: tuple["CostPoint", ...] = field(default=())
    kernel: str = ""  # the event kernel the timings used: "numba" (compiled) or "python"

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


# -------------------------------------------------------------------- measuring
@dataclass
class _Ref:
    times: np.ndarray
    z: np.ndarray
    scale: float
    sticks: list[float]


def _reference(params: Parameters, z0: Sequence[float], t_end: float, times: np.ndarray) -> _Ref:
    from .._reference import Reference

    ref = Reference(params, z0, t_end)
    zs, _ = ref.sample(times)
    z = np.array(zs, dtype=float)
    scale = float(max(np.max(np.abs(z)), max(abs(float(c)) for c in z0)))
    return _Ref(times, z, scale if scale > 0 else 1.0, ref.stick_starts())


def _stick_starts(sol: Any) -> list[float]:
    return [t for t, a, b in sol.events if b == 0 and a != 0]


def _errors(sol: Any, ref: _Ref) -> tuple[float, float, float, int]:
    if sol.t.size != ref.times.size:
        raise SimulationError(f"{sol.method} returned {sol.t.size} of {ref.times.size} samples")
    diff = np.abs(sol.z - ref.z)
    state = float(np.max(diff)) / ref.scale
    final = float(np.max(diff[-1])) / ref.scale
    got = _stick_starts(sol)
    if len(got) != len(ref.sticks):
        stick = math.inf
    else:
        stick = max((abs(a - b) for a, b in zip(got, ref.sticks)), default=0.0)
    return state, final, stick, len(got)


def _timed(run: Any, repeats: int, budget: float) -> list[float]:
    times = []
    spent = 0.0
    for _ in range(repeats):
        t0 = time.perf_counter()
        run()
        dt = time.perf_counter() - t0
        times.append(dt)
        spent += dt
        if spent > budget and len(times) >= 3:
            break
    return times


def measure_tradeoff(
    params: Parameters,
    z0s: Sequence[Sequence[float]],
    t_end: float,
    *,
    label: str = "user gains",
    samples: int = 301,
    repeats: int = 7,
    sweeps: Sequence[Sweep] | None = None,
    budget: float = 2.0,
    quick: bool = False,
) -> Tradeoff:
    """Measure every configuration of ``sweeps`` (default :func:`default_sweeps`) from each of ``z0s``.

    Parameters
    ----------
    params : Parameters
    z0s : sequence of (e_i, s, v)
    t_end : float
    label : str, keyword-only
        A name for the gain set in the report.
    samples : int, keyword-only
        Equally spaced sample times on ``[0, t_end]`` where the state error is measured.
    repeats : int, keyword-only
        Timed runs per configuration (fewer once a configuration spent ``budget`` seconds, at least 3).
    budget : float, keyword-only
    quick : bool, keyword-only
        Three knob values per method (for tests).
    """
    from .._simulation import simulate

    if not z0s:
        raise UsageError("tradeoff needs at least one initial state")
    if samples < 2:
        raise UsageError(f"tradeoff needs at least 2 sample times; got {samples}")
    if repeats < 1:
        raise UsageError(f"tradeoff needs at least 1 repeat; got {repeats}")
    z0s = tuple(tuple(float(c) for c in z) for z in z0s)
    for z in z0s:
        if len(z) != 3 or not all(map(math.isfinite, z)):
            raise UsageError(f"an initial state is three finite numbers (e_i, s, v); got {z}")
    times = np.linspace(0.0, float(t_end), int(samples))
    t0 = time.perf_counter()
    refs = [_reference(params, z, t_end, times) for z in z0s]
    ref_seconds = time.perf_counter() - t0
    scale = max(max(abs(c) for c in z) for z in z0s) or 1.0
    if sweeps is None:
        sweeps = default_sweeps(scale, quick=quick)
    # Steady state: the compiled event kernel when numba is there and allowed (the automatic
    # choice would run calls this small in plain Python until 3 s were spent there, mid-measurement).
    from .._simulation import _jit

    if _jit.jit_enabled():
        _jit.compiled()
    # warm up: compile/import each method once, outside the timings
    for sweep in sweeps:
        try:
            simulate(params, z0s[0], min(1.0, t_end), method=sweep.methods[-1], t_eval=times[times <= min(1.0, t_end)])
        except SimulationError:
            pass
    curves = []
    for sweep in sweeps:
        pts = []
        for method in sweep.methods:
            pts.append(_measure_point(params, z0s, t_end, times, refs, sweep.label, method, repeats, budget))
        knob = type(sweep.methods[0]).knob
        order, n = fit_order([p.value for p in pts if p.ok], [p.error_state for p in pts if p.ok])
        curves.append(Curve(sweep.label, knob, type(sweep.methods[0]).order, tuple(pts), order, n))
    return Tradeoff(
        kernel=_jit.variant(),
        params=params,
        label=label,
        z0s=z0s,
        t_end=float(t_end),
        samples=int(samples),
        curves=tuple(curves),
        reference_sticks=tuple(len(r.sticks) for r in refs),
        reference_seconds=ref_seconds,
    )


def _measure_point(params, z0s, t_end, times, refs, label, method, repeats, budget) -> Point:
    from .._simulation import Status, simulate

    knob = type(method).knob
    value = None if knob is None else float(getattr(method, knob))
    config = _config(method)
    nan = math.nan
    errs = []
    try:
        for z, ref in zip(z0s, refs):
            sol = simulate(params, z, t_end, method=method, t_eval=times)
            if sol.status not in Status.COMPLETE:
                raise SimulationError(f"stopped early: {sol.status} at t = {sol.t_stop:g}")
            errs.append(_errors(sol, ref))
    except SimulationError as exc:
        return Point(label, type(method).name, knob, value, config, nan, nan, nan, 0, nan, nan, nan, 0, str(exc))

    def run() -> None:
        for z in z0s:
            simulate(params, z, t_end, method=method, t_eval=times)

    per = [dt / len(z0s) for dt in _timed(run, repeats, budget)]
    return Point(
        label=label,
        method=type(method).name,
        knob=knob,
        value=value,
        config=config,
        error_state=max(e[0] for e in errs),
        error_final=max(e[1] for e in errs),
        error_stick=max(e[2] for e in errs),
        sticks=sum(e[3] for e in errs),
        time_median=statistics.median(per),
        time_min=min(per),
        time_max=max(per),
        repeats=len(per),
    )


def _config(method: Any) -> str:
    knob = type(method).knob
    name = type(method).name
    if knob is None:
        return name
    extra = f", {method.law}" if name == "regularized" else ""
    return f"{name}({knob}={getattr(method, knob):g}{extra})"


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


def measure_cost(
    params: Parameters,
    z0: Sequence[float],
    *,
    horizons: Sequence[float] = (3.0, 10.0, 30.0, 100.0, 300.0),
    sizes: Sequence[int] = (1, 10, 100, 1000, 10000),
    t_batch: float = 30.0,
    samples: int = 301,
    repeats: int = 3,
    budget: float = 3.0,
) -> tuple[CostPoint, ...]:
    """How the cost grows with the horizon ``T`` (one trajectory) and the batch size ``N``.

    ``event`` runs a batch with :func:`simulate_batch` (the kernel in
    parallel); the other methods have no batch path and run ``N`` times.  A
    configuration stops growing once the next measurement would exceed
    four times ``budget`` seconds (the cost grows about linearly).  The
    initial states of a batch are ``z0`` scaled by factors in ``[0.5, 1.5]``
    (a fixed seed).
    """
    from .._simulation import EventDriven, IvpEvents, Moreau, Regularized, simulate, simulate_batch

    scale = max(abs(float(c)) for c in z0) or 1.0
    configs = [
        EventDriven(),
        Moreau(h=1e-3),
        IvpEvents(rtol=1e-8, atol=1e-11 * scale),
        Regularized(epsilon=1e-4, rtol=1e-8, atol=1e-10 * scale),
    ]
    out: list[CostPoint] = []
    for method in configs:
        simulate(params, z0, 1.0, method=method)  # warm up
        for T in horizons:
            ts = np.linspace(0.0, T, samples)
            try:
                per = _timed(lambda: simulate(params, z0, T, method=method, t_eval=ts), repeats, budget)
            except SimulationError:
                break
            out.append(CostPoint(_config(method), "T", float(T), 1, statistics.median(per), min(per), max(per)))
            if statistics.median(per) * 3 > 4 * budget:  # the next horizon is about 3 times longer
                break
    rng = np.random.default_rng(12)
    ts = np.linspace(0.0, t_batch, samples)
    for method in configs:
        last: tuple[int, float] | None = None
        for n in sizes:
            if last is not None and last[1] * n / last[0] > 4 * budget:
                break  # the cost grows about linearly in N: the next size would far exceed the budget
            Z = np.asarray(z0, dtype=float) * rng.uniform(0.5, 1.5, size=(n, 1))
            kernel = ""
            if type(method).name == "event":
                from .._simulation._jit import variant

                run = lambda Z=Z: simulate_batch(params, Z, t_batch, t_eval=ts)  # noqa: E731
            else:
                run = lambda Z=Z, method=method: [simulate(params, z, t_batch, method=method, t_eval=ts) for z in Z]  # noqa: E731
            run()
            per = _timed(run, repeats, budget)
            if type(method).name == "event":  # the tier the timed runs used (plain Python for small work)
                kernel = variant(work=n * (samples + 64))
            out.append(CostPoint(_config(method), "N", t_batch, int(n), statistics.median(per), min(per), max(per), kernel))
            last = (n, statistics.median(per))
    return tuple(out)


# -------------------------------------------------------------------- figures
def check_formats(formats: Sequence[str]) -> tuple[str, ...]:
    """The figure formats asked for (``png`` always), refusing unknown ones."""
    bad = [f for f in formats if f not in FIGURE_FORMATS]
    if bad:
        raise UsageError(f"unknown figure format(s) {', '.join(map(repr, bad))}; expected some of {', '.join(FIGURE_FORMATS)}")
    return tuple(dict.fromkeys(("png", *formats)))


_STYLE = {
    "event": ("black", "*"),
    "moreau": ("tab:blue", "o"),
    "regularized tanh": ("tab:orange", "s"),
    "regularized sat": ("tab:red", "D"),
    "ivp-events": ("tab:green", "^"),
}


# where each curve writes its knob values, so that neighbouring curves do not overwrite each other
_OFFSET = {"regularized tanh": (-6, 5), "regularized sat": (6, -9)}


def tradeoff_figures(result: Tradeoff, out: Path, stem: str, formats: Sequence[str] = ("png",)) -> list[Path]:
    """The Pareto figure and (when measured) the cost figure; returns the files written."""
    from .figures import _pyplot, save_figure

    plt = _pyplot()
    formats = check_formats(formats)
    written: list[Path] = []
    fig, ax = plt.subplots(figsize=(7.2, 5.0))
    for c in result.curves:
        color, marker = _STYLE.get(c.label, ("grey", "x"))
        pts = [p for p in c.points if p.ok]
        if not pts:
            continue
        order = "" if c.fitted_order is None else f", fitted order {c.fitted_order:.2f} in {c.knob}"
        ax.plot([p.time_median for p in pts], [max(p.error_state, 1e-17) for p in pts], color=color, marker=marker,
                ms=9 if c.label == "event" else 5, lw=1.2, label=f"{c.label}{order}")
        ax.errorbar([p.time_median for p in pts], [max(p.error_state, 1e-17) for p in pts],
                    xerr=[[p.time_median - p.time_min for p in pts], [p.time_max - p.time_median for p in pts]],
                    fmt="none", ecolor=color, elinewidth=0.8, capsize=2)
        offset = _OFFSET.get(c.label, (4, 3))
        for p in pts:
            if p.knob is not None and p in (pts[0], pts[-1]):
                ax.annotate(f"{p.knob}={p.value:g}", (p.time_median, max(p.error_state, 1e-17)), fontsize=6,
                            textcoords="offset points", xytext=offset, color=color,
                            ha="left" if offset[0] > 0 else "right")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per trajectory [s] (median; bars: fastest–slowest of the repeats)")
    ax.set_ylabel(r"state error $\max_t |z-z_{\mathrm{ref}}|_\infty / \max_t |z_{\mathrm{ref}}|_\infty$")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"Speed/accuracy trade, {result.label}, $t\\in[0,{result.t_end:g}]$, "
                 f"{len(result.z0s)} initial state(s)\nerror against the 50-digit mpmath reference", fontsize=9)
    fig.tight_layout()
    written += save_figure(fig, out / f"{stem}_pareto", formats)
    if result.cost:
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.4))
        configs = list(dict.fromkeys(c.config for c in result.cost))
        for config in configs:
            key = config.split("(")[0]
            label = {"regularized": "regularized tanh"}.get(key, key)
            color, marker = _STYLE.get(label, ("grey", "x"))
            for ax, axis in ((ax1, "T"), (ax2, "N")):
                pts = [c for c in result.cost if c.config == config and c.axis == axis]
                if pts:
                    xs = [c.t_end if axis == "T" else c.n for c in pts]
                    ax.plot(xs, [c.seconds for c in pts], color=color, marker=marker, label=config)
                    plain = [c for c in pts if c.kernel == "python"]
                    if plain:
                        ax.plot([c.n for c in plain], [c.seconds for c in plain], ls="none", marker="o", ms=11,
                                mfc="none", mec=color, label="event: plain-Python kernel (the package's tier for small work)")
        n_batch = next((c.t_end for c in result.cost if c.axis == "N"), 0)
        ax1.set_xlabel("horizon $T$ [s]")
        ax1.set_ylabel("wall time, one trajectory [s]")
        ax1.set_title("cost against the horizon (N = 1)", fontsize=9)
        ax2.set_xlabel("batch size $N$")
        ax2.set_ylabel("wall time, whole batch [s]")
        ax2.set_title(f"cost against the batch size ($T$ = {n_batch:g}; event: simulate_batch)", fontsize=9)
        for ax in (ax1, ax2):
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(alpha=0.3, which="both")
        # one legend below both panels, so that it hides no data
        handles, labels = ax2.get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=7.5, frameon=False)
        fig.suptitle(f"Cost growth, {result.label} (median of repeats)", fontsize=10)
        fig.tight_layout(rect=(0, 0.1, 1, 1))
        written += save_figure(fig, out / f"{stem}_cost", formats)
    return written
