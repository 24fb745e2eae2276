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
from pathlib import Path
from typing import Iterable

from .._infra.errors import CertificateError, CertificateFormatError, InputFileError, ParameterError, SymbolicFrictionError
from .._model.parameters import Parameters
from ._template import Template, register
from .certificate import MAX_FILE_BYTES, SCHEMA, TEMPLATE_ID, Certificate, atomic_write_text, dumps, from_data, load
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
    "STABILITY",
    "write_listed_certificates",
]

TABLE_I_LABELS = {"a": "Table I, case (a)", "b": "Table I, case (b)"}
TABLE_I_FILES: tuple[str, ...] = tuple(f"case_{case}_{mode}.json" for case in TABLE_I_LABELS for mode in MODES)
"""The committed certificates of ``proofs/`` (both cases of Table I, both modes)."""
QUADRATIC_TABLE_I_FILES: tuple[str, ...] = ("case_a.json", "case_b.json")
"""Table I's certificates in the quadratic template, under ``proofs/quadratic/``."""


def certify(
    params: Parameters, *, mode: str = "tightest", margin: object = None, label: str = "", physical: dict | None = None
) -> Certificate:
    """Search, round and exactly verify a certificate for ``params``.

    Parameters
    ----------
    params : Parameters
        Gains satisfying Assumption 1.
    mode : {"tightest", "feasible"}, keyword-only
        ``tightest`` minimises the overshoot bound κ; ``feasible`` returns
        constants with a wider margin from a cheaper (non-SDP) search.
    margin : number, keyword-only
        Relative margin on the strict inequalities (default: 1/10⁶ for
        tightest, 1/100 for feasible).
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
        If ``params`` has static friction above Coulomb (``f_s > f_c``).
    InfeasibleError, InaccurateSolveError
        If the solver does not report an optimal solution.
    CertificateError
        If the rounded constants do not verify (never silently returned).

    Examples
    --------
    >>> cert = certify(Parameters.table_i("a"))
    >>> cert.k1, cert.k2, cert.overshoot_bound
    (Fraction(2, 1), Fraction(2, 1), '3.46703')
    """
    if params.stiction:
        # Proposition 1 is about the paper's model; with f_s > f_c the mass hunts (see hunting_cycle)
        raise ParameterError(
            f"a stability certificate is for the paper's model f_s = f_c; got f_s = {params.f_s} > f_c = {params.f_c}: "
            "with static friction above Coulomb the loop hunts (symbolic-friction hunting)"
        )
    candidate = find_candidate(params, mode=mode, margin=margin)
    certificate = to_certificate(candidate, label=label)
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
    path = Path(path)
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


def certify_table_i(directory: str | os.PathLike[str] = "proofs", *, modes: Iterable[str] = MODES) -> list[Path]:
    """Certify Table I's cases (a) and (b) in each mode and write them under ``directory``.

    Returns the written paths (JSON and Markdown, in order).
    """
    directory = Path(directory)
    written: list[Path] = []
    for case, label in TABLE_I_LABELS.items():
        for mode in modes:
            cert = certify(Parameters.table_i(case), mode=check_mode(mode), label=label)
            written.extend(write_certificate(cert, directory / f"{table_i_stem(case, mode)}.json"))
    return written


def regenerate(certificate: Certificate) -> Certificate:
    """What ``certify`` would produce now for the gains, mode, margin and label of ``certificate``.

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
        physical=certificate.physical,
    )


def stability_staleness(certificate: Certificate, path: Path) -> str:
    """Why the committed ``path`` (and its ``.md`` report) differ from what ``certify`` writes now; empty if they do not."""
    try:
        fresh = regenerate(certificate)
        json_text, md_text, _ = render_files(fresh, name=path.name)
    except SymbolicFrictionError as exc:
        return f"cannot be regenerated: {exc}"
    from .._infra.io import read_limited

    md_path = path.with_suffix(".md")
    stale = []
    if read_limited(path, limit=MAX_FILE_BYTES, what="certificate") != json_text.encode("utf-8"):
        stale.append(path.name)
    if not md_path.exists():
        return f"its report {md_path.name} is missing"
    try:
        md_bytes = read_limited(md_path, limit=MAX_FILE_BYTES, what="proof report")
    except InputFileError as exc:
        return f"its report is unreadable: {exc}"
    if md_bytes != md_text.encode("utf-8"):
        stale.append(md_path.name)
    if stale:
        return (
            f"{' and '.join(stale)} {'differ' if len(stale) > 1 else 'differs'} from what `symbolic-friction certify` "
            "writes now"
        )
    return ""


STABILITY = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: from_data(data, source=source),
    verify=lambda certificate, source: verify_certificate(certificate, source=source),
    dumps=dumps,
    stale=stability_staleness,
    failure=lambda report: "; ".join(check.message for check in report.failures),
    claim=lambda certificate: f"κ ≤ {certificate.overshoot_bound}",
    default=True,
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
        elif path.parent == directory / "quadratic" and path.name in QUADRATIC_TABLE_I_FILES:
            # Table I in the quadratic template: its gains are known from the name
            from .quadratic import QUADRATIC
            from .quadratic_search import certify_quadratic

            case = path.stem[-1]
            written.append(QUADRATIC.write(certify_quadratic(Parameters.table_i(case), label=TABLE_I_LABELS[case]), path))
    return written
