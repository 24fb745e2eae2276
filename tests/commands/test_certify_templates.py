"""``symbolic-friction certify --template paper|quadratic|sup-flow|auto`` and the choice behind it (``_certify/choose.py``)."""

from __future__ import annotations

import json
from fractions import Fraction
import re
import time
from pathlib import Path

import pytest

from symbolic_friction import Parameters
from symbolic_friction._certify import choose
from symbolic_friction._certify.choose import certify_template, searchable_templates
from symbolic_friction._certify.templates import read_certificate_file, verify_template_file
from symbolic_friction._cli.main import main
from symbolic_friction._infra.errors import CertificateError, CertificateFormatError, ParameterError
from tests.computed_once import computed_once

CASE_A = ["--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"]
STIFF = ["--k-p", "1", "--k-i", "1", "--k-v", "1e6", "--f-c", "1"]


def _one(tmp_path: Path) -> Path:
    (path,) = tmp_path.glob("*.json")
    return path


def test_templates_know_their_names():
    templates = searchable_templates()
    assert list(templates) == ["paper", "quadratic", "sup-flow"]
    assert templates["paper"].id == "lyapunov-pair/v1" and templates["quadratic"].id == "quadratic/v1"
    assert templates["sup-flow"].id == "sup-flow/v2"
    assert all(t.name == name for name, t in templates.items())


def test_every_searchable_template_instantiates_only_obligations_check_proves():
    """``auto`` chooses among templates ``check`` fully covers: each obligation a file names is one ``check`` runs."""
    from symbolic_friction._certify.certificate import OBLIGATIONS as PAPER
    from symbolic_friction._certify.quadratic import OBLIGATIONS as QUADRATIC
    from symbolic_friction._certify.sup_flow import OBLIGATIONS as SUP_FLOW
    from symbolic_friction._obligations import registry

    ids = {cls.id for cls in registry()}
    cited = set(PAPER) | set(QUADRATIC) | set(SUP_FLOW)
    assert cited <= ids, cited - ids
    assert set(searchable_templates()) == {"paper", "quadratic", "sup-flow"}  # a new template must be added to this test


@pytest.fixture(scope="module")
def shared_sup_flow_searches():
    """Each sup-flow (pieces) search of this module run once: Table I (a)'s is asked for by two tests (about 2 s each).

    The search is deterministic (its file is Table I's committed one), and a deadline far away changes nothing: the
    verifier's parts are capped at ``MAX_TOTAL_PARTS`` (about 6 s of a deadline's time).  So a call with no deadline,
    or one more than ten minutes away, is answered by the first such call with the same arguments; any other call,
    and a search that raises, runs as it is.
    """
    from symbolic_friction._certify import sup_flow_search

    def near(options: dict) -> bool:
        return options.get("deadline") is not None and options["deadline"] - time.monotonic() < 600

    with computed_once(sup_flow_search, "certify_sup_flow", ignore=("deadline",), fresh=near):
        yield


@pytest.fixture(scope="module", autouse=True)
def shared_kappa_lin_lower():
    """The proven lower end of κ_lin computed once per gains in this module (about 0.15-0.2 s each).

    ``certify`` measures every κ against it, and the tests here ask for Table I (a)'s a dozen times.  It is a pure
    function of the parameters (a float search for the peak time, then an arb enclosure at the precision it sets and
    restores), so a later call with equal parameters gets the first call's value; a call that raises is not kept.
    """
    from symbolic_friction._certify import flow_bound

    with computed_once(flow_bound, "kappa_lin_lower"):
        yield


@pytest.fixture(scope="module", autouse=True)
def shared_one_piece_searches():
    """Each one-piece sup-flow search of this module run once per gains and options (about 0.1-0.15 s each).

    ``auto`` runs it twice for Table I (a) and twice for the stiff gains.  It is deterministic (the
    certificate is frozen, and the same gains give the same SDPs and the same rounding), so a later call with equal
    arguments gets the first call's certificate; a search that raises is not kept, and a test that replaces the
    search (``monkeypatch``) replaces this too.
    """
    from symbolic_friction._certify import sup_flow_tail

    with computed_once(sup_flow_tail, "certify_sup_flow_tail"):
        yield


def _untimed(line: str) -> str:
    return re.sub(r" in [0-9]+\.[0-9]{2} s", "", line)


