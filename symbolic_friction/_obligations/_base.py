"""The proof-obligation contract.

An *obligation* is one step of the paper's proof that algebra can decide, for
symbolic (all-gain) parameters.  It has two halves, kept apart so that tests
can break the subject and watch the check fail:

* :meth:`Obligation.derive` builds the *subject*: the objects under test
  (``A``, ``P``, ``V_k``, the derived ``k``-conditions, …) taken from the
  package's own model code, as a frozen dataclass of sympy objects.
* :meth:`Obligation.verify` decides the statement about a given subject and
  returns an :class:`Outcome`: ``holds`` or ``fails`` with a residual or a
  counterexample.  It must not consult the package model again, only the
  subject, so that an altered subject is really what gets checked.

:meth:`Obligation.run` times ``derive`` + ``verify`` and packs a
:class:`Result`.
"""

from __future__ import annotations

import abc
import time
from dataclasses import dataclass, field
from typing import Any, ClassVar

__all__ = ["Obligation", "Outcome", "Result", "Erratum", "HOLDS", "FAILS"]

HOLDS = "holds"
FAILS = "fails"


@dataclass(frozen=True)
class Outcome:
    """Verdict of :meth:`Obligation.verify`.

    Attributes
    ----------
    holds : bool
        Whether the statement was proved for the subject.
    reason : str
        On failure: the residual or counterexample, in words and numbers.
        On success: optionally a short remark.
    details : tuple of (str, str)
        ``(label, LaTeX)`` pairs of the derived expressions, rendered into
        ``proofs/obligations.md``.  Must be deterministic.
    """

    holds: bool
    reason: str = ""
    details: tuple[tuple[str, str], ...] = ()

    @classmethod
    def fail(cls, reason: str, details: tuple[tuple[str, str], ...] = ()) -> "Outcome":
        """A failing outcome with its residual or counterexample."""
        return cls(False, reason, details)


@dataclass(frozen=True)
class Result:
    """One obligation's row in ``symbolic-friction check``."""

    id: str
    paper: str
    statement: str
    method: str
    status: str
    seconds: float
    reason: str = ""
    details: tuple[tuple[str, str], ...] = ()

    @property
    def holds(self) -> bool:
        return self.status == HOLDS

    def as_json(self) -> dict[str, Any]:
        """The JSON record of ``check --json``."""
        return {
            "id": self.id,
            "paper": self.paper,
            "statement": self.statement,
            "method": self.method,
            "status": self.status,
            "seconds": round(self.seconds, 4),
            "reason": self.reason,
            "details": [{"label": a, "latex": b} for a, b in self.details],
        }


@dataclass(frozen=True)
class Erratum:
    """A place where the paper's text is wrong and the corrected statement was checked."""

    where: str
    paper_says: str
    correct: str
    checked_by: str

    def as_json(self) -> dict[str, str]:
        return {"where": self.where, "paper_says": self.paper_says, "correct": self.correct, "checked_by": self.checked_by}


class Obligation(abc.ABC):
    """Base class of every proof obligation.

    Subclasses set the class attributes and implement :meth:`derive` and
    :meth:`verify`.

    Attributes
    ----------
    id : str
        Follows the paper, e.g. ``"lemma2.dVdt"``.
    paper : str
        Reference in the paper, e.g. ``"Lemma 2, item 2; eq. (dVdt)"``.
    statement : str
        One line, what is proved.
    method : str
        How: ``"sympy identity"``, ``"exhaustive case split"``, …
    errata : tuple of Erratum
        Corrections of the paper's text that this obligation checks.
    """

    id: ClassVar[str]
    paper: ClassVar[str]
    statement: ClassVar[str]
    method: ClassVar[str]
    errata: ClassVar[tuple[Erratum, ...]] = ()

    @abc.abstractmethod
    def derive(self) -> Any:
        """Build the subject from the package's model, for symbolic gains."""

    @abc.abstractmethod
    def verify(self, subject: Any) -> Outcome:
        """Decide the statement for ``subject``; never raise for a false statement."""

    def run(self, subject: Any = None) -> Result:
        """Derive (unless ``subject`` is given), verify, and time both."""
        start = time.perf_counter()
        if subject is None:
            subject = self.derive()
        outcome = self.verify(subject)
        seconds = time.perf_counter() - start
        return Result(
            id=self.id,
            paper=self.paper,
            statement=self.statement,
            method=self.method,
            status=HOLDS if outcome.holds else FAILS,
            seconds=seconds,
            reason=outcome.reason,
            details=outcome.details,
        )
