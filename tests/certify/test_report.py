"""The Markdown proof report is rendered from what the verifier checked."""

from __future__ import annotations

from dataclasses import replace
from fractions import Fraction as F

from symbolic_friction import Parameters
from symbolic_friction._certify import certify, render_markdown, verify_certificate


def test_report_shows_gains_constants_every_inequality_and_kappa():
    cert = certify(Parameters.table_i("a"), mode="tightest", label="Table I, case (a)")
    report = verify_certificate(cert)
    text = render_markdown(report, name="case_a_tightest.json")
    assert text.startswith("# Stability certificate: Table I, case (a) (tightest)\n")
    assert "**Verdict: PROVED.** All 29 inequalities" in text
    assert f"≤ **{cert.overshoot_bound}**" in text
    assert "| k_v | 32/5 | 6.4 |" in text
    assert "| c | decrease rate, 2(k_v k_p − k_i) | 152/5 | 30.4 |" in text
    for check in report.checks:
        assert f"- ✓ `{check.name}` ({check.obligation}): {check.instance}" in text
    for heading in ("### Lemma 2", "### Lemma 3", "### Proposition 1", "## Provenance"):
        assert heading in text
    assert "symbolic-friction verify case_a_tightest.json" in text
    assert text.endswith("\n") and not text.endswith("\n\n")
    # every table row has the same number of cells (no stray '|' from |σ||v|)
    rows = [line for line in text.splitlines() if line.startswith("| k3 ")]
    assert rows and rows[0].replace("\\|", "").count("|") == 5


def test_report_of_a_failing_certificate_marks_the_failure():
    cert = certify(Parameters.table_i("b"), mode="feasible")
    bad = replace(cert, k3=F(1), provenance=None)
    text = render_markdown(verify_certificate(bad))
    assert "**Verdict: NOT PROVED.**" in text
    assert "- ✗ **fails** `k3 > k2` (lemma3.hatV_derivative): 1 > 2" in text
    assert "## Provenance" not in text
    assert text.startswith("# Stability certificate\n")
