"""The certificate dataclass and its strict, deterministic JSON file format."""

from __future__ import annotations

import json
import os
import stat
from dataclasses import replace
from fractions import Fraction as F

import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import CertificateFormatError
from symbolic_friction._certify import OBLIGATIONS, SCHEMA, Certificate, Provenance, certify, dumps, load, loads
from symbolic_friction._certify import certificate as certificate_module
from symbolic_friction._certify.certificate import atomic_write_text


@pytest.fixture(scope="module")
def cert() -> Certificate:
    return certify(Parameters.table_i("a"), mode="tightest", label="Table I, case (a)")


@pytest.fixture()
def data(cert) -> dict:
    return json.loads(dumps(cert))


def test_round_trip_is_exact(cert):
    again = loads(dumps(cert))
    assert again == cert
    assert again.k_v == F(32, 5) and isinstance(again.c2, F)
    assert again.provenance.obligations == OBLIGATIONS


def test_file_text_is_deterministic_and_canonical(cert):
    text = dumps(cert)
    assert text == dumps(loads(text))
    assert text.endswith("}\n") and not text.endswith("\n\n")
    data = json.loads(text)
    assert list(data) == sorted(data)
    assert list(data["constants"]) == sorted(data["constants"])
    assert text.startswith('{\n  "constants": {\n    "c": ')
    assert data["schema"] == SCHEMA
    assert data["parameters"] == {"f_c": "1", "k_i": "4", "k_p": "3", "k_v": "32/5"}
    assert all(isinstance(v, str) for v in data["constants"].values())


def test_no_timestamps_timings_or_library_versions(data):
    text = json.dumps(data)
    import cvxpy
    import clarabel

    for forbidden in ("time", "date", "seconds", "cvxpy", cvxpy.__version__, clarabel.__version__):
        assert forbidden not in text.lower(), forbidden
    assert set(data["provenance"]) == {
        "package",
        "package_version",
        "mode",
        "margin",
        "solver",
        "solver_status",
        "obligations",
        "label",
        "search",
    }
    assert data["provenance"]["search"] == "closed-form"


def test_kappa_squared_and_kappa(cert):
    assert cert.kappa_squared == cert.c2 * cert.c2_hat / (cert.c1 * cert.c1_hat)
    assert cert.kappa == F(cert.overshoot_bound) and isinstance(cert.kappa, F)
    assert cert.kappa**2 >= cert.kappa_squared  # the claim, exactly
    assert list(cert.constants) == ["k1", "k2", "k3", "k4", "c1", "c2", "c1_hat", "c2_hat", "c"]
    assert list(cert.parameters) == ["k_p", "k_i", "k_v", "f_c"]


# -- strict parsing: every malformed file names what is wrong ---------------------------
def _loads(data) -> Certificate:
    return loads(json.dumps(data), source="x.json")


def test_non_json_is_rejected_with_position():
    with pytest.raises(CertificateFormatError, match=r"x.json: not valid JSON: Expecting value at line 1, column 1"):
        loads("this is not JSON", source="x.json")


def test_non_utf8_bytes_are_rejected():
    with pytest.raises(CertificateFormatError, match=r"x.json: not valid JSON: not UTF-8"):
        loads(b'{"schema": "\xff"}', source="x.json")


def test_nan_and_infinity_are_rejected():
    with pytest.raises(CertificateFormatError, match=r"the constant NaN is not allowed"):
        loads('{"schema": NaN}', source="x.json")


def test_duplicate_keys_are_rejected():
    with pytest.raises(CertificateFormatError, match=r"duplicate key 'schema'"):
        loads('{"schema": "a", "schema": "b"}', source="x.json")


def test_top_level_must_be_an_object():
    with pytest.raises(CertificateFormatError, match=r"must be a JSON object; got a JSON array"):
        _loads([1, 2])


def test_missing_schema(data):
    del data["schema"]
    with pytest.raises(CertificateFormatError, match=r"missing key 'schema' \(expected 'symbolic-friction/certificate/v1'\)"):
        _loads(data)


def test_unknown_schema(data):
    data["schema"] = "symbolic-friction/certificate/v2"
    with pytest.raises(CertificateFormatError, match=r"unknown schema 'symbolic-friction/certificate/v2'; expected"):
        _loads(data)


def test_missing_top_level_keys(data):
    del data["constants"], data["overshoot_bound"]
    with pytest.raises(CertificateFormatError, match=r"missing keys 'constants', 'overshoot_bound' in certificate"):
        _loads(data)


def test_missing_constant(data):
    del data["constants"]["c2_hat"]
    with pytest.raises(CertificateFormatError, match=r"missing key 'constants.c2_hat' in constants"):
        _loads(data)


