"""Where each method stops being trustworthy: a fixed matrix of hard cases of the inclusion
``x' ∈ A x - b SGN(v)`` (eq. xDot), each simulated by every method at its default knob and certified by
``certify``, and every outcome classified against the independent 50-digit reference (:mod:`._reference`).

The cells (:func:`cells`):

* the Routh boundary of Assumption 1, ``k_v k_p / k_i = 1 + 10⁻ᵏ`` for
  ``k = 1, 3, 6, 9, 12`` (a pair of roots ``10⁻ᵏ`` from the imaginary axis);
* a double root, a triple root and roots ``10⁻⁶`` apart;
* stiff gains, roots ``-10⁻³, -1, -10³`` (spread ``10⁶``);
* Table I case (a) with ``f_c`` from ``10⁻⁹`` to ``10⁹``;
* case (a) with ``|z₀|`` from ``10⁻⁹`` to ``10⁹``;
* long horizons (case (a) to ``T = 3000``, case (b) to ``T = 1000``).

Each (cell, method) is one of

* ``ok`` — the run completed and its state error (sup over the sample times of ``|z - z_ref|∞``, relative
  to ``max_t |z_ref(t)|∞``) is within the method's claim at its knob, :func:`claimed_error`;
* ``refused`` — the method raised :class:`~symbolic_friction.errors.SimulationError`
  or stopped early with a status that says so; the reason is kept;
* ``wrong`` — the run completed, said nothing, and its error exceeds the
  claim: *silently wrong*.  The package's contract is that no cell is;
* ``no answer`` — the run had not returned after :data:`RUN_LIMIT` seconds and was stopped (the runs are
  made in forked child processes for this): not wrong, but not usable either.

``certify`` is ``proved`` (the exact verifier proved the certificate *and* its overshoot bound
``|x(t)|_𝒜 ≤ κ |x(0)|_𝒜`` holds along the reference solution), ``refused`` (an error with its reason), or
``wrong`` (proved, but the reference solution violates the bound).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from fractions import Fraction as F
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ._infra.errors import SimulationError, SymbolicFrictionError
from ._infra.guards import check_items, check_real
from ._model.parameters import Parameters

__all__ = [
    "Cell", "Outcome", "Extremes", "cells", "default_methods", "claimed_error", "classify_run", "run_extremes",
    "extremes_figure", "RUN_LIMIT",
]

OK, REFUSED, WRONG, PROVED, HUNG = "ok", "refused", "wrong", "proved", "no answer"
# a run that has not returned after this many seconds is stopped and reported as giving no answer
RUN_LIMIT = 15.0
MAX_LIMIT, MAX_METHODS = 3600.0, 64  # the most a caller may ask for: each method runs on every cell, each run that long
# the exact method's claim: it agrees with the reference to this relative error (rounding only)
EVENT_CLAIM = 1e-9
# a method's claim at knob q of declared order p is min(CAP, FACTOR q^p), relative to the solution's size
FACTOR, CAP = 1e3, 1e-1
SAMPLES = 201


@dataclass(frozen=True)
class Cell:
    """One hard case: a group (row block of the heat map), a label, gains, an initial state, a horizon."""

    group: str
    label: str
    params: Parameters
    z0: tuple[float, float, float]
    t_end: float


def _roots(*r: F, f_c: F = F(1)) -> Parameters:
    """Gains with characteristic roots ``-r`` (``s³ + k_v s² + k_p s + k_i``)."""
    a, b, c = r
    return Parameters(k_v=a + b + c, k_p=a * b + b * c + c * a, k_i=a * b * c, f_c=f_c)


def _fast_and_pair(fast: F, zeta: F, omega: F) -> Parameters:
    """Gains with characteristic polynomial ``(s + fast)(s² + 2ζω s + ω²)``."""
    two_zw = 2 * zeta * omega
    return Parameters(k_v=fast + two_zw, k_p=fast * two_zw + omega * omega, k_i=fast * omega * omega)


# Seeded draws of the admissible gains users reach: k_p, k_i log-uniform over 1e-4..1e4, Routh margin
# k_v k_p / k_i = 1 + 10^U with U uniform in [-9, 1], |z0| log-uniform over 0.1..100, T = 20.
RANDOM_SEED, RANDOM_CELLS = 2026, 6


def random_cells(seed: int = RANDOM_SEED, n: int = RANDOM_CELLS) -> list[Cell]:
    """``n`` cells of random admissible gains (three significant digits, exact), labelled by their gains."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        k_p, k_i = (F(f"{10 ** rng.uniform(-4, 4):.3g}") for _ in range(2))
        margin = 1 + F(f"{10 ** rng.uniform(-9, 1):.3g}")
        direction = rng.normal(size=3)
        z0 = direction / np.linalg.norm(direction) * 10 ** rng.uniform(-1, 2)
        params = Parameters(k_p=k_p, k_i=k_i, k_v=margin * k_i / k_p)
        label = f"k_p {float(k_p):.3g}, k_i {float(k_i):.3g}, margin 1+{float(margin - 1):.2g}"
        out.append(Cell("random admissible", label, params, tuple(float(c) for c in z0), 20.0))
    return out


