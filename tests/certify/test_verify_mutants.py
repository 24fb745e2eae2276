"""The exact verifier's every verdict and message, pinned on forged certificates (kills its mutants).

Each case is a committed Table I certificate with one field forged (or a
namespace of plain numbers, to reach premises that a :class:`Certificate`
cannot violate, such as ``k_i > 0``).  The verifier's full report (every
check, its verdict and its exact instance, and the summary) is compared
with ``golden/verify_reports.json``: a changed comparison, a dropped premise,
a wrong minor or a garbled message each changes some line.  Regenerate the
file only after checking the difference by hand::

    SF_REGENERATE_GOLDEN=1 python -m pytest -n 0 tests/certify/test_verify_mutants.py
"""

from __future__ import annotations

from dataclasses import replace
from fractions import Fraction as F
from pathlib import Path
from types import SimpleNamespace

import pytest

from tests.certify.golden import assert_golden

from symbolic_friction.errors import CertificateError
from symbolic_friction._certify.certificate import Provenance, load
from symbolic_friction._certify.verify import (
    Check,
    Inequality,
    Semidefinite,
    Undefined,
    VerificationReport,
    _det,
    decide,
    premises,
    verify_certificate,
    verify_file,
)

ROOT = Path(__file__).resolve().parents[2]


def _cert(name: str):
    return load(ROOT / "proofs" / f"{name}.json")


def _physical(cert, **changes):
    m = F(2)
    phys = {"m": m, "k_p_bar": cert.k_p * m, "k_i_bar": cert.k_i * m, "k_d_bar": cert.k_v * m - F(1, 3),
            "alpha_v": F(1, 3), "f_c_bar": cert.f_c * m}
    phys.update(changes)
    return phys


def _report_lines(report: VerificationReport) -> list[str]:
    return [f"{c.obligation} | {c}" for c in report.checks] + ["summary | " + report.summary(), f"proved | {report.proved}",
                                                               f"failures | {len(report.failures)}"]


def _forged_cases() -> dict[str, list[str]]:
    a = _cert("case_a_tightest")
    b = _cert("case_b_feasible")
    prov = a.provenance
    cases = {
        "a": a,
        "b": b,
        "a.c_doubled": replace(a, c=a.c * 2),
        "a.c1_above_lambda_min": replace(a, c1=a.c1 * 3),
        "a.c2_below_lambda_max": replace(a, c2=a.c2 / 2),
        "a.c1_above_c2": replace(a, c1=a.c2 * 2, c2=a.c2),
        "a.k3_small": replace(a, k3=F(1, 10)),
        "a.k3_equal_k2": replace(a, k3=a.k2),
        "a.k4_small": replace(a, k4=F(1)),
        "a.k4_equal_kp_k2": replace(a, k4=a.k_p * a.k2, k3=F(199, 100)),
        "a.k1_large": replace(a, k1=F(40)),
        "a.c1_hat_large": replace(a, c1_hat=F(3, 2)),
        "a.c1_hat_k4": replace(a, k4=F(3, 2), c1_hat=F(1)),
        "a.c1_hat_equal_k1_half": replace(a, c1_hat=a.k1 / 2),
        "a.c2_hat_small": replace(a, c2_hat=F(1, 2)),
        "a.c2_hat_below_c1_hat": replace(a, c2_hat=F(1, 2), c1_hat=F(1)),
        "a.kappa_small": replace(a, overshoot_bound="1.5"),
        "a.kappa_exact": replace(a, overshoot_bound="3.46703"),
        "a.gains_of_b": replace(a, k_p=b.k_p, k_i=b.k_i, k_v=b.k_v),
        "a.assumption1_fails": replace(a, k_i=F(30)),
        "a.label_b": replace(a, provenance=replace(prov, label="Table I, case (b)")),
        "a.label_free_text": replace(a, provenance=replace(prov, label="compared with Table I, case (b)")),
        "a.label_upper": replace(a, provenance=replace(prov, label="Table I, case (A)")),
        "a.claims_unknown": replace(a, provenance=replace(prov, obligations=("lemma2.P", "cor1.iss"))),
        "a.claims_two_unknown": replace(a, provenance=replace(prov, obligations=("cor1.iss", "lemma2.P", "hunting"))),
        "a.claims_nothing": replace(a, provenance=replace(prov, obligations=())),
        "a.no_provenance": replace(a, provenance=None),
        "a.physical_ok": replace(a, physical=_physical(a)),
        "a.physical_kp": replace(a, physical=_physical(a, k_p_bar=a.k_p * 3)),
        "a.physical_ki": replace(a, physical=_physical(a, k_i_bar=a.k_i * 3)),
        "a.physical_kv": replace(a, physical=_physical(a, alpha_v=F(1))),
        "a.physical_fc": replace(a, physical=_physical(a, f_c_bar=a.f_c * 3)),
    }
    return {name: _report_lines(verify_certificate(cert, source=name)) for name, cert in cases.items()}


