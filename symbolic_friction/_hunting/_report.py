"""What ``symbolic-friction hunting`` computes for one gain set: search, proof, simulation check, figure.

* :func:`simulation_agreement`: a long exact simulation from a nearby stick
  exit; after the transient its stick exits must repeat the cycle's (``σ``
  and the exit times) to within the stated tolerance;
* :func:`amplitude_sweep`: the cycle over a range of ``f_s/f_c``;
* :func:`hunting_figure`: the cycle in the phase plane, the map ``P`` with its
  fixed point, and the sweep.
"""

from __future__ import annotations

import dataclasses

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from .._model.parameters import Parameters
from ._map import HuntingCycle, HuntingMap, find_cycles

__all__ = ["Agreement", "simulation_agreement", "amplitude_sweep", "hunting_figure", "with_static"]


def with_static(params: Parameters, f_s: object) -> Parameters:
    """``params`` with the static level ``f_s`` (validated again: ``f_s ≥ f_c``)."""
    return dataclasses.replace(params, f_s=f_s)


@dataclass(frozen=True)
class Agreement:
    """The cycle against a long exact simulation from a nearby start.

    Attributes
    ----------
    start_offset : float
        Relative change of ``σ`` at the start (``σ*(1 + start_offset)``).
    periods : int
        Periods simulated.
    exits : int
        Stick exits in the simulation.
    sigma_error : float
        ``max | |σ| - σ* |`` over the last ``tail`` exits.
    half_period_error : float
        ``max |Δt - T/2|`` between the last ``tail`` consecutive exits.
    state_error : float
        ``max |z_exit ∓ z*|`` (infinity norm, ``z*`` the cycle's exit state) over the last exits.
    tail : int
    last_sigmas : tuple of float
        ``|σ|`` at the last ``tail`` exits (to be compared with a proved box).
    """

    start_offset: float
    periods: int
    exits: int
    sigma_error: float
    half_period_error: float
    state_error: float
    tail: int
    last_sigmas: tuple = ()

    def holds(self, tol: float = 1e-9) -> bool:
        return self.exits > self.tail and max(self.sigma_error, self.half_period_error, self.state_error) <= tol

    def describe(self) -> str:
        return (
            f"long exact simulation ({self.periods} periods from σ = σ*(1 {self.start_offset:+g}), {self.exits} stick exits): "
            f"last {self.tail} exits within |Δσ| ≤ {self.sigma_error:.2e}, |Δz| ≤ {self.state_error:.2e}, "
            f"|Δt - T/2| ≤ {self.half_period_error:.2e}"
        )


def simulation_agreement(cycle: HuntingCycle, *, start_offset: float = 1e-3, periods: int | None = None, tail: int = 6) -> Agreement:
    """Simulate from the stick exit ``σ*(1 + start_offset)`` and compare the last stick exits with the cycle."""
    from .._simulation import simulate

    m = abs(cycle.multiplier)
    if periods is None:
        # enough half periods for start_offset·|m|ⁿ to fall below 1e-14 (the transient), plus the tail
        n = 20 if m < 1e-3 else int(math.ceil(math.log(1e-14 / start_offset) / math.log(min(m, 0.999)))) + tail + 4
        periods = max(4, int(math.ceil(n / 2)))
    z0 = dataclasses.replace(cycle, sigma=cycle.sigma * (1.0 + start_offset)).exit_state
    t_end = periods * cycle.period
    sol = simulate(cycle.params, z0, t_end, t_eval=[0.0, t_end], max_events=100_000)
    exits = [(t, x) for (t, before, _), x in zip(sol.events, sol.event_x) if before == 0]
    star = np.array(cycle.exit_state)
    if len(exits) <= tail:
        return Agreement(start_offset, periods, len(exits), math.inf, math.inf, math.inf, tail)
    last = exits[-tail:]
    sig_err = max(abs(abs(x[0]) - cycle.sigma) for _, x in last)
    from .._model.coordinates import x_to_z

    z_err = 0.0
    for _, x in last:
        z = np.asarray(x_to_z(cycle.params, np.asarray(x, dtype=float)[None]))[0]
        z_err = max(z_err, float(np.max(np.abs(z - np.sign(x[0]) * star))))
    times = [t for t, _ in exits[-(tail + 1):]]
    dt_err = max(abs((b - a) - cycle.period / 2) for a, b in zip(times, times[1:]))
    return Agreement(
        start_offset, periods, len(exits), float(sig_err), float(dt_err), float(z_err), tail,
        tuple(abs(float(x[0])) for _, x in last),
    )


def amplitude_sweep(params: Parameters, ratios) -> list[tuple[float, HuntingCycle | None]]:
    """The (stable-or-not) symmetric cycle with the largest ``σ*`` at each ``f_s/f_c`` in ``ratios``."""
    out = []
    for r in ratios:
        q = with_static(params, params.f_c * Fraction(str(r)))
        cycles = [c for c in find_cycles(q, general=False) if c.symmetric]
        out.append((float(r), cycles[-1] if cycles else None))
    return out


def hunting_figure(cycle: HuntingCycle, path, *, sweep=None) -> None:
    """Phase plane of the cycle, the map ``σ ↦ -P(σ)`` with its fixed point, and the sweep (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .._infra.io import atomic_write
    from ._map import cycle_orbit

    P = HuntingMap(cycle.params)
    orbit = cycle_orbit(cycle, samples=20001)
    ncols = 3 if sweep else 2
    fig, axes = plt.subplots(1, ncols, figsize=(5.0 * ncols, 4.2))
    ax = axes[0]
    stick = orbit.mode == 0
    ax.plot(orbit.z[:, 1], orbit.z[:, 2], lw=1.2, color="C0", label="slip")
    ax.plot(orbit.z[stick, 1], orbit.z[stick, 2], ".", ms=3, color="C3", label="stick")
    ax.set_xlabel("position s")
    ax.set_ylabel("velocity v")
    ax.set_title(f"hunting cycle, period {cycle.period:.4g}")
    ax.legend(loc="best", fontsize=8)
    ax = axes[1]
    grid = np.linspace(cycle.sigma * 0.05, cycle.sigma * 3.0, 300)
    minus_p = np.array([-P(s) for s in grid])
    ax.plot(grid, minus_p, color="C0", label="σ ↦ -P(σ)")
    ax.plot(grid, grid, "--", color="0.5", lw=0.8, label="identity")
    ax.plot([cycle.sigma], [cycle.sigma], "o", color="C3", label=f"σ* = {cycle.sigma:.6g} (multiplier {cycle.multiplier:.3g})")
    ax.set_xlabel("σ at a stick exit (φ = f_s)")
    ax.set_ylabel("-σ at the next stick exit")
    ax.set_title("the hunting map")
    ax.legend(loc="best", fontsize=8)
    if sweep:
        ax = axes[2]
        rs = [r for r, c in sweep if c is not None]
        amp = [c.amplitude_distance for r, c in sweep if c is not None]
        amp_s = [c.amplitude_s for r, c in sweep if c is not None]
        ax.plot([1.0] + rs, [0.0] + amp, "o-", label=r"max $|z|_{\mathcal{A}}$")
        ax.plot([1.0] + rs, [0.0] + amp_s, "s-", label="max |s|")
        ax.set_xlabel("f_s / f_c")
        ax.set_ylabel("cycle amplitude")
        ax.set_title("amplitude grows from 0 at f_s = f_c")
        ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    atomic_write(path, lambda fh: fig.savefig(fh, format="png", dpi=110))
    plt.close(fig)
