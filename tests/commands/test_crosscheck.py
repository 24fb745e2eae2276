"""``symbolic-friction crosscheck``: exit 0 passed, 1 violated (with counterexample files), 2 bad input."""

from __future__ import annotations

import io
import json
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import pytest

from symbolic_friction._cli.main import main
from tests.computed_once import computed_once

REPO = Path(__file__).resolve().parents[2]
PROOFS = REPO / "proofs"
FAST = ["--trajectories", "60", "--no-adversarial", "--samples", "101"]


@pytest.fixture(scope="module", autouse=True)
def shared_kappa_lin_lower():
    """The proven lower end of κ_lin computed once per gains in this module (about 0.1-0.2 s each).

    The tightness table of every report gives it per certificate, and the runs here cross-check Table I's gains fifteen times.  It is a pure function of the parameters (a float search for the
    peak time, then an arb enclosure at the precision it sets and restores), so a later call with equal parameters
    gets the first call's value; a call that raises is not kept.
    """
    from symbolic_friction._certify import flow_bound

    with computed_once(flow_bound, "kappa_lin_lower"):
        yield


def _case(case: str = "a", mode: str = "tightest") -> dict:
    return json.loads((PROOFS / f"case_{case}_{mode}.json").read_text(encoding="utf-8"))


def _write(tmp_path: Path, data: dict, name: str) -> str:
    path = tmp_path / name
    path.write_text(json.dumps(data, indent=2), encoding="utf-8")
    return str(path)


def test_paper_certificates_pass(capsys):
    files = [str(PROOFS / f"case_{c}_tightest.json") for c in "ab"]
    assert main(["crosscheck", *files, *FAST]) == 0
    out = capsys.readouterr().out
    last = out.strip().splitlines()[-1]
    assert last.startswith("crosscheck: PASSED — 2 certificate(s), 120 trajectories (0 incomplete)")
    assert "proved exactly before the cross-check" in out
    for pid in ("lemma2.decrease", "lemma3.hatV_nonincreasing", "prop1.stability", "remark.stick_sigma"):
        assert pid in out
    assert "traj" in out and "checked" in out and "margin" in out and "fail" in out
    assert "tightness ratio" in out
    assert "rtol = 1e-08" in out and "1e-14" in out  # the tolerance and its justification


def test_default_is_every_committed_certificate(monkeypatch, capsys):
    monkeypatch.chdir(REPO)
    assert main(["crosscheck", "--trajectories", "30", "--no-adversarial", "--samples", "51"]) == 0
    out = capsys.readouterr().out
    assert "crosscheck: PASSED — 8 certificate(s)" in out.strip().splitlines()[-1]
    for stem in ("case_a_feasible", "case_a_tightest", "case_b_feasible", "case_b_tightest", "sup_flow/case_a", "quadratic/case_a",
                 "quadratic/case_b"):
        assert stem in out
    # the tightness of each committed certificate, per template
    table = out[out.index("tightness per certificate"):].splitlines()
    assert [row.split()[:2] for row in table[2:10]] == [  # by gain set: the certificates sharing trajectories
        ["case_a_feasible", "paper"], ["case_a_tightest", "paper"], ["quadratic/case_a", "quadratic"],
        ["sup_flow/case_a", "sup-flow"],
        ["case_b_feasible", "paper"], ["case_b_tightest", "paper"], ["quadratic/case_b", "quadratic"],
        ["sup_flow/case_b", "sup-flow"]]


def test_unproved_certificate_is_refused_with_the_inequality_named(tmp_path, capsys):
    data = _case("a")
    c = Fraction(data["constants"]["c"])
    data["constants"]["c"] = str(10 * c).replace(" ", "")  # 10 × 2(k_v k_p - k_i): the verifier rejects it
    path = _write(tmp_path, data, "wrong_c.json")
    out_dir = tmp_path / "cx"
    assert main(["crosscheck", path, *FAST, "--out", str(out_dir)]) == 1
    captured = capsys.readouterr()
    lines = captured.out.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in captured.err
    assert lines[0].startswith(f"crosscheck: REFUSED — {path} does not verify")
    assert "c = 2(k_v·k_p − k_i): 304 = 2·(96/5 − 4) = 152/5 is false" in lines[0]
    assert not out_dir.exists()


def test_edited_overshoot_bound_is_refused(tmp_path, capsys):
    data = _case("a")
    data["overshoot_bound"] = "3.2"  # below √(c₂ĉ₂/(c₁ĉ₁)) ≈ 3.4670: verify rejects it
    path = _write(tmp_path, data, "forged.json")
    assert main(["crosscheck", path, *FAST]) == 1
    line = capsys.readouterr().out.strip()
    assert line.startswith("crosscheck: REFUSED") and "overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat)" in line


def test_event_limit_makes_the_run_incomplete_not_passed(capsys):
    assert main(["crosscheck", str(PROOFS / "case_a_tightest.json"), *FAST, "--max-events", "3"]) == 1
    out = capsys.readouterr().out
    assert "INCOMPLETE:" in out and "nothing was checked on their unsimulated part" in out
    last = out.strip().splitlines()[-1]
    assert last.startswith("crosscheck: INCOMPLETE — 1 certificate(s), 60 trajectories (")
    import re

    incomplete = int(re.search(r"trajectories \((\d+) incomplete\)", last).group(1))
    assert 0 < incomplete <= 60


