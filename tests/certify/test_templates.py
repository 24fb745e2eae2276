"""Certificate templates: a new kind of proof file is one module and a registration.

A throwaway template (Assumption 1 for given gains, ``k_v k_p > k_i``, decided
in rationals) is registered here, in this file only, and goes through the
package's generic path: written, read back by its ``template`` id, verified
exactly, listed and checked for staleness like the package's own certificates.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import pytest

from symbolic_friction.errors import CertificateFormatError
from symbolic_friction._certify import Template, check_listed_certificates, register
from symbolic_friction._certify._template import registered, unregister
from symbolic_friction._certify.templates import builtin_templates, read_certificate_file, verify_template_file

ID = "throwaway-assumption1/v1"
SCHEMA = "symbolic-friction/certificate/v1"


@dataclass(frozen=True)
class Claim:
    k_p: Fraction
    k_i: Fraction
    k_v: Fraction


@dataclass(frozen=True)
class Report:
    certificate: Claim
    proved: bool


def _read(data: object, source: str) -> Claim:
    if not isinstance(data, dict) or sorted(data) != ["gains", "schema", "template"]:
        raise CertificateFormatError(f"{source}: not a {ID} certificate")
    return Claim(**{k: Fraction(data["gains"][k]) for k in ("k_p", "k_i", "k_v")})


def _dumps(claim: Claim) -> str:
    gains = {k: str(getattr(claim, k)) for k in ("k_p", "k_i", "k_v")}
    return json.dumps({"schema": SCHEMA, "template": ID, "gains": gains}, indent=2, sort_keys=True) + "\n"


def _stale(claim: Claim, path: Path) -> str:
    return "" if path.read_text(encoding="utf-8") == _dumps(claim) else f"{path.name} differs from what is written now"


@pytest.fixture
def template():
    t = register(Template(
        id=ID, schema=SCHEMA, read=_read, dumps=_dumps, stale=_stale,
        verify=lambda claim, source: Report(claim, claim.k_v * claim.k_p > claim.k_i),
        failure=lambda report: "k_v k_p > k_i is false",
        claim=lambda claim: "Assumption 1",
    ))
    yield t
    unregister(t)


def test_a_registered_template_round_trips_through_write_read_verify_and_staleness(template, tmp_path):
    claim = Claim(Fraction(3), Fraction(4), Fraction(32, 5))
    path = template.write(claim, tmp_path / "slow_axis.json")

    read_template, read_claim = read_certificate_file(path)
    assert read_template is template and read_claim == claim
    checked_template, report = verify_template_file(path)
    assert checked_template is template and report.proved

    (entry,) = check_listed_certificates(tmp_path, ["slow_axis.json"])
    assert entry.ok and entry.describe() == f"ok     {path} (proved, up to date, Assumption 1)"

    path.write_text(path.read_text(encoding="utf-8").replace("\n", "\n "), encoding="utf-8")  # same claim, other bytes
    (entry,) = check_listed_certificates(tmp_path, ["slow_axis.json"])
    assert entry.proved and entry.stale and "differs from what is written now" in entry.reason

    template.write(Claim(Fraction(1), Fraction(4), Fraction(1)), path)  # k_v k_p = 1 < 4
    (entry,) = check_listed_certificates(tmp_path, ["slow_axis.json"])
    assert not entry.proved and not entry.ok and entry.reason == "k_v k_p > k_i is false"


def test_an_unknown_template_id_is_a_format_error(tmp_path):
    path = tmp_path / "x.json"
    path.write_text(json.dumps({"schema": SCHEMA, "template": "no-such-template/v1"}), encoding="utf-8")
    with pytest.raises(CertificateFormatError, match="unknown certificate template 'no-such-template/v1'"):
        read_certificate_file(path)
    (entry,) = check_listed_certificates(tmp_path, ["x.json"])
    assert not entry.ok and entry.reason.startswith("malformed: unknown certificate template")


def test_a_template_id_is_registered_once(template):
    with pytest.raises(ValueError, match="already registered"):
        register(Template(id=ID, schema="other", read=_read, verify=_read, dumps=_dumps, stale=_stale,
                          failure=str, claim=str))
    assert registered().count(template) == 1


def test_the_package_templates_are_the_schema_defaults():
    stability, hunting = builtin_templates()[:2]
    assert (stability.id, stability.default) == ("lyapunov-pair/v1", True)
    assert (hunting.id, hunting.default) == ("hunting-cycle/v1", True)
    ids = [t.id for t in builtin_templates()]
    assert ids[:7] == ["lyapunov-pair/v1", "hunting-cycle/v1", "lyapunov-box/v1", "quadratic/v1", "sup-flow/v1",
                       "sup-flow/v2", "reset-contraction/v1"]
    reset = builtin_templates()[6]
    assert reset.default and reset.schema == "symbolic-friction/reset-contraction-certificate/v1" and reset.regenerate


def test_a_file_naming_its_own_template_reads_as_before(tmp_path):
    """A committed certificate with its default ``template`` member added reads and verifies unchanged."""
    source = Path(__file__).resolve().parents[2] / "proofs" / "case_a_tightest.json"
    data = json.loads(source.read_text(encoding="utf-8"))
    data["template"] = "lyapunov-pair/v1"
    path = tmp_path / "case_a_tightest.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    template, report = verify_template_file(path)
    assert template.id == "lyapunov-pair/v1" and report.proved
    data["template"] = "hunting-cycle/v1"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(CertificateFormatError, match="expected 'symbolic-friction/hunting-certificate/v1'"):
        read_certificate_file(path)
