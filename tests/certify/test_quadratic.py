"""The quadratic template (beyond the paper): the committed files, every verifier premise refused when
broken, the copositivity decision on each of its branches, the file format, and trajectories that never
contradict a proved certificate."""

from __future__ import annotations

import dataclasses
import json
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._certify import copositive
from symbolic_friction._certify.copositive import decide_copositive
from symbolic_friction._certify.quadratic import (
    QUADRATIC,
    QuadraticCertificate,
    dumps_quadratic,
    quadratic_premises,
    verify_quadratic,
)
from symbolic_friction._certify.templates import verify_template_file
from symbolic_friction._infra.errors import CertificateFormatError

PROOFS = Path(__file__).resolve().parents[2] / "proofs" / "quadratic"
F = Fraction


def _load(case: str) -> QuadraticCertificate:
    return QuadraticCertificate.from_dict(json.loads((PROOFS / f"case_{case}.json").read_text()), source=case)


@pytest.mark.parametrize("case, target", [("a", F("1.85")), ("b", F("3.35"))])
def test_committed_files_prove_the_target_bound(case, target):
    template, report = verify_template_file(PROOFS / f"case_{case}.json")
    assert template is QUADRATIC
    assert report.proved, report.summary()
    assert report.certificate.kappa <= target
    table = Parameters.table_i(case)
    assert report.certificate.parameters == {n: getattr(table, n) for n in ("k_p", "k_i", "k_v", "f_c")}
    assert QUADRATIC.stale(report.certificate, PROOFS / f"case_{case}.json") == ""


def _with(cert: QuadraticCertificate, **changes) -> QuadraticCertificate:
    constants = dict(cert.constants)
    overshoot = changes.pop("overshoot_bound", cert.overshoot_bound)
    gains = {k: changes.pop(k) for k in ("k_p", "k_i", "k_v") if k in changes}
    constants.update({k: F(v) for k, v in changes.items()})
    return dataclasses.replace(cert, constants=constants, overshoot_bound=overshoot, **gains)


BREAKS = [
    ("k_v·k_p > k_i", dict(k_i=F(100))),
    ("P − I ⪰ 0", dict(p22=F(1, 2))),
    ("c2·I − P ⪰ 0", dict(c2=F(1))),
    ("c > 0", dict(c=F(0))),
    ("−(AᵀP + PA) − c·e3e3ᵀ ⪰ 0", dict(c=F(1000))),
    ("−(K·B+ + B+ᵀ·K) copositive", dict(k23=F(-1, 10))),
    ("band form (s = −1) copositive", dict(k13=F(0))),
    ("K31 ≥ 0", dict(k13=F(-1, 10))),
    ("K32 ≥ 0", dict(k23=F(-1, 10))),
    ("K33 ≥ 0", dict(k33=F(-1))),
    ("K − I copositive", dict(k22=F(1, 2))),
    ("gamma·I − K copositive", dict(gamma=F(1))),
    ("U − V copositive at v = 0", dict(k22=F(1))),
    ("U − V copositive at φ = ±f_c", dict(k33=F(1))),
    ("overshoot_bound² ≥ c2", dict(overshoot_bound="1.0")),
    ("overshoot_bound² ≥ gamma", dict(overshoot_bound="1.0")),
]


@pytest.mark.parametrize("name, change", BREAKS, ids=[b[0] for b in BREAKS])
def test_each_premise_refuses_a_forged_certificate(name, change):
    report = verify_quadratic(_with(_load("a"), **change))
    assert not report.proved
    assert name in {c.name for c in report.failures}, report.summary()
    assert name in report.summary()


def test_every_premise_has_a_breaking_case():
    names = {p.name for p in quadratic_premises(dataclasses.replace(_load("a")))}
    # the format refuses k_i, k_p, f_c ≤ 0 and κ ≤ 0 before the verifier runs
    structural = {"k_i > 0", "k_p > 0", "f_c > 0", "overshoot_bound > 0"}
    also = {"−(K·B− + B−ᵀ·K) copositive", "band form (s = +1) copositive"}  # the two tests below
    assert names - structural - also - {b[0] for b in BREAKS} == set()


