"""The closed-form certificate: verified by the exact verifier for every gain set satisfying Assumption 1.

Property tests draw exact rational gains over ratios up to 10¹² and Routh margins down to 1 + 10⁻³⁰;
``certify`` (closed form by default) must return a certificate that the verifier proves.
"""

from __future__ import annotations

from fractions import Fraction as F

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from symbolic_friction import Parameters
from symbolic_friction.errors import ParameterError
from symbolic_friction._certify import certify, verify_certificate
from symbolic_friction._certify.closed_form import closed_form_constants, sqrt_up


def _scaled(e_lo: int, e_hi: int) -> st.SearchStrategy[F]:
    """Exact positive rationals m·10^e with 1 ≤ m < 10 of a few digits."""
    return st.builds(lambda m, e: F(m, 1000) * F(10) ** e, st.integers(1000, 9999), st.integers(e_lo, e_hi))


ROUTH = st.one_of(
    st.just(1 + F(1, 10**30)),
    st.builds(lambda k: 1 + F(1, 10**k), st.integers(1, 30)),
    st.builds(lambda q: 1 + q, _scaled(-6, 12)),
)


# The strategies the composites draw from, built once: hypothesis validates a strategy the first time it is drawn
# from, and a strategy built inside a composite is new at every example (about half of these tests' time went there).
GAIN = _scaled(-12, 12)
F_C = _scaled(-6, 6)


@st.composite
def gains(draw) -> Parameters:
    k_i, k_v = draw(GAIN), draw(GAIN)
    routh = draw(ROUTH)  # k_v·k_p/k_i
    return Parameters(k_p=routh * k_i / k_v, k_i=k_i, k_v=k_v, f_c=draw(F_C))


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(gains())
def test_closed_form_certificates_verify_for_random_gains(params):
    cert = certify(params)
    assert verify_certificate(cert).proved
    assert cert.provenance.search == "closed-form" and cert.provenance.solver == "none"


@pytest.mark.parametrize("k_i, k_v, routh", [
    (F(10**12), F(1), 1 + F(1, 10**30)),
    (F(1), F(10**12), 1 + F(1, 10**30)),
    (F(1, 10**12), F(10**12), F(10**12)),
    (F(10**12), F(1, 10**12), 1 + F(1, 10**30)),
    (F(4), F(32, 5), 1 + F(1, 10**30)),
])
def test_extremes_verify(k_i, k_v, routh):
    params = Parameters(k_p=routh * k_i / k_v, k_i=k_i, k_v=k_v, f_c=1)
    for mode in ("tightest", "feasible"):
        assert verify_certificate(certify(params, mode=mode)).proved


def test_table_i_kappa_is_the_sdp_tightest():
    for case, kappa in (("a", "3.46703"), ("b", "7.88526")):
        assert certify(Parameters.table_i(case)).overshoot_bound == kappa


def test_table_i_keeps_the_sdp_s_kappa_in_both_modes():
    """The committed Table I certificates were the SDP's: the closed form reproduces all four κ (case (b)
    feasible through the balanced k₁ = k₄, which the k₁ = 2 family cannot reach: 8.01425)."""
    for case, mode, kappa, k1_is_2 in (("a", "tightest", "3.46703", True), ("a", "feasible", "3.51842", True),
                                       ("b", "tightest", "7.88526", False), ("b", "feasible", "8.01380", False)):
        cert = certify(Parameters.table_i(case), mode=mode)
        assert (cert.overshoot_bound, cert.k1 == 2) == (kappa, k1_is_2)
        assert verify_certificate(cert).proved


BALANCED_K_V = _scaled(-6, 6)
BALANCED_RATIO = st.fractions(min_value=F(1, 10**9), max_value=F(99, 100), max_denominator=10**9)
BALANCED_ROUTH = st.one_of(st.just(1 + F(1, 10**30)), st.builds(lambda q: 1 + q, _scaled(-9, 3)))
BALANCED_F_C = _scaled(-3, 3)


@st.composite
def balanced_gains(draw) -> Parameters:
    """Gains where k₁ = k₄ applies: k_p ≲ 1 and k_i/k_v ≲ 1 (and beyond, to its boundary)."""
    k_v = draw(BALANCED_K_V)
    k_i = k_v * draw(BALANCED_RATIO)
    k_p = k_i / k_v * draw(BALANCED_ROUTH)
    return Parameters(k_p=k_p, k_i=k_i, k_v=k_v, f_c=draw(BALANCED_F_C))


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(balanced_gains(), st.sampled_from([("tightest", F(1, 10**6)), ("feasible", F(1, 100)), ("tightest", F(1, 3))]))
def test_the_balanced_constants_verify_and_never_raise_kappa(params, mode_margin):
    from symbolic_friction._certify.closed_form import closed_form_certificate

    mode, margin = mode_margin
    a = params.k_v / params.k_i
    cert = closed_form_certificate(params, mode=mode, margin=margin)
    report = verify_certificate(cert)
    assert report.proved, report.summary()
    base = closed_form_constants(a, a, params.k_p, params.k_p, mu=margin, loose=mode == "feasible")
    assert cert.kappa_squared <= base.kappa_squared
    assert (cert.k1 == cert.k4) or (cert.k1, cert.k4) == (base.k1, base.k4)


@pytest.mark.parametrize("case, premise", [("a", "k4 > k_p·k2"), ("large r", "k3 > (k_i/k_v)·k1")])
def test_each_condition_of_the_balanced_constants_guards_a_premise(case, premise):
    """Outside its two conditions the balanced form is not used, and forced there the verifier refuses it."""
    from dataclasses import replace

    from symbolic_friction._certify.closed_form import balanced, closed_form_certificate

    params = Parameters.table_i("a") if case == "a" else Parameters(k_p=F(3), k_i=F(4), k_v=F(2), f_c=1)
    a = params.k_v / params.k_i
    base = closed_form_constants(a, a, params.k_p, params.k_p, mu=F(1, 100))
    assert balanced(base, a, params.k_p) is None
    T = sqrt_up(F(101, 100) * base.k3**2)
    cert = closed_form_certificate(params, mode="tightest", margin=F(1, 100))
    forced = replace(cert, k1=T, k4=T, c2_hat=(T + base.k3) / 2)
    failures = [c.name for c in verify_certificate(forced).failures]
    assert premise in failures


def test_without_margin_the_closed_form_is_refused():
    with pytest.raises(ValueError, match="the margin μ must be positive"):
        closed_form_constants(F(8, 5), F(8, 5), F(3), F(3), mu=F(0))
    with pytest.raises(ParameterError, match=r"margin must be in \(0, 1\]"):
        certify(Parameters.table_i("a"), margin=0)


def test_a_corner_outside_assumption_1_is_refused():
    with pytest.raises(ValueError, match="Assumption 1 needs k_v·k_p > k_i, i.e. a·k_p > 1; got 1/2·2 ≤ 1"):
        closed_form_constants(F(1, 2), F(1), F(2), F(3))


def test_an_unknown_search_is_refused():
    with pytest.raises(ParameterError, match="search must be one of 'closed-form', 'sdp'; got 'newton'"):
        certify(Parameters.table_i("a"), search="newton")


@given(st.fractions(min_value=0, max_value=10**9, max_denominator=10**6), st.integers(2, 20))
def test_sqrt_up_is_an_upper_bound_within_its_digits(q, digits):
    s = sqrt_up(q, digits)
    assert s >= 0 and s * s >= q
    if q > 0:
        assert s * s <= q * (1 + F(1, 10 ** (digits - 2))) ** 2
