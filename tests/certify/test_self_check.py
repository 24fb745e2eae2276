"""`check` checks itself: the shipped false certificates are refused naming their premise, and breaking the
verifier (a dropped premise, a wrong decision, a broken python-flint) makes the self-check, hence `check`, fail."""

from __future__ import annotations

import json
import re
from fractions import Fraction as F

import pytest

from symbolic_friction._certify import hunting_proof, self_check
from symbolic_friction._certify import verify as verify_module
from symbolic_friction._certify.self_check import DIRECTORY, refuse_false_certificates
from symbolic_friction._cli.main import main

MANIFEST = json.loads((DIRECTORY / "manifest.json").read_text(encoding="utf-8"))["false_certificates"]
FALSE = [e for e in MANIFEST if e["premise"] is not None]


def test_the_shipped_files_are_what_the_forger_writes():
    from tests.certify.forge_false_certificates import forged

    files, manifest = forged()
    assert manifest == MANIFEST
    assert sorted(p.name for p in DIRECTORY.glob("*.json")) == sorted(list(files) + ["manifest.json"])
    for name, text in files.items():
        assert (DIRECTORY / name).read_text(encoding="utf-8") == text, name


def test_every_premise_has_a_false_certificate_that_names_it():
    from symbolic_friction._certify.quadratic import quadratic_premises

    for template, premises, count in (("stability", verify_module.premises, 27), ("quadratic", quadratic_premises, 22)):
        names = [p.name for p in premises(_Ones())]
        targeted = [e["premise"] for e in FALSE if e["template"] == template]
        assert sorted(targeted) == sorted(names) and len(names) == count, template
    # the sup-flow premises only that template has (those it shares with the quadratic one are the quadratic files')
    from symbolic_friction._certify.self_check import SUP_FLOW_PREMISES
    from symbolic_friction._certify.sup_flow import SupFlowCertificate, sup_flow_premises

    names = set()
    for name in ("true_sup_flow.json", "sup-flow_tail_rate.json"):  # the paper's P in the tail, and the file's own
        data = json.loads((DIRECTORY / name).read_text(encoding="utf-8"))
        names |= {p.name for p in sup_flow_premises(SupFlowCertificate.from_dict(data))}
    assert set(SUP_FLOW_PREMISES) <= names and len(SUP_FLOW_PREMISES) == 12
    assert sorted(e["premise"] for e in FALSE if e["template"] == "sup-flow") == sorted(SUP_FLOW_PREMISES)
    # sup-flow/v2: every premise of its one-piece true files (with and without the drag split) that its frame (version
    # 1's, broken by the sup-flow files) does not hold, the no-drag file's c2 premise being version 1's own (same name,
    # same decision), and the exits of the two-piece file (a finite piece, and the tail past T > 0)
    from symbolic_friction._certify.self_check import SUP_FLOW_V2_PREMISES
    from symbolic_friction._certify.sup_flow import FlowExit, frame_premises
    from symbolic_friction._certify.sup_flow_v2 import SupFlowCertificateV2

    own = set()
    for name in ("true_sup_flow_v2.json", "true_sup_flow_v2_pieces.json", "true_sup_flow_v2_no_drag.json"):
        cert = SupFlowCertificateV2.from_dict(json.loads((DIRECTORY / name).read_text(encoding="utf-8")))
        frame = {p.name for p in frame_premises(cert)} | {"c2 ≥ ‖e^(At)‖² for every t ≥ 0"}
        own |= {p.name for p in cert.premises() if p.name not in frame and (len(cert.pieces) == 1 or isinstance(p, FlowExit))}
    assert own == set(SUP_FLOW_V2_PREMISES) and len(SUP_FLOW_V2_PREMISES) == 28
    assert sorted(e["premise"] for e in FALSE if e["template"] == "sup-flow/v2") == sorted(SUP_FLOW_V2_PREMISES)
    # reset contraction: every premise of either kind (overshoot or not) of file
    from symbolic_friction._certify.reset_contraction_proof import PREMISES as RESET

    assert sorted(set(e["premise"] for e in FALSE if e["template"] == "reset-contraction")) == sorted(RESET)
    assert len(RESET) == 19
    for e in FALSE:
        assert e["premise"] in e["fails"], e["file"]
    # where the premises are independent, exactly that premise fails
    alone = [e for e in FALSE if e["fails"] == [e["premise"]]]
    assert len(alone) >= 40
    # sup-flow/v2: alone where the premises are independent (the others are implied by the exits, K3j ≥ 0 or ℓ ≥ 0)
    v2 = {e["premise"] for e in alone if e["template"] == "sup-flow/v2"}
    assert len(v2) == 19, sorted(v2)


