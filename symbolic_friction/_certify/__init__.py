"""Proof certificates for given gains (paper: Lemma 2, Lemma 3, Proposition 1).

* :mod:`.closed_form` — the default search: constants written down for any
  gains (and for a box of gains), no solver.
* :mod:`.search` — numerical search with cvxpy + Clarabel (the only module
  importing cvxpy; ``search="sdp"``); returns a floating-point :class:`Candidate`.
* :mod:`.rounding` — exact rational rounding and repair of a candidate.
* :mod:`.certificate` — the :class:`Certificate` dataclass and its JSON format.
* :mod:`.verify` — the exact verifier (Fractions only; no code shared with
  the search); the only place a certificate is called proved.
* :mod:`.report` — the Markdown proof report.
* :mod:`.pipeline` — certify, write, regenerate, staleness of a stability certificate.
* :mod:`.box` — the box certificate: pieces of a box of gains, each decided
  at its four corners by the exact verifier.
* :mod:`.hunting`, :mod:`.hunting_proof` — the hunting certificate and its Krawczyk proof.
* :mod:`._template`, :mod:`.templates` — certificate templates: each kind of proof
  file (its ``template`` id) with its reader, exact verifier, writer and
  staleness check; :func:`.templates.check_listed_certificates` runs them.
* :mod:`.sweep` — many gain sets, with any ``concurrent.futures.Executor``.

Importing this package does not import cvxpy; the first search does.
"""

from __future__ import annotations

from .certificate import (
    OBLIGATIONS,
    SCHEMA,
    Certificate,
    Provenance,
    dumps,
    dumps_certificate,
    load,
    load_certificate,
    loads,
    loads_certificate,
)
from ._template import Template, register
from .pipeline import (
    TABLE_I_FILES,
    certify,
    certify_table_i,
    default_stem,
    regenerate,
    render_files,
    table_i_stem,
    write_certificate,
)
from .report import render_markdown
from .search import DEFAULT_MARGIN, MODES, Candidate, Search, find_candidate
from .sweep import SweepItem, certify_many
from .templates import CommittedCertificate, check_committed_certificates, check_listed_certificates, write_listed_certificates
from .verify import Check, VerificationReport, verify_certificate, verify_file

__all__ = [
    "SCHEMA",
    "OBLIGATIONS",
    "MODES",
    "DEFAULT_MARGIN",
    "TABLE_I_FILES",
    "Certificate",
    "Provenance",
    "Candidate",
    "Search",
    "find_candidate",
    "certify",
    "certify_many",
    "SweepItem",
    "certify_table_i",
    "check_committed_certificates",
    "check_listed_certificates",
    "write_listed_certificates",
    "CommittedCertificate",
    "regenerate",
    "render_files",
    "render_markdown",
    "write_certificate",
    "default_stem",
    "table_i_stem",
    "dumps",
    "loads",
    "load",
    "dumps_certificate",
    "loads_certificate",
    "load_certificate",
    "Check",
    "VerificationReport",
    "verify_certificate",
    "verify_file",
    "Template",
    "register",
]
