"""Extreme gains certify AND verify exactly.

* 1,000 random gain sets, k_i from 1e-6 to 1e6 and k_p from 1e-6 to 1e6,
  with k_v k_p / k_i from 1 + 1e-9 to 1e6; one in ten exactly at the Routh
  boundary k_v k_p / k_i = 1 + 1e-9 (built with Fractions);
* exactly repeated roots (s + a)³ (k_v = 3a, k_p = 3a², k_i = a³) and
  near-repeated roots;
* f_c from 1e-9 to 1e9.
"""

from __future__ import annotations

import random
from fractions import Fraction as F

import pytest

from symbolic_friction import Parameters
from symbolic_friction._certify import certify, certify_many, verify_certificate

ROUTH_EPS = F(1, 10**9)


def _decimal(x: float) -> F:
    return F(f"{x:.6g}")


def random_gains(n: int, seed: int = 2024) -> list[Parameters]:
    """Gain sets spread over many decades; see the module docstring."""
    rng = random.Random(seed)
    out = []
    for i in range(n):
        f_c = _decimal(10 ** rng.uniform(-9, 9))
        kind = i % 10
        if kind == 7:  # exactly repeated roots
            a = _decimal(10 ** rng.uniform(-2, 2))
            out.append(Parameters(k_v=3 * a, k_p=3 * a**2, k_i=a**3, f_c=f_c))
            continue
        if kind == 8:  # near-repeated roots -a, -a(1+ε), -a(1+2ε)
            a = _decimal(10 ** rng.uniform(-2, 2))
            eps = _decimal(10 ** rng.uniform(-9, -3))
            r1, r2, r3 = a, a * (1 + eps), a * (1 + 2 * eps)
            out.append(Parameters(k_v=r1 + r2 + r3, k_p=r1 * r2 + r1 * r3 + r2 * r3, k_i=r1 * r2 * r3, f_c=f_c))
            continue
        k_i = _decimal(10 ** rng.uniform(-6, 6))
        k_p = _decimal(10 ** rng.uniform(-6, 6))
        rho = 1 + ROUTH_EPS if kind == 0 else 1 + _decimal(10 ** rng.uniform(-9, 6))
        out.append(Parameters(k_v=rho * k_i / k_p, k_p=k_p, k_i=k_i, f_c=f_c))
    return out


@pytest.fixture(scope="module")
def gains() -> list[Parameters]:
    g = random_gains(1000)
    ki = [float(p.k_i) for p in g]
    assert min(ki) < 1e-5 and max(ki) > 1e5  # the sample really spans k_i ∈ [1e-6, 1e6]
    assert sum(p.routh_margin == 1 + ROUTH_EPS for p in g) == 100
    return g


@pytest.mark.slow
@pytest.mark.parametrize("mode", ["tightest", "feasible"])
def test_one_thousand_random_gain_sets_certify_and_verify(gains, mode):
    items = certify_many(gains, mode=mode, progress=False)
    failures = [(item.params, item.error) for item in items if not item.ok]
    assert failures == []
    for item in items:
        report = verify_certificate(item.certificate)
        assert report.proved, report.summary()
        cert = item.certificate
        assert (cert.k_p, cert.k_i, cert.k_v, cert.f_c) == (item.params.k_p, item.params.k_i, item.params.k_v, item.params.f_c)


@pytest.mark.parametrize(
    "params",
    [
        Parameters(k_v=3, k_p=3, k_i=1),  # (s + 1)³
        Parameters(k_v=F(3, 10**3), k_p=F(3, 10**6), k_i=F(1, 10**9)),  # (s + 1e-3)³
        Parameters(k_v=300, k_p=30000, k_i=10**6),  # (s + 100)³
        Parameters(k_v=3 + 3 * F(1, 10**9), k_p=3 + 6 * F(1, 10**9), k_i=1 + 3 * F(1, 10**9)),  # ≈ (s+1)³
    ],
    ids=["triple-root", "triple-root-small", "triple-root-large", "near-triple-root"],
)
@pytest.mark.parametrize("mode", ["tightest", "feasible"])
def test_repeated_roots(params, mode):
    assert verify_certificate(certify(params, mode=mode)).proved


@pytest.mark.parametrize("k_i", [F(1, 10**6), F(1), F(10**6)])
@pytest.mark.parametrize("k_p", [F(1, 10**6), F(1), F(10**6)])
def test_exactly_at_one_plus_1e_minus_9_of_the_routh_boundary(k_i, k_p):
    params = Parameters(k_v=(1 + ROUTH_EPS) * k_i / k_p, k_p=k_p, k_i=k_i)
    assert params.routh_margin == 1 + ROUTH_EPS
    cert = certify(params, mode="tightest")
    assert verify_certificate(cert).proved
    # λ_min(P) ≈ det/λ_max ≈ 1e-9·(k_v k_p/k_i)/λ_max: c1 is tiny but positive, and κ is large
    assert 0 < cert.c1 < F(1, 10**8)


@pytest.mark.parametrize("f_c", ["1e-9", "1e-3", "1", "1e3", "1e9"])
def test_coulomb_level_over_eighteen_decades(f_c):
    params = Parameters(k_v="6.4", k_p=3, k_i=4, f_c=f_c)
    cert = certify(params, mode="tightest")
    assert verify_certificate(cert).proved
    # f_c enters neither P nor the k-conditions: the constants do not depend on it
    reference = certify(Parameters.table_i("a"), mode="tightest")
    assert cert.constants == reference.constants and cert.overshoot_bound == reference.overshoot_bound