def cells() -> list[Cell]:
    """The fixed matrix of hard cases (see the module docstring)."""
    a = Parameters.table_i("a")
    out = []
    for k in (1, 3, 6, 9, 12):
        p = Parameters(k_p=1, k_i=1, k_v=1 + F(1, 10**k), f_c=1)
        out.append(Cell("Routh boundary", f"k_v k_p/k_i = 1+1e-{k}", p, (0.0, 1.0, 0.0), 30.0))
    out.append(Cell("repeated roots", "double root (s+1)^2(s+2)", _roots(F(1), F(1), F(2)), (0.0, 1.0, 0.0), 30.0))
    out.append(Cell("repeated roots", "triple root (s+1)^3", _roots(F(1), F(1), F(1)), (0.0, 1.0, 0.0), 30.0))
    out.append(Cell("repeated roots", "roots 1e-6 apart", _roots(F(1), 1 + F(1, 10**6), 1 + 2 * F(1, 10**6)), (0.0, 1.0, 0.0), 30.0))
    out.append(Cell("stiff", "roots -1e-3, -1, -1e3", _roots(F(1, 1000), F(1), F(1000)), (0.0, 1.0, 0.0), 5.0))
    for e in (4, 8):
        # (s + 10^e)(s² + 0.2 s + 1): a fast root 10^e times the slow pair's frequency
        p = _fast_and_pair(F(10) ** e, F(1, 10), F(1))
        out.append(Cell("stiff", f"fast/slow 1e{e}, slow pair zeta 0.1", p, (0.0, 1.0, 0.0), 5.0))
    out.extend(random_cells())
    for e in (-9, -3, 3, 9):
        p = Parameters(k_p=a.k_p, k_i=a.k_i, k_v=a.k_v, f_c=F(10) ** e)
        out.append(Cell("f_c", f"case (a), f_c = 1e{e}", p, (0.0, 1.0, 0.0), 30.0))
    for e in (-9, -3, 3, 9):
        out.append(Cell("|z0|", f"case (a), z0 = 1e{e}*(0,1,0)", a, (0.0, 10.0**e, 0.0), 30.0))
    out.append(Cell("long horizon", "case (a), T = 300", a, (0.0, 1.0, 0.0), 300.0))
    out.append(Cell("long horizon", "case (a), T = 3000", a, (0.0, 1.0, 0.0), 3000.0))
    out.append(Cell("long horizon", "case (b), T = 1000", Parameters.table_i("b"), (0.0, 3.0, 0.0), 1000.0))
    return out


def default_methods(*, theta: float = 1.0) -> list[Any]:
    """Each method at its default knobs (what a user gets without choosing); Moreau's θ-method at ``theta``."""
    from ._simulation import EventDriven, IvpEvents, Moreau, Regularized

    return [EventDriven(), Moreau(theta=theta), Regularized(), IvpEvents()]


def claimed_error(method: Any) -> float:
    """The relative state error a method claims at its knob (see the module docstring; Moreau at ``θ = ½``
    claims its second order)."""
    order = getattr(method, "accuracy_order", type(method).order)
    if math.isinf(order):
        return EVENT_CLAIM
    q = float(getattr(method, type(method).knob))
    return min(CAP, FACTOR * q**order)


