"""``symbolic-friction verify FILE…``: exit 0 proved, 1 failed inequality, 2 malformed."""

from __future__ import annotations

import json
import subprocess
import sys
from fractions import Fraction as F
from pathlib import Path

import pytest

from symbolic_friction._certify import TABLE_I_FILES
from symbolic_friction._cli.main import main

REPO = Path(__file__).resolve().parents[2]
PROOFS = REPO / "proofs"


def _case_a() -> dict:
    return json.loads((PROOFS / "case_a_tightest.json").read_text(encoding="utf-8"))


def _write(tmp_path: Path, data, name: str = "bad.json") -> str:
    path = tmp_path / name
    path.write_text(data if isinstance(data, str) else json.dumps(data, indent=2), encoding="utf-8")
    return str(path)


def test_committed_proofs_verify(capsys):
    assert main(["verify", *(str(PROOFS / name) for name in TABLE_I_FILES)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 4 and all(line.startswith("PROVED ") for line in out)


def test_verbose_prints_every_inequality(capsys):
    assert main(["verify", "-v", str(PROOFS / "case_b_tightest.json")]) == 0
    out = capsys.readouterr().out
    assert "  ✓ k3 > k2: " in out and "[lemma3.hatV_derivative]" in out
    assert out.count("  ✓ ") == 29  # 27 inequalities of the proof, 2 provenance checks (obligations, Table I label)


# -- failed inequalities: exit 1, the message names the inequality -----------------------
def test_k3_nudged_below_k2(tmp_path, capsys):
    data = _case_a()
    data["constants"]["k3"] = "199/100"
    assert main(["verify", _write(tmp_path, data)]) == 1
    assert "k3 > k2: 199/100 > 2 is false" in capsys.readouterr().out


def test_c1_raised_above_lambda_min(tmp_path, capsys):
    data = json.loads((PROOFS / "case_b_tightest.json").read_text(encoding="utf-8"))
    c1 = F(data["constants"]["c1"])
    data["constants"]["c1"] = str(c1 * F(1000001, 1000000))
    assert main(["verify", _write(tmp_path, data)]) == 1
    out = capsys.readouterr().out
    assert out.startswith("FAILED ") and "P − c1·I ⪰ 0:" in out and "is false" in out


def test_c2_hat_lowered_by_one_percent(tmp_path, capsys):
    data = _case_a()
    data["constants"]["c2_hat"] = str(F(data["constants"]["c2_hat"]) * F(99, 100))
    assert main(["verify", _write(tmp_path, data)]) == 1
    out = capsys.readouterr().out
    assert "c2_hat·I − K/2 ⪰ 0:" in out and "is false" in out


def test_c_enlarged_ten_times(tmp_path, capsys):
    data = _case_a()
    data["constants"]["c"] = "304"
    assert main(["verify", _write(tmp_path, data)]) == 1
    assert "c = 2(k_v·k_p − k_i): 304 = 2·(96/5 − 4) = 152/5 is false" in capsys.readouterr().out


# -- a number of the wrong sign is a false claim: exit 1, the premise named (never 2, never a traceback) ------
@pytest.mark.parametrize(("group", "name", "text", "says"), [
    ("parameters", "k_p", "-3", ["k_p > 0: -3 > 0 is false"]),
    ("parameters", "f_c", "0", ["f_c > 0: 0 > 0 is false"]),
    ("constants", "k1", "-2", ["k1 > 0: -2 > 0 is false"]),
    ("constants", "c", "-1/2", ["c > 0: -1/2 > 0 is false"]),
    (None, "overshoot_bound", "-3.7", ["overshoot_bound > 0: -37/10 > 0 is false"]),
    # zero divisors: the sign premise fails, and the premises that would divide by the zero are not evaluated
    ("parameters", "k_i", "0", ["k_i > 0: 0 > 0 is false",
                                "P − c1·I ⪰ 0: not evaluated (P has the entry k_v/k_i, and k_i = 0)"]),
    ("parameters", "k_v", "0", ["k_v·k_p > k_i: 0 > 4 is false",
                                "k3 > (k_i/k_v)·k1: not evaluated (it has k_i/k_v, and k_v = 0)"]),
    ("parameters", "k_v", "-32/5", ["k_v·k_p > k_i: -96/5 > 4 is false"]),
    ("constants", "c1", "0", ["c1 > 0: 0 > 0 is false",
                              "overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat): not evaluated (it divides by c1·c1_hat = 0·"]),
    ("constants", "c1_hat", "0", ["c1_hat > 0: 0 > 0 is false", "overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat): not evaluated"]),
])
def test_a_number_of_the_wrong_sign_fails_naming_the_premise(tmp_path, capsys, group, name, text, says):
    data = _case_a()
    del data["provenance"]  # a Table I label would add its own failure for an edited gain
    (data if group is None else data[group])[name] = text
    path = _write(tmp_path, data)
    assert main(["verify", path]) == 1
    out, err = capsys.readouterr()
    assert out.startswith(f"FAILED {path}: ") and err == "" and all(s in out for s in says), out
    # every output form renders it: --json lists the failures, -v every check, JUnit one failure
    assert main(["verify", "--json", "-v", "--junit-xml", str(tmp_path / "r.xml"), path]) == 1
    payload = json.loads(capsys.readouterr().out)
    assert payload["passed"] is False and payload["files"][0]["status"] == "failed"
    assert "<failure" in (tmp_path / "r.xml").read_text(encoding="utf-8")


def test_everything_zero_is_refused_without_a_crash(tmp_path, capsys):
    data = _case_a()
    del data["provenance"]
    data["parameters"] = {k: "0" for k in data["parameters"]}
    data["constants"] = {k: "0" for k in data["constants"]}
    data["overshoot_bound"] = "0"
    assert main(["verify", _write(tmp_path, data)]) == 1
    out = capsys.readouterr().out
    assert out.startswith("FAILED ") and out.count("not evaluated") == 5 and "Traceback" not in out


# -- malformed files: exit 2 via the CLI's error handling --------------------------------------
@pytest.mark.parametrize(
    ("mutate", "message"),
    [
        (lambda d: d["constants"].__setitem__("k3", 2.0), r"constants.k3 must be a string holding an exact rational.*float 2.0"),
        (lambda d: d["constants"].pop("c1"), r"missing key 'constants.c1'"),
        (lambda d: d.pop("parameters"), r"missing key 'parameters' in certificate"),
        (lambda d: d.__setitem__("schema", "other/v1"), r"unknown schema 'other/v1'"),
        (lambda d: d["parameters"].__setitem__("k_v", "6.4"), r"parameters.k_v must be an exact rational string"),
        (lambda d: d["parameters"].__setitem__("k_p", "-3.0"), r"parameters.k_p must be an exact rational string"),
        (lambda d: d["constants"].__setitem__("k1", "−2"), r"constants.k1 must be an exact rational string"),  # U+2212
        (lambda d: d.__setitem__("overshoot_bound", "+3.7"), r"overshoot_bound must be a plain decimal string"),
        (lambda d: d.__setitem__("overshoot_bound", "-3.7e0"), r"overshoot_bound must be a plain decimal string"),
        (lambda d: d["provenance"].__setitem__("margin", "-1/100"), r"provenance.margin must be positive; got '-1/100'"),
    ],
    ids=["float", "missing-constant", "missing-parameters", "unknown-schema", "decimal", "signed-decimal", "unicode-minus",
         "plus-bound", "exponent-bound", "margin"],
)
def test_malformed_files_exit_2(tmp_path, capsys, mutate, message):
    import re

    data = _case_a()
    mutate(data)
    assert main(["verify", _write(tmp_path, data)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("symbolic-friction verify: error: ") and re.search(message, err), err


def test_non_json_exits_2(tmp_path, capsys):
    assert main(["verify", _write(tmp_path, "certificate: yes\n")]) == 2
    err = capsys.readouterr().err
    assert "bad.json: not valid JSON: Expecting value at line 1, column 1" in err


def test_missing_file_exits_2(tmp_path, capsys):
    assert main(["verify", str(tmp_path / "nope.json")]) == 2
    assert "no such file or directory" in capsys.readouterr().err


def test_every_file_is_checked_and_the_worst_status_wins(tmp_path, capsys):
    bad = _case_a()
    bad["constants"]["k3"] = "1"
    files = [str(PROOFS / "case_a_feasible.json"), _write(tmp_path, bad, "failing.json"), _write(tmp_path, "[", "junk.json")]
    assert main(["verify", *files]) == 2  # malformed beats failed
    captured = capsys.readouterr()
    lines = captured.out.splitlines()
    assert lines[0].startswith("PROVED ") and lines[1].startswith("FAILED ") and lines[2].startswith("MALFORMED ")
    assert main(["verify", *files[:2]]) == 1
    empty = _write(tmp_path, "{}", "empty.json")
    assert main(["verify", files[2], empty]) == 2
    captured = capsys.readouterr()
    assert f"2 of 2 files are missing or malformed (reasons above): {files[2]}, {empty}" in captured.err


def test_each_error_is_printed_once(tmp_path, capsys):
    # a lone file: its reason is the error line and nothing else
    junk = _write(tmp_path, "[", "junk.json")
    assert main(["verify", junk]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and (captured.out + captured.err).count("not valid JSON") == 1
    # a listing: the reason on the file's line, the closing error names the file only
    assert main(["verify", str(PROOFS / "case_a_feasible.json"), junk]) == 2
    captured = capsys.readouterr()
    assert (captured.out + captured.err).count("not valid JSON") == 1
    assert "MALFORMED" in captured.out and "1 of 2 files are missing or malformed" in captured.err


def test_console_script_exit_codes(tmp_path):
    bad = _case_a()
    bad["constants"]["k3"] = "1"
    path = _write(tmp_path, bad)
    run = lambda *args: subprocess.run([sys.executable, "-m", "symbolic_friction", "verify", *args], capture_output=True, text=True)  # noqa: E731
    assert run(str(PROOFS / "case_a_tightest.json")).returncode == 0
    failed = run(path)
    assert failed.returncode == 1 and "k3 > k2: 1 > 2 is false" in failed.stdout
    assert run(_write(tmp_path, "nope", "x.json")).returncode == 2


def test_verify_imports_no_solver_and_no_sympy():
    code = (
        "import sys\n"
        "from symbolic_friction._cli.main import main\n"
        f"rc = main(['verify', {str(PROOFS / 'case_a_tightest.json')!r}])\n"
        "print(rc, sorted(m for m in ('cvxpy', 'clarabel', 'sympy', 'scipy') if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "0 []"
