"""Tables and counterexample files of a cross-check run."""

from __future__ import annotations

import json
import math
import pytest

from symbolic_friction._crosscheck import PROPERTIES
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck import crosscheck
from symbolic_friction._crosscheck import format_report
from symbolic_friction._crosscheck import write_counterexamples
from tests.crosscheck.helpers import _cert


def test_report_text_names_every_property(paper_report):
    text = format_report(paper_report)
    for p in PROPERTIES:
        assert p.id in text
    assert "PASSED" in text and "tightness ratio" in text and "rtol = 1e-08" in text


def test_counterexample_files(wrong_report, tmp_path):
    case, wrong, checks, report = wrong_report
    files = write_counterexamples(report, tmp_path)
    assert len(files) == 4
    for path in files:
        data = json.loads(path.read_text(encoding="utf-8"))
        assert data["counterexamples"]
        for cx in data["counterexamples"]:
            assert {"property", "z0", "x0", "t", "values", "relative_slack"} <= set(cx)
            assert cx["relative_slack"] < -report.rtol
    assert not list(tmp_path.glob(".*.tmp"))  # atomic writes leave no temporary file


def test_report_is_json_safe(paper_report):
    # counterexample values are plain numbers (no NaN/inf leak into files)
    for check in paper_report.checks:
        for r in check.results:
            assert math.isfinite(r.worst_margin) or r.samples == 0
