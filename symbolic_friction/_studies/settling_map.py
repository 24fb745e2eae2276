"""How much faster reset PID settles than the paper's PID, over a grid of admissible gains (beyond the paper).

A map in the style of Table I: ``k_p`` and ``k_i`` on log-spaced exact
rationals, ``k_v = m·k_i/k_p`` for a fixed Routh margin ``m = k_v k_p/k_i > 1``
(Assumption 1), ``f_c = 1``, one initial state.  At each point both
controllers are simulated exactly by the event kernel, with the settling
definition of :func:`symbolic_friction._studies.settling.compare_settling`
(reset PID of :mod:`symbolic_friction._model.reset`); the heat map is
:mod:`.settling_map_plot`.

What is measured, per friction level:

* ``f_s = f_c`` (the paper's model; Proposition 1 for PID, the ``reset.*``
  obligations for reset PID): the settling time to ``|s| ≤ tol·|s(0)|`` for
  good, and the ratio PID over reset.  Where only reset settles by ``t_end``
  the ratio is ``inf`` and ``t_end/t_reset`` is a strict lower bound of it;
  where neither does it is undefined (grey in the figure).
* ``f_s > f_c``: both controllers hunt (same stick-exit map, see
  :mod:`symbolic_friction._studies.settling`), so neither settles to a
  tolerance (and ``|s|`` crosses 0 in every slip, so "first reaches a level"
  says nothing).  The honest question left is how fast each reaches the hunting
  cycle: the time after which ``|s| ≤ band·a*`` for good, with ``a*`` the
  amplitude ``max |s|`` of the largest *stable* symmetric cycle the hunting map
  finds (found, not proved here: :func:`stiction_table` proves them).  Where no
  stable cycle is found the tolerance criterion is used, and the cell says so.

"For good" means up to ``t_end``; a run inside the level only at ``t_end`` is
not settled.  Resets only remove stick time: the stick
exits, in ``σ``, are the same for both controllers (each cell checks this on
PID's exits, :attr:`SettlingCell.same_exits`), so up to the settling-time
resolution ``t_end/(samples - 1)`` reset PID is never slower.  One
finite-horizon effect is corrected, and flagged: a PID run that ends inside a
long stick with small ``|s|`` looks settled on ``[0, t_end]`` although its next
slip leaves the level.  Reset PID's run, which has passed that stick, shows that
slip: past reset PID's exit number ``pid_exits + 1`` its trajectory is PID's
future up to stick durations.  If ``|s|`` exceeds the level there, PID is
counted as not settled by ``t_end`` (:attr:`SettlingCell.pid_refuted`).
:attr:`SettlingMap.slower` lists every cell where reset PID is still measured
slower (expected empty).

:func:`stiction_table` gives, per Table I case and ``f_s/f_c``,
:func:`~symbolic_friction._studies.settling.hunting_verdict` for PID and for
reset PID: stick-phase resets cannot remove hunting, because the stick still
has to carry ``φ`` from ``f_c`` to ``f_s`` and then exits where PID's does.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import numpy as np

from .._infra.errors import ParameterError
from .._model.parameters import Parameters
from .settling import pid_refuted, same_exits, settled_at, simulate_trajectory

__all__ = ["SettlingCell", "SettlingMap", "StictionEntry", "StictionTable", "log_gains", "settling_ratio_map",
           "stiction_table"]



def log_gains(points: int = 8, *, lo: float = -0.5, hi: float = 1.0, digits: int = 4) -> tuple[Fraction, ...]:
    """``points`` exact rationals, ``10^x`` for ``x`` evenly spaced over ``[lo, hi]``, to ``digits`` significant digits.

    Examples
    --------
    >>> [float(g) for g in log_gains(4, lo=0, hi=1)]
    [1.0, 2.154, 4.642, 10.0]
    """
    if isinstance(points, bool) or not isinstance(points, int) or points < 1:
        raise ParameterError(f"points must be a positive integer; got {points!r}")
    exps = [lo] if points == 1 else [lo + (hi - lo) * j / (points - 1) for j in range(points)]
    return tuple(Fraction(format(10.0 ** x, f".{digits}g")) for x in exps)


@dataclass(frozen=True)
class SettlingCell:
    """One gain set of the map, both controllers.

    Attributes
    ----------
    k_p, k_i, k_v, f_s_ratio : Fraction
        The gains (``f_c = 1``) and ``f_s/f_c``.
    criterion : str
        ``"tol"`` (``|s| ≤ tol·|s(0)|``) or ``"band"`` (``|s| ≤ band·a*``, ``a*`` the hunting amplitude).
    level : float
        The ``|s|`` level of the criterion.
    pid_time, reset_time : float or None
        When each settles to ``level`` for good (None: not by ``t_end``).
    pid_final, reset_final : float
        ``|s(t_end)|``.
    resets : int
        Reset PID's resets.
    hunting : str
        The hunting verdict for PID (found, not proved, for ``f_s > f_c``).
    pid_exits, reset_exits : int
        Stick exits of each run.
    same_exits : bool
        Whether PID's stick exits are, in ``σ``, the first ``pid_exits`` of reset PID's (module docstring).
    pid_refuted : bool
        PID was inside the level from ``t_PID`` to ``t_end``, but its future, which reset PID's run
        shows past PID's last stick exit, leaves it: PID does not settle by ``t_end`` (``pid_time`` None).
    """

    k_p: Fraction
    k_i: Fraction
    k_v: Fraction
    f_s_ratio: Fraction
    criterion: str
    level: float
    pid_time: float | None
    reset_time: float | None
    pid_final: float
    reset_final: float
    resets: int
    hunting: str
    pid_exits: int = 0
    reset_exits: int = 0
    same_exits: bool = True
    pid_refuted: bool = False

    @property
    def ratio(self) -> float | None:
        """PID's time over reset's: ``inf`` if only reset settles, None if reset does not."""
        a, b = self.pid_time, self.reset_time
        if b is None:
            return None
        if a is None:
            return math.inf
        return a / b if b > 0 else (1.0 if a == 0 else math.inf)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready: gains as exact strings, times as floats or None, ``ratio`` ``"inf"`` or None where so."""
        ratio = self.ratio
        return {"k_p": str(self.k_p), "k_i": str(self.k_i), "k_v": str(self.k_v), "f_s_ratio": str(self.f_s_ratio),
                "criterion": self.criterion, "level": self.level, "pid_time": self.pid_time,
                "reset_time": self.reset_time, "ratio": "inf" if ratio == math.inf else ratio,
                "pid_final": self.pid_final, "reset_final": self.reset_final, "resets": self.resets,
                "hunting": self.hunting, "pid_exits": self.pid_exits, "reset_exits": self.reset_exits,
                "same_exits": self.same_exits, "pid_refuted": self.pid_refuted}


