"""Which template proves the tightest overshoot bound κ (eq. stabState) for one gain set.

``certify`` can search three templates whose every step ``check`` proves: the
paper's (:data:`.pipeline.STABILITY`, the constants of Lemmas 2 and 3, found
by the closed form of :mod:`.closed_form` or the SDP of :mod:`.search`), and
two beyond the paper: the quadratic template (:data:`.quadratic.QUADRATIC`, a
free ``P`` with ``P₁₂ = 0`` and ``U = yᵀKy``, found by the SDP of
:mod:`.quadratic_search`) and the sup-flow template (:data:`.sup_flow.SUP_FLOW`,
``V_∞`` built on the friction-free flow and time pieces of ``U``, found by
the SDPs of :mod:`.sup_flow_search`).  :func:`certify_template` certifies with one of
them, or (``"auto"``) with each and keeps the proved certificate of smallest
κ.  A template is compared only through a certificate its own exact verifier
proves (re-decided here, independently of the search that found it); a search
that finds nothing (the SDP is infeasible or inaccurate, e.g. for stiff gains)
is an attempt with a reason, never a κ.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from .._infra.errors import CertificateError, ParameterError, SolverError, SymbolicFrictionError
from .._model.parameters import Parameters
from ._template import Template

__all__ = ["TEMPLATE_CHOICES", "searchable_templates", "paper_only_options", "refuse_paper_only", "Attempt", "TemplateChoice",
           "certify_template"]

TEMPLATE_CHOICES: tuple[str, ...] = ("auto", "paper", "quadratic", "sup-flow")
"""What ``certify --template`` accepts: a template's name, or ``auto`` (the tightest proved one)."""


def searchable_templates() -> dict[str, Template]:
    """The templates ``certify`` can search, by name, in the order ``auto`` tries them (the paper's first).

    Each instantiates only obligations that ``check`` proves (their ids:
    :data:`.certificate.OBLIGATIONS`, :data:`.quadratic.OBLIGATIONS`,
    :data:`.sup_flow_v2.OBLIGATIONS`; a test holds them to the registry of obligations).  The sup-flow
    searches write version 2 (:mod:`.sup_flow_v2`); version 1 files are still read and verified.
    """
    from .pipeline import STABILITY
    from .quadratic import QUADRATIC
    from .sup_flow_v2 import SUP_FLOW_V2

    return {t.name: t for t in (STABILITY, QUADRATIC, SUP_FLOW_V2)}


def paper_only_options(*, mode: str | None = None, margin: object = None, search: str | None = None,
                       physical: dict | None = None) -> list[str]:
    """The options given that only the paper's template takes (``--mode feasible``, ``--margin``, ``--search``,
    and physical parameters, which only the paper's file records: a quadratic file would lose them)."""
    given = []
    if physical is not None:
        given.append("physical parameters (--m …)")
    if mode not in (None, "tightest"):
        given.append(f"--mode {mode}")
    if margin is not None:
        given.append("--margin")
    if search is not None:
        given.append(f"--search {search}")
    return given


@dataclass(frozen=True)
class Attempt:
    """One template's try at a gain set: a proved certificate, or why there is none.

    Attributes
    ----------
    template : Template
    certificate : object or None
        A certificate its template's verifier proves (None: none found).
    reason : str
        Why there is no certificate (empty when there is one).
    search : str
        Which search of the template (``closed form``, ``one piece``, ``pieces``, ``sdp``; empty: its only one).
    seconds : float
        Wall time of the search and its exact verification.
    """

    template: Template
    certificate: Any = None
    reason: str = ""
    search: str = ""
    seconds: float = 0.0

    def __post_init__(self) -> None:
        if (self.certificate is None) == (not self.reason):
            raise ValueError("an attempt has either a certificate or a reason, not both or neither")

    @property
    def kappa(self) -> Fraction | None:
        """The proved κ, exact (None without a certificate)."""
        return None if self.certificate is None else Fraction(self.certificate.overshoot_bound)

    @property
    def title(self) -> str:
        """``"sup-flow (one piece)"``: the template, and the search when it has several."""
        return self.template.name + (f" ({self.search})" if self.search else "")

    def describe(self, *, timed: bool = False) -> str:
        """``"quadratic: κ 1.80834"`` or ``"quadratic: no certificate (…)"`` (``timed``: the seconds too)."""
        when = f" in {self.seconds:.2f} s" if timed else ""
        if self.certificate is None:
            return f"{self.title}: no certificate{when} ({self.reason})"
        return f"{self.title}: κ {self.certificate.overshoot_bound}{when}"

    def write(self, path: str | os.PathLike[str]) -> tuple[Path, ...]:
        """Write the certificate to ``path`` atomically (the paper's template adds its Markdown report)."""
        if self.certificate is None:
            raise CertificateError(f"nothing to write: {self.describe()}")
        if self.template.name == "paper":
            from .pipeline import write_certificate

            return write_certificate(self.certificate, path)
        return (self.template.write(self.certificate, path),)