def test_no_certificate_found(monkeypatch, tmp_path, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["crosscheck"]) == 2
    assert "no certificate given and no proofs/*.json" in capsys.readouterr().err


def test_skipped_files_are_named_with_the_reason(monkeypatch, tmp_path, capsys):
    import shutil

    (tmp_path / "proofs").mkdir()
    shutil.copy(PROOFS / "case_a_feasible.json", tmp_path / "proofs")
    shutil.copy(PROOFS / "hunting" / "case_a_fs1.2.json", tmp_path / "proofs" / "hunt.json")
    shutil.copy(PROOFS / "box_physical.json", tmp_path / "proofs" / "box.json")
    monkeypatch.chdir(tmp_path)
    assert main(["crosscheck", "--trajectories", "4", "--no-adversarial", "--samples", "11"]) == 0
    out = capsys.readouterr().out
    assert "skipped proofs/hunt.json: a hunting certificate: it proves a cycle of the stiction model" in out
    assert "skipped proofs/box.json: a box certificate: it proves a box of gain sets at its corners" in out
    assert main(["crosscheck", "--trajectories", "4", "--no-adversarial", "--samples", "11", "--json"]) == 0
    skipped = json.loads(capsys.readouterr().out)["skipped"]
    assert [s["file"] for s in skipped] == ["proofs/box.json", "proofs/hunt.json"] and "stiction" in skipped[1]["reason"]
    (tmp_path / "proofs" / "case_a_feasible.json").unlink()
    assert main(["crosscheck"]) == 2
    assert "(skipped 2 of another template)" in capsys.readouterr().err


def test_malformed_certificate(tmp_path, capsys):
    path = tmp_path / "bad.json"
    path.write_text("{not json", encoding="utf-8")
    assert main(["crosscheck", str(path), *FAST]) == 2
    assert "not valid JSON" in capsys.readouterr().err


@pytest.mark.parametrize(
    "option, value, message",
    [("--rtol", "2", "--rtol must lie in (0, 1); got '2'"), ("--theta", "1.5", "--theta must lie in (0, 1]; got '1.5'")],
)
def test_option_ranges(option, value, message, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["crosscheck", str(PROOFS / "case_a_tightest.json"), option, value])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


@pytest.mark.parametrize(
    "option, value, message",
    [
        ("--trajectories", "0", "--trajectories must be an integer from 1 to 1000000 (a bound on time and memory); got '0'"),
        ("--trajectories", "many", "--trajectories must be an integer from 1 to 1000000 (ASCII digits); got 'many'"),
        ("--trajectories", "٣", "(ASCII digits); got '٣'"),
        ("--horizon", "-3", "--horizon must lie in (0, 1e+06]; got '-3'"),
        ("--horizon", "soon", "--horizon must be a decimal such as '6.4' or a fraction such as '32/5'; got 'soon'"),
        ("--horizon", "1e999", "--horizon must lie in (0, 1e+06]; got '1e999'"),
    ],
)
def test_argument_types(option, value, message, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["crosscheck", option, value])
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


def test_decay_option(capsys):
    assert main(["crosscheck", str(PROOFS / "case_a_tightest.json"), *FAST, "--decay"]) == 0
    assert "decay of |x(t)|_A" in capsys.readouterr().out


def test_iss_table_in_report():
    from symbolic_friction import Parameters
    from symbolic_friction._crosscheck import crosscheck, format_report, iss_gain

    report = crosscheck([PROOFS / "case_a_tightest.json"], trajectories=20, adversarial=False, samples=51)
    est = iss_gain(Parameters.table_i("a"), ("0", "0.1"), horizon=10.0, h=1e-2)
    text = format_report(type(report)(**{**report.__dict__, "iss": {"case_a_tightest": est}}))
    assert "empirical ISS gain" in text and "greedy" in text and "stribeck" in text
    assert "worst case" not in text.lower()
    # the worst found over selections, and a search that a Stribeck law beats, said so
    import dataclasses

    from symbolic_friction._crosscheck import WorstFound

    found = {0.1: WorstFound(rho=0.1, bound=0.3, law="greedy", initial_state=(0.0, 0.5, 0.0), stribeck={"0.1": 0.04}),
             1.0: WorstFound(rho=1.0, bound=0.2, law="greedy", initial_state=(0.0, 0.5, 0.0), stribeck={"0.1": 0.33})}
    est = dataclasses.replace(est, worst_found=found)
    text = format_report(type(report)(**{**report.__dict__, "iss": {"case_a_tightest": est}}))
    assert "rho = 0.1: worst found 0.3" in text
    assert text.count("SEARCH NOT DONE") == 1


def test_progress_bar_when_enabled(monkeypatch):
    from symbolic_friction._crosscheck import crosscheck

    err = io.StringIO()
    monkeypatch.setattr(sys, "stderr", err)
    crosscheck([PROOFS / "case_a_tightest.json"], trajectories=20, adversarial=False, samples=51, progress=True)
    assert "crosscheck" in err.getvalue() and "20/20" in err.getvalue()


def test_command_module_imports_only_the_standard_library():
    code = (
        "import sys\n"
        "import symbolic_friction._cli.crosscheck\n"
        "print(sorted(m for m in ('numpy', 'scipy', 'sympy', 'matplotlib', 'cvxpy') if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
