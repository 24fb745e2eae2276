"""The k-conditions of Lemma 3 as data (symbolic_friction._model.kconditions)."""

from __future__ import annotations

import random
from fractions import Fraction as F

import pytest
import sympy as sp

from symbolic_friction._infra.errors import CertificateError, InvalidNumberError, NonFiniteError
from symbolic_friction._model.kconditions import CONDITION_NAMES, Condition, check_k_conditions, k_conditions

# case (a) of Table I and constants that satisfy every condition:
# k_i/k_v = 5/8, so k3 = 2 > 5/8·1 and > k2 = 1; k4 = 5 > 5/4, > 3·1, > 2²/1
CASE_A = (F(3), F(4), F(32, 5))
GOOD = (F(1), F(1), F(2), F(5))


def test_names_and_order():
    conds = k_conditions(*CASE_A, *GOOD)
    assert tuple(c.name for c in conds) == CONDITION_NAMES
    assert [c.kind for c in conds] == ["positivity"] * 4 + ["derivative"] * 4 + ["definiteness"]
    assert all(c.strict for c in conds)


def test_satisfied_with_fractions():
    conds = check_k_conditions(*CASE_A, *GOOD)
    assert all(c.holds() for c in conds)
    assert conds[4].rhs == F(5, 8)  # (k_i/k_v)·k1, exact
    assert conds[8].lhs == 5 and conds[8].rhs == 4


def test_ints_stay_exact():
    conds = k_conditions(3, 4, 6, 1, 1, 2, 5)
    assert isinstance(conds[4].rhs, F) and conds[4].rhs == F(2, 3)


# one violation per condition, at equality, so strictness is also tested
VIOLATIONS = [
    ((F(0), F(1), F(2), F(5)), "k1 > 0: 0 > 0 is false"),
    ((F(1), F(0), F(2), F(5)), "k2 > 0: 0 > 0 is false"),
    ((F(1), F(1), F(-1), F(5)), "k3 > 0: -1 > 0 is false"),
    ((F(1), F(1), F(2), F(-1)), "k4 > 0: -1 > 0 is false"),
    ((F(4), F(1, 2), F(5, 2), F(10)), r"k3 > \(k_i/k_v\)·k1: 5/2 > 5/2 is false"),
    ((F(1), F(2), F(2), F(7)), "k3 > k2: 2 > 2 is false"),
    ((F(1), F(1), F(8), F(5)), r"k4 > \(k_i/k_v\)·k3: 5 > 5 is false"),
    ((F(1), F(2), F(3), F(6)), "k4 > k_p·k2: 6 > 6 is false"),
    ((F(1), F(1), F(2), F(4)), "k1·k4 > k3²: 4 > 4 is false"),
]


@pytest.mark.parametrize("ks, message", VIOLATIONS, ids=CONDITION_NAMES)
def test_each_violation_is_named_with_its_numbers(ks, message):
    with pytest.raises(CertificateError, match=message):
        check_k_conditions(*CASE_A, *ks)


def test_every_violated_condition_is_listed():
    with pytest.raises(CertificateError, match=r"k3 > \(k_i/k_v\)·k1: 1/2 > 5/8 is false; k3 > k2: 1/2 > 3/5 is false"):
        check_k_conditions(3, 4, "6.4", 1, "3/5", "1/2", 8)


def test_bad_numbers():
    with pytest.raises(NonFiniteError, match="k3 must be finite"):
        check_k_conditions(*CASE_A, 1, 1, "nan", 5)
    with pytest.raises(InvalidNumberError, match="k1 must be a decimal"):
        check_k_conditions(*CASE_A, "one", 1, 2, 5)
    with pytest.raises(InvalidNumberError, match="k_v must be nonzero: it divides in k3 > \\(k_i/k_v\\)·k1; got k_v = 0"):
        check_k_conditions(3, 4, 0, *GOOD)


def test_holds_refuses_inexact_sides():
    cond = k_conditions(3.0, 4.0, 6.4, 1.0, 1.0, 2.0, 5.0)[5]
    with pytest.raises(InvalidNumberError, match="'k3 > k2' can only be decided for exact rationals; its lhs is float 2.0"):
        cond.holds()
    k = sp.symbols("k_1:5", positive=True)
    sym = k_conditions(*sp.symbols("k_p k_i k_v", positive=True), *k)
    with pytest.raises(InvalidNumberError, match="its lhs is Symbol k_1"):
        sym[0].holds()
    assert sym[0].describe() == "k1 > 0: k_1 > 0"


def test_symbolic_sides():
    k_p, k_i, k_v = sp.symbols("k_p k_i k_v", positive=True)
    k = sp.symbols("k_1:5", positive=True)
    conds = k_conditions(k_p, k_i, k_v, *k)
    assert sp.simplify(conds[4].margin - (k[2] - k_i * k[0] / k_v)) == 0
    assert sp.expand(conds[8].margin - (k[0] * k[3] - k[2] ** 2)) == 0


def test_unknown_name_is_rejected():
    with pytest.raises(ValueError, match="unknown k-condition name 'k5 > 0'"):
        Condition(name="k5 > 0", lhs=1, rhs=0, kind="positivity", source="-")


def test_agrees_with_the_papers_max_form():
    """k₃ > max{(k_i/k_v)k₁, k₂}, k₄ > max{(k_i/k_v)k₃, k_p k₂, k₃²/k₁} with k_j > 0, on random rationals."""
    rng = random.Random(20240611)
    agree = 0
    for _ in range(500):
        k_p, k_i, k_v = (F(rng.randint(1, 40), rng.randint(1, 40)) for _ in range(3))
        ks = [F(rng.randint(1, 60), rng.randint(1, 12)) for _ in range(4)]
        k1, k2, k3, k4 = ks
        paper = k3 > max(k_i / k_v * k1, k2) and k4 > max(k_i / k_v * k3, k_p * k2, k3**2 / k1)
        ours = all(c.holds() for c in k_conditions(k_p, k_i, k_v, *ks))
        assert paper == ours
        agree += paper
    assert 0 < agree < 500  # both outcomes were exercised
