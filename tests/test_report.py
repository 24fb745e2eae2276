"""``proofs/obligations.md`` rendering and the atomic write (symbolic_friction._obligations._report)."""

import os
from types import SimpleNamespace

import pytest

from symbolic_friction._obligations._report import REPORT_NAME, render_report, report_path, write_atomic


def _result(ident, status="holds", reason="", details=(("A", "x^2"),), seconds=1.0):
    return SimpleNamespace(
        id=ident, paper="eq. (a|b)", statement="|x| ≥ 0", method="sympy identity",
        status=status, reason=reason, details=details, seconds=seconds,
    )


def test_render_is_deterministic_and_ignores_timings():
    a = render_report([_result("x.one", seconds=1.0)], [])
    b = render_report([_result("x.one", seconds=9.5)], [])
    assert a == b
    assert a.endswith("\n") and not a.endswith("\n\n")


def test_render_shows_every_field_and_latex_blocks():
    err = SimpleNamespace(where="Appendix", paper_says="V = v²", correct="V = σ²", checked_by="x.two")
    text = render_report([_result("x.one"), _result("x.two", "fails", "residual 1")], [err])
    assert "**1 of 2 obligations hold.**" in text
    assert "| 1 | [`x.one`](#ob-1-x-one) | eq. (a\\|b) | holds |" in text  # pipes escaped in the table
    assert "## 2. `x.two` — fails" in text and "- **Result:** fails — residual 1" in text
    assert "$$\nA :\\quad x^2\n$$" in text
    assert "1. **Appendix.** The paper says: V = v². Correct: V = σ². Checked by: `x.two`." in text


def test_render_without_errata():
    assert "None recorded." in render_report([_result("x.one")], [])


def test_report_path():
    assert report_path("proofs").name == REPORT_NAME == "obligations.md"


def test_write_atomic_replaces_the_file(tmp_path):
    target = tmp_path / "obligations.md"
    write_atomic(target, "first\n")
    write_atomic(target, "second ✓\n")
    assert target.read_bytes() == "second ✓\n".encode("utf-8")
    assert os.listdir(tmp_path) == ["obligations.md"]


def test_write_atomic_leaves_the_old_file_when_replacing_fails(tmp_path, monkeypatch):
    target = tmp_path / "obligations.md"
    target.write_text("old\n", encoding="utf-8")

    def broken_replace(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", broken_replace)
    with pytest.raises(OSError, match="disk full"):
        write_atomic(target, "new\n")
    assert target.read_text(encoding="utf-8") == "old\n"
    assert os.listdir(tmp_path) == ["obligations.md"]  # the temp file was removed
