"""Fixtures shared by the cross-check tests: one run on the paper's certificates, one on wrong ones."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._crosscheck import Claims, crosscheck
from symbolic_friction._model.lyapunov import lyapunov_matrix
from tests.crosscheck.helpers import N_SMALL, PROOFS, _cert


@pytest.fixture(scope="session")
def paper_report():
    """The four committed certificates on a small sample (both modes share trajectories)."""
    files = [PROOFS / f"case_{c}_{m}.json" for c in "ab" for m in ("feasible", "tightest")]
    return crosscheck(files, trajectories=N_SMALL, seed=1, progress=False)


def _lambda_min_P(cert) -> float:
    p = Parameters(k_p=cert.k_p, k_i=cert.k_i, k_v=cert.k_v, f_c=cert.f_c)
    return float(np.linalg.eigvalsh(lyapunov_matrix(p))[0])


def wrong_certificates(cert, observed_overshoot: float) -> dict:
    """Altered copies the exact verifier would reject (built in memory, never verified)."""
    kappa = 0.5 * (1.0 + observed_overshoot)  # strictly between 1 and the observed overshoot
    c1 = Fraction(_lambda_min_P(cert) * 1.01).limit_denominator(10**9)
    return {
        "kappa": dataclasses.replace(cert, overshoot_bound=f"{kappa:.6f}"),
        "c": dataclasses.replace(cert, c=10 * 2 * (cert.k_v * cert.k_p - cert.k_i)),
        "c1": dataclasses.replace(cert, c1=c1),
        # k4 < k_p k2 violates a derived condition of Lemma 3 (eq. hatVdot)
        "k4": dataclasses.replace(cert, k4=cert.k_p * cert.k2 / 2),
    }


_WRONG_REPORTS: dict[str, tuple] = {}
"""``wrong_report``'s value per case, kept for the session: pytest holds one value of a parametrized fixture at a
time and sets it up again whenever the tests switch between ``a`` and ``b``, which a worker running these modules one
at a time did for each module (the same seeded run of several seconds, again and again)."""


@pytest.fixture(scope="session", params=["a", "b"])
def wrong_report(request, paper_report):
    case = request.param
    if case not in _WRONG_REPORTS:
        cert = _cert(case)
        observed = next(c for c in paper_report.checks if c.label == f"case_{case}_tightest").max_overshoot
        wrong = wrong_certificates(cert, max(observed.values()))
        claims = [Claims.from_certificate(c, label=name) for name, c in wrong.items()]
        report = crosscheck(claims, trajectories=N_SMALL, seed=2, progress=False, require_proved=False)
        _WRONG_REPORTS[case] = (case, wrong, {c.label: c for c in report.checks}, report)
    return _WRONG_REPORTS[case]
