"""``check``'s gate, path by path: how section results become the closing line, the JSON verdict and the exit code.

The sections are replaced by fakes (no obligation is derived), so each
test takes milliseconds and reaches one path of ``check.run``: every section
satisfied, one failing (first, middle, last), one crashing, ``--json``.
"""

from __future__ import annotations

import json

import pytest

from symbolic_friction._cli import _sections, check
from symbolic_friction._cli.main import build_parser


def _section(name, ok, *, summary=None, notes=(), counts=None, rows=None):
    def make(args):
        return _sections.Section(
            title=f"T-{name}", columns=("a", "b"), rows=rows if rows is not None else [("x", "y")],
            json={name: {"ok": ok}}, ok=ok, notes=list(notes), summary=summary if summary is not None else f"{name} summary",
            counts=counts or {name: 1},
        )

    make.__name__ = name
    return make


def _crashing(args):
    raise ValueError("boom 7")


def _args(tmp_path, *extra):
    (tmp_path / "proofs").mkdir(exist_ok=True)
    return build_parser().parse_args(["check", "--proofs", str(tmp_path / "proofs"), *extra])


def _run(monkeypatch, tmp_path, sections, *extra):
    monkeypatch.setattr(check, "SECTIONS", sections)
    return check.run(_args(tmp_path, *extra))


def test_all_satisfied_passes(monkeypatch, tmp_path, capsys):
    rc = _run(monkeypatch, tmp_path, [_section("one", True), _section("two", True)])
    out = capsys.readouterr().out
    assert rc == 0
    assert out.rstrip().splitlines()[-1] == "check: PASSED — one summary; two summary"


@pytest.mark.parametrize("bad", [0, 1, 2])
def test_any_failing_section_fails(monkeypatch, tmp_path, capsys, bad):
    sections = [_section(f"s{i}", i != bad) for i in range(3)]
    rc = _run(monkeypatch, tmp_path, sections)
    last = capsys.readouterr().out.rstrip().splitlines()[-1]
    assert rc == 1
    others = "; ".join(f"s{i} summary" for i in range(3) if i != bad)
    assert last == f"check: FAILED — s{bad} summary; {others}"


def test_a_crashing_section_fails_and_says_why(monkeypatch, tmp_path, capsys):
    rc = _run(monkeypatch, tmp_path, [_section("one", True), _crashing])
    out = capsys.readouterr().out
    assert rc == 1
    assert "FAILED _crashing crashed: ValueError: boom 7" in out
    assert out.rstrip().splitlines()[-1] == "check: FAILED — _crashing crashed: ValueError: boom 7; one summary"


def test_json_carries_the_verdict_and_every_member(monkeypatch, tmp_path, capsys):
    rc = _run(monkeypatch, tmp_path, [_section("one", True, counts={"n": 3}), _section("two", False, notes=["FAILED x"])], "--json")
    captured = capsys.readouterr()
    payload = json.loads(captured.out)
    assert rc == 1
    assert payload["passed"] is False
    assert payload["one"] == {"ok": True} and payload["two"] == {"ok": False}
    assert payload["counts"] == {"n": 3, "two": 1}
    assert payload["configuration"]["only"] is None and payload["configuration"]["proofs"] == str(tmp_path / "proofs")
    assert "FAILED x" in captured.err
    assert captured.err.rstrip().splitlines()[-1] == "check: FAILED — two summary; one summary"
    rc = _run(monkeypatch, tmp_path, [_section("one", True)], "--json")
    assert rc == 0 and json.loads(capsys.readouterr().out)["passed"] is True


def test_closing_line_names_failed_sections_first_and_falls_back_to_the_title():
    S = _sections.Section
    ok = S("Good", (), [], {}, True, summary="")
    bad = S("Bad", (), [], {}, False, summary="2 of 3 hold")
    assert _sections.closing_line([ok, bad]) == "check: FAILED — 2 of 3 hold; Good"
    assert _sections.closing_line([ok]) == "check: PASSED — Good"


def test_crashed_section_is_failing_and_named():
    def maker(args):
        raise AssertionError

    s = _sections._crashed(maker, KeyError("k"))
    assert s.ok is False and s.title == "maker"
    assert s.summary == "maker crashed: KeyError: 'k'"
    assert s.rows == [("maker crashed: KeyError: 'k'",)] and s.columns == ("error",)
    assert s.notes == ["FAILED maker crashed: KeyError: 'k'"]
    assert s.json == {}
    (case,) = s.cases
    assert case.name == "maker" and case.classname == "check.sections" and case.error == s.summary
    anonymous = _sections._crashed(object(), ValueError("v"))
    assert anonymous.title == "section" and anonymous.summary == "section crashed: ValueError: v"


def test_verdict_notes_are_recognised():
    for note in ("FAILS a", "FAILED b", "STALE c", "MALFORMED d"):
        assert _sections._is_verdict(note)
    for note in ("holds", " FAILED", "note: x", "failed"):
        assert not _sections._is_verdict(note)
