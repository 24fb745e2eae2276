"""Find, prove and write certificates: search → exact rounding → exact
verification → atomic write of the JSON and its Markdown report.

Nothing is written unless :func:`~._certify.verify.verify_certificate` has
proved it, and regenerating a certificate writes byte-identical files, which
is what :func:`check_committed_certificates` relies on to detect stale files.
"""

from __future__ import annotations

import dataclasses
import hashlib
import os
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Iterable

from .._infra.errors import CertificateError, CertificateFormatError, InputFileError, ParameterError, SymbolicFrictionError
from .._infra.rational import short_rational
from .._model.parameters import Parameters
from ._template import Template, register
from .certificate import MAX_FILE_BYTES, OBLIGATIONS, SCHEMA, TEMPLATE_ID, Certificate, atomic_write_text, dumps, from_data, load
from .report import render_markdown
from .rounding import to_certificate
from .search import MODES, check_margin, check_mode, find_candidate
from .verify import VerificationReport, verify_certificate

__all__ = [
    "certify",
    "render_files",
    "write_certificate",
    "certify_table_i",
    "table_i_stem",
    "TABLE_I_FILES",
    "default_stem",
    "regenerate",
    "stability_staleness",
    "stability_drift",
    "STABILITY",
    "write_listed_certificates",
]

TABLE_I_LABELS = {"a": "Table I, case (a)", "b": "Table I, case (b)"}
TABLE_I_FILES: tuple[str, ...] = tuple(f"case_{case}_{mode}.json" for case in TABLE_I_LABELS for mode in MODES)
"""The committed certificates of ``proofs/`` (both cases of Table I, both modes)."""
BEYOND_TABLE_I_FILES: tuple[str, ...] = ("case_a.json", "case_b.json")
"""Table I's certificates in the templates beyond the paper, under ``proofs/quadratic/`` and ``proofs/sup_flow/``."""
RESET_TABLE_I_FILES: tuple[str, ...] = ("case_a_contraction.json",)
"""Table I's reset-contraction certificates, under ``proofs/reset/`` (case (b) has none: its slip from a stick never ends)."""


MAX_GAIN_DIGITS = 500
"""The longest numerator or denominator of a gain :func:`certify` takes: the closed form's formulas multiply up to
eight of them, and Python prints no integer beyond 4300 digits (a 600-digit gain set could fail there); ``f_c`` only
scales the certificate and may be longer."""


def _digits(n: int) -> int:
    """Decimal digits of ``|n|`` (a number of bits beyond Python's 4300-digit ``str`` limit: more than enough)."""
    return len(str(abs(n))) if n.bit_length() < 14_000 else n.bit_length()


SEARCHES: tuple[str, ...] = ("closed-form", "sdp")
"""The searches ``certify`` can use; the first is the default."""


def check_search(search: object) -> str:
    """Return ``search`` if it is one of :data:`SEARCHES`, else raise ParameterError."""
    if search not in SEARCHES:
        raise ParameterError(f"search must be one of {', '.join(repr(s) for s in SEARCHES)}; got {search!r}")
    return str(search)


