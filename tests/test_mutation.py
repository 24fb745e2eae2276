"""The mutation script (tests/mutation/run.py): its list stays honest, and its fast subset is caught."""

from __future__ import annotations

from collections import Counter

import pytest

from tests.mutation.mutants import FAST, MUTANTS, TARGETS, Mutant
from tests.mutation.run import ROOT, DoesNotApply, apply, run_one, source_files


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
    files = source_files()
    base = run_one(None, files)
    assert base.check_rc == 0 and base.verify_rc == 0, base.caught_by
    for mutant in (m for m in MUTANTS if m.id in FAST):
        outcome = run_one(mutant, files)
        assert outcome.caught, (mutant.id, outcome)
        assert outcome.caught_by.startswith("check:"), outcome.caught_by
