"""Box certificates: one κ for every gain set in a box, decided at every piece's four corners.

The committed boxes verify; 2,000 gain sets inside each (every piece's corners, the rest random)
verify as point certificates with the box's constants; a shifted box, a box certified with a
smaller box's constants, a broken cover and a box leaving Assumption 1 are refused.
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import random
from fractions import Fraction as F
from pathlib import Path

import pytest

from symbolic_friction.errors import AssumptionError, CertificateFormatError, ParameterError
from symbolic_friction._certify import Certificate, check_listed_certificates, verify_certificate
from symbolic_friction._certify.box import (
    BOX,
    box_from_data,
    certify_box,
    dumps_box,
    normalised_box,
    verify_box,
)
from symbolic_friction._certify.templates import builtin_templates, read_certificate_file

PROOFS = Path(__file__).resolve().parents[2] / "proofs"
COMMITTED = ("box_case_a_10pct.json", "box_physical.json")


def _pm(value: F, rel: F) -> tuple[F, F]:
    return value * (1 - rel), value * (1 + rel)


def case_a(rel: F) -> dict:
    return {"k_p": _pm(F(3), rel), "k_i": _pm(F(4), rel), "k_v": _pm(F(32, 5), rel), "f_c": (F(1), F(1))}


@pytest.fixture(scope="module")
def committed():
    return {name: read_certificate_file(PROOFS / name)[1] for name in COMMITTED}


def test_the_committed_boxes_verify_and_are_up_to_date(committed):
    for entry in check_listed_certificates(PROOFS, COMMITTED):
        assert entry.ok, entry.describe()
    assert builtin_templates()[2] is BOX
    a = committed["box_case_a_10pct.json"]
    assert a.box == case_a(F(1, 10)) and len(a.pieces) == 16
    assert F(a.overshoot_bound) < F(4)


def test_one_piece_and_a_finer_cover():
    one, many = certify_box(case_a(F(1, 10))), certify_box(case_a(F(1, 10)), pieces=8)
    assert one.overshoot_bound == "4.23132" and F(many.overshoot_bound) < F(one.overshoot_bound)
    tol = certify_box(case_a(F(1, 10)), kappa_tol=F(1, 100))
    assert F(tol.overshoot_bound) < F(one.overshoot_bound) and tol.provenance["kappa_tol"] == "1/100"


def _piece_of(cert, point):
    return next(p for p in cert.pieces if all(lo <= point[n] <= hi for n, (lo, hi) in
                                              (("k_p", p.k_p), ("k_i", p.k_i), ("k_v", p.k_v))))


POINTS = 2000
"""Gain sets per committed box verified as point certificates."""


def _points_inside(cert, seed: str) -> list[dict]:
    """:data:`POINTS` gain sets in the box: every corner of every piece (where a piece's constants are tightest, and
    a point lies on several pieces), then seeded uniform draws on the box's 10⁻⁶ grid.

    Drawn here rather than by hypothesis, whose engine took about 4 ms a point around the 0.5 ms of its verification.
    """
    names = ("k_p", "k_i", "k_v", "f_c")
    points = {}
    for piece in cert.pieces:
        for corner in itertools.product(piece.k_p, piece.k_i, piece.k_v, cert.box["f_c"]):
            points.setdefault(corner, dict(zip(names, corner)))
    rng = random.Random(seed)
    while len(points) < POINTS:
        point = {n: lo + (hi - lo) * F(rng.randint(0, 10**6), 10**6) for n, (lo, hi) in ((n, cert.box[n]) for n in names)}
        points.setdefault(tuple(point.values()), point)
    return list(points.values())


@pytest.mark.slow
@pytest.mark.parametrize("name", COMMITTED)
def test_random_points_inside_a_committed_box_verify_as_points(name, committed):
    cert = committed[name]
    points = _points_inside(cert, name)
    assert len(points) == POINTS
    for point in points:
        piece = _piece_of(cert, point)
        c = 2 * (point["k_v"] * point["k_p"] - point["k_i"])
        report = verify_certificate(Certificate(**point, **piece.constants, c=c, overshoot_bound=cert.overshoot_bound))
        assert report.proved, (point, report.summary())


def test_a_shifted_box_is_refused(committed):
    cert = committed["box_case_a_10pct.json"]
    shift = F(11, 10)
    moved = dataclasses.replace(
        cert, box={**cert.box, "k_p": tuple(x * shift for x in cert.box["k_p"])},
        pieces=tuple(dataclasses.replace(p, k_p=tuple(x * shift for x in p.k_p)) for p in cert.pieces),
    )
    report = verify_box(moved)
    assert not report.proved and any("corner" in c.name for c in report.failures)


def test_the_constants_of_a_smaller_box_fail_on_the_larger_one():
    small = certify_box(case_a(F(1, 20)))
    large = dataclasses.replace(small, box=case_a(F(1, 10)), pieces=(dataclasses.replace(
        small.pieces[0], **{n: case_a(F(1, 10))[n] for n in ("k_p", "k_i", "k_v")}),))
    report = verify_box(large)
    failing_corners = {c.name.split(":")[0] for c in report.failures if "corner" in c.name}
    assert not report.proved and len(failing_corners) >= 2, report.summary()


def test_a_broken_cover_is_refused():
    cert = certify_box(case_a(F(1, 10)), pieces=4)
    assert "volumes sum" in verify_box(dataclasses.replace(cert, pieces=cert.pieces[1:])).summary()
    doubled = dataclasses.replace(cert, pieces=cert.pieces + cert.pieces[:1])
    assert "interiors are disjoint" in verify_box(doubled).summary()


def test_a_box_leaving_assumption_1_is_refused_naming_the_corner():
    box = {"k_p": (F(1, 2), F(3)), "k_i": (F(1), F(4)), "k_v": (F(6), F(7)), "f_c": (F(1), F(1))}
    with pytest.raises(AssumptionError, match="leaves Assumption 1 at its corner k_p = 1/2, k_i = 4, k_v = 6: k_v·k_p = 3 ≤ k_i = 4"):
        certify_box(box)
    with pytest.raises(ParameterError, match=r"needs 0 < k_p,lo ≤ k_p,hi; got k_p ∈ \[3, 2\]"):
        certify_box({**box, "k_p": (F(3), F(2))})
    with pytest.raises(ParameterError, match=r"--pieces must be an integer in \[1, 4096\]; got 0"):
        certify_box(case_a(F(1, 10)), pieces=0)


def test_a_physical_box_normalises_monotonically_and_is_checked(committed):
    cert = committed["box_physical.json"]
    assert cert.box == normalised_box(cert.physical)
    assert cert.box["k_p"] == (F(29, 5) / F(21, 10), F(31, 5) / F(19, 10))
    narrowed = dataclasses.replace(cert, box={**cert.box, "k_v": (cert.box["k_v"][0] * 2, cert.box["k_v"][1])})
    assert "k_v of the physical box lies in the box" in verify_box(narrowed).summary()
    with pytest.raises(AssumptionError, match="the mass needs m > 0 on the whole box"):
        normalised_box({**cert.physical, "m": (F(0), F(1))})


def test_the_file_round_trips_and_is_read_strictly(committed, tmp_path):
    cert = committed["box_case_a_10pct.json"]
    text = dumps_box(cert)
    assert text == (PROOFS / "box_case_a_10pct.json").read_text(encoding="utf-8")
    data = json.loads(text)
    assert box_from_data(data) == cert
    data["pieces"][0]["constants"]["k1"] = 2.0
    with pytest.raises(CertificateFormatError, match=r"does not match the box certificate schema at pieces\[0\].constants.k1"):
        box_from_data(data)
    data = json.loads(text)
    data["box"]["k_p"] = ["3", "2"]
    with pytest.raises(CertificateFormatError, match=r"box.k_p must have lo ≤ hi; got \[3, 2\]"):
        box_from_data(data)


def test_a_changed_file_is_stale(committed, tmp_path):
    path = tmp_path / "box.json"
    path.write_text(dumps_box(committed["box_case_a_10pct.json"]).replace("\n", "\n "), encoding="utf-8")  # same claim
    (entry,) = check_listed_certificates(tmp_path, ["box.json"])
    assert entry.ok and "differs from what `symbolic-friction certify` writes now" in entry.drift
    (entry,) = check_listed_certificates(tmp_path, ["box.json"], strict=True)
    assert entry.proved and entry.stale and "differs from what `symbolic-friction certify` writes now" in entry.reason


@pytest.mark.parametrize("schema", ["box-certificate-v1.schema.json", "certificate-v1.schema.json"])
def test_the_validators_inlined_refs_report_what_the_shipped_schema_does(schema):
    """The validators use the schemas with their ``$defs`` refs inlined (faster): the same verdicts, the same errors."""
    import jsonschema

    from symbolic_friction._certify import _schema, box

    raw = json.loads((Path(_schema.__file__).parents[1] / "schemas" / schema).read_text(encoding="utf-8"))
    fast = box._validator() if schema.startswith("box") else _schema._validator()
    assert "$ref" not in json.dumps(fast.schema) and "$ref" in json.dumps(raw)
    valid = json.loads((PROOFS / ("box_case_a_10pct.json" if schema.startswith("box") else "case_a_tightest.json")).read_text())
    documents = [valid, [], {**valid, "extra": 1}, {k: v for k, v in valid.items() if k != "overshoot_bound"}]
    for key, value in valid.items():
        for wrong in (1.5, ["1", "2", "3"], {"a": "1"}):
            documents.append({**valid, key: wrong})
        if isinstance(value, dict):
            for inner in value:
                documents.append({**valid, key: {**value, inner: [1, "1/0x"]}})

    def best(validator, data):
        error = jsonschema.exceptions.best_match(validator.iter_errors(data))
        return None if error is None else (error.message, list(error.absolute_path), error.validator)

    slow = jsonschema.Draft202012Validator(raw)
    assert best(fast, valid) is None
    for data in documents:
        assert best(fast, data) == best(slow, data), data
