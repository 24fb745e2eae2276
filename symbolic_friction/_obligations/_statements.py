"""What Lemma 2 and Lemma 3 conclude, in the form Proposition 1's proof uses them.

Proposition 1's stability bound (eq. stabState) is a chain of inequalities
whose premises are the conclusions of Lemma 2 and Lemma 3 at particular
points.  They are written here once, as functions returning ``(lhs, rhs)``
of ``lhs ≤ rhs``:

* :func:`lemma2_lower_bound` — Lemma 2 item 1: ``c₁|x|²_𝒜 ≤ V(x)``;
* :func:`lemma2_decrease` — Lemma 2 item 2 (eq. Vdecrease, with the
  nonnegative ``c∫v²`` dropped): ``V(x(t₂)) ≤ V(x(t₁))`` for ``t₂ ≥ t₁``;
* :func:`lemma3_V_bounds` — eq. (VandR) on ``R``: ``c₁|x|²_𝒜 ≤ V ≤ c₂|x|²_𝒜``;
* :func:`lemma3_hatV_bounds` — eq. (hatVandHatR) on ``R̂``;
* :func:`lemma3_hatV_nonincreasing` — eq. (hatVdot): ``V̂`` does not increase
  while the solution stays in ``R̂``.

Each lemma's obligation checks (with :func:`statement_failure`) that the
statement here is exactly the inequality it proves, and
``prop1.stability_bound`` builds its premises by calling these functions, so
weakening a statement fails the lemma's obligation and changes the premises
Proposition 1 is checked with.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import sympy as sp

from ._decide import is_zero

__all__ = [
    "lemma2_lower_bound",
    "lemma2_decrease",
    "lemma3_V_bounds",
    "lemma3_hatV_bounds",
    "lemma3_hatV_nonincreasing",
    "statement_failure",
]

Pair = tuple[Any, Any]


def lemma2_lower_bound(c1: Any, dist2: Any, V: Any) -> Pair:
    """Lemma 2 item 1 at one point: ``c₁|x|²_𝒜 ≤ V(x)``."""
    return c1 * dist2, V


def lemma2_decrease(V_later: Any, V_earlier: Any) -> Pair:
    """Lemma 2 item 2 between two times: ``V(x(t₂)) ≤ V(x(t₁))``."""
    return V_later, V_earlier


def lemma3_V_bounds(c1: Any, c2: Any, dist2: Any, V: Any) -> tuple[Pair, Pair]:
    """eq. (VandR) at a point of ``R``: ``c₁|x|²_𝒜 ≤ V`` and ``V ≤ c₂|x|²_𝒜``."""
    return (c1 * dist2, V), (V, c2 * dist2)


def lemma3_hatV_bounds(c1_hat: Any, c2_hat: Any, dist2: Any, V_hat: Any) -> tuple[Pair, Pair]:
    """eq. (hatVandHatR) at a point of ``R̂``: ``ĉ₁|x|²_𝒜 ≤ V̂`` and ``V̂ ≤ ĉ₂|x|²_𝒜``."""
    return (c1_hat * dist2, V_hat), (V_hat, c2_hat * dist2)


def lemma3_hatV_nonincreasing(V_hat_later: Any, V_hat_earlier: Any) -> Pair:
    """eq. (hatVdot), integrated while in ``R̂``: ``V̂(x(t₂)) ≤ V̂(x(t₁))``."""
    return V_hat_later, V_hat_earlier


def statement_failure(statement: Callable[..., Any], proved: Callable[..., Any]) -> str | None:
    """``None`` if ``statement`` gives exactly the inequalities ``proved`` describes, else why not.

    Both are called on the same fresh positive symbols; ``proved`` returns
    the gaps ``rhs - lhs`` that the calling obligation has shown
    nonnegative, in the order of ``statement``'s pairs.
    """
    n = statement.__code__.co_argcount if hasattr(statement, "__code__") else 4
    args = sp.symbols(f"a_0:{n}", positive=True)
    got = statement(*args)
    pairs = got if isinstance(got[0], tuple) else (got,)
    want = proved(*args)
    want = want if isinstance(want, tuple) else (want,)
    if len(pairs) != len(want):
        return f"the statement has {len(pairs)} inequalities, the proof {len(want)}"
    for (lhs, rhs), gap in zip(pairs, want):
        if not is_zero(sp.expand(sp.sympify(rhs) - sp.sympify(lhs) - gap)):
            return f"the statement {lhs} ≤ {rhs} is not what is proved here ({gap} ≥ 0)"
    return None