def _namespace_cases() -> dict[str, list[str]]:
    """Premises decided from plain numbers (a stand-in, as the obligations pass symbols); zeros that divide are not evaluated."""
    a = _cert("case_a_tightest")
    base = {n: getattr(a, n) for n in ("k_p", "k_i", "k_v", "f_c", "k1", "k2", "k3", "k4", "c", "c1", "c2", "c1_hat", "c2_hat")}
    base["kappa"] = F(a.overshoot_bound)
    forged = {
        "ns.ok": {},
        "ns.k_i_negative": {"k_i": F(-4)},
        "ns.k_p_negative": {"k_p": F(-3)},
        "ns.f_c_zero": {"f_c": F(0)},
        "ns.c_zero": {"c": F(0)},
        "ns.c1_negative": {"c1": F(-1)},
        "ns.k2_negative": {"k2": F(-1)},
        "ns.k1_zero": {"k1": F(0)},
        "ns.c1_hat_negative": {"c1_hat": F(-1)},
        "ns.kappa_zero": {"kappa": F(0)},
        "ns.kappa_negative": {"kappa": -F(a.overshoot_bound)},
        # a zero divisor: the premises that divide by it fail unevaluated, beside the sign premise it breaks
        "ns.k_i_zero": {"k_i": F(0)},
        "ns.k_v_zero": {"k_v": F(0)},
        "ns.k_v_negative": {"k_v": F(-32, 5)},
        "ns.c1_zero": {"c1": F(0)},
        "ns.c1_hat_zero": {"c1_hat": F(0)},
        "ns.all_zero": {n: F(0) for n in base},
    }
    out = {}
    for name, change in forged.items():
        checks = tuple(decide(p) for p in premises(SimpleNamespace(**dict(base, **change))))
        out[name] = [f"{c.obligation} | {c}" for c in checks]
    return out


def _decide_cases() -> dict[str, list[str]]:
    def psd(m):
        return str(decide(Semidefinite("o", "M ⪰ 0", tuple(tuple(F(x) for x in row) for row in m))))

    def ineq(lhs, op, rhs, text=None, terms=()):
        return str(decide(Inequality("o", f"l {op} r", F(lhs), op, F(rhs), text, tuple(F(t) for t in terms))))

    lines = [
        psd([[1, 0, 0], [0, 1, 0], [0, 0, 1]]),
        psd([[0, 0, 0], [0, 0, 0], [0, 0, 0]]),
        psd([[1, 0, 0], [0, 0, 0], [0, 0, -1]]),  # only the minor {3} is negative
        psd([[0, 0, 1], [0, 0, 0], [1, 0, 0]]),  # leading minors 0, 0, 0; {1,3} = -1
        psd([[1, 2, 0], [2, 1, 0], [0, 0, 1]]),  # {1,2} = -3
        psd([[2, 1, 1], [1, 2, 1], [1, 1, 2]]),
        psd([[1, 1, 1], [1, 1, 1], [1, 1, 1]]),  # singular, PSD, smallest minor 0
        psd([[F(1, 3), 0, 0], [0, F(1, 7), 0], [0, 0, 5]]),
        psd([[4, 2, 2], [2, 1, 2], [2, 2, 4]]),  # {2,3} = 0, det < 0
        ineq(2, ">", 1), ineq(1, ">", 1), ineq(0, ">", 1),
        ineq(2, ">=", 1), ineq(1, ">=", 1), ineq(0, ">=", 1),
        ineq(1, "<=", 2), ineq(1, "<=", 1), ineq(2, "<=", 1),
        ineq(1, "==", 1), ineq(1, "==", 2), ineq(F(1, 3), "==", F(2, 6), "({} + {})", (F(1, 6), F(1, 6))),
        ineq(3, ">=", 2, "2·({} − {})", (3, 2)),
    ]
    return {"decide": lines}


def _all_cases() -> dict[str, list[str]]:
    return {**_forged_cases(), **_namespace_cases(), **_decide_cases()}


@pytest.fixture(scope="module")
def actual() -> dict[str, list[str]]:
    return _all_cases()


def test_every_report_is_the_golden_one(actual):
    assert_golden("verify_reports.json", actual)


