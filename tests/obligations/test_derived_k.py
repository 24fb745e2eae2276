"""Sharing Lemma 3's derived k-conditions within one ``check`` run, and only there."""

from __future__ import annotations

import dataclasses

import sympy as sp

from symbolic_friction._obligations import _derived_k
from symbolic_friction._obligations.lemma3 import HatVDerivative


def _counting(monkeypatch):
    calls = []
    real = _derived_k._derive_k_conditions

    def count(subject):
        calls.append(subject)
        return real(subject)

    monkeypatch.setattr(_derived_k, "_derive_k_conditions", count)
    return calls


def test_equal_subjects_share_one_derivation_inside_the_block(monkeypatch):
    calls = _counting(monkeypatch)
    with _derived_k.shared_derivations():
        first = _derived_k.derived_k_conditions(HatVDerivative().derive())
        again = _derived_k.derived_k_conditions(HatVDerivative().derive())
    assert len(calls) == 1 and again is first


def test_nothing_is_shared_outside_the_block(monkeypatch):
    calls = _counting(monkeypatch)
    with _derived_k.shared_derivations():
        _derived_k.derived_k_conditions(HatVDerivative().derive())
    _derived_k.derived_k_conditions(HatVDerivative().derive())
    assert len(calls) == 2 and _derived_k._SHARED == []


def test_a_subject_differing_in_one_assumption_is_derived_again(monkeypatch):
    calls = _counting(monkeypatch)
    s = HatVDerivative().derive()
    other = dataclasses.replace(s, zeta=sp.Symbol(s.zeta.name))  # same name, without the assumption
    with _derived_k.shared_derivations():
        _derived_k.derived_k_conditions(s)
        _derived_k.derived_k_conditions(other)
    assert len(calls) == 2
