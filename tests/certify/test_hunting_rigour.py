"""The hunting proof's decisions on built inputs: each rigour case that `check` runs catches the weaker decision it targets."""

from __future__ import annotations

import inspect
import textwrap

import pytest

from symbolic_friction._certify import hunting_cycle, hunting_proof
from symbolic_friction._certify.hunting_rigour import rigour_cases


def test_every_case_is_decided_right_on_this_install():
    cases = rigour_cases()
    assert len(cases) == 19 and all(c.ok for c in cases), [(c.name, c.got) for c in cases if not c.ok]


def _mutant(module, name, old, new):
    source = textwrap.dedent(inspect.getsource(getattr(module, name)))
    assert old in source, old
    namespace = dict(vars(module))
    exec(compile(source.replace(old, new, 1), f"<mutant of {name}>", "exec"), namespace)
    return namespace[name]


MUTANTS = [
    (hunting_proof, "_inside", "(k - lo) > 0", "(k - lo) >= 0", "krawczyk: K touching the lower end"),
    (hunting_proof, "_inside", "(hi - k) > 0", "(hi - k) >= 0", "krawczyk: K touching the upper end"),
    (hunting_proof, "_inside", "bool((k - lo) > 0) and ", "", "krawczyk: K across the lower end"),
    (hunting_proof, "_inside", " and bool((hi - k) > 0)", "", "krawczyk: K across the upper end"),
    (hunting_proof, "_positive_on", "if bool(ball > 0):", "if not bool(ball < 0):", "first zero: a value touching 0"),
    (hunting_proof, "_positive_on", "or bool(ball <= 0):\n                return False, pieces",
     "or bool(ball <= 0):\n                return True, pieces", "first zero: a ball holding 0"),
    (hunting_proof, "_positive_on", "            if bool(ball > 0):\n                continue\n", "            continue\n",
     "first zero: a value touching 0"),
    (hunting_proof, "_positive_on", "range(64)", "range(63)", "first zero: negative on the last piece only"),
    (hunting_proof, "_positive_on", "range(64)", "range(1, 64)", "first zero: negative on the first piece only"),
    (hunting_proof, "_positive_on", "        if bool(ball > 0):\n            continue\n", "        if pieces > 1:\n            continue\n",
     "first zero: negative on the last piece only"),
    (hunting_proof, "_sticks", "phi > -f_s", "phi >= -f_s", "stick: φ = -f_s exactly"),
    (hunting_proof, "_sticks", "phi < f_s", "phi <= f_s", "stick: φ = f_s exactly"),
    (hunting_proof, "_shape_ok", "0 < s_lo < s_hi", "0 <= s_lo < s_hi", "shape: σ_lo = 0"),
    (hunting_proof, "_lower", "math.nextafter(float(x.lower()), -math.inf)", "float(x.lower())",
     "outward: the multiplier's floats"),
    (hunting_proof, "_upper", "math.nextafter(float(x.upper()), math.inf)", "float(x.upper())",
     "outward: the multiplier's floats"),
    (hunting_cycle, "_round", "-((-n.numerator) // n.denominator) if up else ", "round(n) if up else ",
     "outward: a written interval"),
]


@pytest.mark.parametrize("module, name, old, new, caught_by", MUTANTS, ids=[f"{m[1]}:{m[2][:24]}" for m in MUTANTS])
def test_each_weaker_decision_is_caught(monkeypatch, module, name, old, new, caught_by):
    monkeypatch.setattr(module, name, _mutant(module, name, old, new))
    failed = [c.name for c in rigour_cases() if not c.ok]
    assert any(f.startswith(caught_by) for f in failed), failed


def test_a_ball_without_its_radius_is_caught(monkeypatch):
    monkeypatch.setattr(hunting_proof._Arb, "ball", lambda self, lo, hi: self.q((lo + hi) / 2))
    failed = [c.name for c in rigour_cases() if not c.ok]
    assert "outward: a box's ball holds both ends" in failed
