"""The trusted base's last gaps (issue 33, item 5): each one-token mutant below fails a row ``check`` runs.

* the kernel's certified scan without the fourth-order term of its bound on ``|u''|``
  misses a graze inside one scan cell (:func:`._kernel_check.graze_row`);
* the rounding tolerance of ``φ = −k_i e_i − k_p s`` at rest with ``k_i`` and ``k_p`` swapped
  snaps a state 40 ulps beyond ``f_c`` onto the boundary (:func:`._kernel_check.rest_rounding_row`);
* the closed-form slips of the ``R̂`` intervals without ``f_c`` leave the kernel's trajectory at ``f_c ≠ 1``;
* ``V ≤ c₂|x|²_𝒜`` checked with ``2c₂``, ``V/2``, ``2c₂`` in its exact re-decision, or without the points
  near 𝒜, no longer catches the self-test's ``c2 near 𝒜``;
* ``V̂`` nonincreasing without the ``R̂`` intervals that end at an event no longer catches ``k4 to an event``.

Each mutant is the real source with one replacement, loaded as a module and put in place of the original.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from symbolic_friction._crosscheck import _kernel_check, _selftest, lemma3
from symbolic_friction._crosscheck._claims import Claims

from .test_kernel_check import _load, failing, mutate_kernel
from .test_selftest import PROOFS


def _lemma3_mutant(old: str, new: str):
    return _load("symbolic_friction._crosscheck.lemma3_mut", Path(lemma3.__file__), [(old, new)])


def _caught(results, prop: str) -> bool:
    """The self-test's rule: a failing property with a counterexample that exact arithmetic does not refute."""
    return any(r.id == prop and not r.passed and r.counterexample is not None and r.counterexample.exact is not False
               for r in results)


@pytest.fixture(scope="module")
def certs():
    return {case: _selftest._at_coulomb_level(_selftest.table_i_certificates(PROOFS)[case], _selftest.F_C_OF_CASE.get(case, 1))
            for case in "ab"}


# -- the kernel ----------------------------------------------------------------------------------------------


def test_the_two_exact_rows_hold():
    assert _kernel_check.graze_row().ok and _kernel_check.rest_rounding_row().ok


@pytest.mark.parametrize("flow", [
    [("slack = grow * (max(u2_prev, u2_next) + extra)", "slack = grow * max(u2_prev, u2_next)")],
    [("extra = grow * min(m4 * r_p,", "extra = 0.0 * min(m4 * r_p,")],
], ids=["cell bound", "fast table"])
def test_a_scan_bound_without_its_fourth_order_term_misses_the_graze(monkeypatch, flow):
    mutate_kernel(monkeypatch, flow=flow)
    bad = failing(_kernel_check.kernel_rows())
    assert len(bad) == 1 and bad[0].scenario.startswith("graze"), bad
    assert "first event (t, mode before) is None" in bad[0].detail


def test_the_rounding_tolerance_with_k_i_and_k_p_swapped_fails_the_row_at_rest(monkeypatch):
    mutate_kernel(monkeypatch, kernel=[("K[I_GAIN_KI] * abs(float(z0[0])) + K[I_GAIN_KP] * abs(float(z0[1]))",
                                        "K[I_GAIN_KP] * abs(float(z0[0])) + K[I_GAIN_KI] * abs(float(z0[1]))")])
    bad = failing(_kernel_check.kernel_rows())
    assert len(bad) == 1 and bad[0].scenario.startswith("at rest") and "starts in mode 0" in bad[0].detail


