"""The simulation contract: one result type and one base class for methods.

Lemma 1: the inclusion ``x' ∈ A x - b SGN(v)`` (eq. xDot) has a unique
solution from every initial state, and in each mode it is affine in closed
form (slip ``v > 0``: ``x' = Ax - b``; stick: ``σ' = 0, φ' = σ, v = 0``;
slip ``v < 0``: ``x' = Ax + b``).  Every method below approximates (or, for
``event``, computes) that solution.
"""

from __future__ import annotations

import abc
from dataclasses import dataclass, fields
from functools import cached_property
from typing import Any, ClassVar

import numpy as np

from .._infra.errors import SimulationError
from .._model.parameters import Parameters
from ._trajectories import AlongStates, Status, Trajectories

__all__ = ["Solution", "SimulationMethod", "Status", "RTOL_FLOOR", "check_rtol", "finite_or_raise"]

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


def finite_or_raise(method: str, t: np.ndarray, z: np.ndarray) -> None:
    """Refuse samples that left the range of float64 (inf or NaN), naming where."""
    bad = ~np.isfinite(z).all(axis=-1)
    if bad.any():
        i = int(np.argmax(bad))
        raise SimulationError(
            f"the {method} solution leaves the range of float64 (about ±1.8e308) at t = {float(t[i]):g}: "
            "scale the initial state down"
        )


class Solution(AlongStates):
    """One simulated solution: a view of one row of a :class:`.Trajectories`.

    Attributes
    ----------
    params : Parameters
    method : str
    t : ndarray, shape (n,)
        Sample times (those after an incomplete trajectory's stop dropped).
    z : ndarray, shape (n, 3)
        ``(e_i, s, v)``.
    x : ndarray, shape (n, 3)
        ``(σ, φ, v)``.
    mode : ndarray of int, shape (n,)
        ``+1`` slip with ``v > 0``, ``0`` stick, ``-1`` slip with ``v < 0``.
    events : tuple of (float, int, int)
        ``(t, mode_before, mode_after)`` for every mode change.
    event_x : ndarray, shape (n_events, 3)
        The state at each event (NaN where the method does not compute it).
    status : str
        One of :class:`Status`.
    complete : bool
    options : dict
        The accuracy knobs used.
    trajectories, index
        The batch this is a view of, and the row.
    """

    def __init__(self, trajectories: "Trajectories", index: int) -> None:
        self.trajectories = trajectories
        self.index = index
        complete = trajectories.status[index] in Status.COMPLETE
        self._keep = slice(None) if complete else trajectories.t <= trajectories.t_stop[index]

    @classmethod
    def from_samples(
        cls,
        *,
        params: Parameters,
        method: str,
        t: np.ndarray,
        z: np.ndarray,
        mode: np.ndarray,
        events: tuple[tuple[float, int, int], ...],
        status: str,
        options: dict[str, Any],
    ) -> "Solution":
        """A solution from samples of one trajectory (the time-stepping methods), states at events unknown (NaN)."""
        from .._model.coordinates import z_to_x

        t = np.asarray(t, dtype=float)
        z = np.asarray(z, dtype=float).reshape(-1, 3)
        n = len(events)
        ev = np.array(events, dtype=float).reshape(n, 3)
        batch = Trajectories(
            params=params,
            method=method,
            t=t,
            z=z[None],
            x=z_to_x(params, z)[None],
            mode=np.asarray(mode, dtype=np.int8)[None],
            event_t=ev[None, :, 0],
            event_x=np.full((1, n, 3), np.nan),
            event_before=ev[None, :, 1].astype(np.int8),
            event_after=ev[None, :, 2].astype(np.int8),
            event_residual=np.zeros((1, n)),
            n_events=np.array([n]),
            status=np.array([status], dtype=object),
            t_stop=np.array([t[-1] if t.size else 0.0]),
            z0=z[:1].copy() if z.size else np.zeros((1, 3)),
            x0=z_to_x(params, z[:1]) if z.size else np.zeros((1, 3)),
            options=dict(options),
        )
        return cls(batch, 0)

    # -- what the row holds ----------------------------------------------------------
    @property
    def params(self) -> Parameters:
        return self.trajectories.params

    @property
    def method(self) -> str:
        return self.trajectories.method

    @property
    def options(self) -> dict[str, Any]:
        return self.trajectories.options

    @property
    def status(self) -> str:
        return str(self.trajectories.status[self.index])

    @property
    def complete(self) -> bool:
        return self.status in Status.COMPLETE

    @cached_property
    def t(self) -> np.ndarray:
        return self.trajectories.t[self._keep]

    @cached_property
    def z(self) -> np.ndarray:
        return self.trajectories.z[self.index][self._keep]

    @cached_property
    def x(self) -> np.ndarray:
        """States in ``(σ, φ, v)``, shape (n, 3)."""
        return self.trajectories.x[self.index][self._keep]

    @cached_property
    def mode(self) -> np.ndarray:
        return self.trajectories.mode[self.index][self._keep]

    @cached_property
    def events(self) -> tuple[tuple[float, int, int], ...]:
        return self.trajectories.events(self.index)

    @property
    def event_x(self) -> np.ndarray:
        return self.trajectories.event_x[self.index, : int(self.trajectories.n_events[self.index])]

    @property
    def t_stop(self) -> float:
        return float(self.trajectories.t_stop[self.index])

    def __repr__(self) -> str:
        return f"Solution(method={self.method!r}, samples={self.t.size}, events={len(self.events)}, status={self.status!r})"


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
