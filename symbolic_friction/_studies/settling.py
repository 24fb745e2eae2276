"""Settling of the paper's PID against reset PID, from one initial state, on exact trajectories (beyond the paper).

The paper's §IV: with Coulomb friction PID converges, but not exponentially,
because each stick lasts longer as ``s`` shrinks (``φ`` must travel the band
``[-f_c, f_c]`` at the rate ``σ = -k_i s``).  Reset PID
(:mod:`symbolic_friction._model.reset`) jumps ``φ`` to ``sign(σ) f_c`` at a
stick, so the stick ends at once.  Since ``σ`` is constant during a stick and
every stick ends at ``φ = sign(σ) f_s`` with or without the jump, **the
sequence of stick exits is the same for both controllers; resets only remove
stick time**.  Hence reset PID is never slower to reach a level of ``|s|``
(``tests/simulation/test_reset.py``), and with ``f_s > f_c`` it hunts on the
very cycle of PID (the hunting map ``P`` of :mod:`symbolic_friction._hunting`
is unchanged), which :func:`hunting_verdict` then reports as proved.

Everything here is measured on the event kernel's exact trajectories; only
the hunting cycle's existence is proved (the Krawczyk proof of the hunting
certificate).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any

from .._infra.errors import ParameterError
from .._model.parameters import Parameters

__all__ = ["ControllerRun", "SettlingComparison", "compare_settling", "hunting_verdict", "DEFAULT_DWELL", "MAX_SAMPLES",
           "Trajectory", "simulate_trajectory", "settled_at", "same_exits", "pid_refuted"]

DEFAULT_DWELL = Fraction(1, 100)
"""The reset's dwell time when the gains give none (any ``τ_d > 0`` is proved; this one is short against a slip)."""
MAX_SAMPLES = 200_001
"""Samples of each trajectory (plus its events): the settling time is resolved to ``t_end/(MAX_SAMPLES - 1)``."""
MAX_EVENTS = 1_000_000
_SAME_MAP = "; reset PID has PID's stick-exit map"


@dataclass(frozen=True)
class ControllerRun:
    """One controller's trajectory, summarised.

    Attributes
    ----------
    settling_time : float or None
        The first time after which ``|s| ≤ tol·|s(0)|`` up to ``t_end`` (on the
        samples and the events; ``|s|`` is constant in sticks), or None if
        ``|s(t_end)|`` is still above it.
    events, resets : int
        Mode changes and resets (a reset is an event too).
    overshoot : float
        ``max_t |x(t)|_𝒜 / |x(0)|_𝒜`` (eq. distFromA) on the samples.
    hunting : str
        ``"no (f_s = f_c: Proposition 1)"``, or the verdict of :func:`hunting_verdict`.
    t, s, V : ndarray
        The samples, ``s(t)`` and ``V(x(t))`` of eq. (lyapLikeV), for the figure.
    """

    name: str
    settling_time: float | None
    events: int
    resets: int
    overshoot: float
    hunting: str
    status: str
    t: Any = field(repr=False, compare=False, default=None)
    s: Any = field(repr=False, compare=False, default=None)
    V: Any = field(repr=False, compare=False, default=None)

    def as_json(self) -> dict[str, Any]:
        """The keys of ``settling --json``."""
        return {"settling_time": self.settling_time, "events": self.events, "resets": self.resets,
                "overshoot": self.overshoot, "hunting": self.hunting, "status": self.status}


@dataclass(frozen=True)
class SettlingComparison:
    """PID and reset PID from the same state: :class:`ControllerRun` each, and the inputs."""

    params: Parameters
    z0: tuple[Fraction, Fraction, Fraction]
    tol: Fraction
    t_end: float
    dwell: Fraction
    pid: ControllerRun
    reset: ControllerRun

    @property
    def speedup(self) -> float | None:
        """PID's settling time over reset's (inf if only reset settles, None if neither does)."""
        a, b = self.pid.settling_time, self.reset.settling_time
        if b is None:
            return None
        if a is None:
            return math.inf
        return a / b if b > 0 else (1.0 if a == 0 else math.inf)

    def as_json(self) -> dict[str, Any]:
        return {"gains": self.params.without_reset().as_strings(), "z0": [str(c) for c in self.z0], "tol": str(self.tol),
                "t_end": self.t_end, "reset_dwell": str(self.dwell), "pid": self.pid.as_json(), "reset": self.reset.as_json()}


_SETTLED = ("t_end reached", "equilibrium reached")
_EXIT_RTOL = 1e-6  # σ at matching stick exits of two runs agree to the float error of the event kernel


@dataclass(frozen=True)
class Trajectory:
    """One exact trajectory, summarised for settling: samples (and every event time), stick exits, resets."""

    t: Any
    x: Any
    s: Any
    status: str
    events: int
    resets: int
    exit_t: Any
    exit_sigma: Any

    @property
    def complete(self) -> bool:
        """Whether the kernel followed it to ``t_end`` (or onto 𝒜)."""
        return self.status in _SETTLED


