"""``--json`` on certify, verify, crosscheck and simulate: stdout is one JSON document, and it says what the text says."""

from __future__ import annotations

import json
from pathlib import Path

from symbolic_friction._cli.main import main

REPO = Path(__file__).resolve().parents[2]
PROOFS = REPO / "proofs"


def _json(capsys):
    captured = capsys.readouterr()
    return json.loads(captured.out), captured.err


def test_verify_json_lists_gains_verdict_and_failures(tmp_path, capsys):
    bad = json.loads((PROOFS / "case_a_tightest.json").read_text(encoding="utf-8"))
    bad["constants"]["k3"] = bad["constants"]["k2"]
    (tmp_path / "bad.json").write_text(json.dumps(bad), encoding="utf-8")
    assert main(["verify", "--json", str(PROOFS / "case_b_tightest.json"), str(tmp_path / "bad.json")]) == 1
    payload, _ = _json(capsys)
    good, wrong = payload["files"]
    assert payload["passed"] is False
    assert good["status"] == "proved" and good["gains"] == {"k_p": "33/50", "k_i": "2/25", "k_v": "3/2", "f_c": "1"}
    assert good["label"] == "Table I, case (b)" and good["failures"] == []
    assert wrong["status"] == "failed" and any(f["inequality"] == "k3 > k2" for f in wrong["failures"])


def test_verify_text_prints_the_gains(capsys):
    assert main(["verify", str(PROOFS / "case_a_feasible.json")]) == 0
    assert "[k_p=3, k_i=4, k_v=32/5, f_c=1]" in capsys.readouterr().out


def test_verify_json_on_a_malformed_file_still_exits_2_with_one_line(tmp_path, capsys):
    (tmp_path / "m.json").write_text("{", encoding="utf-8")
    assert main(["verify", "--json", str(tmp_path / "m.json")]) == 2
    payload, err = _json(capsys)
    assert payload["files"][0]["status"] == "malformed" and len(err.strip().splitlines()) == 1


def test_certify_json_keeps_physical_gains_and_label(tmp_path, capsys):
    args = ["certify", "--json", "--mode", "feasible", "--out", str(tmp_path), "--name", "axis", "--label", "x axis",
            "--m", "2", "--k-p-bar", "6", "--k-i-bar", "8", "--k-d-bar", "12.3", "--alpha-v", "0.5", "--f-c-bar", "2"]
    assert main(args) == 0
    payload, _ = _json(capsys)
    assert payload["proved"] is True and payload["label"] == "x axis"
    assert payload["parameters"] == {"k_p": "3", "k_i": "4", "k_v": "32/5", "f_c": "1"}
    assert payload["physical"]["k_d_bar"] == "123/10" and payload["physical"]["alpha_v"] == "1/2"
    assert Path(payload["file"]) == tmp_path / "axis.json"
    on_disk = json.loads((tmp_path / "axis.json").read_text(encoding="utf-8"))
    assert on_disk["physical"] == payload["physical"] and on_disk["provenance"]["label"] == "x axis"
    assert main(["verify", str(tmp_path / "axis.json")]) == 0  # the physical parameters normalise to the gains


def test_verify_refuses_physical_parameters_that_do_not_normalise(tmp_path, capsys):
    data = json.loads((PROOFS / "case_a_feasible.json").read_text(encoding="utf-8"))
    data["provenance"]["label"] = ""
    data["physical"] = {"m": "2", "k_p_bar": "6", "k_i_bar": "8", "k_d_bar": "12", "alpha_v": "0", "f_c_bar": "2"}
    (tmp_path / "p.json").write_text(json.dumps(data), encoding="utf-8")
    assert main(["verify", str(tmp_path / "p.json")]) == 1
    assert "k_v = (k_d_bar + alpha_v)/m: 32/5 = 6 is false" in capsys.readouterr().out


