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


# -- what check.run prints, line by line, on every path (golden file) ------------------------------------------------
#
# Three fake sections (one passing with a table and notes, one failing whose rows were streamed, one passing
# with neither summary nor notes) run through check.run from each configuration origin, as a table and as
# --json, at each verbosity, with and without --junit-xml.  Every line of stdout, stderr and the JUnit file is
# pinned: the configuration note and its level, the stream of --json's notes, the wrapping of long notes, the
# closing line, the JSON payload and the test cases.

_LONG = ("note: a long note that the terminal wraps: " + "word " * 30).rstrip()


def _printing_sections():
    from symbolic_friction._infra.junit import Case

    def alpha(args):
        return _sections.Section(
            "Alpha table", ("name", "value"), [("r1", "v1"), ("r2", "v2")], {"alpha": [1, 2, "κ ≤ 1 — σ"]}, True,
            ["note: alpha plain", _LONG], summary="alpha: 2 rows", counts={"alpha_rows": 2},
            cases=[Case("a.1", "check.alpha", seconds=0.25), Case("a.2", "check.alpha", skipped="not run")],
        )

    def beta(args):
        return _sections.Section(
            "Beta table", ("x",), [("streamed row",)], {"beta": {"ok": False}}, False,
            ["FAILED beta: broke", "beta detail"], summary="beta: 0 of 1", counts={"beta_ok": 0},
            cases=[Case("b.1", "check.beta", seconds=1.5, failure="broke\nsecond line", output="out")], streamed=True,
        )

    def gamma(args):
        return _sections.Section("Gamma title", ("c",), [], {"gamma": None}, True)

    return [alpha, beta, gamma]


def _printed(monkeypatch, tmp_path, capsys, *, origin, as_json, level, junit=False, only=False):
    from symbolic_friction._cli import _parallel
    from symbolic_friction._infra import output

    tmp_path = tmp_path / f"run{len(list(tmp_path.iterdir()))}"  # a fresh directory: no configuration left behind
    tmp_path.mkdir()
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("COLUMNS", "100")
    monkeypatch.setenv(_parallel.ENV, "1")
    monkeypatch.setattr(output, "_VERBOSITY", [level])
    monkeypatch.setattr(check, "SECTIONS", _printing_sections())
    (tmp_path / "proofs").mkdir(exist_ok=True)
    argv = ["check"]
    if origin == "--proofs":
        argv += ["--proofs", str(tmp_path / "proofs")]
    elif origin == "config":
        (tmp_path / "symbolic-friction.toml").write_text('proofs = "proofs"\nreport = false\ncertificates = ["a.json"]\n')
        argv += ["--config", str(tmp_path / "symbolic-friction.toml")]
    else:
        argv += ["--no-certificates"]
    if only:
        argv += ["--only", "lemma3"]
        monkeypatch.setattr(check, "obligations_section", _printing_sections()[0])
    if as_json:
        argv += ["--json"]
    if junit:
        argv += ["--junit-xml", str(tmp_path / "out" / "check.xml")]
    rc = check.run(build_parser().parse_args(argv))
    captured = capsys.readouterr()
    lines = [f"exit {rc}"] + ["out: " + x for x in captured.out.splitlines()] + ["err: " + x for x in captured.err.splitlines()]
    if junit:
        lines += ["xml: " + x for x in (tmp_path / "out" / "check.xml").read_text(encoding="utf-8").splitlines()]
    return [x.replace(str(tmp_path), "<TMP>") for x in lines]


def test_every_line_check_prints_is_pinned(monkeypatch, tmp_path, capsys):
    from tests.certify.golden import assert_golden

    actual = {}
    for origin in ("--proofs", "config", "none"):
        for as_json in (False, True):
            for level in (0, 1, 2):
                actual[f"{origin} json={as_json} level={level}"] = _printed(
                    monkeypatch, tmp_path, capsys, origin=origin, as_json=as_json, level=level)
    for as_json in (False, True):
        actual[f"junit json={as_json}"] = _printed(monkeypatch, tmp_path, capsys, origin="--proofs", as_json=as_json,
                                                   level=1, junit=True)
        actual[f"only json={as_json}"] = _printed(monkeypatch, tmp_path, capsys, origin="--proofs", as_json=as_json,
                                                  level=2, only=True)
    assert_golden("check_run_printing.json", actual)


