"""The mode table: modes that disagree with the states are caught."""

from __future__ import annotations



from symbolic_friction import Parameters
from symbolic_friction._crosscheck import Claims
from symbolic_friction._crosscheck._checker import BatchChecker
from tests.crosscheck.helpers import _cert
from tests.crosscheck.helpers import _synthetic


def test_mode_inconsistent_with_state_is_caught():
    p = Parameters.table_i("a")
    cl = Claims.from_certificate(_cert("a"))
    b = _synthetic(p, [0.0, 1.0], [[0.0, 3.0, 1.0], [0.0, 3.0, -1.0]], [1, 1])  # mode +1 with v < 0
    chk = BatchChecker(p, [cl])
    chk.add(b, attractivity=False)
    r = {r.id: r for r in chk.results()[0]}["model.modes"]
    assert r.failures == 1 and r.counterexample.values["v"] == -1.0