@dataclass(frozen=True)
class TemplateChoice:
    """The certificate ``certify`` writes for one gain set, and what the other templates gave.

    Attributes
    ----------
    chosen : Attempt
        The proved certificate kept (smallest κ among the attempts).
    attempts : tuple of Attempt
        Every template tried, in order (``chosen`` among them).
    requested : str
        ``"auto"`` or the template's name.
    note : str
        Why ``auto`` tried fewer templates (an option only one takes), or empty.
    kappa_lin_lower : Fraction or None
        A proven lower end of ``κ_lin = sup_t ‖e^{At}‖₂``, below which no κ can be
        (:func:`.flow_bound.kappa_lin_lower`; None where it could not be had).
    target : Fraction or None
        ``(1 + kappa_tol)·kappa_lin_lower``: the searches stopped once a proved κ was at most this.
    """

    chosen: Attempt
    attempts: tuple[Attempt, ...]
    requested: str = "auto"
    note: str = ""
    kappa_lin_lower: Fraction | None = None
    target: Fraction | None = None

    def __post_init__(self) -> None:
        if self.chosen.certificate is None or self.chosen not in self.attempts:
            raise ValueError("the chosen attempt must be one of the attempts and have a certificate")

    @property
    def template(self) -> Template:
        return self.chosen.template

    @property
    def certificate(self) -> Any:
        return self.chosen.certificate

    @property
    def others(self) -> tuple[Attempt, ...]:
        return tuple(a for a in self.attempts if a is not self.chosen)

    @property
    def ratio(self) -> Fraction | None:
        """κ / (the lower end of κ_lin): how far the proved bound can be from the truth, at most (None without it)."""
        if self.kappa_lin_lower is None:
            return None
        return self.chosen.kappa / self.kappa_lin_lower

    def describe(self, *, timed: bool = False) -> str:
        """One line: which template, its κ, and the others' κ or why they gave none (``timed``: with seconds)."""
        head = f"template {self.chosen.title}"
        if self.requested == "auto":
            head += " (auto: the smallest proved κ" + (f"; {self.note}" if self.note else "") + ")"
        others = "; ".join(a.describe(timed=timed) for a in self.others)
        when = f" in {self.chosen.seconds:.2f} s" if timed else ""
        return head + f": κ {self.certificate.overshoot_bound}{when}" + (f"; {others}" if others else "")

    def against_kappa_lin(self) -> str:
        """``"κ ≤ 1.0212·κ_lin (κ_lin ≥ 1.4141960)"``, rounded so that the claim stays true, or empty."""
        if self.kappa_lin_lower is None:
            return ""
        from .._infra.bounds import bound_text

        ratio, lower = bound_text(self.ratio, 5, direction="up"), bound_text(self.kappa_lin_lower, 8, direction="down")
        return f"κ ≤ {ratio}·κ_lin (κ_lin ≥ {lower}, proven)"


SEARCHES: dict[str, tuple[str, ...]] = {
    "paper": ("closed form",),
    "sup-flow": ("one piece", "pieces"),
    "quadratic": ("sdp",),
}
"""Each template's searches, cheapest first."""

AUTO_ORDER: tuple[tuple[str, str], ...] = (
    ("paper", "closed form"), ("sup-flow", "one piece"), ("quadratic", "sdp"), ("sup-flow", "pieces"),
)
"""What ``auto`` tries, in order: the closed form (under a millisecond, the floor), the one-piece sup-flow
certificate and the quadratic template's SDP (tens of milliseconds each), then time pieces (seconds)."""

DEFAULT_KAPPA_TOL = Fraction(1, 10)
"""``auto`` stops once a proved κ is at most ``(1 + this)`` times the proven lower end of κ_lin."""
MAX_KAPPA_TOL = 1000
"""The largest ``kappa_tol`` taken (``κ`` within ``1001·κ_lin``: the closed form's floor on most gains)."""
DEFAULT_BUDGET = 5.0
"""Seconds ``auto`` spends on one gain set before it keeps what it has (a search is not started past it)."""
STIFFNESS_LIMIT = 1e3
"""Time pieces are not searched where the flow's fastest and slowest rates are further apart than this: their
cover of ``[0, T]`` would need more intervals than the verifier allows (the one-piece certificate serves there)."""


