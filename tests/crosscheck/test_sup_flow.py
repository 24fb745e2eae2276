"""The cross-check of sup-flow certificates: their bound κ, close to the truth, checked trajectory by trajectory."""

from __future__ import annotations

import dataclasses
import json
import math

import pytest

from symbolic_friction._certify.sup_flow import verify_sup_flow
from symbolic_friction._certify.templates import read_certificate_file
from symbolic_friction._crosscheck import Claims, crosscheck
from symbolic_friction._crosscheck._report import format_tightness
from symbolic_friction._infra.errors import UnprovedCertificateError
from tests.crosscheck.helpers import N_SMALL, PROOFS, _result

KAPPA_ONLY = ["prop1.stability", "prop1.attractivity", "remark.stick_sigma", "model.modes"]


def _sup_flow(case: str):
    return read_certificate_file(PROOFS / "sup_flow" / f"case_{case}.json")[1]


@pytest.fixture(scope="module")
def case_b():
    """Case (b)'s sup-flow and quadratic certificates on the same trajectories, the adversary aimed at them."""
    return crosscheck([PROOFS / "sup_flow" / "case_b.json", PROOFS / "quadratic" / "case_b.json"],
                      trajectories=N_SMALL, seed=5, progress=False)


def test_a_sup_flow_certificate_is_held_to_its_bound_and_is_tight(case_b):
    sup, quadratic = case_b.checks
    assert case_b.passed
    assert sup.label == "sup_flow/case_b" and sup.claims.template_name == "sup-flow"
    assert [r.id for r in sup.results] == KAPPA_ONLY
    assert _result(sup, "prop1.stability").samples > N_SMALL  # every sample and event, not one per trajectory
    worst = max(sup.max_overshoot.values())
    assert 2.3 < worst <= 2.39826
    # within 1.25× of what trajectories reach, and far tighter than the quadratic template on the same ones
    assert sup.tightness["all"] == pytest.approx(worst / 2.39826) and sup.tightness["all"] > 0.8
    assert quadratic.tightness["all"] < sup.tightness["all"]


def test_the_tightness_table_names_the_template(case_b):
    rows = format_tightness(case_b).splitlines()[2:]
    assert rows[0].split()[:3] == ["sup_flow/case_b", "sup-flow", "2.39826"] and rows[0].endswith("held")
    assert "2.396915" in rows[0]  # the proven friction-free floor (2.3969157…, rounded down), which κ is within 0.2 % of


def test_a_forged_sup_flow_kappa_below_the_observed_overshoot_fails_on_trajectories():
    """κ = 2.2 for case (b), where trajectories reach ≈ 2.39: the verifier refuses it, and so do the trajectories."""
    forged = dataclasses.replace(_sup_flow("b"), overshoot_bound="2.2")
    assert not verify_sup_flow(forged).proved
    with pytest.raises(UnprovedCertificateError, match="does not verify"):
        crosscheck([forged], trajectories=5, progress=False)
    report = crosscheck([forged], trajectories=N_SMALL, seed=6, progress=False, require_proved=False)
    (check,) = report.checks
    assert not report.passed and [r.id for r in check.results if not r.passed] == ["prop1.stability"]
    assert _result(check, "prop1.stability").counterexample.values["observed_ratio"] > 2.2


def test_sup_flow_claims_carry_no_constant_of_the_paper():
    claims = Claims.from_certificate(_sup_flow("a"), label="s")
    assert claims.template == "sup-flow/v2" and claims.kappa == pytest.approx(1.37852)
    assert math.isnan(claims.c1) and claims.exact["c2"] == str(_sup_flow("a").constants["c2"])


def test_the_cli_reports_the_template_in_json(tmp_path, capsys):
    from symbolic_friction._cli.main import main

    argv = ["crosscheck", str(PROOFS / "sup_flow" / "case_a.json"), "--trajectories", "20", "--no-adversarial", "--json",
            "--out", str(tmp_path)]
    assert main(argv) == 0
    (cert,) = json.loads(capsys.readouterr().out)["certificates"]
    assert cert["template"] == "sup-flow" and cert["verdict"] == "passed"
