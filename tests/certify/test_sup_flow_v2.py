"""The sup-flow template, version 2 (``_certify/sup_flow_v2.py``): every premise kind broken once, the format, and
version 1's exits when ``ℓ = 0``.

The certificates are the shipped true ones of the self-check (``false_certificates/true_sup_flow_v2*.json``: one
piece ``[0, ∞)`` with the friction-drag split, the same split at ``t = 1/2``, one piece without the split), each
verified in about 10 ms.
"""

from __future__ import annotations

import copy
import json
import re
from fractions import Fraction

import pytest

from symbolic_friction._certify import sup_flow_enclosure
from symbolic_friction._certify.self_check import DIRECTORY
from symbolic_friction._certify.sup_flow import (
    FlowExit,
    FlowNorm,
    SupFlowCertificate,
    SupFlowPiece,
    dumps_sup_flow,
    verify_sup_flow,
)
from symbolic_friction._certify.sup_flow_v2 import (
    SCHEMA,
    SUP_FLOW_V2,
    TEMPLATE_ID,
    SupFlowCertificateV2,
    SupFlowPieceV2,
    load_sup_flow,
    sup_flow_v2_premises,
)
from symbolic_friction._infra.errors import CertificateFormatError

ENTRIES = ("11", "12", "13", "22", "23", "33")
EXIT = "piece 1: U± ≥ |e^(At)w|² on the exits of R̂ and of f > ℓᵀy for t in [0, ∞)"
FLOW = "c2 ≥ ‖e^(At)‖² for every t ≥ 0 and c2 ≥ ‖e^(At)·D_ℓ‖² (both signs)"


def _data(name: str = "true_sup_flow_v2.json") -> dict:
    return json.loads((DIRECTORY / name).read_text(encoding="utf-8"))


def _verify(data: dict):
    return verify_sup_flow(SupFlowCertificateV2.from_dict(data))


def _failed(data: dict) -> list[str]:
    report = _verify(data)
    assert not report.proved
    return [check.name for check in report.failures]


def _piece(**values):
    """An edit of piece 1: ``name=value`` or ``name=("×", factor)``."""
    def edit(data):
        piece = data["pieces"][0]
        for name, value in values.items():
            piece[name] = str(Fraction(piece[name]) * value[1] if isinstance(value, tuple) else Fraction(value))
    return edit


def _scale(plus=1, minus=1):
    return _piece(**{f"kp{e}": ("×", Fraction(plus)) for e in ENTRIES}, **{f"km{e}": ("×", Fraction(minus)) for e in ENTRIES})


def _constants(**values):
    return lambda data: data["constants"].update({name: str(value) for name, value in values.items()})


def test_the_true_files_are_proved_and_version_2():
    for name in ("true_sup_flow_v2.json", "true_sup_flow_v2_pieces.json", "true_sup_flow_v2_no_drag.json"):
        report = _verify(_data(name))
        assert report.proved, report.summary()
        assert type(report.certificate) is SupFlowCertificateV2
        assert all(type(p) is SupFlowPieceV2 for p in report.certificate.pieces)


