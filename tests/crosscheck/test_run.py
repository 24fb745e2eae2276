"""The driver :func:`crosscheck`: the paper's certificates pass, wrong ones fail only where they are wrong, bad input is refused."""

from __future__ import annotations

import dataclasses
import numpy as np
import pytest

from symbolic_friction.errors import ParameterError
from symbolic_friction import Parameters
from symbolic_friction._crosscheck import PROPERTIES
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck import crosscheck
from symbolic_friction._crosscheck._run import default_horizon
from symbolic_friction._crosscheck._run import sample_times
from symbolic_friction._simulation.batch import simulate_batch
from tests.crosscheck.helpers import N_SMALL, PROOFS


def test_paper_certificates_pass(paper_report):
    assert paper_report.passed
    assert len(paper_report.checks) == 4
    for check in paper_report.checks:
        assert check.trajectories == N_SMALL
        for r in check.results:
            assert r.failures == 0, (check.label, r.id, r.counterexample)
            assert r.counterexample is None
            if r.id == "remark.stick_sigma" and check.label.startswith("case_b"):
                continue  # case (b): solutions stick at most once (paper, Section III)
            assert r.samples > 0, (check.label, r.id)
            assert r.worst_margin >= -paper_report.rtol
        # the certified bound is not attained: observed overshoot / κ < 1, per search mode
        tight = check.tightness
        assert set(tight) >= {"random spheres", "grid", "special", "adversarial", "all"}
        assert 0.2 < tight["all"] < 1.0
        assert max(check.max_overshoot.values()) >= 1.0


def test_properties_are_reported_in_paper_order(paper_report):
    ids = [r.id for r in paper_report.checks[0].results]
    assert ids == [p.id for p in PROPERTIES]


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"trajectories": 0}, "trajectories must be an integer ≥ 1; got 0"),
        ({"samples": 2}, "samples must be an integer ≥ 3; got 2"),
        ({"horizon": -1.0}, "horizon must be a finite number > 0; got -1.0"),
        ({"rtol": 0.0}, r"rtol must be in \(0, 1\); got 0.0"),
        ({"theta": 1.5}, r"theta must be in \(0, 1\]; got 1.5"),
    ],
)
def test_crosscheck_argument_errors(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        crosscheck([PROOFS / "case_a_feasible.json"], **kwargs)


def test_crosscheck_needs_a_certificate():
    with pytest.raises(ParameterError, match="no certificate to cross-check"):
        crosscheck([])


def test_unproved_certificate_is_refused_by_default(tmp_path):
    from dataclasses import replace

    from symbolic_friction.errors import UnprovedCertificateError
    from symbolic_friction._certify import load

    cert = load(PROOFS / "case_a_tightest.json")
    forged = replace(cert, c2=cert.c2 / 2)  # c₂ below λ_max(P)
    with pytest.raises(UnprovedCertificateError, match="c2·I − P ⪰ 0"):
        crosscheck([forged], trajectories=10, progress=False)
    with pytest.raises(UnprovedCertificateError, match="cannot be verified exactly"):
        crosscheck([Claims.from_certificate(cert)], trajectories=10, progress=False)


def test_incomplete_trajectories_are_counted_and_never_hold():
    report = crosscheck([PROOFS / "case_a_tightest.json"], trajectories=40, adversarial=False, samples=51,
                        progress=False, max_events=2)
    check = report.checks[0]
    assert 0 < check.incomplete <= 40 + len(report.checks)  # resolution runs may add some
    assert check.verdict == "incomplete" and not check.passed and not report.passed
    assert report.summary().startswith("crosscheck: INCOMPLETE")
    # the unsimulated tail was not used: overshoots of incomplete runs are not measurements
    assert np.isnan(check.overshoots).sum() >= 1


def test_incomplete_batch_keeps_nan_after_the_stop():

    p = Parameters.table_i("a")
    batch = simulate_batch(p, np.array([[0.0, 3.0, 0.0]]), 30.0, t_eval=np.linspace(0, 30, 31), max_events=2)
    assert not batch.complete[0]
    assert np.isnan(batch.x[0, -1]).all()  # never held at the last state


def test_default_horizon_and_samples():
    assert default_horizon(Parameters.table_i("b")) == 100.0  # slowest root -0.2
    t = sample_times(10.0, 11)
    assert t[0] == 0 and t[-1] == 10.0 and np.all(np.diff(t) > 0) and t[1] < t[-1] - t[-2]





def test_only_the_altered_property_fails(wrong_report):
    case, wrong, checks, report = wrong_report
    expected = {
        "kappa": {"prop1.stability"},
        "c": {"lemma2.decrease"},
        "c1": {"lemma2.lower_bound"},
        "k4": {"lemma3.hatV_nonincreasing", "lemma3.hatV_lower"},
    }
    for name, check in checks.items():
        failed = {r.id for r in check.results if r.failures}
        assert failed and failed <= expected[name], (name, failed)
