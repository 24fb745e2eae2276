"""The sup-flow template (``_certify/sup_flow.py``): the committed Table I files, and every premise broken once."""

from __future__ import annotations

import copy
import re
import json
from fractions import Fraction
from pathlib import Path

import pytest

from symbolic_friction._certify import sup_flow, sup_flow_enclosure
from symbolic_friction._certify.sup_flow import SupFlowCertificate, verify_sup_flow
from symbolic_friction._infra.errors import CertificateFormatError, ParameterError

PROOFS = Path(__file__).resolve().parent / "data" / "sup_flow_v1"  # version 1 files (proofs/sup_flow/ is version 2 now)
BOUNDS = {"a": Fraction("1.716"), "b": Fraction("2.996")}
"""1.25 × the worst overshoot exact trajectories reach (1.3725 and 2.397)."""


def _data(case: str = "a") -> dict:
    return json.loads((PROOFS / f"case_{case}.json").read_text(encoding="utf-8"))


def _verify(data: dict):
    return verify_sup_flow(SupFlowCertificate.from_dict(data))


def _failed(data: dict) -> list[str]:
    report = _verify(data)
    assert not report.proved
    return [check.name for check in report.failures]


@pytest.mark.parametrize("case", ["a", "b"])
def test_committed_table_i_files_are_proved_within_a_quarter_of_the_observed_overshoot(case):
    report = _verify(_data(case))
    assert report.proved, report.summary()
    kappa = report.certificate.kappa
    assert kappa <= BOUNDS[case]
    # and not below the friction-free limit no certificate can beat (1.373268 and 2.39557)
    assert kappa >= {"a": Fraction("1.373268"), "b": Fraction("2.39557")}[case]
    assert report.summary().startswith("PROVED")
    assert any("parts" in check.instance for check in report.checks)  # the flow was enclosed, not skipped


def test_committed_files_are_canonical(tmp_path):
    for path in PROOFS.glob("*.json"):
        cert = SupFlowCertificate.from_dict(json.loads(path.read_text(encoding="utf-8")))
        assert sup_flow.dumps_sup_flow(cert) == path.read_text(encoding="utf-8")
        assert sup_flow.SUP_FLOW.stale(cert, path) == ""
        edited = tmp_path / path.name
        edited.write_text(path.read_text(encoding="utf-8").replace("  ", " "), encoding="utf-8")
        assert "canonical" in sup_flow.SUP_FLOW.stale(cert, edited)


def _scale_piece(data: dict, index: int, factor: Fraction, names=("k11", "k13", "k22", "k23", "k33")) -> dict:
    data = copy.deepcopy(data)
    for name in names:
        data["pieces"][index][name] = str(Fraction(data["pieces"][index][name]) * factor)
    return data


def test_assumption_1_and_f_c():
    data = _data()
    data["parameters"]["k_i"] = "100"
    assert "k_v·k_p > k_i" in _failed(data)
    data = _data()
    data["parameters"]["f_c"] = "0"
    assert _failed(data) == ["f_c > 0"]


def test_pieces_must_start_at_0_follow_each_other_and_end_at_infinity():
    data = _data()
    data["pieces"][0]["start"] = "1/1000"
    failed = _failed(data)
    assert "the first piece starts at t = 0" in failed
    assert all("not evaluated" in c.instance for c in _verify(data).failures if "U ≥" in c.name or "c2 ≥" in c.name)
    data = _data()
    data["pieces"][3]["start"] = str(Fraction(data["pieces"][3]["start"]) + Fraction(1, 10**6))  # a gap
    assert "piece 4 starts where piece 3 ends" in _failed(data)
    data = _data()
    data["pieces"][-1]["end"] = "1000"
    assert "the last piece ends at ∞" in _failed(data)
    data = _data()
    data["pieces"][1]["end"] = "inf"  # an infinite piece before the last
    assert "piece 3 starts where piece 2 ends" in _failed(data)


def test_a_piece_that_is_empty_is_refused():
    data = _data()
    data["pieces"][1]["end"] = data["pieces"][1]["start"]
    data["pieces"][2]["start"] = data["pieces"][1]["start"]
    report = _verify(data)
    assert not report.proved
    assert any("empty piece" in c.instance for c in report.failures)


def _paper_tail() -> dict:
    """A true certificate whose tail uses the paper's P (no tail constants: the first format's files)."""
    from symbolic_friction._certify.self_check import DIRECTORY

    return json.loads((DIRECTORY / "true_sup_flow.json").read_text(encoding="utf-8"))


