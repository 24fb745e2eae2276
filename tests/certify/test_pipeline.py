"""Certify → verify → write, byte-identical regeneration, and staleness of committed files."""

from __future__ import annotations

import json
import shutil
from dataclasses import replace
from fractions import Fraction as F
from pathlib import Path

import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import CertificateError, CertificateFormatError, ParameterError
from symbolic_friction._certify import (
    TABLE_I_FILES,
    certify,
    certify_table_i,
    check_committed_certificates,
    default_stem,
    dumps,
    regenerate,
    render_files,
    verify_certificate,
    write_certificate,
)
from symbolic_friction._certify import pipeline as pipeline_module

REPO = Path(__file__).resolve().parents[2]
CASE_A = Parameters.table_i("a")


@pytest.fixture(scope="module")
def table_dir(tmp_path_factory) -> Path:
    directory = tmp_path_factory.mktemp("proofs")
    certify_table_i(directory)
    return directory


def test_certify_table_i_writes_eight_files(table_dir):
    names = sorted(p.name for p in table_dir.iterdir())
    expected = sorted(TABLE_I_FILES + tuple(n.replace(".json", ".md") for n in TABLE_I_FILES))
    assert names == expected


def test_regeneration_is_byte_identical(table_dir, tmp_path):
    certify_table_i(tmp_path)
    for path in table_dir.iterdir():
        assert (tmp_path / path.name).read_bytes() == path.read_bytes(), path.name


def test_committed_proofs_are_verified_and_up_to_date():
    """The files under proofs/ are exactly what `symbolic-friction certify` writes now."""
    results = check_committed_certificates(REPO / "proofs", expected=TABLE_I_FILES)
    # tests/hunting, test_quadratic, test_sup_flow, test_reset_contraction
    results = [r for r in results if r.path.parent.name not in ("hunting", "quadratic", "sup_flow", "reset")]
    assert [r.path.name for r in results] == sorted(TABLE_I_FILES + ("box_case_a_10pct.json", "box_physical.json"))
    for result in results:
        assert result.ok, result.describe()
        assert result.describe().startswith("ok ")


def test_check_detects_a_stale_markdown_report(table_dir, tmp_path):
    work = tmp_path / "p"
    shutil.copytree(table_dir, work)
    md = work / "case_a_tightest.md"
    md.write_text(md.read_text(encoding="utf-8") + "edited\n", encoding="utf-8")
    results = {r.path.name: r for r in check_committed_certificates(work)}
    bad = results["case_a_tightest.json"]
    assert bad.ok and "its report case_a_tightest.md differs from what `certify` renders now" in bad.drift
    results = {r.path.name: r for r in check_committed_certificates(work, strict=True)}
    bad = results["case_a_tightest.json"]
    assert bad.proved and bad.stale and not bad.ok
    assert bad.reason.startswith("drift (strict): its report case_a_tightest.md differs")
    assert bad.describe().startswith("STALE ")
    assert all(r.ok for name, r in results.items() if name != "case_a_tightest.json")


def test_check_detects_a_valid_but_stale_certificate(table_dir, tmp_path):
    work = tmp_path / "p"
    shutil.copytree(table_dir, work)
    path = work / "case_b_feasible.json"
    data = json.loads(path.read_text(encoding="utf-8"))
    data["constants"]["c2"] = "100"  # still a valid (looser) bound, but not what certify writes
    data["overshoot_bound"] = "100.000"
    path.write_text(json.dumps(data, indent=2, sort_keys=True) + "\n", encoding="utf-8")
    result = {r.path.name: r for r in check_committed_certificates(work)}["case_b_feasible.json"]
    assert result.ok and "c2 100 → " in result.drift and "κ 100.000 → 8.01380 (better)" in result.drift
    result = {r.path.name: r for r in check_committed_certificates(work, strict=True)}["case_b_feasible.json"]
    assert result.proved and result.stale and "c2 100 → " in result.reason


