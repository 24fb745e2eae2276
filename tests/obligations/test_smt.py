"""The obligations' algebra re-decided by z3 (``check --smt``; :mod:`symbolic_friction._obligations._smt`).

A planted false claim, and a claim made by a broken decision procedure, give
``counterexample`` with a model that makes the claim false in exact rational
arithmetic; true obligations are confirmed; the committed ``proofs/smt/*.smt2``
are what the export writes now, and an edited, missing or extra file is
reported; the exporter refuses what nonlinear real arithmetic cannot say.
"""

from __future__ import annotations

import shutil
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp

pytest.importorskip("z3")

from symbolic_friction._model import symbolic as _symbolic
from symbolic_friction._obligations import _decide, all_obligations
from symbolic_friction._obligations import _smt as smt
from symbolic_friction._obligations._base import Obligation, Outcome

ROOT = Path(__file__).resolve().parents[2]
PROOFS = ROOT / "proofs"


def _obligation(ident: str) -> Obligation:
    return next(ob for ob in all_obligations() if ob.id == ident)


def _rational(text: str) -> Fraction:
    assert not text.endswith("?"), f"not an exact value: {text}"
    return Fraction(text)


def _value_at(expr: sp.Expr, model: dict[str, str]) -> sp.Rational:
    """``expr`` at the model, in exact rational arithmetic (every symbol must have a rational value)."""
    values = {s: sp.Rational(_rational(model[s.name]).numerator, _rational(model[s.name]).denominator)
              for s in expr.free_symbols}
    value = expr.xreplace(values)
    assert value.is_Rational, value
    return value


class PlantedFalse(Obligation):
    """Test only: claims ``k_v k_p − 2 k_i ≥ 0`` under Assumption 1, i.e. ``δ − k_i ≥ 0``: false."""

    id = "planted.false"
    paper = "none (a test)"
    statement = "k_v k_p - 2 k_i ≥ 0 under Assumption 1 (false)"
    method = "a declared claim"

    def derive(self) -> sp.Expr:
        g = _decide.G()
        return sp.expand((g.k_v * g.k_p - 2 * g.k_i).subs(_symbolic.assumption1_substitution(g)))

    def verify(self, subject: sp.Expr) -> Outcome:
        smt.declare_claim(subject, "nonneg")
        return Outcome(True, "planted")


class BrokenProcedure(Obligation):
    """Test only: decides ``k_p − k_i > 0`` with ``sign_of`` (which a test breaks)."""

    id = "planted.broken_sign_of"
    paper = "none (a test)"
    statement = "k_p - k_i > 0 (false)"
    method = "sign_of"

    def derive(self) -> sp.Expr:
        g = _decide.G()
        return g.k_p - g.k_i

    def verify(self, subject: sp.Expr) -> Outcome:
        return Outcome(_decide.sign_of(subject) == 1)


@pytest.fixture(scope="module")
def exported():
    """Every obligation's claims, exported once for the module (about 10 s)."""
    return smt.export_smt()


def test_a_planted_false_obligation_gets_a_counterexample_that_refutes_it():
    subject = PlantedFalse().derive()
    g = _decide.G()
    assert subject == g.delta - g.k_i  # Assumption 1's encoding k_v = (k_i + δ)/k_p is in the claim
    (ob,) = smt.export_smt([PlantedFalse()])
    assert ob.expressible and len(ob.claims) == 1
    (out,) = smt.run_smt([ob], timeout_s=10)
    assert out.status == "counterexample", out
    model = dict(out.model)
    assert set(model) == {"delta", "k_i"}
    assert all(_rational(model[n]) > 0 for n in model)  # the model satisfies the hypotheses (δ, k_i > 0) ...
    assert _value_at(subject, model) < 0  # ... and refutes the claim
    line = smt.render_smt([out], 0.5).splitlines()[0]
    assert "counterexample" in line and "model: " in line


def test_a_broken_decision_procedure_is_caught(monkeypatch):
    """``sign_of`` that ignores negative coefficients says ``k_p − k_i > 0``; z3 refutes it with a model."""
    monkeypatch.setattr(_decide, "_coefficient_sign", lambda coefficients: 1 if len(coefficients) else 0)
    ob = BrokenProcedure()
    assert ob.run().holds  # the package's own check is fooled
    (exported,) = smt.export_smt([ob])
    assert [c.label for c in exported.claims] == [f"sign_of: {sp.sstr(ob.derive())} > 0"]
    (out,) = smt.run_smt([exported])
    assert out.status == "counterexample"
    assert _value_at(ob.derive(), dict(out.model)) <= 0