@dataclass(frozen=True)
class Outcome:
    """The result of one method (or ``certify``) on one cell."""

    cell: str
    method: str
    outcome: str  # ok, refused, wrong, proved
    error: float  # relative state error (NaN when refused; for certify: max |x(t)|_A / (κ |x(0)|_A))
    claim: float
    reason: str = ""
    seconds: float = 0.0


@dataclass
class _Ref:
    times: np.ndarray
    z: np.ndarray
    scale: float
    seconds: float


def _reference(cell: Cell) -> _Ref:
    from ._reference import Reference

    t0 = time.perf_counter()
    times = np.linspace(0.0, cell.t_end, SAMPLES)
    ref = Reference(cell.params, cell.z0, cell.t_end, max_events=2000)
    if ref.status == "max_events":
        raise SimulationError(f"the reference stopped at {len(ref.events)} events on {cell.label}")
    z = np.array(ref.sample(times)[0], dtype=float)
    scale = float(max(np.max(np.abs(z)), max(abs(c) for c in cell.z0)))
    return _Ref(times, z, scale or 1.0, time.perf_counter() - t0)


def classify_run(method: Any, cell: Cell, ref: _Ref) -> Outcome:
    """Simulate ``cell`` with ``method`` and classify the run against the reference."""
    from ._simulation import Status, simulate

    claim = claimed_error(method)
    name = _name(method)
    t0 = time.perf_counter()
    try:
        sol = simulate(cell.params, cell.z0, cell.t_end, method=method, t_eval=ref.times)
    except SimulationError as exc:
        return Outcome(cell.label, name, REFUSED, math.nan, claim, str(exc), time.perf_counter() - t0)
    seconds = time.perf_counter() - t0
    if sol.status not in Status.COMPLETE:
        return Outcome(cell.label, name, REFUSED, math.nan, claim, f"stopped early: {sol.status} at t = {sol.t_stop:g}", seconds)
    err = float(np.max(np.abs(sol.z - ref.z))) / ref.scale
    if not math.isfinite(err) or err > claim:
        return Outcome(cell.label, name, WRONG, err, claim, f"error {err:.2e} above its claim {claim:.0e}", seconds)
    return Outcome(cell.label, name, OK, err, claim, "", seconds)


def classify_runs_limited(methods: Sequence[Any], cell: Cell, ref: _Ref, limit: float = RUN_LIMIT) -> list[Outcome]:
    """Each method's :func:`classify_run` on ``cell`` in turn, in one forked child (a fork per run cost more than most
    runs), each run stopped after ``limit`` seconds (then ``no answer``, and a new child makes the runs after it)."""
    import multiprocessing as mp

    # what the runs import, imported once here, not in each child (scipy.integrate 0.5 CPU-s, flint for the roots)
    import flint  # noqa: F401
    import scipy.integrate  # noqa: F401

    try:
        ctx = mp.get_context("fork")
    except ValueError:  # no fork on this platform: run in-process, without the limit
        return [classify_run(m, cell, ref) for m in methods]
    outcomes: list[Outcome] = []
    while len(outcomes) < len(methods):
        rest = list(methods[len(outcomes):])
        recv, send = ctx.Pipe(duplex=False)
        child = ctx.Process(target=_child, args=(send, rest, cell, ref), daemon=True)
        child.start()
        send.close()
        for method in rest:  # each run's time counts from the previous answer, when the child starts it
            t0 = time.perf_counter()
            try:
                if recv.poll(limit):
                    outcomes.append(recv.recv())
                    continue
                reason = f"no answer within {limit:g} s (stopped)"
            except EOFError:  # the child died without an answer (killed, or it crashed while sending)
                reason = "the child process ended without an answer"
            outcomes.append(Outcome(cell.label, _name(method), HUNG, math.nan, claimed_error(method), reason,
                                    time.perf_counter() - t0))
            break  # a new child makes the runs after this one
        recv.close()
        child.join(1.0)
        if child.is_alive():
            child.kill()
            child.join()
    return outcomes


def _child(send: Any, methods: list[Any], cell: Cell, ref: _Ref) -> None:
    for method in methods:
        t0 = time.perf_counter()
        try:
            outcome = classify_run(method, cell, ref)
        except Exception as exc:  # a crash is an answer too: reported, never lost with the cell
            outcome = Outcome(cell.label, _name(method), HUNG, math.nan, claimed_error(method),
                              f"crashed: {type(exc).__name__}: {exc}", time.perf_counter() - t0)
        send.send(outcome)


