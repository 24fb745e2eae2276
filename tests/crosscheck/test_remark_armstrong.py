"""The Remark after Lemma 2: |σ| growing between stick phases is caught."""

from __future__ import annotations



from symbolic_friction import Parameters
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck._checker import BatchChecker
from tests.crosscheck.helpers import _cert
from tests.crosscheck.helpers import _synthetic


def test_sigma_growing_between_stick_phases_is_caught():
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    # stick from t=0 with σ=-0.1, slip, stick again at t=2 with σ=0.3 (|σ| grew)
    b = _synthetic(
        p, [0.0, 0.5, 1.5, 2.5],
        [[-0.1, 0.0, 0.0], [-0.1, -0.05, 0.0], [-0.05, -1.2, -0.3], [0.3, -0.5, 0.0]],
        [0, 0, -1, 0],
        ev_t=[1.0, 2.0], ev_x=[[-0.1, -1.0, 0.0], [0.3, -0.5, 0.0]], before=[0, -1], after=[-1, 0],
    )
    chk = BatchChecker(p, [cl])
    chk.add(b, attractivity=False)
    r = {r.id: r for r in chk.results()[0]}["remark.stick_sigma"]
    assert r.failures == 1
    assert r.counterexample.values["sigma_next_stick"] == 0.3
    assert r.counterexample.values["sigma_previous_stick"] == -0.1
