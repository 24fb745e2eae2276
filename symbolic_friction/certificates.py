"""Certificates beyond the everyday calls: the search, file (de)serialisation, sweeps and Table I.

:func:`symbolic_friction.certify` and :func:`symbolic_friction.verify_certificate`
are the everyday calls; here is what they are made of.

Examples
--------
The round trip of a certificate file, with the everyday calls:

>>> import tempfile, pathlib
>>> import symbolic_friction as sf
>>> cert = sf.certify(sf.Parameters.table_i("a"), mode="feasible")
>>> isinstance(cert, sf.Certificate), cert.kappa ** 2 >= cert.kappa_squared  # κ exact, a Fraction
(True, True)
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> json_path, md_path = sf.write_certificate(cert, folder / "case_a.json")
>>> sf.load_certificate(json_path) == cert
True
>>> report = sf.verify_file(json_path)
>>> isinstance(report, sf.VerificationReport), report.proved
(True, True)
"""

from __future__ import annotations

from ._namespace import lazy_getattr

# name -> private module that defines it (imported on first use)
_LAZY: dict[str, str] = {
    "certify_many": "._certify",
    "SweepItem": "._certify",
    "Provenance": "._certify",
    "Candidate": "._certify",
    "find_candidate": "._certify",
    "loads_certificate": "._certify",
    "dumps_certificate": "._certify",
    "certify_table_i": "._certify",
    "check_committed_certificates": "._certify",
    "CommittedCertificate": "._certify",
    "TABLE_I_FILES": "._certify",
}

__all__ = list(_LAZY)

__getattr__ = lazy_getattr("symbolic_friction", globals(), _LAZY)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