def test_verify_refuses_a_table_i_label_on_other_gains(tmp_path, capsys):
    data = json.loads((PROOFS / "case_a_feasible.json").read_text(encoding="utf-8"))
    data["provenance"]["label"] = "Table I, case (b)"
    (tmp_path / "l.json").write_text(json.dumps(data), encoding="utf-8")
    assert main(["verify", str(tmp_path / "l.json")]) == 1
    assert "label 'Table I, case (b)' ⇒ Table I, case (b) gains" in capsys.readouterr().out


def test_verify_refuses_listed_obligations_it_does_not_prove(tmp_path, capsys):
    data = json.loads((PROOFS / "case_a_feasible.json").read_text(encoding="utf-8"))
    data["provenance"]["obligations"].append("cor1.iss")
    (tmp_path / "o.json").write_text(json.dumps(data), encoding="utf-8")
    assert main(["verify", str(tmp_path / "o.json")]) == 1
    assert "cor1.iss not instantiated" in capsys.readouterr().out


def test_crosscheck_json(capsys, tmp_path):
    assert main(["crosscheck", "--json", str(PROOFS / "case_a_tightest.json"), "--trajectories", "20", "--samples", "31",
                 "--no-adversarial", "--out", str(tmp_path / "cx")]) == 0
    payload, _ = _json(capsys)
    assert payload["passed"] is True and payload["summary"].startswith("crosscheck: PASSED")
    (cert,) = payload["certificates"]
    assert cert["verdict"] == "passed" and cert["proved"] is True and cert["exact"]["k_v"] == "32/5"
    assert cert["properties"] and all(p["passed"] and p["checked"] > 0 for p in cert["properties"])
    assert not (tmp_path / "cx").exists()  # nothing failed: no counterexample directory left behind


def test_crosscheck_junit(tmp_path, capsys):
    import xml.etree.ElementTree as ET

    report = tmp_path / "x.xml"
    assert main(["crosscheck", str(PROOFS / "case_b_tightest.json"), "--trajectories", "20", "--samples", "31",
                 "--no-adversarial", "--junit-xml", str(report)]) == 0
    cases = list(ET.parse(report).getroot().iter("testcase"))
    assert cases[0].get("classname") == "crosscheck.certificates"
    assert len(cases) > 5 and all(c.find("failure") is None for c in cases)


def test_simulate_json(tmp_path, capsys):
    assert main(["simulate", "paper-a", "--json", "--out", str(tmp_path)]) == 0
    payload, _ = _json(capsys)
    assert payload["scene"] == "paper-a" and len(payload["trajectories"]) == 5
    assert all(Path(f).exists() for f in payload["files"])
    assert payload["trajectories"][0]["events"] > 0


def test_simulate_list_json(capsys):
    assert main(["simulate", "--list", "--json"]) == 0
    payload, _ = _json(capsys)
    assert "paper-a" in payload["scenes"]


def test_verify_junit_has_one_case_per_certificate(tmp_path, capsys):
    import xml.etree.ElementTree as ET

    bad = json.loads((PROOFS / "case_a_tightest.json").read_text(encoding="utf-8"))
    bad["constants"]["k3"] = bad["constants"]["k2"]
    (tmp_path / "bad.json").write_text(json.dumps(bad), encoding="utf-8")
    report = tmp_path / "v.xml"
    assert main(["verify", str(PROOFS / "case_a_feasible.json"), str(tmp_path / "bad.json"),
                 "--junit-xml", str(report)]) == 1
    suite = ET.parse(report).getroot().find("testsuite")
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors")) == ("2", "1", "0")
    good, wrong = suite.findall("testcase")
    assert good.find("failure") is None and good.find("system-out").text == "k_p=3, k_i=4, k_v=32/5, f_c=1"
    assert "k3 > k2" in wrong.find("failure").get("message")


def test_free_text_that_mentions_table_i_claims_nothing(tmp_path, capsys):
    data = json.loads((PROOFS / "case_a_feasible.json").read_text(encoding="utf-8"))
    data["provenance"]["label"] = "compared with Table I, case (b)"
    (tmp_path / "f.json").write_text(json.dumps(data), encoding="utf-8")
    assert main(["verify", str(tmp_path / "f.json")]) == 0
    assert "PROVED" in capsys.readouterr().out
