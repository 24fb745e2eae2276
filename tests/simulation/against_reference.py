"""The one way the simulation tests compare the event-driven method with the mpmath reference."""

from __future__ import annotations

import numpy as np

from symbolic_friction._reference import Reference
from symbolic_friction._simulation import simulate


def simulate_and_reference(params, z0, t_end: float, samples: int):
    """``(solution, reference, z_ref, mode_ref)`` at ``samples`` equally spaced times in ``[0, t_end]``."""
    t = np.linspace(0.0, t_end, samples)
    sol = simulate(params, z0, t_end, t_eval=t)
    ref = Reference(params, z0, t_end)
    z_ref, mode_ref = ref.sample(t)
    return sol, ref, np.array(z_ref), np.array(mode_ref)


def scale_of(z0) -> float:
    """The scale of a state error: ``max(1, |z0|)``."""
    return max(1.0, float(np.linalg.norm(z0)))