def simulate_trajectory(params: Parameters, z0: Any, t_end: float, samples: int) -> Trajectory:
    """The event kernel from ``z0`` on ``samples`` equally spaced times plus every event time."""
    import numpy as np

    from .._simulation import simulate

    grid = np.linspace(0.0, t_end, samples)
    start = [float(c) for c in z0]
    sol = simulate(params, start, t_end, t_eval=grid, max_events=MAX_EVENTS)
    times = np.array([e[0] for e in sol.events], dtype=float)
    t = np.union1d(grid, times[np.isfinite(times)]) if times.size else grid
    if t.size != grid.size:  # |s| is sampled at every event too
        sol = simulate(params, start, t_end, t_eval=t, max_events=MAX_EVENTS)
    exits = [(e[0], float(x[0])) for e, x in zip(sol.events, np.asarray(sol.event_x)) if e[1] == 0 and e[2] != 0]
    return Trajectory(t=np.asarray(sol.t), x=np.asarray(sol.x), s=np.asarray(sol.z[:, 1]), status=sol.status,
                      events=len(sol.events), resets=sum(1 for e in sol.events if e[1:] == (0, 0)),
                      exit_t=np.array([e[0] for e in exits]), exit_sigma=np.array([e[1] for e in exits]))


def settled_at(t: Any, s: Any, level: float) -> float | None:
    """The first sample or event time after which ``|s| ≤ level`` up to the end; None if that is only the end."""
    import numpy as np

    above = np.nonzero(np.abs(s) > level)[0]
    if above.size == 0:
        return 0.0
    return None if above[-1] + 2 >= t.size else float(t[above[-1] + 1])


def same_exits(pid: Trajectory, reset: Trajectory) -> bool:
    """Whether PID's stick exits are, in ``σ``, the first of reset PID's (the module's key fact, measured)."""
    import numpy as np

    n = pid.exit_sigma.size
    if reset.exit_sigma.size < n:
        return False
    a, b = pid.exit_sigma, reset.exit_sigma[:n]
    return bool(np.all(np.abs(a - b) <= _EXIT_RTOL * np.maximum(np.abs(a), np.abs(b)) + 1e-300))


def pid_refuted(pid: Trajectory, reset: Trajectory, level: float) -> bool:
    """Whether PID, inside ``level`` from some time to ``t_end``, leaves it later: reset PID's run shows it.

    With the same stick exits, reset PID's run past its exit number
    ``len(pid exits) + 1`` is PID's future after ``t_end`` up to stick
    times; PID may end inside a long stick with small ``|s|`` and slip out of
    the level after ``t_end``.
    """
    import numpy as np

    if not (same_exits(pid, reset) and reset.exit_t.size > pid.exit_t.size):
        return False
    future = reset.s[reset.t >= reset.exit_t[pid.exit_t.size]]
    return bool(np.any(np.abs(future) > level))


def _run(name: str, params: Parameters, traj: Trajectory, level: float, hunting: str) -> ControllerRun:
    import numpy as np

    from .._model.attractor import distance_x
    from .._model.lyapunov import V

    d = distance_x(params, traj.x)
    d0 = float(d[0])
    return ControllerRun(
        name=name, settling_time=settled_at(traj.t, traj.s, level) if traj.complete else None,
        events=traj.events, resets=traj.resets, overshoot=float(np.nanmax(d) / d0) if d0 > 0 else math.nan,
        hunting=hunting, status=traj.status, t=traj.t, s=traj.s, V=np.asarray(V(params, traj.x), dtype=float),
    )


def hunting_verdict(params: Parameters, *, prove: bool = True) -> str:
    """Whether the loop hunts: ``"no (…)"``, ``"cycle proven (…)"``, ``"cycle found, not proven"`` or ``"no cycle found"``.

    With ``f_s = f_c`` Proposition 1 rules hunting out (for reset PID the
    ``reset.*`` obligations with the hybrid invariance principle).  With
    ``f_s > f_c`` the symmetric cycles of the hunting map are searched and the
    first is proved by the Krawczyk test (:func:`symbolic_friction.prove_cycle`);
    reset PID has the same map (module docstring), so the same verdict.
    """
    if not params.stiction:
        return "no (f_s = f_c: Proposition 1)" if not params.reset else "no (f_s = f_c: reset.* obligations)"
    from .._hunting._map import find_cycles

    plain = params.without_reset()
    cycles = find_cycles(plain, general=False)
    if not cycles:
        return "no cycle found"
    cycle = cycles[0]
    same = _SAME_MAP if params.reset else ""
    if prove:
        from .._hunting._study import certificate_for

        _, proof = certificate_for(plain, cycle.sigma, cycle.slip_time)
        if proof.proved:
            return f"cycle proven (σ* = {cycle.sigma:.6g}, period {cycle.period:.6g}{same})"
    return f"cycle found, not proven (σ* = {cycle.sigma:.6g}{same})"