def test_an_unusable_junit_path_is_refused_before_any_section_runs(monkeypatch, tmp_path):
    from symbolic_friction._infra.errors import SymbolicFrictionError

    ran = []

    def section(args):
        ran.append(1)
        return _sections.Section("S", ("a",), [], {}, True)

    (tmp_path / "taken").mkdir()  # a directory where the report file should go
    monkeypatch.setattr(check, "SECTIONS", [section])
    with pytest.raises(SymbolicFrictionError, match="--junit-xml"):
        check.run(_args(tmp_path, "--junit-xml", str(tmp_path / "taken")))
    assert ran == []


def test_run_takes_a_namespace_without_the_optional_attributes(monkeypatch, tmp_path, capsys):
    """A caller's Namespace need not carry --junit-xml, --only or --json: each defaults to off."""
    import argparse

    (tmp_path / "proofs").mkdir()
    monkeypatch.setattr(check, "SECTIONS", [_section("one", True)])
    args = argparse.Namespace(proofs=str(tmp_path / "proofs"), config=None, write=False, strict=False, no_certificates=False)
    assert check.run(args) == 0
    assert capsys.readouterr().out.rstrip().splitlines()[-1] == "check: PASSED — one summary"


def _run_sections_calls(monkeypatch, tmp_path) -> list[dict]:
    """The keyword arguments ``check`` gives ``run_sections``: without ``--only``, then with it."""
    from symbolic_friction._cli import _parallel

    seen = []
    real = _parallel.run_sections

    def spy(makers, args, **kw):
        seen.append(kw)
        return real(makers, args, **kw)

    monkeypatch.setattr(_parallel, "run_sections", spy)
    monkeypatch.setenv(_parallel.ENV, "1")
    monkeypatch.setattr(check, "obligations_section", _section("only", True))
    assert _run(monkeypatch, tmp_path, [_section("one", True)]) == 0
    assert _run(monkeypatch, tmp_path, [_section("one", True)], "--only", "lemma3") == 0
    return seen


def test_every_obligation_may_go_to_the_other_core_unless_only_is_given(monkeypatch, tmp_path):
    """Without --only, run_sections gets every obligation, in the paper's order, as the tail both cores claim from;
    with it, none."""
    from symbolic_friction._obligations import all_obligations

    seen = _run_sections_calls(monkeypatch, tmp_path)
    assert [[name for name, _ in _items(kw.get("tail"))] for kw in seen] == [[ob.id for ob in all_obligations()], []]


def _items(tail):
    """The tail's items: run_sections takes a list, or a function each process calls after the fork."""
    return (tail() if callable(tail) else tail) or []


def test_the_tail_is_shared_in_its_groups_within_the_shared_derivations_unless_only_is_given(monkeypatch, tmp_path):
    """Without --only, run_sections gets the obligations (the tail both processes claim, from either end), the groups of TOGETHER (claimed as one) and the shared derivations the worker decides them within;
    with --only, an empty tail."""
    from symbolic_friction._obligations import _derived_k

    seen = _run_sections_calls(monkeypatch, tmp_path)
    tail = [name for name, _ in check._decide_tail()]
    assert tail
    got = [(None if kw.get("tail") is None else [name for name, _ in _items(kw["tail"])], kw.get("together")) for kw in seen]
    assert got == [(tail, check.TOGETHER), ([], check.TOGETHER)]
    # the context is made after the fork (it imports sympy there): entering it opens one block of shared derivations
    for kw in seen:
        depth = len(_derived_k._SHARED)
        with kw["context"]():
            assert len(_derived_k._SHARED) == depth + 1
        assert len(_derived_k._SHARED) == depth


class _Pipe:
    """stdout as a pipe buffers it (written out on flush); stderr is unbuffered: both merge into one log."""

    def __init__(self, log, buffered):
        self.log, self.buffered, self.pending = log, buffered, []

    def write(self, text):
        (self.pending if self.buffered else self.log).append(text)
        return len(text)

    def flush(self):
        self.log.extend(self.pending)
        self.pending.clear()


def test_json_reaches_a_merged_log_before_the_notes(monkeypatch, tmp_path):
    """``check --json 2>&1 | tee log``: the JSON document is flushed before the notes and the closing line."""
    import sys

    log = []
    monkeypatch.setattr(sys, "stdout", _Pipe(log, buffered=True))
    monkeypatch.setattr(sys, "stderr", _Pipe(log, buffered=False))
    monkeypatch.setattr(check, "SECTIONS", [_section("one", True, notes=["note: n"])])
    rc = check.run(_args(tmp_path, "--json"))
    sys.stdout.flush()
    text = "".join(log)
    assert rc == 0 and text.index('"passed": true') < text.index("note: n") < text.index("check: PASSED")
