"""Tampered corpora (issue 33): neither verifier accepts a false file, and where they differ a format rule says why.

The corpora are :mod:`tests.independent.tampered`'s: single edits of every committed certificate of every kind the
independent checker reads, their truth decided from what each claims (not by either verifier).  The default run
decides a seeded sample of :data:`~tests.independent.tampered.DEFAULT_PER_KIND` edits per kind (at most a dozen of
the sup-flow file whose main verification takes 2 s); the full sweep, 600 per kind, is
``python -m tests.independent.tampered --all`` (it prints the counts).  Asserted here:

* every edit whose claim is stronger than the committed file proves (κ below its rounding or below what the
  file's constants give, a gain box enlarged, a Krawczyk box moved off the zero, ρ lowered, a radius raised, a
  time shortened, ``stable`` or ``overshoot`` flipped, gains leaving Assumption 1) is refused by both;
* no file is proved by one and refused by the other, unless the main verifier refuses it by a format rule (a
  malformed file, ``c``'s defining equation, a Table I label, the provenance's obligations) and ``verify`` prints
  one ``DISAGREE`` line saying so; neither crashes;
* the truth oracle itself, and ``verify``'s lines on the format rules (regression tests).
"""

from __future__ import annotations

import json
from fractions import Fraction

import pytest

from symbolic_friction._cli.main import main
from tests.independent import tampered

pytestmark = pytest.mark.slow


def test_every_kind_has_committed_files():
    assert {kind for kind, _ in tampered.sources()} == set(tampered.KINDS)


KINDS = tuple(k for k in tampered.KINDS if not k.startswith("sup-flow"))  # sup-flow: test_tampered_sup_flow.py


def check_kind(kind: str) -> None:
    """The default sample of ``kind``: no problem, every class and every type of edit in it (also for sup-flow).

    Every edit is decided by both verifiers; the sup-flow premises on the flow (both verifiers') and the main one's
    copositivity premises and box corners that an edit leaves as they were (most pieces of a file) keep their first
    verdict within the sample, as in the self-check."""
    from symbolic_friction._certify.box import shared_corners
    from symbolic_friction._certify.sup_flow import shared_decisions
    from symbolic_friction.independent import shared

    with shared_decisions(), shared_corners(), shared():
        tally, outcomes, found = tampered.default_run(kind)
    assert not found, "\n".join(found[:20])
    assert tally.edits >= 100 and tally.edits == tally.both_refuse + tally.both_accept + tally.disagree
    assert {"same", "weaker", "false", "other"} <= {o.edit.claim for o in outcomes}
    assert tally.both_accept and tally.both_refuse
    assert all(not (o.main or o.independent) for o in outcomes if o.edit.claim == "false")
    # every type of edit the generator makes of the kind's files is in the sample
    assert {o.edit.family.partition(" @ ")[0] for o in outcomes} == tampered.edit_types(kind)


@pytest.mark.parametrize("kind", KINDS)
def test_the_tampered_corpus_of_each_kind(kind):
    check_kind(kind)


def test_the_sample_is_deterministic():
    first = [e.what for e in tampered.corpus(30, 0, ("paper",))["paper"]]
    assert first == [e.what for e in tampered.corpus(30, 0, ("paper",))["paper"]]
    assert first != [e.what for e in tampered.corpus(30, 1, ("paper",))["paper"]]


# -- the truth oracle ------------------------------------------------------------------------------------------------


def _data(name: str) -> dict:
    return json.loads((tampered.ROOT / "proofs" / name).read_text(encoding="utf-8"))


@pytest.mark.parametrize("kappa, claim", [
    ("3.51843", "weaker"), ("100", "weaker"), ("3.518415", "other"), ("3.51841", "other"),
    ("3.5184", "false"), ("1.75921", "false"), ("0", "false"), ("-3.51842", "false"), ("3.51842", "same"),
])
def test_kappa_is_weaker_within_its_rounding_or_false(kappa, claim):
    old = _data("case_a_feasible.json")
    assert tampered.claim_class("paper", old, {**old, "overshoot_bound": kappa})[0] == claim


