"""The decay fit of |x(t)|_𝒜."""

from __future__ import annotations

import pytest

from symbolic_friction import Parameters
from symbolic_friction._crosscheck import decay_fit


def test_decay_is_a_power_law_in_case_a_and_exponential_in_case_b():
    fa = decay_fit(Parameters.table_i("a"), trajectories=6, horizon=1000.0)
    fb = decay_fit(Parameters.table_i("b"), trajectories=6, horizon=1000.0)
    assert fa.verdict == "power law" and 0.5 < fa.power_exponent < 2.0 and fa.stick_phases >= 3
    assert fb.verdict == "exponential"
    assert fb.exponential_rate == pytest.approx(0.2, rel=0.05)  # the slowest root of case (b)
    assert "power law" in fa.describe()
