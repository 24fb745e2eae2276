"""Run an SMT solver on the exported claims: :func:`run_smt`, :class:`SmtOutcome` and the one-line-per-obligation render.

Each claim is one solver call on its own context (z3; cvc5 as a second
backend), with a time limit.  Claims run on ``workers`` threads (the solvers
release the GIL), cheapest first, so under a tight budget the most
obligations are decided.  An obligation is

* ``confirmed`` when every claim got the expected answer (``unsat`` for the
  negation of a universal claim);
* ``counterexample`` when one got the other answer: for a universal claim the
  solver's model (exact rationals ``p/q``; an irrational algebraic number as a
  decimal ending in ``?``) makes the claim false;
* ``timeout`` or ``unknown`` when a claim was not decided in its time (its own
  limit, the obligation's share or the total budget) or the solver gave up;
* ``not expressible`` when a claim is outside nonlinear real arithmetic, or
  when the obligation decided nothing algebraic; the reason says which.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from ._encode import ClaimScript
from ._export import SmtObligation

__all__ = ["STATUSES", "ClaimAnswer", "SmtOutcome", "render_smt", "run_smt", "smt_summary", "solve_claim", "solver_version"]

STATUSES = ("confirmed", "counterexample", "unknown", "timeout", "not expressible")


@dataclass(frozen=True)
class ClaimAnswer:
    """One solver call: ``answer`` is ``"unsat"``, ``"sat"``, ``"unknown"`` or ``"timeout"``."""

    answer: str
    seconds: float
    model: tuple[tuple[str, str], ...] = ()
    why: str = ""


@dataclass(frozen=True)
class SmtOutcome:
    """One obligation's row of ``check --smt``.

    Attributes
    ----------
    id : str
    status : str
        One of :data:`STATUSES`.
    seconds : float
        Solver time summed over its claims.
    reason : str
        Why, when not confirmed (the refuted claim, the reason it is not expressible, …).
    claims, confirmed : int
        How many claims it has (expressible ones) and how many were confirmed.
    model : tuple of (str, str)
        For a counterexample: ``(symbol, value)``; values are exact ``p/q`` or decimals ending in ``?``.
    """

    id: str
    status: str
    seconds: float
    reason: str = ""
    claims: int = 0
    confirmed: int = 0
    model: tuple[tuple[str, str], ...] = ()

    @property
    def expressible(self) -> bool:
        return self.status != "not expressible"

    def as_json(self) -> dict[str, Any]:
        return {"id": self.id, "status": self.status, "seconds": round(self.seconds, 3), "reason": self.reason,
                "claims": self.claims, "confirmed": self.confirmed, "model": dict(self.model)}


def solver_version(solver: str = "z3") -> str:
    """``"z3 4.x.y"`` or ``"cvc5 1.x.y"``; raises :class:`ImportError` when the solver is not installed."""
    if solver == "z3":
        import z3

        return f"z3 {z3.get_version_string()}"
    if solver == "cvc5":
        import cvc5

        return f"cvc5 {getattr(cvc5, '__version__', '?')}"
    raise ValueError(f"unknown solver {solver!r}; expected 'z3' or 'cvc5'")


def _z3_value(v: Any) -> str:
    import z3

    if z3.is_rational_value(v):
        return str(Fraction(v.numerator_as_long(), v.denominator_as_long()))
    if z3.is_algebraic_value(v):
        return v.as_decimal(30)  # ends in "?": an approximation of an irrational root
    return str(v)


def _z3(script: ClaimScript, timeout_s: float) -> ClaimAnswer:
    import z3

    ctx = z3.Context()
    s = z3.Solver(ctx=ctx)
    s.set("timeout", max(1, int(timeout_s * 1000)))
    start = time.perf_counter()
    s.from_string(script.text)
    r = s.check()
    seconds = time.perf_counter() - start
    if r == z3.sat:
        m = s.model()
        return ClaimAnswer("sat", seconds, tuple((shown, _z3_value(m.eval(z3.Real(n, ctx), model_completion=True)))
                                                 for n, shown in _shown(script)))
    if r == z3.unsat:
        return ClaimAnswer("unsat", seconds)
    why = s.reason_unknown()
    return ClaimAnswer("timeout" if why in ("timeout", "canceled") else "unknown", seconds, (), why)


def _shown(script: ClaimScript) -> list[tuple[str, str]]:
    """``(SMT name, name to show)``: the sympy symbol's name, or the SMT name where two symbols share one."""
    counts: dict[str, int] = {}
    for _, name in script.names:
        counts[name] = counts.get(name, 0) + 1
    return [(n, name if counts[name] == 1 else n) for n, name in script.names]