def test_the_tail_needs_p_and_its_p():
    for data, whose in ((_data(), "the tail's P"), (_paper_tail(), "the paper's P")):
        assert _verify(data).proved
        data["constants"]["p"] = "0"
        assert "p > 0" in _failed(data)
        data["constants"]["p"] = "1000"
        assert f"P − p·I ⪰ 0 ({whose})" in _failed(data)


def test_the_tails_own_p_must_be_a_lyapunov_matrix():
    data = _data()
    data["constants"]["tail_p12"] = str(Fraction(data["constants"]["tail_p12"]) + 1)  # (AᵀP + PA)₁₁ = 2P₁₂ > 0
    assert "−(AᵀP + PA) ⪰ 0 (the tail's P)" in _failed(data)


def test_the_papers_p_must_be_a_lyapunov_matrix(monkeypatch):
    """The tail step needs AᵀP + PA ⪯ 0: a wrong P from the model is refused, naming that premise."""
    real = sup_flow.lyapunov_matrix_entries

    def wrong(k_p, k_i, k_v):
        p = [list(row) for row in real(k_p, k_i, k_v)]
        p[1][2] = p[2][1] = p[1][2] + 1  # P₂₃ ≠ 0 breaks AᵀP + PA ⪯ 0
        return tuple(tuple(row) for row in p)

    monkeypatch.setattr(sup_flow, "lyapunov_matrix_entries", wrong)
    assert "−(AᵀP + PA) ⪰ 0 (the paper's P)" in _failed(_paper_tail())


def test_c2_below_the_peak_of_the_flow_is_refused():
    data = _data()
    data["constants"]["c2"] = "3/2"  # sup ‖e^(At)‖² ≈ 1.886 for case (a)
    assert _failed(data) == ["c2 ≥ ‖e^(At)‖² for every t ≥ 0"]
    (check,) = _verify(data).failures
    assert check.instance.startswith("refuted at t = ") and "‖e^(At)‖² > c2 there" in check.instance


def test_a_horizon_too_early_for_the_tail_is_refused():
    data = _data()
    tail = copy.deepcopy(data["pieces"][-1])
    first = copy.deepcopy(data["pieces"][0])
    first["end"] = tail["start"] = "1/64"
    data["pieces"] = [first, tail]
    failed = _failed(data)
    assert "c2 ≥ ‖e^(At)‖² for every t ≥ 0" in failed and "piece 2: U ≥ |e^(At)w|² on the exits of R̂ for t in [1/64, ∞)" in failed


def test_k_of_the_first_piece_must_dominate_the_distance():
    assert "K1 − I copositive (piece 1)" in _failed(_scale_piece(_data(), 0, Fraction(1, 2)))


def test_each_piece_must_not_increase_on_r_hat():
    data = _data()
    data["pieces"][2]["k23"] = "-1"
    failed = _failed(data)
    assert "piece 3: K32 ≥ 0" in failed
    assert any(name.startswith("piece 3: −(K·B") for name in failed)
    data = _data()
    data["pieces"][2]["k11"] = "1000"  # the band form's corner −k_i·K11 + k_v·K13 turns negative for s = −1
    assert "piece 3: band form (s = −1) copositive" in _failed(data)


def test_gamma_must_bound_each_piece():
    data = _data()
    data["pieces"][2]["gamma"] = "1/10"
    assert _failed(data) == ["piece 3: gamma·I − K copositive"]
    data = _data()
    data["pieces"][2]["gamma"] = str(Fraction(data["overshoot_bound"]) ** 2 + 1)
    assert _failed(data) == ["overshoot_bound² ≥ gamma (piece 3)"]


def test_a_piece_whose_u_is_below_the_flow_on_the_exits_is_refused():
    """Scaling K keeps every cone premise; only the exit premise, decided on the enclosures, can see it."""
    data = _data()
    index = len(data["pieces"]) // 2
    failed = _failed(_scale_piece(data, index, Fraction(1, 2)))
    (check,) = _verify(_scale_piece(data, index, Fraction(1, 2))).failures
    assert check.instance.startswith("refuted at t = ")  # a false premise is found false, not merely undecided
    assert failed == [f"piece {index + 1}: U ≥ |e^(At)w|² on the exits of R̂ for t in "
                      + sup_flow.SupFlowPiece(start=Fraction(data["pieces"][index]["start"]),
                                              end=Fraction(data["pieces"][index]["end"]),
                                              constants={n: Fraction(1) for n in sup_flow.PIECE_CONSTANTS}).interval_text()]


