"""One gain set's run: every trajectory is counted once and checked for every certificate."""

from __future__ import annotations

import numpy as np

from symbolic_friction import Parameters
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck._run import GroupRun
from tests.crosscheck.helpers import _cert


class _Bar:
    def __init__(self):
        self.n = 0

    def update(self, n):
        self.n += n


def test_evaluate_counts_and_checks_every_certificate():
    p = Parameters.table_i("b")
    claims = [Claims.from_certificate(_cert("b", m), label=m) for m in ("feasible", "tightest")]
    bar = _Bar()
    run = GroupRun(p, claims, T=30.0, samples=51, rtol=1e-8, theta=0.5, seed=0, chunk=7, bar=bar)
    ov = run.evaluate(np.array([[0.0, 3.0, 0.0]] * 10) * np.arange(1, 11)[:, None], "test")
    assert run.count == bar.n == 10 and ov.shape == (10,) and np.all(ov >= 1.0)
    for results in run.checker.results():
        assert next(r for r in results if r.id == "prop1.stability").trajectories == 10
