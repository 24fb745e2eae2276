"""``_simulation/_radau.py``: scipy's Radau with its linear solves made by LAPACK directly.

The binding: on the package's methods that run Radau (``regularized``, ``ivp-events`` with
``integrator="Radau"``, the event method's fallback) the class gives scipy's ``Radau`` results bit for bit, and a
solve that differs (a mutant below) is caught by the same comparison.
"""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from scipy.integrate import Radau as ScipyRadau
from scipy.integrate import solve_ivp
from scipy.linalg import lu_factor, lu_solve

import symbolic_friction._simulation._radau as fast
from symbolic_friction import Parameters
from symbolic_friction._simulation import IvpEvents, Regularized, simulate
from symbolic_friction._simulation.regularized import vector_field

CASE_A = Parameters.table_i("a")
# case (a) and a stiff gain set (roots -1e-3, -1, -1e3)
GAINS = [CASE_A, Parameters(k_v=F("1001.001"), k_p=F("1001.001"), k_i=1, f_c=1)]
METHODS = [Regularized(), Regularized(epsilon=1e-3, law="sat"), IvpEvents(integrator="Radau", rtol=1e-10, atol=1e-12)]


def _both(monkeypatch, params, method):
    """The run with the package's Radau, then with scipy's (the factory handing back the name)."""
    t = np.linspace(0.0, 4.0, 41)  # case (a): a slip and the stick it ends in (an event)
    ours = simulate(params, (0.0, 1.0, 0.0), 4.0, method=method, t_eval=t)
    with monkeypatch.context() as m:
        m.setattr(fast, "integrator", lambda name: name)
        theirs = simulate(params, (0.0, 1.0, 0.0), 4.0, method=method, t_eval=t)
    return ours, theirs


def _same(a, b) -> bool:
    return np.array_equal(a.t, b.t) and np.array_equal(a.z, b.z) and a.events == b.events and a.status == b.status


@pytest.mark.parametrize("method", METHODS, ids=["regularized-tanh", "regularized-sat", "ivp-events-radau"])
@pytest.mark.parametrize("params", GAINS, ids=["a", "stiff"])
def test_the_package_s_radau_is_scipy_s_bit_for_bit(monkeypatch, params, method):
    ours, theirs = _both(monkeypatch, params, method)
    assert _same(ours, theirs)


def test_it_is_the_solver_the_methods_hand_solve_ivp(monkeypatch):
    seen = []
    real = fast.Radau.__init__

    def spy(self, *args, **kwargs):
        real(self, *args, **kwargs)
        seen.append(self.solve_lu is fast.solve_lu)

    monkeypatch.setattr(fast.Radau, "__init__", spy)
    simulate(CASE_A, (0.0, 1.0, 0.0), 2.0, method=Regularized())
    simulate(CASE_A, (0.0, 1.0, 0.0), 2.0, method=IvpEvents(integrator="Radau"))
    assert len(seen) >= 2 and all(seen)
    assert fast.integrator("Radau") is fast.Radau and fast.integrator("BDF") == "BDF"


def test_a_wrong_solve_is_caught(monkeypatch):
    # the binding above, on a mutant: the transposed system solved instead (trans=1)
    def transposed(lu_and_piv, b):
        return lu_solve(lu_and_piv, b, trans=1, overwrite_b=True)

    monkeypatch.setattr(fast, "solve_lu", transposed)
    ours, theirs = _both(monkeypatch, CASE_A, Regularized())
    assert not _same(ours, theirs)


def test_solve_lu_is_lu_solve_and_refuses_what_it_refuses():
    rng = np.random.default_rng(3)
    for dtype in (float, complex):
        for _ in range(200):
            a = rng.normal(size=(3, 3)) + 3 * np.eye(3)
            b = rng.normal(size=3)
            if dtype is complex:
                a, b = a + 1j * rng.normal(size=(3, 3)), b + 1j * rng.normal(size=3)
            factors = lu_factor(a)
            assert np.array_equal(fast.solve_lu(factors, b.copy()), lu_solve(factors, b.copy(), overwrite_b=True))
    with pytest.raises(ValueError, match="infs or NaNs"):
        fast.solve_lu(lu_factor(np.eye(3)), np.array([1.0, np.nan, 0.0]))
    # a solve Radau does not make (several right-hand sides) goes to scipy unchanged
    many = rng.normal(size=(3, 2))
    assert np.array_equal(fast.solve_lu(lu_factor(np.eye(3) * 2), many.copy()), many / 2)


def test_solve_ivp_directly():
    rhs, jac = vector_field(CASE_A, 1e-3, "tanh")
    runs = [solve_ivp(rhs, (0.0, 2.0), [0.0, 1.0, 0.0], method=m, jac=jac, rtol=1e-9, atol=1e-12)
            for m in (fast.Radau, ScipyRadau)]
    assert runs[0].nfev == runs[1].nfev and np.array_equal(runs[0].y, runs[1].y)
