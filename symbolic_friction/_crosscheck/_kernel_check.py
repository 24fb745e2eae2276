"""The trajectories the cross-check trusts, against the independent reference, where ``f_c ≠ 1`` and ``f_s > f_c``.

The cross-check decides the paper's properties on the event-driven kernel's
trajectories and on the closed-form ``∫ v²`` (:mod:`._along`).  Errors that
vanish at ``f_c = 1`` (a factor ``f_c`` dropped from the dense output, the
event state, the stick duration or ``∫ v²``), or without static friction
(a sign slip where a stick ends at ``±f_s`` or in the offset the slip leaves
with), or on one kind of sample grid (the stepped propagator used on uniform
grids), or at a horizon just after an event (the scan's last partial cell),
would pass it unseen.  So ``check`` runs the kernel on :data:`SCENARIOS`:

* ``f_c ∈ {1, 2, 1e-6, 1e6}`` with the states scaled by ``f_c``, each with
  ``f_s = f_c`` and ``f_s = 6/5·f_c``; from the initial state chosen, the
  solution slips both ways and sticks from both sides (events
  ``-1 → 0 → 1 → 0 → -1``);
* on a uniform grid and on ``t_j = T (j/(n-1))²``;
* and with the horizon ``t_end = t_event·(1 + 10⁻⁹)`` just after the third
  event (a slip's end, found by the scan).

It compares, with the tolerances :data:`STATE_TOL`, :data:`TIME_TOL` and
:data:`INTEGRAL_TOL` (relative to the trajectory's scale, its horizon and
``scale²·T``): every sample's state and mode, every event's time, modes and
state, and the cross-check's ``∫₀^T v²``, with what the independent 50-digit
reference (:mod:`symbolic_friction._reference`, sharing no code with the
kernel) computed for the same scenario.  The reference's numbers are shipped
(``kernel_reference.json``, written by :func:`reference_data`; a test re-derives
them), so ``check`` pays only for the kernel: a patched or broken install whose
kernel drifts fails ``check``.  On the uniform grids the cross-check's closed-form
flow of each slip interval of the chain (:func:`.lemma3.slip_points`, which gives
the interior points of eq. hatVdot's ``R̂`` intervals) must also land on the
kernel's next point: an ``x*_k`` without ``f_c`` there is invisible at ``f_c = 1``.

Two more rows hold the kernel to exact facts rather than to shipped numbers:

* **a graze inside one scan cell** (:func:`graze_row`).  On lightly damped gains
  (``k_v ≪ √k_p/8``) ``v`` along a slip is a fast oscillation on a slow offset,
  and ``|v''|`` peaks between two points of the scan's grid: a slip built so that
  ``v`` dips to ``−δ f_c`` (``δ = 10⁻¹¹``) in the middle of a cell, which a
  bound on ``|v''|`` without its fourth-order term clears (it misses every dip
  below ``10⁻⁹ f_c``), must end before that point;
* **at rest just beyond ``f_c``** (:func:`rest_rounding_row`).  ``φ = −k_i e_i − k_p s``
  is rounded, and the kernel puts a ``φ`` within its rounding of ``±f_c`` on the
  boundary; a state whose exact ``φ`` is ``f_c(1 + 40ε)``, more than that
  rounding but less than the rounding with ``k_i`` and ``k_p`` swapped (here
  ``k_p/k_i > 11`` and ``k_i|e_i| ≫ k_p|s|``), must start in the mode the
  appendix's table gives it in exact arithmetic: a slip (row (ii)), not the
  stick that ``σ < 0`` decides on the boundary.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from fractions import Fraction
from importlib import resources
from typing import Any

import numpy as np

__all__ = ["SCENARIOS", "STATE_TOL", "TIME_TOL", "INTEGRAL_TOL", "Scenario", "KernelRow", "kernel_rows", "reference_data",
           "DATA_FILE", "graze_row", "rest_rounding_row", "GRAZE", "REST"]

STATE_TOL = 1e-12
"""A sample's or an event's state may differ from the reference's by this much times the trajectory's scale."""

TIME_TOL = 1e-12
"""An event time may differ by this much times the horizon."""

INTEGRAL_TOL = 1e-12
"""The cross-check's ``∫₀^T v²`` may differ by this much times ``scale²·T``."""

DATA_FILE = "kernel_reference.json"

