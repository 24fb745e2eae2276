"""Per-certificate outcomes: verdicts and tightness."""

from __future__ import annotations

from symbolic_friction._crosscheck._outcome import search_mode


def test_search_modes():
    assert search_mode("sphere r=1f_c") == "random spheres" and search_mode("adversarial x") == "adversarial"
    assert search_mode("grid 5") == "grid" and search_mode("origin") == "special"


def test_verdicts(paper_report):
    for check in paper_report.checks:
        assert check.verdict == "passed" and check.complete
        assert check.tightness["all"] == max(check.max_overshoot.values()) / check.claims.kappa


def test_repr_is_the_verdict_line(paper_report):
    text = repr(paper_report)
    assert text == f"CrosscheckReport({paper_report.summary()})" and "\n" not in text and len(text) < 300
