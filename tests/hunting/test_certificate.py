"""Hunting certificates: written atomically, re-checked by `verify`, rejected when tampered with."""

from __future__ import annotations

import json
from fractions import Fraction as F
from pathlib import Path

import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import CertificateFormatError
from symbolic_friction._hunting import HuntingCertificate, box_around, find_cycles, verify_hunting_file, write_hunting
from symbolic_friction._hunting._report import with_static
from symbolic_friction._cli.main import main

A12 = with_static(Parameters.table_i("a"), F(6, 5))
PROOFS = Path(__file__).resolve().parents[2] / "proofs"


@pytest.fixture(scope="module")
def cert_file(tmp_path_factory):
    (c,) = find_cycles(A12, general=False)
    cert = HuntingCertificate(params=A12, box=box_around(c.sigma, c.slip_time), cycle={"period": f"{c.period:.17g}"})
    return write_hunting(cert, tmp_path_factory.mktemp("h") / "a.json")


def edited(tmp_path, src, edit):
    data = json.loads(Path(src).read_text(encoding="utf-8"))
    edit(data)
    out = tmp_path / "edited.json"
    out.write_text(json.dumps(data), encoding="utf-8")
    return out


def test_round_trip_verifies(cert_file):
    report = verify_hunting_file(cert_file)
    assert report.proved and report.summary().startswith("PROVED ")
    data = json.loads(Path(cert_file).read_text(encoding="utf-8"))
    assert data["parameters"] == {"k_p": "3", "k_i": "4", "k_v": "32/5", "f_c": "1", "f_s": "6/5"}
    assert data["schema"] == "symbolic-friction/hunting-certificate/v1" and data["verdict"] == "proved"


def test_verify_dispatches_on_the_schema(cert_file, capsys):
    assert main(["verify", str(cert_file), str(PROOFS / "case_a_tightest.json")]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("PROVED ") and "hunting cycle" in out[0]
    assert out[1].startswith("PROVED ") and "29 inequalities" in out[1]


def _shift_sigma(d):
    lo, hi = (F(x) for x in d["box"]["sigma"])
    w = hi - lo
    d["box"]["sigma"] = [str(lo + 2 * w), str(hi + 2 * w)]


def _shrink_sigma(d):
    lo, hi = (F(x) for x in d["box"]["sigma"])
    d["box"]["sigma"] = [str(lo), str(lo + (hi - lo) / 10)]  # σ* is at the centre: no longer inside


@pytest.mark.parametrize(
    "edit",
    [
        _shift_sigma,
        _shrink_sigma,
        lambda d: d["parameters"].update(k_v="6401/1000"),
        lambda d: d["parameters"].update(f_s="12001/10000"),
        lambda d: d["parameters"].update(f_s="1"),
        lambda d: d.update(verdict="not proved"),
    ],
    ids=["interval-moved", "interval-shrunk", "k_v", "f_s", "f_s=f_c", "verdict"],
)
def test_tampering_is_rejected(cert_file, tmp_path, capsys, edit):
    path = edited(tmp_path, cert_file, edit)
    assert main(["verify", str(path)]) == 1
    assert capsys.readouterr().out.startswith("NOT PROVED ")


@pytest.mark.parametrize(
    "edit, match",
    [
        (lambda d: d["box"].update(sigma=[0.1, 0.2]), "must be a string holding an exact rational"),
        (lambda d: d.update(extra=1), "unknown keys"),
        (lambda d: d["parameters"].pop("f_s"), "parameters must have exactly"),
        (lambda d: d["parameters"].update(f_s="1/2"), "f_s ≥ f_c"),
        (lambda d: d.update(precision_bits=8), "precision_bits"),
    ],
)
def test_malformed_files_are_refused(cert_file, tmp_path, capsys, edit, match):
    path = edited(tmp_path, cert_file, edit)
    with pytest.raises(CertificateFormatError, match=match):
        verify_hunting_file(path)
    assert main(["verify", str(path)]) == 2


COMMITTED = sorted((Path(__file__).resolve().parents[2] / "proofs" / "hunting").glob("*.json"))


def test_the_committed_hunting_certificates_verify():
    """Table I (a), (b) with f_s = 1.2 f_c and three other gain sets (written by `symbolic-friction hunting`)."""
    assert len(COMMITTED) >= 5
    for path in COMMITTED:
        assert verify_hunting_file(path).proved, path


def test_check_verifies_a_listed_hunting_certificate_and_catches_a_moved_box(cert_file, tmp_path):
    from symbolic_friction._certify import check_listed_certificates

    good = edited(tmp_path, cert_file, lambda d: None)
    (entry,) = check_listed_certificates(tmp_path, [good.name])
    assert entry.ok and "a hunting cycle" in entry.describe()
    bad = edited(tmp_path, cert_file, _shift_sigma)
    (entry,) = check_listed_certificates(tmp_path, [bad.name])
    assert not entry.ok and entry.describe().startswith("FAILED") and "NOT PROVED" in entry.reason


def test_crosscheck_leaves_hunting_certificates_to_verify(cert_file, tmp_path, monkeypatch):
    # with no files crosscheck takes the configured certificates: the hunting ones are not its business
    (tmp_path / "proofs").mkdir()
    edited(tmp_path / "proofs", cert_file, lambda d: None)
    monkeypatch.chdir(tmp_path)
    assert main(["crosscheck"]) == 2  # refused as "no certificate", not fed to the stability checks


def test_hunting_files_are_read_as_strictly_as_stability_certificates(cert_file, tmp_path):
    text = Path(cert_file).read_text(encoding="utf-8")
    duplicate = tmp_path / "dup.json"
    duplicate.write_text(text.replace('"verdict": "proved"', '"verdict": "proved", "verdict": "proved"'), encoding="utf-8")
    with pytest.raises(CertificateFormatError, match="duplicate key 'verdict'"):
        verify_hunting_file(duplicate)
    loose = edited(tmp_path, cert_file, lambda d: d["parameters"].update(k_p="3.0"))
    with pytest.raises(CertificateFormatError, match="parameters.k_p must be an exact rational string"):
        verify_hunting_file(loose)
