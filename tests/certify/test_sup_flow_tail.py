"""The one-piece sup-flow search (``_certify/sup_flow_tail.py``), the tail's exact Lyapunov matrix
(``_certify/lyapunov_tail.py``), the conic SDP builder (``_certify/_conic.py``) and κ_lin's proven lower end."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symbolic_friction import Parameters
from symbolic_friction._certify._conic import Affine, Program
from symbolic_friction._certify.flow_bound import kappa_lin_bound, kappa_lin_lower
from symbolic_friction._certify.lyapunov_tail import best_conditioned_lyapunov, exact_lyapunov
from symbolic_friction._certify.sup_flow import verify_sup_flow
from symbolic_friction._certify.sup_flow_tail import certify_sup_flow_tail
from symbolic_friction._certify.verify import Semidefinite
from symbolic_friction._infra.errors import CertificateError, ParameterError
from symbolic_friction._model.quadratic import lyapunov_rate_entries

STIFF = [
    (F(1000), F(1), F(1)),
    (F(1), F(1, 1000), F(1000001, 10**9)),  # Routh margin 1 + 1e-6
    (F(1, 1000), F(1), F(1000001, 1000)),  # a complex pair decaying at about 5e-13
    (F(100), F(10**4), F(10001, 100)),
    (F(1000), F(1, 1000), F(1000)),  # poles about -999, -1, -1e-6
]


def _psd(rows) -> bool:
    return all(d >= 0 for _, d in Semidefinite("", "", rows).minors())


# -- the conic builder --------------------------------------------------------------------------------------


def test_a_small_sdp_is_solved_and_read_back():
    """min t with [[t, 1], [1, t]] ⪰ 0 is t = 1; max t with t ≤ 2 is 2."""
    program = Program()
    t = program.variable()
    program.psd([[t, 1.0], [1.0, t]])
    status, x = program.solve(t)
    assert status == "optimal" and Program.value(t, x) == pytest.approx(1.0, abs=1e-7)
    program = Program()
    t = program.variable()
    program.nonneg(2.0 - t)
    status, x = program.solve(t, maximize=True)
    assert status == "optimal" and Program.value(t, x) == pytest.approx(2.0, abs=1e-7)


def test_copositivity_allows_a_negative_form_that_is_copositive_and_refuses_one_that_is_not():
    """[[1, t], [t, 1]] is copositive for t ≥ −1 (and for every t ≥ 0, though not PSD there): min t is −1."""
    program = Program()
    t = program.variable()
    program.copositive([[1.0, t], [t, 1.0]], [1, 1], 0.0)
    program.nonneg(t + 5.0)
    status, x = program.solve(t)
    assert status == "optimal" and Program.value(t, x) == pytest.approx(-1.0, abs=1e-6)
    program = Program()
    t = program.variable()
    program.copositive([[1.0, 3.0], [3.0, 1.0]], [1, 1], 0.0)  # copositive: accepted
    program.copositive([[-1.0, t], [t, 1.0]], [1, 1], 0.0)  # a negative diagonal entry: never copositive
    status, x = program.solve(t)
    assert status.startswith("infeasible") and x == []


def test_a_structurally_zero_diagonal_keeps_its_row_nonnegative():
    program = Program()
    t = program.variable()
    program.copositive([[0.0, t], [t, 1.0]], [0, 1], 0.5)
    status, x = program.solve(t)
    assert status == "optimal" and Program.value(t, x) == pytest.approx(0.5, abs=1e-7)


def test_affine_expressions_refuse_a_product_of_two_unknowns():
    program = Program()
    a, b = program.variable(), program.variable()
    assert Program.value(2 * a - b / 4 + 1, [1.0, 4.0]) == 2.0
    assert Program.value(3 - a * Affine(2.0), [1.0, 0.0]) == 1.0
    with pytest.raises(TypeError, match="a product of two unknowns is not affine"):
        a * b


# -- the tail's Lyapunov matrix, exactly --------------------------------------------------------------------


@pytest.mark.parametrize("k", STIFF + [(F(3), F(4), F(32, 5))], ids=str)
def test_the_tails_p_is_exactly_a_lyapunov_matrix_even_on_slow_flows(k):
    p = exact_lyapunov(k, best_conditioned_lyapunov(tuple(float(x) for x in k)))
    assert all(isinstance(x, F) for row in p for x in row) and all(p[i][j] == p[j][i] for i in range(3) for j in range(3))
    assert _psd(tuple(tuple(-x for x in row) for row in lyapunov_rate_entries(*k, p)))
    assert _psd(p)


def test_a_float_p_that_is_not_lyapunov_is_repaired_not_trusted():
    """The identity is no Lyapunov matrix for case (a); the exact P built near it is one."""
    k = (F(3), F(4), F(32, 5))
    rate = lyapunov_rate_entries(*k, ((F(1), F(0), F(0)), (F(0), F(1), F(0)), (F(0), F(0), F(1))))
    assert not _psd(tuple(tuple(-x for x in row) for row in rate))
    p = exact_lyapunov(k, np.eye(3))
    assert _psd(tuple(tuple(-x for x in row) for row in lyapunov_rate_entries(*k, p)))


# -- the one-piece certificate ------------------------------------------------------------------------------


@pytest.mark.parametrize("k", STIFF, ids=str)
def test_stiff_slow_and_spread_gains_get_a_one_piece_certificate_within_2_6_of_kappa_lin(k):
    params = Parameters(k_p=k[0], k_i=k[1], k_v=k[2], f_c=1)
    cert = certify_sup_flow_tail(params)
    assert verify_sup_flow(cert).proved and len(cert.pieces) == 1 and cert.pieces[0].start == 0 and cert.own_tail
    ratio = cert.kappa / kappa_lin_lower(params)
    assert 1 <= ratio <= F(26, 10)


def test_static_friction_and_float_range_are_refused():
    with pytest.raises(ParameterError, match="a stability certificate is for the paper's model f_s = f_c"):
        certify_sup_flow_tail(Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1, f_s=2))
    with pytest.raises(CertificateError, match="beyond the range of the floats the SDPs work in"):
        certify_sup_flow_tail(Parameters(k_p="1e300", k_i="1e300", k_v=3, f_c=1))


_LOG = st.floats(min_value=-4, max_value=4)


# derandomized as the suite's other property tests: the same 25 examples on every run (and so the same time)
@settings(max_examples=25, deadline=None, derandomize=True, database=None)
@given(_LOG, _LOG, st.floats(min_value=-3, max_value=3))
def test_no_proved_kappa_is_below_the_proven_lower_end_of_kappa_lin(log_kp, log_ki, log_margin):
    """Two independent facts about one number: a proved κ below a proven lower end of κ_lin would show one unsound."""
    k_p, k_i = F(f"{10 ** log_kp:.4g}"), F(f"{10 ** log_ki:.4g}")
    k_v = F(f"{(1 + 10 ** log_margin) * float(k_i / k_p):.6g}")
    if not k_v * k_p > k_i:
        return
    params = Parameters(k_p=k_p, k_i=k_i, k_v=k_v, f_c=1)
    try:
        cert = certify_sup_flow_tail(params)
    except CertificateError:
        return  # a search may find nothing; it must never prove too much
    assert verify_sup_flow(cert).proved
    assert cert.kappa >= kappa_lin_lower(params)


# -- κ_lin's lower end ---------------------------------------------------------------------------------------


def test_the_lower_end_is_inside_the_full_enclosure():
    for case in "ab":
        params = Parameters.table_i(case)
        bound = kappa_lin_bound(params)
        assert bound.lower <= kappa_lin_lower(params) <= bound.upper


def test_the_lower_end_refuses_what_it_cannot_take():
    # Parameters refuses such gains itself; a stand-in reaches the function's own guard
    with pytest.raises(ParameterError, match="Assumption 1 needs k_v·k_p > k_i > 0"):
        kappa_lin_lower(_Gains(F(1), F(1), F(1)))
    with pytest.raises(ParameterError, match="beyond the float range"):
        kappa_lin_lower(Parameters(k_p="1e300", k_i="1e300", k_v=3, f_c=1))


class _Gains:
    def __init__(self, k_p, k_i, k_v):
        self.k_p, self.k_i, self.k_v, self.f_c = k_p, k_i, k_v, F(1)

    def as_floats(self):
        return float(self.k_p), float(self.k_i), float(self.k_v), 1.0
