"""claim1.cases: all eleven rows of the appendix table (Claim 1)."""

import dataclasses

import pytest
import sympy as sp

from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.claim1 import ROWS, Claim1Cases, StickBranch

g = G()


@pytest.fixture(scope="module")
def claim1():
    ob = Claim1Cases()
    return ob, ob.derive()


def _replace_row(subject, label, **changes):
    rows = tuple(dataclasses.replace(r, **changes) if r.label == label else r for r in subject.rows)
    return dataclasses.replace(subject, rows=rows)


def _row(subject, label):
    return next(r for r in subject.rows if r.label == label)


def test_claim1_holds_on_all_rows(claim1):
    ob, subject = claim1
    out = ob.verify(subject)
    assert out.holds, out.reason
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
    out = ob.verify(altered)
    assert out.holds is False
    assert out.reason.startswith("row (v)") and "not in SGN(0)" in out.reason


def test_wrong_stick_duration_row_vii_fails(claim1):
    ob, subject = claim1
    sb = subject.bar[0]
    br = _row(subject, "vii").stick[0]
    out = ob.verify(_replace_row(subject, "vii", stick=(dataclasses.replace(br, T=4 * g.f_c / sb),)))
    assert out.holds is False
    assert out.reason.startswith("row (vii)") and "w = 3" in out.reason


def test_negative_duration_fails(claim1):
    ob, subject = claim1
    sb = subject.bar[0]
    br = _row(subject, "vii").stick[0]
    out = ob.verify(_replace_row(subject, "vii", stick=(dataclasses.replace(br, T=-2 * g.f_c / sb),)))
    assert out.holds is False
    assert "not shown positive" in out.reason


def test_paper_V0_with_xi_v_fails(claim1):
    ob, subject = claim1
    V = dict(subject.V)
    V[0] = g.k_v / g.k_i * g.v**2
    out = ob.verify(dataclasses.replace(subject, V=V))
    assert out.holds is False
    assert out.reason.startswith("row (v)") and "V_0(ξ) = 0" in out.reason


def test_row_iii_with_k_minus_one_fails(claim1):
    ob, subject = claim1
    out = ob.verify(_replace_row(subject, "iii", k=-1))
    assert out.holds is False
    assert "row (iii): the paper's d^1ξ_v/dt^1(0) = 0 but f_-1 gives 2*f_c" in out.reason
    out = ob.verify(_replace_row(subject, "iii", k=-1, claims=()))
    assert out.holds is False
    assert "row (iii)" in out.reason and "has sign 1" in out.reason


def test_row_iii_with_stick_and_no_solution_fails(claim1):
    ob, subject = claim1
    out = ob.verify(_replace_row(subject, "iii", k=0))
    assert out.holds is False
    assert "0 explicit solutions given" in out.reason


def test_row_ix_mirror_with_k_one_fails(claim1):
    ob, subject = claim1
    out = ob.verify(_replace_row(subject, "ix", k=1, claims=()))
    assert out.holds is False
    assert "row (ix)" in out.reason and "not k = 1" in out.reason


def test_row_x_with_k_one_fails(claim1):
    ob, subject = claim1
    out = ob.verify(_replace_row(subject, "x", k=1))
    assert out.holds is False
    assert "row (x)" in out.reason


def test_row_xi_with_k_zero_fails(claim1):
    ob, subject = claim1
    out = ob.verify(_replace_row(subject, "xi", k=0))
    assert out.holds is False
    assert "row (xi)" in out.reason


def test_row_vi_wrong_branch_duration_fails(claim1):
    ob, subject = claim1
    sb, pb, _ = subject.bar
    row = _row(subject, "vi")
    branches = (row.stick[0], row.stick[1], dataclasses.replace(row.stick[2], T=(g.f_c - pb) / sb))
    out = ob.verify(_replace_row(subject, "vi", stick=branches))
    assert out.holds is False
    assert "row (vi)" in out.reason and "σ̄ < 0" in out.reason


def test_row_vi_unbounded_stick_with_moving_sigma_fails(claim1):
    ob, subject = claim1
    row = _row(subject, "vi")
    branches = (dataclasses.replace(row.stick[0], T=sp.oo), row.stick[1], row.stick[2])
    out = ob.verify(_replace_row(subject, "vi", stick=branches))
    assert out.holds is False
    assert "not constant on an unbounded stick" in out.reason


def test_wrong_stick_solution_fails(claim1):
    ob, subject = claim1
    sb, pb, _ = subject.bar
    br = _row(subject, "v").stick[0]
    wrong = sp.ImmutableMatrix([sb, pb - sb * subject.t, 0])
    out = ob.verify(_replace_row(subject, "v", stick=(dataclasses.replace(br, xi=wrong),)))
    assert out.holds is False
    assert "does not solve ξ' = f_0(ξ)" in out.reason


def test_wrong_stick_initial_condition_fails(claim1):
    ob, subject = claim1
    sb, pb, _ = subject.bar
    br = _row(subject, "iv").stick[0]
    wrong = sp.ImmutableMatrix([sb, pb + 1, 0])
    out = ob.verify(_replace_row(subject, "iv", stick=(StickBranch(None, wrong, br.T),)))
    assert out.holds is False
    assert "is not the initial condition" in out.reason


def test_paper_claim_altered_fails(claim1):
    ob, subject = claim1
    sb = subject.bar[0]
    out = ob.verify(_replace_row(subject, "iii", claims=((1, sp.Integer(0)), (2, -sb))))
    assert out.holds is False
    assert "the paper's d^2ξ_v/dt^2(0)" in out.reason


def test_dropped_row_leaves_a_gap(claim1):
    ob, subject = claim1
    out = ob.verify(dataclasses.replace(subject, rows=tuple(r for r in subject.rows if r.label != "vi")))
    assert out.holds is False
    assert "fall in 0 rows" in out.reason and "|φ| < f_c" in out.reason


def test_overlapping_rows_fail(claim1):
    ob, subject = claim1
    out = ob.verify(_replace_row(subject, "ii", phi=None))
    assert out.holds is False
    assert "fall in 2 rows" in out.reason


def test_flipped_friction_fails(claim1):
    ob, subject = claim1
    out = ob.verify(dataclasses.replace(subject, b=-subject.b))
    assert out.holds is False
    assert "is not the selection A x - b·(1)" in out.reason


def test_non_positive_rate_fails(claim1):
    ob, subject = claim1
    out = ob.verify(dataclasses.replace(subject, c=-subject.c))
    assert out.holds is False
    assert "not shown positive under Assumption 1" in out.reason


def test_wrong_V1_fails(claim1):
    ob, subject = claim1
    V = dict(subject.V)
    V[1] = V[1] + g.v**2
    out = ob.verify(dataclasses.replace(subject, V=V))
    assert out.holds is False
    assert out.reason.startswith("row (i)")


def test_bad_k_fails(claim1):
    ob, subject = claim1
    out = ob.verify(_replace_row(subject, "i", k=2))
    assert out.holds is False
    assert "k = 2 is not in {-1, 0, 1}" in out.reason
