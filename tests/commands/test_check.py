"""``symbolic-friction check``: exit codes, ``--json`` schema, ``--write``
determinism, staleness detection and start-up cost."""

from __future__ import annotations

import contextlib
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import symbolic_friction._obligations as obligations
from symbolic_friction._cli import check
from symbolic_friction._obligations._base import Erratum, Obligation, Outcome
from symbolic_friction._cli.main import main

REPO = Path(__file__).resolve().parents[2]
MY_IDS = (
    "coordinates",
    "regularization",
    "assumption1.routh",
    "equilibria",
    "distance",
    "lemma1.uniqueness",
    "lemma2.P",
    "lemma2.lower_bound",
    "lemma2.dVdt",
    "remark.armstrong",
    "claim1.cases",
    "prop1.invariance",
)


# --------------------------------------------------------------------------- the real run (once)


@pytest.fixture(scope="module")
def full_run(tmp_path_factory):
    """``check --json --write`` on every obligation, run once for this module."""
    proofs = tmp_path_factory.mktemp("proofs")
    _copy_hunting(proofs)  # listed too, and `--write` cannot invent their gains
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(["check", "--json", "--write", "--proofs", str(proofs)])
    return rc, json.loads(out.getvalue()), err.getvalue(), proofs / "obligations.md"


def test_every_obligation_holds(full_run):
    rc, payload, err, _ = full_run
    failing = [(o["id"], o["reason"]) for o in payload["obligations"] if o["status"] != "holds"]
    assert failing == []
    assert rc == 0, err


def test_json_schema(full_run):
    _, payload, _, _ = full_run
    # no "smt": a fresh proofs directory has no smt/, so --write exports no SMT-LIB (tests/commands/test_check_smt.py)
    assert set(payload) == {"obligations", "errata", "certificates", "crosscheck_self_test", "self_check", "independent",
                            "passed", "counts", "configuration"}
    # the independent checker: every configured certificate proved, every shipped false one refused
    assert all(f["proved"] == f["must_prove"] for f in payload["independent"])
    assert payload["counts"]["independent_ok"] == payload["counts"]["independent_files"] == 16 + 138
    assert payload["configuration"]["source"].endswith("pyproject.toml") and payload["configuration"]["report"] is True
    assert len(payload["configuration"]["certificates"]) == 16 and payload["configuration"]["only"] is None
    assert payload["passed"] is True
    assert payload["counts"]["selftest_ok"] == payload["counts"]["selftest_rows"] == 58  # 26 kernel runs + 2 × 16
    assert payload["counts"]["obligations"] == payload["counts"]["obligations_hold"] == len(payload["obligations"])
    assert payload["counts"]["certificates"] == payload["counts"]["certificates_proved"] == 16
    assert [c["proved"] and not c["stale"] for c in payload["certificates"]] == [True] * 16
    ids = [o["id"] for o in payload["obligations"]]
    assert len(ids) == len(set(ids))
    assert [i for i in ids if i in MY_IDS] == list(MY_IDS)  # all present, in paper order
    for o in payload["obligations"]:
        assert {"id", "paper", "statement", "method", "status", "seconds"} <= set(o)
        assert o["status"] in ("holds", "fails")
        assert isinstance(o["seconds"], float) and o["seconds"] >= 0
        assert all(isinstance(o[k], str) and o[k] for k in ("id", "paper", "statement", "method"))
        assert all(set(d) == {"label", "latex"} for d in o["details"])
    for e in payload["errata"]:
        assert set(e) == {"where", "paper_says", "correct", "checked_by"}
    v0 = [e for e in payload["errata"] if "V_0" in e["paper_says"]]
    assert v0 and "ξ_σ²" in v0[0]["correct"]


def test_write_reports_every_obligation_with_latex(full_run):
    _, payload, err, report = full_run
    text = report.read_text(encoding="utf-8")
    assert f"wrote {report}" in err
    for o in payload["obligations"]:
        assert f"`{o['id']}` — {o['status']}" in text
    assert text.count("$$") % 2 == 0 and "\\left[\\begin{matrix}" in text
    assert "## Errata" in text and "ξ_σ²" in text
    assert "seconds" not in text and " s)" not in text  # no timings: byte-deterministic