class _Ones:
    from symbolic_friction._certify.quadratic import CONSTANTS

    constants = {name: F(1) for name in CONSTANTS}

    def __getattr__(self, name):
        return F(1)


def test_the_self_check_passes_on_this_install():
    result = refuse_false_certificates()
    assert result.ok and result.uncovered == ()
    assert len(result.refusals) == len(MANIFEST) == 138


@pytest.mark.parametrize("entry", FALSE, ids=lambda e: e["file"])
def test_verify_refuses_each_false_file_naming_its_premise(entry, capsys):
    """Exit 1 (refused by the verifier), never 2 (malformed): a number of the wrong sign is a false claim, not bad input."""
    assert set(entry) == {"file", "template", "premise", "fails"}, "the manifest has no `reader`: every file is read"
    assert main(["verify", str(DIRECTORY / entry["file"])]) == 1
    out, err = capsys.readouterr()
    assert out.startswith(("FAILED ", "NOT PROVED ")) and not err, (out, err)
    assert entry["premise"] in out or entry["premise"] == "verdict", out
    if entry["premise"] == "verdict":
        assert "verdict is 'not proved'" in out
    if entry["template"] != "hunting":  # every check the manifest lists is named, as "NAME: … is false"
        assert all(f"{name}: " in out for name in entry["fails"]), out


SIGNS = [e for e in FALSE if e["template"] != "hunting" and e["premise"].endswith(" > 0")]
"""The files that break a sign premise: the format once refused 15 of them (exit 2) before the verifier could."""


