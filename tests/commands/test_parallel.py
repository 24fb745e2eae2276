"""``check``'s sections on two cores: same sections, same order, and a dying worker fails them."""

from __future__ import annotations

import argparse
import os
import sys

import pytest

from symbolic_friction._cli import _parallel
from symbolic_friction._cli._sections import Section

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux") or (os.cpu_count() or 1) < 2,
                                reason="needs fork and two cores")


def _maker(name: str, ok: bool = True):
    def make(args):
        return Section(name, ("pid",), [(str(os.getpid()),)], {name: args.json}, ok, [], summary=name)

    make.__name__ = name
    return make


def test_sections_come_back_in_order_and_the_later_ones_ran_elsewhere(monkeypatch):
    monkeypatch.delenv(_parallel.ENV, raising=False)
    args = argparse.Namespace(json=False)
    got = list(_parallel.run_sections([_maker("one"), _maker("two", ok=False), _maker("three")], args, parallel=True))
    assert [s.title for s in got] == ["one", "two", "three"] and [s.ok for s in got] == [True, False, True]
    assert got[0].rows[0][0] == str(os.getpid()) and got[1].rows[0][0] != str(os.getpid())
    assert got[0].json == {"one": False} and got[1].json == {"two": True}  # the worker streams nothing
    assert args.json is False


def test_a_section_that_raises_in_the_worker_fails():
    def boom(args):
        raise ValueError("no luck")

    got = list(_parallel.run_sections([_maker("one"), boom, _maker("three")], argparse.Namespace(json=False), parallel=True))
    assert not got[1].ok and "boom crashed: ValueError: no luck" in got[1].summary and got[2].ok


def test_a_worker_that_dies_leaves_its_sections_to_this_process():
    parent = os.getpid()

    def die_in_worker(args):
        if os.getpid() != parent:
            os._exit(3)
        return Section("here", ("pid",), [(str(os.getpid()),)], {}, True, [], summary="here")

    got = list(_parallel.run_sections([_maker("one"), die_in_worker, _maker("three")], argparse.Namespace(json=False),
                                      parallel=True))
    assert [s.ok for s in got] == [True, True, True]
    assert got[1].rows == [(str(parent),)] and got[2].rows == [(str(parent),)]
    assert "decided in the main process" in got[1].notes[-1] and "without a result" in got[1].notes[-1]


def test_one_job_runs_everything_here(monkeypatch):
    monkeypatch.setenv(_parallel.ENV, "1")
    assert not _parallel.parallel_allowed()
    got = list(_parallel.run_sections([_maker("one"), _maker("two")], argparse.Namespace(json=False)))
    assert {s.rows[0][0] for s in got} == {str(os.getpid())}


def _held_until_claimed(monkeypatch, args, name, limit=3.0):
    """Make this process's coordinates obligation wait until the worker has claimed ``name`` from the back of the
    tail (at most ``limit`` s, the fixed sleep this replaces: a claim is a flag set under the lock, read here)."""
    import time

    from symbolic_friction._obligations.coordinates import Coordinates

    real = Coordinates.verify

    def held(self, subject):
        deadline = time.monotonic() + limit
        while time.monotonic() < deadline:
            claims = args.claims
            if claims is not None and claims.owner[claims.names.index(name)] == 2:  # 2: the child's
                break
            time.sleep(0.005)
        return real(self, subject)

    monkeypatch.setattr(Coordinates, "verify", held)


def _small_check(monkeypatch, tmp_path, later, *, tail=None):
    """``check.run`` on two obligations (coordinates held until the worker, done with its cheap later section,
    has claimed claim1.cases from the back of the tail) and one cheap later section."""
    from symbolic_friction import _obligations
    from symbolic_friction._cli import check
    from symbolic_friction._obligations.claim1 import Claim1Cases
    from symbolic_friction._obligations.coordinates import Coordinates

    args = argparse.Namespace(json=True, write=False, proofs=str(tmp_path), config=None, no_certificates=True,
                              only=None, junit_xml=None)
    _held_until_claimed(monkeypatch, args, "claim1.cases")
    monkeypatch.delenv(_parallel.ENV, raising=False)
    monkeypatch.setattr(_parallel, "parallel_allowed", lambda: True)  # also under pytest-xdist's threads
    monkeypatch.setattr(_obligations, "all_obligations", lambda: [Coordinates(), Claim1Cases()])
    monkeypatch.setattr(check, "SECTIONS", [check.obligations_section, later])
    if tail is not None:
        monkeypatch.setattr(check, "_decide_tail", tail)
    monkeypatch.chdir(tmp_path)
    return check.run(args)