def test_the_golden_file_has_both_verdicts_for_every_obligation(actual):
    """The pinned reports are not vacuous: every obligation the verifier names fails somewhere and holds somewhere."""
    verdicts: dict[str, set[str]] = {}
    for lines in actual.values():
        for line in lines:
            head, _, rest = line.partition(" | ")
            if rest[:1] in "✓✗" and rest:
                verdicts.setdefault(head, set()).add(rest[0])
    for obligation in ("lemma2.P", "model", "lemma2.dVdt", "lemma2.lower_bound", "lemma3.R", "lemma3.hatV_bounds",
                       "lemma3.hatV_derivative", "prop1.stability_bound", "provenance"):
        assert verdicts[obligation] == {"✓", "✗"}, obligation


def test_the_committed_certificates_verify_and_a_forged_one_does_not():
    for name in ("case_a_feasible", "case_a_tightest", "case_b_feasible", "case_b_tightest"):
        report = verify_file(ROOT / "proofs" / f"{name}.json")
        assert report.proved and report.failures == ()
        assert report.source.endswith(f"{name}.json")
        report.raise_if_failed()
    bad = verify_certificate(replace(_cert("case_a_tightest"), c2=F(1)))
    assert not bad.proved
    assert [c.name for c in bad.failures] == ["c2·I − P ⪰ 0"]
    with pytest.raises(CertificateError, match=r"^FAILED <certificate>: c2·I − P ⪰ 0: .* is false$"):
        bad.raise_if_failed()


def test_determinants_in_the_entries_own_arithmetic():
    assert _det([]) == 1 and isinstance(_det([]), F)
    assert _det([[F(5, 3)]]) == F(5, 3)
    assert _det([[1, 2], [3, 4]]) == -2
    assert _det([[0, 1], [1, 0]]) == -1
    assert _det([[0, 0, 1], [0, 1, 0], [1, 0, 0]]) == -1
    assert _det([[2, 0, 1], [1, 3, 2], [1, 1, 1]]) == 0
    assert _det([[1, 2, 3], [4, 5, 6], [7, 8, 10]]) == -3


def test_semidefinite_lists_every_principal_minor_smallest_first():
    m = Semidefinite("o", "n", ((F(1), F(2), F(3)), (F(2), F(5), F(6)), (F(3), F(6), F(10))))
    minors = m.minors()
    assert [idx for idx, _ in minors] == [(0,), (1,), (2,), (0, 1), (0, 2), (1, 2), (0, 1, 2)]
    assert [d for _, d in minors] == [1, 5, 10, 1, 1, 14, 1]


def test_a_float_or_a_bool_is_refused_by_name():
    with pytest.raises(CertificateError, match=r"^k3 > k2: the verifier decides exact rationals only; got float 0\.5$"):
        decide(Inequality("o", "k3 > k2", 0.5, ">", F(0)))
    with pytest.raises(CertificateError, match="got bool True"):
        decide(Inequality("o", "k3 > k2", F(1), ">", True))
    with pytest.raises(CertificateError, match=r"^M: .*got float"):
        decide(Semidefinite("o", "M", ((F(1), 0.0, F(0)), (F(0), F(1), F(0)), (F(0), F(0), F(1)))))
    assert decide(Inequality("o", "n", 2, ">", 1)).holds  # ints are exact


def test_verify_certificate_refuses_what_is_not_a_certificate():
    with pytest.raises(TypeError, match="^verify_certificate needs a Certificate; got dict$"):
        verify_certificate({})


def test_check_message_and_str():
    good, bad = Check("o", "a > b", "2 > 1", True), Check("o", "a > b", "1 > 2", False)
    assert (good.message, str(good)) == ("a > b: 2 > 1", "✓ a > b: 2 > 1")
    assert (bad.message, str(bad)) == ("a > b: 1 > 2 is false", "✗ a > b: 1 > 2 is false")


def test_provenance_is_checked_without_a_label_match():
    """A provenance whose obligations are all proved, with a label that is not Table I's: one check, holding."""
    a = _cert("case_a_tightest")
    prov = Provenance(mode="m", margin=F(1), solver="s", solver_status="t", package_version="0", obligations=("lemma2.P",), label="x")
    report = verify_certificate(replace(a, provenance=prov))
    assert [(c.name, c.holds) for c in report.checks if c.obligation == "provenance"] == [
        ("provenance.obligations ⊆ obligations instantiated", True)]