@dataclass(frozen=True)
class SettlingMap:
    """The result of :func:`settling_ratio_map`: its inputs and one :class:`SettlingCell` per (ratio, k_i, k_p)."""

    k_p: tuple[Fraction, ...]
    k_i: tuple[Fraction, ...]
    margin: Fraction
    f_s_ratios: tuple[Fraction, ...]
    z0: tuple[Fraction, Fraction, Fraction]
    tol: Fraction
    band: Fraction
    t_end: float
    samples: int
    dwell: Fraction
    cells: tuple[SettlingCell, ...]

    @property
    def resolution(self) -> float:
        """The sample spacing ``t_end/(samples - 1)``: settling times are resolved to it."""
        return self.t_end / (self.samples - 1)

    def cells_at(self, f_s_ratio: Any) -> list[SettlingCell]:
        """The cells of one friction level, ``k_i`` major, ``k_p`` minor."""
        r = Fraction(f_s_ratio)
        if r not in self.f_s_ratios:
            raise ParameterError(f"the map has f_s/f_c in {[str(q) for q in self.f_s_ratios]}; got {r}")
        return [c for c in self.cells if c.f_s_ratio == r]

    def grid(self, f_s_ratio: Any, what: str = "ratio") -> np.ndarray:
        """An array ``(len(k_i), len(k_p))`` of a cell attribute (``ratio``, ``pid_time``, …); None becomes nan."""
        values = [getattr(c, what) for c in self.cells_at(f_s_ratio)]
        return np.array([math.nan if v is None else float(v) for v in values]).reshape(len(self.k_i), len(self.k_p))

    @property
    def slower(self) -> tuple[SettlingCell, ...]:
        """Cells where reset PID settles later than PID by more than :attr:`resolution`, or only PID settles."""
        return tuple(c for c in self.cells if c.pid_time is not None and
                     (c.reset_time is None or c.reset_time > c.pid_time + self.resolution))

    def summary(self, f_s_ratio: Any) -> dict[str, Any]:
        """Counts and the min / median / max of the finite ratios at one friction level.

        ``only_reset`` counts the cells where only reset PID settles (ratio
        ``inf``; ``lower_bounds`` gives ``t_end/t_reset`` there), ``neither``
        those where neither does, ``pid_refuted`` those where PID's apparent
        settling was refuted by its future, ``different_exits`` those whose
        stick exits differ (expected 0).
        """
        cells = self.cells_at(f_s_ratio)
        finite = sorted(c.ratio for c in cells if c.ratio is not None and math.isfinite(c.ratio))
        only = [self.t_end / c.reset_time for c in cells if c.ratio == math.inf and c.reset_time]
        stats = ({"min": finite[0], "median": float(np.median(finite)), "max": finite[-1]} if finite
                 else {"min": None, "median": None, "max": None})
        return {"f_s_ratio": str(Fraction(f_s_ratio)), "cells": len(cells), "both": len(finite), **stats,
                "only_reset": sum(c.ratio == math.inf for c in cells), "neither": sum(c.ratio is None for c in cells),
                "pid_refuted": sum(c.pid_refuted for c in cells), "different_exits": sum(not c.same_exits for c in cells),
                "lower_bounds": (min(only), max(only)) if only else None,
                "criteria": sorted({c.criterion for c in cells})}

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready: the inputs as exact strings, the summaries, the slower cells and every cell."""
        return {"k_p": [str(q) for q in self.k_p], "k_i": [str(q) for q in self.k_i], "margin": str(self.margin),
                "f_s_ratios": [str(q) for q in self.f_s_ratios], "z0": [str(q) for q in self.z0],
                "tol": str(self.tol), "band": str(self.band), "t_end": self.t_end, "samples": self.samples,
                "dwell": str(self.dwell), "resolution": self.resolution,
                "summary": [self.summary(r) for r in self.f_s_ratios],
                "slower": [c.as_dict() for c in self.slower], "cells": [c.as_dict() for c in self.cells]}


def _hunting_level(params: Parameters, band: Fraction) -> tuple[float, str] | None:
    """``band·a*`` with ``a*`` the largest stable symmetric cycle's ``max |s|``, and a note; None if there is none."""
    from .._hunting._map import find_cycles

    stable = [c for c in find_cycles(params, general=False) if c.stable and math.isfinite(c.amplitude_s)]
    if not stable:
        return None
    cycle = max(stable, key=lambda c: c.amplitude_s)
    return float(band) * cycle.amplitude_s, f"a* = {cycle.amplitude_s:.6g} (σ* = {cycle.sigma:.6g}, stable)"


