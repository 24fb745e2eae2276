"""The exact event-driven method over many initial states.

A batch is the one kernel of :mod:`._kernel` (one trajectory, closed-form
flows of eq. subcasesAffine, the appendix's mode table, the certified event
search of :mod:`.search`) run over every initial state, in parallel over the
cores when numba compiles it.  The result is the one trajectory type,
:class:`.Trajectories`.  Large batches stream: :func:`iter_batches` yields
chunks whose memory is bounded, whatever the number of initial states.
"""

from __future__ import annotations

from typing import Any, Iterator

import numpy as np

from .._infra.errors import SimulationError
from .._model.parameters import Parameters
from .._infra.guards import check_memory
from .._infra.rational import shown
from ._trajectories import Trajectories
from ._base import MAX_EVENTS, MAX_GRID_POINTS, _check_float_model, _check_horizon, _check_samples, _check_t_eval
from .event import _check_positive_int, run

__all__ = ["simulate_batch", "iter_batches", "DEFAULT_CHUNK"]

# Trajectories per chunk of iter_batches: with 301 samples a chunk holds about
# 16384 × 301 × (2 × 3 + 1) × 8 B ≈ 280 MB of samples at most.
DEFAULT_CHUNK = 16_384


def _check_states(Z0: Any) -> np.ndarray:
    if isinstance(Z0, (str, bytes, dict, set)):
        raise SimulationError(f"the initial states Z0 must be an (N, 3) array of numbers (e_i, s, v); got {shown(Z0)}")
    if isinstance(Z0, np.ndarray):  # its float copy and finiteness check, before they are made
        check_memory(name="Z0's length", value=Z0.shape[0] if Z0.ndim else 0, count=Z0.size, item_bytes=8 + 2,
                     what=f"{Z0.size} numbers of initial states", error=SimulationError)
    try:
        arr = np.asarray(Z0, dtype=float)
    except OverflowError:  # an integer or Fraction beyond float64 (10**400)
        raise SimulationError("the initial states Z0 must lie within the range of float64 (about ±1.8e308)") from None
    except (TypeError, ValueError):
        raise SimulationError("the initial states Z0 must be an (N, 3) array of numbers (e_i, s, v)") from None
    if arr.ndim != 2 or arr.shape[1] != 3 or arr.shape[0] == 0:
        raise SimulationError(f"the initial states Z0 must have shape (N, 3) with N ≥ 1; got shape {arr.shape}")
    bad = ~np.all(np.isfinite(arr), axis=1)
    if bad.any():
        i = int(np.argmax(bad))
        raise SimulationError(
            f"all initial states Z0 must be finite; {int(bad.sum())} row(s) are not, first row {i}: {arr[i].tolist()}"
        )
    return arr


def simulate_batch(
    params: Parameters,
    Z0: Any,
    t_end: float,
    *,
    t_eval: Any = None,
    max_events: int = 10_000,
    grid_points: int = 1001,
    source: Any = None,
) -> Trajectories:
    """Exact event-driven solutions from many initial states (the one kernel over each, in parallel).

    Parameters
    ----------
    params : Parameters
    Z0 : array_like, shape (N, 3)
        Initial states ``(e_i, s, v)``; must be finite.
    t_end : float
        Horizon, ``> 0``.
    t_eval : array_like, optional, keyword-only
        Common sample times in ``[0, t_end]`` (nondecreasing); default
        ``grid_points`` equally spaced times.
    max_events : int, keyword-only
        Stop a trajectory after this many mode changes (status ``MAX_EVENTS``).
    grid_points : int, keyword-only
        Number of default sample times when ``t_eval`` is None.
    source : array_like of str, shape (N,), optional, keyword-only
        A label per initial state, kept in the result.

    Returns
    -------
    Trajectories

    Examples
    --------
    >>> p = Parameters.table_i("a")
    >>> sol = simulate_batch(p, [[0, 5, 0], [0, 0, 3]], 30.0, t_eval=[0.0, 15.0, 30.0])
    >>> sol.z.shape, sol.n_events.tolist()
    ((2, 3, 3), [10, 6])
    """
    Z0, t_end, t_eval = _validated(params, Z0, t_end, t_eval, max_events, grid_points)
    if source is not None:
        if isinstance(source, (str, bytes, dict, set)):
            raise SimulationError(f"source must hold one label per initial state ({Z0.shape[0]}); got {shown(source)}")
        source = np.asarray(source, dtype=object).reshape(-1)
        if source.shape != (Z0.shape[0],):
            raise SimulationError(f"source must hold one label per initial state ({Z0.shape[0]}); got {source.size}")
    return run(params, Z0, t_end, t_eval, max_events=max_events, source=source, options={"max_events": max_events})


def _validated(params: Parameters, Z0: Any, t_end: Any, t_eval: Any, max_events: Any, grid_points: Any,
               chunk: int | None = None):

    if not isinstance(params, Parameters):
        raise SimulationError(f"params must be a Parameters instance; got {type(params).__name__}")
    _check_positive_int("max_events", max_events, 1, MAX_EVENTS)
    _check_positive_int("grid_points", grid_points, 2, MAX_GRID_POINTS)
    longest = _check_float_model(params)
    Z0 = _check_states(Z0)
    t_end = _check_horizon(t_end, longest)
    t_eval = _check_t_eval(t_eval, t_end)
    # the samples of the result (of one chunk), before numpy is asked for them
    rows = Z0.shape[0] if chunk is None else min(chunk, Z0.shape[0])
    if t_eval is None:
        _check_samples("grid_points", grid_points, rows, int(grid_points))
    else:
        _check_samples("t_eval's size", t_eval.size, rows, t_eval.size)
    if t_eval is None:
        t_eval = np.linspace(0.0, t_end, int(grid_points))
    return Z0, t_end, t_eval


def iter_batches(
    params: Parameters,
    Z0: Any,
    t_end: float,
    *,
    t_eval: Any = None,
    max_events: int = 10_000,
    grid_points: int = 1001,
    chunk: int = DEFAULT_CHUNK,
) -> Iterator[Trajectories]:
    """:func:`simulate_batch` in chunks of at most ``chunk`` initial states, yielded in order.

    Only one chunk's samples are held at a time, so a million trajectories
    stream through in bounded memory; reduce each chunk (``V``, the
    distance, a property check) before asking for the next.

    Examples
    --------
    >>> p = Parameters.table_i("a")
    >>> Z0 = np.zeros((5, 3)); Z0[:, 2] = np.arange(1, 6)
    >>> [len(b) for b in iter_batches(p, Z0, 10.0, t_eval=[0.0, 10.0], chunk=2)]
    [2, 2, 1]
    """
    _check_positive_int("chunk", chunk, 1)
    Z0, t_end, t_eval = _validated(params, Z0, t_end, t_eval, max_events, grid_points, chunk)
    for lo in range(0, Z0.shape[0], chunk):
        yield run(params, Z0[lo : lo + chunk], t_end, t_eval, max_events=max_events, options={"max_events": max_events})
