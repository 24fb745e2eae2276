"""Obligations binding the certificate verifier to the proof, and Assumption 1's encoding."""

import dataclasses
from fractions import Fraction

import sympy as sp

from symbolic_friction._certify import verify as verify_module
from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.assumption1 import Assumption1Encoding
from symbolic_friction._obligations.certificate import (
    CertificateVerifier,
    VerifierDecision,
    _premise_rows,
    _symbolic_certificate,
)

from ._helpers import assert_fails, assert_holds, obligation_fixture

g = G()
verifier = obligation_fixture(CertificateVerifier)
decision = obligation_fixture(VerifierDecision)
encoding = obligation_fixture(Assumption1Encoding)


def test_all_hold(verifier, decision, encoding):
    for ob, subject in (verifier, decision, encoding):
        assert_holds(ob, subject)


def _without(subject, fragment):
    kept = tuple(p for p in subject.premises if fragment not in p[0])
    assert len(kept) < len(subject.premises), fragment
    return dataclasses.replace(subject, premises=kept)


def test_dropping_c2_bound_fails(verifier):
    ob, s = verifier
    assert_fails(ob, _without(s, "c2·I − P"), "c₂I − P ⪰ 0")


def test_dropping_c1_hat_k4_fails(verifier):
    ob, s = verifier
    assert_fails(ob, _without(s, "c1_hat ≤ k4/2"), "ĉ₁ ≤ k4/2")


def test_leading_minors_only_fails(verifier):
    ob, s = verifier
    leading = ("{1}]", "{1,2}]", "{1,2,3}]")
    kept = tuple(p for p in s.premises if "minor" not in p[0] or p[0].endswith(leading))
    assert_fails(ob, dataclasses.replace(s, premises=kept), "principal minor {2}")


def test_kappa_without_hat_factor_fails(verifier):
    ob, s = verifier
    cert = _symbolic_certificate()
    rows = tuple(
        (n, sp.expand(cert.kappa**2 - cert.c2 / cert.c1), k) if n.startswith("overshoot_bound²") else (n, m, k)
        for n, m, k in s.premises
    )
    assert_fails(ob, dataclasses.replace(s, premises=rows), "κ² ≥ c₂ĉ₂/(c₁ĉ₁)")


def test_non_strict_premise_does_not_support_a_strict_claim(verifier):
    ob, s = verifier
    rows = tuple((n, m, ">=" if n == "c1 > 0" else k) for n, m, k in s.premises)
    assert_fails(ob, dataclasses.replace(s, premises=rows), "c₁ > 0")


def test_weakened_k_condition_fails(verifier):
    ob, s = verifier
    k2, k3 = _symbolic_certificate().k2, _symbolic_certificate().k3
    rows = tuple((n, k3 - k2 / 2, k) if n == "k3 > k2" else (n, m, k) for n, m, k in s.premises)
    assert_fails(ob, dataclasses.replace(s, premises=rows), "hatVdot")


def test_wrong_decrease_rate_fails(verifier):
    ob, s = verifier
    cert = _symbolic_certificate()
    rows = tuple(
        (n, cert.c - (cert.k_v * cert.k_p - cert.k_i), k) if n.startswith("c = ") else (n, m, k) for n, m, k in s.premises
    )
    assert_fails(ob, dataclasses.replace(s, premises=rows), "decrease rate")


def test_the_real_premise_list_has_every_minor():
    rows = _premise_rows(verify_module.premises(_symbolic_certificate()))
    assert sum("minor" in n for n, _, _ in rows) == 3 * 7


def test_decision_non_strict_comparison_fails(decision):
    ob, s = decision
    real = s.decide

    def lax(premise):
        check = real(premise)
        if isinstance(premise, verify_module.Inequality) and premise.op == ">" and premise.lhs == premise.rhs:
            return dataclasses.replace(check, holds=True)
        return check

    assert_fails(ob, dataclasses.replace(s, decide=lax), "decides 1 > 1 as True")


def test_decision_leading_minors_only_fails(decision):
    ob, s = decision

    class Leading(verify_module.Semidefinite):
        def minors(self):
            return [(tuple(range(n)), m) for (idx, m) in super().minors() for n in [len(idx)] if idx == tuple(range(n))]

    assert_fails(ob, dataclasses.replace(s, semidefinite=Leading), "⪰ 0 as True")


def test_decision_non_strict_condition_fails(decision):
    ob, s = decision

    class Lax:
        def __init__(self, lhs, rhs):
            self.lhs, self.rhs = lhs, rhs

        def holds(self):
            return self.lhs >= self.rhs

    assert_fails(ob, dataclasses.replace(s, condition=Lax), "Condition.holds decides 1 > 1 as True")


def test_encoding_wrong_substitution_fails(encoding):
    ob, s = encoding
    assert_fails(ob, dataclasses.replace(s, substitution={g.k_v: (g.k_i - g.delta) / g.k_p}), "not δ")


def test_encoding_substituting_the_wrong_gain_fails(encoding):
    ob, s = encoding
    assert_fails(ob, dataclasses.replace(s, substitution={g.k_p: (g.k_i + g.delta) / g.k_v}), "k_v only")


def test_encoding_not_onto_fails(encoding):
    ob, s = encoding
    # k_v = (k_i + δ²)/k_p also gives margin δ² > 0, but not "δ" and not every k_v from δ = k_v k_p − k_i
    assert_fails(ob, dataclasses.replace(s, substitution={g.k_v: (g.k_i + g.delta**2) / g.k_p}), "not δ")
