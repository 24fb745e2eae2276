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


def test_no_arguments_regenerates_table_i_in_both_modes_and_every_template(tmp_path, capsys):
    assert main(["certify", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 8 and all(line.startswith("wrote ") for line in out)
    assert "case_a_tightest.json and case_a_tightest.md (tightest) for k_p=3, k_i=4, k_v=32/5, f_c=1: |x(t)|_A <= 3.46703" in out[1]
    assert "quadratic/case_a.json (quadratic template) for k_p=3, k_i=4, k_v=32/5, f_c=1: |x(t)|_A <= 1.80833" in out[4]
    assert "sup_flow/case_a.json (sup-flow template) for k_p=3, k_i=4, k_v=32/5, f_c=1: |x(t)|_A <= 1.37852" in out[6]
    for directory in ("quadratic", "sup_flow"):  # what `check` verifies under proofs/quadratic/ and proofs/sup_flow/
        for name in ("case_a.json", "case_b.json"):
            assert (tmp_path / directory / name).read_bytes() == (REPO / "proofs" / directory / name).read_bytes()
    for name in TABLE_I_FILES:
        assert verify_file(tmp_path / name).proved
        # identical to the committed proofs/ (the CLI is what generated them)
        assert (tmp_path / name).read_bytes() == (REPO / "proofs" / name).read_bytes()
        md = name.replace(".json", ".md")
        assert (tmp_path / md).read_bytes() == (REPO / "proofs" / md).read_bytes()


def test_mode_restricts_the_table_i_regeneration(tmp_path, capsys):
    assert main(["certify", "--out", str(tmp_path), "--mode", "feasible"]) == 0
    # --mode is the paper's template's: the quadratic files are not written
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.json")) == [
        "case_a_feasible.json", "case_b_feasible.json"]


def test_one_gain_set_from_exact_strings(tmp_path, capsys):
    argv = ["certify", "--k-p", "3", "--k-i", "4", "--k-v", "32/5", "--f-c", "0.5", "--template", "paper",
            "--out", str(tmp_path)]
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
    argv = ["certify", "--m", "1", "--k-p-bar", "3", "--k-i-bar", "4", "--k-d-bar", "6.4", "--f-c-bar", "1",
            "--template", "paper"]
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


def test_the_sdp_search_is_still_available(tmp_path, capsys):
    argv = ["certify", "--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--search", "sdp", "--name", "s",
            "--out", str(tmp_path), "--json"]
    assert main(argv) == 0
    assert json.loads(capsys.readouterr().out)["search"] == "sdp"
    cert = load(tmp_path / "s.json")
    assert cert.provenance.search == "sdp" and cert.provenance.solver == "CLARABEL" and verify_file(tmp_path / "s.json").proved


def test_a_box_of_gains_is_certified_and_verified(tmp_path, capsys):
    argv = ["certify", "--k-p", "2.7:3.3", "--k-i", "3.6:4.4", "--k-v", "5.76:7.04", "--f-c", "1", "--pieces", "16",
            "--name", "box_case_a_10pct", "--label", "Table I, case (a), every gain within 10 %", "--out", str(tmp_path)]
    assert main(argv) == 0
    assert "(16 piece(s)): |x(t)|_A <= 3.92278·|x(0)|_A for every gain set in the box" in capsys.readouterr().out
    assert (tmp_path / "box_case_a_10pct.json").read_bytes() == (REPO / "proofs" / "box_case_a_10pct.json").read_bytes()
    assert main(["verify", str(tmp_path / "box_case_a_10pct.json"), "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["passed"] and payload["files"][0]["kind"] == "box" and payload["files"][0]["pieces"] == 16


def test_a_physical_box_reproduces_the_committed_file(tmp_path, capsys):
    argv = ["certify", "--m", "1.9:2.1", "--k-p-bar", "5.8:6.2", "--k-i-bar", "7.8:8.2", "--k-d-bar", "12:12.6",
            "--alpha-v", "0.4:0.6", "--f-c-bar", "1.8:2.2", "--pieces", "8", "--name", "box_physical",
            "--label", "a 2 kg axis: mass ±5 %, gains and friction within a few per cent", "--out", str(tmp_path)]
    assert main(argv) == 0
    assert (tmp_path / "box_physical.json").read_bytes() == (REPO / "proofs" / "box_physical.json").read_bytes()


@pytest.mark.parametrize("argv, message", [
    (["--k-p", "0.5:3.3", "--k-i", "3.6:4.4", "--k-v", "5.76:7.04", "--f-c", "1"],
     "the box leaves Assumption 1 at its corner k_p = 1/2, k_i = 22/5, k_v = 144/25: k_v·k_p = 72/25 ≤ k_i = 22/5"),
    (["--k-p", "3:2", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], "--k-p 3:2: an interval LO:HI needs LO ≤ HI"),
    (["--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--pieces", "4"], "--pieces applies to a box"),
    (["--k-p", "2:3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--search", "sdp"], "a box is certified by the closed form only"),
    (["--k-p", "2:3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--pieces", "2", "--kappa-tol", "0.1"], "give --pieces or --kappa-tol, not both"),
])
def test_bad_boxes_exit_2_naming_the_problem(tmp_path, capsys, argv, message):
    assert main(["certify", *argv, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1
    assert list(tmp_path.glob("*.json")) == []