def test_an_obligation_the_worker_claims_is_decided_there_and_reported(monkeypatch, tmp_path, capsys):
    from symbolic_friction._obligations._base import Outcome
    from symbolic_friction._obligations.claim1 import Claim1Cases

    parent = os.getpid()
    monkeypatch.setattr(Claim1Cases, "verify", lambda self, s: Outcome.fail(f"decided in {os.getpid()}"))
    code = _small_check(monkeypatch, tmp_path, _maker("later"))
    out = capsys.readouterr().out
    assert code == 1
    import json

    row = next(o for o in json.loads(out)["obligations"] if o["id"] == "claim1.cases")
    assert row["status"] != "holds" and "decided in" in row["reason"] and str(parent) not in row["reason"]


def test_a_worker_that_dies_on_a_claimed_obligation_leaves_it_to_this_process(monkeypatch, tmp_path, capsys):
    from symbolic_friction._cli import check
    from symbolic_friction._obligations._base import Outcome
    from symbolic_friction._obligations.claim1 import Claim1Cases

    parent = os.getpid()
    real_tail = check._decide_tail

    def dying_tail():
        return [(name, (lambda: os._exit(5)) if name == "claim1.cases" else work) for name, work in real_tail()]

    monkeypatch.setattr(Claim1Cases, "verify", lambda self, s: Outcome.fail(f"decided in {os.getpid()}"))
    _small_check(monkeypatch, tmp_path, _maker("later"), tail=dying_tail)
    import json

    row = next(o for o in json.loads(capsys.readouterr().out)["obligations"] if o["id"] == "claim1.cases")
    assert row["status"] != "holds" and row["reason"] == f"decided in {parent}"


def test_a_process_that_loaded_numba_does_not_fork(monkeypatch):
    monkeypatch.delenv(_parallel.ENV, raising=False)
    monkeypatch.setitem(sys.modules, "numba", object())
    assert not _parallel.parallel_allowed()


def test_the_worker_draws_no_progress_bar():
    from symbolic_friction._infra.output import verbosity

    def seen(args):
        return Section("seen", ("verbosity",), [(str(verbosity()),)], {}, True, [], summary="seen")

    got = list(_parallel.run_sections([_maker("one"), seen], argparse.Namespace(json=False), parallel=True))
    assert got[1].rows == [("0",)] and verbosity() == 1


def test_only_linux_forks(monkeypatch):
    monkeypatch.delenv(_parallel.ENV, raising=False)
    monkeypatch.setattr(sys, "platform", "darwin")
    assert not _parallel.parallel_allowed()


def test_a_process_with_other_threads_does_not_fork(monkeypatch):
    import threading

    monkeypatch.delenv(_parallel.ENV, raising=False)
    monkeypatch.setattr(threading, "active_count", lambda: 2)
    assert not _parallel.parallel_allowed()


def test_claims_split_a_list_between_its_two_ends():
    import multiprocessing

    claims = _parallel.Claims(multiprocessing.get_context("fork"), ["a", "b", "c", "d"])
    assert claims.take_back() == (3,)  # the child's: from the back
    assert claims.take_front("a") and claims.take_front("b")  # this process's: from the front
    assert claims.take_back() == (2,)
    assert not claims.take_front("c") and not claims.take_front("d")  # claimed by the child: ask the inbox
    assert claims.take_back() is None  # it met this process: nothing left, nothing done twice


def test_items_claimed_together_go_to_one_process():
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    claims = _parallel.Claims(ctx, ["a", "b", "c", "d", "e"], (("b", "d"),))
    assert claims.take_back() == (4,) and claims.take_back() == (1, 3)  # d brings b along
    assert claims.take_front("a") and not claims.take_front("b")
    assert claims.take_back() == (2,) and claims.take_back() is None  # b is already the child's; a is not
    claims = _parallel.Claims(ctx, ["a", "b", "c", "d", "e"], (("b", "d"),))
    assert claims.take_front("a") and claims.take_front("b")  # b brings d along
    assert claims.take_back() == (4,) and claims.take_back() == (2,)  # the child passes over d, this process's
    assert not claims.take_front("c") and claims.take_front("d")
    assert claims.take_back() is None


def _tail_user(names, wait_for_child):
    """A first section that works through ``names`` like the obligations: here if claimed first, else the inbox's."""
    import time

    def first(args):
        deadline = time.monotonic() + 30
        while wait_for_child and args.claims.back.value > 0 and args.inbox.proc.is_alive() and time.monotonic() < deadline:
            time.sleep(0.01)  # let the child claim every item (or die)
        rows = []
        for name in names:
            if args.claims.take_front(name):
                rows.append((name, str(os.getpid())))
            else:
                try:
                    rows.append((name, str(args.inbox.get("claimed", name))))
                except RuntimeError as exc:
                    rows.append((name, f"here: {exc}"))
        return Section("first", ("item", "by"), rows, {}, True, [], summary="first")

    return first


