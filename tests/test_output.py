"""Output helpers: tables fit the width, ASCII fallback never crashes, verbosity levels."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from symbolic_friction._infra.output import _ascii_replace, emit, format_table, set_verbosity

REPO = Path(__file__).resolve().parents[1]


def test_table_fits_the_width_and_keeps_short_columns_whole():
    rows = [("lemma3.hatV_derivative", "x" * 200, "holds")]
    text = format_table("T", ("id", "statement", "status"), rows, width=80)
    assert all(len(line) <= 80 for line in text.splitlines())
    assert "lemma3.hatV_derivative" in text and "holds" in text and "…" in text


def test_table_is_unchanged_when_it_fits():
    text = format_table("T", ("a", "b"), [("1", "2")], width=80)
    assert text.splitlines()[1:] == ["a  b", "-  -", "1  2"]


def test_ascii_replacement():
    err = UnicodeEncodeError("ascii", "κ ≤ 𝒜 ٣", 0, 7, "x")
    assert _ascii_replace(err) == ("kappa <= A ?", 7)


def test_verbosity_levels(capsys):
    try:
        set_verbosity(0)
        emit("normal")
        emit("verdict", level=0)
        set_verbosity(2)
        emit("detail", level=2)
    finally:
        set_verbosity(1)
    assert capsys.readouterr().out == "verdict\ndetail\n"


def _cli(args, **env):
    full = dict(os.environ, PYTHONPATH=str(REPO), **env)
    return subprocess.run([sys.executable, "-m", "symbolic_friction", *args], capture_output=True, cwd=REPO, env=full, timeout=300)


def test_ascii_stdout_prints_a_verdict_without_crashing():
    proc = _cli(["verify", "-v", "proofs/case_a_tightest.json"], PYTHONIOENCODING="ascii")
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout.decode("ascii")  # pure ASCII
    assert "PROVED" in out and "<= 3.46703*|x(0)|_A" in out and "] >= 0 (all 7 principal minors >= 0" in out


def test_columns_is_honoured_by_check_tables():
    proc = _cli(["check", "--only", "lemma2"], COLUMNS="90")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.decode().splitlines()
    assert max(len(line) for line in lines) <= 90
    assert any(line.startswith("lemma2.dVdt") for line in lines)
