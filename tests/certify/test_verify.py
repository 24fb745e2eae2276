"""The exact verifier: every inequality can fail, and says which one did."""

from __future__ import annotations

import ast
import inspect
from dataclasses import replace
from fractions import Fraction as F

import mpmath
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import CertificateError
from symbolic_friction._certify import Certificate, VerificationReport, certify, verify_certificate, verify_file
from symbolic_friction._certify import verify as verify_module
from symbolic_friction._certify.verify import Inequality, Semidefinite, _det, decide


def _psd_check(obligation, name, m):
    return decide(Semidefinite(obligation, name, tuple(tuple(F(x) for x in row) for row in m)))


@pytest.fixture(scope="module")
def cert_a() -> Certificate:
    return certify(Parameters.table_i("a"), mode="tightest")


@pytest.fixture(scope="module")
def cert_b() -> Certificate:
    return certify(Parameters.table_i("b"), mode="feasible")


def _failures(cert: Certificate) -> list[str]:
    return [check.message for check in verify_certificate(cert).failures]


def test_table_i_certificates_are_proved(cert_a, cert_b):
    for cert in (cert_a, cert_b):
        report = verify_certificate(cert)
        assert report.proved and report.failures == ()
        assert len([c for c in report.checks if c.obligation != "provenance"]) == 27
        assert [c.name for c in report.checks if c.obligation == "provenance"] == [
            "provenance.obligations ⊆ obligations instantiated"
        ]  # no label naming Table I, no physical parameters
        assert report.summary().startswith("PROVED <certificate>: all 28 inequalities hold")
        report.raise_if_failed()  # no exception


def test_report_lists_every_inequality_in_paper_order(cert_a):
    names = [check.name for check in verify_certificate(cert_a).checks]
    assert names[:4] == ["k_i > 0", "k_p > 0", "k_v·k_p > k_i", "f_c > 0"]
    for expected in (
        "P − c1·I ⪰ 0",
        "c2·I − P ⪰ 0",
        "k3 > (k_i/k_v)·k1",
        "k3 > k2",
        "k4 > (k_i/k_v)·k3",
        "k4 > k_p·k2",
        "k1·k4 > k3²",
        "c1_hat ≤ k1/2",
        "c1_hat ≤ k2/2",
        "c1_hat ≤ k4/2",
        "c2_hat·I − K/2 ⪰ 0",
        "c = 2(k_v·k_p − k_i)",
        "overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat)",
    ):
        assert expected in names
    obligations = {check.obligation for check in verify_certificate(cert_a).checks} - {"provenance"}
    assert obligations == {
        "lemma2.P",
        "model",
        "lemma2.dVdt",
        "lemma2.lower_bound",
        "lemma3.R",
        "lemma3.hatV_derivative",
        "lemma3.hatV_bounds",
        "prop1.stability_bound",
    }


# -- the Done-when failures ------------------------------------------------------------------
def test_k3_nudged_below_k2_fails_naming_the_inequality(cert_a):
    bad = replace(cert_a, k3=cert_a.k2 - F(1, 10**6))
    assert _failures(bad) == ["k3 > k2: 1999999/1000000 > 2 is false"]


def test_c1_raised_above_lambda_min_fails(cert_a):
    # case (a): λ_min(P) = 1 exactly (the decoupled middle entry)
    bad = replace(cert_a, c1=F(101, 100))
    failures = _failures(bad)
    assert any(msg.startswith("P − c1·I ⪰ 0:") and "is false" in msg for msg in failures)
    assert "principal minor {2} = -1/100 < 0" in failures[0]


def test_c1_raised_just_above_an_irrational_lambda_min_fails(cert_b):
    """Case (b): λ_min(P) is irrational; 1e-12 above it fails, 1e-12 below it passes (50-digit reference)."""
    with mpmath.workdps(50):
        p = mpmath.matrix([[mpmath.mpf(75) / 4, 0, -1], [0, 1, 0], [-1, 0, mpmath.mpf(33) / 50]])
        lam_min = min(mpmath.eigsy(p, eigvals_only=True))
        above = F(mpmath.nstr(lam_min * (1 + mpmath.mpf(10) ** -12), 40))
        below = F(mpmath.nstr(lam_min * (1 - mpmath.mpf(10) ** -12), 40))
    assert [m.split(":")[0] for m in _failures(replace(cert_b, c1=above))] == ["P − c1·I ⪰ 0"]
    assert _failures(replace(cert_b, c1=below)) == []


