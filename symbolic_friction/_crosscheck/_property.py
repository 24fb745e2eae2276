"""The property contract: one certified inequality of the paper, checked along trajectories.

A *property* is one claim of the paper instantiated with a certificate's
constants (Lemma 2, Lemma 3, Proposition 1, the Remark after Lemma 2, the
mode table of the appendix).  Like an
:class:`~symbolic_friction._obligations._base.Obligation` it keeps its two
inputs apart so that a test can break either and watch the check fail:

* the **trajectories** (:class:`~symbolic_friction._simulation.Trajectories`),
  read through :func:`~._along.along`, which evaluates the package's one
  model (``V``, ``V_k``, ``|x|_𝒜``, ``R``: :mod:`symbolic_friction._model.lyapunov`,
  :mod:`symbolic_friction._model.attractor`) on them once and shares it between
  the properties;
* the **certificate** (:class:`~._claims.Claims`), whose constants enter
  only the right-hand sides.

:meth:`Property.check` returns an :class:`Evaluation`: the *relative slack*
``(rhs - lhs)/scale`` of every instance of the inequality (a sampled point,
a pair of times, a pair of stick phases), the mask of instances where the
inequality applies, and a witness that builds the :class:`~._results.Counterexample`
at any instance.  It never raises for a false inequality and never decides
pass/fail itself: the tolerance is applied by the
:class:`~._checker.BatchChecker`, in one place.

Tolerance
---------
A violation is a relative slack below ``-rtol`` (default
:data:`DEFAULT_RTOL`).  The scale of an inequality is the size its two sides
can have on that trajectory: ``L = max_t |x(t)| + f_c`` for distances and
``|σ|``, ``coef·L²`` for quadratic forms, ``coef`` the largest coefficient
involved.  The event-driven simulator matches an independent mpmath
reference to about ``1e-14`` relative (``tests/benchmarks/bench_accuracy.py``;
the tests hold it to ``1e-13``), so a quadratic form errs by far less than
``1e-12·|M|L²``; ``rtol = 1e-8`` leaves a safety factor of at least ``10⁴``,
while every genuine violation found by the tests is larger than ``1e-3``.
"""

from __future__ import annotations

import abc
from dataclasses import dataclass, field
from typing import Any, Callable, ClassVar

import numpy as np

__all__ = ["Property", "Evaluation", "DEFAULT_RTOL", "DEFAULT_THETA"]

DEFAULT_RTOL = 1e-8
"""Relative tolerance of every check (justified in the module docstring)."""

DEFAULT_THETA = 0.5
"""Attractivity on a finite horizon: ``|x(T)|_𝒜 ≤ θ |x(0)|_𝒜`` is required."""


@dataclass(frozen=True, eq=False)
class Evaluation:
    """The instances of one inequality on a batch of trajectories.

    Attributes
    ----------
    slack : ndarray, shape (N, K)
        Relative slack ``(rhs - lhs)/scale`` of each instance (row = trajectory).
    mask : ndarray of bool, shape (N, K)
        Where the inequality applies (only these instances are counted).
    witness : callable
        ``witness((i, p)) -> Counterexample`` at instance ``(i, p)``; its
        ``trajectory`` is the row ``i`` (the checker shifts it).
    inconclusive : int
        Instances that can neither hold nor fail on this horizon.
    extremes : tuple
        ``(key, values, mask, largest)``: an observed extreme ratio to report.
    more : tuple of Evaluation
        Further instances of the same property on the same trajectories
        (e.g. the events after the samples); they do not count trajectories again.
    """

    slack: np.ndarray
    mask: np.ndarray
    witness: Callable[[tuple[int, ...]], Any]
    inconclusive: int = 0
    extremes: tuple = ()
    more: tuple["Evaluation", ...] = field(default=())

    def failures(self, rtol: float) -> int:
        """Instances below ``-rtol`` (NaN where the mask holds counts as a failure)."""
        r = np.where(self.mask, self.slack, np.inf)
        own = int(np.count_nonzero((r < -rtol) | (np.isnan(r) & self.mask)))
        return own + sum(e.failures(rtol) for e in self.more)


class Property(abc.ABC):
    """Base class of every checked property.

    Subclasses set the class attributes and implement :meth:`check`.

    Attributes
    ----------
    id : str
        Follows the paper, e.g. ``"lemma2.decrease"``.
    paper : str
        Reference in the paper, e.g. ``"Lemma 2, item 2 (eq. Vdecrease)"``.
    statement : str
        The inequality, in one line.
    uses_certificate : bool
        ``False`` for properties of the solutions alone (the mode table, the
        Remark after Lemma 2, ``V`` nonincreasing, attractivity): evaluated
        once per batch and shared by the certificates of the gain set.
    paper_constants : bool
        Whether the property reads the constants of Lemmas 2 and 3 (or the
        paper's ``V``, ``V̂``), so applies to certificates of the paper's
        template only; ``False`` for one that reads only κ (any template).
    """

    id: ClassVar[str]
    paper: ClassVar[str]
    statement: ClassVar[str]
    uses_certificate: ClassVar[bool] = True
    paper_constants: ClassVar[bool] = True

    def applies_to(self, certificate: Any) -> bool:
        """Whether this property is a claim of ``certificate`` (:class:`~._claims.Claims`) at all."""
        return not self.uses_certificate or not self.paper_constants or certificate.is_paper

    @property
    def inequality(self) -> str:
        """The statement (the name the reports use)."""
        return self.statement

    @abc.abstractmethod
    def check(self, trajectories: Any, certificate: Any) -> Evaluation:
        """Relative slacks of the inequality on ``trajectories`` for ``certificate``'s constants."""

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.id}: {self.statement}>"