_GAINS = {"k_p": Fraction(3), "k_i": Fraction(4), "k_v": Fraction(32, 5)}  # Table I, case (a)
_Z0 = (0.3, 2.0, -1.0)  # per unit f_c: slips both ways, sticks from both sides (module docstring)
_T = 10.0
_F_CS = ("1", "2", "1e-6", "1e6")


@dataclass(frozen=True)
class Scenario:
    """One run of the kernel: gains, ``f_c`` (``f_s = f_c·ratio``), the scaled initial state, horizon and grid."""

    name: str
    f_c: str
    stiction: bool
    grid: str  # "uniform", "squared" or "after event"

    def params(self) -> Any:
        from .._infra.rational import to_rational
        from .._model.parameters import Parameters

        f_c = to_rational(self.f_c, name="f_c")
        return Parameters(**_GAINS, f_c=f_c, f_s=f_c * Fraction(6, 5) if self.stiction else None)

    def z0(self) -> tuple[float, float, float]:
        scale = float(Fraction(self.f_c))
        return tuple(c * scale for c in _Z0)  # type: ignore[return-value]

    def times(self, t_end: float) -> np.ndarray:
        if self.grid == "uniform":
            return np.linspace(0.0, t_end, 121)
        if self.grid == "squared":
            return t_end * (np.arange(61) / 60.0) ** 2
        return np.linspace(0.0, t_end, 25)


SCENARIOS: tuple[Scenario, ...] = tuple(
    Scenario(f"f_c={f}{', f_s=6/5 f_c' if st else ''}, {grid}", f, st, grid)
    for f in _F_CS for st in (False, True) for grid in ("uniform", "squared", "after event")
)
"""Every scenario ``check`` runs (module docstring)."""


@dataclass(frozen=True)
class KernelRow:
    """One scenario's verdict: ``ok``, and what differed first (empty when ok)."""

    scenario: str
    ok: bool
    detail: str


def _horizon(scenario: Scenario, data: dict) -> float:
    return float(data["t_end"]) if scenario.grid == "after event" else _T


def reference_data(scenarios: tuple[Scenario, ...] = SCENARIOS) -> dict[str, Any]:
    """What the 50-digit reference computes for each scenario (the content of :data:`DATA_FILE`).

    The uniform and squared grids and the probe of "after event" run the same ``(params, z₀, T)``:
    one :class:`~symbolic_friction._reference.Reference` (whose answers depend only on those) serves the three.
    """
    import mpmath

    from .._reference import Reference

    runs: dict[tuple[str, bool, float], Any] = {}

    def run(sc: Scenario, t_end: float) -> Any:
        key = (sc.f_c, sc.stiction, t_end)
        if key not in runs:
            runs[key] = Reference(sc.params(), sc.z0(), t_end)
        return runs[key]

    out: dict[str, Any] = {}
    for sc in scenarios:
        t_end = _T
        if sc.grid == "after event":
            t_end = float(run(sc, _T).events[2][0] * (1 + mpmath.mpf("1e-9")))
        ref = run(sc, t_end)
        t = sc.times(t_end)
        zs, modes = ref.sample(t)
        events = []
        for te, before, after in ref.events:
            x, _ = ref.x_at(te)
            events.append([float(te), int(before), int(after), [float(c) for c in x]])
        scale = ref.scale_of(zs)  # ref.scale(t), from the samples just taken
        entry = {"t_end": repr(t_end), "z": [[repr(float(c)) for c in z] for z in zs], "mode": [int(m) for m in modes],
                 "events": events, "scale": scale}
        if sc.grid == "uniform":
            entry["integral_v2"] = float(_integral_v2(ref, t_end))
        out[sc.name] = entry
    return out


def _integral_v2(ref: Any, t_end: float) -> Any:
    """``∫₀^T v²`` of the reference: mpmath quadrature on each piece between events.

    Between two events the mode is fixed, so ``v²`` is an entire function of ``t`` (sums of products of
    exponentials and trigonometric functions, or zero), where Gauss–Legendre converges at least as fast as
    mpmath's default tanh-sinh (made for singular endpoints): half the reference's states for the same
    30-digit sums.
    """
    import mpmath

    cuts = [mpmath.mpf(0)] + [te for te, _, _ in ref.events if te < t_end] + [mpmath.mpf(t_end)]
    with mpmath.workdps(30):
        return sum(mpmath.quad(lambda s: ref.z_mpf_at(s)[0][2] ** 2, [a, b], method="gauss-legendre")
                   for a, b in zip(cuts, cuts[1:]) if b > a)


