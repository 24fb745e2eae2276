"""The paper's list of properties, in the paper's order.

Each entry is a :class:`~._property.Property` from the module of its part of
the paper: :mod:`.lemma2` (items 1 and 2), :mod:`.lemma3` (eqs. VandR,
hatVandHatR, hatVdot), :mod:`.prop1` (stability, attractivity),
:mod:`.remark_armstrong` (the Remark after Lemma 2) and :mod:`.mode_table`
(Claim 1, the appendix's table).  The :class:`~._checker.BatchChecker`
loops over them.
"""

from __future__ import annotations

from . import lemma2, lemma3, mode_table, prop1, remark_armstrong
from ._property import DEFAULT_RTOL, DEFAULT_THETA, Evaluation, Property
from ._results import Counterexample, PropertyResult

__all__ = ["PROPERTIES", "properties", "DEFAULT_RTOL", "DEFAULT_THETA", "Property", "Evaluation", "Counterexample",
           "PropertyResult"]


def properties(*, rtol: float = DEFAULT_RTOL, theta: float = DEFAULT_THETA) -> tuple[Property, ...]:
    """The properties in the paper's order, with the run's tolerance and attractivity factor."""
    return (
        lemma2.Decrease(),
        lemma2.Nonincreasing(),
        lemma2.LowerBound(),
        lemma3.VUpper(),
        lemma3.HatVLower(),
        lemma3.HatVUpper(),
        lemma3.HatVNonincreasing(),
        prop1.Stability(),
        prop1.Attractivity(theta=theta),
        remark_armstrong.StickSigma(rtol=rtol),
        mode_table.Modes(),
    )


PROPERTIES: tuple[Property, ...] = properties()
"""Every checked property, with the default tolerance and θ."""