def test_the_row_at_rest_lies_between_the_two_tolerances():
    """Its exact ``φ − f_c`` exceeds the kernel's tolerance (8 ulps of ``k_i|e_i| + k_p|s|``, plus 4 of ``f_c``)
    with the rounding of ``φ`` to spare, and is below the tolerance with ``k_i`` and ``k_p`` swapped."""
    from fractions import Fraction

    from symbolic_friction._model.parameters import Parameters

    ulps, s_rel = _kernel_check.REST
    p = Parameters(**_kernel_check.GRAZE)
    f_c, eps = float(p.f_c), 2.0**-52
    s = s_rel * f_c
    e_i = -(f_c * (1 + ulps * eps) + float(p.k_p) * s) / float(p.k_i)
    gap = float(-p.k_i * Fraction(e_i) - p.k_p * Fraction(s) - p.f_c)
    right = 8 * eps * (float(p.k_i) * abs(e_i) + float(p.k_p) * s) + 4 * eps * f_c
    swapped = 8 * eps * (float(p.k_p) * abs(e_i) + float(p.k_i) * s) + 4 * eps * f_c
    assert 2 * right < gap and 2 * gap < swapped, (right, gap, swapped)


# -- the closed-form slips of the R̂ intervals ----------------------------------------------------------------


def test_slip_points_without_f_c_fail_every_scenario_at_f_c_not_1(monkeypatch):
    mutant = _lemma3_mutant("star[:, 1] = k * a.f_c", "star[:, 1] = k")
    monkeypatch.setattr(lemma3, "slip_points", mutant.slip_points)
    bad = failing(_kernel_check.kernel_rows())
    assert len(bad) == 6 and not any(r.scenario.startswith("f_c=1,") for r in bad)
    assert all("closed-form slip" in r.detail for r in bad)


# -- V ≤ c₂|x|²_𝒜 near 𝒜 -------------------------------------------------------------------------------------


def test_the_near_attractor_variant_is_caught_and_confirmed_exactly(certs):
    for case, cert in certs.items():
        _, results = _selftest._near_attractor(cert, seed=0)
        assert _caught(results, "lemma3.V_upper"), case
        assert [r.id for r in results if not r.passed] == ["lemma3.V_upper"], case


@pytest.mark.parametrize("old, new", [
    ("rel = (c2 * a.d2 - a.V) / scale", "rel = (2 * c2 * a.d2 - a.V) / scale"),
    ("rel = (c2 * a.d2 - a.V) / scale", "rel = (c2 * a.d2 - a.V / 2) / scale"),
    ('not (V(params, xq) <= Fraction(certificate.exact["c2"]) *', 'not (V(params, xq) <= 2 * Fraction(certificate.exact["c2"]) *'),
    ("return Evaluation(rel, a.in_R & a.off_A, witness,", "return Evaluation(rel, a.in_R & a.far, witness,"),
], ids=["2 c2", "V/2", "exact 2 c2", "skips near A"])
def test_a_loosened_V_upper_misses_the_near_attractor_variant(monkeypatch, certs, old, new):
    mutant = _lemma3_mutant(old, new)
    monkeypatch.setattr(lemma3.VUpper, "check", mutant.VUpper.check)
    monkeypatch.setattr(lemma3.VUpper, "exact_violation", staticmethod(mutant.VUpper.exact_violation))
    for case, cert in certs.items():
        _, results = _selftest._near_attractor(cert, seed=0)
        assert not _caught(results, "lemma3.V_upper"), case


# -- V̂ nonincreasing up to an event ---------------------------------------------------------------------------


def test_intervals_in_R_hat_that_end_at_an_event_are_needed_to_catch_k4_to_an_event(monkeypatch, certs):
    k4 = {case: Claims.from_certificate(_selftest.wrong_variants(cert, 1.5)["k4"], label="k4") for case, cert in certs.items()}
    for claims in k4.values():
        assert _caught(_selftest._growth_run(claims, seed=0)[2], "lemma3.hatV_nonincreasing")
    mutant = _lemma3_mutant("run &= a.in_Rhat[:, :-1] | a.in_Rhat[:, 1:]", "run &= a.in_Rhat[:, :-1] & a.in_Rhat[:, 1:]")
    monkeypatch.setattr(lemma3, "rhat_intervals", mutant.rhat_intervals)
    for case, claims in k4.items():
        assert not _caught(_selftest._growth_run(claims, seed=0)[2], "lemma3.hatV_nonincreasing"), case
