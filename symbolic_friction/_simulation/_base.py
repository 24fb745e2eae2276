"""The simulation contract: one result type and one base class for methods.

Lemma 1: the inclusion ``x' ∈ A x - b SGN(v)`` (eq. xDot) has a unique
solution from every initial state, and in each mode it is affine in closed
form (slip ``v > 0``: ``x' = Ax - b``; stick: ``σ' = 0, φ' = σ, v = 0``;
slip ``v < 0``: ``x' = Ax + b``).  Every method below approximates (or, for
``event``, computes) that solution.
"""

from __future__ import annotations

import abc
import functools
import math
from dataclasses import dataclass, fields
from typing import Any, ClassVar

import numpy as np

from .._infra.errors import SimulationError
from .._infra.guards import check_memory, check_real
from .._infra.rational import shown
from .._model.parameters import Parameters
from ._trajectories import Solution, Status

__all__ = ["Solution", "SimulationMethod", "Status", "RTOL_FLOOR", "check_rtol", "finite_or_raise", "as_float"]

EPS = 2.220446049250313e-16
# scipy's solve_ivp silently raises a smaller rtol to this; the package refuses instead
RTOL_FLOOR = 100 * EPS


def check_rtol(rtol: Any) -> None:
    """Refuse an ``rtol`` below what float64 resolves (a knob that would silently not be honoured)."""
    if float(rtol) < RTOL_FLOOR:
        raise SimulationError(
            f"option rtol = {float(rtol):.3g} is below what float64 can resolve (scipy would silently use "
            f"{RTOL_FLOOR:.3g}); use rtol ≥ {RTOL_FLOOR:.3g}"
        )


def as_float(value: Any) -> float:
    """``float(value)``, with an integer beyond float64 (``10**400``) read as ±inf rather than raising OverflowError."""
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def finite_or_raise(method: str, t: np.ndarray, z: np.ndarray) -> None:
    """Refuse samples that left the range of float64 (inf or NaN), naming where."""
    bad = ~np.isfinite(z).all(axis=-1)
    if bad.any():
        i = int(np.argmax(bad))
        raise SimulationError(
            f"the {method} solution leaves the range of float64 (about ±1.8e308) at t = {float(t[i]):g}: "
            "scale the initial state down"
        )


# -- the arguments of simulate and simulate_batch, checked once for every method --
MAX_TIME_CONSTANTS = 1e300
"""``t_end·‖A‖∞`` is at most this: a longer horizon (``t_end = 1e308``) leaves the range of float64 in the
time arithmetic of every method (a count of steps or scan cells overflows), so it is refused up front."""


@functools.lru_cache(maxsize=256)  # once per gain set: simulate() is called per trajectory
def _check_float_model(params: Parameters) -> float:
    """Refuse gains whose float64 model does not exist: the coordinate change ``z = T⁻¹ x`` (eq. CoC) and ``A``
    need ``k_i²``, ``k_p/k_i²``, ``k_v`` and ``f_c`` representable, neither zero nor infinite.

    Exact work (``certify``, the obligations) takes any positive rational; a simulation computes in float64.

    Returns
    -------
    float
        The longest horizon a simulation of these gains may ask for, ``MAX_TIME_CONSTANTS/‖A‖∞``.
    """
    from .._model.coordinates import coc_inverse_entries

    k_p, k_i, k_v, f_c = params.as_floats()
    try:
        entries = [x for row in coc_inverse_entries(k_p, k_i) for x in row]
        ok = all(math.isfinite(x) for x in (*entries, k_p, k_i, k_v, f_c)) and min(k_p, k_i, k_v, f_c, k_i * k_i) > 0
    except (ZeroDivisionError, OverflowError):
        ok = False
    if not ok:
        raise SimulationError(
            f"these gains are beyond what a float64 simulation can represent (k_p = {k_p:g}, k_i = {k_i:g}, "
            f"k_v = {k_v:g}, f_c = {f_c:g}: k_i², k_p/k_i² and the gains must be finite and nonzero in float64); "
            "rescale time or the state (the exact commands, certify and check, take them as they are)"
        )
    return MAX_TIME_CONSTANTS / max(k_i, 1.0 + k_p, 1.0 + k_v)


def _check_state(z0: Any) -> np.ndarray:
    try:
        arr = np.asarray(z0, dtype=float)
    except OverflowError:  # an integer or Fraction beyond float64 (10**400)
        raise SimulationError(
            f"the initial state z0 must be within the range of float64 (about ±1.8e308); got {shown(z0)}"
        ) from None
    except (TypeError, ValueError):
        raise SimulationError(f"the initial state z0 must be three numbers (e_i, s, v); got {shown(z0)}") from None
    if arr.shape != (3,):
        raise SimulationError(f"the initial state z0 must have shape (3,) as (e_i, s, v); got shape {arr.shape}")
    if not all(map(math.isfinite, arr.tolist())):
        raise SimulationError(f"all components of the initial state z0 must be finite; got {arr.tolist()}")
    return arr


def _check_horizon(t_end: Any, longest: float = math.inf) -> float:
    if type(t_end) is float and 0.0 < t_end <= longest:  # the fast path of every call
        return t_end
    if type(t_end) is int and 0 < t_end <= longest:
        return float(t_end)
    return check_real(t_end, name="t_end", low=0, high=None if math.isinf(longest) else longest, error=SimulationError,
                      why=f"for these gains, t_end·‖A‖∞ ≤ {MAX_TIME_CONSTANTS:g}: beyond it time leaves float64's range")


