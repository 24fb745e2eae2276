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

from .._infra.errors import CertificateError, ParameterError, SymbolicFrictionError
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
    :data:`.sup_flow.OBLIGATIONS`; a test holds them to the registry of obligations).
    """
    from .pipeline import STABILITY
    from .quadratic import QUADRATIC
    from .sup_flow import SUP_FLOW

    return {t.name: t for t in (STABILITY, QUADRATIC, SUP_FLOW)}


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
    """

    template: Template
    certificate: Any = None
    reason: str = ""

    def __post_init__(self) -> None:
        if (self.certificate is None) == (not self.reason):
            raise ValueError("an attempt has either a certificate or a reason, not both or neither")

    @property
    def kappa(self) -> Fraction | None:
        """The proved κ, exact (None without a certificate)."""
        return None if self.certificate is None else Fraction(self.certificate.overshoot_bound)

    def describe(self) -> str:
        """``"quadratic: κ 1.80834"`` or ``"quadratic: no certificate (…)"``."""
        if self.certificate is None:
            return f"{self.template.name}: no certificate ({self.reason})"
        return f"{self.template.name}: κ {self.certificate.overshoot_bound}"

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
    """

    chosen: Attempt
    attempts: tuple[Attempt, ...]
    requested: str = "auto"
    note: str = ""

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

    def describe(self) -> str:
        """One line: which template, its κ, and the others' κ or why they gave none."""
        head = f"template {self.template.name}"
        if self.requested == "auto":
            head += " (auto: the smallest proved κ" + (f"; {self.note}" if self.note else "") + ")"
        others = "; ".join(a.describe() for a in self.others)
        return head + f": κ {self.certificate.overshoot_bound}" + (f"; {others}" if others else "")


def _try(template: Template, params: Parameters, *, mode: str | None, margin: object, search: str | None,
         label: str, physical: dict | None) -> Attempt:
    """Search with ``template``, then decide the result with the template's own exact verifier."""
    if template.name == "paper":
        from .pipeline import certify

        certificate = certify(params, mode=mode or "tightest", margin=margin, label=label, physical=physical,
                              search=search or "closed-form")
    elif template.name == "quadratic":
        from .quadratic_search import certify_quadratic

        certificate = certify_quadratic(params, label=label)
    else:
        from .sup_flow_search import certify_sup_flow

        certificate = certify_sup_flow(params, label=label)
    report = template.verify(certificate, "<certificate>")
    if not report.proved:  # the searches verify too; the choice trusts only this decision
        raise CertificateError(f"the {template.name} certificate does not verify: {template.failure(report)}")
    return Attempt(template, certificate)


def refuse_paper_only(template: str, paper_only: list[str]) -> None:
    """Raise :class:`ParameterError` if ``template`` is one beyond the paper and a paper-only option was given."""
    if template in ("quadratic", "sup-flow") and paper_only:
        raise ParameterError(f"only the paper's template takes {paper_only[0]}: the {template} template has one "
                             "search (its SDPs), minimises κ and its file records normalised gains only "
                             "(drop it, give normalised gains, or use --template paper)")


def certify_template(
    params: Parameters, *, template: str = "auto", mode: str | None = None, margin: object = None,
    search: str | None = None, label: str = "", physical: dict | None = None,
) -> TemplateChoice:
    """Certify ``params`` with one template, or with each and keep the smallest proved κ.

    Parameters
    ----------
    params : Parameters
        Gains satisfying Assumption 1 (``f_s = f_c``).
    template : {"auto", "paper", "quadratic", "sup-flow"}, keyword-only
        ``paper``: the paper's template (``mode``, ``margin``, ``search`` as
        in :func:`.pipeline.certify`); ``quadratic``: the quadratic template
        (SDP, exact rounding and verification); ``sup-flow``: the sup-flow
        template (SDPs on adaptive time pieces, exact and arb verification);
        ``auto`` (default): each, keeping the proved certificate with the smallest κ.  With ``auto``,
        an option only the paper's template takes restricts the choice to it
        (said in :attr:`TemplateChoice.note`).
    mode, margin, search : keyword-only
        The paper's template's options (None: its defaults, tightest by the closed form).
    label : str, keyword-only
        Kept in the certificate's provenance.
    physical : dict, keyword-only
        Physical parameters, recorded by the paper's template only (so with
        them ``auto`` keeps to the paper's template, and ``quadratic`` refuses).

    Returns
    -------
    TemplateChoice

    Raises
    ------
    ParameterError
        For an unknown template, or an option the requested template does not take.
    CertificateError, SolverError
        If no template gives a proved certificate (``auto``: the reasons of each).
    """
    templates = searchable_templates()
    if template not in TEMPLATE_CHOICES:
        raise ParameterError(f"template must be one of {', '.join(TEMPLATE_CHOICES)}; got {template!r}")
    paper_only = paper_only_options(mode=mode, margin=margin, search=search, physical=physical)
    refuse_paper_only(template, paper_only)
    options = dict(mode=mode, margin=margin, search=search, label=label, physical=physical)
    if template != "auto":
        attempt = _try(templates[template], params, **options)
        return TemplateChoice(attempt, (attempt,), template)
    note = ""
    names = list(templates)
    if paper_only:
        names = ["paper"]
        note = f"only the paper's template takes {', '.join(paper_only)}"
    attempts, errors = [], []
    for name in names:
        try:
            attempts.append(_try(templates[name], params, **options))
        except SymbolicFrictionError as exc:
            # gains one search cannot take (e.g. f_c beyond float range for an SDP) may suit another
            errors.append(exc)
            attempts.append(Attempt(templates[name], reason=_reason(exc)))
    proved = [a for a in attempts if a.certificate is not None]
    if not proved:
        if len(errors) == 1 or isinstance(errors[0], ParameterError):
            raise errors[0]  # bad input for the paper's template is bad input: its own message
        raise CertificateError("no template gives a proved certificate: " + "; ".join(a.describe() for a in attempts))
    chosen = min(proved, key=lambda a: a.kappa)  # first (the paper's) on a tie
    return TemplateChoice(chosen, tuple(attempts), "auto", note)


def _reason(exc: BaseException, *, limit: int = 300) -> str:
    """Why a search gave no certificate, on one line, for beside a result.

    The quadratic search lists a solver status per margin tried; when they
    agree this says it once (``the SDP is infeasible at every margin tried``).
    """
    import re

    text = " ".join(str(exc).split())
    text = text.split("verifies exactly: ", 1)[-1]
    statuses = re.findall(r"margin [^:]+: solver status (\S+)", text)
    if statuses and len(set(statuses)) == 1 and len(statuses) == text.count("margin "):
        text = f"its SDP is {statuses[0]} at every margin tried ({len(statuses)})"
    return text if len(text) <= limit else text[: limit - 1] + "…"
