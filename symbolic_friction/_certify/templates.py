"""Every kind of proof file, read, verified and checked for staleness by its template.

:func:`builtin_templates` imports the modules that register the package's
templates (a missing one is an :class:`ImportError`): the stability
certificate of Proposition 1 (:data:`.pipeline.STABILITY`), the hunting
certificate (:data:`.hunting.HUNTING`), the box certificate (:data:`.box.BOX`), the quadratic
template (:data:`.quadratic.QUADRATIC`, beyond the paper), the sup-flow template (:data:`.sup_flow.SUP_FLOW`)
and the reset-contraction certificate (:data:`.reset_contraction.RESET_CONTRACTION`, reset PID).  The functions below take any file,
pick its template from its ``template`` member or its ``schema``
(:func:`._template.template_for`) and run that template's reader, exact
verifier and staleness check; ``symbolic-friction verify`` and ``check`` go
through them, so a registered template needs nothing else.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterable

from .._infra.errors import CertificateFormatError, InputFileError
from ._template import Template, registered, template_for

__all__ = [
    "builtin_templates",
    "read_certificate_file",
    "verify_any_file",
    "verify_template_file",
    "CommittedCertificate",
    "check_committed_certificates",
    "check_listed_certificates",
    "write_listed_certificates",
]


def builtin_templates() -> tuple[Template, ...]:
    """The package's templates, registered (the stability certificate first); then every registered one."""
    from .box import BOX
    from .hunting import HUNTING
    from .pipeline import STABILITY
    from .quadratic import QUADRATIC
    from .reset_contraction import RESET_CONTRACTION
    from .sup_flow import SUP_FLOW
    from .sup_flow_v2 import SUP_FLOW_V2

    first = (STABILITY, HUNTING, BOX, QUADRATIC, SUP_FLOW, SUP_FLOW_V2, RESET_CONTRACTION)
    return first + tuple(t for t in registered() if t not in first)


def read_certificate_file(path: str | os.PathLike[str]) -> tuple[Template, Any]:
    """Read a certificate file once, strictly, and parse it with the template it names.

    Raises
    ------
    InputFileError, CertificateFormatError
        If the file cannot be read, is not strict JSON, names an unknown
        template or is not a well-formed certificate of its template.
    """
    from .certificate import read_json

    stability = builtin_templates()[0]
    data, source = read_json(path), str(path)
    template = template_for(data, fallback=stability)
    return template, template.read(data, source)


def verify_template_file(path: str | os.PathLike[str]) -> tuple[Template, Any]:
    """Read a certificate file and decide it exactly with its template's verifier: ``(template, report)``."""
    template, certificate = read_certificate_file(path)
    return template, template.verify(certificate, str(path))


def verify_any_file(path: str | os.PathLike[str]) -> tuple[bool, Any]:
    """``(is_hunting, report)`` for a certificate file of any template (see :func:`verify_template_file`)."""
    from .hunting import HUNTING

    template, report = verify_template_file(path)
    return template is HUNTING, report


@dataclass(frozen=True)
class CommittedCertificate:
    """The state of one committed certificate (see :func:`check_committed_certificates`).

    Attributes
    ----------
    path : Path
        The JSON file (or the expected path of a missing one).
    report : VerificationReport, HuntingReport or None
        Exact verification, or None if the file is missing or malformed.
    stale : bool
        True if the file (and what its template writes beside it) differs
        byte-for-byte from what would be written now (or is missing, or
        cannot be regenerated).
    reason : str
        Why it is not ok (empty when ok).
    claim : str
        What the file shows when proved (its template's words: ``κ ≤ …``, ``a hunting cycle``).
    drift : str
        How the file differs from what would be written now although it proves
        the same statement (empty: none); reported, and counted in ``stale``
        only when checked strictly.
    """

    path: Path
    report: Any
    stale: bool
    reason: str = ""
    claim: str = ""
    drift: str = ""

    @property
    def proved(self) -> bool:
        return self.report is not None and self.report.proved

    @property
    def ok(self) -> bool:
        """Proved and up to date."""
        return self.proved and not self.stale

    def describe(self) -> str:
        """One line for ``symbolic-friction check``."""
        if self.ok and self.drift:
            return f"ok     {self.path} (proved, {self.claim}); drift, not a failure: {self.drift}"
        if self.ok:
            return f"ok     {self.path} (proved, up to date, {self.claim})"
        state = "STALE " if self.stale and self.report is not None and self.report.proved else "FAILED"
        return f"{state} {self.path}: {self.reason}"


def _check_one(path: Path, *, strict: bool = False, expected: dict | None = None) -> CommittedCertificate:
    from .box import shared_corners

    # a box file's drift regenerates it and verifies what it wrote: the same corners on the same numbers as the
    # file's own, when nothing drifted, so each is decided once per file
    with shared_corners():
        return _check_file(path, strict=strict, expected=expected)


