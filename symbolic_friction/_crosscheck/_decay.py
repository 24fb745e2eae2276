"""How ``|x(t)|_𝒜 → 0`` (Proposition 1, item 1): exponential or not?

The paper (Section III) explains why convergence is *not* exponential when
solutions keep sticking: during a stick phase starting with ``σ = σ̄``,
``φ`` ramps at rate ``σ̄`` across ``[-f_c, f_c]``, so the phase lasts about
``2f_c/|σ̄|`` while ``|x|_𝒜 = |σ̄|`` stays constant.  Near 𝒜 each slip
maps ``σ̄`` to a fixed multiple of itself (the slip dynamics are linear
around ``x*_k``), so ``|σ̄|`` shrinks geometrically per stick–slip cycle
while the cycle durations grow geometrically: the envelope decays like a
power of ``t``, not like ``e^{-λt}``.  When solutions stop sticking (three
real roots, case (b)), the last slip converges to ``x*_k = (0, ±f_c, 0)``
exponentially.

:func:`decay_fit` measures this: on long exact solutions it takes the
envelope ``D(t) = max_{s ≥ t} |x(s)|_𝒜`` over the tail and fits both
``log D = a - λt`` and ``log D = a - p log t``, reporting which fits better.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._model.parameters import Parameters

__all__ = ["DecayFit", "decay_fit"]


@dataclass(frozen=True)
class DecayFit:
    """Tail fits of ``|x(t)|_𝒜`` (medians over the trajectories).

    Attributes
    ----------
    trajectories : int
    horizon : float
    exponential_rate : float
        ``λ`` of ``D ≈ C e^{-λt}``.
    exponential_r2 : float
        Coefficient of determination of that fit (in ``log D``).
    power_exponent : float
        ``p`` of ``D ≈ C t^{-p}``.
    power_r2 : float
    stick_phases : float
        Median number of stick phases per trajectory on the horizon.
    verdict : str
        ``"power law"`` or ``"exponential"``: the better fit.
    """

    trajectories: int
    horizon: float
    exponential_rate: float
    exponential_r2: float
    power_exponent: float
    power_r2: float
    stick_phases: float
    verdict: str

    def describe(self) -> str:
        return (
            f"{self.verdict}: |x|_A tail ~ t^-{self.power_exponent:.3g} (R²={self.power_r2:.4f}) vs "
            f"e^(-{self.exponential_rate:.3g} t) (R²={self.exponential_r2:.4f}); "
            f"median {self.stick_phases:g} stick phases on [0, {self.horizon:g}]"
        )


def _fit(u: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    A = np.stack([np.ones_like(u), u], axis=1)
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    pred = A @ coef
    ss_res = float(np.sum((y - pred) ** 2))
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    return float(coef[1]), 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0


def decay_fit(params: Parameters, *, trajectories: int = 12, horizon: float = 2000.0, seed: int = 0) -> DecayFit:
    """Fit the tail of ``|x(t)|_𝒜`` on ``trajectories`` long exact solutions.

    Initial states are random on the sphere ``|x| = 3 f_c``; samples are
    geometric in ``t`` on ``[1, horizon]``; the tail is ``[horizon/100, horizon]``.
    """
    from .._model.attractor import distance_x
    from .._model.coordinates import x_to_z
    from .._simulation.batch import simulate_batch

    rng = np.random.default_rng(seed)
    g = rng.standard_normal((trajectories, 3))
    X0 = 3.0 * float(params.f_c) * g / np.linalg.norm(g, axis=1)[:, None]
    t = np.concatenate([[0.0], np.geomspace(1.0, horizon, 400)])
    batch = simulate_batch(params, x_to_z(params, X0), float(t[-1]), t_eval=t)
    d = distance_x(params, batch.x)
    env = np.maximum.accumulate(d[:, ::-1], axis=1)[:, ::-1]
    tail = t >= horizon / 100.0
    lam, r2e, p, r2p = [], [], [], []
    for row in env:
        ok = tail & (row > 1e-250)
        if np.count_nonzero(ok) < 10:
            continue
        y = np.log(row[ok])
        s1, q1 = _fit(t[ok], y)
        s2, q2 = _fit(np.log(t[ok]), y)
        lam.append(-s1)
        r2e.append(q1)
        p.append(-s2)
        r2p.append(q2)
    sticks = np.sum((batch.event_after == 0) & np.isfinite(batch.event_t), axis=1) + (batch.mode[:, 0] == 0)
    med = lambda a: float(np.median(a)) if len(a) else float("nan")  # noqa: E731
    verdict = "power law" if med(r2p) > med(r2e) else "exponential"
    return DecayFit(
        trajectories=len(lam),
        horizon=horizon,
        exponential_rate=med(lam),
        exponential_r2=med(r2e),
        power_exponent=med(p),
        power_r2=med(r2p),
        stick_phases=float(np.median(sticks)),
        verdict=verdict,
    )