def classify_certify(cell: Cell, ref: _Ref, cache: dict) -> Outcome:
    """``certify`` on the cell's gains (once per gain set), its bound checked along the reference."""
    from ._model.attractor import distance_x
    from ._certify import certify
    from ._model.coordinates import z_to_x

    t0 = time.perf_counter()
    key = cell.params
    if key not in cache:
        try:
            cache[key] = (certify(cell.params), None)  # returns only what the exact verifier proved
        except SymbolicFrictionError as exc:
            cache[key] = (None, f"{type(exc).__name__}: {exc}")
    cert, reason = cache[key]
    seconds = time.perf_counter() - t0
    if cert is None:
        return Outcome(cell.label, "certify", REFUSED, math.nan, 1.0, reason, seconds)
    kappa = float(cert.overshoot_bound)
    d = distance_x(cell.params, z_to_x(cell.params, ref.z))
    ratio = float(np.max(d)) / (kappa * float(d[0])) if d[0] > 0 else (0.0 if np.max(d) == 0 else math.inf)
    if ratio > 1 + 1e-9:
        return Outcome(cell.label, "certify", WRONG, ratio, 1.0, f"bound kappa = {kappa:.4g} violated along the reference", seconds)
    return Outcome(cell.label, "certify", PROVED, ratio, 1.0, f"kappa = {kappa:.4g}", seconds)


def _md(text: str) -> str:
    """A Markdown table cell: ``|`` (as in ``|z0|``) escaped, line breaks folded (a row is one line)."""
    return " ".join(text.split()).replace("|", "\\|")


def _name(method: Any) -> str:
    knob = type(method).knob
    if knob is None:
        return type(method).name
    theta = getattr(method, "theta", 1.0)
    extra = "" if theta == 1.0 else f", theta={theta:g}"
    return f"{type(method).name}({knob}={getattr(method, knob):g}{extra})"


@dataclass(frozen=True)
class Extremes:
    """Every outcome of the matrix, and the time it took."""

    cells: tuple[Cell, ...]
    methods: tuple[str, ...]
    outcomes: tuple[Outcome, ...]
    seconds: float
    reference_seconds: float
    references: dict = field(default_factory=dict, repr=False, compare=False)

    def __repr__(self) -> str:
        # the counts; report() has the table
        counts = ", ".join(f"{v} {k}" for k, v in sorted(self.counts().items()))
        return f"Extremes({len(self.cells)} cells × {len(self.methods) + 1} columns: {counts}; {self.seconds:.1f} s)"

    def counts(self) -> dict[str, int]:
        from collections import Counter

        return dict(Counter(o.outcome for o in self.outcomes))

    def get(self, cell: str, method: str) -> Outcome:
        return next(o for o in self.outcomes if o.cell == cell and o.method == method)

    @property
    def silently_wrong(self) -> list[Outcome]:
        return [o for o in self.outcomes if o.outcome == WRONG]

    def report(self) -> str:
        """A Markdown report: one row per cell, one column per method and ``certify``."""
        cols = list(self.methods) + ["certify"]
        lines = [
            "# Extremes: where each method stops being trustworthy",
            "",
            "Generated by `symbolic-friction extremes` (also by `symbolic-friction figures`). Each cell is "
            "simulated by every method at its default knob and certified; errors are the sup over "
            f"{SAMPLES} sample times of |z - z_ref|, relative to max |z_ref|, against the 50-digit mpmath "
            "reference. `ok`: within the method's claim (event 1e-9; others min(0.1, 1000 knob^order)); "
            "`refused`: the method said why; `wrong`: silently beyond its claim. certify: `proved` "
            "(exactly, and the overshoot bound holds along the reference), `refused`, or `wrong`.",
            "",
            "| group | cell | " + " | ".join(f"`{c}`" for c in cols) + " |",
            "|---|---|" + "---|" * len(cols),
        ]
        by_cell = {}
        for o in self.outcomes:
            by_cell.setdefault(o.cell, {})[o.method] = o
        for cell in self.cells:
            row = by_cell[cell.label]
            entries = []
            for c in cols:
                o = row[c]
                if o.outcome == OK:
                    entries.append(f"ok {o.error:.1e}")
                elif o.outcome == PROVED:
                    entries.append(f"proved ({o.reason})")
                elif o.outcome == REFUSED:
                    entries.append(f"refused: {o.reason}")  # whole: a cut reason hides what to change
                elif o.outcome == HUNG:
                    entries.append(f"no answer: {o.reason}")
                else:
                    entries.append(f"**WRONG** {o.reason}")
            cols_md = [_md(cell.group), _md(cell.label), *map(_md, entries)]
            lines.append("| " + " | ".join(cols_md) + " |")
        counts = ", ".join(f"{v} {k}" for k, v in sorted(self.counts().items()))
        lines += ["", f"{len(self.cells)} cells x {len(cols)} columns: {counts}; "
                      f"{self.seconds:.1f} s in all ({self.reference_seconds:.1f} s for the references)."]
        return "\n".join(lines) + "\n"