def test_missing_parameter(data):
    del data["parameters"]["f_c"]
    with pytest.raises(CertificateFormatError, match=r"missing key 'parameters.f_c' in parameters"):
        _loads(data)


def test_unknown_keys(data):
    data["constants"]["c3"] = "1"
    with pytest.raises(CertificateFormatError, match=r"unknown key 'c3' in constants"):
        _loads(data)
    del data["constants"]["c3"]
    data["timestamp"] = "now"
    data["extra"] = 1
    with pytest.raises(CertificateFormatError, match=r"unknown keys 'extra', 'timestamp' in certificate"):
        _loads(data)


def test_constants_must_be_an_object(data):
    data["constants"] = ["1"]
    with pytest.raises(CertificateFormatError, match=r"constants must be a JSON object; got a JSON array"):
        _loads(data)


def test_a_float_in_constants(data):
    data["constants"]["k3"] = 2.0
    with pytest.raises(CertificateFormatError, match=r"constants.k3 must be a string holding an exact rational.*got the float 2.0"):
        _loads(data)


def test_an_integer_in_parameters(data):
    data["parameters"]["k_p"] = 3
    with pytest.raises(CertificateFormatError, match=r"parameters.k_p must be a string .*got the int 3"):
        _loads(data)


@pytest.mark.parametrize("text", ["1.5", "3 / 5", "abc", "1e-3", "", "0x10"])
def test_malformed_rational_strings(data, text):
    data["constants"]["c1"] = text
    with pytest.raises(CertificateFormatError, match=r"constants.c1 must be an exact rational string such as '32/5'"):
        _loads(data)


def test_zero_denominator(data):
    data["constants"]["k1"] = "3/0"
    with pytest.raises(CertificateFormatError, match=r"constants.k1 has a zero denominator: '3/0'"):
        _loads(data)


@pytest.mark.parametrize("text", ["0", "-1/2", "0/7", "-0", "+0/3"])
def test_a_non_positive_value_is_read_and_refused_by_its_premise(data, text):
    """A sign is a premise, not format: the reader keeps the number, the verifier names ``k4 > 0``."""
    from symbolic_friction._certify.verify import verify_certificate

    data["constants"]["k4"] = text
    cert = _loads(data)
    assert cert.k4 == F(text.lstrip("+"))
    report = verify_certificate(cert)
    assert not report.proved and report.failures[0].message == f"k4 > 0: {F(text.lstrip('+'))} > 0 is false"


def test_a_non_positive_parameter_is_read_and_refused_by_its_premise(data):
    from symbolic_friction._certify.verify import verify_certificate

    data["parameters"]["f_c"] = "-1"
    del data["provenance"]  # its Table I label would fail too
    report = verify_certificate(_loads(data))
    assert [c.message for c in report.failures] == ["f_c > 0: -1 > 0 is false"]


@pytest.mark.parametrize(
    ("value", "message"),
    [
        (3.5, r"overshoot_bound must be a decimal string such as '3.69516'; got the float 3.5"),
        ("3.5e0", r"overshoot_bound must be a plain decimal string"),
        ("7/2", r"overshoot_bound must be a plain decimal string"),
        ("+3.5", r"overshoot_bound must be a plain decimal string"),
        ("- 3.5", r"overshoot_bound must be a plain decimal string"),
        ("--3.5", r"overshoot_bound must be a plain decimal string"),
        ("1." + "5" * 20_000, r"overshoot_bound has 20002 characters; at most 20000 are accepted"),
    ],
)
def test_overshoot_bound_format(data, value, message):
    data["overshoot_bound"] = value
    with pytest.raises(CertificateFormatError, match=message):
        _loads(data)


@pytest.mark.parametrize("text", ["0.000", "-3.5", "-0"])
def test_a_non_positive_overshoot_bound_is_read_and_refused_by_its_premise(data, text):
    from symbolic_friction._certify.verify import verify_certificate

    data["overshoot_bound"] = text
    cert = _loads(data)
    assert cert.overshoot_bound == text and cert.kappa == F(text)
    report = verify_certificate(cert)
    assert [c.name for c in report.failures][0] == "overshoot_bound > 0"


def test_provenance_is_optional_but_strict(data):
    del data["provenance"]
    assert _loads(data).provenance is None


def test_provenance_must_be_an_object(data):
    data["provenance"] = "cvxpy"
    with pytest.raises(CertificateFormatError, match=r"provenance must be a JSON object; got str"):
        _loads(data)


def test_provenance_keys(data):
    del data["provenance"]["mode"]
    with pytest.raises(CertificateFormatError, match=r"missing key 'provenance.mode' in provenance"):
        _loads(data)