@pytest.mark.parametrize("ident", ["lemma2.P", "assumption1.encoding", "lemma3.hatV_bounds"])
def test_true_obligations_are_confirmed(ident):
    (ob,) = smt.export_smt([_obligation(ident)])
    assert ob.expressible and ob.verdict == "holds"
    (out,) = smt.run_smt([ob], timeout_s=10)
    assert out.status == "confirmed", out
    assert out.confirmed == out.claims == len(ob.claims) > 0


def test_an_existential_claim_expects_sat():
    """``is_zero`` answering False for a rational function claims "not identically 0": a witness must exist."""
    a = _decide.pos("a")
    with smt.recording() as claims:
        assert not _decide.is_zero(a - 1)
    (claim,) = claims
    script = smt.encode(claim)
    assert claim.kind == "nonzero" and script.expect == "sat"
    assert smt.solve_claim(script).answer == "sat"


def test_the_recording_keeps_decisions_only_and_restores_the_procedures():
    a, b = _decide.pos("a"), _decide.pos("b")
    original = _decide.sign_of
    with smt.recording() as claims:
        assert _decide.sign_of(a - b) is None  # undecided: no claim
        assert _decide.sign_of(a + b) == 1
        from symbolic_friction._obligations import _inequalities

        assert _inequalities.is_nonneg((a - b) ** 2 / (a + b))  # its inner sign_of of the denominator is not kept
    assert _decide.sign_of is original
    assert [(c.kind, c.sign, c.source) for c in claims] == [("sign", 1, "sign_of"), ("nonneg", None, "is_nonneg")]


def test_the_exporter_refuses_what_is_not_real_arithmetic():
    a = _decide.pos("a")
    x = sp.Symbol("x", real=True)
    for expr, why in ((sp.sqrt(a) - 1, "radical"), (sp.exp(a) - 1, "exponential"), (sp.sin(x) + 2, "transcendental"),
                      (sp.Float("0.5") * a, "floating-point")):
        with pytest.raises(smt.NotExpressible, match=why):
            smt.encode(smt.Claim("nonneg", expr, None, "declared"))


def test_a_claim_with_a_radical_makes_its_obligation_not_expressible():
    class Radical(PlantedFalse):
        id = "planted.radical"

        def verify(self, subject: sp.Expr) -> Outcome:
            smt.declare_claim(sp.sqrt(_decide.G().k_p) + 1, "sign", 1)
            smt.declare_claim(_decide.G().k_p + 1, "sign", 1)
            return Outcome(True)

    (ob,) = smt.export_smt([Radical()])
    assert not ob.expressible and len(ob.claims) == 1 and "radical" in ob.inexpressible[0][1]
    (out,) = smt.run_smt([ob])
    assert out.status == "not expressible" and "radical" in out.reason and out.confirmed == 1


def test_piecewise_and_abs_are_exact():
    x = sp.Symbol("x", real=True)
    c = _decide.pos("c")
    true = smt.Claim("zero", sp.Abs(x) - sp.Piecewise((x, x >= 0), (-x, True)), None, "declared")
    false = smt.Claim("nonneg", sp.Max(x, c) - sp.Abs(x), None, "declared")  # fails at x < -c
    assert smt.solve_claim(smt.encode(true)).answer == "unsat"
    answer = smt.solve_claim(smt.encode(false))
    assert answer.answer == "sat"
    model = dict(answer.model)
    assert _rational(model["x"]) < -_rational(model["c"])


def test_a_denominator_is_assumed_nonzero_only_where_it_is_used():
    x = sp.Symbol("x", real=True)
    # false only at x = 0, which a global hypothesis x != 0 (from 1/x on another branch) would wrongly exclude
    claim = smt.Claim("nonneg", sp.Piecewise((1 / x, x > 0), (-1, sp.Eq(x, 0)), (1, True)), None, "declared")
    answer = smt.solve_claim(smt.encode(claim))
    assert answer.answer == "sat" and _rational(dict(answer.model)["x"]) == 0
    # the same for a divisor in a later branch's condition, evaluated only where x != 0
    claim = smt.Claim("nonneg", sp.Piecewise((-1, sp.Eq(x, 0)), (1, 1 / x > 0), (2, True)), None, "declared")
    answer = smt.solve_claim(smt.encode(claim))
    assert answer.answer == "sat" and _rational(dict(answer.model)["x"]) == 0