def run_extremes(methods: Sequence[Any] | None = None, *, only: Sequence[str] | None = None, certify: bool = True,
                 limit: float = RUN_LIMIT, theta: float = 1.0) -> Extremes:
    """Run the matrix (or the cells whose group or label is in ``only``), each run stopped after ``limit`` s.

    ``methods`` is a list of methods, each configured (``Moreau(h=1e-3)``) or a name (``"event"``), or one of
    them; ``theta`` is the weight of Moreau's θ-method among the default methods (ignored when ``methods`` is given).

    Raises
    ------
    ParameterTypeError
        If ``methods`` or ``only`` is not a list (``None``: the defaults, every cell), or a cell name not a ``str``.
    SimulationError
        Before any cell is run: a method that is neither a method nor a name, more than :data:`MAX_METHODS`, ``limit``
        not in ``(0, MAX_LIMIT]`` seconds, ``theta`` outside ``[1/2, 1]``, or no cell matching ``only``.

    Examples
    --------
    >>> from symbolic_friction import run_extremes
    >>> result = run_extremes(only=["repeated roots"], certify=False)  # doctest: +SKIP
    >>> result.silently_wrong  # doctest: +SKIP
    []
    >>> print(result.report())  # doctest: +SKIP
    """
    from ._simulation import SimulationMethod, configure, event

    t0 = time.perf_counter()
    limit = check_real(limit, name="limit", high=MAX_LIMIT, error=SimulationError, why="seconds per run, a bound on time")
    methods = default_methods(theta=theta) if methods is None else check_items(
        methods, name="methods", what="a list of simulation methods (e.g. [EventDriven(), 'moreau'])", high=MAX_METHODS,
        single=(str, SimulationMethod), each=lambda m: configure(m, {}), error=SimulationError)
    matrix = cells()
    only = None if only is None else check_items(only, name="only", what="a list of cell groups or labels", single=str,
                                                 high=len(matrix) + 64, kind=str, error=SimulationError)
    chosen = [c for c in matrix if only is None or c.group in only or c.label in only]
    if not chosen:
        raise SimulationError(f"no extreme cell matches {list(only or [])}; groups: {sorted({c.group for c in matrix})}")
    outcomes, refs = [], {}
    cache: dict = {}
    ref_seconds = 0.0
    event.preload_compiled()  # the compiled kernel, if the runs use it: loaded here once, not in each forked child
    for cell in chosen:
        ref = refs[cell.label] = _reference(cell)
        ref_seconds += ref.seconds
        outcomes.extend(classify_runs_limited(methods, cell, ref, limit))
        if certify:
            outcomes.append(classify_certify(cell, ref, cache))
    return Extremes(tuple(chosen), tuple(_name(m) for m in methods), tuple(outcomes), time.perf_counter() - t0, ref_seconds, refs)