def _cell(params: Parameters, ratio: Fraction, z, tol: Fraction, band: Fraction, t_end: float, samples: int,
          dwell: Fraction) -> SettlingCell:
    pid = simulate_trajectory(params, z, t_end, samples)
    reset = simulate_trajectory(replace(params, reset_dwell=dwell), z, t_end, samples)
    # |s(0)| = 0: relative to max |s|, as compare_settling does
    level = float(tol) * (abs(float(z[1])) if z[1] != 0 else float(np.nanmax(np.abs(pid.s))))
    criterion, hunting = "tol", "no (f_s = f_c: Proposition 1)"
    if params.stiction:
        found = _hunting_level(params, band)
        hunting = "no stable symmetric cycle found: tolerance criterion"
        if found is not None:
            level, note = found
            criterion, hunting = "band", f"cycle found, not proven: {note}"
    pid_time = settled_at(pid.t, pid.s, level) if pid.complete else None
    reset_time = settled_at(reset.t, reset.s, level) if reset.complete else None
    same = same_exits(pid, reset)
    refuted = pid_time is not None and pid_refuted(pid, reset, level)
    return SettlingCell(
        k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_s_ratio=ratio, criterion=criterion, level=level,
        pid_time=None if refuted else pid_time, reset_time=reset_time, pid_final=abs(float(pid.s[-1])),
        reset_final=abs(float(reset.s[-1])), resets=reset.resets, hunting=hunting, pid_exits=int(pid.exit_t.size),
        reset_exits=int(reset.exit_t.size), same_exits=same, pid_refuted=refuted)


