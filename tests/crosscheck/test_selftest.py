"""The cross-check's self-test, which ``check`` runs: it can fail."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pytest

from symbolic_friction._certify import load
from symbolic_friction._cli import check
from symbolic_friction._crosscheck import _results
from symbolic_friction._crosscheck._selftest import EXPECTED, crosscheck_self_test

PROOFS = Path(__file__).resolve().parents[2] / "proofs"


@pytest.fixture(scope="module")
def certs():
    return {case: load(PROOFS / f"case_{case}_tightest.json") for case in "ab"}


def test_self_test_passes_and_names_what_caught_each_variant(certs):
    result = crosscheck_self_test(certs)
    assert result.ok
    kernel = [r for r in result.rows if r.case == "kernel"]
    assert len(kernel) == 26 and all(r.expected == "matches the reference" for r in kernel)
    rest = [r.variant for r in result.rows if r.case != "kernel"]
    assert rest == ["edited kappa", "event limit", "proved", *EXPECTED] * 2
    for variant in ("c2", "c1_hat", "c2_hat", "NaN c", "stalled", "mode"):
        assert variant in EXPECTED
    for row in result.rows:
        if row.variant in EXPECTED:
            assert EXPECTED[row.variant] in row.caught_by


def test_a_cross_check_that_cannot_fail_fails_the_self_test(certs, monkeypatch):
    # every relative slack reported as comfortably positive: no property can fail any more
    real_add = _results.Tally.add

    def never_fails(self, rel, mask, make, **kw):
        return real_add(self, np.where(np.isfinite(rel), np.abs(rel), rel), mask, make, **kw)

    monkeypatch.setattr(_results.Tally, "add", never_fails)
    result = crosscheck_self_test(certs)
    assert not result.ok
    # a NaN slack stays a failure whatever the sign of the others (the NaN c rows, one per case)
    assert all(not r.ok for r in result.rows if r.variant in EXPECTED and r.variant != "NaN c")


def test_a_cross_check_that_always_fails_fails_the_self_test(certs, monkeypatch):
    real_add = _results.Tally.add

    def always_fails(self, rel, mask, make, **kw):
        return real_add(self, np.where(np.isfinite(rel), -np.abs(rel) - 1.0, rel), mask, make, **kw)

    monkeypatch.setattr(_results.Tally, "add", always_fails)
    result = crosscheck_self_test(certs)
    assert not result.ok
    assert not next(r for r in result.rows if r.variant == "proved").ok


def test_check_section_reports_a_broken_cross_check(monkeypatch, capsys):
    real_add = _results.Tally.add
    monkeypatch.setattr(
        _results.Tally, "add", lambda self, rel, mask, make, **kw: real_add(self, np.abs(rel), mask, make, **kw)
    )
    args = argparse.Namespace(proofs=str(PROOFS), write=False, json=False, no_certificates=False)
    section = check.crosscheck_section(args)
    assert not section.ok
    assert "2 of 26 wrong certificates caught" in section.summary and "4 of 4 refusals hold" in section.summary
    assert "26 of 26 kernel runs match the reference" in section.summary
    assert any(note.startswith("FAILED cross-check self-test (a) kappa: expected prop1.stability") for note in section.notes)


def test_a_cross_check_that_accepts_unproved_certificates_fails_the_self_test(certs, monkeypatch):
    from symbolic_friction._crosscheck import _run

    real = _run._as_claims
    monkeypatch.setattr(_run, "_as_claims", lambda items, require_proved: real(items, require_proved=False))
    result = crosscheck_self_test(certs)
    assert not result.ok
    assert [r.caught_by for r in result.rows if r.variant == "edited kappa"] == [("accepted",)] * 2


def test_a_cross_check_that_hides_the_event_limit_fails_the_self_test(certs, monkeypatch):
    from symbolic_friction._simulation import _trajectories

    # a result type that reports every trajectory as complete
    monkeypatch.setattr(_trajectories.Status, "COMPLETE", (*_trajectories.Status.COMPLETE, _trajectories.Status.MAX_EVENTS))
    result = crosscheck_self_test(certs)
    assert not result.ok
    assert not next(r for r in result.rows if r.variant == "event limit").ok


def test_a_nan_slack_hidden_as_a_pass_fails_the_self_test(certs, monkeypatch):
    real_add = _results.Tally.add

    def hides_nan(self, rel, mask, make, **kw):
        return real_add(self, np.where(np.isnan(rel), 1.0, rel), mask, make, **kw)

    monkeypatch.setattr(_results.Tally, "add", hides_nan)
    result = crosscheck_self_test(certs)
    assert not result.ok
    assert [r.ok for r in result.rows if r.variant == "NaN c"] == [False, False]


def test_a_kernel_that_drifts_from_the_reference_fails_check(monkeypatch):
    from symbolic_friction._crosscheck import _kernel_check

    real = _kernel_check.kernel_rows

    def drifted():
        rows = list(real())
        rows[7] = _kernel_check.KernelRow(rows[7].scenario, False, "at t = 1.0 the kernel's z = …")
        return tuple(rows)

    monkeypatch.setattr(_kernel_check, "kernel_rows", drifted)
    args = argparse.Namespace(proofs=str(PROOFS), write=False, json=False, no_certificates=False)
    section = check.crosscheck_section(args)
    assert not section.ok
    assert "25 of 26 kernel runs match the reference" in section.summary
    assert any(n.startswith("FAILED cross-check self-test (kernel) f_c=2") for n in section.notes)


def test_case_b_runs_at_f_c_2_and_still_verifies(certs):
    from symbolic_friction._certify import verify_certificate
    from symbolic_friction._crosscheck._selftest import F_C_OF_CASE, _at_coulomb_level

    assert F_C_OF_CASE == {"b": 2}
    scaled = _at_coulomb_level(certs["b"], 2)
    assert scaled.f_c == 2 and verify_certificate(scaled).proved and "at f_c = 2" in scaled.provenance.label


def test_a_mode_table_check_without_f_c_fails_the_self_test(certs, monkeypatch):
    """|φ| ≤ 1 instead of |φ| ≤ f_c on a stick: invisible at f_c = 1, caught on case (b) at f_c = 2."""
    import importlib.util
    import sys

    from symbolic_friction._crosscheck import mode_table

    path = Path(mode_table.__file__)
    source = path.read_text(encoding="utf-8").replace("np.abs(xs[..., 1]) - f_c", "np.abs(xs[..., 1]) - 1.0")
    spec = importlib.util.spec_from_loader("symbolic_friction._crosscheck._mode_table_mut", loader=None)
    mutant = importlib.util.module_from_spec(spec)
    mutant.__package__ = "symbolic_friction._crosscheck"
    monkeypatch.setitem(sys.modules, spec.name, mutant)
    exec(compile(source, str(path), "exec"), mutant.__dict__)
    monkeypatch.setattr(mode_table.Modes, "check", mutant.Modes.check)
    result = crosscheck_self_test(certs)
    assert not result.ok
    bad = [(r.case, r.variant) for r in result.rows if not r.ok]
    assert ("b", "proved") in bad and ("a", "proved") not in bad


@pytest.mark.parametrize("case", ["a", "b"])
def test_the_sampled_starts_catch_a_wrong_k4_for_every_seed(case):
    # check's self-test finds its V̂-growth starts with numpy alone (no scipy.optimize import): it must
    # not depend on a lucky seed
    from symbolic_friction._crosscheck import _selftest
    from symbolic_friction._crosscheck._claims import Claims

    cert = _selftest._at_coulomb_level(_selftest.table_i_certificates(PROOFS)[case], _selftest.F_C_OF_CASE.get(case, 1))
    k4 = Claims.from_certificate(_selftest.wrong_variants(cert, 1.5)["k4"], label="k4")
    for seed in range(4):
        # the dense run, and the one sampled at t = 0 and the horizon only (its R̂ intervals end at events)
        for results in _selftest._growth_run(k4, seed=seed)[1:]:
            assert any(r.id == "lemma3.hatV_nonincreasing" and not r.passed and r.counterexample is not None
                       for r in results), seed
