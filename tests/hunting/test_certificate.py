"""Hunting certificates: written atomically, re-checked by `verify`, rejected when tampered with."""

from __future__ import annotations

import json
from fractions import Fraction as F
from pathlib import Path

import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import CertificateFormatError
from symbolic_friction._certify.hunting import certificate_for
from symbolic_friction._hunting import find_cycles, verify_hunting_file, write_hunting
from symbolic_friction._hunting._report import with_static
from symbolic_friction._cli.main import main

A12 = with_static(Parameters.table_i("a"), F(6, 5))
PROOFS = Path(__file__).resolve().parents[2] / "proofs"


@pytest.fixture(scope="module")
def cert_file(tmp_path_factory):
    (c,) = find_cycles(A12, general=False)
    cert, _ = certificate_for(A12, c.sigma, c.slip_time)
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

    good = tmp_path / "good.json"
    good.write_bytes(Path(cert_file).read_bytes())
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


def test_every_number_of_cycle_is_decided_and_an_edited_one_fails_naming_it(cert_file, tmp_path, capsys):
    data = json.loads(Path(cert_file).read_text(encoding="utf-8"))
    assert sorted(data["cycle"]) == ["multiplier", "period", "sigma", "slip_time", "stable", "stick_time"]
    for field, value in [("period", ["99", "99"]), ("stick_time", ["0", "1"]), ("slip_time", ["1", "2"]),
                         ("sigma", ["1/2", "1"]), ("multiplier", ["-1", "0"]), ("stable", False)]:
        path = edited(tmp_path, cert_file, lambda d: d["cycle"].update({field: value}))
        report = verify_hunting_file(path)
        assert [c.name for c in report.checks if not c.holds] == [f"cycle.{field}"]
        assert main(["verify", str(path)]) == 1
        out = capsys.readouterr().out
        assert out.startswith("NOT PROVED ") and f"cycle.{field}" in out


def test_a_looser_but_true_cycle_verifies_and_drifts(cert_file, tmp_path):
    """A wider interval is still proved (it holds the enclosure); it is not what `hunting` writes: drift, stale when strict."""
    from symbolic_friction._certify import check_listed_certificates

    path = edited(tmp_path, cert_file, lambda d: d["cycle"].update(period=["46", "47"]))
    assert verify_hunting_file(path).proved
    (entry,) = check_listed_certificates(tmp_path, [path.name])
    assert entry.ok and "differs from what `symbolic-friction hunting` writes" in entry.drift
    (entry,) = check_listed_certificates(tmp_path, [path.name], strict=True)
    assert entry.proved and entry.stale and "differs from what `symbolic-friction hunting` writes" in entry.reason


def test_regenerating_a_committed_hunting_file_gives_its_bytes():
    from symbolic_friction._certify.hunting import dumps, load_hunting

    for path in COMMITTED:
        cert = load_hunting(path)
        (s_lo, s_hi), (t_lo, t_hi) = cert.box.sigma, cert.box.tau
        fresh, proof = certificate_for(cert.params, (s_lo + s_hi) / 2, (t_lo + t_hi) / 2)
        assert proof.proved and dumps(fresh) == path.read_text(encoding="utf-8"), path
        # from a start off by 1e-12 (what a float search returns) the polished zero, hence the file, is the same
        again, _ = certificate_for(cert.params, float(s_lo) * (1 + 1e-12), float(t_hi))
        assert dumps(again) == dumps(fresh)


def test_a_cycle_member_that_is_not_intervals_is_malformed(cert_file, tmp_path):
    for edit, match in [
        (lambda d: d["cycle"].update(period="46.86"), "cycle.period must be a list"),
        (lambda d: d["cycle"].update(iss={}), "cycle must have exactly the keys"),
        (lambda d: d["cycle"].update(period=["47", "46"]), "lo ≤ hi"),
        (lambda d: d["cycle"].update(stable="yes"), "cycle.stable must be true, false or null"),
    ]:
        with pytest.raises(CertificateFormatError, match=match):
            verify_hunting_file(edited(tmp_path, cert_file, edit))


def test_check_write_regenerates_a_stale_hunting_file(cert_file, tmp_path):
    from symbolic_friction._certify import check_listed_certificates, write_listed_certificates

    path = edited(tmp_path, cert_file, lambda d: d["cycle"].update(period=["46", "47"]))
    assert check_listed_certificates(tmp_path, [path.name], strict=True)[0].stale
    assert write_listed_certificates(tmp_path, [path.name]) == [path]
    assert path.read_bytes() == Path(cert_file).read_bytes()
    (entry,) = check_listed_certificates(tmp_path, [path.name], strict=True)
    assert entry.ok and not entry.drift
