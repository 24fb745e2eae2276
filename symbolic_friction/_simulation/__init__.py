"""Simulation of the inclusion ``x' ∈ A x - b SGN(v)`` (eq. xDot / xPhDot).

One entry point, :func:`simulate`, and one class per method, each registered
in :data:`METHODS` by name and imported only when asked for (so that an
event-driven scene never imports scipy.integrate).
"""

from __future__ import annotations

import importlib
import math
from typing import Any

import numpy as np

from .._errors import SimulationError
from .._parameters import Parameters
from ._base import SimulationMethod, Solution
from ._trajectories import Status, Trajectories

__all__ = [
    "simulate",
    "simulate_batch",
    "iter_batches",
    "Trajectories",
    "METHODS",
    "get_method",
    "Solution",
    "SimulationMethod",
    "Status",
]

# method name -> "module:Class", relative to this package
METHODS: dict[str, str] = {
    "event": "event:EventDriven",
    "moreau": "moreau:Moreau",
    "regularized": "regularized:Regularized",
    "ivp-events": "ivp_events:IvpEvents",
}


_INSTANCES: dict[str, SimulationMethod] = {}


def get_method(name: str) -> SimulationMethod:
    """The method registered as ``name`` (its module imported on first use)."""
    method = _INSTANCES.get(name) if isinstance(name, str) else None
    if method is not None:
        return method
    if not isinstance(name, str) or name not in METHODS:
        raise SimulationError(f"unknown method {name!r}; expected one of {', '.join(sorted(METHODS))}")
    module_name, cls_name = METHODS[name].split(":")
    module = importlib.import_module(f"{__name__}.{module_name}")
    method = _INSTANCES[name] = getattr(module, cls_name)()
    return method


def _check_state(z0: Any) -> np.ndarray:
    try:
        arr = np.asarray(z0, dtype=float)
    except (TypeError, ValueError):
        raise SimulationError(f"the initial state z0 must be three numbers (e_i, s, v); got {z0!r}") from None
    if arr.shape != (3,):
        raise SimulationError(f"the initial state z0 must have shape (3,) as (e_i, s, v); got shape {arr.shape}")
    if not all(map(math.isfinite, arr.tolist())):
        raise SimulationError(f"all components of the initial state z0 must be finite; got {arr.tolist()}")
    return arr


def _check_horizon(t_end: Any) -> float:
    try:
        t = float(t_end)
    except (TypeError, ValueError):
        raise SimulationError(f"t_end must be a number; got {t_end!r}") from None
    if not math.isfinite(t) or t <= 0:
        raise SimulationError(f"t_end must be finite and > 0; got {t_end!r}")
    return t


def _check_t_eval(t_eval: Any, t_end: float) -> np.ndarray | None:
    if t_eval is None:
        return None
    arr = np.asarray(t_eval, dtype=float)
    if arr.ndim != 1 or arr.size == 0:
        raise SimulationError(f"t_eval must be a non-empty 1-D sequence of times; got shape {arr.shape}")
    if not np.isfinite(arr.sum()) and not np.isfinite(arr).all():  # the sum is finite for finite times (cheap)
        raise SimulationError("t_eval must contain only finite times")
    if arr[0] < 0 or arr[-1] > t_end or (arr[1:] < arr[:-1]).any():
        raise SimulationError(
            f"t_eval must be nondecreasing within [0, t_end] = [0, {t_end:g}]; got range [{arr.min():g}, {arr.max():g}]"
        )
    return arr


def simulate(
    params: Parameters,
    z0: Any,
    t_end: float,
    *,
    method: str = "event",
    t_eval: Any = None,
    **options: Any,
) -> Solution:
    """Simulate the inclusion (eq. xPhDot) from ``z0 = (e_i, s, v)`` over ``[0, t_end]``.

    Parameters
    ----------
    params : Parameters
    z0 : array_like, shape (3,)
        Initial state ``(e_i, s, v)``; must be finite.
    t_end : float
        Horizon, ``> 0``.
    method : {"event", "moreau", "regularized", "ivp-events"}, keyword-only
        ``"event"`` is the exact event-driven reference.
    t_eval : array_like, optional, keyword-only
        Sample times in ``[0, t_end]``; the solution is sampled exactly there.
    **options
        Accuracy knobs of the method (see each method's ``options``).
        Unknown options raise :class:`SimulationError`.

    Returns
    -------
    Solution
    """
    if not isinstance(params, Parameters):
        raise SimulationError(f"params must be a Parameters instance; got {type(params).__name__}")
    solver = get_method(method)
    unknown = sorted(set(options) - set(solver.options))
    if unknown:
        raise SimulationError(
            f"unknown option(s) {', '.join(map(repr, unknown))} for method {method!r}; "
            f"expected some of {', '.join(sorted(solver.options)) or '(none)'}"
        )
    merged = {**solver.options, **options}
    solver._validate(merged)
    z = _check_state(z0)
    t = _check_horizon(t_end)
    te = _check_t_eval(t_eval, t)
    return solver._solve(params, z, t, te, merged)


def __getattr__(name: str) -> Any:
    # simulate_batch lives with the event method; import it only when asked for
    if name in ("simulate_batch", "iter_batches"):
        from . import batch

        return getattr(batch, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