def certify(
    params: Parameters, *, mode: str = "tightest", margin: object = None, label: str = "", physical: dict | None = None,
    search: str = "closed-form",
) -> Certificate:
    """Search, round and exactly verify a certificate for ``params``.

    Parameters
    ----------
    params : Parameters
        Gains satisfying Assumption 1.
    mode : {"tightest", "feasible"}, keyword-only
        ``tightest`` keeps the margin on the strict k-conditions only (with
        the SDP: minimises κ); ``feasible`` keeps a wider margin (the closed
        form moves c₁ and c₂ outward by it too; the SDP minimises a linear
        surrogate instead of κ).
    margin : number, keyword-only
        Relative margin on the strict inequalities (default: 1/10⁶ for
        tightest, 1/100 for feasible).
    search : {"closed-form", "sdp"}, keyword-only
        ``closed-form`` (default) writes the constants of
        :mod:`.closed_form` down for any gains, without a solver; ``sdp``
        solves the semidefinite program of :mod:`.search` (cvxpy + Clarabel).
        Either way the exact verifier decides, and the certificate records
        which search produced it.
    label : str, keyword-only
        Free text stored in the provenance.
    physical : dict, keyword-only
        The physical parameters ``params`` came from (``m``, ``k_p_bar``,
        ``k_i_bar``, ``k_d_bar``, ``alpha_v``, ``f_c_bar``), recorded in the
        certificate; the verifier checks that they normalise to ``params``.
        Default: ``params.physical`` (set by :meth:`Parameters.from_physical`).

    Returns
    -------
    Certificate
        A certificate that :func:`~symbolic_friction.verify_certificate` proves.

    Raises
    ------
    ParameterError
        If ``params`` has static friction above Coulomb (``f_s > f_c``), or an unknown search.
    InfeasibleError, InaccurateSolveError
        If the SDP solver does not report an optimal solution.
    CertificateError
        If the rounded constants do not verify (never silently returned).

    Examples
    --------
    >>> cert = certify(Parameters.table_i("a"))
    >>> cert.k1, cert.k2, cert.overshoot_bound
    (Fraction(2, 1), Fraction(2, 1), '3.46703')
    """
    if not isinstance(params, Parameters):
        raise ParameterError(f"params must be a Parameters instance (e.g. Parameters.table_i('a')); got {type(params).__name__}")
    if not isinstance(label, str):
        raise ParameterError(f"label must be a string; got {type(label).__name__}")
    for name in ("k_p", "k_i", "k_v"):  # the closed form multiplies them (f_c only scales: 10**999 is fine)
        q = getattr(params, name)
        if max(_digits(q.numerator), _digits(q.denominator)) > MAX_GAIN_DIGITS:
            raise ParameterError(f"certify takes gains k_p, k_i, k_v of at most {MAX_GAIN_DIGITS} digits in numerator "
                                 f"and denominator; got {name} = {short_rational(q)}")
    params.check_paper_model()
    search = check_search(search)
    if search == "closed-form":
        from .closed_form import closed_form_certificate

        mode = check_mode(mode)
        certificate = closed_form_certificate(params, mode=mode, margin=check_margin(margin, mode), label=label)
    else:
        certificate = to_certificate(find_candidate(params, mode=mode, margin=margin), label=label)
    if physical is None and params.physical is not None:  # gains from Parameters.from_physical
        physical = params.physical.as_dict()
    if physical is not None:
        certificate = dataclasses.replace(certificate, physical=physical)
    report = verify_certificate(certificate)
    if not report.proved:
        raise CertificateError(
            f"the rounded {mode} candidate for {params} does not verify exactly: "
            + "; ".join(check.message for check in report.failures)
        )
    return certificate


def render_files(certificate: Certificate, *, name: str) -> tuple[str, str, VerificationReport]:
    """The JSON text and the Markdown report of a *proved* certificate.

    Raises
    ------
    CertificateError
        If the certificate does not verify (nothing unproved is ever rendered
        for writing).
    """
    report = verify_certificate(certificate, source=name)
    report.raise_if_failed()
    return dumps(certificate), render_markdown(report, name=name), report


def write_certificate(certificate: Certificate, path: str | os.PathLike[str]) -> tuple[Path, Path]:
    """Verify ``certificate`` and write ``path`` (JSON) and its ``.md`` report, atomically.

    Returns
    -------
    (Path, Path)
        The JSON file and the Markdown file.

    Raises
    ------
    ParameterError
        If ``path`` does not end in ``.json``.
    CertificateError
        If the certificate does not verify; nothing is written then.
    """
    from .._infra.guards import check_path

    if not isinstance(certificate, Certificate):
        raise ParameterError(f"certificate must be a Certificate (from certify or load_certificate); got {type(certificate).__name__}")
    path = Path(check_path(path, name="path", what="the certificate's JSON file"))
    if path.suffix != ".json":
        raise ParameterError(f"a certificate file name must end in '.json'; got {str(path)!r}")
    json_text, md_text, _ = render_files(certificate, name=path.name)
    md_path = path.with_suffix(".md")
    atomic_write_text(path, json_text)
    atomic_write_text(md_path, md_text)
    return path, md_path