@pytest.mark.parametrize("edit, premise, alone", [
    (_constants(ell1=Fraction(-1, 1000)), "ell1 ≥ 0", False),  # and the band forms: their (1, 1) entry is 2K₁₃ℓ₁
    (_constants(ell2=Fraction(-1, 10**6)), "ell2 ≥ 0", True),
    (_constants(ell3=Fraction(-1, 10**6)), "ell3 ≥ 0", True),
    (_constants(c2=1), FLOW, True),
    (_constants(ell1=2, ell2=2, ell3=2), FLOW, False),  # the drag maps grow: c₂ and the drag exit form fail
    (_piece(kp11=Fraction(9, 10)), "K+1 − I copositive (piece 1)", False),  # the exit at t = 0 fails with it
    (_piece(km22=Fraction(9, 10)), "K−1 − I copositive (piece 1)", False),
    (_piece(kp12=Fraction(-1, 1000), kp23=("×", 2)), "piece 1: K+12 ≥ 0", True),
    (_piece(km12=Fraction(1, 1000), km23=("×", Fraction(5, 4))), "piece 1: −K−12 ≥ 0", True),
    (_piece(kp22=("×", 2)), "piece 1: drag rate form of K+ (s = +1) copositive", True),
    (_piece(km12=0), "piece 1: drag rate form of K− (s = −1) copositive", True),
    (_piece(kp11=-1), "piece 1: drag band form of K+ (s = +1) copositive", False),  # the corner k_i·K₁₁ + k_v·K₁₃ < 0
    (_piece(km11=("×", Fraction(11, 10))), "piece 1: drag band form of K− (s = −1) copositive", True),
    (_piece(kp13=Fraction(-1, 10**6)), "piece 1: K+31 ≥ 0", False),
    (_piece(km13=Fraction(-1, 10**6)), "piece 1: K−31 ≥ 0", False),
    (_piece(kp23=Fraction(-1, 10**6)), "piece 1: K+32 ≥ 0", False),  # the rate form's (2, 2) entry is 2K₂₃(1 + ℓ₂)
    (_piece(km23=Fraction(-1, 10**6)), "piece 1: K−32 ≥ 0", False),
    (_piece(kp33=Fraction(-1, 10**6)), "piece 1: K+33 ≥ 0", False),
    (_piece(km33=Fraction(-1, 10**6)), "piece 1: K−33 ≥ 0", False),
    (_scale(plus=Fraction(6, 5)), "piece 1: gamma·I − K+ copositive", True),
    (_piece(gamma=1), "piece 1: gamma·I − K− copositive", False),  # and K+'s
    (_scale(minus=Fraction(21, 20)), "piece 1: coupling (K+ − K−) on (|dz φ|, |v|) copositive", True),
    (_scale(plus=Fraction(9, 20), minus=Fraction(9, 20)), EXIT, True),  # every cone premise is homogeneous in K±
    (_scale(plus=Fraction(2, 5), minus=Fraction(2, 5)), EXIT, False),  # and K− − I: at t = 0 the exits imply it
    (lambda d: d.update(overshoot_bound="-3.6"), "overshoot_bound > 0", True),
    (lambda d: d.update(overshoot_bound="3.4"), "overshoot_bound² ≥ c2", False),  # and γ
    (_piece(gamma=13), "overshoot_bound² ≥ gamma (piece 1)", True),
])
def test_every_premise_kind_is_named_when_it_fails(edit, premise, alone):
    data = _data()
    edit(data)
    failed = _failed(data)
    assert premise in failed
    assert (failed == [premise]) is alone, failed


def test_each_premise_is_its_obligations():
    names = {p.name: p.obligation for p in sup_flow_v2_premises(SupFlowCertificateV2.from_dict(_data()))}
    assert names["ell1 ≥ 0"] == names[FLOW] == "sup_flow_v2.drag_region"
    assert names["piece 1: K+12 ≥ 0"] == names["piece 1: drag band form of K− (s = −1) copositive"] == "sup_flow_v2.U_rate"
    assert names["piece 1: coupling (K+ − K−) on (|dz φ|, |v|) copositive"] == "sup_flow_v2.sign_crossing"
    assert names[EXIT] == "sup_flow_v2.exit"
    assert names["piece 1: gamma·I − K− copositive"] == names["overshoot_bound² ≥ c2"] == "sup_flow_v2.stability_bound"