def test_check_reports_missing_malformed_failing_and_unregenerable_files(table_dir, tmp_path):
    work = tmp_path / "p"
    shutil.copytree(table_dir, work)
    (work / "case_a_feasible.json").unlink()
    (work / "case_b_tightest.md").unlink()
    (work / "junk.json").write_text("not json", encoding="utf-8")
    data = json.loads((work / "case_a_tightest.json").read_text(encoding="utf-8"))
    data["constants"]["k3"] = "1"
    (work / "failing.json").write_text(json.dumps(data), encoding="utf-8")
    data = json.loads((work / "case_b_feasible.json").read_text(encoding="utf-8"))
    del data["provenance"]
    (work / "anonymous.json").write_text(json.dumps(data), encoding="utf-8")
    shutil.copy(work / "case_b_feasible.md", work / "anonymous.md")
    results = {r.path.name: r for r in check_committed_certificates(work, expected=TABLE_I_FILES)}
    assert results["case_a_feasible.json"].reason == "missing; run `symbolic-friction certify`"
    assert results["case_b_tightest.json"].reason == "its report case_b_tightest.md is missing"
    assert results["junk.json"].reason.startswith("malformed: ") and "not valid JSON" in results["junk.json"].reason
    assert results["junk.json"].describe().startswith("FAILED ")
    assert not results["failing.json"].proved and "k3 > k2: 1 > 2 is false" in results["failing.json"].reason
    # proved, but without provenance it cannot be regenerated: drift, a failure only when strict
    assert results["anonymous.json"].ok and "no provenance" in results["anonymous.json"].drift
    assert sorted(name for name, r in results.items() if r.ok) == ["anonymous.json", "case_a_tightest.json", "case_b_feasible.json"]
    strict = {r.path.name: r for r in check_committed_certificates(work, expected=TABLE_I_FILES, strict=True)}
    assert strict["anonymous.json"].stale and "no provenance" in strict["anonymous.json"].reason


def test_write_refuses_an_unproved_certificate(tmp_path):
    bad = replace(certify(CASE_A), k3=F(1))
    with pytest.raises(CertificateError, match=r"FAILED case.json: .*k3 > k2: 1 > 2 is false"):
        write_certificate(bad, tmp_path / "case.json")
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(CertificateError, match="k3 > k2: 1 > 2 is false"):
        render_files(bad, name="x.json")


def test_write_needs_a_json_name(tmp_path):
    with pytest.raises(ParameterError, match=r"must end in '.json'; got '.*case.txt'"):
        write_certificate(certify(CASE_A), tmp_path / "case.txt")


def test_certify_never_returns_an_unverified_certificate(monkeypatch):
    real = pipeline_module.to_certificate
    monkeypatch.setattr(pipeline_module, "to_certificate", lambda cand, label="": replace(real(cand), c=F(1)))
    with pytest.raises(CertificateError, match=r"rounded tightest candidate for .* does not verify exactly: c = 2"):
        certify(CASE_A, search="sdp")


def test_certify_never_returns_an_unverified_closed_form_certificate(monkeypatch):
    import symbolic_friction._certify.closed_form as closed_form_module

    real = closed_form_module.closed_form_certificate
    monkeypatch.setattr(closed_form_module, "closed_form_certificate", lambda *a, **k: replace(real(*a, **k), k3=F(2)))
    with pytest.raises(CertificateError, match=r"rounded tightest candidate for .* does not verify exactly: k3 > k2: 2 > 2 is false"):
        certify(CASE_A)


def test_regenerate_needs_provenance_and_a_known_mode():
    cert = certify(CASE_A, mode="feasible", label="x")
    assert dumps(regenerate(cert)) == dumps(cert)
    with pytest.raises(CertificateFormatError, match="no provenance, so it cannot be regenerated"):
        regenerate(replace(cert, provenance=None))
    with pytest.raises(CertificateFormatError, match=r"provenance.mode is 'manual'; only feasible, tightest"):
        regenerate(replace(cert, provenance=replace(cert.provenance, mode="manual")))


def test_default_stem_is_deterministic_and_distinguishes_gains():
    a = default_stem(CASE_A, "tightest")
    assert a == default_stem(Parameters(k_p="3", k_i="4.0", k_v="32/5"), "tightest")
    assert a.startswith("certificate_") and a.endswith("_tightest") and len(a) == len("certificate_") + 12 + 9
    assert a != default_stem(Parameters.table_i("b"), "tightest")


def test_write_listed_certificates_regenerates_from_provenance_and_never_invents_gains(tmp_path):
    import shutil
    from pathlib import Path

    from symbolic_friction._certify import check_listed_certificates, write_listed_certificates

    repo = Path(__file__).resolve().parents[2]
    shutil.copy(repo / "proofs" / "case_b_feasible.json", tmp_path / "mine.json")
    written = write_listed_certificates(tmp_path, ["mine.json", "absent.json"])
    assert [p.name for p in written] == ["mine.json", "mine.md"]
    assert (tmp_path / "mine.json").read_bytes() == (repo / "proofs" / "case_b_feasible.json").read_bytes()
    entries = check_listed_certificates(tmp_path, ["mine.json", "absent.json"])
    assert [e.ok for e in entries] == [True, False]
    assert entries[1].reason.startswith("missing; create it with `symbolic-friction certify")


def test_physical_values_reach_the_certificate():
    params = Parameters.from_physical(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.3", alpha_v="0.5", f_c_bar=2)
    cert = certify(params, mode="feasible")
    assert cert.physical == params.physical.as_dict()
    assert verify_certificate(cert).proved
    # the verifier re-derives the gains from them: a forged mass fails
    forged = replace(cert, physical={**cert.physical, "m": F(3)})
    assert not verify_certificate(forged).proved
    assert certify(Parameters.table_i("a"), mode="feasible").physical is None