def test_the_sign_premises_are_refused_by_the_verifier_through_the_console_script():
    """The files whose premise is a sign, in one ``symbolic-friction verify`` process: exit 1, one FAILED line each."""
    import subprocess
    import sys

    assert len(SIGNS) == 22
    run = subprocess.run([sys.executable, "-m", "symbolic_friction", "verify", *(str(DIRECTORY / e["file"]) for e in SIGNS)],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 1 and "MALFORMED" not in run.stdout and "error" not in run.stderr, run.stderr
    lines = run.stdout.splitlines()
    assert len(lines) == len(SIGNS)
    for entry, line in zip(SIGNS, lines):
        # "k1 > 0: -2 > 0 is false": the premise, its instance, the verdict
        assert line.startswith(f"FAILED {DIRECTORY / entry['file']}: "), line
        premise = re.escape(entry["premise"])
        assert re.search(rf"(: |; ){premise}: -?[0-9]+(/[0-9]+)? > 0 is false(; | \[)", line), line


def test_the_true_controls_are_proved(capsys):
    for name in ("true_stability.json", "true_hunting.json", "true_quadratic.json", "true_sup_flow.json",
                 "true_sup_flow_single.json", "true_sup_flow_v2.json", "true_sup_flow_v2_pieces.json",
                 "true_sup_flow_v2_no_drag.json", "true_reset_contraction.json", "true_reset_contraction_dwell.json",
                 "true_reset_contraction_no_overshoot.json"):
        assert main(["verify", str(DIRECTORY / name)]) == 0
    assert capsys.readouterr().out.count("PROVED ") == 11


# -- breaking the verifier breaks the self-check ----------------------------------------------------------


def _failed(result):
    return [r.file for r in result.refusals if not r.ok]


def test_a_dropped_premise_fails_the_self_check(monkeypatch):
    real = verify_module.premises
    monkeypatch.setattr(verify_module, "premises", lambda cert: [p for p in real(cert) if p.name != "k3 > k2"])
    result = refuse_false_certificates()
    assert not result.ok and "stability_k3_over_k2.json" in _failed(result)


def test_leading_minors_only_fail_the_self_check(monkeypatch):
    """A PSD test by leading principal minors accepts [[0, 0], [0, -1]]-like matrices: the forged c2_hat file is then proved."""
    from symbolic_friction._certify.verify import Semidefinite

    monkeypatch.setattr(Semidefinite, "minors", lambda self: [
        (tuple(range(k)), verify_module._det([row[:k] for row in self.matrix[:k]])) for k in (1, 2, 3)])
    result = refuse_false_certificates()
    assert not result.ok


def test_a_sup_flow_v2_without_its_drag_premises_fails_the_self_check(monkeypatch):
    """Deciding c₂ and the exits without the drag maps ``D_ℓ`` proves the files where only they fail; dropping the
    coupling premise proves the coupling file."""
    from symbolic_friction._certify import sup_flow_enclosure, sup_flow_v2

    real_exit = sup_flow_enclosure._exit_holds
    monkeypatch.setattr(sup_flow_enclosure, "_pullbacks", lambda gram, maps: [gram])
    monkeypatch.setattr(sup_flow_enclosure, "_exit_holds",
                        lambda forms, gram, **kw: real_exit([(s, k, None) for s, k, _ in forms], gram, **kw))
    # the files where only a drag premise fails are proved; the one where the planes fail is still refused
    assert _failed(refuse_false_certificates()) == ["sup-flow-v2_c2_drag.json", "sup-flow-v2_exit_tail.json",
                                                     "sup-flow-v2_exit.json"]
    monkeypatch.undo()
    real = sup_flow_v2.sup_flow_v2_premises
    monkeypatch.setattr(sup_flow_v2, "sup_flow_v2_premises", lambda cert: [p for p in real(cert) if "coupling" not in p.name])
    # the coupling file is proved; the K+33 file no longer names the coupling, which fails with it
    assert set(_failed(refuse_false_certificates())) == {"sup-flow-v2_coupling.json", "sup-flow-v2_k33_plus.json"}


def test_a_non_strict_decision_fails_the_self_check(monkeypatch):
    monkeypatch.setitem(verify_module._DECIDE, ">", lambda m: m >= 0)
    monkeypatch.setitem(verify_module._DECIDE, ">=", lambda m: m >= -1)
    assert not refuse_false_certificates().ok


def test_a_broken_matrix_exponential_fails_the_self_check(monkeypatch):
    import flint

    monkeypatch.setattr(flint.arb_mat, "exp", lambda self: self * 0 + flint.arb_mat(3, 3, [1, 0, 0, 0, 1, 0, 0, 0, 1]),
                        raising=False)
    result = refuse_false_certificates()
    assert not result.ok and "true_hunting.json" in _failed(result)


def test_a_krawczyk_test_on_one_end_fails_the_self_check(monkeypatch):
    monkeypatch.setattr(hunting_proof, "_inside", lambda k, lo, hi: bool((k - lo) > 0))
    result = refuse_false_certificates()
    assert _failed(result) == ["hunting_zero_above_sigma.json", "hunting_zero_above_tau.json"]


def _mutant(module, name, old, new):
    import inspect
    import textwrap

    source = textwrap.dedent(inspect.getsource(getattr(module, name)))
    assert old in source, old
    namespace = dict(vars(module))
    exec(compile(source.replace(old, new, 1), f"<mutant of {name}>", "exec"), namespace)
    return namespace[name]


@pytest.mark.parametrize("old, new, caught_by", [
    # the derivative sign from τ_a onward, not only on the final box
    ("M.ball(t_a, t_hi)", "M.ball(t_lo, t_hi)", "hunting_monotone_too_early.json"),
    # σ > 0
    ("shape = _shape_ok(params, box)", "shape = params.f_s > params.f_c", "hunting_sigma_not_positive.json"),
    # the first-zero search runs on the whole of [δ, τ_a]
    ("delta, t_a,\n", "t_a - (t_a - delta) / 64, t_a,\n", "hunting_later_zero.json"),
    # the start: v' > 0 on [0, δ] for every σ of the box
    ("M.state(S, M.ball(Fraction(0), delta))", "M.state(M.q(s_lo), M.ball(Fraction(0), delta))",
     "hunting_start_unshown.json"),
])
def test_a_weakened_hunting_proof_fails_the_self_check(monkeypatch, old, new, caught_by):
    monkeypatch.setattr(hunting_proof, "_prove", _mutant(hunting_proof, "_prove", old, new))
    assert caught_by in _failed(refuse_false_certificates())


def test_an_unchecked_cycle_fails_the_self_check(monkeypatch):
    from symbolic_friction._certify import hunting

    monkeypatch.setattr(hunting, "decide_claims", lambda *a, **k: ())
    failed = _failed(refuse_false_certificates())
    assert "hunting_cycle_period.json" in failed and "hunting_cycle_stable.json" in failed


def test_a_copositivity_decision_that_trusts_undecided_fails_the_self_check(monkeypatch):
    from symbolic_friction._certify import copositive, quadratic

    real = copositive.decide_copositive

    def lenient(matrix):
        decision = real(matrix)
        return type(decision)(True, decision.reason) if decision.holds is False else decision

    monkeypatch.setattr(quadratic, "decide_copositive", lenient)
    failed = _failed(refuse_false_certificates())
    assert "quadratic_u_upper.json" in failed and "true_quadratic.json" not in failed


def _run_check(monkeypatch, tmp_path, capsys) -> str:
    from symbolic_friction._cli import check

    monkeypatch.setattr(check, "SECTIONS", [check.self_check_section])
    assert main(["check", "--proofs", str(tmp_path)]) == 1
    return capsys.readouterr().out


def test_check_fails_when_the_verifier_accepts_one_false_file(monkeypatch, tmp_path, capsys):
    """A verifier that drops every failing premise of the k1 file (and only that file) proves it: `check` fails, naming it."""
    real = verify_module.premises
    monkeypatch.setattr(verify_module, "premises", lambda cert: [
        p for p in real(cert) if not (cert.k1 < 0 and not verify_module.decide(p).holds)])
    result = refuse_false_certificates()
    assert _failed(result) == ["stability_k1_positive.json"]
    # the broken main verifier proves it; the independent checker does not, so `verify` refuses and says so
    assert main(["verify", str(DIRECTORY / "stability_k1_positive.json")]) == 1
    assert "the main verifier proves it; the independent checker refuses it" in capsys.readouterr().out
    out = _run_check(monkeypatch, tmp_path, capsys)
    assert "FAILED self-check stability_k1_positive.json: breaks k1 > 0; expected k1 > 0, k1·k4 > k3², c1_hat ≤ k1/2, got proved" in out
    assert out.strip().splitlines()[-1].startswith("check: FAILED")


def test_check_fails_when_a_false_file_is_refused_only_as_malformed(monkeypatch, tmp_path, capsys):
    """A reader that refuses signs (exit 2) keeps the verifier from deciding them: that is not a refusal."""
    from symbolic_friction._certify.certificate import Certificate
    from symbolic_friction._infra.errors import CertificateFormatError

    real = Certificate.from_dict.__func__

    def refuses_signs(cls, data):
        for group in ("parameters", "constants"):
            for key, value in data[group].items():
                if value.startswith("-"):
                    raise CertificateFormatError(f"{group}.{key} must be positive; got {value!r}")
        return real(cls, data)

    monkeypatch.setattr(Certificate, "from_dict", classmethod(refuses_signs))
    result = refuse_false_certificates()
    malformed = [r for r in result.refusals if not r.ok]
    assert {r.file for r in malformed} == {e["file"] for e in SIGNS if e["template"] == "stability"} - {"stability_kappa_positive.json"}
    assert all(r.named[0].startswith("malformed: ") and "must be positive" in r.named[0] for r in malformed)
    out = _run_check(monkeypatch, tmp_path, capsys)
    assert "FAILED self-check stability_k1_positive.json: breaks k1 > 0; expected k1 > 0, k1·k4 > k3², c1_hat ≤ k1/2, got malformed: " in out


def test_a_verifier_that_raises_fails_the_self_check_without_raising(monkeypatch):
    def crash(*args):
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(verify_module, "provenance_checks", crash)
    result = refuse_false_certificates()
    crashed = [r for r in result.refusals if not r.ok]
    assert not result.ok and "true_stability.json" in {r.file for r in crashed}
    assert all(r.named == ("crashed: ZeroDivisionError: division by zero",) for r in crashed)


def test_a_wrong_manifest_is_a_failure_not_a_pass(tmp_path):
    import shutil

    for path in DIRECTORY.glob("*.json"):
        shutil.copy(path, tmp_path / path.name)
    manifest = json.loads((tmp_path / "manifest.json").read_text(encoding="utf-8"))
    manifest["false_certificates"] = [e for e in manifest["false_certificates"] if e["premise"] != "k3 > k2"]
    (tmp_path / "manifest.json").write_text(json.dumps(manifest), encoding="utf-8")
    result = refuse_false_certificates(tmp_path)
    assert not result.ok and result.uncovered == ("stability: k3 > k2",)
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "manifest.json").write_text('{"false_certificates": []}', encoding="utf-8")
    assert not refuse_false_certificates(empty).ok  # nothing refused proves nothing