@pytest.mark.parametrize("axis, interval, claim", [
    ("k_p", ["27/10", "3"], "weaker"), ("k_p", ["26/10", "33/10"], "false"), ("k_i", ["18/5", "23/5"], "false"),
    ("k_v", ["33/10", "27/10"], "weaker"), ("f_c", ["1/2", "2"], "weaker"), ("f_c", ["0", "1"], "false"),
])
def test_a_box_is_weaker_when_smaller_and_false_when_enlarged(axis, interval, claim):
    old = _data("box_case_a_10pct.json")
    new = {**old, "box": {**old["box"], axis: interval}}
    assert tampered.claim_class("box", old, new)[0] == claim


def test_gains_that_leave_assumption_1_are_false_and_others_are_another_claim():
    old = _data("quadratic/case_a.json")
    edit = lambda **g: {**old, "parameters": {**old["parameters"], **g}}  # noqa: E731
    assert tampered.claim_class("quadratic", old, edit(k_i="0"))[0] == "false"
    assert tampered.claim_class("quadratic", old, edit(k_v="1"))[0] == "false"  # k_v·k_p = 3 < k_i = 4
    assert tampered.claim_class("quadratic", old, edit(k_p="4"))[0] == "other"
    assert tampered.claim_class("quadratic", old, edit(f_c="2"))[0] == "weaker"  # x ↦ x/f_c scales it away


def test_a_krawczyk_box_off_the_zero_and_a_flipped_stability_are_false():
    old = _data("hunting/case_a_fs1.2.json")
    lo, hi = old["cycle"]["sigma"]
    off = {**old, "box": {**old["box"], "sigma": [hi + "0", hi + "1"]}}  # far above the enclosure of σ*
    assert tampered.claim_class("hunting", old, off)[0] == "false"
    onto = {**old, "box": {**old["box"], "sigma": [lo, hi]}}
    assert tampered.claim_class("hunting", old, onto)[0] == "other"
    assert tampered.claim_class("hunting", old, {**old, "cycle": {**old["cycle"], "stable": False}})[0] == "false"
    assert tampered.claim_class("hunting", old, {**old, "cycle": {**old["cycle"], "stable": None}})[0] == "weaker"


@pytest.mark.parametrize("member, factor, claim", [
    (("rho",), Fraction(99, 100), "false"), (("rho",), Fraction(101, 100), "weaker"),
    (("rho",), 1 - Fraction(1, 10**6), "other"), (("radius",), Fraction(101, 100), "false"),
    (("radius",), Fraction(1, 2), "weaker"), (("cycle_time",), Fraction(99, 100), "false"),
    (("settling", "time"), Fraction(99, 100), "false"), (("settling", "tol"), Fraction(1, 2), "false"),
    (("settling", "tol"), Fraction(99, 100), "other"), (("settling", "tol"), 2, "weaker"),
])
def test_the_reset_contraction_numbers_are_bounds_each_way(member, factor, claim):
    old = _data("reset/case_a_contraction.json")
    new = json.loads(json.dumps(old))
    holder = new
    for key in member[:-1]:
        holder = holder[key]
    holder[member[-1]] = tampered.rational_text(Fraction(holder[member[-1]]) * factor)
    assert tampered.claim_class("reset-contraction", old, new)[0] == claim
    assert tampered.claim_class("reset-contraction", old, {**old, "overshoot": False})[0] == "false"


def test_the_generator_makes_every_kind_of_edit_the_issue_names():
    types = set().union(*(tampered.edit_types(kind) for kind in ("paper", "box", "hunting", "reset-contraction")))
    for name in ("nudge +1e-12", "nudge −1e-6", "nudge +1e-2", "×2", "÷2", "negated", "zero", "key removed",
                 "key added", "schema", "template", "label", "spelling: JSON float", "spelling: unreduced",
                 "interval swapped", "piece dropped", "piece duplicated", "pieces swapped", "piece overlapping its neighbour",
                 "piece leaving a gap", "κ just below the constants' bound", "κ raised", "Krawczyk box shrunk off the zero",
                 "overshoot flipped", "long nudge +1e-4400"):
        assert name in types, name


