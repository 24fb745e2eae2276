"""The Krawczyk proof of hunting cycles, pinned on the committed boxes and on forged ones (kills its mutants).

For every committed hunting certificate and for forged boxes (shifted, with
``σ ≤ 0``, ``τ_a`` past the box, ``f_s = f_c``, ``τ_a`` where ``v`` still
rises, a ``v`` with an early dip) the full list of checks (name, verdict and
the enclosures that decided it), the verdict, the multiplier's enclosure and
the stability are compared with ``golden/hunting_proofs.json``.  Every line
comes from exact rationals and arb balls at a fixed precision, so it is
deterministic.  Regenerate only after checking the difference by hand::

    SF_REGENERATE_GOLDEN=1 python -m pytest -n 0 tests/certify/test_hunting_proof_mutants.py
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
from fractions import Fraction as F
from pathlib import Path

import pytest

from symbolic_friction import Parameters
from symbolic_friction._certify import hunting_proof as H
from symbolic_friction._certify.hunting import load_hunting

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = Path(__file__).parent / "golden" / "hunting_proofs.json"
NAMES = ("case_a_fs1.2", "case_b_fs1.2", "triple_root_fs1.2", "stiff_fs1.2", "high_gain_fs1.4")


def _cert(name):
    return load_hunting(ROOT / "proofs" / "hunting" / f"{name}.json")


def _lines(proof: H.CycleProof) -> list[str]:
    return [str(ch) for ch in proof.checks] + [f"proved {proof.proved}", f"multiplier {proof.multiplier!r}",
                                                f"stable {proof.stable}"]


def _cases(monkeypatch) -> dict[str, list[str]]:
    out = {}
    for name in NAMES:
        c = _cert(name)
        out[name] = _lines(H.prove_cycle(c.params, c.box, precision=c.precision_bits))
    c = _cert("case_a_fs1.2")
    p, box = c.params, c.box
    (s_lo, s_hi), (t_lo, t_hi) = box.sigma, box.tau
    ws, wt = s_hi - s_lo, t_hi - t_lo
    forged = {
        "sigma_shifted_up": dataclasses.replace(box, sigma=(s_lo + 2 * ws, s_hi + 2 * ws)),
        "sigma_shifted_down": dataclasses.replace(box, sigma=(s_lo - 2 * ws, s_hi - 2 * ws)),
        "tau_shifted_up": dataclasses.replace(box, tau=(t_lo + 2 * wt, t_hi + 2 * wt)),
        "tau_shifted_down": dataclasses.replace(box, tau=(t_lo - 2 * wt, t_hi - 2 * wt)),
        "sigma_half_out": dataclasses.replace(box, sigma=(s_lo + ws / 2, s_hi + ws / 2)),
        "tau_half_out": dataclasses.replace(box, tau=(t_lo - wt / 2, t_hi - wt / 2)),
        "sigma_wide": dataclasses.replace(box, sigma=(s_lo - 1000 * ws, s_hi + 1000 * ws)),
        "sigma_negative": dataclasses.replace(box, sigma=(-s_hi, -s_lo)),
        "sigma_from_zero": dataclasses.replace(box, sigma=(F(0), s_hi)),
        "sigma_reversed": dataclasses.replace(box, sigma=(s_hi, s_lo)),
        "tau_reversed": dataclasses.replace(box, tau=(t_hi, t_lo)),
        "monotone_at_box": dataclasses.replace(box, monotone_from=t_lo),
        "monotone_zero": dataclasses.replace(box, monotone_from=F(0)),
        "monotone_early": dataclasses.replace(box, monotone_from=F(1, 10)),
    }
    for name, b in forged.items():
        out[name] = _lines(H.prove_cycle(p, b))
    out["f_s_equals_f_c"] = _lines(H.prove_cycle(Parameters.table_i("a"), box))
    out["f_s_below_box_stick"] = _lines(H.prove_cycle(dataclasses.replace(p, f_s=F(11, 10)), box))
    out["other_gains"] = _lines(H.prove_cycle(_cert("case_b_fs1.2").params, box))
    real = H._Arb.state

    def dipping(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        if self.ball(F(1, 2), F(1)).overlaps(tau):
            y = [y[0], y[1], y[2] - 1]
        return E, y, dy

    with monkeypatch.context() as m:
        m.setattr(H._Arb, "state", dipping)
        out["v_dips"] = _lines(H.prove_cycle(p, box))

    def straddling(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        if self.ball(F(1, 2), F(1)).overlaps(tau):
            y = [y[0], y[1], y[2] * 0 + self.arb(0, 1)]  # a ball that contains 0 is not positive
        return E, y, dy

    with monkeypatch.context() as m:
        m.setattr(H._Arb, "state", straddling)
        out["v_straddles_zero"] = _lines(H.prove_cycle(p, box))

    def no_start(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        return E, y, [dy[0], dy[1], dy[2] - 10**6]

    with monkeypatch.context() as m:
        m.setattr(H._Arb, "state", no_start)
        out["v_never_rises"] = _lines(H.prove_cycle(p, box))
    out["box_around"] = [repr(H.box_around(0.1, 2.5)), repr(H.box_around(-0.25, 0.05, relative=1e-6)),
                         repr(H.box_around(3.0, 1000.0))]
    return out


@pytest.fixture(scope="module")
def actual():
    with pytest.MonkeyPatch.context() as mp:
        return _cases(mp)


def test_every_proof_is_the_golden_one(actual):
    if os.environ.get("SF_REGENERATE_GOLDEN"):
        GOLDEN.write_text(json.dumps(actual, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    golden = json.loads(GOLDEN.read_text(encoding="utf-8"))
    assert sorted(actual) == sorted(golden)
    for name in golden:
        assert actual[name] == golden[name], name


def test_the_golden_file_has_every_check_both_ways(actual):
    seen: dict[str, set[str]] = {}
    for lines in actual.values():
        for line in lines:
            verdict, _, rest = line.partition("  ")
            if verdict in ("holds", "FAILS"):
                seen.setdefault(rest.split(":")[0], set()).add(verdict)
    for check in ("box", "krawczyk", "first_zero.start", "first_zero.positive", "first_zero.decreasing", "stick"):
        assert seen[check] == {"holds", "FAILS"}, check
    for name in NAMES:
        assert actual[name][-3] == "proved True" and actual[name][-1] == "stable True"


def test_a_forged_box_is_never_proved(actual):
    for name, lines in actual.items():
        if name not in NAMES and name not in ("box_around", "sigma_wide"):
            assert "proved False" in lines, name


def test_the_helpers_round_outward_and_exactly():
    from flint import arb

    x = arb(1) / 3
    assert H._lower(x) <= 1 / 3 <= H._upper(x) and H._lower(x) < H._upper(x)
    assert H._lower(arb(2)) == math.nextafter(2.0, 0) and H._upper(arb(2)) == math.nextafter(2.0, 3)
    assert H._exact_mid(arb(1) / 4) == F(1, 4) and H._exact_mid(arb(3) * 8) == 24 and H._exact_mid(arb(-5) / 2) == F(-5, 2)
    assert H._short(F(0)) == 0 and H._short(F(1, 3)) == F("0.33333333333333331")
    assert H._short(F(-2)) == -2


def test_the_precision_is_set_for_the_proof_and_restored(monkeypatch):
    from flint import ctx

    seen = []
    real = H._prove

    def spy(params, box):
        seen.append(ctx.prec)
        return real(params, box)

    monkeypatch.setattr(H, "_prove", spy)
    c = _cert("case_a_fs1.2")
    before = ctx.prec
    H.prove_cycle(c.params, c.box, precision=200)
    assert seen == [200] and ctx.prec == before
    with pytest.raises(RuntimeError):
        monkeypatch.setattr(H, "_prove", lambda params, box: (_ for _ in ()).throw(RuntimeError("x")))
        H.prove_cycle(c.params, c.box, precision=300)
    assert ctx.prec == before