def _check_t_eval(t_eval: Any, t_end: float) -> np.ndarray | None:
    if t_eval is None:
        return None
    if isinstance(t_eval, (str, bytes, dict, set)):
        raise SimulationError(f"t_eval must be a non-empty 1-D sequence of times; got {shown(t_eval)}")
    try:
        arr = np.asarray(t_eval, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise SimulationError(f"t_eval must be a non-empty 1-D sequence of finite times; got {shown(t_eval)}") from None
    if arr.ndim != 1 or arr.size == 0:
        raise SimulationError(f"t_eval must be a non-empty 1-D sequence of times; got shape {arr.shape}")
    # Written so that NaN fails every comparison: nondecreasing within [0, t_end] implies finite.
    if not (arr[0] >= 0 and arr[-1] <= t_end and (arr[1:] >= arr[:-1]).all()):
        if not np.isfinite(arr).all():
            raise SimulationError("t_eval must contain only finite times")
        raise SimulationError(
            f"t_eval must be nondecreasing within [0, t_end] = [0, {t_end:g}]; got range [{arr.min():g}, {arr.max():g}]"
        )
    return arr


def _check_samples(name: str, value: Any, trajectories: int, samples: int) -> None:
    """Refuse, before numpy allocates them, result arrays beyond the memory cap (:data:`.._infra.guards.MAX_BYTES`)."""
    check_memory(name=name, value=value, count=trajectories, item_bytes=SAMPLE_BYTES * samples + TRAJECTORY_BYTES,
                 what=f"{trajectories} trajectories × {samples} samples", error=SimulationError,
                 hint="fewer samples, or fewer trajectories at a time (iter_batches streams them in chunks)")


MAX_EVENTS = 1_000_000
"""The most events ``max_events`` may allow one trajectory (a hunting trajectory takes about 3 s per 10⁶ events, and
each event is a sample too: 42 + 49 B)."""
MAX_GRID_POINTS = 10_000_000
"""The most sample times ``grid_points`` may ask for (49 B per sample of a trajectory)."""
SAMPLE_BYTES = 2 * 3 * 8 + 1
"""Bytes of one sample of one trajectory in a result: ``z`` and ``x`` (3 float64 each) and the mode (int8)."""
TRAJECTORY_BYTES = 2 * 32 * 42 + 512
"""Bytes of one trajectory besides its samples: its first event buffers, its state, status and stop time."""


@dataclass(frozen=True, kw_only=True)
class SimulationMethod(abc.ABC):
    """Base class of a simulation method: a frozen configuration whose fields are its accuracy knobs.

    ``simulate(params, z0, t_end, method=Moreau(h=1e-3))`` runs a configured
    method; ``method="moreau", h=1e-3`` builds the same object from its name.

    Contract for implementers
    -------------------------
    * Subclass as ``@dataclass(frozen=True, kw_only=True)``; every field is
      a keyword option with its default (an accuracy knob, or a limit).
    * Set the class variables ``name`` (the ``method=`` string), ``order``
      (the declared order of accuracy in ``knob``: the error behaves like
      ``knob**order``; ``math.inf`` for an exact method) and ``knob`` (the
      field that trades speed for accuracy, or ``None``).  Set ``stiction =
      True`` only if the method models static friction above Coulomb
      (``f_s > f_c``); ``simulate`` refuses such parameters to the others.
      Likewise ``resets = True`` only if it models reset PID
      (``Parameters.reset_dwell``).
    * Implement :meth:`_validate`, called on construction with
      :attr:`options`, which raises
      :class:`~symbolic_friction.SimulationError` naming the option and the
      value.
    * Implement :meth:`_solve`, which receives validated float data and
      returns a :class:`Solution`.  With ``t_eval`` given, the samples must
      be exactly at those times.  It must never return a silently wrong
      answer: leaving the valid range (overflow, a knob float64 cannot
      resolve, a step larger than the horizon) raises ``SimulationError`` or
      ends with a status that says so.
    """

    name: ClassVar[str]
    order: ClassVar[float]
    knob: ClassVar[str | None]
    # Whether the method models static friction above Coulomb (``Parameters.f_s > f_c``);
    # a method that does not is refused such parameters by ``simulate``.
    stiction: ClassVar[bool] = False
    # Whether the method models reset PID (``Parameters.reset_dwell``), whose resets are events.
    resets: ClassVar[bool] = False

    def __post_init__(self) -> None:
        self._validate(self.options)

    @property
    def options(self) -> dict[str, Any]:
        """The knobs of this configuration, by name (a fresh dict)."""
        names = self.__dict__.get("_names")
        if names is None:  # the field names, once per instance (frozen: they never change)
            names = tuple(f.name for f in fields(self))
            object.__setattr__(self, "_names", names)
        return {name: getattr(self, name) for name in names}

    @abc.abstractmethod
    def _validate(self, options: dict[str, Any]) -> None:
        """Raise SimulationError for invalid option values."""

    @abc.abstractmethod
    def _solve(
        self, params: Parameters, z0: np.ndarray, t_end: float, t_eval: np.ndarray | None, options: dict[str, Any]
    ) -> Solution:
        """Integrate from ``z0`` over ``[0, t_end]``."""