def table_i_stem(case: str, mode: str) -> str:
    """``"case_a_tightest"`` etc."""
    return f"case_{case}_{mode}"


def default_stem(params: Parameters, mode: str) -> str:
    """A deterministic file stem for one gain set: ``certificate_<hash of the exact gains>_<mode>``."""
    key = ",".join(f"{k}={v}" for k, v in params.as_strings().items())
    return f"certificate_{hashlib.sha256(key.encode()).hexdigest()[:12]}_{mode}"


def certify_table_i(
    directory: str | os.PathLike[str] = "proofs", *, modes: Iterable[str] = MODES, search: str = "closed-form"
) -> list[Path]:
    """Certify Table I's cases (a) and (b) in each mode and write them under ``directory``.

    Returns the written paths (JSON and Markdown, in order).
    """
    directory = Path(directory)
    written: list[Path] = []
    for case, label in TABLE_I_LABELS.items():
        for mode in modes:
            cert = certify(Parameters.table_i(case), mode=check_mode(mode), label=label, search=search)
            written.extend(write_certificate(cert, directory / f"{table_i_stem(case, mode)}.json"))
    return written


def regenerate(certificate: Certificate) -> Certificate:
    """What ``certify`` would produce now for the gains, mode, margin, label and search of ``certificate``.

    Raises
    ------
    CertificateFormatError
        If the certificate has no provenance or an unknown mode (it cannot be regenerated).
    """
    prov = certificate.provenance
    if prov is None:
        raise CertificateFormatError("the certificate has no provenance, so it cannot be regenerated")
    if prov.mode not in MODES:
        raise CertificateFormatError(
            f"provenance.mode is {prov.mode!r}; only {', '.join(MODES)} certificates can be regenerated"
        )
    return certify(
        certificate.as_parameters(), mode=prov.mode, margin=check_margin(prov.margin, prov.mode), label=prov.label,
        physical=certificate.physical, search=prov.search,
    )


def stability_staleness(certificate: Certificate, path: Path) -> str:
    """Why the committed ``path`` no longer states what ``certify`` proves (empty if it does).

    Stale means a different statement, not different rounding: the file lists
    other obligations than the ones a certificate instantiates now, or its
    Markdown report is missing.  A file that proves the same statement with
    other digits is *drift* (:func:`stability_drift`).
    """
    prov = certificate.provenance
    if prov is not None and tuple(prov.obligations) != OBLIGATIONS:
        return (f"written for a different statement: it lists the obligations {', '.join(prov.obligations)}; "
                f"a certificate now instantiates {', '.join(OBLIGATIONS)}")
    md_path = path.with_suffix(".md")
    if not md_path.exists():
        return f"its report {md_path.name} is missing"
    return ""


def stability_drift(certificate: Certificate, path: Path) -> str:
    """How ``path`` (and its report) differ from what ``certify`` writes now for the same gains and provenance.

    Names every constant that changed (old → new) and whether κ got better or
    worse; empty when the files are byte-identical.
    """
    from .._infra.io import read_limited
    from .._infra.rational import format_rational as fmt
    from .certificate import CONSTANT_NAMES

    try:
        fresh = regenerate(certificate)
        json_text, md_text, _ = render_files(fresh, name=path.name)
    except SymbolicFrictionError as exc:
        return f"cannot be regenerated here: {exc}"
    notes = []
    if read_limited(path, limit=MAX_FILE_BYTES, what="certificate") != json_text.encode("utf-8"):
        changed = [f"{n} {fmt(getattr(certificate, n))} → {fmt(getattr(fresh, n))}"
                   for n in CONSTANT_NAMES if getattr(certificate, n) != getattr(fresh, n)]
        old, new = certificate.kappa, fresh.kappa  # exact at any length
        if old != new:
            changed.append(f"κ {certificate.overshoot_bound} → {fresh.overshoot_bound} ({'better' if new < old else 'worse'})")
        was, now = (certificate.provenance.package_version if certificate.provenance else ""), (
            fresh.provenance.package_version if fresh.provenance else "")
        if was != now:
            changed.append(f"written by symbolic-friction {was or '(unknown)'}, now {now}")
        notes.append(f"{path.name}: " + ("; ".join(changed) if changed else "the same numbers, written differently"))
    md_path = path.with_suffix(".md")
    try:
        if read_limited(md_path, limit=MAX_FILE_BYTES, what="proof report") != md_text.encode("utf-8"):
            notes.append(f"its report {md_path.name} differs from what `certify` renders now")
    except InputFileError as exc:
        notes.append(f"its report is unreadable: {exc}")
    if notes:
        notes.append("`symbolic-friction check --write` rewrites them")
    return "; ".join(notes)