def test_the_files_are_deterministic_and_self_contained(exported):
    files = smt.smt_files(exported)
    again = smt.smt_files(smt.export_smt([_obligation(i) for i in ("lemma2.dVdt", "lemma2.P")]))  # alone, another order
    assert again == {name: files[name] for name in ("lemma2.P.smt2", "lemma2.dVdt.smt2")}
    text = files["lemma2.P.smt2"]
    assert text.isascii() and text.startswith("; SMT-LIB 2 queries of the proof obligation `lemma2.P`")
    assert text.count("\n(check-sat)\n") == text.count("\n(reset)\n") == len(next(o for o in exported if o.id == "lemma2.P").claims)
    assert "(push" not in text  # blocks are independent: each is solved non-incrementally


def test_every_polynomial_obligation_is_exported_and_the_others_say_why(exported):
    ids = [ob.id for ob in all_obligations()]
    assert [ob.id for ob in exported] == ids
    assert all(ob.verdict == "holds" for ob in exported)
    poly = [ob for ob in exported if ob.expressible]
    assert len(poly) >= 0.75 * len(exported)
    for ob in exported:
        assert ob.expressible or ob.reason or ob.inexpressible, ob.id


def test_the_committed_files_are_up_to_date(exported):
    assert smt.stale_smt(PROOFS, exported) == [], "run `symbolic-friction check --write` and commit proofs/smt/"


def test_an_edited_missing_or_extra_file_is_reported(exported, tmp_path):
    shutil.copytree(PROOFS / "smt", tmp_path / "smt")
    assert smt.stale_smt(tmp_path, exported) == []
    edited = tmp_path / "smt" / "lemma2.P.smt2"
    edited.write_text(edited.read_text().replace("(assert (> k_p 0))", "(assert (>= k_p 0))", 1))
    (tmp_path / "smt" / "lemma2.dVdt.smt2").unlink()
    (tmp_path / "smt" / "planted.smt2").write_text("(check-sat)\n")
    assert smt.stale_smt(tmp_path, exported) == [
        (tmp_path / "smt" / "lemma2.P.smt2", "stale"),
        (tmp_path / "smt" / "lemma2.dVdt.smt2", "missing"),
        (tmp_path / "smt" / "planted.smt2", "unexpected"),
    ]
    written = smt.write_smt(tmp_path, exported)
    assert smt.stale_smt(tmp_path, exported) == []
    assert not (tmp_path / "smt" / "planted.smt2").exists()
    assert sorted(p.name for p in written) == sorted(smt.smt_files(exported))


def test_the_summary_counts_polynomial_obligations():
    outs = [smt.SmtOutcome("a", "confirmed", 1.0, claims=2, confirmed=2), smt.SmtOutcome("b", "timeout", 10.0, "slow", 3, 1),
            smt.SmtOutcome("c", "not expressible", 0.0, "no claim")]
    assert smt.smt_summary(outs, 12.34) == "z3: confirmed 1 of 2 polynomial obligations (50 %), 1 of 3 overall, in 12.3 s"
    lines = smt.render_smt(outs, 12.34).splitlines()
    assert [line.split()[:2] for line in lines[:3]] == [["a", "confirmed"], ["b", "timeout"], ["c", "not"]]
    assert lines[3] == smt.smt_summary(outs, 12.34)


def test_cvc5_is_a_second_backend():
    pytest.importorskip("cvc5")
    (planted,) = smt.export_smt([PlantedFalse()])
    (out,) = smt.run_smt([planted], solver="cvc5")
    assert out.status == "counterexample"
    assert _value_at(PlantedFalse().derive(), dict(out.model)) < 0
    (ok,) = smt.run_smt(smt.export_smt([_obligation("lemma2.P")]), solver="cvc5")
    assert ok.status == "confirmed", ok


def test_a_spent_budget_is_a_timeout_never_a_confirmation():
    (ob,) = smt.export_smt([_obligation("lemma2.lower_bound")])
    (out,) = smt.run_smt([ob], budget_s=0.0)
    assert out.status == "timeout" and out.confirmed == 0 and "budget" in out.reason


def test_a_solver_error_leaves_the_claim_undecided(monkeypatch):
    from symbolic_friction._obligations._smt import _run

    def broken(script, *, timeout_s, solver):
        raise RuntimeError("boom")

    monkeypatch.setattr(_run, "solve_claim", broken)
    (ob,) = smt.export_smt([_obligation("lemma2.P")])
    (out,) = smt.run_smt([ob])
    assert out.status == "unknown" and "boom" in out.reason


def test_recording_around_ones_own_run_gives_the_same_export():
    ob = _obligation("lemma3.R")
    with smt.recording() as claims:
        assert ob.run().holds
    assert smt.translate(ob, claims, "holds") == smt.export_one(_obligation("lemma3.R"))