def settling_ratio_map(
    *,
    k_p: Sequence[Any] | None = None,
    k_i: Sequence[Any] | None = None,
    points: int = 8,
    margin: Any = 2,
    f_s_ratios: Sequence[Any] = (1, Fraction(6, 5)),
    z0: Sequence[Any] = (0, 3, 0),
    tol: Any = Fraction(1, 10**6),
    band: Any = Fraction(11, 10),
    t_end: float = 200.0,
    samples: int = 4001,
    dwell: Any = Fraction(1, 100),
    on_cell: Callable[[SettlingCell], None] | None = None,
) -> SettlingMap:
    """Settling of PID and reset PID over a ``(k_p, k_i)`` grid at a fixed Routh margin, exactly simulated.

    Parameters
    ----------
    k_p, k_i : sequences of numbers or None, keyword-only
        The axes (exact); default :func:`log_gains` of ``points`` values over ``10^-0.5 … 10^1``.
    points : int, keyword-only
        Points per default axis.
    margin : number > 1, keyword-only
        The Routh margin ``k_v k_p/k_i``: ``k_v = margin·k_i/k_p`` at every point.
    f_s_ratios : sequence of numbers ≥ 1, keyword-only
        ``f_s/f_c`` levels (``f_c = 1``); ``1`` is the paper's Coulomb friction.
    z0 : 3 numbers, keyword-only
        The initial state ``(e_i, s, v)``, exact.
    tol : number in (0, 1), keyword-only
        Settled when ``|s| ≤ tol·|s(0)|`` for good (``f_s = f_c``, or no stable hunting cycle found).
    band : number ≥ 1, keyword-only
        With a stable hunting cycle of amplitude ``a*``: settled when ``|s| ≤ band·a*`` for good.
    t_end : float, keyword-only
    samples : int, keyword-only
        Samples on ``[0, t_end]`` besides the events; the times are resolved to ``t_end/(samples - 1)``.
    dwell : number > 0, keyword-only
        The reset's dwell time.
    on_cell : callable or None, keyword-only
        Called with each :class:`SettlingCell` as it is done (progress).

    Returns
    -------
    SettlingMap

    Raises
    ------
    ParameterError
        If ``margin ≤ 1``, an ``f_s/f_c < 1``, ``band < 1``, or an option of
        :func:`~symbolic_friction._studies.settling.compare_settling` is out of range.

    Examples
    --------
    >>> m = settling_ratio_map(k_p=[3], k_i=[4], margin="4.8", f_s_ratios=[1], samples=2001)
    >>> cell = m.cells[0]
    >>> cell.pid_time is None, 71 < cell.reset_time < 72, m.slower  # Table I (a): only reset PID settles
    (True, True, ())
    """
    from .._infra.rational import to_rational

    margin = to_rational(margin, name="margin")
    band = to_rational(band, name="band")
    if margin <= 1:
        raise ParameterError(f"the Routh margin k_v k_p/k_i must be > 1 (Assumption 1); got {margin}")
    if band < 1:
        raise ParameterError(f"band must be ≥ 1 (a multiple of the hunting amplitude); got {band}")
    ratios = tuple(to_rational(r, name="f_s_ratios") for r in f_s_ratios)
    if not ratios or any(r < 1 for r in ratios):
        raise ParameterError(f"f_s/f_c must be ≥ 1 (at least one); got {[str(r) for r in ratios]}")
    kp = tuple(to_rational(q, name="k_p") for q in (log_gains(points) if k_p is None else k_p))
    ki = tuple(to_rational(q, name="k_i") for q in (log_gains(points) if k_i is None else k_i))
    if not kp or not ki:
        raise ParameterError("k_p and k_i need at least one value each")
    if not hasattr(z0, "__len__") or len(z0) != 3:
        raise ParameterError(f"z0 must be three numbers (e_i, s, v); got {z0!r}")
    z = tuple(to_rational(c, name=f"z0[{i}]") for i, c in enumerate(z0))
    tol, dwell = to_rational(tol, name="tol"), to_rational(dwell, name="dwell")
    cells = []
    for ratio in ratios:
        for i_gain in ki:
            for p_gain in kp:
                params = Parameters(k_p=p_gain, k_i=i_gain, k_v=margin * i_gain / p_gain, f_c=1,
                                    f_s=None if ratio == 1 else ratio)
                cell = _cell(params, ratio, z, tol, band, float(t_end), samples, dwell)
                cells.append(cell)
                if on_cell is not None:
                    on_cell(cell)
    return SettlingMap(k_p=kp, k_i=ki, margin=margin, f_s_ratios=ratios, z0=z, tol=tol, band=band,
                       t_end=float(t_end), samples=samples, dwell=dwell, cells=tuple(cells))