def extremes_figure(result: Extremes, path: Path, formats: Sequence[str] = ("png",)) -> list[Path]:
    """The heat map: cells (rows) by methods and ``certify`` (columns), coloured by the outcome."""
    from matplotlib.colors import LogNorm
    from matplotlib.patches import Patch

    from ._studies.figures import _pyplot, save_figure

    plt = _pyplot()
    cols = list(result.methods) + ["certify"]
    rows = [c.label for c in result.cells]
    err = np.full((len(rows), len(cols)), np.nan)
    fig, ax = plt.subplots(figsize=(9.5, 0.34 * len(rows) + 2.2))
    for i, r in enumerate(rows):
        for j, c in enumerate(cols):
            o = result.get(r, c)
            if o.outcome == OK:
                err[i, j] = max(o.error, 1e-17)
    im = ax.imshow(err, aspect="auto", cmap="viridis", norm=LogNorm(vmin=1e-16, vmax=1e-1))
    for i, r in enumerate(rows):
        for j, c in enumerate(cols):
            o = result.get(r, c)
            if o.outcome == OK:
                txt, color = ("0 (exact)" if o.error == 0 else f"{o.error:.0e}"), "white" if o.error < 1e-6 else "black"
            elif o.outcome == PROVED:
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, color="tab:green", alpha=0.55, lw=0))
                txt, color = "proved", "black"
            elif o.outcome == REFUSED:
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor="0.85", hatch="///", edgecolor="0.6", lw=0))
                txt, color = "refused", "black"
            elif o.outcome == HUNG:
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, color="tab:orange", lw=0))
                txt, color = f"no answer\n({RUN_LIMIT:g} s)", "black"
            else:
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, color="red", lw=0))
                txt, color = "WRONG", "white"
            ax.text(j, i, txt, ha="center", va="center", fontsize=6.5, color=color)
    ax.set_xticks(range(len(cols)), [c.replace("(", "\n").rstrip(")") for c in cols], fontsize=7.5)
    ax.xaxis.tick_top()
    ax.set_yticks(range(len(rows)), [f"{c.group}: {c.label}" for c in result.cells], fontsize=7)
    cb = fig.colorbar(im, ax=ax, fraction=0.04, pad=0.02)
    cb.set_label("relative state error vs the 50-digit reference (ok cells)", fontsize=7)
    ax.legend(handles=[Patch(color="tab:green", alpha=0.55, label="certify: proved, bound holds along the reference"),
                       Patch(facecolor="0.85", hatch="///", edgecolor="0.6", label="refused, with a reason (see the report)"),
                       Patch(color="tab:orange", label=f"no answer within {RUN_LIMIT:g} s"),
                       Patch(color="red", label="silently wrong (beyond the method's claim)")],
              loc="upper center", bbox_to_anchor=(0.5, -0.01), ncol=2, fontsize=7, frameon=False)
    counts = ", ".join(f"{v} {k}" for k, v in sorted(result.counts().items()))
    ax.set_title(f"Extremes: each method at its default knob and certify on hard cases ({counts})", fontsize=9, pad=28)
    fig.tight_layout()
    return save_figure(fig, path.parent / path.stem, formats)


def _extremes_group(group: str) -> Extremes:
    """The matrix's cells of one ``group`` (a task of the ``extremes`` figure; its references dropped, for pickling)."""
    return replace(run_extremes(only=[group]), references={})


def combine_extremes(parts: Sequence[Extremes]) -> Extremes:
    """One matrix from the results of disjoint groups, cells in the matrix's order (the parts' methods agree)."""
    order = {c.label: i for i, c in enumerate(cells())}
    chosen = sorted((c for part in parts for c in part.cells), key=lambda c: order[c.label])
    methods = parts[0].methods
    if any(part.methods != methods for part in parts):
        raise SimulationError("the parts of the extremes matrix were run with different methods")
    outcomes = tuple(o for part in parts for o in part.outcomes)
    return Extremes(tuple(chosen), methods, outcomes, sum(p.seconds for p in parts), sum(p.reference_seconds for p in parts))


def _register() -> None:
    from ._studies.figures import _FORMATS_NOW, Task, register_split
    from ._infra.io import atomic_write

    def tasks() -> list[Task]:
        groups = list(dict.fromkeys(c.group for c in cells()))
        # one task per group of cells, so that the matrix (the longest figure) shares both cores
        return [Task(f"extremes ({g})", _extremes_group, (g,), cost=7.0) for g in groups]

    def draw(out: Path, parts: list) -> list[Path]:
        result = combine_extremes(parts)
        report = out / "extremes.md"
        atomic_write(report, lambda fh: fh.write(result.report().encode()))
        png = extremes_figure(result, out / "extremes_heatmap.png", _FORMATS_NOW())
        return [report, png[0]]

    register_split("extremes", "the extremes matrix: every method and certify on hard cases (report extremes.md + heat map)",
                   tasks=tasks, draw=draw)


_register()