def test_c2_hat_lowered_by_one_percent_fails(cert_a):
    bad = replace(cert_a, c2_hat=cert_a.c2_hat * F(99, 100))
    failures = _failures(bad)
    assert [m.split(":")[0] for m in failures] == ["c2_hat·I − K/2 ⪰ 0"]
    assert "is false" in failures[0]


def test_c_enlarged_ten_times_fails(cert_a):
    bad = replace(cert_a, c=cert_a.c * 10)
    assert _failures(bad) == ["c = 2(k_v·k_p − k_i): 304 = 2·(96/5 − 4) = 152/5 is false"]


def test_c2_below_lambda_max_fails(cert_a):
    bad = replace(cert_a, c2=F(7, 2))  # λ_max(P) ≈ 3.5207
    failures = _failures(bad)
    assert [m.split(":")[0] for m in failures] == ["c2·I − P ⪰ 0"]


def test_overshoot_bound_too_small_fails(cert_a):
    bad = replace(cert_a, overshoot_bound="3.46702")  # the tight value rounds up to 3.46703
    assert [m.split(":")[0] for m in _failures(bad)] == ["overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat)"]


def test_c1_hat_above_half_a_diagonal_entry_fails(cert_a):
    bad = replace(cert_a, c1_hat=F(3, 2))
    failures = [m.split(":")[0] for m in _failures(bad)]
    assert failures == ["c1_hat ≤ k1/2", "c1_hat ≤ k2/2"]


@pytest.mark.parametrize(
    ("field", "value", "expected"),
    [
        ("k1", F(10), "k3 > (k_i/k_v)·k1: 1000001/500000 > 25/4 is false"),
        ("k4", F(2), "k4 > k_p·k2: 2 > 6 is false"),
        ("k4", F(1, 1), "k4 > (k_i/k_v)·k3: 1 > 1000001/800000 is false"),
    ],
)
def test_each_k_condition_can_fail(cert_a, field, value, expected):
    assert expected in _failures(replace(cert_a, **{field: value}))


def test_k1_k4_not_above_k3_squared_fails(cert_a):
    bad = replace(cert_a, k1=F(2, 3), c1_hat=F(1, 3))  # k1·k4 = 4.00000 < k3² ≈ 4.000004
    assert "k1·k4 > k3²: 1000001/250000 > 1000002000001/250000000000 is false" in _failures(bad)


def test_assumption_1_violated_in_a_file_is_a_failed_claim(cert_a):
    bad = replace(cert_a, k_v=F(1), c=F(1))
    failures = _failures(bad)
    assert failures[0] == "k_v·k_p > k_i: 3 > 4 is false"


def test_c1_larger_than_c2_fails(cert_a):
    bad = replace(cert_a, c2=F(1, 2))
    assert "c1 ≤ c2: 1 ≤ 1/2 is false" in _failures(bad)


def test_raise_if_failed_names_every_failure(cert_a):
    bad = replace(cert_a, k3=F(1), c=F(1))
    report = verify_certificate(bad, source="bad.json")
    assert not report.proved
    with pytest.raises(CertificateError, match=r"FAILED bad.json: c = 2\(k_v·k_p − k_i\): 1 = .* is false; .*k3 > k2: 1 > 2 is false"):
        report.raise_if_failed()


def test_verify_needs_a_certificate():
    with pytest.raises(TypeError, match="verify_certificate needs a Certificate; got dict"):
        verify_certificate({"k1": 1})


def test_verify_file(tmp_path, cert_a):
    from symbolic_friction._certify import dumps

    path = tmp_path / "a.json"
    path.write_text(dumps(cert_a), encoding="utf-8")
    report = verify_file(path)
    assert isinstance(report, VerificationReport) and report.proved and report.source == str(path)


