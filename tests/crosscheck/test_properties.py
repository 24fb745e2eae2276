"""The property contract: every property of the paper's list can fail, on a wrong certificate or a wrong trajectory.

Each property is handed the same exact trajectories twice: with the proved
certificate it holds, with one wrong constant it fails, and its witness is a
counterexample with a negative slack.  Properties of the solutions alone (the
mode table, the Remark after Lemma 2, attractivity, ``V`` nonincreasing) are
broken through hand-made wrong trajectories in their own test modules; here
the mode table's event check is broken too.
"""

from __future__ import annotations

import dataclasses
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._crosscheck import PROPERTIES, Claims
from symbolic_friction._crosscheck._property import DEFAULT_RTOL, Evaluation, Property
from symbolic_friction._crosscheck._run import sample_times
from symbolic_friction._simulation.batch import simulate_batch
from tests.crosscheck.helpers import _cert, _synthetic

PACKAGE = Path(__file__).resolve().parents[2] / "symbolic_friction" / "_crosscheck"


@pytest.fixture(scope="module")
def batch():
    p = Parameters.table_i("a")
    rng = np.random.default_rng(11)
    X0 = rng.normal(size=(200, 3)) * np.array([1.0, 3.0, 2.0])
    return simulate_batch(p, x_to_z(p, X0), 60.0, t_eval=sample_times(60.0, 201))


def _prop(pid: str) -> Property:
    return next(p for p in PROPERTIES if p.id == pid)


def _worst(ev: Evaluation) -> tuple[int, int]:
    r = np.where(ev.mask, ev.slack, np.inf)
    return tuple(int(i) for i in np.unravel_index(int(np.argmin(r)), r.shape))


WRONG = [
    ("lemma2.decrease", lambda c: {"c": 10 * c.c}),
    ("lemma2.lower_bound", lambda c: {"c1": 3 * c.c1}),
    ("lemma3.V_upper", lambda c: {"c2": c.c2 / 3}),
    ("lemma3.hatV_lower", lambda c: {"c1_hat": c.c2_hat}),
    ("lemma3.hatV_upper", lambda c: {"c2_hat": c.c1_hat}),
    ("prop1.stability", lambda c: {"overshoot_bound": "1.01"}),
]


@pytest.mark.parametrize("pid, change", WRONG, ids=[w[0] for w in WRONG])
def test_a_wrong_certificate_fails_the_property_it_breaks(batch, pid, change):
    cert = _cert("a")
    prop = _prop(pid)
    good = prop.check(batch, Claims.from_certificate(cert))
    assert good.failures(DEFAULT_RTOL) == 0 and np.count_nonzero(good.mask) > 0
    wrong = Claims.from_certificate(dataclasses.replace(cert, **change(cert)), label="wrong")
    ev = prop.check(batch, wrong)
    assert ev.failures(DEFAULT_RTOL) > 0, pid
    cx = ev.witness(_worst(ev))
    assert cx.property == pid and cx.relative_slack < -DEFAULT_RTOL
    if pid in ("lemma2.lower_bound", "lemma3.V_upper", "lemma3.hatV_lower", "lemma3.hatV_upper"):
        assert cx.exact is True  # re-decided in rational arithmetic at the float state


def test_an_event_that_is_not_a_zero_of_v_fails_the_mode_table():
    p = Parameters.table_i("a")
    b = _synthetic(p, [0.0, 2.0], [[0.0, 3.0, 1.0], [0.0, 1.0, 0.0]], [1, 0],
                   ev_t=[1.0], ev_x=[[0.0, 1.0, 0.0]], before=[1], after=[0], residual=[0.5])
    ev = _prop("model.modes").check(b, None)
    assert ev.failures(DEFAULT_RTOL) == 1
    cx = ev.more[0].witness((0, 0))
    assert cx.values["v_at_event_time"] == 0.5 and cx.t == 1.0


def test_every_property_states_its_paper_reference():
    ids = [p.id for p in PROPERTIES]
    assert len(ids) == len(set(ids)) == 11
    for p in PROPERTIES:
        assert isinstance(p, Property) and p.paper and p.statement
        assert p.id.split(".")[0] in ("lemma2", "lemma3", "prop1", "remark", "model")


def test_no_cross_check_module_is_over_400_lines():
    for path in PACKAGE.glob("*.py"):
        n = len(path.read_text(encoding="utf-8").splitlines())
        assert n <= 400, f"{path.name}: {n} lines"


def test_tests_mirror_the_package():
    here = Path(__file__).resolve().parent
    for path in PACKAGE.glob("*.py"):
        if path.name == "__init__.py":
            continue
        name = path.stem.lstrip("_")
        assert (here / f"test_{name}.py").exists(), f"no tests/crosscheck/test_{name}.py for {path.name}"