def test_the_tail_piece_below_the_tail_form_is_refused():
    data = _data()
    failed = _failed(_scale_piece(data, len(data["pieces"]) - 1, Fraction(0)))  # every cone premise holds for K = 0
    assert failed == [f"piece {len(data['pieces'])}: U ≥ |e^(At)w|² on the exits of R̂ for t in "
                      f"[{data['pieces'][-1]['start']}, ∞)"]


def test_an_undecided_enclosure_is_not_proved(monkeypatch):
    """When the bisection runs out of parts the premise says so and fails: giving up is never *proved*."""
    monkeypatch.setattr(sup_flow_enclosure, "MAX_PARTS", 1)
    report = _verify(_data())
    assert not report.proved
    assert any("not decided" in c.instance for c in report.failures)


def test_one_verification_has_a_budget_of_parts(monkeypatch):
    monkeypatch.setattr(sup_flow_enclosure, "MAX_TOTAL_PARTS", 20)
    report = _verify(_data())
    assert not report.proved
    assert any("within the 20 parts of one verification" in c.instance for c in report.failures)


def test_a_piece_stretched_beyond_where_its_k_holds_is_refused():
    """Piece 1's K over the whole finite horizon: it is below the flow somewhere there, and the verifier says so."""
    data = _data()
    # one piece stretched over the whole finite horizon with piece 1's K: its enclosures are wide
    first, tail = copy.deepcopy(data["pieces"][0]), data["pieces"][-1]
    first["end"] = tail["start"]
    data["pieces"] = [first, tail]
    report = _verify(data)
    assert not report.proved
    assert "piece 1: U ≥ |e^(At)w|² on the exits of R̂ for t in [0, " in " ".join(c.name for c in report.failures)


def test_the_bound_itself():
    data = _data()
    data["overshoot_bound"] = "-1.5"
    assert "overshoot_bound > 0" in _failed(data)
    data = _data()
    data["overshoot_bound"] = "1.3"
    assert "overshoot_bound² ≥ c2" in _failed(data)


@pytest.mark.parametrize("edit, message", [
    (lambda d: d.update(pieces={}), "pieces must be a list of 1 to 256 objects"),
    (lambda d: d.update(pieces=[]), "pieces must be a list of 1 to 256 objects"),
    (lambda d: d.update(pieces=d["pieces"] * 20), "pieces must be a list of 1 to 256 objects"),
    (lambda d: d["pieces"][0].pop("gamma"), "missing key 'pieces[0].gamma'"),
    (lambda d: d["pieces"][0].update(extra="1"), "unknown key 'extra'"),
    (lambda d: d["pieces"][0].update(end="infinity"), "pieces[0].end must be an exact rational"),
    (lambda d: d["pieces"][0].update(k11=1.5), "pieces[0].k11 must be a string"),
    (lambda d: d["constants"].pop("p"), "missing key 'constants.p'"),
    (lambda d: d.update(template="quadratic/v1"), "is not symbolic-friction/sup-flow-certificate/v1"),
])
def test_malformed_files_are_refused_by_the_reader(edit, message):
    data = _data()
    edit(data)
    with pytest.raises(CertificateFormatError, match=re.escape(message)):
        SupFlowCertificate.from_dict(data)


def test_the_search_refuses_what_it_cannot_certify():
    from symbolic_friction._certify.sup_flow_search import certify_sup_flow
    from symbolic_friction._model.parameters import Parameters

    with pytest.raises(ParameterError, match="f_s = 6/5 > f_c = 1"):
        certify_sup_flow(Parameters(k_p=3, k_i=4, k_v=Fraction(32, 5), f_c=1, f_s=Fraction(6, 5)))
    with pytest.raises(ParameterError, match="rel_tol must be in"):
        certify_sup_flow(Parameters.table_i("a"), rel_tol=2)


def test_ball_ends_stay_bounded_and_outward():
    """An end of a ball far below 2^-4096 moves outward to 0 or ±2^-4096; one beyond 2^4096 decides nothing."""
    import flint

    tiny, huge = flint.arb(2) ** -10_000, flint.arb(2) ** 10_000
    bound = Fraction(1, 2**sup_flow_enclosure.EXPONENT_LIMIT)
    assert sup_flow_enclosure._end(tiny, down=True) == 0 and sup_flow_enclosure._end(tiny, down=False) == bound
    assert sup_flow_enclosure._end(-tiny, down=True) == -bound and sup_flow_enclosure._end(-tiny, down=False) == 0
    assert sup_flow_enclosure._end(flint.arb(3) / 4, down=True) == Fraction(3, 4)
    with pytest.raises(sup_flow_enclosure._TooWide):
        sup_flow_enclosure._end(huge, down=True)
    k = ((flint.arb(1), 0, 0), (0, flint.arb(1), 0), (0, 0, flint.arb(1)))
    gram = ((huge, 0 * huge, 0 * huge), (0 * huge, flint.arb(0), flint.arb(0)), (0 * huge, flint.arb(0), flint.arb(0)))
    forms = ((1, k, None), (-1, k, None))
    assert sup_flow_enclosure._exit_holds(forms, gram)[0] is False  # not proved
    assert sup_flow_enclosure._exit_holds(forms, gram, end=sup_flow_enclosure._upper)[0] is True  # and not refuted either