def test_auto_keeps_the_sup_flow_certificate_for_table_i_and_names_the_others(tmp_path, capsys, shared_sup_flow_searches):
    # a budget no machine exhausts: the time pieces are halved to their end, so the file is Table I's committed one
    assert main(["certify", *CASE_A, "--out", str(tmp_path), "--budget", "3600"]) == 0
    first, against, wrote = capsys.readouterr().out.splitlines()
    assert re.search(r"κ 1\.37852 in [0-9]+\.[0-9]{2} s; paper", first)  # every search says how long it took
    assert _untimed(first) == ("template sup-flow (pieces) (auto: the smallest proved κ): κ 1.37852; paper: κ 3.46703; "
                               "sup-flow (one piece): κ 1.77986; quadratic: κ 1.80833")
    # κ against the proven lower end of κ_lin = 1.3732677…: 1.37852/1.37326771 = 1.003824… rounded up
    assert against == "κ ≤ 1.0039·κ_lin (κ_lin ≥ 1.3732677, proven)"
    assert wrote.startswith("wrote ") and "(sup-flow template)" in wrote and "<= 1.37852·|x(0)|_A" in wrote
    path = _one(tmp_path)
    assert path.name.endswith("_sup-flow.json")
    committed = json.loads((Path(__file__).resolve().parents[2] / "proofs" / "sup_flow" / "case_a.json").read_text())
    committed["provenance"]["label"] = ""
    assert json.loads(path.read_text()) == committed  # the search is deterministic: Table I's committed file, unlabelled
    # verify dispatches on the template the file names
    template, report = verify_template_file(path)
    assert template.name == "sup-flow" and report.proved
    assert main(["verify", str(path)]) == 0
    assert "premises of the sup-flow template hold" in capsys.readouterr().out