# -- verify says which format rule -----------------------------------------------------------------------------------


def _verify(capsys, path) -> tuple[int, list[str]]:
    status = main(["verify", str(path)])
    captured = capsys.readouterr()
    return status, [line for line in (captured.out + captured.err).splitlines() if line.startswith("DISAGREE")]


@pytest.mark.parametrize("edit, rule", [
    (lambda d: d["constants"].update(c="30"), "only by its format rule c = 2(k_v·k_p − k_i)"),
    (lambda d: d["provenance"].update(label="Table I, case (b)"), "only by its format rule label 'Table I, case (b)'"),
    (lambda d: d["provenance"].update(obligations=["lemma9.nowhere"]), "provenance.obligations"),
    (lambda d: d["parameters"].update(k_p=3), "only by a format rule of its reader (which the independent checker does "
                                              "not apply): parameters.k_p must be a string"),
    (lambda d: d.update(extra="1"), "unknown key 'extra' in certificate"),
    (lambda d: d.update(overshoot_bound="351842/100000"), "overshoot_bound must be a plain decimal"),
])
def test_verify_names_the_format_rule_of_a_disagreement(tmp_path, capsys, edit, rule):
    data = _data("case_a_feasible.json")
    edit(data)
    path = tmp_path / "edited.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    status, lines = _verify(capsys, path)
    assert status in (1, 2) and len(lines) == 1, lines
    assert lines[0].startswith(f"DISAGREE {path}: the independent checker proves it; the main verifier refuses it ")
    assert rule in lines[0], lines[0]


def test_verify_says_nothing_where_both_refuse_or_both_prove(tmp_path, capsys):
    assert _verify(capsys, tampered.ROOT / "proofs" / "case_a_feasible.json") == (0, [])
    data = _data("case_a_feasible.json")
    data["constants"]["k3"] = "1"  # a premise: both refuse
    (tmp_path / "bad.json").write_text(json.dumps(data), encoding="utf-8")
    assert _verify(capsys, tmp_path / "bad.json") == (1, [])
    data["parameters"]["k_p"] = 3  # malformed for the main reader, and false for the independent checker
    (tmp_path / "both.json").write_text(json.dumps(data), encoding="utf-8")
    assert _verify(capsys, tmp_path / "both.json") == (2, [])


def test_verify_json_records_a_format_rule_disagreement(tmp_path, capsys):
    data = _data("quadratic/case_a.json")
    data["schema"] = "symbolic-friction/certificate/v1"
    (tmp_path / "q.json").write_text(json.dumps(data), encoding="utf-8")
    assert main(["verify", "--json", str(tmp_path / "q.json")]) == 2
    record = json.loads(capsys.readouterr().out)["files"][0]
    assert record["status"] == "malformed" and record["independent"] == "proved"
    assert record["disagreement"].startswith("format rule: ") and "schema" in record["disagreement"]


def test_a_premise_disagreement_is_not_called_a_format_rule(tmp_path, capsys, monkeypatch):
    # were the independent checker to prove what a premise of the main verifier refuses, verify says it is a premise
    from symbolic_friction._cli import verify

    monkeypatch.setattr(verify, "_independent_verdict", lambda name: (True, ""))
    data = _data("case_a_feasible.json")
    data["constants"]["k3"] = "1"
    (tmp_path / "bad.json").write_text(json.dumps(data), encoding="utf-8")
    status, lines = _verify(capsys, tmp_path / "bad.json")
    assert status == 1 and len(lines) == 1 and "by a premise, not a format rule: k3 > (k_i/k_v)·k1; k3 > k2" in lines[0]
