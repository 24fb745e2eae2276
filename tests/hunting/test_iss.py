"""A hunting cycle against Corollary 1's empirical ISS gain."""

from __future__ import annotations

from fractions import Fraction as F

from symbolic_friction import Parameters
from symbolic_friction._hunting import find_cycles
from symbolic_friction._hunting._iss import IssComparison, iss_comparison
from symbolic_friction._hunting._report import with_static


def test_the_case_a_cycle_lies_within_the_worst_found_gain():
    (c,) = find_cycles(with_static(Parameters.table_i("a"), F(6, 5)), general=False)
    cmp = iss_comparison(c, horizon=60.0)
    assert cmp.rho == 0.2 and cmp.amplitude == c.amplitude_distance
    assert set(cmp.gamma) == {"greedy", "stribeck", "rest point"}
    assert cmp.gamma["rest point"] == 0.2 / 4  # ρ f_c/k_i, exact
    assert cmp.within and cmp.worst_found > cmp.amplitude > 0
    assert "within the worst found" in cmp.describe()


def test_the_comparison_can_fail():
    cmp = IssComparison(rho=0.2, amplitude=1.0, gamma={"greedy": 0.5, "stribeck": 0.1, "rest point": 0.05})
    assert not cmp.within and "ABOVE the worst found" in cmp.describe()
