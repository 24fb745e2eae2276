"""The files ``crosscheck`` checks by default: the paper's and the quadratic template, every other one named with its reason."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from symbolic_friction._crosscheck._files import SKIPPED, default_certificate_files, default_certificate_selection

PROOFS = Path(__file__).resolve().parents[2] / "proofs"


def test_other_templates_are_named_with_their_reason(tmp_path, monkeypatch):
    proofs = tmp_path / "proofs"
    proofs.mkdir()
    for name in ("case_a_tightest.json", "box_physical.json", "hunting/case_a_fs1.2.json", "quadratic/case_a.json"):
        shutil.copy(PROOFS / name, proofs / Path(name).name.replace("case_a.json", "quadratic_a.json").replace("case_a_fs1.2", "hunting_a"))
    monkeypatch.chdir(tmp_path)
    files, skipped = default_certificate_selection()
    assert files == ["proofs/case_a_tightest.json", "proofs/quadratic_a.json"]
    reasons = dict(skipped)
    assert set(reasons) == {"proofs/box_physical.json", "proofs/hunting_a.json"}
    assert reasons["proofs/hunting_a.json"] == SKIPPED["hunting-cycle/v1"]
    assert reasons["proofs/box_physical.json"] == SKIPPED["lyapunov-box/v1"]
    assert default_certificate_files() == files


def test_files_under_proofs_are_found_in_subdirectories(tmp_path, monkeypatch):
    (tmp_path / "proofs" / "quadratic").mkdir(parents=True)
    shutil.copy(PROOFS / "quadratic" / "case_b.json", tmp_path / "proofs" / "quadratic" / "case_b.json")
    monkeypatch.chdir(tmp_path)
    assert default_certificate_selection() == (["proofs/quadratic/case_b.json"], [])


def test_nothing_left_is_an_error(tmp_path, monkeypatch):
    (tmp_path / "proofs").mkdir()
    shutil.copy(PROOFS / "box_physical.json", tmp_path / "proofs" / "b.json")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FileNotFoundError, match="skipped 1 of another template"):
        default_certificate_selection()