def _cvc5(script: ClaimScript, timeout_s: float) -> ClaimAnswer:
    import cvc5

    tm = cvc5.TermManager()
    s = cvc5.Solver(tm)
    s.setOption("produce-models", "true")
    s.setOption("tlimit-per", str(max(1, int(timeout_s * 1000))))
    s.setLogic("QF_NRA")
    parser = cvc5.InputParser(s)
    parser.setStringInput(cvc5.InputLanguage.SMT_LIB_2_6, script.text, "claim")
    symbols = parser.getSymbolManager()
    start = time.perf_counter()
    while not (cmd := parser.nextCommand()).isNull():
        cmd.invoke(s, symbols)
    r = s.checkSat()
    seconds = time.perf_counter() - start
    if r.isSat():
        terms = {str(t): t for t in symbols.getDeclaredTerms()}
        model = []
        for n, shown in _shown(script):
            v = s.getValue(terms[n])
            model.append((shown, str(v.getRealValue()) if v.isRealValue() else str(v)))
        return ClaimAnswer("sat", seconds, tuple(model))
    if r.isUnsat():
        return ClaimAnswer("unsat", seconds)
    why = str(r.getUnknownExplanation())
    return ClaimAnswer("timeout" if "TIMEOUT" in why else "unknown", seconds, (), why)


def solve_claim(script: ClaimScript, *, timeout_s: float = 10.0, solver: str = "z3") -> ClaimAnswer:
    """One claim's query on a fresh solver context, stopped after ``timeout_s``."""
    if solver == "z3":
        return _z3(script, timeout_s)
    if solver == "cvc5":
        return _cvc5(script, timeout_s)
    raise ValueError(f"unknown solver {solver!r}; expected 'z3' or 'cvc5'")


def _verdict(ob: SmtObligation, answers: list[ClaimAnswer | None]) -> SmtOutcome:
    outcome = _status(ob, answers)
    if ob.verdict != "holds":  # the claims of a failing check are still claims, but say so
        note = "the package's own check fails this obligation"
        outcome = SmtOutcome(outcome.id, outcome.status, outcome.seconds, f"{outcome.reason}; {note}" if outcome.reason else note,
                             outcome.claims, outcome.confirmed, outcome.model)
    return outcome


def _status(ob: SmtObligation, answers: list[ClaimAnswer | None]) -> SmtOutcome:
    seconds = sum(a.seconds for a in answers if a is not None)
    n, done = len(ob.claims), 0
    for script, a in zip(ob.claims, answers):
        if a is not None and a.answer == script.expect:
            done += 1
    if not ob.claims:
        return SmtOutcome(ob.id, "not expressible", 0.0, _inexpressible_reason(ob))
    for script, a in zip(ob.claims, answers):
        if a is not None and a.answer in ("sat", "unsat") and a.answer != script.expect:
            what = ("the solver found a model of its negation" if script.expect == "unsat"
                    else "the solver shows the expression is identically 0")
            return SmtOutcome(ob.id, "counterexample", seconds, f"{script.label}: {what}", n, done, a.model)
    for status in ("timeout", "unknown"):
        hit = [(s, a) for s, a in zip(ob.claims, answers) if a is not None and a.answer == status]
        if hit:
            detail = f" ({hit[0][1].why})" if hit[0][1].why else ""
            return SmtOutcome(ob.id, status, seconds, f"{len(hit)} claim(s) not decided{detail}, e.g. {hit[0][0].label}", n, done)
    if any(a is None for a in answers):
        return SmtOutcome(ob.id, "timeout", seconds, f"the time budget ran out after {done} of {n} claims", n, done)
    if ob.inexpressible:
        return SmtOutcome(ob.id, "not expressible", seconds, f"{_inexpressible_reason(ob)}; the other {n} confirmed", n, done)
    return SmtOutcome(ob.id, "confirmed", seconds, "", n, done)


def _inexpressible_reason(ob: SmtObligation) -> str:
    if not ob.inexpressible:
        return ob.reason
    reasons = sorted({why for _, why in ob.inexpressible})
    return f"{len(ob.inexpressible)} claim(s) not expressible: {', '.join(reasons)}"


