"""Simulation of the inclusion ``x' ∈ A x - b SGN(v)`` (eq. xDot / xPhDot).

One entry point, :func:`simulate`, and one class per method, each registered
in :data:`METHODS` by name and imported only when asked for (so that an
event-driven scene never imports scipy.integrate).
"""

from __future__ import annotations

import dataclasses
import importlib
from typing import Any

from .._infra.errors import SimulationError
from .._model.parameters import Parameters
from ._base import (
    SimulationMethod, Solution, _check_float_model, _check_horizon, _check_samples, _check_state, _check_t_eval,
)
from ._trajectories import Status, Trajectories

__all__ = [
    "simulate",
    "simulate_batch",
    "iter_batches",
    "Trajectories",
    "METHODS",
    "get_method",
    "method_class",
    "configure",
    "EventDriven",
    "Moreau",
    "Regularized",
    "IvpEvents",
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


def method_class(name: str) -> type[SimulationMethod]:
    """The class registered as ``name`` (its module imported on first use)."""
    if not isinstance(name, str) or name not in METHODS:
        raise SimulationError(f"unknown method {name!r}; expected one of {', '.join(sorted(METHODS))}")
    module_name, cls_name = METHODS[name].split(":")
    module = importlib.import_module(f"{__name__}.{module_name}")
    return getattr(module, cls_name)


def get_method(name: str) -> SimulationMethod:
    """The method registered as ``name``, with its default knobs."""
    method = _INSTANCES.get(name) if isinstance(name, str) else None
    if method is None:
        method = _INSTANCES[name] = method_class(name)()
    return method


def configure(method: Any, options: dict[str, Any]) -> SimulationMethod:
    """A configured method from a :class:`SimulationMethod` or a name, with ``options`` applied.

    Raises
    ------
    SimulationError
        For an unknown method, an unknown option or an invalid value.
    """
    if isinstance(method, SimulationMethod):
        base = method
    elif isinstance(method, str):
        if not options:
            return get_method(method)
        base = get_method(method)
    else:
        raise SimulationError(
            f"method must be a name ({', '.join(sorted(METHODS))}) or a configured method such as Moreau(h=1e-3); "
            f"got {type(method).__name__}"
        )
    if not options:
        return base
    unknown = sorted(set(options) - set(base.options))
    if unknown:
        raise SimulationError(
            f"unknown option(s) {', '.join(map(repr, unknown))} for method {base.name!r}; "
            f"expected some of {', '.join(sorted(base.options)) or '(none)'}"
        )
    return dataclasses.replace(base, **options)


def simulate(
    params: Parameters,
    z0: Any,
    t_end: float,
    *,
    method: Any = "event",
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
    method : SimulationMethod or {"event", "moreau", "regularized", "ivp-events"}, keyword-only
        A configured method (``EventDriven()``, ``Moreau(h=1e-3)``,
        ``Regularized(epsilon=1e-5, law="sat")``, ``IvpEvents(rtol=1e-10)``),
        or its name; ``"event"`` is the exact event-driven reference.
    t_eval : array_like, optional, keyword-only
        Sample times in ``[0, t_end]``; the solution is sampled exactly there.
    **options
        Accuracy knobs of the method (its fields), applied to ``method``.
        Unknown options raise :class:`SimulationError`.

    Returns
    -------
    Solution
        States ``z`` and ``x`` as ``(n_t, 3)`` rows; ``solution.states`` is
        ``z`` as ``(3, n_t)``, python-control's orientation.

    Examples
    --------
    >>> from symbolic_friction import Moreau, Parameters, simulate
    >>> p = Parameters.table_i("a")
    >>> sol = simulate(p, (0, 1, 0), 20)
    >>> sol.status, len(sol.events) > 0, sol.z.shape == (sol.t.size, 3)
    ('t_end reached', True, True)
    >>> rough = simulate(p, (0, 1, 0), 20, method=Moreau(h=1e-3), t_eval=sol.t)
    >>> bool(abs(rough.z - sol.z).max() < 1e-2)  # first order in h
    True
    """
    if not isinstance(params, Parameters):
        raise SimulationError(f"params must be a Parameters instance; got {type(params).__name__}")
    solver = configure(method, options)
    if params.stiction and not solver.stiction:
        raise SimulationError(
            f"method {solver.name!r} models Coulomb friction only (f_s = f_c); got f_s = {params.f_s} > f_c = {params.f_c}: "
            "use the event-driven method"
        )
    if params.reset and not solver.resets:
        raise SimulationError(
            f"method {solver.name!r} models the paper's PID only; got reset PID (reset_dwell = {params.reset_dwell}): "
            "use the event-driven method, whose resets are events"
        )
    longest = _check_float_model(params)
    z = _check_state(z0)
    t = _check_horizon(t_end, longest)
    te = _check_t_eval(t_eval, t)
    if te is not None and te.size > 100_000:  # the samples the result holds, before they are allocated
        _check_samples("t_eval's size", te.size, 1, te.size)
    return solver._solve(params, z, t, te, solver.options)


_CLASSES = {"EventDriven": "event", "Moreau": "moreau", "Regularized": "regularized", "IvpEvents": "ivp-events"}


def __getattr__(name: str) -> Any:
    # simulate_batch lives with the event method; import it (and the method classes) only when asked for
    if name in ("simulate_batch", "iter_batches"):
        from . import batch

        return getattr(batch, name)
    if name in _CLASSES:
        return method_class(_CLASSES[name])
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
