"""claim1.cases: all eleven rows of the appendix table (Claim 1)."""

import dataclasses

import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.claim1 import ROWS, Claim1Cases, StickBranch

from ._helpers import assert_fails, assert_holds, obligation_fixture, replace_item, replace_key

g = G()
claim1 = obligation_fixture(Claim1Cases)


def _replace_row(subject, label, **changes):
    return replace_item(subject, "rows", "label", label, **changes)


def _row(subject, label):
    return next(r for r in subject.rows if r.label == label)


def test_claim1_holds_on_all_rows(claim1):
    ob, subject = claim1
    out = assert_holds(ob, subject)
    assert tuple(r.label for r in subject.rows) == ROWS
    shown = {label.split("}")[0].split("(")[1].rstrip(")") for label, _ in out.details}
    assert shown == set(ROWS)  # every row, (vi)-(xi) included, produced its own evidence


def test_row_v_duration_is_the_papers(claim1):
    ob, subject = claim1
    sb = subject.bar[0]
    assert _row(subject, "v").stick[0].T == -2 * g.f_c / sb
    assert _row(subject, "vii").stick[0].T == 2 * g.f_c / sb
    assert dict(_row(subject, "iii").claims)[2] == sb


def test_wrong_stick_duration_row_v_fails(claim1):
    ob, subject = claim1
    sb = subject.bar[0]
    br = _row(subject, "v").stick[0]
    altered = _replace_row(subject, "v", stick=(dataclasses.replace(br, T=-3 * g.f_c / sb),))
    out = assert_fails(ob, altered, "not in SGN(0)")
    assert out.reason.startswith("row (v)")


def test_wrong_stick_duration_row_vii_fails(claim1):
    ob, subject = claim1
    sb = subject.bar[0]
    br = _row(subject, "vii").stick[0]
    out = assert_fails(ob, _replace_row(subject, "vii", stick=(dataclasses.replace(br, T=4 * g.f_c / sb),)), "w = 3")
    assert out.reason.startswith("row (vii)")


def test_negative_duration_fails(claim1):
    ob, subject = claim1
    sb = subject.bar[0]
    br = _row(subject, "vii").stick[0]
    assert_fails(ob, _replace_row(subject, "vii", stick=(dataclasses.replace(br, T=-2 * g.f_c / sb),)), "not shown positive")


def test_paper_V0_with_xi_v_fails(claim1):
    ob, subject = claim1
    out = assert_fails(ob, replace_key(subject, "V", 0, g.k_v / g.k_i * g.v**2), "V_0(ξ) = 0")
    assert out.reason.startswith("row (v)")


def test_row_iii_with_k_minus_one_fails(claim1):
    ob, subject = claim1
    assert_fails(ob, _replace_row(subject, "iii", k=-1), "row (iii): the paper's d^1ξ_v/dt^1(0) = 0 but f_-1 gives 2*f_c")
    assert_fails(ob, _replace_row(subject, "iii", k=-1, claims=()), "row (iii)", "has sign 1")


def test_row_iii_with_stick_and_no_solution_fails(claim1):
    ob, subject = claim1
    assert_fails(ob, _replace_row(subject, "iii", k=0), "0 explicit solutions given")


def test_row_ix_mirror_with_k_one_fails(claim1):
    ob, subject = claim1
    assert_fails(ob, _replace_row(subject, "ix", k=1, claims=()), "row (ix)", "not k = 1")


def test_row_x_with_k_one_fails(claim1):
    ob, subject = claim1
    assert_fails(ob, _replace_row(subject, "x", k=1), "row (x)")


def test_row_xi_with_k_zero_fails(claim1):
    ob, subject = claim1
    assert_fails(ob, _replace_row(subject, "xi", k=0), "row (xi)")


def test_row_vi_wrong_branch_duration_fails(claim1):
    ob, subject = claim1
    sb, pb, _ = subject.bar
    row = _row(subject, "vi")
    branches = (row.stick[0], row.stick[1], dataclasses.replace(row.stick[2], T=(g.f_c - pb) / sb))
    assert_fails(ob, _replace_row(subject, "vi", stick=branches), "row (vi)", "σ̄ < 0")


def test_row_vi_unbounded_stick_with_moving_sigma_fails(claim1):
    ob, subject = claim1
    row = _row(subject, "vi")
    branches = (dataclasses.replace(row.stick[0], T=sp.oo), row.stick[1], row.stick[2])
    assert_fails(ob, _replace_row(subject, "vi", stick=branches), "not constant on an unbounded stick")


def test_wrong_stick_solution_fails(claim1):
    ob, subject = claim1
    sb, pb, _ = subject.bar
    br = _row(subject, "v").stick[0]
    wrong = sp.ImmutableMatrix([sb, pb - sb * subject.t, 0])
    assert_fails(ob, _replace_row(subject, "v", stick=(dataclasses.replace(br, xi=wrong),)), "does not solve ξ' = f_0(ξ)")


def test_wrong_stick_initial_condition_fails(claim1):
    ob, subject = claim1
    sb, pb, _ = subject.bar
    br = _row(subject, "iv").stick[0]
    wrong = sp.ImmutableMatrix([sb, pb + 1, 0])
    assert_fails(ob, _replace_row(subject, "iv", stick=(StickBranch(None, wrong, br.T),)), "is not the initial condition")


def test_paper_claim_altered_fails(claim1):
    ob, subject = claim1
    sb = subject.bar[0]
    assert_fails(ob, _replace_row(subject, "iii", claims=((1, sp.Integer(0)), (2, -sb))), "the paper's d^2ξ_v/dt^2(0)")


def test_dropped_row_leaves_a_gap(claim1):
    ob, subject = claim1
    assert_fails(
        ob, dataclasses.replace(subject, rows=tuple(r for r in subject.rows if r.label != "vi")), "fall in 0 rows", "|φ| < f_c"
    )


def test_overlapping_rows_fail(claim1):
    ob, subject = claim1
    assert_fails(ob, _replace_row(subject, "ii", phi=None), "fall in 2 rows")


def test_flipped_friction_fails(claim1):
    ob, subject = claim1
    assert_fails(ob, dataclasses.replace(subject, b=-subject.b), "is not the selection A x - b·(1)")


def test_non_positive_rate_fails(claim1):
    ob, subject = claim1
    assert_fails(ob, dataclasses.replace(subject, c=-subject.c), "not shown positive under Assumption 1")


def test_wrong_V1_fails(claim1):
    ob, subject = claim1
    out = assert_fails(ob, replace_key(subject, "V", 1, subject.V[1] + g.v**2))
    assert out.reason.startswith("row (i)")


def test_bad_k_fails(claim1):
    ob, subject = claim1
    assert_fails(ob, _replace_row(subject, "i", k=2), "k = 2 is not in {-1, 0, 1}")