STABILITY = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: from_data(data, source=source),
    verify=lambda certificate, source: verify_certificate(certificate, source=source),
    dumps=dumps,
    stale=stability_staleness,
    claim=lambda certificate: f"κ ≤ {certificate.overshoot_bound}",
    default=True,
    drift=stability_drift,
    name="paper",
))
"""The stability certificate of Proposition 1 (Lemma 2, Lemma 3): constants of ``V`` and ``V̂`` and κ."""


def write_listed_certificates(directory: str | os.PathLike[str], names: Iterable[str]) -> list[Path]:
    """Regenerate the certificates ``names`` under ``directory`` (``check --write``).

    An existing certificate is re-certified from its own provenance (gains,
    mode, margin, label, physical parameters); a missing file named like one
    of Table I's (``case_a_tightest.json`` …) is certified for Table I's
    gains.  A missing file of any other name cannot be created (its gains are
    unknown) and is left for :func:`check_listed_certificates` to report.  A
    hunting certificate is rewritten from its gains and the zero in its box
    (:func:`.hunting.regenerate_hunting`).

    Returns the written paths (JSON and Markdown, in order).
    """
    from .hunting import is_hunting_file, load_hunting, regenerate_hunting, write_hunting

    directory = Path(directory)
    written: list[Path] = []
    table_i = {table_i_stem(case, mode) + ".json": (case, mode) for case in TABLE_I_LABELS for mode in MODES}
    for name in names:
        path = directory / name
        fresh = None
        if path.exists() and is_hunting_file(path):
            written.append(write_hunting(regenerate_hunting(load_hunting(path)), path))
            continue
        if path.exists():
            try:
                fresh = regenerate(load(path))
            except (CertificateFormatError, InputFileError):
                fresh = None
        if fresh is None and path.name in table_i and path.parent == directory:
            case, mode = table_i[path.name]
            fresh = certify(Parameters.table_i(case), mode=mode, label=TABLE_I_LABELS[case])
        if fresh is not None:
            written.extend(write_certificate(fresh, path))
        elif path.parent == directory / "quadratic" and path.name in BEYOND_TABLE_I_FILES:
            # Table I in the quadratic template: its gains are known from the name
            from .quadratic import QUADRATIC
            from .quadratic_search import certify_quadratic

            case = path.stem[-1]
            written.append(QUADRATIC.write(certify_quadratic(Parameters.table_i(case), label=TABLE_I_LABELS[case]), path))
        elif path.parent == directory / "sup_flow" and path.name in BEYOND_TABLE_I_FILES:
            from .sup_flow import SUP_FLOW
            from .sup_flow_search import certify_sup_flow

            case = path.stem[-1]
            written.append(SUP_FLOW.write(certify_sup_flow(Parameters.table_i(case), label=TABLE_I_LABELS[case], tail="own"), path))
        elif path.parent == directory / "reset" and path.name in RESET_TABLE_I_FILES:
            # an existing one regenerates itself (its template's `regenerate`); a missing one is Table I's
            from .reset_contraction import RESET_CONTRACTION, certify_contraction

            case = path.stem.split("_")[1]
            written.append(RESET_CONTRACTION.write(certify_contraction(Parameters.table_i(case), label=TABLE_I_LABELS[case]), path))
    return written