def test_a_false_exit_is_refuted_on_a_finite_piece_and_past_t():
    """K± of one piece a quarter: its exit premise fails (found false, not merely undecided), and on the first piece
    K± − I with it."""
    data = _data("true_sup_flow_v2_pieces.json")
    for index, text in ((0, "[0, 1/2)"), (1, "[1/2, ∞)")):
        edited = copy.deepcopy(data)
        for e in ENTRIES:
            for tag in ("kp", "km"):
                edited["pieces"][index][tag + e] = str(Fraction(edited["pieces"][index][tag + e]) / 4)
        name = f"piece {index + 1}: U± ≥ |e^(At)w|² on the exits of R̂ and of f > ℓᵀy for t in {text}"
        failures = {c.name: c for c in _verify(edited).failures}
        assert set(failures) == {name} | ({"K+1 − I copositive (piece 1)", "K−1 − I copositive (piece 1)"} if index == 0 else set())
        assert failures[name].instance.startswith("refuted at t = " if index == 0 else "v = 0, sign σ = ")


# -- the shipped exit files: which exit form fails ----------------------------------------------------------


class _PlanesOnly(SupFlowCertificateV2):
    """A version-2 certificate decided without its drag maps: the exit planes alone, ``c₂`` against ``e^{At}`` alone."""

    def drag_maps(self):
        return ()


@pytest.mark.parametrize("name", ["sup-flow-v2_exit.json", "sup-flow-v2_exit_tail.json", "sup-flow-v2_c2_drag.json"])
def test_where_a_shipped_file_fails_only_the_drag_premises_fail(name):
    """The finite-piece and tail exit files and the c₂ file are refused by the drag forms only: without ``D_ℓ`` proved."""
    data = _data(name)
    report = _verify(data)
    assert not report.proved and all("D_ℓ" in c.name or "f > ℓᵀy" in c.name for c in report.failures)
    if name != "sup-flow-v2_c2_drag.json":
        assert "f = ℓᵀy, sign σ = −" in report.failures[0].instance
    planes = verify_sup_flow(_PlanesOnly.from_dict(data))
    assert planes.proved, planes.summary()


def test_where_the_plane_file_fails_only_the_planes_of_one_sign_fail():
    """Past T = 1/2 with K⁻ scaled down: the planes of σ < 0 fail at y = e₁, the drag exit form of both signs holds."""
    import flint

    from symbolic_friction._certify.copositive import decide_copositive
    from symbolic_friction._model import sup_flow as model

    cert = SupFlowCertificateV2.from_dict(_data("sup-flow-v2_exit_plane.json"))
    (check,) = verify_sup_flow(cert).failures
    assert check.name.startswith("piece 2: ") and check.instance.startswith("v = 0, sign σ = −")
    premise = next(p for p in cert.premises() if isinstance(p, FlowExit) and p.index == 1)
    old = flint.ctx.prec
    flint.ctx.prec = sup_flow_enclosure.PRECISION
    try:
        gram = sup_flow_enclosure._tail_gram(premise, cert.pieces[1].start)
        arb = sup_flow_enclosure._arb
        for s, k in cert.pieces[1].signed_forms():
            d = dict(cert.drag_maps())[s]
            form = model.pullback_gap(tuple(tuple(arb(x) for x in row) for row in k), gram,
                                      tuple(tuple(arb(x) for x in row) for row in d))
            low = [[sup_flow_enclosure._lower(form[i][j]) for j in range(3)] for i in range(3)]
            rows = [[low[i][j] if i == j else min(low[i][j], low[j][i]) for j in range(3)] for i in range(3)]
            assert decide_copositive(rows).holds is True, s
        # and the planes of σ > 0 hold
        holds, _ = sup_flow_enclosure._exit_holds(
            [(1, tuple(tuple(arb(x) for x in row) for row in cert.pieces[1].form(1)), None)], gram)
        assert holds
    finally:
        flint.ctx.prec = old


# -- without the drag split: version 1's exits -----------------------------------------------------------------


def _as_version_2(data: dict) -> dict:
    """A version-1 file written as version 2 with ``K⁺ = K⁻ = K`` (``K₁₂ = 0``) and ``ℓ = 0``."""
    out = copy.deepcopy(data)
    out.update(schema=SCHEMA, template=TEMPLATE_ID)
    out["constants"].update(ell1="0", ell2="0", ell3="0")
    for piece in out["pieces"]:
        k = {e: piece.pop(f"k{e}", "0") for e in ENTRIES}
        piece.update({f"{tag}{e}": k[e] for tag in ("kp", "km") for e in ENTRIES})
    return out