def _search(template: Template, search: str, params: Parameters, *, mode: str | None, margin: object,
            search_option: str | None, label: str, physical: dict | None, deadline: float | None) -> Any:
    """Run one search of ``template``; its result is decided by :func:`_try`."""
    if template.name == "paper":
        from .pipeline import certify

        return certify(params, mode=mode or "tightest", margin=margin, label=label, physical=physical,
                       search=search_option or "closed-form")
    if template.name == "quadratic":
        from .quadratic_search import certify_quadratic

        return certify_quadratic(params, label=label)
    if search == "one piece":
        from .sup_flow_tail import certify_sup_flow_tail

        return certify_sup_flow_tail(params, label=label)
    _check_not_stiff(params)
    from .sup_flow_search import certify_sup_flow

    return certify_sup_flow(params, label=label, tail="own", deadline=deadline)


def _check_not_stiff(params: Parameters) -> None:
    import numpy as np

    from .flow_bound import flow_rates

    rates = flow_rates(params)
    if not np.all(np.isfinite(rates)) or not min(rates) > 0:
        raise CertificateError("not tried: the flow's rates are beyond float range")
    if max(rates) > STIFFNESS_LIMIT * min(rates):
        raise CertificateError(f"not tried: the flow's rates are {max(rates) / min(rates):.3g} apart (stiff or slow), "
                               f"beyond the {STIFFNESS_LIMIT:.0e} time pieces can cover")


def _try(template: Template, search: str, params: Parameters, *, alone: bool = False, first: bool = True,
         **options: Any) -> Attempt:
    """Search with ``template``, then decide the result with the template's own exact verifier.

    A failure of the search or its solver is the attempt's reason (a
    :class:`SymbolicFrictionError`'s message, or the type and message of
    anything else a solver raises), never a traceback; ``alone`` (the only
    search asked for) raises it instead, anything but our own errors as
    :class:`SolverError`.  A :class:`ParameterError` (bad input) is raised by
    the ``first`` search and is a reason after it.
    """
    import time

    label = search if len(SEARCHES[template.name]) > 1 else ""
    start = time.monotonic()
    try:
        certificate = _search(template, search, params, **options)
        report = template.verify(certificate, "<certificate>")
        if not report.proved:  # the searches verify too; the choice trusts only this decision
            raise CertificateError(f"the {template.name} certificate does not verify: {template.failure(report)}")
    except ParameterError as exc:
        if alone or first:
            raise  # bad input is bad input
        return Attempt(template, reason=_reason(exc), search=label, seconds=time.monotonic() - start)
    except SymbolicFrictionError as exc:
        if alone:
            raise
        return Attempt(template, reason=_reason(exc), search=label, seconds=time.monotonic() - start)
    except Exception as exc:  # noqa: BLE001 - a solver's own error is this attempt's reason, never a traceback
        # a solver or a float library refusing extreme numbers (e.g. cvxpy's "Problem data contains NaN or Inf")
        failed = f"the {template.name} search failed: {type(exc).__name__}: "
        if alone:
            raise SolverError(failed + " ".join(str(exc).split())) from None
        return Attempt(template, reason=_reason(exc, prefix=failed), search=label, seconds=time.monotonic() - start)
    return Attempt(template, certificate, search=label, seconds=time.monotonic() - start)


def refuse_paper_only(template: str, paper_only: list[str]) -> None:
    """Raise :class:`ParameterError` if ``template`` is one beyond the paper and a paper-only option was given."""
    if template in ("quadratic", "sup-flow") and paper_only:
        raise ParameterError(f"only the paper's template takes {paper_only[0]}: the {template} template has one "
                             "search (its SDPs), minimises κ and its file records normalised gains only "
                             "(drop it, give normalised gains, or use --template paper)")


