"""What a cross-check run found: per certificate and for the whole run."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .._infra import limits
from .._infra.guards import check_count, check_instance, check_items, check_real
from .._model.parameters import Parameters
from ._results import Counterexample, PropertyResult

if TYPE_CHECKING:  # annotations only
    from ._claims import Claims

__all__ = ["CertificateCheck", "CrosscheckReport", "SEARCH_MODES", "search_mode", "slowest_root", "default_horizon",
           "sample_times", "MAX_SEED", "MAX_CERTIFICATES", "MAX_TRAJECTORIES", "MAX_SAMPLES", "MAX_TOTAL_SAMPLES", "MAX_HORIZON"]

MAX_TRAJECTORIES = limits.CROSSCHECK_MAX_TRAJECTORIES
MAX_SAMPLES = limits.CROSSCHECK_MAX_SAMPLES
MAX_TOTAL_SAMPLES = limits.CROSSCHECK_MAX_TOTAL_SAMPLES
MAX_HORIZON = limits.CROSSCHECK_MAX_HORIZON
"""Bounds on the work one :func:`~._run.crosscheck` may ask for (time and memory), checked before anything is
simulated or allocated (the command line's options have the same bounds)."""

MAX_SEED = 2**31 - 1
"""The largest seed of a run: each gain set adds its offset (``1000·i``) and scipy's optimisers take seeds below ``2**32``."""
MAX_CERTIFICATES = 10_000
"""The most certificates one run checks (each is verified exactly, then simulated with its gain set)."""

SEARCH_MODES = ("random spheres", "grid", "special", "adversarial")
"""Sources of initial states, for the per-mode tightness ratio."""


def search_mode(label: str) -> str:
    """Map an initial-state label to one of :data:`SEARCH_MODES`."""
    if label.startswith("sphere"):
        return "random spheres"
    if label.startswith("grid"):
        return "grid"
    if label.startswith("adversarial"):
        return "adversarial"
    return "special"


def slowest_root(params: Parameters) -> float:
    """``Re λ`` of the slowest eigenvalue ``λ`` of ``A`` (eq. xDot), i.e. root of ``det(sI - A)``."""
    from .._model.coordinates import system_matrix

    return float(np.max(np.linalg.eigvals(system_matrix(params)).real))


def default_horizon(params: Parameters) -> float:
    """``20/|Re λ|`` for the slowest eigenvalue ``λ`` of ``A`` (rounded up)."""
    return float(math.ceil(20.0 / abs(slowest_root(params))))


def sample_times(horizon: float, samples: int) -> np.ndarray:
    """``t_j = T (j/(n-1))²``: dense at the start, where overshoots and ``R̂`` visits happen."""
    u = np.linspace(0.0, 1.0, samples)
    return horizon * u * u


@dataclass(frozen=True)
class CertificateCheck:
    """The cross-check of one certificate.

    Attributes
    ----------
    claims : Claims
    source : str
        File the certificate came from (or ``""``).
    results : tuple of PropertyResult
    trajectories : int
        Trajectories simulated for this gain set.
    horizon : float
    max_overshoot : dict
        Search mode -> largest observed ``sup_t |x(t)|_𝒜/|x(0)|_𝒜``.
    worst_state : tuple of float
        ``x(0)`` of the largest overshoot found.
    seconds : float
        Wall time of the gain set's run (shared by its certificates).
    incomplete : int
        Trajectories the simulator could not finish (event limit); they are
        never counted as holding, and any makes the check incomplete.
    proved : bool or None
        Whether exact verification proved the certificate first (``None``:
        candidate constants checked on purpose, ``require_proved=False``).
    """

    claims: Claims
    source: str
    results: tuple[PropertyResult, ...]
    trajectories: int
    horizon: float
    max_overshoot: dict
    worst_state: tuple[float, float, float]
    seconds: float
    overshoots: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    initial_distance: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    modes: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    incomplete: int = 0
    proved: bool | None = None
    overshoot_search: Any = None
    """The :class:`~._overshoot.OvershootSearch` of the gain set (worst overshoot found per scale), or ``None``."""

    @property
    def label(self) -> str:
        return self.claims.label

    @property
    def complete(self) -> bool:
        """Every trajectory was simulated to its horizon."""
        return self.incomplete == 0

    @property
    def passed(self) -> bool:
        """Every property held on complete data (an incomplete run never passes)."""
        return self.complete and all(r.passed for r in self.results)

    @property
    def verdict(self) -> str:
        """``"passed"``, ``"failed"`` (a property is violated) or ``"incomplete"``."""
        if not all(r.passed for r in self.results):
            return "failed"
        return "passed" if self.complete else "incomplete"

    @property
    def tightness(self) -> dict:
        """Search mode -> largest overshoot / κ (and ``"all"``)."""
        out = {mode: value / self.claims.kappa for mode, value in self.max_overshoot.items()}
        if self.max_overshoot:
            out["all"] = max(self.max_overshoot.values()) / self.claims.kappa
        return out

    def counterexamples(self) -> list[Counterexample]:
        return [r.counterexample for r in self.results if r.counterexample is not None]


@dataclass(frozen=True)
class CrosscheckReport:
    """Everything a cross-check run found.

    Attributes
    ----------
    checks : tuple of CertificateCheck
    rtol, theta : float
    seed : int
    seconds : float
    decay : dict
        Gain-set label -> :class:`~._overshoot.DecayFit` (if requested).
    iss : dict
        Gain-set label -> :class:`~._iss.IssEstimate` (if requested).

    Examples
    --------
    >>> from symbolic_friction import crosscheck
    >>> report = crosscheck(["proofs/case_a_tightest.json"], trajectories=1000)  # doctest: +SKIP
    >>> report  # doctest: +SKIP
    CrosscheckReport(crosscheck: PASSED — 1 certificate(s), 1000 trajectories (0 incomplete), ...)
    >>> print(format_report(report))  # every property, its margin and its tightness  # doctest: +SKIP
    """

    checks: tuple[CertificateCheck, ...]
    rtol: float
    theta: float
    seed: int
    seconds: float
    decay: dict = field(default_factory=dict)
    iss: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        """Refuse a report :func:`crosscheck` never returns (``CrosscheckReport("x", 1, 1, 1, 1)``), naming the field.

        Raises
        ------
        ParameterTypeError
            If ``checks`` is not a tuple of :class:`CertificateCheck`, or ``decay`` or ``iss`` not a dict.
        ParameterError
            If ``rtol`` is not in ``(0, 1]``, ``theta`` not in ``(0, 1]``, ``seed`` not an integer from 0 to
            :data:`MAX_SEED` or ``seconds`` not a finite number ≥ 0.
        """
        checks = check_items(self.checks, name="checks", what="a tuple of CertificateCheck (crosscheck makes reports)",
                             high=MAX_CERTIFICATES, kind=CertificateCheck)
        object.__setattr__(self, "checks", tuple(checks))
        check_real(self.rtol, name="rtol", high=1)
        check_real(self.theta, name="theta", high=1)
        check_count(self.seed, name="seed", low=0, high=MAX_SEED)
        check_real(self.seconds, name="seconds", low=0, low_open=False)
        check_instance(self.decay, dict, name="decay", what="a dict (gain-set label -> DecayFit)")
        check_instance(self.iss, dict, name="iss", what="a dict (gain-set label -> IssEstimate)")

    def __repr__(self) -> str:
        # the verdict line, not thousands of characters of nested results (format_report prints those)
        return f"CrosscheckReport({self.summary()})"

    @property
    def passed(self) -> bool:
        return bool(self.checks) and all(c.passed for c in self.checks)

    @property
    def incomplete(self) -> int:
        """Incomplete trajectories over every gain set (each gain set counted once)."""
        seen: dict[Any, int] = {}
        for c in self.checks:
            seen[c.claims.params] = c.incomplete
        return sum(seen.values())

    @property
    def trajectories(self) -> int:
        seen: dict[Any, int] = {}
        for c in self.checks:
            seen[c.claims.params] = c.trajectories
        return sum(seen.values())

    def summary(self) -> str:
        """The last line: what was checked, with counts, and the verdict."""
        failed = [c.label for c in self.checks if c.verdict == "failed"]
        verdict = "FAILED" if failed else ("INCOMPLETE" if self.incomplete else "PASSED")
        checked = sum(r.samples for c in self.checks for r in c.results)
        kinds = len({r.id for c in self.checks for r in c.results})  # a quadratic certificate has fewer claims
        text = (
            f"crosscheck: {verdict} — {len(self.checks)} certificate(s), {self.trajectories} trajectories "
            f"({self.incomplete} incomplete), {checked} instances of {kinds} properties checked"
        )
        if failed:
            text += f"; violated by {', '.join(failed)}"
        return text + f" ({self.seconds:.1f} s)"

    def counterexamples(self) -> list[Counterexample]:
        return [cx for c in self.checks for cx in c.counterexamples()]


