"""The certificate's JSON Schema: shipped in the package, used on every read, agreeing with the parser."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest

from symbolic_friction._certify.certificate import json_schema, loads, validate_schema
from symbolic_friction._infra.errors import CertificateFormatError

REPO = Path(__file__).resolve().parents[2]
PROOFS = sorted((REPO / "proofs").glob("case_*.json"))  # the stability certificates (the box files have their own schema)


def test_committed_certificates_match_the_schema():
    assert len(PROOFS) == 4
    for path in PROOFS:
        validate_schema(json.loads(path.read_text(encoding="utf-8")))


def test_the_schema_is_a_valid_draft_2020_12_schema():
    import jsonschema

    jsonschema.Draft202012Validator.check_schema(json_schema())


def _base():
    return json.loads(PROOFS[0].read_text(encoding="utf-8"))


def _set(data, path, value):
    obj = data
    for key in path[:-1]:
        obj = obj[key]
    if value is KeyError:
        del obj[path[-1]]
    else:
        obj[path[-1]] = value
    return data


BAD = [
    (("parameters", "k_p"), "-3.0"),
    (("parameters", "k_p"), "--3"),
    (("parameters", "k_p"), "٣"),
    (("overshoot_bound",), "+3.5"),
    (("provenance", "margin"), "0"),
    (("parameters", "k_p"), 3),
    (("constants", "k1"), "1.5"),
    (("constants", "k1"), "1" * 20_001),
    (("constants", "c"), KeyError),
    (("overshoot_bound",), "３.5"),
    (("schema",), "symbolic-friction/certificate/v2"),
    (("extra",), "x"),
    (("provenance", "obligations"), "lemma2.P"),
    (("physical",), {"m": "1"}),
]


@pytest.mark.parametrize("path, value", BAD, ids=[".".join(p) + "=" + repr(v)[:12] for p, v in BAD])
def test_schema_and_parser_both_refuse(path, value):
    data = _set(copy.deepcopy(_base()), path, value)
    with pytest.raises(CertificateFormatError):
        validate_schema(data)  # the schema alone refuses it
    with pytest.raises(CertificateFormatError):
        loads(json.dumps(data))  # and so does reading it


SIGNED = [
    (("parameters", "k_p"), "0"),
    (("parameters", "k_p"), "-3"),
    (("parameters", "k_v"), "-32/5"),
    (("constants", "k1"), "-2"),
    (("constants", "c1_hat"), "0/7"),
    (("overshoot_bound",), "-3.5"),
]


@pytest.mark.parametrize("path, value", SIGNED, ids=[".".join(p) + "=" + v for p, v in SIGNED])
def test_schema_and_parser_both_read_a_number_of_the_wrong_sign(path, value):
    """Signs are premises: the schema and the parser accept the number, the verifier refuses it naming the premise."""
    from symbolic_friction._certify.verify import verify_certificate

    data = _set(copy.deepcopy(_base()), path, value)
    validate_schema(data)
    report = verify_certificate(loads(json.dumps(data)))
    assert not report.proved and any(c.name.endswith(" > 0") or c.name == "k_v·k_p > k_i" for c in report.failures)


def test_physical_parameters_round_trip(tmp_path):
    data = _base()
    data["physical"] = {"m": "2", "k_p_bar": "6", "k_i_bar": "8", "k_d_bar": "61/5", "alpha_v": "1/5", "f_c_bar": "2"}
    validate_schema(data)
    cert = loads(json.dumps(data))
    assert cert.physical["k_d_bar"] * 5 == 61 and "m=2" in cert.gains_text()


def test_readme_publishes_the_shipped_schema():
    # the specification page of the file formats (docs/guide/formats.md, formerly the README)
    readme = (REPO / "docs" / "guide" / "formats.md").read_text(encoding="utf-8")
    block = readme.split("<!-- certificate schema -->", 2)[1]
    text = block.split("```json", 1)[1].split("```", 1)[0]
    assert json.loads(text) == json_schema()


def test_a_file_with_too_many_values_is_refused_before_the_schema():
    """10⁵ array items would take the schema validator seconds: the reader counts values first."""
    import time

    from symbolic_friction._certify._json import MAX_VALUES, parse_json
    from symbolic_friction._infra.errors import CertificateFormatError

    assert parse_json(json.dumps({"a": ["x"] * (MAX_VALUES - 2)})) is not None
    start = time.perf_counter()
    with pytest.raises(CertificateFormatError, match=f"more than {MAX_VALUES} JSON values"):
        parse_json(json.dumps({"a": ["x"] * 300_000}))
    assert time.perf_counter() - start < 2


def test_only_the_first_violations_are_ranked(monkeypatch):
    """jsonschema's best_match ranks every error it is given: 3·10⁵ of them took 50 s; the first 100 are enough."""
    from symbolic_friction._certify import _schema

    error = next(_schema._validator().iter_errors({"schema": 1}))
    taken = []

    class Endless:
        def iter_errors(self, data):
            while True:
                assert len(taken) <= _schema._MAX_ERRORS, "more violations ranked than needed"
                taken.append(1)
                yield error

    monkeypatch.setattr(_schema, "_validator", lambda: Endless())
    with pytest.raises(CertificateFormatError, match="does not match the certificate schema"):
        validate_schema({})
    assert len(taken) == _schema._MAX_ERRORS