def test_the_minus_sign_rate_premise_fails_alone():
    # a larger K₂₃ breaks only the s = −1 rate form
    cert = _load("a")
    report = verify_quadratic(_with(cert, k23=cert.constants["k23"] * F(6, 5)))
    assert [c.name for c in report.failures] == ["−(K·B− + B−ᵀ·K) copositive"]


def test_the_plus_sign_band_premise_can_fail():
    cert = _load("a")
    report = verify_quadratic(_with(cert, k13=-cert.constants["k13"]))
    assert "band form (s = +1) copositive" in {c.name for c in report.failures}


# -- the copositivity decision, branch by branch ----------------------------------------------


@pytest.mark.parametrize(
    "matrix, holds, words",
    [
        ([[F(-1)]], False, "diagonal entry 1"),
        ([[1, -2], [-2, 1]], False, "entry (1,2)"),
        ([[0, -1], [-1, 5]], False, "entry (1,2)"),  # a zero diagonal needs a nonnegative row
        ([[1, -1], [-1, 1]], True, "Hadeler"),  # b² = ac: on the boundary, still copositive
        ([[0, 1], [1, 0]], True, "Hadeler"),
        ([[1, 2, 3], [2, 1, 0], [3, 0, 1]], True, "every entry ≥ 0"),
        ([[2, -1, 0], [-1, 2, -1], [0, -1, 2]], True, "positive semidefinite"),
        ([[1, 1, -1], [1, 1, 1], [-1, 1, 1]], True, "Hadeler's 3×3 inequality holds"),  # copositive, not PSD
        ([[1, -1, 0], [-1, 1, -1], [0, -1, 1]], False, "Hadeler's 3×3 inequality fails"),  # every 2×2 face is fine
        # the same at half scale: Hadeler's inequality is −0.35, so a slack of 1 would accept it
        ([[F(1, 2), F(-1, 2), 0], [F(-1, 2), F(1, 2), F(-1, 2)], [0, F(-1, 2), F(1, 2)]], False, "fails: -0.35"),
    ],
)
def test_copositivity_branches(matrix, holds, words):
    decision = decide_copositive([[F(x) for x in row] for row in matrix])
    assert decision.holds is holds and words in decision.reason


def test_copositivity_samples_agree():
    rng = np.random.default_rng(5)
    grid = np.array([(i, j, 40 - i - j) for i in range(41) for j in range(41 - i)], dtype=float) / 40
    for _ in range(300):
        a = rng.integers(-4, 5, (3, 3))
        a = a + a.T
        decision = decide_copositive([[F(int(x)) for x in row] for row in a])
        smallest = np.einsum("ni,ij,nj->n", grid, a.astype(float), grid).min()
        if decision.holds:
            assert smallest >= -1e-12, a
        else:
            assert decision.holds is False  # never undecided on integers


def test_copositivity_undecided_is_not_proved(monkeypatch):
    # at 2 bits the balls of Hadeler's inequality cannot be separated from 0: the answer is "undecided"
    monkeypatch.setattr(copositive, "PRECISIONS", (2,))
    m = [[F(2), F(-1), F(8)], [F(-1), F(8), F(-1)], [F(8), F(-1), F(6)]]
    decision = decide_copositive(m)
    assert decision.holds is None and "undecided" in decision.reason
    monkeypatch.setattr(copositive, "PRECISIONS", (128,))
    assert decide_copositive(m).holds is True


def test_undecided_copositivity_fails_the_premise(monkeypatch):
    from symbolic_friction._certify import quadratic

    monkeypatch.setattr(quadratic, "decide_copositive", lambda m: copositive.CopositivityDecision(None, "undecided"))
    report = verify_quadratic(_load("a"))
    assert not report.proved and any("undecided" in c.instance for c in report.failures)


@pytest.mark.parametrize("bad", [[[F(1), F(2)], [F(3), F(1)]], [[1.0]], [[F(1)] * 4] * 4, []])
def test_copositivity_refuses_what_it_cannot_decide(bad):
    with pytest.raises(ValueError):
        decide_copositive(bad)


# -- file format ----------------------------------------------------------------------------


def test_round_trip_is_byte_identical():
    text = (PROOFS / "case_b.json").read_text()
    assert dumps_quadratic(QuadraticCertificate.from_dict(json.loads(text))) == text


