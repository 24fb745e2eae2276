"""``check --smt`` and the SMT-LIB files under ``proofs/smt/`` (:mod:`symbolic_friction._cli._smt`).

The command's side of the SMT pass: a planted false obligation makes ``check --smt`` fail with the solver's
model, true ones are confirmed, ``--write`` writes the files and a missing or edited one is ``STALE``, and a
missing solver or a bad time limit is a one-line usage error (exit 2).  The library is tested in
``tests/obligations/test_smt.py``.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

pytest.importorskip("z3")

import symbolic_friction._obligations as obligations
from symbolic_friction._cli import check
from symbolic_friction._cli.main import main
from symbolic_friction._obligations import _smt
from tests.obligations.test_smt import PlantedFalse, _obligation, _rational, _value_at

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def only(monkeypatch):
    """``check`` with just the obligations section (and the SMT one) over the given obligations."""

    def use(*obs):
        monkeypatch.setattr(check, "SECTIONS", [check.obligations_section])
        monkeypatch.setattr(obligations, "all_obligations", lambda: list(obs))
        monkeypatch.setattr(obligations, "all_errata", lambda: [])

    return use


def test_true_obligations_are_confirmed_and_their_files_written_then_compared(only, tmp_path, capsys):
    only(_obligation("lemma2.P"), _obligation("assumption1.encoding"))
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0
    assert not (tmp_path / "smt").exists()  # a project opts in: plain --write exports nothing ...
    assert main(["check", "--write", "--smt", "--proofs", str(tmp_path)]) == 0  # ... --write --smt creates it
    assert sorted(p.name for p in (tmp_path / "smt").iterdir()) == ["assumption1.encoding.smt2", "lemma2.P.smt2"]
    for name in ("assumption1.encoding.smt2", "lemma2.P.smt2"):  # the same bytes as the committed files
        assert (tmp_path / "smt" / name).read_bytes() == (REPO / "proofs" / "smt" / name).read_bytes()
    capsys.readouterr()
    assert main(["check", "--smt", "--proofs", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "confirmed 2 of 2 polynomial obligations (100 %)" in out and "files up to date" in out
    assert "check: PASSED" in out.splitlines()[-1]


def test_a_planted_false_obligation_fails_check_smt_with_its_model(only, tmp_path, capsys):
    only(_obligation("lemma2.P"), PlantedFalse())
    (tmp_path / "smt").mkdir()
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0  # the package's own check is fooled
    capsys.readouterr()
    assert main(["check", "--smt", "--json", "--proofs", str(tmp_path)]) == 1
    captured = capsys.readouterr()
    payload = json.loads(captured.out)
    row = next(o for o in payload["smt"]["outcomes"] if o["id"] == "planted.false")
    assert row["status"] == "counterexample" and set(row["model"]) == {"delta", "k_i"}
    assert _value_at(PlantedFalse().derive(), row["model"]) < 0  # the model refutes the claim, exactly
    assert all(_rational(v) > 0 for v in row["model"].values())
    assert payload["counts"]["smt_counterexamples"] == 1 and payload["passed"] is False
    assert "FAILED smt planted.false: counterexample" in captured.err


@pytest.mark.parametrize("edit", ["missing", "edited", "extra"])
def test_a_missing_edited_or_extra_file_is_stale(only, tmp_path, capsys, edit):
    only(_obligation("lemma2.P"))
    (tmp_path / "smt").mkdir()
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0
    target = tmp_path / "smt" / "lemma2.P.smt2"
    if edit == "missing":
        target.unlink()
    elif edit == "edited":
        target.write_text(target.read_text(encoding="ascii").replace("(> ", "(>= ", 1), encoding="ascii")
    else:
        shutil.copy(target, tmp_path / "smt" / "planted.smt2")
    capsys.readouterr()
    assert main(["check", "--smt", "--proofs", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert "STALE:" in out and {"missing": "is missing", "edited": "is stale", "extra": "is unexpected"}[edit] in out
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0  # --write brings it back
    assert main(["check", "--smt", "--proofs", str(tmp_path)]) == 0


def test_without_smt_the_solver_is_not_run_and_only_write_exports(only, tmp_path, capsys, monkeypatch):
    only(_obligation("lemma2.P"))
    (tmp_path / "smt").mkdir()
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0
    assert (tmp_path / "smt" / "lemma2.P.smt2").is_file()
    monkeypatch.setattr(_smt, "run_smt", lambda *a, **k: pytest.fail("the solver ran without --smt"))
    monkeypatch.setattr(_smt, "export_smt", lambda *a, **k: pytest.fail("exported without --smt or --write"))
    capsys.readouterr()
    assert main(["check", "--proofs", str(tmp_path)]) == 0
    assert "SMT" not in capsys.readouterr().out


def test_no_empty_smt_directory_is_made(only, tmp_path):
    from symbolic_friction._obligations._base import Obligation, Outcome

    class Numeric(Obligation):
        id, paper, statement, method = "fake.numeric", "none", "1 = 1", "=="

        def derive(self):
            return 1

        def verify(self, subject):
            return Outcome(subject == 1)

    only(Numeric())
    assert main(["check", "--write", "--smt", "--proofs", str(tmp_path)]) == 0
    assert not (tmp_path / "smt").exists()


def test_a_missing_solver_is_a_one_line_usage_error(only, tmp_path, capsys, monkeypatch):
    only(_obligation("lemma2.P"))

    def absent(solver="z3"):
        raise ImportError(f"No module named {solver!r}")

    monkeypatch.setattr(_smt, "solver_version", absent)
    assert main(["check", "--smt", "--proofs", str(tmp_path)]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and "Traceback" not in captured.err
    assert captured.err.strip().splitlines() == [captured.err.strip()]
    assert "pip install 'symbolic-friction[smt]'" in captured.err


@pytest.mark.parametrize("option,value", [("--smt-timeout", "0"), ("--smt-budget", "-1"), ("--smt-timeout", "1e9"),
                                          ("--smt-budget", "nan")])
def test_a_bad_time_limit_is_a_usage_error(tmp_path, capsys, option, value):
    assert main(["check", "--smt", option, value, "--proofs", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert option in err and "Traceback" not in err


def test_cvc5_decides_the_same_obligation(only, tmp_path, capsys):
    pytest.importorskip("cvc5")
    only(_obligation("lemma2.P"))
    assert main(["check", "--write", "--smt", "--proofs", str(tmp_path)]) == 0
    capsys.readouterr()
    assert main(["check", "--smt", "--smt-solver", "cvc5", "--proofs", str(tmp_path)]) == 0
    assert "cvc5" in capsys.readouterr().out
