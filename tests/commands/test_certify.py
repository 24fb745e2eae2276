"""``symbolic-friction certify``."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from symbolic_friction._certify import TABLE_I_FILES, default_stem, load, verify_file
from symbolic_friction import Parameters
from symbolic_friction._cli.main import main

REPO = Path(__file__).resolve().parents[2]


def test_no_arguments_regenerates_table_i_in_both_modes(tmp_path, capsys):
    assert main(["certify", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 4 and all(line.startswith("wrote ") for line in out)
    assert "case_a_tightest.json and case_a_tightest.md (tightest) for k_p=3, k_i=4, k_v=32/5, f_c=1: |x(t)|_A <= 3.46703" in out[1]
    for name in TABLE_I_FILES:
        assert verify_file(tmp_path / name).proved
        # identical to the committed proofs/ (the CLI is what generated them)
        assert (tmp_path / name).read_bytes() == (REPO / "proofs" / name).read_bytes()
        md = name.replace(".json", ".md")
        assert (tmp_path / md).read_bytes() == (REPO / "proofs" / md).read_bytes()


def test_mode_restricts_the_table_i_regeneration(tmp_path, capsys):
    assert main(["certify", "--out", str(tmp_path), "--mode", "feasible"]) == 0
    assert sorted(p.name for p in tmp_path.glob("*.json")) == ["case_a_feasible.json", "case_b_feasible.json"]


def test_one_gain_set_from_exact_strings(tmp_path, capsys):
    argv = ["certify", "--k-p", "3", "--k-i", "4", "--k-v", "32/5", "--f-c", "0.5", "--out", str(tmp_path)]
    assert main(argv) == 0
    stem = default_stem(Parameters(k_p=3, k_i=4, k_v="6.4", f_c="0.5"), "tightest")
    cert = load(tmp_path / f"{stem}.json")
    assert (str(cert.k_v), str(cert.f_c)) == ("32/5", "1/2")
    assert (tmp_path / f"{stem}.md").exists()
    assert cert.provenance.mode == "tightest"


def test_one_gain_set_from_physical_parameters_with_name_margin_and_mode(tmp_path, capsys):
    argv = [
        "certify",
        "--m", "2", "--k-p-bar", "6", "--k-i-bar", "8", "--k-d-bar", "12.3", "--alpha-v", "0.5", "--f-c-bar", "2",
        "--mode", "feasible", "--margin", "1/1000", "--name", "mass2", "--out", str(tmp_path),
    ]  # fmt: skip
    assert main(argv) == 0
    # the normalised gains that were certified are printed, with the physical values they came from
    assert "for k_p=3, k_i=4, k_v=32/5, f_c=1 (m=2, k_p_bar=6," in capsys.readouterr().out
    cert = load(tmp_path / "mass2.json")
    params = Parameters.from_physical(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.3", alpha_v="0.5", f_c_bar=2)
    assert (cert.k_p, cert.k_i, cert.k_v, cert.f_c) == (params.k_p, params.k_i, params.k_v, params.f_c)
    assert cert.provenance.mode == "feasible" and str(cert.provenance.margin) == "1/1000"
    assert verify_file(tmp_path / "mass2.json").proved


def test_physical_parameters_without_alpha_v(tmp_path, capsys):
    argv = ["certify", "--m", "1", "--k-p-bar", "3", "--k-i-bar", "4", "--k-d-bar", "6.4", "--f-c-bar", "1"]
    assert main(argv + ["--name", "a", "--out", str(tmp_path)]) == 0
    assert load(tmp_path / "a.json").k_v == Parameters.table_i("a").k_v


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--k-p", "3", "--k-i", "4"], r"certify needs all of --k-p --k-i --k-v --f-c; missing --k-v --f-c"),
        (["--m", "1", "--k-p-bar", "3"], r"missing --k-i-bar --k-d-bar --f-c-bar"),
        (["--k-p", "3", "--m", "1"], r"give either normalised gains .* not both; got --k-p, --m"),
        (["--name", "x"], r"--name applies to one gain set"),
        (["--k-p", "3", "--k-i", "4", "--k-v", "1", "--f-c", "1"], r"Assumption 1 needs k_v·k_p > k_i; got 3 ≤ 4"),
        (["--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "nan"], r"f_c must be finite; got 'nan'"),
        (["--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "0"], r"needs f_c > 0; got f_c = 0"),
        (["--m", "0", "--k-p-bar", "3", "--k-i-bar", "4", "--k-d-bar", "6", "--f-c-bar", "1"], r"needs m > 0; got m = 0"),
        (["--k-p", "x", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], r"k_p must be a decimal such as '6.4'"),
        (["--margin", "2"], r"margin must be in \(0, 1\] \(a relative margin\); got margin = 2"),
    ],
)
def test_bad_input_exits_2_with_a_one_line_message(tmp_path, capsys, argv, message):
    assert main(["certify", "--out", str(tmp_path), *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("symbolic-friction certify: error: ")
    assert len(err.strip().splitlines()) == 1
    assert re.search(message, err), err
    assert list(tmp_path.iterdir()) == []


def test_unknown_mode_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["certify", "--mode", "best"])
    assert exc.value.code == 2


def test_console_script_end_to_end(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "symbolic_friction", "certify", "--k-p", "0.66", "--k-i", "0.08", "--k-v", "1.5",
         "--f-c", "1", "--name", "b", "--out", str(tmp_path)],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    data = json.loads((tmp_path / "b.json").read_text(encoding="utf-8"))
    assert data["parameters"] == {"f_c": "1", "k_i": "2/25", "k_p": "33/50", "k_v": "3/2"}