@pytest.mark.parametrize("where, key, value, premise", [
    ("parameters", "k_i", "-4", "k_i > 0"),
    ("parameters", "k_p", "-3", "k_p > 0"),
    ("piece", "k22", 2, "piece 3: −(K·B+ + B+ᵀ·K) copositive"),
    ("piece", "k22", Fraction(101, 100), "piece 3: −(K·B− + B−ᵀ·K) copositive"),
    ("piece", "k11", -100, "piece 3: band form (s = +1) copositive"),
    ("piece", "k13", -1, "piece 3: K31 ≥ 0"),
    ("piece", "k33", Fraction(-1, 10), "piece 3: K33 ≥ 0"),
])
def test_every_premise_kind_is_named_when_it_fails(where, key, value, premise):
    data = _data()
    if where == "parameters":
        data["parameters"][key] = value
        report = _verify(data)
        # the enclosures need Assumption 1: they are not evaluated, and say so
        assert all(not c.evaluated for c in report.failures if "U ≥" in c.name or "c2 ≥" in c.name)
    else:
        data["pieces"][2][key] = str(Fraction(data["pieces"][2][key]) * value)
    assert premise in _failed(data)


def test_a_single_piece_from_0_to_infinity_is_closed_by_the_tail_at_0_and_a_negative_start_is_refused():
    """T = 0 is a sound horizon (the tail bound holds for every t ≥ 0); a piece starting before 0 is not."""
    data = _data()
    tail = copy.deepcopy(data["pieces"][-1])
    tail["start"] = "0"
    data["pieces"] = [tail]
    failed = _failed(data)
    assert "T ≥ 0 (the last piece starts at or after 0)" not in failed
    # this piece's U was made for t ≥ 32, not for the whole flow: only the flow premises can fail
    assert set(failed) <= {"c2 ≥ ‖e^(At)‖² for every t ≥ 0", "piece 1: U ≥ |e^(At)w|² on the exits of R̂ for t in [0, ∞)"}
    tail["start"] = "-1"
    assert "T ≥ 0 (the last piece starts at or after 0)" in _failed(data)


def test_the_arb_shortcut_proves_only_what_the_exact_decision_proves():
    """The fast test on the lower ends of a 2×2 ball form never says True where decide_copositive would not."""
    import random

    import flint

    from symbolic_friction._certify.copositive import decide_copositive

    rng = random.Random(7)
    agree = 0
    for _ in range(400):
        a, b, c = (Fraction(rng.randint(-40, 400), rng.randint(1, 50)) for _ in range(3))
        radius = Fraction(rng.randint(0, 5), 1000)
        ball = lambda q: flint.arb(sup_flow_enclosure._arb(q), sup_flow_enclosure._arb(radius))  # noqa: E731
        form = ((ball(a), ball(b)), (ball(b), ball(c)))
        lows = [sup_flow_enclosure._lower(x) for x in (form[0][0], form[0][1], form[1][1])]
        exact = decide_copositive(((lows[0], lows[1]), (lows[1], lows[2]))).holds is True
        fast = sup_flow_enclosure._lower_ends_clearly_copositive(form)
        assert not fast or exact, (a, b, c, radius)
        agree += fast == exact
    assert agree >= 390  # and it decides almost everything the exact test does
    # b² just above ac: not copositive, and the shortcut must not say it is
    edge = ((flint.arb(1), flint.arb(-1) - flint.arb(2) ** -100), (flint.arb(-1) - flint.arb(2) ** -100, flint.arb(1)))
    assert not sup_flow_enclosure._lower_ends_clearly_copositive(edge)
    assert sup_flow_enclosure._lower_ends_clearly_copositive(((flint.arb(1), flint.arb(-1)), (flint.arb(-1), flint.arb(1))))