@dataclass(frozen=True)
class StictionEntry:
    """One Table I case at one ``f_s/f_c``: the hunting verdict of PID and of reset PID."""

    case: str
    f_s_ratio: Fraction
    pid: str
    reset: str

    @property
    def pid_proved(self) -> bool:
        """Whether a hunting cycle of PID is proved (Krawczyk)."""
        return self.pid.startswith("cycle proven")

    @property
    def reset_proved(self) -> bool:
        """Whether reset PID's hunting cycle is proved (PID's cycle, on the same stick-exit map)."""
        return self.reset.startswith("cycle proven")

    def as_dict(self) -> dict[str, Any]:
        return {"case": self.case, "f_s_ratio": str(self.f_s_ratio), "pid": self.pid, "reset": self.reset,
                "pid_proved": self.pid_proved, "reset_proved": self.reset_proved}


@dataclass(frozen=True)
class StictionTable:
    """The stiction table of :func:`stiction_table`."""

    dwell: Fraction
    entries: tuple[StictionEntry, ...]

    def as_dict(self) -> dict[str, Any]:
        return {"dwell": str(self.dwell), "entries": [e.as_dict() for e in self.entries]}

    def markdown(self) -> str:
        """A Markdown table: case, ``f_s/f_c``, PID's verdict, reset PID's verdict."""
        rows = ["| case | f_s/f_c | PID | reset PID |", "|---|---|---|---|"]
        rows += [f"| ({e.case}) | {float(e.f_s_ratio):g} | {e.pid} | {e.reset} |" for e in self.entries]
        return "\n".join(rows)


def stiction_table(ratios: Sequence[Any] = (Fraction(11, 10), Fraction(6, 5), Fraction(3, 2), 2),
                   cases: Sequence[str] = ("a", "b"), *, dwell: Any = Fraction(1, 100),
                   prove: bool = True) -> StictionTable:
    """Whether PID and reset PID hunt, per Table I case and ``f_s/f_c`` (``f_c = 1``).

    Each verdict is :func:`~symbolic_friction._studies.settling.hunting_verdict`:
    the symmetric cycles of the hunting map are searched and the first is
    proved by the Krawczyk test.  Reset PID's verdict is PID's cycle, which
    reset PID keeps because its stick exits are PID's (module docstring).

    Parameters
    ----------
    ratios : sequence of numbers > 1
    cases : sequence of ``"a"``, ``"b"``
    dwell : number > 0, keyword-only
        Reset PID's dwell time.
    prove : bool, keyword-only
        Prove the cycles (about a second each) or only find them.

    Raises
    ------
    ParameterError
        If a ratio is not ``> 1`` (with ``f_s = f_c`` there is no hunting: Proposition 1).

    Examples
    --------
    >>> t = stiction_table([Fraction(6, 5)], ["a"], prove=False)
    >>> t.entries[0].pid
    'cycle found, not proven (σ* = 0.105045)'
    """
    from .._infra.rational import to_rational
    from .settling import hunting_verdict

    rs = tuple(to_rational(r, name="ratios") for r in ratios)
    if any(r <= 1 for r in rs):
        raise ParameterError(f"f_s/f_c must be > 1 for hunting; got {[str(r) for r in rs]}")
    dwell = to_rational(dwell, name="dwell")
    entries = []
    for case in cases:
        base = Parameters.table_i(case)
        for r in rs:
            plain = replace(base, f_s=r * base.f_c)
            entries.append(StictionEntry(case=case, f_s_ratio=r, pid=hunting_verdict(plain, prove=prove),
                                         reset=hunting_verdict(replace(plain, reset_dwell=dwell), prove=prove)))
    return StictionTable(dwell=dwell, entries=tuple(entries))