@pytest.mark.slow
def test_write_is_deterministic_across_processes(full_run, tmp_path):
    """A second process (other hash seed) writes the same bytes."""
    _, _, _, report = full_run
    # The second process writes obligations.md, the file compared; --no-certificates spares it regenerating the 16
    # certificates, which nothing here compares (that they are what the CLI writes is tests/commands/test_certify.py's
    # byte comparison with proofs/, and full_run regenerates and verifies them).  For the same reason it leaves out
    # the cross-check self-test and the independent checker (they write nothing; full_run passes them); the
    # self-check stays beside the obligations so that `check` still forks its second process, which takes
    # obligations from the back of the list (_parallel.run_sections): the split whose output must not vary either.
    kept = "[check.obligations_section, check.self_check_section]"
    code = (f"from symbolic_friction._cli import check\ncheck.SECTIONS[:] = {kept}\n"
            "from symbolic_friction._cli.main import entry_point\nentry_point()")
    env = dict(os.environ, PYTHONHASHSEED="12345")
    proc = subprocess.run(
        [sys.executable, "-c", code, "check", "--write", "--no-certificates", "--proofs", str(tmp_path)],
        capture_output=True, text=True, env=env, timeout=300,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert (tmp_path / "obligations.md").read_bytes() == report.read_bytes()


def test_committed_report_is_current(full_run):
    """``proofs/obligations.md`` in the repository is what ``check --write`` writes now."""
    _, _, _, report = full_run
    committed = REPO / "proofs" / "obligations.md"
    assert committed.is_file(), "run `symbolic-friction check --write` and commit proofs/obligations.md"
    assert committed.read_bytes() == report.read_bytes(), "proofs/obligations.md is stale: run `symbolic-friction check --write`"


# --------------------------------------------------------------------------- mechanics, with small fake obligations


class _Holds(Obligation):
    id = "fake.holds"
    paper = "eq. (x)"
    statement = "|x| ≥ 0"
    method = "sympy identity"
    errata = (Erratum(where="§0", paper_says="1 = 2", correct="1 = 1", checked_by="fake.holds"),)

    def derive(self):
        return 0

    def verify(self, subject):
        return Outcome(True, "fine", (("x", "x^2"),))


class _Fails(_Holds):
    id = "fake.fails"
    errata = ()

    def verify(self, subject):
        return Outcome.fail("residual k_i - 1 is not zero")


class _Crashes(_Holds):
    id = "fake.crashes"
    errata = ()

    def verify(self, subject):
        raise ZeroDivisionError("division by zero in a broken check")


@pytest.fixture
def fake(monkeypatch):
    """Replace the obligation list by the given fake classes (and check only obligations)."""

    def use(*classes):
        monkeypatch.setattr(check, "SECTIONS", [check.obligations_section])
        monkeypatch.setattr(obligations, "all_obligations", lambda: [c() for c in classes])
        monkeypatch.setattr(obligations, "all_errata", lambda: [e for c in classes for e in c.errata])

    return use


def test_table_lists_columns_and_errata(fake, tmp_path, capsys):
    fake(_Holds)
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    header = next(line for line in out.splitlines() if line.startswith("id"))
    assert header.split() == ["id", "paper", "statement", "method", "status", "seconds"]
    assert "fake.holds" in out and "holds" in out
    assert "Errata" in out and 'the paper says "1 = 2"; correct: 1 = 1' in out
    assert "1 of 1 obligations hold" in out


def test_failing_obligation_exits_1_and_shows_the_residual(fake, tmp_path, capsys):
    fake(_Holds, _Fails)
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert "FAILS fake.fails: residual k_i - 1 is not zero" in out
    assert "1 of 2 obligations hold" in out
    assert "`fake.fails` — fails" in (tmp_path / "obligations.md").read_text(encoding="utf-8")


def test_crashing_obligation_is_reported_as_failing(fake, tmp_path, capsys):
    fake(_Crashes)
    assert main(["check", "--json", "--no-certificates", "--proofs", str(tmp_path / "none")]) == 1
    record = json.loads(capsys.readouterr().out)["obligations"][0]
    assert record["status"] == "fails"
    assert "ZeroDivisionError: division by zero in a broken check" in record["reason"]


def test_write_twice_is_byte_identical(fake, tmp_path, capsys):
    fake(_Holds, _Fails)
    main(["check", "--write", "--proofs", str(tmp_path / "a")])
    main(["check", "--write", "--proofs", str(tmp_path / "b")])
    first = (tmp_path / "a" / "obligations.md").read_bytes()
    assert first == (tmp_path / "b" / "obligations.md").read_bytes()
    main(["check", "--write", "--proofs", str(tmp_path / "a")])
    assert (tmp_path / "a" / "obligations.md").read_bytes() == first
    assert sorted(p.name for p in (tmp_path / "a").iterdir()) == ["obligations.md"]  # no temp files left


def test_stale_report_exits_1(fake, tmp_path, capsys):
    fake(_Holds)
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0
    assert main(["check", "--proofs", str(tmp_path)]) == 0
    report = tmp_path / "obligations.md"
    report.write_text(report.read_text(encoding="utf-8").replace("holds", "held"), encoding="utf-8")
    capsys.readouterr()
    assert main(["check", "--proofs", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert f"STALE: {report} differs from what `check` derives now" in out


def test_missing_report_exits_1(fake, tmp_path, capsys):
    fake(_Holds)
    assert main(["check", "--proofs", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert f"STALE: {tmp_path / 'obligations.md'} is missing; run `symbolic-friction check --write`" in out


def test_missing_proofs_dir_is_a_usage_error(fake, tmp_path, capsys):
    fake(_Holds)
    missing = tmp_path / "no-such-dir"
    assert main(["check", "--proofs", str(missing)]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in captured.err
    assert f"proofs directory {str(missing)!r} does not exist" in lines[0] and "--no-certificates" in lines[0]
    assert not missing.exists()


def test_proofs_path_that_is_a_file_is_a_usage_error(fake, tmp_path, capsys):
    fake(_Holds)
    a_file = tmp_path / "proofs"
    a_file.write_text("not a directory", encoding="utf-8")
    assert main(["check", "--proofs", str(a_file)]) == 2
    assert f"--proofs {a_file} is not a directory" in capsys.readouterr().err


def test_missing_proofs_dir_with_no_certificates_says_what_was_not_checked(fake, tmp_path, capsys):
    fake(_Holds)
    missing = tmp_path / "no-such-dir"
    assert main(["check", "--no-certificates", "--proofs", str(missing)]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last.startswith("check: PASSED — 1 of 1 obligations hold")
    assert "not checked (no such directory)" in last


def test_write_creates_the_proofs_dir(fake, tmp_path, capsys):
    fake(_Holds)
    target = tmp_path / "new" / "proofs"
    assert main(["check", "--write", "--proofs", str(target)]) == 0
    assert (target / "obligations.md").is_file()


def test_json_keeps_stdout_pure_and_notes_on_stderr(fake, tmp_path, capsys):
    fake(_Holds)
    assert main(["check", "--json", "--proofs", str(tmp_path)]) == 1  # no report yet: stale
    captured = capsys.readouterr()
    payload = json.loads(captured.out)
    assert payload["obligations"][0]["id"] == "fake.holds"
    assert payload["errata"] == [{"where": "§0", "paper_says": "1 = 2", "correct": "1 = 1", "checked_by": "fake.holds"}]
    assert "STALE" in captured.err


def test_sections_can_be_appended(fake, tmp_path, capsys, monkeypatch):
    fake(_Holds)

    def certificates(args):
        return check.Section("Certificates", ("file", "status"), [("a.json", "proved")], {"certificates": ["a.json"]}, False, ["a.json: not proved"])

    monkeypatch.setattr(check, "SECTIONS", [*check.SECTIONS, certificates])
    assert main(["check", "--json", "--write", "--proofs", str(tmp_path)]) == 1
    captured = capsys.readouterr()
    payload = json.loads(captured.out)
    assert set(payload) == {"obligations", "errata", "certificates", "passed", "counts", "configuration"}
    assert payload["passed"] is False
    assert captured.err.strip().splitlines()[-1].startswith("check: FAILED — Certificates; 1 of 1 obligations hold")


def test_crashing_section_fails(fake, tmp_path, capsys, monkeypatch):
    fake(_Holds)

    def broken(args):
        raise RuntimeError("boom")

    monkeypatch.setattr(check, "SECTIONS", [*check.SECTIONS, broken])
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 1
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last.startswith("check: FAILED — broken crashed: RuntimeError: boom")


def test_stale_report_makes_the_last_line_say_failed(fake, tmp_path, capsys):
    fake(_Holds)
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0
    assert capsys.readouterr().out.strip().splitlines()[-1].startswith("check: PASSED")
    (tmp_path / "obligations.md").write_text("edited", encoding="utf-8")
    assert main(["check", "--proofs", str(tmp_path)]) == 1
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last == f"check: FAILED — 1 of 1 obligations hold, {tmp_path / 'obligations.md'} STALE"


def test_no_obligations_is_a_failure(fake, tmp_path, capsys):
    fake()
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 1
    assert "check: FAILED — 0 of 0 obligations hold" in capsys.readouterr().out


def test_no_certificates_flag_and_empty_directory(tmp_path, capsys):
    args = check_args(tmp_path)
    args.no_certificates = True
    section = check.certificates_section(args)
    assert section.ok and section.summary == "certificates not checked (--no-certificates)"
    args.no_certificates = False
    section = check.certificates_section(args)
    assert not section.ok  # Table I's files (and the hunting ones) are required and missing
    assert section.summary.startswith("0 of 16 certificates proved exactly")


# --------------------------------------------------------------------------- start-up cost


HEAVY = ("sympy", "scipy", "cvxpy", "matplotlib")


def _modules_after(code: str) -> list[str]:
    probe = code + f"\nimport sys\nprint(sorted(m for m in {HEAVY!r} if m in sys.modules))\n"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1].replace("'", '"'))


def test_importing_the_cli_does_not_import_sympy():
    assert _modules_after("import symbolic_friction._cli.main") == []


def test_check_help_does_not_import_sympy():
    code = (
        "import contextlib, io\nfrom symbolic_friction._cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    try:\n        main(['check', '--help'])\n    except SystemExit:\n        pass"
    )
    assert _modules_after(code) == []


# --------------------------------------------------------------------------- the certificates section


def _copy_hunting(proofs):
    """The listed files whose gains `--write` cannot invent: the hunting and the box certificates."""
    import shutil

    shutil.copytree(REPO / "proofs" / "hunting", proofs / "hunting")
    for name in ("box_case_a_10pct.json", "box_physical.json"):
        shutil.copy(REPO / "proofs" / name, proofs / name)


def _copy_proofs(tmp_path):
    import shutil

    dst = tmp_path / "proofs"
    shutil.copytree(REPO / "proofs", dst)
    return dst


def test_certificates_section_passes_on_committed_proofs(tmp_path):
    section = check.certificates_section(check_args(_copy_proofs(tmp_path)))
    assert section.ok and len(section.rows) == 16
    assert all(row[1:3] == ("yes", "yes") for row in section.rows)


def test_certificates_section_fails_on_a_stale_or_wrong_certificate(tmp_path):
    proofs = _copy_proofs(tmp_path)
    target = proofs / "case_a_feasible.json"
    data = json.loads(target.read_text(encoding="utf-8"))
    data["overshoot_bound"] = "1.5"  # below sqrt(c2 ĉ2 / (c1 ĉ1)): no longer a proof
    target.write_text(json.dumps(data), encoding="utf-8")
    section = check.certificates_section(check_args(proofs))
    assert not section.ok
    assert any("case_a_feasible.json" in note and "FAILED" in note for note in section.notes)


def test_certificates_section_requires_table_i_files(tmp_path):
    proofs = _copy_proofs(tmp_path)
    (proofs / "case_b_tightest.json").unlink()
    section = check.certificates_section(check_args(proofs))
    assert not section.ok
    assert any("case_b_tightest.json" in note and "missing" in note for note in section.notes)


def check_args(proofs, *, write=False):
    import argparse

    return argparse.Namespace(proofs=str(proofs), write=write, json=False, no_certificates=False)


# --------------------------------------------------------------------------- --only, --junit-xml, configuration


def test_only_rederives_one_part_and_compares_nothing_else(tmp_path, capsys):
    import xml.etree.ElementTree as ET

    report = tmp_path / "r.xml"
    assert main(["check", "--only", "lemma2", "--proofs", str(tmp_path), "--junit-xml", str(report)]) == 0
    out = capsys.readouterr().out
    last = out.strip().splitlines()[-1]
    assert last.startswith("check: PASSED — 3 of 3 obligations hold (only lemma2)")
    names = [c.get("name") for c in ET.parse(report).getroot().iter("testcase")]
    assert names == ["lemma2.P", "lemma2.lower_bound", "lemma2.dVdt"]


def test_only_unknown_part_is_a_usage_error(capsys):
    assert main(["check", "--only", "lemma9"]) == 2
    err = capsys.readouterr().err
    assert "--only lemma9 selects no obligation" in err and "lemma3" in err


def test_junit_report_has_a_failure_per_failing_obligation(fake, tmp_path, capsys):
    import xml.etree.ElementTree as ET

    fake(_Holds, _Fails)
    report = tmp_path / "r.xml"
    assert main(["check", "--write", "--proofs", str(tmp_path), "--junit-xml", str(report)]) == 1
    cases = {c.get("name"): c for c in ET.parse(report).getroot().iter("testcase")}
    failing = [n for n, c in cases.items() if c.find("failure") is not None]
    assert failing == [_Fails.id]


def test_stale_report_closing_line_agrees_with_the_exit_code(fake, tmp_path, capsys):
    """The closing line names what is stale first, and says FAILED exactly when the exit code is 1."""
    fake(_Holds)
    assert main(["check", "--write", "--proofs", str(tmp_path)]) == 0
    (tmp_path / "obligations.md").write_text("edited", encoding="utf-8")
    capsys.readouterr()
    code = main(["check", "--proofs", str(tmp_path)])
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert code == 1 and last.startswith("check: FAILED — ") and "STALE" in last


def test_proofs_dir_without_configuration_checks_every_certificate_in_it(tmp_path, monkeypatch, capsys):
    import shutil

    mine = tmp_path / "mine"
    mine.mkdir()
    for name in ("case_b_feasible.json", "case_b_feasible.md"):
        shutil.copy(REPO / "proofs" / name, mine / name)
    (tmp_path / ".git").mkdir()  # a repository of its own: the checkout's configuration is not found
    monkeypatch.chdir(tmp_path)
    args = check_args(mine)
    target = check.resolve_target(args)
    assert target.certificates is None and target.report is False  # no obligations.md, no Table I demanded
    section = check.certificates_section(args)
    assert section.ok and [Path(row[0]).name for row in section.rows] == ["case_b_feasible.json"]


def test_a_crashing_section_is_an_error_in_the_junit_report(fake, tmp_path, capsys, monkeypatch):
    import xml.etree.ElementTree as ET

    fake(_Holds)

    def broken(args):
        raise RuntimeError("boom")

    monkeypatch.setattr(check, "SECTIONS", [check.obligations_section, broken])
    report = tmp_path / "r.xml"
    assert main(["check", "--write", "--proofs", str(tmp_path), "--junit-xml", str(report)]) == 1
    errors = [c for c in ET.parse(report).getroot().iter("testcase") if c.find("error") is not None]
    assert [c.get("name") for c in errors] == ["broken"] and "RuntimeError: boom" in errors[0].find("error").text
