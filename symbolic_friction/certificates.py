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

The quadratic template (beyond the paper) proves a tighter bound for Table I, case (a):

>>> from symbolic_friction.certificates import certify_quadratic, verify_quadratic
>>> quadratic = certify_quadratic(sf.Parameters.table_i("a"))  # doctest: +SKIP
>>> verify_quadratic(quadratic).proved, quadratic.overshoot_bound  # doctest: +SKIP
(True, '1.80834')

The sup-flow template (beyond the paper: ``V_∞``, the peak of the friction-free flow, on ``R`` and time
pieces of ``U`` on ``R̂``; version 2 with forms per sign of ``σv``) comes within 0.4 % of the friction-free
limit ``sup_t ‖e^{At}‖₂ = 1.3733``:

>>> from symbolic_friction.certificates import load_sup_flow, verify_sup_flow
>>> sup = load_sup_flow("proofs/sup_flow/case_a.json")  # doctest: +SKIP
>>> verify_sup_flow(sup).proved, sup.overshoot_bound, len(sup.pieces)  # doctest: +SKIP
(True, '1.37852', 33)

Reset PID (beyond the paper) settles exponentially on Table I (a): ``|σ|`` shrinks by ``ρ ≤ 0.458633`` per slip,
proved in arb balls:

>>> from symbolic_friction.certificates import certify_contraction, verify_contraction
>>> contraction = certify_contraction(sf.Parameters.table_i("a"))
>>> verify_contraction(contraction).proved, contraction.rho
(True, Fraction(458633, 1000000))

What ``symbolic-friction certify`` does by default: the closed form, then the other searches cheapest first
until κ is within 10 % of κ_lin's proven lower end (or 6 s are spent), the smallest proved κ kept:

>>> from symbolic_friction.certificates import certify_template
>>> choice = certify_template(sf.Parameters.table_i("a"))  # doctest: +SKIP
>>> choice.describe()  # doctest: +SKIP
'template sup-flow (pieces) (auto: the smallest proved κ): κ 1.44800; paper: κ 3.46703; sup-flow (one piece): κ 1.79444; quadratic: κ 1.80833'
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
    # boxes of gains (one certificate for an interval of each gain)
    "certify_box": "._certify.box",
    "verify_box": "._certify.box",
    "BoxCertificate": "._certify.box",
    # the quadratic template (beyond the paper: free P with P12 = 0, a general U = y'Ky)
    "certify_quadratic": "._certify.quadratic_search",
    "verify_quadratic": "._certify.quadratic",
    "QuadraticCertificate": "._certify.quadratic",
    # the sup-flow template (beyond the paper: V_inf on R, time pieces of U on R-hat)
    "certify_contraction": "._certify.reset_contraction",
    "verify_contraction": "._certify.reset_contraction",
    "load_contraction": "._certify.reset_contraction",
    "ContractionCertificate": "._certify.reset_contraction",
    "certify_sup_flow": "._certify.sup_flow_search",
    "verify_sup_flow": "._certify.sup_flow",
    "load_sup_flow": "._certify.sup_flow_v2",
    "SupFlowCertificate": "._certify.sup_flow",
    # the choice of template (certify --template auto|paper|quadratic|sup-flow)
    "certify_template": "._certify.choose",
    "TemplateChoice": "._certify.choose",
}

__all__ = list(_LAZY)

__getattr__ = lazy_getattr("symbolic_friction", globals(), _LAZY)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