def test_auto_stops_at_the_target_and_within_the_budget(tmp_path, capsys):
    """A generous --kappa-tol stops after the closed form; --budget 0.001 starts nothing after the first search."""
    assert main(["certify", *CASE_A, "--out", str(tmp_path), "--kappa-tol", "2", "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["template"] == "paper" and payload["alternatives"] == []  # 3.46703 ≤ 3·1.3733: the target is met
    assert main(["certify", *CASE_A, "--out", str(tmp_path), "--kappa-tol", "0", "--budget", "0.001", "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["template"] == "paper" and payload["alternatives"] == [] and payload["kappa_lin_lower"]


def test_stiff_gains_get_a_tight_one_piece_certificate_and_every_failure_is_a_reason(tmp_path, capsys):
    assert main(["certify", *STIFF, "--out", str(tmp_path)]) == 0
    first, against, _ = capsys.readouterr().out.splitlines()
    assert _untimed(first).startswith("template sup-flow (one piece) (auto: the smallest proved κ): κ ")
    assert "paper: κ 1414.22" in first
    ratio = float(against.split("·κ_lin")[0].split("≤ ")[1])
    assert 1 <= ratio <= 2
    assert read_certificate_file(_one(tmp_path))[0].name == "sup-flow"
    assert main(["certify", *STIFF, "--name", "j", "--json", "--out", str(tmp_path)]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["template"] == "sup-flow" and payload["template_search"] == "one piece"
    assert payload["alternatives"][0]["template"] == "paper" and payload["alternatives"][0]["overshoot_bound"] == "1414.22"
    assert all(set(a) == {"template", "search", "overshoot_bound", "reason", "seconds"} for a in payload["alternatives"])


def test_gains_at_the_edge_of_float_range_are_reasons_never_a_traceback(tmp_path, capsys):
    """cvxpy once ended this in 'ValueError: Problem data contains NaN or Inf'; every search now says why, on one line."""
    huge = ["--k-p", "1e300", "--k-i", "1e300", "--k-v", "3", "--f-c", "1"]
    assert main(["certify", *huge, "--out", str(tmp_path)]) == 0
    out = capsys.readouterr()
    assert "Traceback" not in out.out + out.err and out.err == ""
    assert out.out.splitlines()[0].startswith("template paper (auto: the smallest proved κ)")
    for template in ("quadratic", "sup-flow"):
        assert main(["certify", *huge, "--template", template, "--out", str(tmp_path)]) == 2
        err = capsys.readouterr().err
        assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_a_solver_raising_anything_is_a_reason_in_auto_and_a_solver_error_alone(monkeypatch, shared_sup_flow_searches):
    from symbolic_friction._certify import quadratic_search
    from symbolic_friction._infra.errors import SolverError

    def broken(params, **_):
        raise ValueError("Problem data contains NaN or Inf")

    monkeypatch.setattr(quadratic_search, "certify_quadratic", broken)
    choice = certify_template(Parameters.table_i("a"), kappa_tol=0, budget=None)
    (quad,) = [a for a in choice.attempts if a.template.name == "quadratic"]
    assert quad.reason == "the quadratic search failed: ValueError: Problem data contains NaN or Inf"
    with pytest.raises(SolverError, match="the quadratic search failed: ValueError: Problem data contains NaN or Inf"):
        certify_template(Parameters.table_i("a"), template="quadratic")


def test_template_quadratic_writes_a_quadratic_file_and_json(tmp_path, capsys):
    argv = ["certify", *CASE_A, "--template", "quadratic", "--name", "q", "--label", "case a", "--json",
            "--out", str(tmp_path)]
    assert main(argv) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["template"] == "quadratic" and payload["template_id"] == "quadratic/v1"
    assert payload["overshoot_bound"] == "1.80833" and payload["report"] is None and payload["alternatives"] == []
    template, cert = read_certificate_file(tmp_path / "q.json")
    assert template.name == "quadratic" and cert.provenance.label == "case a"


def test_template_paper_is_todays_certificate_by_either_search(tmp_path, capsys):
    assert main(["certify", *CASE_A, "--template", "paper", "--name", "p", "--out", str(tmp_path)]) == 0
    assert capsys.readouterr().out.startswith("wrote ")  # no choice line: one template asked for
    _, cert = read_certificate_file(tmp_path / "p.json")
    assert cert.overshoot_bound == "3.46703" and cert.provenance.search == "closed-form"
    assert main(["certify", *CASE_A, "--template", "paper", "--search", "sdp", "--name", "s", "--out", str(tmp_path),
                 "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["template"] == "paper" and payload["search"] == "sdp" and payload["mode"] == "tightest"


def test_auto_with_an_option_of_the_paper_only_certifies_with_the_paper_and_says_so(tmp_path, capsys):
    assert main(["certify", *CASE_A, "--mode", "feasible", "--out", str(tmp_path)]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert _untimed(first) == "template paper (auto: the smallest proved κ; only the paper's template takes --mode feasible): κ 3.51842"


PHYSICAL_A = ["--m", "2", "--k-p-bar", "6", "--k-i-bar", "8", "--k-d-bar", "12.3", "--alpha-v", "0.5", "--f-c-bar", "2"]


def test_physical_parameters_are_never_lost_to_a_template_that_cannot_record_them(tmp_path, capsys):
    # auto keeps to the paper's template, whose file records them; asking for the quadratic one is refused
    assert main(["certify", *PHYSICAL_A, "--out", str(tmp_path / "auto")]) == 0
    out = capsys.readouterr().out
    assert "only the paper's template takes physical parameters" in out
    (written,) = (tmp_path / "auto").glob("*.json")
    assert json.loads(written.read_text())["physical"]["k_d_bar"] == "123/10"
    assert main(["certify", "--template", "quadratic", *PHYSICAL_A, "--out", str(tmp_path / "q")]) == 2
    err = capsys.readouterr().err
    assert "only the paper's template takes physical parameters" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "q").exists() or list((tmp_path / "q").iterdir()) == []


@pytest.mark.parametrize("extra, says", [
    (["--search", "sdp"], "only the paper's template takes --search sdp"),
    (["--search", "closed-form"], "only the paper's template takes --search closed-form"),
    (["--mode", "feasible"], "only the paper's template takes --mode feasible"),
    (["--margin", "1/1000"], "only the paper's template takes --margin"),
])
def test_options_of_the_paper_only_are_refused_with_the_quadratic_template(tmp_path, capsys, extra, says):
    assert main(["certify", *CASE_A, "--template", "quadratic", *extra, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert says in err and len(err.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


def test_a_box_is_refused_with_the_quadratic_template(tmp_path, capsys):
    argv = ["certify", "--k-p", "2.7:3.3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--template", "quadratic",
            "--out", str(tmp_path)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "a box (intervals LO:HI) is certified with the paper's template only" in err
    assert len(err.strip().splitlines()) == 1


def test_table_i_with_the_quadratic_template_writes_proofs_quadratic(tmp_path, capsys):
    assert main(["certify", "--template", "quadratic", "--out", str(tmp_path)]) == 0
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.json")) == [
        "quadratic/case_a.json", "quadratic/case_b.json"]


# --- the library function: the choice trusts only the templates' exact verifiers -------------------------------

def test_the_choice_is_the_smallest_proved_kappa():
    choice = certify_template(Parameters.table_i("b"), budget=None)
    assert choice.template.name == "sup-flow" and choice.certificate.overshoot_bound == "2.39826"
    assert choice.chosen.title == "sup-flow (pieces)"
    assert [a.describe() for a in choice.others] == ["paper: κ 7.88526", "sup-flow (one piece): κ 2.99848",
                                                     "quadratic: κ 3.27300"]
    assert choice.target == choice.kappa_lin_lower * Fraction(11, 10) and choice.ratio < Fraction(1003, 1000)


def test_a_quadratic_certificate_its_verifier_refuses_is_never_chosen(monkeypatch):
    """Break the quadratic template's verifier: ``auto`` must keep the paper's certificate."""
    import dataclasses

    quadratic = searchable_templates()["quadratic"]
    refusing = dataclasses.replace(quadratic, verify=lambda cert, source: _Refused(cert),
                                   failure=lambda report: "forged refusal")
    monkeypatch.setattr(choose, "searchable_templates",
                        lambda: {"paper": searchable_templates()["paper"], "quadratic": refusing})
    choice = certify_template(Parameters.table_i("a"))
    assert choice.template.name == "paper" and choice.certificate.overshoot_bound == "3.46703"
    assert "does not verify: forged refusal" in choice.others[0].reason


class _Refused:
    proved = False

    def __init__(self, certificate):
        self.certificate = certificate
        self.failures = ()


def test_a_failing_search_is_a_reason_and_no_template_at_all_is_an_error(monkeypatch):
    from symbolic_friction._certify import pipeline, quadratic_search, sup_flow_search, sup_flow_tail

    def no_sdp(params, **_):
        raise CertificateError("no quadratic certificate for X verifies exactly: margin 1e-07: solver status inaccurate")

    def no_pieces(params, **_):
        raise CertificateError("no sup-flow certificate for X verifies exactly: the SDP of the piece starting at t = 0 "
                               "is infeasible at every margin tried")

    def no_piece(params, **_):
        raise CertificateError("no one-piece sup-flow certificate for X verifies exactly: the SDP for U is infeasible")

    monkeypatch.setattr(quadratic_search, "certify_quadratic", no_sdp)
    monkeypatch.setattr(sup_flow_search, "certify_sup_flow", no_pieces)
    monkeypatch.setattr(sup_flow_tail, "certify_sup_flow_tail", no_piece)
    choice = certify_template(Parameters.table_i("a"))
    assert choice.template.name == "paper"
    reasons = {a.title: a.reason for a in choice.others}
    assert reasons == {"sup-flow (one piece)": "the SDP for U is infeasible",
                       "quadratic": "its SDP is inaccurate at every margin tried (1)",
                       "sup-flow (pieces)": "the SDP of the piece starting at t = 0 is infeasible at every margin tried"}

    def no_paper(params, **_):
        raise CertificateError("the rounded candidate does not verify exactly")

    monkeypatch.setattr(pipeline, "certify", no_paper)
    with pytest.raises(CertificateError, match="no template gives a proved certificate: paper: no certificate"):
        certify_template(Parameters.table_i("a"))


def test_gains_only_the_paper_can_take_fall_back_to_it_and_bad_gains_keep_their_message(monkeypatch):
    """f_c = 10⁹⁹⁹ is exact input the closed form takes and the SDP (floats) cannot: the paper's, with the reason."""
    choice = certify_template(Parameters(k_p=3, k_i=4, k_v="6.4", f_c="1e999"))
    assert choice.template.name == "paper" and choice.certificate.overshoot_bound == "3.46703"
    assert "outside the range of floating point" in choice.others[0].reason
    with pytest.raises(ParameterError, match="a stability certificate is for the paper's model f_s = f_c"):
        certify_template(Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1, f_s=2))


def test_bad_template_and_options_raise_parameter_errors():
    with pytest.raises(ParameterError, match="template must be one of auto, paper, quadratic, sup-flow; got 'sos'"):
        certify_template(Parameters.table_i("a"), template="sos")
    with pytest.raises(ParameterError, match="only the paper's template takes --mode feasible: the sup-flow template"):
        certify_template(Parameters.table_i("a"), template="sup-flow", mode="feasible")
    with pytest.raises(ParameterError, match="only the paper's template takes --margin"):
        certify_template(Parameters.table_i("a"), template="quadratic", margin="1/1000")


def test_verify_dispatches_on_the_template_a_file_names(tmp_path):
    """The same numbers under another template's name are read by that template's reader, and refused."""
    data = json.loads((Path(__file__).resolve().parents[2] / "proofs" / "quadratic" / "case_a.json").read_text())
    data["template"] = "lyapunov-pair/v1"
    (tmp_path / "x.json").write_text(json.dumps(data))
    with pytest.raises(CertificateFormatError):
        verify_template_file(tmp_path / "x.json")
    data["template"] = "sup-flow/v1"
    (tmp_path / "y.json").write_text(json.dumps(data))
    with pytest.raises(CertificateFormatError, match="missing key 'pieces' in certificate"):
        verify_template_file(tmp_path / "y.json")
    data["template"] = "sos/v1"
    (tmp_path / "z.json").write_text(json.dumps(data))
    with pytest.raises(CertificateFormatError, match="unknown certificate template 'sos/v1'"):
        verify_template_file(tmp_path / "z.json")