def load_reference() -> dict[str, Any]:
    """The shipped reference numbers (:data:`DATA_FILE`)."""
    text = resources.files(__package__).joinpath(DATA_FILE).read_text(encoding="utf-8")
    return json.loads(text)


def kernel_rows(data: dict[str, Any] | None = None) -> tuple[KernelRow, ...]:
    """Run the kernel on every scenario and compare it with the reference (module docstring)."""
    from .._simulation.batch import simulate_batch
    from ._along import along

    data = load_reference() if data is None else data
    rows = []
    for sc in SCENARIOS:
        ref = data.get(sc.name)
        if ref is None:
            rows.append(KernelRow(sc.name, False, "no reference numbers for this scenario"))
            continue
        t_end = _horizon(sc, ref)
        t = sc.times(t_end)
        batch = simulate_batch(sc.params(), np.array([sc.z0()]), t_end, t_eval=t, max_events=64)
        detail = _compare(batch, ref, t_end)
        if not detail and "integral_v2" in ref:
            got = float(along(batch).cumI[0, -1])
            want = float(ref["integral_v2"])
            if not abs(got - want) <= INTEGRAL_TOL * ref["scale"] ** 2 * t_end:
                detail = f"the cross-check's ∫v² = {got!r}, the reference's {want!r}"
            if not detail:  # on the uniform grids, whose chain is built for ∫v² already
                detail = _slip_points_detail(batch, float(ref["scale"]))
        rows.append(KernelRow(sc.name, not detail, detail))
    return (*rows, graze_row(), rest_rounding_row())


def _slip_points_detail(batch: Any, scale: float) -> str:
    """``""`` if the cross-check's closed-form flow of every slip interval ends on the kernel's next point."""
    from ._along import along
    from .lemma3 import slip_points

    a = along(batch)
    rows, cols = np.nonzero(a.dt_pos & (a.k_int != 0))
    if rows.size == 0:
        return ""
    ends = slip_points(a, rows, cols, (1.0,))[:, 0]
    err = np.abs(ends - a.xs[rows, cols + 1]).max(axis=1)
    bad = np.flatnonzero(~(err <= STATE_TOL * scale))
    if not bad.size:
        return ""
    j = int(bad[0])
    start, got, want = float(a.ch.t[rows[j], cols[j]]), ends[j].tolist(), a.xs[rows[j], cols[j] + 1].tolist()
    return f"the cross-check's closed-form slip from t = {start!r} ends at {got}, the kernel's next point is {want}"


GRAZE = {"k_p": Fraction(900), "k_i": Fraction(80), "k_v": Fraction(1, 8), "f_c": Fraction(2)}
"""Lightly damped gains of the two exact rows (``k_v = 1/8 ≪ √k_p/8 = 3.75``; Assumption 1: ``k_v k_p = 112.5 > k_i``)."""

REST = (40, 1e-9)
"""The row at rest: ``φ = f_c(1 + 40ε)`` exactly, with ``s = 10⁻⁹ f_c`` (so ``σ = −k_i s < 0``)."""


def graze_row(*, cell: int = 10, depth: float = 1e-11) -> KernelRow:
    """A slip whose ``v`` dips to ``−depth·f_c`` in the middle of scan cell ``cell`` must end before it (module docstring).

    The state at ``τ_m = (cell + ½)Δ`` (``Δ`` the scan table's cell) is
    ``y = f_c (1, −k_v δ, −δ)`` about the slip's equilibrium ``(0, f_c, 0)``:
    ``v = −δ f_c``, ``v' = y₂ − k_v y₃ = 0``, ``v'' ≈ f_c`` (eq. subcasesAffine:f1);
    the slip starts at ``e^{−Aτ_m} y``, where ``v > 0``.  So ``v`` has a zero
    in ``(0, τ_m)``, and the kernel's first event must be there.
    """
    from .._model.coordinates import x_to_z
    from .._model.parameters import Parameters
    from .._simulation.batch import simulate_batch
    from .._simulation.slip import slip_model

    name = f"graze {depth:g}·f_c deep inside scan cell {cell} (k_v ≪ √k_p)"
    params = Parameters(**GRAZE)
    model = slip_model(params)
    f_c = float(params.f_c)
    tau_m = (cell + 0.5) * model.table.dt
    y = f_c * np.array([1.0, -float(params.k_v) * depth, -depth])
    y0 = model.expm.apply(np.array([-tau_m]), y)[0]
    # the construction itself: v > 0 at the start, v < 0 at τ_m (the closed form, independent of the scan)
    v_end = float(model.expm.apply(np.array([tau_m]), y0)[0, 2])
    if not (y0[2] > 0 and v_end < 0):
        return KernelRow(name, False, f"the built slip has v(0) = {y0[2]!r}, v(τ_m) = {v_end!r}: not a dip below 0")
    x0 = y0 + np.array([0.0, f_c, 0.0])
    batch = simulate_batch(params, x_to_z(params, x0[None, :]), 2 * tau_m, t_eval=np.array([0.0, 2 * tau_m]))
    n = int(batch.n_events[0])
    first = (float(batch.event_t[0, 0]), int(batch.event_before[0, 0])) if n else None
    if first is None or first[1] != 1 or not 0.0 < first[0] < tau_m:
        return KernelRow(name, False, f"the kernel's first event (t, mode before) is {first}; "
                                      f"v = {v_end!r} < 0 at τ_m = {tau_m!r}, so the slip ends before τ_m")
    return KernelRow(name, True, "")


