"""``check``'s sections on two cores: same sections, same order, and a dying worker fails them."""

from __future__ import annotations

import argparse
import os

import pytest

from symbolic_friction._cli import _parallel
from symbolic_friction._cli._sections import Section

pytestmark = pytest.mark.skipif(not _parallel.parallel_allowed() and os.environ.get(_parallel.ENV) != "1",
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


def test_a_worker_that_dies_fails_its_sections():
    def die(args):
        os._exit(3)

    got = list(_parallel.run_sections([_maker("one"), die, _maker("three")], argparse.Namespace(json=False), parallel=True))
    assert got[0].ok and not got[1].ok and not got[2].ok
    assert "without a result" in got[1].summary


def test_one_job_runs_everything_here(monkeypatch):
    monkeypatch.setenv(_parallel.ENV, "1")
    assert not _parallel.parallel_allowed()
    got = list(_parallel.run_sections([_maker("one"), _maker("two")], argparse.Namespace(json=False)))
    assert {s.rows[0][0] for s in got} == {str(os.getpid())}
