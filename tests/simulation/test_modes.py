"""Mode selection at v = 0: the appendix's table of Claim 1, rows (i)–(xi)."""

from __future__ import annotations

import itertools
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction._simulation._kernel import mode_after_slip
from symbolic_friction._simulation.modes import (
    TABLE,
    mode_at_rest,
    select_mode,
    table_row,
)

from symbolic_friction._reference import reference_table_mode

F_C = F(3, 2)

# One exact state per row, in (σ, φ, v), and the k the paper's table gives.
ROWS = {
    "i": ((F(-1), F(0), F(1, 3)), 1),
    "ii": ((F(-1), F_C + F(1, 7), F(0)), 1),
    "iii": ((F(1, 5), F_C, F(0)), 1),
    "iv": ((F(0), F_C, F(0)), 0),
    "v": ((F(-1, 5), F_C, F(0)), 0),
    "vi": ((F(2), F(1, 2), F(0)), 0),
    "vii": ((F(1, 5), -F_C, F(0)), 0),
    "viii": ((F(0), -F_C, F(0)), 0),
    "ix": ((F(-1, 5), -F_C, F(0)), -1),
    "x": ((F(1), -F_C - F(1, 7), F(0)), -1),
    "xi": ((F(1), F(0), F(-1, 3)), -1),
}


def test_table_lists_the_papers_eleven_rows_in_order():
    assert [row for row, _, _ in TABLE] == list(ROWS)
    assert [k for _, _, k in TABLE] == [k for _, k in ROWS.values()]


@pytest.mark.parametrize("row", list(ROWS))
def test_each_row_is_recognised_exactly_and_gives_the_papers_mode(row):
    (sigma, phi, v), k = ROWS[row]
    assert table_row(sigma, phi, v, F_C) == row
    assert select_mode(sigma, phi, v, F_C) == k
    assert reference_table_mode(sigma, phi, v, F_C) == k


def test_boundaries_are_exact_for_fractions():
    # one part in 10^30 off the boundary is a different row
    tiny = F(1, 10**30)
    assert table_row(F(1), F_C - tiny, F(0), F_C) == "vi"
    assert table_row(F(1), F_C + tiny, F(0), F_C) == "ii"
    assert table_row(F(-1), -F_C + tiny, F(0), F_C) == "vi"
    assert table_row(F(-1), -F_C - tiny, F(0), F_C) == "x"
    assert table_row(tiny, F_C, F(0), F_C) == "iii"
    assert table_row(-tiny, -F_C, F(0), F_C) == "ix"


def test_agrees_with_the_independent_reference_table_on_a_grid():
    values = [F(-2), F(-1), F(0), F(1), F(2)]
    phis = [F_C * c for c in (F(-2), F(-1), F(-1, 2), F(0), F(1, 2), F(1), F(2))]
    for sigma, phi, v in itertools.product(values, phis, [F(-1), F(0), F(1)]):
        assert select_mode(sigma, phi, v, F_C) == reference_table_mode(sigma, phi, v, F_C), (sigma, phi, v)


def test_mode_at_rest_without_tolerance_is_the_exact_table():
    for (sigma, phi, v), k in ROWS.values():
        if v != 0:
            continue
        base, offset, mode = mode_at_rest(sigma, 0, phi, F_C, 0)
        assert mode == k
        assert base * F_C + offset == phi


def test_mode_at_rest_keeps_the_offset_exact_relative_to_its_boundary():
    # φ = f_c - 1e-300 is not representable as a float sum, but as (base=1, offset=-1e-300) it is
    base, offset, mode = mode_at_rest(1.0, 1, -1e-300, 1.0, 0.0)
    assert (base, offset, mode) == (1, -1e-300, 0)  # row (vi): a stick, no slip
    base, offset, mode = mode_at_rest(1.0, -1, 1e-300, 1.0, 0.0)
    assert (base, offset, mode) == (-1, 1e-300, 0)


@pytest.mark.parametrize(
    "sigma, expected",
    [(2.0, 1), (0.0, 0), (-2.0, 0)],
)
def test_within_tolerance_of_plus_f_c_sigma_decides_as_rows_iii_iv_v(sigma, expected):
    for offset in (-3e-16, 0.0, 3e-16):
        base, off, mode = mode_at_rest(sigma, 1, offset, 1.0, 4e-16)
        assert (base, off, mode) == (1, 0.0, expected)
    # just outside the tolerance the table decides by φ again
    assert mode_at_rest(sigma, 1, -5e-16, 1.0, 4e-16)[2] == 0
    assert mode_at_rest(sigma, 1, 5e-16, 1.0, 4e-16)[2] == 1


@pytest.mark.parametrize(
    "sigma, expected",
    [(2.0, 0), (0.0, 0), (-2.0, -1)],
)
def test_within_tolerance_of_minus_f_c_sigma_decides_as_rows_vii_viii_ix(sigma, expected):
    base, off, mode = mode_at_rest(sigma, 0, -1.0 + 1e-16, 1.0, 1e-15)
    assert (base, off, mode) == (-1, 0.0, expected)


def test_the_rounding_of_adding_f_c_is_part_of_the_tolerance():
    # φ given as 0·f_c + offset: the sum's own rounding counts even with tol = 0
    f_c = 1e6
    # one ulp below f_c = 1e6 is within the rounding of any φ computed near 1e6
    assert mode_at_rest(1.0, 0, np.nextafter(f_c, 0.0), f_c, 0.0) == (1, 0.0, 1)
    # -f_c + 2 f_c (+ a sub-ulp amount) is +f_c: the sum's rounding is tolerated
    assert mode_at_rest(-1.0, -1, 2 * f_c + 1e-10, f_c, 0.0) == (1, 0.0, 0)
    # far enough away it is not
    assert mode_at_rest(1.0, 0, f_c - 1e-6, f_c, 0.0) == (0, f_c - 1e-6, 0)


def test_mode_after_slip_clamps_the_wrong_side_then_decides_by_sigma():
    # a slip with v > 0 can only end with φ ≤ f_c: a positive offset is rounding
    assert mode_after_slip(1.0, 1e-17, 1, 1.0, 0.0) == (1, 0.0, 1)  # grazing, the slip goes on
    assert mode_after_slip(-1.0, 1e-17, 1, 1.0, 0.0) == (1, 0.0, 0)  # row (v): stick
    assert mode_after_slip(-1.0, -1e-17, -1, 1.0, 0.0) == (-1, 0.0, -1)
    # a genuine end of slip: below f_c by more than rounding is a stick, below -f_c a reversal
    assert mode_after_slip(-1.0, -0.5, 1, 1.0, 1e-15) == (1, -0.5, 0)
    assert mode_after_slip(-1.0, -2.5, 1, 1.0, 1e-15) == (1, -2.5, -1)
    assert mode_after_slip(1.0, 2.5, -1, 1.0, 1e-15) == (-1, 2.5, 1)
