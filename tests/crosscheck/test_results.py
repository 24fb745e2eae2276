"""The tally: the worst slack, the failure count and a stamped counterexample."""

from __future__ import annotations

import numpy as np

from symbolic_friction._crosscheck import PROPERTIES
from symbolic_friction._crosscheck._results import Counterexample, Tally


def _cx(i):
    return Counterexample(property="prop1.stability", certificate="", trajectory=i, source="s", z0=(0, 0, 0),
                          x0=(0, 0, 0), t=1.0, t_start=None, x=(0, 0, 0), values={}, relative_slack=-1.0)


def test_tally_keeps_the_worst_violation_with_its_run_wide_index():
    prop = next(p for p in PROPERTIES if p.id == "prop1.stability")
    t = Tally(prop, "cert", 1e-8)
    t.add(np.array([[0.1, -0.5], [0.2, 0.3]]), np.ones((2, 2), bool), lambda idx: _cx(idx[0]), offset=10)
    t.add(np.array([[-0.1]]), np.ones((1, 1), bool), lambda idx: _cx(idx[0]), offset=12)
    r = t.result()
    assert (r.failures, r.samples, r.trajectories, r.worst_margin) == (2, 5, 3, -0.5)
    cx = r.counterexample
    assert cx.trajectory == 10 and cx.certificate == "cert" and cx.paper == prop.paper
    assert cx.values["tolerance_relative"] == 1e-8 and cx.to_dict()["inequality"] == prop.statement
