"""The obligations machinery: a verdict becomes a status, a crash is a failure, nothing holds by default."""

from __future__ import annotations

import pytest

from symbolic_friction._obligations import _base, run_checked
from symbolic_friction._obligations._base import FAILS, HOLDS, Obligation, Outcome, Result


class _Fixed(Obligation):
    id, paper, statement, method = "test.fixed", "nowhere", "a statement", "by fiat"

    def __init__(self, holds: bool, reason: str = "") -> None:
        self._holds, self._reason, self.derived = holds, reason, 0

    def derive(self):
        self.derived += 1
        return "subject"

    def verify(self, subject):
        assert subject in ("subject", "given")
        return Outcome(self._holds, self._reason, (("x", "1"),))


class _Crashing(_Fixed):
    id = "test.crashing"

    def verify(self, subject):
        raise ZeroDivisionError("7 / 0")


def test_run_maps_the_verdict_to_the_status():
    good, bad = _Fixed(True).run(), _Fixed(False, "residual 3").run()
    assert (good.status, good.holds) == (HOLDS, True) and (bad.status, bad.holds) == (FAILS, False)
    assert bad.reason == "residual 3" and bad.details == (("x", "1"),)
    assert (bad.id, bad.paper, bad.statement, bad.method) == ("test.fixed", "nowhere", "a statement", "by fiat")
    assert bad.seconds >= 0


def test_run_derives_only_without_a_subject():
    ob = _Fixed(True)
    ob.run("given")
    assert ob.derived == 0
    ob.run()
    assert ob.derived == 1


def test_run_checked_reports_a_crash_as_failing_and_calls_back_in_order():
    seen = []
    results = run_checked([_Fixed(True), _Crashing(True), _Fixed(False)], on_result=seen.append)
    assert [r.status for r in results] == [HOLDS, FAILS, FAILS]
    assert seen == results
    crash = results[1]
    assert crash.id == "test.crashing" and not crash.holds
    assert crash.reason == "error while checking: ZeroDivisionError: 7 / 0"
    assert run_checked([]) == []


def test_outcome_fail_and_result_json():
    out = Outcome.fail("why", (("a", "b"),))
    assert (out.holds, out.reason, out.details) == (False, "why", (("a", "b"),))
    r = Result("i", "p", "s", "m", FAILS, 0.123456, "r", (("l", "t"),))
    assert r.as_json() == {"id": "i", "paper": "p", "statement": "s", "method": "m", "status": "fails", "seconds": 0.1235,
                           "reason": "r", "details": [{"label": "l", "latex": "t"}]}
    assert not Result("i", "p", "s", "m", "unknown", 0.0).holds
    assert (HOLDS, FAILS) == ("holds", "fails")


def test_an_obligation_must_implement_derive_and_verify():
    class Incomplete(Obligation):
        id, paper, statement, method = "x.y", "p", "s", "m"

    with pytest.raises(TypeError):
        Incomplete()
    assert _base.Erratum("w", "p", "c", "b").as_json() == {"where": "w", "paper_says": "p", "correct": "c", "checked_by": "b"}