def run_smt(
    exported: Sequence[SmtObligation],
    *,
    timeout_s: float = 10.0,
    obligation_s: float = 40.0,
    budget_s: float = 60.0,
    solver: str = "z3",
    workers: int = 2,
) -> list[SmtOutcome]:
    """Decide every exported claim with ``solver``; one :class:`SmtOutcome` per obligation, in the given order.

    Parameters
    ----------
    exported : sequence of SmtObligation
        From :func:`._export.export_smt`.
    timeout_s : float
        Time limit of one solver call (one claim).
    obligation_s : float
        Limit on an obligation's solver time, summed over its claims (a claim starts with what is left).
    budget_s : float
        Wall-clock budget of the whole run; claims not started by then count as timed out.
    solver : str
        ``"z3"`` or ``"cvc5"`` (must be installed; :func:`solver_version` checks).
    workers : int
        Threads; each claim runs on its own z3 context (z3 releases the GIL while it solves).  cvc5 runs on
        one thread, and its time limit is checked less often (a large polynomial can overrun it).
    """
    solver_version(solver)  # ImportError now, not in a thread
    if solver == "cvc5":
        workers = 1
    jobs = sorted(((len(s.text), i, k) for i, ob in enumerate(exported) for k, s in enumerate(ob.claims)))
    answers: list[list[ClaimAnswer | None]] = [[None] * len(ob.claims) for ob in exported]
    spent = [0.0] * len(exported)
    settled = [False] * len(exported)  # a counterexample or an undecided claim decides the obligation's status
    lock = threading.Lock()
    queue = iter(jobs)
    deadline = time.perf_counter() + budget_s

    def work() -> None:
        while True:
            with lock:
                job = next(queue, None)
                if job is None:
                    return
                _, i, k = job
                left = min(timeout_s, obligation_s - spent[i], deadline - time.perf_counter())
                if settled[i]:
                    continue
                if left <= 0:
                    if deadline - time.perf_counter() > 0:  # the obligation's share is spent
                        answers[i][k] = ClaimAnswer("timeout", 0.0, (), "the obligation's time share is spent")
                        settled[i] = True
                    continue
            script = exported[i].claims[k]
            try:
                answer = solve_claim(script, timeout_s=left, solver=solver)
            except Exception as exc:  # noqa: BLE001 - a solver's error leaves the claim undecided, never confirmed
                answer = ClaimAnswer("unknown", 0.0, (), f"solver error: {type(exc).__name__}: {exc}")
            with lock:
                answers[i][k] = answer
                spent[i] += answer.seconds
                if answer.answer != script.expect:
                    settled[i] = True

    threads = [threading.Thread(target=work, name=f"smt-{n}", daemon=True) for n in range(max(1, workers))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return [_verdict(ob, a) for ob, a in zip(exported, answers)]


def smt_summary(outcomes: Sequence[SmtOutcome], seconds: float, solver: str = "z3") -> str:
    """``"z3 …: confirmed N of M polynomial obligations (P %), N of T overall, in S s"``."""
    poly = [o for o in outcomes if o.expressible]
    ok = sum(1 for o in poly if o.status == "confirmed")
    share = f" ({100 * ok / len(poly):.0f} %)" if poly else ""
    bad = sum(1 for o in outcomes if o.status == "counterexample")
    tail = f"; {bad} COUNTEREXAMPLE{'S' if bad != 1 else ''}" if bad else ""
    return (f"{solver}: confirmed {ok} of {len(poly)} polynomial obligations{share}, {ok} of {len(outcomes)} overall, "
            f"in {seconds:.1f} s{tail}")


def render_smt(outcomes: Sequence[SmtOutcome], seconds: float, solver: str = "z3") -> str:
    """One line per obligation (id, status, solver seconds, claims confirmed, reason) and the summary line."""
    width = max((len(o.id) for o in outcomes), default=2)
    lines = []
    for o in outcomes:
        counts = f"{o.confirmed}/{o.claims}" if o.claims else "-"
        line = f"{o.id:<{width}}  {o.status:<15}  {o.seconds:6.2f} s  {counts:>7}"
        if o.reason:
            line += f"  {o.reason}"
        if o.model:
            line += "  model: " + ", ".join(f"{k} = {v}" for k, v in o.model)
        lines.append(line)
    lines.append(smt_summary(outcomes, seconds, solver))
    return "\n".join(lines) + "\n"