def compare_settling(
    params: Parameters,
    z0: Any = (0, 3, 0),
    *,
    tol: Any = Fraction(1, 10**6),
    t_end: float = 200.0,
    dwell: Any = None,
    samples: int = 20001,
    prove_hunting: bool = True,
) -> SettlingComparison:
    """Simulate the paper's PID and reset PID exactly from ``z0 = (e_i, s, v)`` and compare their settling.

    Parameters
    ----------
    params : Parameters
        The gains (a ``reset_dwell`` in them is the reset's dwell time).
    z0 : 3 numbers, keyword
        The initial state, exact.
    tol : number, keyword-only
        Settled when ``|s| ≤ tol·|s(0)|`` from then on (``|s(0)| = 0``: relative to ``max |s|``).
    t_end : float, keyword-only
    dwell : number or None, keyword-only
        The reset's dwell time (default: the gains', else :data:`DEFAULT_DWELL`).
    samples : int, keyword-only
        Sample times on ``[0, t_end]`` besides the events (2 to :data:`MAX_SAMPLES`).
    prove_hunting : bool, keyword-only
        With ``f_s > f_c``, prove the hunting cycle (about a second) or only find it.

    Raises
    ------
    ParameterError
        If ``tol`` is not in ``(0, 1)``, ``t_end`` not positive and finite, or ``samples`` out of range.

    Examples
    --------
    >>> c = compare_settling(Parameters.table_i("b"), (-5, "0.3", "1.2"), t_end=120.0, samples=2001)
    >>> c.pid.settling_time > c.reset.settling_time, c.reset.resets
    (True, 1)
    """
    from .._infra.rational import to_rational

    tol = to_rational(tol, name="tol")
    if not 0 < tol < 1:
        raise ParameterError(f"tol must be in (0, 1); got {tol}")
    if not (isinstance(t_end, (int, float)) and math.isfinite(t_end) and 0 < t_end <= 1e9):
        raise ParameterError(f"t_end must be a positive finite time up to 1e9; got {t_end!r}")
    if isinstance(samples, bool) or not isinstance(samples, int) or not 2 <= samples <= MAX_SAMPLES:
        raise ParameterError(f"samples must be an integer in 2..{MAX_SAMPLES}; got {samples!r}")
    if not hasattr(z0, "__len__") or len(z0) != 3:
        raise ParameterError(f"z0 must be three numbers (e_i, s, v); got {z0!r}")
    z = tuple(to_rational(c, name=f"z0[{i}]") for i, c in enumerate(z0))
    if dwell is None:
        dwell = params.reset_dwell if params.reset else DEFAULT_DWELL
    with_reset = replace(params, reset_dwell=dwell)
    plain = params.without_reset()
    hunting_pid = hunting_verdict(plain, prove=prove_hunting)
    # the same stick-exit map (reset.same_stick_exits): PID's verdict holds for reset PID, said so
    hunting_reset = hunting_verdict(with_reset, prove=prove_hunting)
    pid_traj = simulate_trajectory(plain, z, float(t_end), samples)
    reset_traj = simulate_trajectory(with_reset, z, float(t_end), samples)
    import numpy as np

    level = float(tol) * (abs(float(z[1])) if z[1] != 0 else float(np.nanmax(np.abs(pid_traj.s))))
    pid = _run("pid", plain, pid_traj, level, hunting_pid)
    if pid.settling_time is not None and pid_refuted(pid_traj, reset_traj, level):
        pid = replace(pid, settling_time=None)  # settled on [0, t_end] only by a long stick
    return SettlingComparison(
        params=plain, z0=z, tol=tol, t_end=float(t_end), dwell=with_reset.reset_dwell,
        pid=pid, reset=_run("reset", with_reset, reset_traj, level, hunting_reset),
    )


def write_settling_figure(comparison: SettlingComparison, path) -> None:
    """``|s(t)|`` and ``V(x(t))`` for both controllers, log scale, written atomically to ``path`` (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from .._infra.io import atomic_write

    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for run, style in ((comparison.pid, "-"), (comparison.reset, "--")):
        label = f"{run.name} (settles {'never' if run.settling_time is None else f'at {run.settling_time:.4g}'})"
        axes[0].semilogy(run.t, np.maximum(np.abs(run.s), 1e-300), style, label=label)
        axes[1].semilogy(run.t, np.maximum(run.V, 1e-300), style, label=run.name)
    axes[0].axhline(float(comparison.tol) * max(abs(float(comparison.z0[1])), 1e-300), color="grey", lw=0.8)
    axes[0].set_ylabel("|s(t)|")
    axes[1].set_ylabel("V(x(t))")
    axes[1].set_xlabel("t")
    axes[0].legend()
    axes[0].set_title(f"{comparison.params}: PID and reset PID (dwell {comparison.dwell})")
    try:
        atomic_write(path, lambda handle: fig.savefig(handle, format="png", dpi=110))
    finally:
        plt.close(fig)
