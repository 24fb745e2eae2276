"""The property contract itself: an Evaluation counts violations, and NaN never hides one."""

from __future__ import annotations

import numpy as np
import pytest

from symbolic_friction._crosscheck._property import Evaluation, Property


def test_failures_count_below_minus_rtol_only_where_the_mask_holds():
    slack = np.array([[-1.0, -1e-9, 0.5, -2.0]])
    mask = np.array([[True, True, True, False]])
    ev = Evaluation(slack, mask, lambda idx: None)
    assert ev.failures(1e-8) == 1
    assert Evaluation(np.array([[np.nan]]), np.array([[True]]), lambda idx: None).failures(1e-8) == 1
    nested = Evaluation(slack, mask, lambda idx: None, more=(ev,))
    assert nested.failures(1e-8) == 2


def test_a_property_must_implement_check():
    class Incomplete(Property):
        id, paper, statement = "x.y", "nowhere", "nothing"

    with pytest.raises(TypeError):
        Incomplete()