def test_without_the_drag_split_there_are_no_drag_maps_and_the_exits_are_version_1s():
    cert = SupFlowCertificateV2.from_dict(_data("true_sup_flow_v2_no_drag.json"))
    assert cert.ell == (0, 0, 0) and cert.drag_maps() == ()
    premises = {p.name: p for p in cert.premises()}
    assert isinstance(premises["c2 ≥ ‖e^(At)‖² for every t ≥ 0"], FlowNorm)
    assert premises["c2 ≥ ‖e^(At)‖² for every t ≥ 0"].obligation == "sup_flow.bounds"  # version 1's own premise
    assert "piece 1: U± ≥ |e^(At)w|² on the exits of R̂ for t in [0, ∞)" in premises
    assert not any("ℓᵀy" in name or "D_ℓ" in name for name in premises)
    # a version-1 certificate written as version 2 with ℓ = 0 is proved, and refused where version 1 refuses it
    for name in ("true_sup_flow_single.json", "sup-flow_exit_tail.json"):
        v1 = json.loads((DIRECTORY / name).read_text(encoding="utf-8"))
        one = verify_sup_flow(SupFlowCertificate.from_dict(v1))
        two = verify_sup_flow(SupFlowCertificateV2.from_dict(_as_version_2(v1)))
        assert one.proved is two.proved is (name.startswith("true"))
        assert [c.holds for c in one.checks if "U ≥" in c.name] == [c.holds for c in two.checks if "U± ≥" in c.name]


# -- the format ----------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def searched():
    """A version-2 certificate from the one-piece search, with the drag split, on random 04's gains."""
    from symbolic_friction import Parameters
    from symbolic_friction._certify.sup_flow_search import ELL, Layout
    from symbolic_friction._certify.sup_flow_tail import certify_sup_flow_tail

    params = Parameters(k_p="404.727", k_i="0.386406", k_v="0.00105771", f_c=1)
    return params, certify_sup_flow_tail(params, layout=Layout(version=2, ell=ELL))


def test_random_04_with_the_drag_split_is_proved_within_a_percent_of_kappa_lin(searched):
    """Version 1's floor for these gains is (k_i/k_v)² ≈ 133,784 in κ²; the drag split takes it down to κ_lin²."""
    from symbolic_friction._certify.flow_bound import kappa_lin_lower

    params, cert = searched
    assert type(cert) is SupFlowCertificateV2 and cert.drag_maps() and len(cert.pieces) == 1
    assert verify_sup_flow(cert).proved
    assert cert.kappa <= Fraction(101, 100) * kappa_lin_lower(params)


def test_round_trip(searched, tmp_path):
    _, cert = searched
    text = dumps_sup_flow(cert)
    data = json.loads(text)
    assert data["schema"] == SCHEMA and data["template"] == TEMPLATE_ID and "provenance" in data
    again = SupFlowCertificateV2.from_dict(data)
    assert again == cert and again.to_dict() == data and dumps_sup_flow(again) == text
    path = tmp_path / "v2.json"
    path.write_text(text, encoding="utf-8")
    assert SUP_FLOW_V2.stale(again, path) == ""
    path.write_text(text.replace("  ", " "), encoding="utf-8")
    assert "canonical" in SUP_FLOW_V2.stale(again, path)


def test_load_sup_flow_reads_either_version(tmp_path):
    for name, kind in (("true_sup_flow_v2.json", SupFlowCertificateV2), ("true_sup_flow_v2_pieces.json", SupFlowCertificateV2),
                       ("true_sup_flow_single.json", SupFlowCertificate)):
        cert = load_sup_flow(DIRECTORY / name)
        assert type(cert) is kind
    path = tmp_path / "v2.json"
    path.write_text(json.dumps(_data()), encoding="utf-8")
    cert = load_sup_flow(path)
    assert type(cert) is SupFlowCertificateV2 and cert.ell == (Fraction(1, 100),) * 3
    assert verify_sup_flow(cert).proved


