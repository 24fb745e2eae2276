"""The checker refuses batches it cannot check."""

from __future__ import annotations

import numpy as np
import pytest

from symbolic_friction.errors import ParameterError
from symbolic_friction import Parameters
from symbolic_friction.errors import SimulationError
from symbolic_friction._crosscheck import Claims
from symbolic_friction._simulation import Trajectories
from symbolic_friction._crosscheck._checker import BatchChecker
from tests.crosscheck.helpers import _cert
from tests.crosscheck.helpers import _synthetic


def test_checker_rejects_other_gains():
    cl = Claims.from_certificate(_cert("a"))
    with pytest.raises(ParameterError, match="a checker for .* takes only those gains"):
        BatchChecker(Parameters.table_i("b"), [cl])
    chk = BatchChecker(Parameters.table_i("a"), [cl])
    pb = Parameters.table_i("b")
    b = _synthetic(pb, [0.0, 1.0], [[0.1, 0.0, 0.0], [0.1, 0.1, 0.0]], [0, 0])
    with pytest.raises(ParameterError, match="the batch was simulated with"):
        chk.add(b)


def test_malformed_batch():
    p = Parameters.table_i("a")
    z = np.zeros((1, 2, 3))
    ok = dict(
        params=p, method="synthetic", t=np.array([0.0, 1.0]), z=z, x=z, mode=np.zeros((1, 2)),
        event_t=np.zeros((1, 0)), event_x=np.zeros((1, 0, 3)), event_before=np.zeros((1, 0)),
        event_after=np.zeros((1, 0)), event_residual=np.zeros((1, 0)), n_events=np.zeros(1, int),
        status=np.array(["t_end reached"], dtype=object), t_stop=np.ones(1), z0=np.zeros((1, 3)), x0=np.zeros((1, 3)),
    )
    Trajectories(**ok)
    with pytest.raises(SimulationError, match="malformed trajectories: t has shape"):
        Trajectories(**{**ok, "t": np.zeros(3)})
    with pytest.raises(SimulationError, match="nondecreasing"):
        Trajectories(**{**ok, "t": np.array([1.0, 0.0])})
    chk = BatchChecker(p, [Claims.from_certificate(_cert("a"))])
    with pytest.raises(SimulationError, match="strictly increasing"):
        chk.add(Trajectories(**{**ok, "t": np.array([0.0, 0.0])}))