@pytest.mark.parametrize(
    "edit",
    [
        lambda d: d["constants"].pop("gamma"),
        lambda d: d["constants"].__setitem__("k11", 1.5),
        lambda d: d["parameters"].__setitem__("k_p", "-3.0"),
        lambda d: d["parameters"].__setitem__("k_p", "- 3"),
        lambda d: d.__setitem__("template", "quadratic/v2"),
        lambda d: d["provenance"].__setitem__("extra", "x"),
        lambda d: d.__setitem__("overshoot_bound", "1e3"),
        lambda d: d.__setitem__("overshoot_bound", "+1.9"),
    ],
)
def test_malformed_files_are_refused(edit):
    data = json.loads((PROOFS / "case_a.json").read_text())
    edit(data)
    with pytest.raises(CertificateFormatError):
        QuadraticCertificate.from_dict(data)


@pytest.mark.parametrize("group, name, text, failing", [
    ("parameters", "k_p", "-3", "k_p > 0"),
    ("parameters", "k_i", "0", "k_i > 0"),
    ("parameters", "k_v", "0", "k_v·k_p > k_i"),
    ("parameters", "k_v", "-32/5", "k_v·k_p > k_i"),
    ("parameters", "f_c", "0", "f_c > 0"),
    ("constants", "c", "-1", "c > 0"),
    ("overshoot_bound", None, "-1.9", "overshoot_bound > 0"),
    ("overshoot_bound", None, "0", "overshoot_bound > 0"),
])
def test_a_number_of_the_wrong_sign_is_read_and_refused_by_its_premise(group, name, text, failing):
    """A sign is a premise of the template, decided by the verifier (exit 1 of `verify`), not a format error (exit 2)."""
    data = json.loads((PROOFS / "case_a.json").read_text())
    if name is None:
        data[group] = text
    else:
        data[group][name] = text
    report = verify_quadratic(QuadraticCertificate.from_dict(data))
    assert not report.proved and failing in [c.name for c in report.failures]
    assert next(c for c in report.failures if c.name == failing).message.endswith(" is false")


def test_a_reformatted_file_is_stale(tmp_path):
    data = json.loads((PROOFS / "case_a.json").read_text())
    path = tmp_path / "case_a.json"
    path.write_text(json.dumps(data))
    assert "canonical" in QUADRATIC.stale(QuadraticCertificate.from_dict(data), path)


# -- trajectories never contradict a proved certificate --------------------------------------


@pytest.mark.parametrize("case", ["a", "b"])
def test_trajectories_respect_v_and_u(case):
    from symbolic_friction import simulate
    from symbolic_friction._model.coordinates import x_to_z, z_to_x

    params = Parameters.table_i(case)
    cert = _load(case)
    P = np.array(cert.p_matrix(), dtype=float)
    K = np.array(cert.k_matrix(), dtype=float)
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 30.0, 3001)
    for _ in range(12):
        x0 = rng.normal(size=3) * rng.choice([0.5, 2.0, 8.0])
        sol = simulate(params, x_to_z(params, x0), 30.0, t_eval=t)
        x = z_to_x(params, np.asarray(sol.z))
        s, ph, v = x[:, 0], x[:, 1], x[:, 2]
        f = np.where(v > 0, 1.0, np.where(v < 0, -1.0, np.clip(ph, -1.0, 1.0)))
        w = np.stack([s, ph - f, v], 1)
        V = np.einsum("ni,ij,nj->n", w, P, w)
        assert np.all(np.diff(V) <= 1e-9 * np.maximum(V[:-1], 1.0))
        dz = ph - np.clip(ph, -1.0, 1.0)
        y = np.abs(np.stack([s, dz, v], 1))
        U = np.einsum("ni,ij,nj->n", y, K, y)
        inside = v * (ph - np.sign(v)) < 0
        both = inside[:-1] & inside[1:]
        assert np.all(np.diff(U)[both] <= 1e-9 * np.maximum(U[:-1][both], 1.0))
        dist = np.sqrt(s**2 + dz**2 + v**2)
        assert dist.max() <= float(cert.kappa) * dist[0] * (1 + 1e-9)