def test_a_search_short_of_time_gives_the_verifier_fewer_parts_and_it_only_refuses_more():
    cert = SupFlowCertificate.from_dict(_data())
    assert verify_sup_flow(cert).proved
    short = verify_sup_flow(cert, max_parts=2)
    assert not short.proved and any("within the 2 parts of one verification" in c.instance for c in short.failures)
    assert verify_sup_flow(cert, max_parts=10**9).proved  # above the limit: the limit


def test_k_i_zero_without_a_tail_p_is_refused_not_a_traceback():
    """The paper's P divides by k_i: a file with k_i = 0 and no tail P must be refused naming k_i > 0."""
    data = _data()
    data["parameters"]["k_i"] = "0"
    for name in [n for n in data["constants"] if n.startswith("tail_p")]:
        del data["constants"][name]
    report = _verify(data)
    assert not report.proved and "k_i > 0" in [c.name for c in report.failures]


def test_a_shared_flow_verdict_is_keyed_by_every_number_its_premise_reads():
    """``shared_flow_decisions`` (the self-check's) hands a premise the verdict of one decided before only under the
    same key: moving a piece's end (the interval its exit premise covers, in the key itself and in the premise's
    name, which prints the interval exactly) or ``c₂`` gives another key, so a file differing there is decided
    again."""
    import dataclasses

    cert = sup_flow.load_sup_flow(PROOFS / "case_a.json")
    assert len(cert.pieces) >= 2
    first, second = cert.pieces[0], cert.pieces[1]
    middle = (first.start + first.end) / 2
    moved = dataclasses.replace(cert, pieces=(dataclasses.replace(first, end=middle),
                                              dataclasses.replace(second, start=middle), *cert.pieces[2:]))
    raised = dataclasses.replace(cert, constants={**cert.constants, "c2": cert.constants["c2"] + 1})

    def keys(c, kind):
        return [sup_flow._flow_key(p) for p in sup_flow.sup_flow_premises(c) if type(p).__name__ == kind]

    assert keys(moved, "FlowExit")[0] != keys(cert, "FlowExit")[0]
    assert keys(raised, "FlowNorm") != keys(cert, "FlowNorm")
    assert keys(cert, "FlowExit") == keys(sup_flow.load_sup_flow(PROOFS / "case_a.json"), "FlowExit")


def test_an_exit_on_a_finite_piece_is_keyed_without_the_tail_and_the_last_one_with_it():
    """The tail (``P``, ``p``, ``T``) is read only by ``c₂``'s premise and the last piece's exit: an edit of ``p`` keeps
    the keys of the other exits (their kept verdicts) and changes those two; the same numbers give the same key, and
    a shared block decides a file with an edited ``p`` as a fresh verification does."""
    import dataclasses

    cert = sup_flow.load_sup_flow(PROOFS / "case_a.json")
    edited = dataclasses.replace(cert, constants={**cert.constants, "p": cert.constants["p"] / 2})

    def keys(c, kind):
        return [sup_flow._flow_key(p) for p in sup_flow.sup_flow_premises(c) if type(p).__name__ == kind]

    assert keys(edited, "FlowExit")[:-1] == keys(cert, "FlowExit")[:-1]
    assert keys(edited, "FlowExit")[-1] != keys(cert, "FlowExit")[-1]
    assert keys(edited, "FlowNorm") != keys(cert, "FlowNorm")
    fresh = [(c.name, c.holds, c.instance) for c in verify_sup_flow(edited).checks]
    with sup_flow.shared_decisions():
        verify_sup_flow(cert)
        assert [(c.name, c.holds, c.instance) for c in verify_sup_flow(edited).checks] == fresh


def test_the_kept_flow_enclosures_are_those_of_the_certificates_gains():
    """``_flow`` keeps its balls per gains and precision: the same interval for other gains is another enclosure,
    and each is the one a fresh computation gives (a key without the gains would hand one gain set's ``e^{At}``
    to another's premises)."""
    from types import SimpleNamespace

    a, b = Fraction(1, 4), Fraction(3, 4)
    table_a = SimpleNamespace(k_p=Fraction(3), k_i=Fraction(4), k_v=Fraction(32, 5))
    stiff = SimpleNamespace(k_p=Fraction(100), k_i=Fraction(1), k_v=Fraction(1, 2))
    first = sup_flow_enclosure._flow(table_a, a, b)
    second = sup_flow_enclosure._flow(stiff, a, b)
    sup_flow_enclosure._FLOWS.clear()
    assert str(sup_flow_enclosure._flow(stiff, a, b)) == str(second)
    assert str(sup_flow_enclosure._flow(table_a, a, b)) == str(first)
    assert str(first) != str(second)
