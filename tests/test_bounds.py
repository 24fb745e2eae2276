"""Every printed bound rounds in its safe direction (:mod:`symbolic_friction._infra.bounds`).

An upper bound (κ, κ/κ_lin, ρ, a settling time, the hunting escape bound, an enclosure's right end) is
printed rounded up; a lower bound (κ_lin's proven lower end, a hypothesis' radius, an enclosure's left end)
rounded down.  Each place that prints one is checked against the exact value it prints, at values chosen
so that rounding to nearest would print the unsafe side.
"""

from __future__ import annotations

import re
from fractions import Fraction
from pathlib import Path
from types import SimpleNamespace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symbolic_friction._infra.bounds import bound_text

ROOT = Path(__file__).resolve().parents[1]
NUMBER = r"-?\d+(?:\.\d+)?(?:e[+-]?\d+)?"


@settings(max_examples=400, deadline=None)
@given(st.fractions(min_value=Fraction(-10**30), max_value=Fraction(10**30)).filter(lambda q: q != 0),
       st.integers(min_value=1, max_value=20))
def test_up_is_the_least_decimal_above_and_down_the_greatest_below(q, digits):
    up, down = Fraction(bound_text(q, digits, direction="up")), Fraction(bound_text(q, digits, direction="down"))
    assert down <= q <= up
    assert up == down or up > down  # equal exactly when q has at most `digits` digits
    if up != q:
        assert down < q < up
    for text in (bound_text(q, digits, direction="up"), bound_text(q, digits, direction="down")):
        mantissa = re.sub(r"e.*$", "", text).lstrip("-").replace(".", "").lstrip("0")
        assert len(mantissa) <= digits, text


def test_refuses_floats_and_bad_directions():
    with pytest.raises(TypeError):
        bound_text(0.1, direction="up")
    with pytest.raises(ValueError):
        bound_text(Fraction(1, 3), direction="nearest")
    with pytest.raises(ValueError):
        bound_text(Fraction(1, 3), 0, direction="up")


def test_certify_prints_kappa_over_kappa_lin_up_and_kappa_lin_down():
    from symbolic_friction._certify.choose import TemplateChoice

    # nearest would print 1.0212 and 1.3732678: both claims stronger than what is proven
    fake = SimpleNamespace(kappa_lin_lower=Fraction(137326775, 10**8), ratio=Fraction(102124, 10**5))
    assert TemplateChoice.against_kappa_lin(fake) == "κ ≤ 1.0213·κ_lin (κ_lin ≥ 1.3732677, proven)"


def _numbers_after(text: str, label: str) -> Fraction:
    match = re.search(re.escape(label) + r"\s*(" + NUMBER + ")", text)
    assert match, (label, text)
    return Fraction(match.group(1))


def test_reset_contraction_prints_rho_and_times_up_and_its_hypotheses_down():
    from symbolic_friction._certify.reset_contraction import RESET_CONTRACTION, load_contraction, verify_contraction

    cert = load_contraction(ROOT / "proofs" / "reset" / "case_a_contraction.json")
    summary = verify_contraction(cert).summary()
    assert _numbers_after(summary, "|σ_k| ≤") >= cert.rho
    assert _numbers_after(summary, "exits ≤") >= cert.cycle_time
    assert _numbers_after(summary, "for t ≥") >= cert.settling_time
    assert _numbers_after(summary, "stick exit with |σ| ≤") <= cert.radius
    assert _numbers_after(summary, "every dwell ≤") <= max(cert.dwell, cert.tau_lo)
    claim = RESET_CONTRACTION.claim(cert)
    assert _numbers_after(claim, "ρ ≤") >= cert.rho and _numbers_after(claim, "by t =") >= cert.settling_time
    assert _numbers_after(claim, "|σ_0| ≤") <= cert.radius
    assert Fraction(cert.claim_column.removeprefix("ρ≤")) >= cert.rho
    # at a value where nearest rounds down, the column rounds up
    import dataclasses

    edge = dataclasses.replace(cert, rho=Fraction(4586331, 10**7))
    assert edge.claim_column == "ρ≤0.458634"


def test_hunting_prints_its_enclosures_outward():
    from symbolic_friction._certify.hunting import load_hunting, verify_hunting

    for path in sorted((ROOT / "proofs" / "hunting").glob("*.json")):
        cert = load_hunting(path)
        summary = verify_hunting(cert).summary()
        lo, hi = cert.box.sigma
        got = re.search(r"σ\* ∈ \[(" + NUMBER + r"), (" + NUMBER + r")\]", summary)
        assert Fraction(got.group(1)) <= lo and Fraction(got.group(2)) >= hi, summary


def test_hunting_prints_the_escape_bound_up(capsys, tmp_path):
    from symbolic_friction._cli.main import main
    from symbolic_friction._hunting._map import real_root_escape
    from symbolic_friction._model.parameters import Parameters

    gains = ["--k-p", "0.66", "--k-i", "0.08", "--k-v", "1.5", "--f-c", "1", "--f-s", "1.2"]
    main(["hunting", *gains, "--out", str(tmp_path), "--no-simulation", "--no-iss"])
    out = capsys.readouterr().out
    escape = real_root_escape(Parameters(k_p=Fraction(33, 50), k_i=Fraction(2, 25), k_v=Fraction(3, 2), f_c=1,
                                         f_s=Fraction(6, 5)))
    assert _numbers_after(out, "|σ| ≥ |λ₁|(f_s - f_c) =") >= escape.bound
    below = re.search(r"< (" + NUMBER + r"): below the escape bound", out)
    assert below is None or Fraction(below.group(1)) >= escape.bound
    lo, hi = escape.root_bracket
    if lo != hi:
        got = re.search(r"λ₁ ∈ \[(" + NUMBER + r"), (" + NUMBER + r")\]", out)
        assert Fraction(got.group(1)) <= lo and Fraction(got.group(2)) >= hi


@pytest.mark.parametrize("gains,prefix", [((3, 4, Fraction(32, 5)), "1.3732"), ((Fraction(33, 50), Fraction(2, 25), Fraction(3, 2)), "2.3969")])
def test_the_documents_print_kappa_lin_lower_ends_rounded_down(gains, prefix):
    """README and the documentation site print κ_lin's proven lower end for Table I: never above it."""
    from symbolic_friction._certify.flow_bound import kappa_lin_bound, kappa_lin_lower
    from symbolic_friction._model.parameters import Parameters

    params = Parameters(k_p=gains[0], k_i=gains[1], k_v=gains[2], f_c=1)
    lower, upper = kappa_lin_lower(params), kappa_lin_bound(params).upper
    texts = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    found = []
    for path in texts:
        for match in re.finditer(re.escape(prefix) + r"\d*", path.read_text(encoding="utf-8")):
            found.append((path.name, match.group(0)))
    assert found, f"no κ_lin lower end {prefix}… printed in README or docs"
    for name, text in found:
        assert Fraction(text) <= lower or Fraction(text) >= upper, (name, text, float(lower))