def test_provenance_obligations_must_be_a_list(data):
    data["provenance"]["obligations"] = "lemma2.P"
    with pytest.raises(CertificateFormatError, match=r"provenance.obligations must be a list of strings; got str"):
        _loads(data)
    data["provenance"]["obligations"] = ["lemma2.P", 3]
    with pytest.raises(CertificateFormatError, match=r"provenance.obligations must be a list of strings; got \('lemma2.P', 3\)"):
        _loads(data)


def test_provenance_fields_must_be_strings(data):
    data["provenance"]["solver"] = None
    with pytest.raises(CertificateFormatError, match=r"provenance.solver must be a string; got NoneType"):
        _loads(data)


def test_provenance_margin_is_exact(data):
    data["provenance"]["margin"] = 1e-6
    with pytest.raises(CertificateFormatError, match=r"provenance.margin must be a string holding an exact rational"):
        _loads(data)


# -- the constructor validates form (not truth) ------------------------------------------
def test_constructor_accepts_ints_fractions_and_exact_strings(cert):
    other = replace(cert, k1=2, k2="2", k3=F(1000001, 500000))
    assert other.k1 == F(2) and other.k2 == F(2)


def test_constructor_rejects_booleans_and_floats_but_holds_any_sign(cert):
    with pytest.raises(CertificateFormatError, match=r"constants.k1 must be an exact rational; got the boolean True"):
        replace(cert, k1=True)
    with pytest.raises(CertificateFormatError, match=r"constants.c2 must be a string holding an exact rational.*float 3.5"):
        replace(cert, c2=3.5)
    with pytest.raises(CertificateFormatError, match=r"overshoot_bound must be a plain decimal string"):
        replace(cert, overshoot_bound="3.5e0")
    # a false certificate must be representable to be refused: the sign is the verifier's premise
    assert replace(cert, c=F(-1, 2)).c == F(-1, 2) and replace(cert, k_p="-3").k_p == -3


def test_kappa_squared_of_a_zero_denominator_is_an_error_not_a_crash(cert):
    from symbolic_friction.errors import CertificateError

    with pytest.raises(CertificateError, match=r"κ² = c2·c2_hat/\(c1·c1_hat\) is undefined: c1·c1_hat = 0·1 = 0"):
        replace(cert, c1=0, c1_hat=1).kappa_squared


def test_constructor_rejects_a_foreign_provenance(cert):
    with pytest.raises(CertificateFormatError, match=r"provenance must be a Provenance or None; got dict"):
        replace(cert, provenance={"mode": "tightest"})


def test_provenance_constructor_validates():
    with pytest.raises(CertificateFormatError, match=r"provenance.margin must be positive; got 0"):
        Provenance(mode="tightest", margin=F(0), solver="CLARABEL", solver_status="optimal", package_version="0.1.0")


# -- files ------------------------------------------------------------------------------------
def test_load_reads_a_file(tmp_path, cert):
    path = tmp_path / "c.json"
    atomic_write_text(path, dumps(cert))
    assert load(path) == cert
    path.write_text("{", encoding="utf-8")
    with pytest.raises(CertificateFormatError, match=rf"{path.name}: not valid JSON"):
        load(path)


def test_atomic_write_leaves_no_temporary_files_and_readable_mode(tmp_path):
    path = tmp_path / "sub" / "f.json"
    atomic_write_text(path, "one\n")
    atomic_write_text(path, "two\n")
    assert path.read_text(encoding="utf-8") == "two\n"
    assert sorted(p.name for p in path.parent.iterdir()) == ["f.json"]
    assert stat.S_IMODE(path.stat().st_mode) == 0o644


def test_atomic_write_keeps_the_old_file_when_replacing_fails(tmp_path, monkeypatch):
    path = tmp_path / "f.json"
    atomic_write_text(path, "old\n")

    def failing_replace(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(certificate_module.os, "replace", failing_replace)
    with pytest.raises(OSError, match="disk full"):
        atomic_write_text(path, "new\n")
    assert path.read_text(encoding="utf-8") == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.json"]
    assert os.path.exists(path)


def test_as_parameters(cert):
    from symbolic_friction.errors import AssumptionError

    assert cert.as_parameters() == Parameters.table_i("a")
    with pytest.raises(AssumptionError, match=r"Assumption 1 needs k_v·k_p > k_i; got 3 ≤ 4"):
        replace(cert, k_v=F(1)).as_parameters()


def test_importing_the_certificate_package_does_not_import_cvxpy():
    import subprocess
    import sys

    code = "import sys, symbolic_friction._certify as c; print('cvxpy' in sys.modules, 'sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["False", "False"]


def test_top_level_aliases(cert):
    from symbolic_friction._certify import dumps_certificate, load_certificate, loads_certificate

    assert loads_certificate(dumps_certificate(cert)) == cert and load_certificate is load
