"""The sweep API: any Executor, order preserved, failures collected, progress on TTYs only."""

from __future__ import annotations

import io
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from fractions import Fraction as F

import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import InaccurateSolveError, ParameterError
from symbolic_friction._certify import certify_many, dumps, verify_certificate
from symbolic_friction._certify import sweep as sweep_module

GAINS = [
    Parameters(k_v=F(k_v), k_p=F(k_p), k_i=F(k_i))
    for k_v, k_p, k_i in [("6.4", 3, 4), ("1.5", "0.66", "0.08"), (3, 3, 1), ("0.1", 100, 9), (2, "1e5", "1e5"), (1, 1, "0.5")]
]


def _texts(items):
    return [dumps(item.certificate) for item in items]


def test_serial_sweep_returns_proved_certificates_in_input_order():
    items = certify_many(GAINS, progress=False)
    assert [item.index for item in items] == list(range(len(GAINS)))
    assert [item.params for item in items] == GAINS
    assert all(item.ok and item.error == "" for item in items)
    assert all(verify_certificate(item.certificate).proved for item in items)


@pytest.mark.parametrize("make_executor", [lambda: ThreadPoolExecutor(2), lambda: ProcessPoolExecutor(2)], ids=["threads", "processes"])
def test_any_executor_gives_the_same_bytes_as_serial(make_executor):
    serial = _texts(certify_many(GAINS, mode="feasible", progress=False))
    with make_executor() as executor:
        parallel = certify_many(GAINS, mode="feasible", executor=executor, chunksize=2, progress=False)
    assert _texts(parallel) == serial


def test_a_failing_gain_set_does_not_stop_the_sweep(monkeypatch):
    real = sweep_module.certify

    def flaky(params, *, mode, margin):
        if params.k_i == 9:
            raise InaccurateSolveError("CLARABEL returned status 'optimal_inaccurate'")
        return real(params, mode=mode, margin=margin)

    monkeypatch.setattr(sweep_module, "certify", flaky)
    items = certify_many(GAINS, progress=False)
    bad = [item for item in items if not item.ok]
    assert [item.index for item in bad] == [3]
    assert bad[0].certificate is None
    assert bad[0].error == "InaccurateSolveError: CLARABEL returned status 'optimal_inaccurate'"
    assert sum(item.ok for item in items) == len(GAINS) - 1


def test_progress_bar_only_when_asked_or_on_a_terminal():
    quiet = io.StringIO()
    certify_many(GAINS[:2], stream=quiet)  # StringIO is not a TTY
    assert quiet.getvalue() == ""
    loud = io.StringIO()
    certify_many(GAINS[:2], progress=True, stream=loud, chunksize=1)
    text = loud.getvalue()
    assert "certify (tightest)" in text and "2/2" in text and text.endswith("\n")  # drawn by tqdm


def test_invalid_sweep_arguments():
    with pytest.raises(ParameterError, match="chunksize must be a positive integer; got 0"):
        certify_many(GAINS, chunksize=0)
    with pytest.raises(ParameterError, match=r"gains\[1\] must be a Parameters instance; got tuple"):
        certify_many([GAINS[0], (3, 4, 6.4, 1)])
    with pytest.raises(ParameterError, match="mode must be one of"):
        certify_many(GAINS, mode="fast")


def test_empty_sweep():
    assert certify_many([], progress=False) == []
