"""The cross-check's simulations, each done once within a block that shares them.

:func:`simulate` is :func:`~.._simulation.batch.simulate_batch`; within
:func:`shared_simulations` the same arguments give the trajectories computed
before.  The solutions depend on the gains, the initial states and the times
alone (Lemma 1: one solution from each state), so the self-test, which checks a
proved certificate and then its wrong variants on the same gain set, seed and
initial states, simulates them once.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from .._model.parameters import Parameters

__all__ = ["simulate", "shared_simulations"]

@functools.cache
def _simulations() -> Any:
    """The :class:`~.._certify._memo.Memo` of :func:`simulate`, made on first use (importing ``_certify`` at module
    level would load its verifiers with the cross-check)."""
    from .._certify._memo import Memo

    return Memo()


def shared_simulations() -> Any:
    """A block within which :func:`simulate` on the same arguments returns the trajectories it returned before."""
    return _simulations().sharing()


def simulate(params: Parameters, Z0: np.ndarray, t_end: float, *, t_eval: np.ndarray, max_events: int,
             source: np.ndarray | None = None) -> Any:
    """:func:`~.._simulation.batch.simulate_batch`, or within :func:`shared_simulations` its result for the same
    exact arguments (the bytes of the states and times, the horizon, the event limit and the labels).

    A kept result is the same object, read by every property (and :func:`~._along.along`'s view of it, kept
    per object); nothing that reads trajectories writes into them.
    """
    from .._simulation.batch import simulate_batch

    Z0, t_eval = np.ascontiguousarray(Z0, dtype=float), np.ascontiguousarray(t_eval, dtype=float)
    key = (params, Z0.shape, Z0.tobytes(), float(t_end), t_eval.tobytes(), int(max_events),
           None if source is None else tuple(str(s) for s in source))
    return _simulations().get(key, lambda: simulate_batch(params, Z0, t_end, t_eval=t_eval, max_events=max_events,
                                                          source=source))