def test_the_worker_takes_the_tail_from_the_back_once_its_sections_are_done(monkeypatch):
    monkeypatch.delenv(_parallel.ENV, raising=False)
    names = ["x", "y", "z"]
    tail = [(name, os.getpid) for name in names]
    got = list(_parallel.run_sections([_tail_user(names, True), _maker("later")], argparse.Namespace(json=False),
                                      parallel=True, tail=tail))
    by = dict(got[0].rows)
    assert sorted(by) == names and str(os.getpid()) not in by.values() and len(set(by.values())) == 1
    assert got[1].ok and got[1].rows[0][0] == by["x"]  # the same worker did the sections first


def test_a_worker_that_dies_on_a_claimed_item_leaves_it_to_this_process(monkeypatch):
    monkeypatch.delenv(_parallel.ENV, raising=False)
    tail = [("x", os.getpid), ("y", lambda: os._exit(7))]
    got = list(_parallel.run_sections([_tail_user(["x", "y"], True), _maker("later")], argparse.Namespace(json=False),
                                      parallel=True, tail=tail))
    by = dict(got[0].rows)
    assert by["y"].startswith("here:") and "exit code 7" in by["y"]  # the parent's obligation then decides it itself
    assert got[1].ok and got[1].rows == [(str(os.getpid()),)]  # its sections too


def test_a_tail_obligation_claimed_by_the_worker_is_reported_from_there(monkeypatch, tmp_path, capsys):
    import json

    from symbolic_friction import _obligations
    from symbolic_friction._cli import check
    from symbolic_friction._obligations._base import Outcome
    from symbolic_friction._obligations.claim1 import Claim1Cases
    from symbolic_friction._obligations.coordinates import Coordinates
    from symbolic_friction._obligations.table1 import TableI

    parent = os.getpid()
    args = argparse.Namespace(json=True, write=False, proofs=str(tmp_path), config=None, no_certificates=True,
                              only=None, junit_xml=None)
    _held_until_claimed(monkeypatch, args, "table1")  # the worker gets there first
    monkeypatch.setattr(TableI, "verify", lambda self, s: Outcome.fail(f"decided in {os.getpid()}"))
    monkeypatch.setattr(Claim1Cases, "verify", lambda self, s: Outcome(True, "stub"))
    monkeypatch.delenv(_parallel.ENV, raising=False)
    monkeypatch.setattr(_parallel, "parallel_allowed", lambda: True)
    monkeypatch.setattr(_obligations, "all_obligations", lambda: [Coordinates(), Claim1Cases(), TableI()])
    monkeypatch.setattr(check, "SECTIONS", [check.obligations_section, _maker("later")])
    monkeypatch.chdir(tmp_path)
    assert [name for name, _ in check._decide_tail()] == ["coordinates", "claim1.cases", "table1"]
    assert check.run(args) == 1
    rows = {o["id"]: o for o in json.loads(capsys.readouterr().out)["obligations"]}
    assert list(rows) == ["coordinates", "claim1.cases", "table1"]  # the paper's order, whoever decided them
    assert rows["table1"]["status"] != "holds" and str(parent) not in rows["table1"]["reason"]


def test_the_worker_works_through_the_tail_within_the_context(monkeypatch):
    """``check`` passes ``shared_derivations``: a group the worker claims shares one derivation there too."""
    import contextlib

    monkeypatch.delenv(_parallel.ENV, raising=False)
    state = {"inside": False}

    @contextlib.contextmanager
    def context():
        state["inside"] = True
        yield
        state["inside"] = False

    got = list(_parallel.run_sections([_tail_user(["x"], True), _maker("later")], argparse.Namespace(json=False),
                                      parallel=True, tail=[("x", lambda: state["inside"])], context=context))
    assert dict(got[0].rows) == {"x": "True"} and not state["inside"]


@pytest.mark.parametrize("parallel", [True, False])
def test_the_collector_is_off_in_both_processes_while_the_sections_run_and_on_again_after(parallel):
    import gc

    def collecting(args):
        return Section("gc", ("enabled",), [(str(gc.isenabled()),)], {}, True, [], summary="gc")

    assert gc.isenabled()
    got = list(_parallel.run_sections([collecting, collecting], argparse.Namespace(json=False), parallel=parallel))
    assert [s.rows[0][0] for s in got] == ["False", "False"]
    assert gc.isenabled()
    gc.disable()  # a caller that had it off keeps it off
    try:
        list(_parallel.run_sections([collecting], argparse.Namespace(json=False), parallel=False))
        assert not gc.isenabled()
    finally:
        gc.enable()
