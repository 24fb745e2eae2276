"""The cross-check of quadratic-template certificates: only their bound κ is a claim, checked trajectory by trajectory."""

from __future__ import annotations

import dataclasses
import json
import math

import pytest

from symbolic_friction._certify.quadratic import verify_quadratic
from symbolic_friction._certify.templates import read_certificate_file
from symbolic_friction._crosscheck import Claims, crosscheck, format_report
from symbolic_friction._crosscheck._report import format_tightness
from symbolic_friction._infra.errors import CertificateFormatError, UnprovedCertificateError
from tests.computed_once import computed_once
from tests.crosscheck.helpers import N_SMALL, PROOFS, _result

QUADRATIC_A = PROOFS / "quadratic" / "case_a.json"
KAPPA_ONLY = ["prop1.stability", "prop1.attractivity", "remark.stick_sigma", "model.modes"]


@pytest.fixture(scope="module", autouse=True)
def shared_kappa_lin_lower():
    """The proven lower end of κ_lin computed once per gains in this module (about 0.1-0.2 s each).

    The tightness table of every report gives it per certificate, and the tests here format Table I (a)'s eight times.  It is a pure function of the parameters (a float search for the
    peak time, then an arb enclosure at the precision it sets and restores), so a later call with equal parameters
    gets the first call's value; a call that raises is not kept.
    """
    from symbolic_friction._certify import flow_bound

    with computed_once(flow_bound, "kappa_lin_lower"):
        yield


def _quadratic(case: str):
    return read_certificate_file(PROOFS / "quadratic" / f"case_{case}.json")[1]


@pytest.fixture(scope="module")
def both_templates():
    """Case (a)'s tightest paper certificate and its quadratic one, on the same trajectories (adversary on)."""
    return crosscheck([PROOFS / "case_a_tightest.json", QUADRATIC_A], trajectories=N_SMALL, seed=3, progress=False)


def test_a_quadratic_certificate_is_held_to_its_bound_and_the_paper_to_every_property(both_templates):
    paper, quadratic = both_templates.checks
    assert both_templates.passed
    assert quadratic.label == "quadratic/case_a" and quadratic.claims.template_name == "quadratic"
    assert [r.id for r in quadratic.results] == KAPPA_ONLY
    assert len(paper.results) == 11 and paper.claims.template_name == "paper"
    # the same trajectories (one gain set): the same worst overshoot, two tightnesses
    assert paper.max_overshoot == quadratic.max_overshoot
    worst = max(quadratic.max_overshoot.values())
    assert 1.2 < worst <= 1.3733  # below the friction-free limit sup_t ‖e^{At}‖ = 1.373268
    assert quadratic.tightness["all"] == pytest.approx(worst / 1.80833)
    assert paper.tightness["all"] == pytest.approx(worst / 3.46703)
    assert _result(quadratic, "prop1.stability").samples > N_SMALL  # every sample and event, not one per trajectory


def test_the_report_gives_the_tightness_per_certificate_and_template(both_templates):
    table = format_tightness(both_templates)
    rows = table.splitlines()[2:]
    assert rows[0].split()[:3] == ["case_a_tightest", "paper", "3.46703"] and rows[0].endswith("held")
    assert rows[1].split()[:3] == ["quadratic/case_a", "quadratic", "1.80833"] and rows[1].endswith("held")
    assert "-rtol = 1e-08 fails" in table.splitlines()[0]
    assert table in format_report(both_templates)


def test_a_forged_quadratic_kappa_below_the_observed_overshoot_fails_on_trajectories(tmp_path):
    """κ = 1.2 for case (a), where trajectories reach ≈ 1.37: the verifier refuses it, and so does the cross-check."""
    forged = dataclasses.replace(_quadratic("a"), overshoot_bound="1.2")
    assert not verify_quadratic(forged).proved  # the verifier would refuse it …
    with pytest.raises(UnprovedCertificateError, match="does not verify"):
        crosscheck([forged], trajectories=5, progress=False)
    # … so bypass it: the trajectories alone must catch the forged bound
    report = crosscheck([PROOFS / "case_a_tightest.json", forged], trajectories=N_SMALL, seed=4, progress=False,
                        require_proved=False)
    paper, check = report.checks
    assert not report.passed and check.verdict == "failed" and paper.verdict == "passed"
    stability = _result(check, "prop1.stability")
    assert stability.failures > 0 and [r.id for r in check.results if not r.passed] == ["prop1.stability"]
    cx = stability.counterexample
    assert cx.values["kappa"] == 1.2 and cx.values["observed_ratio"] > 1.2
    assert "VIOLATED" in format_tightness(report).splitlines()[3]


def test_quadratic_claims_carry_no_constant_of_the_paper():
    claims = Claims.from_certificate(_quadratic("b"), label="q")
    assert claims.template == "quadratic/v1" and claims.kappa == pytest.approx(3.273)
    assert math.isnan(claims.c1) and claims.exact["p11"] == str(_quadratic("b").constants["p11"])
    with pytest.raises(CertificateFormatError, match="has no constant of Lemmas 2 and 3"):
        dataclasses.replace(claims, c1=1.0)


def test_files_of_other_templates_are_refused_naming_why(tmp_path):
    with pytest.raises(CertificateFormatError, match="a box certificate"):
        crosscheck([PROOFS / "box_physical.json"], trajectories=5, progress=False)


def test_the_cli_reports_the_template_in_json(tmp_path, capsys):
    from symbolic_friction._cli.main import main

    argv = ["crosscheck", str(QUADRATIC_A), "--trajectories", "20", "--no-adversarial", "--json", "--out", str(tmp_path)]
    assert main(argv) == 0
    payload = json.loads(capsys.readouterr().out)
    (cert,) = payload["certificates"]
    assert cert["template"] == "quadratic" and cert["verdict"] == "passed"
    assert [p["id"] for p in cert["properties"]] == KAPPA_ONLY


def test_the_tightness_table_gives_the_proven_friction_free_floor(both_templates):
    # no certificate's κ can go below κ_lin; the table gives its proven lower end and κ as a multiple of it
    rows = [line for line in format_tightness(both_templates).splitlines() if "case_a" in line or "quadratic" in line]
    # 1.3732677…: printed rounded down, so the printed floor is still a lower end; κ/κ_lin rounded up
    assert rows and all(" 1.373267 " in row for row in rows)
    quadratic = next(row for row in rows if row.split()[1] == "quadratic")
    assert quadratic.split()[6] == "1.3169"  # 1.80833/1.37326771… = 1.31681…


def test_the_floor_is_given_on_slow_flows_too_and_left_out_beyond_float_range():
    from fractions import Fraction

    from symbolic_friction import Parameters
    from symbolic_friction._crosscheck._report import _kappa_lin_floor

    # a slowly decaying oscillation, whose full enclosure needs too many intervals: its lower end alone needs none
    slow = _kappa_lin_floor(Parameters(k_p=1, k_i=1, k_v=1 + Fraction(1, 10**6)))
    assert slow is not None and 1 < slow
    assert _kappa_lin_floor(Parameters.table_i("b")) > Fraction("2.396915")
    assert _kappa_lin_floor(Parameters(k_p="1e300", k_i="1e300", k_v=3)) is None
