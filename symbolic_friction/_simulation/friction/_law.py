"""The friction-law contract for the ``moreau`` method and the paper's Coulomb law ``f_c SGN(v)``.

See :mod:`symbolic_friction._simulation.friction` for the scalar inclusion
``D w + h f ∋ r`` each law solves in one implicit Euler step.
"""

from __future__ import annotations

import abc
import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, ClassVar, NamedTuple

import numpy as np

from ..._infra.errors import ParameterError, SimulationError
from ..._infra.rational import format_rational, to_rational

__all__ = ["Step", "FrictionLaw", "Coulomb", "WORST_CASE"]

WORST_CASE = "worst-case"

# sqrt(2/e): the largest slope of u -> 2u exp(-u^2), reached at u = 1/sqrt(2).
_STRIBECK_SLOPE = math.sqrt(2.0 / math.e)


class Step(NamedTuple):
    """Data of one implicit Euler step, from the state at ``t`` to ``t + h``.

    (A named tuple rather than a dataclass: one is built per step, so it must
    be cheap.)

    With ``x_n = (sigma, phi, v)`` the implicit step
    ``x_{n+1} = x_n + h (A x_{n+1} - b lambda)`` gives
    ``sigma_{n+1} = sigma - h k_i w`` and
    ``phi_{n+1} = phi + h sigma - h (h k_i + k_p) w`` for ``w = v_{n+1}``,
    and ``D w + h f_c lambda = r`` (module docstring).

    Attributes
    ----------
    t, h : float
        Step start and size.
    sigma, phi, v : float
        State at ``t`` in ``x`` coordinates.
    k_p, k_i, k_v, f_c : float
        Gains and Coulomb level.
    """

    t: float
    h: float
    sigma: float
    phi: float
    v: float
    k_p: float
    k_i: float
    k_v: float
    f_c: float

    @property
    def D(self) -> float:
        """``1 + h k_v + h^2 k_p + h^3 k_i`` (> 1)."""
        h = self.h
        return 1.0 + h * (self.k_v + h * (self.k_p + h * self.k_i))

    @property
    def r(self) -> float:
        """``v + h phi + h^2 sigma``: the next velocity if friction were absent, times ``D``."""
        return self.v + self.h * (self.phi + self.h * self.sigma)

    def next_x(self, w: float) -> tuple[float, float, float]:
        """``x_{n+1} = (sigma, phi, v)`` after the step if ``v_{n+1} = w``."""
        h = self.h
        return (self.sigma - h * self.k_i * w, self.phi + h * self.sigma - h * (h * self.k_i + self.k_p) * w, w)


class FrictionLaw(abc.ABC):
    """Base class of a friction law ``F`` replacing ``f_c SGN(v)`` in eq. (xDot).

    Contract for implementers
    -------------------------
    * :meth:`graph` returns, for an array of velocities, the lower and upper
      ends of the friction set ``F(v)`` (force per unit mass; the two ends
      coincide where ``F`` is single-valued).  It describes the law (plots,
      containment in ``f_c SGN_ρ``) and is not used by the simulator.
    * :meth:`solve_step` solves the scalar inclusion ``D w + h f ∋ r`` of one
      implicit Euler step (:class:`Step`), returning ``(w, f)`` with
      ``f ∈ F(w)`` (up to rounding) and ``D w + h f = r``.  When ``F`` is
      monotone the solution is unique; otherwise the law documents which
      solution it picks, or :meth:`check_step` rejects step sizes for which
      the solution is not unique.
    * :meth:`check_step` raises :class:`SimulationError` naming ``h`` if the
      step size is unusable (default: every ``h > 0`` is fine).
    * :attr:`time_invariant` is false if the law depends on ``t`` (then a
      state left unchanged by one step is not taken as an equilibrium).
    * Laws are immutable and validated at construction; their numbers are
      kept exact (:class:`~fractions.Fraction`), floats are used only inside
      the numerical methods.
    """

    name: ClassVar[str]

    @abc.abstractmethod
    def graph(self, v: Any, f_c: float) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper ends of ``F(v)`` for an array ``v``."""

    @abc.abstractmethod
    def solve_step(self, step: Step) -> tuple[float, float]:
        """Solve ``D w + h f ∋ r``, ``f ∈ F(w)``; return ``(w, f)``."""

    def stepper(self, *, k_p: float, k_i: float, k_v: float, f_c: float) -> Callable[..., float]:
        """The step as a function ``(t, h, sigma, phi, v, D, r) -> w`` for the Moreau loop, which has ``D`` and
        ``r`` already (computed as :class:`Step` computes them).

        The default builds the :class:`Step` and calls :meth:`solve_step`; a law may return a function
        that skips that (it must give the same ``w``, bit for bit).
        """
        solve = self.solve_step

        def step(t: float, h: float, sigma: float, phi: float, v: float, D: float, r: float) -> float:
            return solve(Step(t, h, sigma, phi, v, k_p, k_i, k_v, f_c))[0]

        return step

    def check_step(self, h: float, *, k_p: float, k_i: float, k_v: float, f_c: float) -> None:
        """Raise :class:`SimulationError` if ``h`` is not usable with this law."""

    @property
    def time_invariant(self) -> bool:
        """Whether the law is the same at all times (default true)."""
        return True

    def describe(self) -> str:
        """One-line description with the exact numbers."""
        return self.name


def _coulomb_solve(r: float, D: float, a: float) -> tuple[float, float]:
    """``D w + a SGN(w) ∋ r`` (``a = h f_c``): the resolvent of a maximal monotone law.

    Returns ``(w, lam)`` with ``lam ∈ SGN(w)``.
    """
    if r > a:
        return (r - a) / D, 1.0
    if r < -a:
        return (r + a) / D, -1.0
    return 0.0, r / a


@dataclass(frozen=True)
class Coulomb(FrictionLaw):
    """The paper's law ``f_c SGN(v)`` (eq. frictionforceSetValued).

    ``simulate(..., method="moreau")`` without ``friction`` uses the same
    closed-form step on a faster path; this class exists so that Coulomb
    friction can be passed, plotted and compared like any other law.
    """

    name: ClassVar[str] = "coulomb"

    def graph(self, v: Any, f_c: float) -> tuple[np.ndarray, np.ndarray]:
        v = np.asarray(v, dtype=float)
        s = np.sign(v) * f_c
        return np.where(v == 0, -f_c, s), np.where(v == 0, f_c, s)

    def solve_step(self, step: Step) -> tuple[float, float]:
        w, lam = _coulomb_solve(step.r, step.D, step.h * step.f_c)
        return w, step.f_c * lam


def _check_nonnegative(value: object, name: str) -> Fraction:
    q = to_rational(value, name=name)
    if q < 0:
        raise ParameterError(f"{name} must be ≥ 0; got {name} = {format_rational(q)}")
    return q


def _check_positive(value: object, name: str) -> Fraction:
    q = to_rational(value, name=name)
    if not q > 0:
        raise ParameterError(f"{name} must be > 0; got {name} = {format_rational(q)}")
    return q


Selection = Callable[[float, tuple[float, float, float]], tuple[float, float]]