def rest_rounding_row() -> KernelRow:
    """A state at rest with exact ``φ = f_c(1 + 40ε)``, ``σ < 0`` starts in the table's mode, a slip (module docstring)."""
    from .._model.parameters import Parameters
    from .._simulation.batch import simulate_batch
    from .._simulation.modes import select_mode

    ulps, s_rel = REST
    name = f"at rest {ulps} ulps beyond f_c (k_p/k_i > 11)"
    params = Parameters(**GRAZE)
    k_p, k_i, f_c = params.k_p, params.k_i, params.f_c
    s = s_rel * float(f_c)
    e_i = -(float(f_c) * (1 + ulps * 2.0**-52) + float(k_p) * s) / float(k_i)
    # the table in exact arithmetic at the float state given (x = T z, eq. CoC)
    sigma, phi = -k_i * Fraction(s), -k_i * Fraction(e_i) - k_p * Fraction(s)
    want = select_mode(sigma, phi, 0, f_c)
    batch = simulate_batch(params, np.array([[e_i, s, 0.0]]), 1e-3, t_eval=np.array([0.0, 1e-3]))
    got = int(batch.mode[0, 0])
    if got != want:
        return KernelRow(name, False, f"the kernel starts in mode {got}; the table gives φ − f_c = "
                                      f"{float(phi - f_c)!r} > 0 exactly, row (ii), mode {want}")
    return KernelRow(name, True, "")


def _compare(batch: Any, ref: dict[str, Any], t_end: float) -> str:
    """The first difference between one kernel run and the reference, or ``""``."""
    scale = float(ref["scale"])
    if not bool(batch.complete[0]):
        return f"the kernel stopped: {batch.status[0]}"
    want_z = np.array([[float(c) for c in z] for z in ref["z"]])
    err = np.abs(batch.z[0] - want_z).max(axis=1)
    bad = np.flatnonzero(~(err <= STATE_TOL * scale))
    if bad.size:
        j = int(bad[0])
        return f"at t = {batch.t[j]!r} the kernel's z = {tuple(batch.z[0, j])}, the reference's {tuple(want_z[j])}"
    modes = np.asarray(batch.mode[0], dtype=int)
    wrong = np.flatnonzero(modes != np.array(ref["mode"]))
    if wrong.size:
        j = int(wrong[0])
        return f"at t = {batch.t[j]!r} the kernel's mode is {modes[j]}, the reference's {ref['mode'][j]}"
    n = int(batch.n_events[0])
    if n != len(ref["events"]):
        return f"the kernel has {n} events, the reference {len(ref['events'])}"
    for e, (te, before, after, x) in enumerate(ref["events"]):
        got = (float(batch.event_t[0, e]), int(batch.event_before[0, e]), int(batch.event_after[0, e]))
        if got[1:] != (before, after) or not abs(got[0] - te) <= TIME_TOL * t_end:
            return f"event {e + 1}: the kernel's (t, before, after) = {got}, the reference's {(te, before, after)}"
        if not np.abs(batch.event_x[0, e] - np.array(x)).max() <= STATE_TOL * scale:
            return f"event {e + 1}: the kernel's x = {tuple(batch.event_x[0, e])}, the reference's {tuple(x)}"
    return ""