def certify_template(
    params: Parameters, *, template: str = "auto", mode: str | None = None, margin: object = None,
    search: str | None = None, label: str = "", physical: dict | None = None,
    kappa_tol: object = DEFAULT_KAPPA_TOL, budget: float | None = DEFAULT_BUDGET,
) -> TemplateChoice:
    """Certify ``params`` with one template, or with the cheapest that reaches the target, keeping the smallest κ.

    ``auto`` tries :data:`AUTO_ORDER` in turn and stops as soon as a proved
    κ is within ``kappa_tol`` of the proven lower end of ``κ_lin`` (no
    template can go below it), or when ``budget`` seconds are spent; a
    template named alone runs its searches (:data:`SEARCHES`) the same way.

    Parameters
    ----------
    params : Parameters
        Gains satisfying Assumption 1 (``f_s = f_c``).
    template : {"auto", "paper", "quadratic", "sup-flow"}, keyword-only
        ``paper``: the paper's template (``mode``, ``margin``, ``search`` as
        in :func:`.pipeline.certify`); ``quadratic``: the quadratic template
        (SDP, exact rounding and verification); ``sup-flow``: the sup-flow
        template (one piece closed by the best-conditioned Lyapunov matrix,
        then time pieces; exact and arb verification); ``auto`` (default):
        each in turn, keeping the proved certificate with the smallest κ.  With
        ``auto``, an option only the paper's template takes restricts the
        choice to it (said in :attr:`TemplateChoice.note`).
    mode, margin, search : keyword-only
        The paper's template's options (None: its defaults, tightest by the closed form).
    label : str, keyword-only
        Kept in the certificate's provenance.
    physical : dict, keyword-only
        Physical parameters, recorded by the paper's template only (so with
        them ``auto`` keeps to the paper's template, and ``quadratic`` refuses).
    kappa_tol : rational, keyword-only
        Stop once ``κ ≤ (1 + kappa_tol)·κ_lin`` (lower end); 0 never stops early.  Exact (``"1/10"``).
    budget : float or None, keyword-only
        Seconds after which no further search is started (time pieces stop halving); None: no limit.

    Returns
    -------
    TemplateChoice

    Raises
    ------
    ParameterError
        For an unknown template, an option the requested template does not take, or a bad ``kappa_tol`` or ``budget``.
    CertificateError, SolverError
        If no search gives a proved certificate (the reasons of each).

    Examples
    --------
    >>> choice = certify_template(Parameters(k_p=1000, k_i="1/1000", k_v=1000, f_c=1))  # doctest: +SKIP
    >>> choice.chosen.title, choice.certificate.overshoot_bound, float(choice.ratio) < 3  # doctest: +SKIP
    ('sup-flow (one piece)', '3.67139', True)
    """
    import math
    import time

    from .._infra.rational import to_rational

    templates = searchable_templates()
    if template not in TEMPLATE_CHOICES:
        raise ParameterError(f"template must be one of {', '.join(TEMPLATE_CHOICES)}; got {template!r}")
    tol = to_rational(kappa_tol, name="kappa_tol")
    if not 0 <= tol <= MAX_KAPPA_TOL:
        raise ParameterError(f"kappa_tol must be in [0, {MAX_KAPPA_TOL}]; got {tol}")
    if budget is not None and (isinstance(budget, bool) or not isinstance(budget, (int, float))
                               or not math.isfinite(budget) or not 0 < budget <= 86_400):
        raise ParameterError(f"budget must be a number of seconds in (0, 86400]; got {budget!r}")
    paper_only = paper_only_options(mode=mode, margin=margin, search=search, physical=physical)
    refuse_paper_only(template, paper_only)
    start = time.monotonic()
    deadline = None if budget is None else start + budget
    options = dict(mode=mode, margin=margin, search_option=search, label=label, physical=physical, deadline=deadline)
    note = ""
    if template == "auto":
        plan = [(name, how) for name, how in AUTO_ORDER if name in templates]
        if paper_only:
            plan = [("paper", "closed form")]
            note = f"only the paper's template takes {', '.join(paper_only)}"
    else:
        plan = [(template, how) for how in SEARCHES[template]]
    lower = _kappa_lin_lower(params) if template != "paper" and not paper_only else None
    target = None if lower is None else lower * (1 + tol)
    attempts: list[Attempt] = []
    for name, how in plan:
        if attempts and any(a.certificate is not None for a in attempts):
            best = min(a.kappa for a in attempts if a.certificate is not None)
            if target is not None and best <= target:
                break
            if deadline is not None and time.monotonic() > deadline:
                break
        # bad input is for the first search to refuse (the paper's, which takes any exact gains); a later search
        # that cannot take them (e.g. beyond float range) only gives a reason
        attempts.append(_try(templates[name], how, params, alone=len(plan) == 1, first=not attempts, **options))
    proved = [a for a in attempts if a.certificate is not None]
    if not proved:
        raise CertificateError("no template gives a proved certificate: " + "; ".join(a.describe() for a in attempts))
    chosen = min(proved, key=lambda a: a.kappa)  # the first (the cheapest) on a tie
    return TemplateChoice(chosen, tuple(attempts), template, note, lower, target)


def _kappa_lin_lower(params: Parameters) -> Fraction | None:
    """The proven lower end of κ_lin, or None where it cannot be had (gains beyond float range)."""
    from .flow_bound import kappa_lin_lower

    try:
        return kappa_lin_lower(params)
    except ParameterError:
        return None


def _reason(exc: BaseException, *, limit: int = 300, prefix: str = "") -> str:
    """Why a search gave no certificate, on one line, for beside a result.

    The quadratic search lists a solver status per margin tried; when they
    agree this says it once (``the SDP is infeasible at every margin tried``).
    """
    import re

    text = prefix + " ".join(str(exc).split())
    text = text.split("verifies exactly: ", 1)[-1]
    statuses = re.findall(r"margin [^:]+: solver status (\S+)", text)
    if statuses and len(set(statuses)) == 1 and len(statuses) == text.count("margin "):
        text = f"its SDP is {statuses[0]} at every margin tried ({len(statuses)})"
    return text if len(text) <= limit else text[: limit - 1] + "…"
