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