# -- the exact PSD test ---------------------------------------------------------------------------
def test_psd_uses_all_principal_minors_not_only_leading_ones():
    # leading minors 0, 0, 0 are all ≥ 0, but the matrix is not PSD
    m = [[0, 0, 0], [0, 0, 0], [0, 0, -1]]
    check = _psd_check("x", "M ⪰ 0", m)
    assert not check.holds and "principal minor {3} = -1 < 0" in check.instance
    # a 2×2 principal minor that is negative while all diagonal entries are ≥ 0
    m = [[1, 0, 2], [0, 1, 0], [2, 0, 1]]
    check = _psd_check("x", "M ⪰ 0", m)
    assert not check.holds and "principal minor {1,3} = -3 < 0" in check.instance
    assert _psd_check("x", "I ⪰ 0", [[1, 0, 0], [0, 1, 0], [0, 0, 1]]).holds


def test_exact_determinant():
    assert _det([[F(1, 2), 1, 0], [1, F(1, 3), 2], [0, 2, 5]]) == F(1, 2) * (F(5, 3) - 4) - 1 * 5
    assert _det([]) == 1


# -- independence from the search ----------------------------------------------------------------
def test_verifier_shares_no_code_with_the_search_and_uses_no_floats():
    tree = ast.parse(inspect.getsource(verify_module))
    imported = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            imported.add(node.module or "")
            imported.update(alias.name for alias in node.names)
        elif isinstance(node, ast.Import):
            imported.update(alias.name for alias in node.names)
    for forbidden in ("search", "rounding", "cvxpy", "numpy", "math", "clarabel"):
        assert forbidden not in imported, forbidden
    calls = {node.func.id for node in ast.walk(tree) if isinstance(node, ast.Call) and isinstance(node.func, ast.Name)}
    assert "float" not in calls
    floats = [node.value for node in ast.walk(tree) if isinstance(node, ast.Constant) and isinstance(node.value, float)]
    assert floats == []


def test_decision_refuses_inexact_numbers():
    with pytest.raises(CertificateError, match="exact rationals only; got float 0.5"):
        decide(Inequality("x", "c1 > 0", 0.5, ">", F(0)))


def test_premises_are_built_once_for_fractions_and_symbols(cert_a):
    import sympy as sp

    from symbolic_friction._obligations.certificate import _symbolic_certificate

    exact = verify_module.premises(verify_module._Exact(cert_a))
    symbolic = verify_module.premises(_symbolic_certificate())
    assert [p.name for p in exact] == [p.name for p in symbolic]
    assert all(isinstance(p.margin()[0], sp.Expr) for p in symbolic if isinstance(p, Inequality))


# -- numbers of any sign: the verifier decides the signs, and a zero divisor is not evaluated, never raised ----------
def test_the_premises_that_divide_by_k_v_are_the_model_s():
    assert verify_module.DIVIDE_BY_K_V == ("k3 > (k_i/k_v)·k1", "k4 > (k_i/k_v)·k3")


@pytest.mark.parametrize("zero, undefined", [
    ("k_i", ["P − c1·I ⪰ 0", "c2·I − P ⪰ 0"]),
    ("k_v", ["k3 > (k_i/k_v)·k1", "k4 > (k_i/k_v)·k3"]),
    ("c1", ["overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat)"]),
    ("c1_hat", ["overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat)"]),
])
def test_a_zero_divisor_leaves_its_premises_unevaluated_and_failing(cert_a, zero, undefined):
    report = verify_certificate(replace(cert_a, **{zero: 0}))
    unevaluated = [c for c in report.checks if not c.evaluated]
    assert [c.name for c in unevaluated] == undefined and not any(c.holds for c in unevaluated)
    assert all(c.message.startswith(f"{c.name}: not evaluated (") and "is false" not in c.message for c in unevaluated)
    assert [c.name for c in report.checks] == [c.name for c in verify_certificate(cert_a).checks]  # same premises, same order
    # the zero also breaks a premise that is evaluated: the refusal never rests on "not evaluated" alone
    assert any(c.evaluated for c in report.failures)


def test_symbols_are_never_taken_for_a_zero_divisor():
    from symbolic_friction._obligations.certificate import _symbolic_certificate

    assert not any(isinstance(p, verify_module.Undefined) for p in verify_module.premises(_symbolic_certificate()))


def test_an_empty_report_proves_nothing(cert_a):
    assert not VerificationReport(cert_a, ()).proved