@pytest.mark.parametrize("edit, message", [
    (lambda d: d["constants"].pop("ell2"), "missing key 'constants.ell2'"),
    (lambda d: d["constants"].update(ell1=0.001), "constants.ell1 must be a string"),
    (lambda d: d["pieces"][0].update(k11="1"), "unknown key 'k11'"),  # a version-1 piece key
    (lambda d: d["pieces"][0].pop("km12"), "missing key 'pieces[0].km12'"),
    (lambda d: d.update(pieces=[]), "pieces must be a list of 1 to 256 objects"),
    (lambda d: d.update(schema="symbolic-friction/sup-flow-certificate/v1"), "is not symbolic-friction/sup-flow-certificate/v2"),
])
def test_malformed_files_are_refused_by_the_reader(edit, message):
    data = _data()
    edit(data)
    with pytest.raises(CertificateFormatError, match=re.escape(message)):
        SupFlowCertificateV2.from_dict(data)


def test_a_version_1_file_is_not_read_as_version_2_nor_the_reverse():
    v1 = json.loads((DIRECTORY / "true_sup_flow_single.json").read_text(encoding="utf-8"))
    with pytest.raises(CertificateFormatError):
        SupFlowCertificateV2.from_dict(v1)
    with pytest.raises(CertificateFormatError):
        SupFlowCertificate.from_dict(_data())


def test_pieces_of_the_wrong_version_are_refused():
    cert = SupFlowCertificateV2.from_dict(_data())
    v1_piece = SupFlowPiece(start=Fraction(0), end=None, constants={n: Fraction(1) for n in SupFlowPiece.names})
    with pytest.raises(CertificateFormatError, match="pieces"):
        SupFlowCertificateV2(k_p=cert.k_p, k_i=cert.k_i, k_v=cert.k_v, f_c=cert.f_c, constants=cert.constants,
                             pieces=(v1_piece,), overshoot_bound=cert.overshoot_bound)
    with pytest.raises(CertificateFormatError, match="pieces"):
        SupFlowCertificate(k_p=cert.k_p, k_i=cert.k_i, k_v=cert.k_v, f_c=cert.f_c, constants={"c2": 1, "p": 1},
                           pieces=cert.pieces, overshoot_bound=cert.overshoot_bound)
    with pytest.raises(CertificateFormatError, match="a piece's constants must be exactly"):
        SupFlowPieceV2(start=Fraction(0), end=None, constants={n: Fraction(1) for n in SupFlowPiece.names})
    with pytest.raises(AttributeError, match="two forms"):
        cert.pieces[0].k_matrix()


def test_a_pieces_premises_are_kept_under_its_numbers_by_name():
    """Within ``shared_decisions`` a piece's premises on its forms are built once per exact numbers, read by name:
    a piece holding the same numbers under other names (here in the reverse order) gets its own premises, as a
    fresh verification builds them, and the file it is in is decided as a fresh verification decides it."""
    import dataclasses

    from symbolic_friction._certify.sup_flow import shared_decisions

    cert = SupFlowCertificateV2.from_dict(_data())
    piece = cert.pieces[0]
    values = [piece.constants[n] for n in piece.names]
    other = dataclasses.replace(cert, pieces=(dataclasses.replace(piece, constants=dict(zip(piece.names, values[::-1]))),
                                              *cert.pieces[1:]))

    def named(c):
        return [(type(p).__name__, p.name, getattr(p, "matrix", None), getattr(p, "lhs", None)) for p in c.premises()]

    fresh, decided = named(other), [(c.name, c.holds, c.instance) for c in verify_sup_flow(other).checks]
    with shared_decisions():
        assert named(cert) != fresh and verify_sup_flow(cert).proved
        assert named(other) == fresh
        assert [(c.name, c.holds, c.instance) for c in verify_sup_flow(other).checks] == decided
