"""Invariances of the exact kernel that a one-point error breaks where Table I's gains cannot see it.

* **Scaling.** ``x' ∈ Ax - b SGN(v)`` with ``b = (0, 0, f_c)``: the solution
  for ``(f_c, f_s)`` from ``c·x0`` is ``c`` times the one for
  ``(f_c/c, f_s/c)`` from ``x0``, at the same times.  With ``c`` a power of
  two every scaling is exact in floating point, so a factor ``f_c``
  dropped anywhere (dense output, event state, stick duration, the offset a
  slip starts from) shows at ``f_c = 2``, ``1/4`` or ``2¹⁰``, while ``f_c = 1``
  hides it.
* **Odd symmetry.** The solution from ``-x0`` is minus the one from ``x0``:
  a sign slip in one slip direction (a stick exit, the offset after a stick)
  breaks it.
* **Uniform grids.** Equally spaced samples are stepped with the exact
  propagator; each must equal the closed form at the same time (a sample
  simulated alone).
* **Horizons just after an event.** With ``t_end = t_event(1 + 10⁻⁹)`` the
  event is still found and is the last one (the scan covers the partial cell
  before the horizon).
"""

from __future__ import annotations

import dataclasses
from fractions import Fraction as F

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._simulation import simulate

A = Parameters.table_i("a")
B = Parameters.table_i("b")
Z0 = (0.0, 0.0, 5.0)
T_END = 40.0
TIMES = np.linspace(0.0, T_END, 161)


def _scaled(p: Parameters, c: F, f_s: F | None = None) -> Parameters:
    f_s = p.f_c if f_s is None else f_s
    return dataclasses.replace(p, f_c=p.f_c * c, f_s=f_s * c)


def _run(p, z0, t_end=T_END, t_eval=TIMES):
    return simulate(p, z0, t_end, t_eval=t_eval)


def _close(a, b, scale, tol=1e-12):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape
    assert np.all(np.abs(a - b) <= tol * scale), float(np.max(np.abs(a - b)))


CASES = {
    "a": (A, None, Z0),
    "b": (B, None, (0.0, -3.0, 5.0)),
    "a_fs1.2": (A, F(6, 5), Z0),
    "a_fs1.5_rest": (A, F(3, 2), (0.0, 5.0, 0.0)),
    "b_fs1.5": (B, F(3, 2), (0.0, 0.0, 5.0)),
    # at rest exactly on φ = f_s with σ = 1 (slips at once); its mirror starts exactly on -f_s
    "a_fs1.5_on_fs": (A, F(3, 2), (-0.1875, -0.25, 0.0)),
    # at rest exactly on φ = f_s with σ = -1 (sticks); its mirror sticks on -f_s
    "a_fs1.5_on_fs_inward": (A, F(3, 2), (-0.5625, 0.25, 0.0)),
}


@pytest.mark.parametrize("c", [F(2), F(1, 4), F(1024)])
@pytest.mark.parametrize("name", list(CASES))
def test_scaling_f_c_scales_the_solution(name, c):
    p, f_s, z0 = CASES[name]
    base = _run(_scaled(p, F(1), f_s), z0)
    big = _run(_scaled(p, c, f_s), tuple(float(c) * q for q in z0))
    scale = float(c) * max(1.0, float(np.max(np.abs(base.x))))
    assert big.status == base.status
    assert [(m0, m1) for _, m0, m1 in big.events] == [(m0, m1) for _, m0, m1 in base.events]
    assert len(base.events) >= 1
    _close([t for t, *_ in big.events], [t for t, *_ in base.events], T_END)
    _close(big.event_x, float(c) * base.event_x, scale)
    _close(big.x, float(c) * base.x, scale)
    assert np.array_equal(big.mode, base.mode)


@pytest.mark.parametrize("name", list(CASES))
def test_the_solution_is_odd(name):
    p, f_s, z0 = CASES[name]
    q = _scaled(p, F(1), f_s)
    plus, minus = _run(q, z0), _run(q, tuple(-v for v in z0))
    scale = max(1.0, float(np.max(np.abs(plus.x))))
    _close(minus.x, -plus.x, scale)
    assert np.array_equal(minus.mode, -plus.mode)
    assert [(t, -m0, -m1) for t, m0, m1 in plus.events] == [(t, m0, m1) for t, m0, m1 in minus.events] or \
        np.allclose([t for t, *_ in plus.events], [t for t, *_ in minus.events], rtol=0, atol=1e-12 * T_END)