def test_verdicts_are_booleans():
    """``verify --json`` prints ``holds``: a verdict is ``True`` or ``False``, never a falsy stand-in."""
    eye = ((F(1), F(0), F(0)), (F(0), F(1), F(0)), (F(0), F(0), F(1)))
    assert decide(Semidefinite("o", "I", eye)).holds is True
    assert decide(Semidefinite("o", "-I", tuple(tuple(-x for x in row) for row in eye))).holds is False
    assert decide(Inequality("o", "n", F(1), ">", F(2))).holds is False
    assert decide(Inequality("o", "n", F(3), ">", F(2))).holds is True
    undefined = decide(Undefined("o", "n", "it divides by 0"))
    assert undefined.holds is False and undefined.evaluated is False and str(undefined) == "✗ n: not evaluated (it divides by 0)"


def test_a_float_anywhere_in_a_premise_is_refused_by_the_premise_name():
    with pytest.raises(CertificateError, match=r"^c1 ≤ c2: .*got float 0\.25$"):
        decide(Inequality("o", "c1 ≤ c2", F(1), "<=", 0.25))
    with pytest.raises(CertificateError, match=r"^c = 2\(k_v·k_p − k_i\): .*got float 1\.5$"):
        decide(Inequality("o", "c = 2(k_v·k_p − k_i)", F(1), "==", F(1), "2·({} − {})", (1.5, F(1))))


def test_a_non_strict_k_condition_is_decided_as_non_strict(monkeypatch):
    """All of the paper's k-conditions are strict; a non-strict one (the form on R̂) must become a ≥ premise."""
    from symbolic_friction._certify import verify as V
    from symbolic_friction._model.kconditions import k_conditions

    def lax(*args):
        return tuple(replace(c, strict=False) if c.name == "k3 > k2" else c for c in k_conditions(*args))

    monkeypatch.setattr(V, "k_conditions", lax)
    a = _cert("case_a_tightest")
    ns = SimpleNamespace(**{n: getattr(a, n) for n in ("k_p", "k_i", "k_v", "f_c", "k1", "k2", "k3", "k4", "c", "c1", "c2",
                                                      "c1_hat", "c2_hat")}, kappa=F(a.overshoot_bound))
    ns.k3 = ns.k2
    (k3k2,) = [p for p in premises(ns) if p.name == "k3 > k2"]
    assert k3k2.op == ">="
    assert decide(k3k2).holds is True and str(decide(k3k2)) == "✓ k3 > k2: 2 ≥ 2"


def test_text_of_rationals_past_pythons_digit_limit():
    """A numerator or a denominator of 20,000 bits (over 4,300 digits: ``str`` refuses it) is still written exactly."""
    from flint import fmpq

    from symbolic_friction._certify.verify import _matrix_text, _text
    from symbolic_friction._infra.rational import format_rational

    def q(x: F) -> fmpq:
        return fmpq(x.numerator, x.denominator)

    huge = 2**20_000 + 1
    for x in (F(1, huge), F(huge, 3), F(-huge, huge + 2), F(3, 7), F(-5), F(0), F(12)):
        assert _text(q(x)) == format_rational(x)
    assert _text(q(F(1, huge))).startswith("1/3980276840") and len(_text(q(F(1, huge)))) == 2 + 6021
    assert _matrix_text([[q(F(1, 2)), q(F(huge))]]) == f"[1/2, {format_rational(F(huge))}]"


@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_determinant_of_every_size_is_sympys_in_fractions_and_fmpq(n):
    """Every entry counts, at every size the verifier meets (4×4 for the sup-flow template's forms)."""
    import random

    import sympy as sp
    from flint import fmpq

    from symbolic_friction._certify.verify import _det

    rng = random.Random(n)
    for _ in range(40):
        m = [[F(rng.randint(-9, 9), rng.randint(1, 5)) for _ in range(n)] for _ in range(n)]
        want = F(str(sp.Matrix([[sp.Rational(x.numerator, x.denominator) for x in row] for row in m]).det()))
        assert _det(m) == want
        got = _det([[fmpq(x.numerator, x.denominator) for x in row] for row in m])
        assert type(got) is fmpq and (got.p, got.q) == (want.numerator, want.denominator)


def test_exact_takes_ints_and_rationals_to_fmpq_and_refuses_the_rest():
    from flint import fmpq

    from symbolic_friction._certify.verify import _exact

    for value in (3, F(-7, 4), fmpq(5, 6), 10**400 + 1):
        q = _exact(value, "x")
        assert type(q) is fmpq and (q.p, q.q) == (F(value).numerator if not isinstance(value, fmpq) else 5,
                                                   F(value).denominator if not isinstance(value, fmpq) else 6)
    for bad in (True, 0.5, "1/2", None, complex(1, 0)):
        with pytest.raises(CertificateError, match=f"x: the verifier decides exact rationals only; got {type(bad).__name__}"):
            _exact(bad, "x")