def _check_file(path: Path, *, strict: bool, expected: dict | None) -> CommittedCertificate:
    try:
        template, report = verify_template_file(path)
    except CertificateFormatError as exc:
        return CommittedCertificate(path, None, True, f"malformed: {exc}")
    except InputFileError as exc:
        return CommittedCertificate(path, None, True, f"unreadable: {exc}")
    if not report.proved:
        return CommittedCertificate(path, report, False, template.failure(report))
    claim = template.claim(report.certificate)
    reason = configured_mismatch(report.certificate, expected or {}) or template.stale(report.certificate, path)
    if reason:
        return CommittedCertificate(path, report, True, reason, claim)
    drift = template.drift(report.certificate, path) if template.drift is not None else ""
    if drift and strict:
        return CommittedCertificate(path, report, True, f"drift (strict): {drift}", claim, drift)
    return CommittedCertificate(path, report, False, "", claim, drift)


def configured_mismatch(certificate: Any, expected: dict) -> str:
    """How a proved certificate disagrees with what the configuration says it proves (empty: it agrees).

    ``expected`` holds ``label`` and ``gains`` (exact) for a configuration entry
    given as a table; a file without them is not compared.
    """
    from .._infra.rational import format_rational

    differences = []
    gains = getattr(certificate, "parameters", None)
    for name, want in expected.get("gains", {}).items():
        got = gains.get(name) if isinstance(gains, dict) else getattr(certificate, name, None)
        if got != want:
            shown = "absent" if got is None else format_rational(got)
            differences.append(f"{name} = {shown} in the file, {format_rational(want)} in the configuration")
    if "label" in expected:
        prov = getattr(certificate, "provenance", None)
        label = getattr(prov, "label", None) if prov is not None else None
        if label != expected["label"]:
            differences.append(f"label {label!r} in the file, {expected['label']!r} in the configuration")
    return "; ".join(differences)


def check_committed_certificates(
    directory: str | os.PathLike[str] = "proofs", *, expected: Iterable[str] = (), strict: bool = False
) -> list[CommittedCertificate]:
    """Verify every ``*.json`` certificate under ``directory`` and detect stale ones.

    Parameters
    ----------
    directory : path
        Searched recursively for ``*.json`` files (sorted, for a stable order).
    expected : iterable of str, keyword-only
        File names (relative to ``directory``) that must exist, e.g.
        :data:`TABLE_I_FILES`; a missing one is reported as stale.
    strict : bool, keyword-only
        Whether drift (same statement, other digits) counts as stale.

    Returns
    -------
    list of CommittedCertificate
        One per file; the directory passes iff every entry is ``ok``.
    """
    directory = Path(directory)
    results = [_check_one(path, strict=strict) for path in sorted(directory.rglob("*.json"))]
    for name in expected:
        path = directory / name
        if not path.exists():
            results.append(CommittedCertificate(path, None, True, "missing; run `symbolic-friction certify`"))
    return results


def check_listed_certificates(
    directory: str | os.PathLike[str], names: Iterable[str], *, strict: bool = False, expectations: dict | None = None
) -> list[CommittedCertificate]:
    """Verify exactly the certificates ``names`` (relative to ``directory``), in order, and detect stale ones.

    A listed file that does not exist is reported as missing (not ok); files
    of ``directory`` that are not listed are not looked at.  ``expectations``
    (``{name: {"label": …, "gains": {…}}}``, from the configuration) must agree
    with the file; with ``strict``, drift fails too.
    """
    directory = Path(directory)
    results = []
    for name in names:
        path = directory / name
        if not path.exists():
            results.append(CommittedCertificate(
                path, None, True,
                "missing; create it with `symbolic-friction certify … --out "
                f"{path.parent} --name {path.stem}` (or `check --write` for Table I's files)",
            ))
        else:
            results.append(_check_one(path, strict=strict, expected=(expectations or {}).get(name)))
    return results


def write_listed_certificates(directory: str | os.PathLike[str], names: Iterable[str]) -> list[Path]:
    """Regenerate the certificates ``names`` under ``directory`` (``check --write``), atomically.

    A file of a template that regenerates itself (a box certificate) is rewritten from its own
    content; every other name goes to the stability certificate's
    :func:`.pipeline.write_listed_certificates` (its provenance, or Table I's gains for Table I's names).
    """
    from .pipeline import write_listed_certificates as write_stability

    builtin_templates()
    directory = Path(directory)
    written: list[Path] = []
    for name in names:
        path = directory / name
        if path.exists():
            try:
                template, certificate = read_certificate_file(path)
            except (CertificateFormatError, InputFileError):
                template = None
            if template is not None and template is not builtin_templates()[0] and template.regenerate is not None:
                written.append(template.write(template.regenerate(certificate), path))
                continue
        written += write_stability(directory, [name])
    return written
