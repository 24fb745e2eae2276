"""The mutation script (tests/mutation/run.py): its list stays honest, and its fast subset is caught."""

from __future__ import annotations

import json
from collections import Counter

import pytest

from tests.mutation.mutants import FAST, MUTANTS, TARGETS, Mutant
from tests.mutation.run import ROOT, DoesNotApply, _failures_without_proofs, apply, run_one, source_files
from tests.mutation.warm import Warm


def test_at_least_forty_mutants_with_unique_ids_over_every_target():
    assert len(MUTANTS) >= 40
    ids = [m.id for m in MUTANTS]
    assert len(ids) == len(set(ids))
    counts = Counter(m.target for m in MUTANTS)
    assert set(counts) == set(TARGETS)
    assert set(FAST) <= set(ids)


@pytest.mark.parametrize("mutant", MUTANTS, ids=lambda m: m.id)
def test_every_mutant_applies_to_the_current_tree(mutant):
    text = (ROOT / mutant.path).read_text(encoding="utf-8")
    assert text.count(mutant.old) == 1, f"{mutant.id}: update its snippet, the code moved"
    assert apply(text, mutant) != text


def test_every_test_a_mutant_names_exists():
    """A missing test file makes pytest fail with a usage error, which must never count as a catch."""
    for m in MUTANTS:
        for test in m.tests:
            assert (ROOT / test.split("::")[0]).is_file(), (m.id, test)


def test_every_equivalent_mutant_says_why():
    for m in MUTANTS:
        assert m.equivalent is None or len(m.equivalent) > 20


def test_apply_refuses_a_snippet_that_is_missing_or_repeated():
    m = Mutant("x", "model", "f.py", "a = 1", "a = 2", "demo")
    with pytest.raises(DoesNotApply, match="occurs 0 times"):
        apply("b = 1\n", m)
    with pytest.raises(DoesNotApply, match="occurs 2 times"):
        apply("a = 1\na = 1\n", m)
    assert apply("a = 1\n", m) == "a = 2\n"


def test_sources_include_the_package_and_the_proofs():
    files = source_files()
    assert "symbolic_friction/_model/lyapunov.py" in files and "proofs/obligations.md" in files
    assert not any(f.startswith("tests/") for f in files)


@pytest.mark.slow
def test_fast_subset_is_caught_by_check_or_verify_alone():
    """Each mutant of ``FAST`` fails ``check`` on its copy, in a section no file under ``proofs/`` can make fail.

    ``regenerate=False`` (run.py's :func:`_check_sources`): one ``check --json --no-certificates`` on each copy as
    committed, the baseline passing that very command whole; a mutant counts as caught there only through an
    obligation or a self-check row (the only sections its run decides), which never read ``proofs/``, so a stale (or
    regenerated) file cannot be what catches it — the guarantee ``check --write`` first gives the full script, at
    about a quarter of its cost.  A mutant not decided that way goes through the script's whole pipeline, after that
    pipeline's own baseline.
    """
    files = source_files()
    with Warm() as warm:  # the quick runs fork one interpreter that has imported the libraries
        base = run_one(None, files, regenerate=False, warm=warm)
        assert base.check_rc == 0 and base.verify_rc in (0, None), base.caught_by
        full_base = base if base.regenerated else None
        for mutant in (m for m in MUTANTS if m.id in FAST):
            outcome = run_one(mutant, files, regenerate=False, warm=warm)
            if outcome.regenerated and full_base is None:  # decided by write, check, verify: their baseline must pass
                full_base = run_one(None, files)
                assert full_base.check_rc == 0 and full_base.verify_rc == 0, full_base.caught_by
            assert outcome.caught, (mutant.id, outcome)
            assert outcome.caught_by.startswith("check:"), outcome.caught_by


def test_only_failures_no_proofs_file_can_cause_count_without_regenerating():
    """What :func:`_check_sources` counts: failing obligations and self-check rows, never a section reading proofs/."""
    payload = {
        "obligations": [{"id": "model.V", "status": "holds"}, {"id": "lemma3.R", "status": "FAILS"}],
        "self_check": [{"file": "a.json", "ok": True}, {"file": "b.json", "ok": False},
                       {"case": "rigour x", "ok": False}],
        "certificates": [{"file": "proofs/c.json", "proved": False, "stale": True}],
        "crosscheck_self_test": [{"case": "a", "variant": "proved", "ok": False}],
        "independent": [{"proved": False, "must_prove": True}],
    }
    assert _failures_without_proofs(payload) == ["lemma3.R", "self-check b.json", "self-check rigour x"]
    assert _failures_without_proofs({k: v for k, v in payload.items() if k not in ("obligations", "self_check")}) == []


def test_what_failed_names_the_catches_of_the_full_pipeline():
    """The full pipeline's summary (steps 2 and 3 of run.py), which the default run reaches only as a fallback."""
    from subprocess import CompletedProcess

    from tests.mutation.run import _what_failed

    payload = {"obligations": [{"id": "lemma3.R", "status": "FAILS"}],
               "certificates": [{"file": "proofs/a.json", "proved": False}],
               "crosscheck_self_test": [{"case": "a", "variant": "c1", "ok": False}]}
    check = CompletedProcess([], 1, json.dumps(payload), "")
    verify = CompletedProcess([], 1, "PROVED proofs/x.json: fine\nFAILED proofs/a.json: c2\n", "")
    assert _what_failed(check, verify) == "check: lemma3.R, certificate a.json, self-test (a) c1; verify: a.json"
    assert _what_failed(CompletedProcess([], 0, "{}", ""), CompletedProcess([], 0, "", "")) == "-"
    crashed = CompletedProcess([], 1, "not json", "Traceback\nValueError: boom")
    assert _what_failed(crashed, CompletedProcess([], 0, "", "")) == "check: check crashed: ValueError: boom"