@pytest.mark.parametrize("name", list(CASES))
def test_uniform_samples_equal_the_closed_form(name):
    p, f_s, z0 = CASES[name]
    q = _scaled(p, F(2), f_s)
    z0 = tuple(2.0 * v for v in z0)
    grid = _run(q, z0)
    scale = max(1.0, float(np.max(np.abs(grid.x))))
    for j in range(1, TIMES.size, 7):
        alone = _run(q, z0, t_eval=np.array([0.0, TIMES[j]]))
        _close(grid.x[j], alone.x[1], scale, tol=1e-11)
        assert grid.mode[j] == alone.mode[1]


@pytest.mark.parametrize("name", list(CASES))
def test_a_horizon_just_after_an_event_still_has_it(name):
    p, f_s, z0 = CASES[name]
    q = _scaled(p, F(2), f_s)
    z0 = tuple(2.0 * v for v in z0)
    full = _run(q, z0, t_eval=None)
    assert len(full.events) >= 1
    for k, (t_e, m0, m1) in enumerate(full.events[:4]):
        cut = _run(q, z0, t_end=t_e * (1 + 1e-9), t_eval=None)
        assert len(cut.events) == k + 1, (k, t_e, m0, m1, cut.events)
        assert abs(cut.events[-1][0] - t_e) <= 1e-12 * t_e and cut.events[-1][1:] == (m0, m1)


@pytest.mark.parametrize("name", ["a", "a_fs1.2"])
def test_event_residual_is_v_where_the_slip_ended(name, monkeypatch):
    """Each slip-ending event records |v| of the closed form at the τ the search returned, not a constant 0.

    The mode table's "v = 0 at events" property reads this residue; recorded as 0 it would be vacuous.  The
    plain-Python kernel is run with the search and the closed form spied on (only the kernel's own calls at
    a slip's end are kept); each slip-ending event's residual must be |v| of the slip that ended there, bit
    for bit, and some residue must be non-zero (else the comparison shows nothing).
    """
    from symbolic_friction._simulation import _kernel
    from symbolic_friction._simulation.search import slip_model
    import sys

    params, f_s, z0 = CASES[name]
    if f_s is not None:
        params = _scaled(params, F(1), f_s)
    ends = []
    for fn in ("first_zero", "flow", "_flow_star"):  # _flow_star: a slip from a stick, of the known length τ*
        original = getattr(_kernel, fn)

        def spy(*a, _original=original, _fn=fn):
            out = _original(*a)
            if sys._getframe(1).f_code.co_name == "trajectory":  # the loop's own call, not the dense output's
                ends.append(abs(out[-1]))
            return out

        monkeypatch.setattr(_kernel, fn, spy)
    K, W, N = slip_model(params).constants(False)
    ts = np.array([0.0, T_END])
    out_x, out_z = np.empty((2, ts.size, 3))
    out_mode = np.empty(ts.size, dtype=np.int8)
    room = 200
    ev_t, ev_x, ev_m, ev_res = np.empty(room), np.empty((room, 3)), np.empty((room, 2), dtype=np.int8), np.empty(room)
    code, n_ev, _ = _kernel.trajectory(K, W, N, np.array(z0, float), np.empty(3), T_END, room, ts,
                                       out_x, out_z, out_mode, ev_t, ev_x, ev_m, ev_res, np.zeros(_kernel.S_SIZE))
    slip_ends = [j for j in range(n_ev) if ev_m[j, 0] != 0]
    assert code == 0 and len(slip_ends) >= 4
    # every slip's end is an event here (no grazing contact): the i-th slip end is the i-th such event
    assert [ev_res[j] for j in slip_ends] == ends[: len(slip_ends)]
    assert any(ev_res[j] > 0 for j in slip_ends)
    assert all(ev_res[j] <= 1e-12 * 5.0 for j in slip_ends)
