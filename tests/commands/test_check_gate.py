"""`check`'s gate: any FAILED or NOT PROVED line means a non-zero exit, and the self-check section fails `check`
when the verifier it checks is broken."""

from __future__ import annotations

import json

import pytest

from symbolic_friction._cli import check
from symbolic_friction._cli._sections import Section, gate
from symbolic_friction._cli.main import main


def _only(monkeypatch, *makers):
    monkeypatch.setattr(check, "SECTIONS", list(makers))


def _passing(note):
    def make(args):
        return Section("forged", ("x",), [("fine",)], {"forged": True}, True, [note], summary="forged: all fine")
    return make


@pytest.mark.parametrize("line", ["FAILED something", "NOT PROVED proofs/x.json: krawczyk fail(s)", "STALE proofs/x.json",
                                  "  FAILS lemma2.P: …", "cross-check (a) c1: NOT CAUGHT"])
def test_a_failure_line_in_a_section_that_says_ok_is_a_failure(monkeypatch, tmp_path, capsys, line):
    _only(monkeypatch, _passing(line))
    assert main(["check", "--proofs", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert out.strip().splitlines()[-1].startswith("check: FAILED") and "it reported success but printed" in out


def test_the_gate_also_reads_table_rows_and_json_agrees(monkeypatch, tmp_path, capsys):
    def make(args):
        return Section("forged", ("file", "verdict"), [("a.json", "NOT PROVED")], {}, True, [], summary="forged")

    _only(monkeypatch, make)
    assert main(["check", "--json", "--proofs", str(tmp_path)]) == 1
    assert json.loads(capsys.readouterr().out)["passed"] is False


def test_a_clean_section_passes(monkeypatch, tmp_path):
    _only(monkeypatch, _passing("3 of 3 things hold"))
    assert main(["check", "--proofs", str(tmp_path)]) == 0
    section = gate(Section("s", (), [("proved", "ok")], {}, True, ["all proved"]))
    assert section.ok and section.notes == ["all proved"]


def test_the_gate_never_turns_a_failure_into_a_pass():
    section = gate(Section("s", (), [], {}, False, ["nothing marked"]))
    assert not section.ok


def test_check_runs_the_self_check_and_passes_on_this_install(monkeypatch, tmp_path, capsys):
    _only(monkeypatch, check.self_check_section)
    assert check.self_check_section in check.SECTIONS
    assert main(["check", "--proofs", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "false certificates refused naming their premise" in out and "rigour cases (hunting proof, decision procedures) decided right" in out


def test_check_fails_when_the_verifier_accepts_a_false_certificate(monkeypatch, tmp_path, capsys):
    from symbolic_friction._certify import verify as verify_module

    real = verify_module.premises
    monkeypatch.setattr(verify_module, "premises", lambda cert: [p for p in real(cert) if p.name != "c1_hat ≤ k2/2"])
    _only(monkeypatch, check.self_check_section)
    assert main(["check", "--proofs", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert "FAILED self-check stability_c1_hat_k2.json: breaks c1_hat ≤ k2/2" in out


def test_check_fails_when_a_hunting_decision_is_weakened(monkeypatch, tmp_path, capsys):
    from symbolic_friction._certify import hunting_proof

    monkeypatch.setattr(hunting_proof, "_sticks", lambda phi, f_s: bool(phi >= -f_s) and bool(phi <= f_s))
    _only(monkeypatch, check.self_check_section)
    assert main(["check", "--proofs", str(tmp_path)]) == 1
    assert "FAILED self-check stick: φ = f_s exactly: expected slips, got sticks" in capsys.readouterr().out
