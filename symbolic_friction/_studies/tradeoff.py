"""The speed/accuracy trade of the simulation methods, measured against the
independent 50-digit reference (:mod:`._reference`) of the inclusion
``x' ∈ A x - b SGN(v)`` (eq. xDot, unique by Lemma 1).

For one gain set and a few initial states, every method runs across its
accuracy knob (:attr:`~._simulation.SimulationMethod.knob`: the Moreau step
``h``, one curve per weight ``θ`` of its θ-method, the regularisation width ``ε`` for both laws, the ``solve_ivp``
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
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from .._infra import limits
from .._infra.errors import SimulationError, UsageError
from .._infra.guards import check_count, check_instance, check_items, check_real, check_states
from .._model.parameters import Parameters
from .tradeoff_result import CostPoint, Curve, Point, Tradeoff, fit_order

__all__ = [
    "Sweep",
    "Point",
    "Curve",
    "Tradeoff",
    "CostPoint",
    "default_sweeps",
    "DEFAULT_THETAS",
    "moreau_label",
    "measure_tradeoff",
    "measure_cost",
    "tradeoff_figures",
    "FIGURE_FORMATS",
]

FIGURE_FORMATS = ("png", "pdf", "svg")

# Bounds checked before any work: the horizon, the sample count and the timed repeats of one run, the size of a state
# (the command line's options have the same bounds).
MAX_T_END, MAX_SAMPLES, MAX_REPEATS, MAX_STATE = (limits.TRADEOFF_MAX_T_END, limits.TRADEOFF_MAX_SAMPLES,
                                                limits.TRADEOFF_MAX_REPEATS, limits.TRADEOFF_MAX_STATE)
MAX_STATES = 100
"""The most initial states of one measurement (each has a 50-digit reference, and every configuration runs from each)."""


@dataclass(frozen=True)
class Sweep:
    """One method's curve: a label and the configured methods along its knob (coarse to fine).

    ``declared_order`` is the order the curve is compared with (default: the
    method's :attr:`~._simulation.SimulationMethod.order`).
    """

    label: str
    methods: tuple[Any, ...]
    declared_order: float | None = None


DEFAULT_THETAS = (1.0, 0.5)


def moreau_label(theta: float) -> str:
    """The curve name of the Moreau θ-method: ``moreau`` for ``θ = 1`` (implicit Euler), else with its θ."""
    return "moreau" if theta == 1.0 else f"moreau theta={theta:g}"


def default_sweeps(scale: float = 1.0, *, quick: bool = False, thetas: Sequence[float] = DEFAULT_THETAS) -> list[Sweep]:
    """The knobs swept by ``symbolic-friction tradeoff``.

    ``scale`` (the size of the initial states) sets the absolute tolerances,
    so that the relative tolerance decides.  The regularised ODE is solved
    with tight tolerances so that ``ε`` alone sets its error.  ``thetas``
    gives one Moreau curve per weight ``θ ∈ [½, 1]`` (each is validated by
    :class:`~._simulation.Moreau`).
    """
    from .._simulation import EventDriven, IvpEvents, Moreau, Regularized

    hs = (1e-1, 1e-2, 1e-3) if quick else (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4)
    eps = (1e-1, 1e-2, 1e-3) if quick else (1e-1, 1e-2, 1e-3, 1e-4, 1e-5)
    rtols = (1e-4, 1e-7, 1e-10) if quick else (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)
    atol = 1e-12 * scale
    moreau = []
    # each weight validated by Moreau first (SimulationError naming theta), then read as a float
    weights = [float(Moreau(theta=t).theta) for t in check_items(thetas, name="thetas", what="a list of weights θ in [1/2, 1]", high=16)]
    for theta in dict.fromkeys(weights):
        methods = tuple(Moreau(h=h, theta=theta) for h in hs)
        moreau.append(Sweep(moreau_label(theta), methods, methods[0].accuracy_order))
    return [
        Sweep("event", (EventDriven(),)),
        *moreau,
        Sweep("regularized tanh", tuple(Regularized(epsilon=e, law="tanh", rtol=1e-10, atol=atol) for e in eps)),
        Sweep("regularized sat", tuple(Regularized(epsilon=e, law="sat", rtol=1e-10, atol=atol) for e in eps)),
        Sweep("ivp-events", tuple(IvpEvents(rtol=r, atol=r * 1e-3 * scale) for r in rtols)),
    ]


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


def _timed(run: Any, repeats: int, budget: float, *, first: float | None = None) -> list[float]:
    """Wall times of up to ``repeats`` calls of ``run`` (fewer once ``budget`` seconds are spent, at least 3);
    ``first``, when given, is the time of a run already made, counted as the first repeat."""
    times = [] if first is None else [first]
    spent = sum(times)
    for _ in range(repeats - len(times)):
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
    thetas: Sequence[float] = DEFAULT_THETAS,
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
    thetas : sequence of float, keyword-only
        The weights of the Moreau θ-method, one curve each (default ``1`` and ``½``);
        used only when ``sweeps`` is not given.

    Raises
    ------
    UsageError
        Before any work, if ``z0s`` is not a non-empty list of at most :data:`MAX_STATES` states of three finite
        numbers (each at most :data:`MAX_STATE` in size), ``t_end`` not in ``(0, MAX_T_END]``, ``samples`` not an
        integer from 2 to :data:`MAX_SAMPLES`, ``repeats`` not from 1 to :data:`MAX_REPEATS` or ``budget`` not a
        finite number ≥ 0.
    ParameterTypeError
        If ``params`` is not a :class:`Parameters`, ``z0s`` not a list (``"x"``), ``label`` not a ``str``
        or ``sweeps`` not a list of :class:`Sweep`.
    SimulationError
        If a weight of ``thetas`` is outside ``[1/2, 1]``.

    Examples
    --------
    >>> from symbolic_friction import Parameters, measure_tradeoff
    >>> result = measure_tradeoff(Parameters.table_i("a"), [(0, 1, 0)], 5, samples=11, quick=True)  # doctest: +SKIP
    >>> result  # doctest: +SKIP
    Tradeoff('user gains', 1 initial state(s), t_end = 5, ... configurations)
    """
    from .._simulation import simulate

    check_instance(params, Parameters, name="params", what="a Parameters instance")
    check_instance(label, str, name="label", what="a str")
    z0s = check_states(z0s, name="z0s", high=MAX_STATES, bound=MAX_STATE, error=UsageError)
    t_end = check_real(t_end, name="t_end", high=MAX_T_END, error=UsageError, why="the reference's cost grows with it")
    samples = check_count(samples, name="samples", low=2, high=MAX_SAMPLES, error=UsageError, why="a bound on memory")
    repeats = check_count(repeats, name="repeats", high=MAX_REPEATS, error=UsageError)
    budget = check_real(budget, name="budget", low=0, low_open=False, error=UsageError)
    if sweeps is not None:
        sweeps = check_items(sweeps, name="sweeps", what="a list of Sweep", high=100, kind=Sweep, error=UsageError)
    scale = max(max(abs(c) for c in z) for z in z0s) or 1.0
    if sweeps is None:  # before the reference: a bad θ is refused at once
        sweeps = default_sweeps(scale, quick=quick, thetas=thetas)
    times = np.linspace(0.0, t_end, samples)
    t0 = time.perf_counter()
    refs = [_reference(params, z, t_end, times) for z in z0s]
    ref_seconds = time.perf_counter() - t0
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
        declared = type(sweep.methods[0]).order if sweep.declared_order is None else sweep.declared_order
        curves.append(Curve(sweep.label, knob, declared, tuple(pts), order, n))
    return Tradeoff(
        kernel=_jit.variant(),
        params=params,
        label=label,
        z0s=z0s,
        t_end=t_end,
        samples=samples,
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
    first = 0.0
    try:
        for z, ref in zip(z0s, refs):
            t0 = time.perf_counter()
            sol = simulate(params, z, t_end, method=method, t_eval=times)
            first += time.perf_counter() - t0
            if sol.status not in Status.COMPLETE:
                raise SimulationError(f"stopped early: {sol.status} at t = {sol.t_stop:g}")
            errs.append(_errors(sol, ref))
    except SimulationError as exc:
        return Point(label, type(method).name, knob, value, config, nan, nan, nan, 0, nan, nan, nan, 0, str(exc))

    def run() -> None:
        for z in z0s:
            simulate(params, z, t_end, method=method, t_eval=times)

    # the runs just measured for their error are the first timed repeat: the same calls, not made again
    per = [dt / len(z0s) for dt in _timed(run, repeats, budget, first=first)]
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
    if name == "moreau" and method.theta != 1.0:
        extra = f", theta={method.theta:g}"
    return f"{name}({knob}={getattr(method, knob):g}{extra})"


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
    "moreau theta=0.5": ("tab:purple", "v"),
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
