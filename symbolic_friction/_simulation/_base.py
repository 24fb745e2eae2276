"""The simulation contract: one result type and one base class for methods.

Lemma 1: the inclusion ``x' ∈ A x - b SGN(v)`` (eq. xDot) has a unique
solution from every initial state, and in each mode it is affine in closed
form (slip ``v > 0``: ``x' = Ax - b``; stick: ``σ' = 0, φ' = σ, v = 0``;
slip ``v < 0``: ``x' = Ax + b``).  Every method below approximates (or, for
``event``, computes) that solution.
"""

from __future__ import annotations

import abc
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, ClassVar

import numpy as np

from .._parameters import Parameters

__all__ = ["Solution", "SimulationMethod", "Status"]


class Status:
    """Why a simulation stopped."""

    T_END = "t_end reached"
    MAX_EVENTS = "max_events reached"
    EQUILIBRIUM = "at an equilibrium"


@dataclass(frozen=True, eq=False)
class Solution:
    """A simulated solution.

    Attributes
    ----------
    params : Parameters
    method : str
    t : ndarray, shape (n,)
    z : ndarray, shape (n, 3)
        ``(e_i, s, v)``.
    mode : ndarray of int, shape (n,)
        ``+1`` slip with ``v > 0``, ``0`` stick, ``-1`` slip with ``v < 0``.
    events : tuple of (float, int, int)
        ``(t, mode_before, mode_after)`` for every mode change.
    status : str
        One of :class:`Status`.
    options : dict
        The accuracy knobs used.
    """

    params: Parameters
    method: str
    t: np.ndarray
    z: np.ndarray
    mode: np.ndarray
    events: tuple[tuple[float, int, int], ...]
    status: str
    options: dict[str, Any] = field(default_factory=dict)

    @cached_property
    def x(self) -> np.ndarray:
        """States in ``(sigma, phi, v)``, shape (n, 3)."""
        from .._coordinates import z_to_x

        return z_to_x(self.params, self.z)

    @cached_property
    def V(self) -> np.ndarray:
        """``V(x(t))`` of eq. (lyapLike), shape (n,)."""
        from .._lyapunov import V

        return V(self.params, self.x)

    @cached_property
    def distance(self) -> np.ndarray:
        """``|x(t)|_𝒜``, shape (n,)."""
        from .._attractor import distance_x

        return distance_x(self.params, self.x)

    def V_hat(self, k: tuple[Any, Any, Any, Any]) -> np.ndarray:
        """``V̂(x(t))`` of eq. (Vhat) for constants ``k = (k1, k2, k3, k4)``."""
        from .._lyapunov import V_hat

        return V_hat(self.params, self.x, k)


class SimulationMethod(abc.ABC):
    """Base class of a simulation method.

    Contract for implementers
    -------------------------
    * Set ``name`` (the ``method=`` string) and ``options``: a mapping from
      each accepted keyword option to its default.  ``simulate`` rejects any
      other option with :class:`~symbolic_friction.SimulationError`.
    * Implement :meth:`_validate` to check option values (raise
      ``SimulationError`` naming the option and the value).
    * Implement :meth:`_solve`, which receives validated float data and
      returns a :class:`Solution`.  With ``t_eval`` given, the samples must be
      exactly at those times.
    """

    name: ClassVar[str]
    options: ClassVar[dict[str, Any]]

    @abc.abstractmethod
    def _validate(self, options: dict[str, Any]) -> None:
        """Raise SimulationError for invalid option values."""

    @abc.abstractmethod
    def _solve(
        self, params: Parameters, z0: np.ndarray, t_end: float, t_eval: np.ndarray | None, options: dict[str, Any]
    ) -> Solution:
        """Integrate from ``z0`` over ``[0, t_end]``."""
