"""Numbers past Python's 4300-digit ``int``/``str`` limit, which the file format allows (found by the tampered corpora).

Regression tests of three findings of ``tests/independent/tampered.py``:

* a κ (``overshoot_bound``, a plain decimal) of more than 4300 digits made every verifier of a κ (paper point, box,
  quadratic, sup-flow) raise a ``ValueError`` from ``Fraction(text)``: it is now read by
  :func:`._certify._json.decimal_value`, exactly, and the file is decided;
* a hunting file with a gain of more than 4300 digits raised the same ``ValueError`` from a message (``str`` of the
  gain); it is decided now;
* a reset-contraction ``rho`` of more than 60 digits was "not evaluated", so a true file (``rho`` raised by
  ``10⁻⁷⁰``) was refused by the main verifier and proved by the independent one; ``rho^cycles ≤ tol`` is now decided
  by both alike: exactly while the power is short (650,000 bits), else in arb balls (undecided: not proved);
* the independent checker's messages held ``str()`` of such numbers (a sup-flow piece's end, a box corner), and its
  exact fallback measured ``rho`` by ``len(str(rho))``: a traceback instead of a verdict.
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import pytest

from symbolic_friction._certify._json import decimal_value
from symbolic_friction._certify.templates import verify_template_file
from symbolic_friction._cli.main import main
from symbolic_friction.independent import check_file
from tests.independent.tampered import rational_text

ROOT = Path(__file__).resolve().parents[2]


def _edited(tmp_path: Path, name: str, edit) -> Path:
    data = json.loads((ROOT / name).read_text(encoding="utf-8"))
    edit(data)
    path = tmp_path / "edited.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


@pytest.mark.parametrize("text, value", [
    ("3.5" + "0" * 5000, Fraction(7, 2)), ("-0.25", Fraction(-1, 4)), ("12", Fraction(12)),
    ("0." + "0" * 4999 + "1", Fraction(1, 10**5000)), ("-3.51842", Fraction(-351842, 100000)),
])
def test_a_decimal_of_any_length_is_read_exactly(text, value):
    assert decimal_value(text) == value


@pytest.mark.parametrize("name", ["proofs/case_a_feasible.json", "proofs/box_physical.json", "proofs/quadratic/case_a.json",
                                  "proofs/sup_flow/case_b.json", "tests/certify/data/sup_flow_v1/case_b.json"])
def test_a_kappa_of_thousands_of_digits_is_decided(tmp_path, capsys, name):
    def longer(data):  # the same κ and a hair more: 4400 more digits
        data["overshoot_bound"] += "0" * 4400 + "1"

    path = _edited(tmp_path, name, longer)
    _, report = verify_template_file(path)
    assert report.proved and check_file(str(path)).proved
    assert main(["verify", str(path)]) == 0
    assert "DISAGREE" not in capsys.readouterr().out

    def lower(data):  # far below the committed κ, in 4400 digits: false, refused (not a traceback)
        data["overshoot_bound"] = "1." + "0" * 4400 + "1"

    path = _edited(tmp_path, name, lower)
    assert not verify_template_file(path)[1].proved and not check_file(str(path)).proved


@pytest.mark.parametrize("gain", ["f_s", "f_c", "k_p"])
def test_a_hunting_gain_of_thousands_of_digits_is_decided(tmp_path, gain):
    def nudged(data):
        value = Fraction(data["parameters"][gain])
        data["parameters"][gain] = rational_text(value * (1 + Fraction(1, 10**4400)))

    path = _edited(tmp_path, "proofs/hunting/case_a_fs1.2.json", nudged)
    _, report = verify_template_file(path)
    assert report.proved == check_file(str(path)).proved
    assert "exact: a 44" in report.summary() or not report.proved


@pytest.mark.parametrize("exponent, cycles, low", [(70, 9, "1/2000"), (4400, 9, "1/2000"), (4400, 100, "1/10000000000000000000000000000000000000000")])
def test_a_long_rho_is_decided(tmp_path, exponent, cycles, low):
    # exactly while ρ^cycles is short (up to 650,000 bits), else in arb balls: both verifiers alike
    def rho(factor, tol=None):
        def edit(data):
            data["rho"] = rational_text(Fraction(data["rho"]) * factor)
            data["settling"]["cycles"] = cycles
            data["settling"]["time"] = rational_text(cycles * Fraction(data["cycle_time"]))
            if tol is not None:
                data["settling"]["tol"] = tol
        return edit

    # a weaker ρ (raised by 10^-exponent): true, and proved by both (it was "not evaluated" past 60 digits)
    path = _edited(tmp_path, "proofs/reset/case_a_contraction.json", rho(1 + Fraction(1, 10**exponent)))
    _, report = verify_template_file(path)
    assert report.proved and check_file(str(path)).proved
    # the same ρ with tol below ρ^cycles: refused by both, the power decided
    path = _edited(tmp_path, "proofs/reset/case_a_contraction.json", rho(1 + Fraction(1, 10**exponent), low))
    _, report = verify_template_file(path)
    failing = [c for c in report.checks if not c.holds]
    assert [c.name for c in failing] == ["rho^cycles ≤ tol"] and failing[0].evaluated
    assert ("∈" in failing[0].instance) == (cycles == 100)  # a ball past 650,000 bits
    assert check_file(str(path)).failing == ["rho^cycles ≤ tol"]


def test_a_long_rho_at_its_own_power_is_decided_exactly(tmp_path):
    # tol = ρ^cycles exactly: no ball decides it, so both verifiers decide it exactly (the power is short enough)
    def edit(data):
        rho = Fraction(data["rho"]) * (1 + Fraction(1, 10**70))
        data["rho"] = rational_text(rho)
        data["settling"]["tol"] = rational_text(rho ** data["settling"]["cycles"])

    path = _edited(tmp_path, "proofs/reset/case_a_contraction.json", edit)
    _, report = verify_template_file(path)
    check = next(c for c in report.checks if c.name == "rho^cycles ≤ tol")
    assert check.holds and report.proved and check_file(str(path)).proved


@pytest.mark.parametrize("name, place, factor", [
    ("proofs/sup_flow/case_b.json", ("pieces", 0, "end"), 1),
    ("tests/certify/data/sup_flow_v1/case_b.json", ("pieces", 1, "start"), 1),
    ("proofs/box_physical.json", ("pieces", 0, "k_v", 0), Fraction(1, 2)),  # a corner where premises fail, named
])
def test_the_independent_checker_names_a_long_number_without_raising(tmp_path, name, place, factor):
    # its messages held str() of the number, which raises past 4300 digits (a traceback, not a verdict)
    def edit(data):
        holder = data
        for key in place[:-1]:
            holder = holder[key]
        holder[place[-1]] = rational_text(Fraction(holder[place[-1]]) * factor * (1 + Fraction(1, 10**4400)))

    path = _edited(tmp_path, name, edit)
    verdict = check_file(str(path))
    assert not verdict.proved and not verify_template_file(path)[1].proved
    assert any("bits)" in name or "bits)" in why for name, _, why in verdict.premises)


def test_a_power_no_ball_decides_and_too_long_to_raise_is_not_proved_by_either(tmp_path):
    # ρ of 102 characters, 2000 cycles, tol within 2^-200 above ρ^2000: the main verifier raised it exactly (ρ had
    # fewer than 60 digits) and proved the file, the independent checker left it undecided; both leave it now
    def edit(data):
        rho = Fraction(458633 * 10**44 + 1, 10**50)
        power = rho ** 2000
        bits = 200 - power.numerator.bit_length() + power.denominator.bit_length()
        tol = Fraction(-((-power.numerator << bits) // power.denominator), 1 << bits)
        data["rho"], data["settling"] = rational_text(rho), {"cycles": 2000, "tol": rational_text(tol),
                                                              "time": rational_text(2000 * Fraction(data["cycle_time"]))}

    path = _edited(tmp_path, "proofs/reset/case_a_contraction.json", edit)
    _, report = verify_template_file(path)
    assert [(c.name, c.evaluated) for c in report.checks if not c.holds] == [("rho^cycles ≤ tol", False)]
    assert check_file(str(path)).failing == ["rho^cycles ≤ tol"]
