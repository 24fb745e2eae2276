"""``check``'s tail named after the fork: each process builds the list itself, the child claims only from the same one."""

from __future__ import annotations

import argparse
import os
import sys
import time

import pytest

from symbolic_friction._cli import _parallel
from symbolic_friction._cli._sections import Section

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux") or (os.cpu_count() or 1) < 2,
                                reason="needs fork and two cores")


def _later(args):
    return Section("later", ("pid",), [(str(os.getpid()),)], {}, True, [], summary="later")


def _first(names, *, until_child_ends=False):
    """A first section that works through ``names`` as the obligations do, after giving the child time to claim
    (until it has claimed every item, or until it has ended: whatever it could claim, it then has)."""

    def first(args):
        deadline = time.monotonic() + 30
        while (args.inbox.proc.is_alive() and time.monotonic() < deadline
               and (until_child_ends or args.claims.back.value > 0)):
            time.sleep(0.01)
        rows = []
        for name in names:
            if args.claims.take_front(name):
                rows.append((name, str(os.getpid())))
            else:
                rows.append((name, str(args.inbox.get("claimed", name))))
        return Section("first", ("item", "by"), rows, {}, True, [], summary="first")

    return first


def _run(first, tail, **kw):
    return list(_parallel.run_sections([first, _later], argparse.Namespace(json=False), parallel=True, tail=tail, **kw))


def test_a_tail_built_in_each_process_is_claimed_by_the_child_from_the_back(monkeypatch):
    monkeypatch.delenv(_parallel.ENV, raising=False)
    built_in = []

    def tail():
        built_in.append(os.getpid())  # in this process only; the child's call is in the child's memory
        return [(name, os.getpid) for name in ("x", "y", "z")]

    got = _run(_first(["x", "y", "z"]), tail)
    by = dict(got[0].rows)
    assert built_in == [os.getpid()]  # this process built it once, after the fork
    assert sorted(by) == ["x", "y", "z"] and str(os.getpid()) not in by.values() and len(set(by.values())) == 1
    assert got[1].rows[0][0] == by["x"]  # the child did its sections, then the tail


def test_a_child_whose_list_differs_claims_nothing(monkeypatch):
    """A list that is not the same in both processes (another length, or other names) is all this process's."""
    monkeypatch.delenv(_parallel.ENV, raising=False)
    parent = os.getpid()
    for other in (["x", "y"], ["x", "y", "w"]):
        def tail(other=other):
            return [(name, os.getpid) for name in (["x", "y", "z"] if os.getpid() == parent else other)]

        got = _run(_first(["x", "y", "z"], until_child_ends=True), tail)
        assert dict(got[0].rows) == {"x": str(parent), "y": str(parent), "z": str(parent)}


def test_a_tail_that_fails_to_build_leaves_every_item_to_this_process(monkeypatch):
    monkeypatch.delenv(_parallel.ENV, raising=False)
    parent = os.getpid()

    def tail():
        if os.getpid() == parent:
            raise RuntimeError("cannot build the tail")
        return [(name, os.getpid) for name in ("x", "y")]

    def first(args):
        assert args.claims.names == () and args.claims.count.value == 0
        return Section("first", ("x",), [], {}, True, [], summary="first")

    got = _run(first, tail)
    assert [s.title for s in got] == ["first", "later"] and all(s.ok for s in got)


def test_a_list_longer_than_the_shared_capacity_is_all_this_processs(monkeypatch):
    monkeypatch.delenv(_parallel.ENV, raising=False)
    monkeypatch.setattr(_parallel.Claims, "CAPACITY", 2)
    names = ["x", "y", "z"]
    got = _run(_first(names, until_child_ends=True), lambda: [(name, os.getpid) for name in names])
    assert dict(got[0].rows) == {name: str(os.getpid()) for name in names}


def test_the_tail_is_not_built_when_everything_runs_here(monkeypatch):
    calls = []
    got = list(_parallel.run_sections([lambda a: _later(a), _later], argparse.Namespace(json=False), parallel=False,
                                      tail=lambda: calls.append(1) or []))
    assert calls == [] and len(got) == 2


def test_adopt_waits_for_the_published_list_and_checks_it():
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    claims = _parallel.Claims(ctx, together=(("b", "c"),))
    assert not claims.adopt(["a"], timeout=0.01)  # nothing published yet
    claims.publish(["a", "b", "c"])
    assert not claims.adopt(["a", "c", "b"], timeout=0.01)  # same length, other order
    assert claims.adopt(["a", "b", "c"], timeout=0.01)
    assert claims.take_back() == (1, 2)  # the group of b and c, claimed as one
    assert claims.take_front("a") and not claims.take_front("b")
