"""The conditions on ``k₁ … k₄`` of Lemma 3 (proof of eq. hatVdot), as data.

The auxiliary function of eq. (Vhat),

.. math::

    \\hat V(x) = \\tfrac12 k_1\\sigma^2 + \\tfrac12 k_2\\,\\mathrm{dz}(\\phi)^2
        + k_3|\\sigma||v| + \\tfrac12 k_4 v^2,

proves stability (Lemma 3, Proposition 1 item 2) when ``k₁ … k₄`` satisfy
the paper's conditions

.. math::

    k_j > 0,\\qquad
    k_3 > \\max\\{\\tfrac{k_i}{k_v}k_1,\\ k_2\\},\\qquad
    k_4 > \\max\\{\\tfrac{k_i}{k_v}k_3,\\ k_p k_2,\\ \\tfrac{k_3^2}{k_1}\\}.

This module states them once, with plain arithmetic, so the same list serves
exact rationals (:class:`fractions.Fraction`; the certificate verifier), sympy
symbols (the obligation ``lemma3.hatV_derivative``, which *derives* the
conditions from ``V̂`` and ``F`` and checks that they are exactly these) and
floats or cvxpy expressions (the certificate search).  The last condition is
written ``k₁k₄ > k₃²`` to avoid a division.

What the derivation shows (see ``symbolic-friction check``):

* positivity is a premise of Lemma 3;
* the four ``max`` conditions are *necessary and sufficient* for ``V̂° ≤ 0``
  on ``R̂`` in their non-strict form (``≥``); the strict form stated here,
  as in the paper, is sufficient and gives the certificate search a margin;
* ``k₁k₄ > k₃²`` makes the matrix ``K`` of ``V̂ = ½wᵀKw`` positive definite
  (the paper's route to eq. hatVandHatR).  It is *not* needed for the lower
  bound on ``R̂``: for the nonnegative vector ``w = (|σ|, |dz(φ)|, |v|)``,
  ``½wᵀKw ≥ ½min(k₁, k₂, k₄)|w|²`` because ``k₃ ≥ 0``.

This module imports neither numpy nor sympy.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from .._infra.errors import CertificateError, InvalidNumberError
from .._infra.rational import format_rational, to_rational

__all__ = [
    "Condition",
    "CONDITION_NAMES",
    "k_conditions",
    "check_k_conditions",
]

CONDITION_NAMES: tuple[str, ...] = (
    "k1 > 0",
    "k2 > 0",
    "k3 > 0",
    "k4 > 0",
    "k3 > (k_i/k_v)·k1",
    "k3 > k2",
    "k4 > (k_i/k_v)·k3",
    "k4 > k_p·k2",
    "k1·k4 > k3²",
)
"""Names of the conditions, in the order :func:`k_conditions` returns them."""

_KINDS = ("positivity",) * 4 + ("derivative",) * 4 + ("definiteness",)
_SOURCES = ("Lemma 3 (k₁,…,k₄ positive)",) * 4 + ("Lemma 3, proof of eq. (hatVdot)",) * 4 + (
    "Lemma 3, proof of eq. (hatVandHatR) (K ≻ 0)",
)


@dataclass(frozen=True)
class Condition:
    """One strict inequality ``lhs > rhs`` on the constants ``k₁ … k₄``.

    Attributes
    ----------
    name : str
        Human-readable form, e.g. ``"k3 > (k_i/k_v)·k1"``; one of
        :data:`CONDITION_NAMES`.
    lhs, rhs : Fraction, sympy expression, float, ...
        The two sides, computed with plain arithmetic from the arguments of
        :func:`k_conditions` (so they are of the arguments' kind).
    kind : str
        ``"positivity"``, ``"derivative"`` (from ``V̂° ≤ 0``) or
        ``"definiteness"`` (``K ≻ 0``).
    source : str
        Where the paper uses it.
    strict : bool
        Always ``True``: every condition is stated as ``lhs > rhs``.
    """

    name: str
    lhs: Any
    rhs: Any
    kind: str
    source: str
    strict: bool = True

    def __post_init__(self) -> None:
        if self.name not in CONDITION_NAMES:
            raise ValueError(f"unknown k-condition name {self.name!r}; expected one of {CONDITION_NAMES}")

    @property
    def margin(self) -> Any:
        """``lhs - rhs``; the condition holds iff this is positive."""
        return self.lhs - self.rhs

    def holds(self) -> bool:
        """Decide ``lhs > rhs`` exactly.

        Raises
        ------
        InvalidNumberError
            If a side is not an exact rational (a float, a symbol, ...):
            a float comparison would not be a proof.
        """
        sides = []
        for label, value in (("lhs", self.lhs), ("rhs", self.rhs)):
            if isinstance(value, float) or not _is_exact(value):
                raise InvalidNumberError(
                    f"condition {self.name!r} can only be decided for exact rationals; "
                    f"its {label} is {type(value).__name__} {value!r}"
                )
            sides.append(to_rational(value, name=f"{self.name} ({label})"))
        return sides[0] > sides[1]

    def describe(self) -> str:
        """``"k3 > k2: 1/2 > 3/5 is false"``-style text for exact sides."""
        lhs, rhs = (format_rational(to_rational(s)) if _is_exact(s) else str(s) for s in (self.lhs, self.rhs))
        verdict = "" if not (_is_exact(self.lhs) and _is_exact(self.rhs)) else (" is true" if self.holds() else " is false")
        return f"{self.name}: {lhs} > {rhs}{verdict}"


def _is_exact(value: Any) -> bool:
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, Fraction)):
        return True
    return type(value).__module__.startswith("sympy") and bool(getattr(value, "is_Rational", False))


def _exact_int(value: Any) -> Any:
    # Python ints would turn k_i/k_v into a float; keep exact input exact.
    if isinstance(value, int) and not isinstance(value, bool):
        return Fraction(value)
    return value


def k_conditions(k_p: Any, k_i: Any, k_v: Any, k1: Any, k2: Any, k3: Any, k4: Any) -> tuple[Condition, ...]:
    """The paper's conditions on ``k₁ … k₄`` for gains ``(k_p, k_i, k_v)``.

    Parameters
    ----------
    k_p, k_i, k_v : Fraction, int, sympy expression or float
        Normalised gains (``k_v > 0`` is assumed: it divides).
    k1, k2, k3, k4 : same kinds
        The constants of eq. (Vhat).

    Returns
    -------
    tuple of Condition
        In the order of :data:`CONDITION_NAMES`.  Python ints are promoted to
        Fractions so the sides stay exact.

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> conds = k_conditions(3, 4, F(32, 5), 1, 1, 2, 8)
    >>> [c.name for c in conds if not c.holds()]
    []
    >>> conds[4].describe()
    'k3 > (k_i/k_v)·k1: 2 > 5/8 is true'
    """
    k_p, k_i, k_v, k1, k2, k3, k4 = (_exact_int(q) for q in (k_p, k_i, k_v, k1, k2, k3, k4))
    zero = k1 - k1
    pairs = (
        (k1, zero),
        (k2, zero),
        (k3, zero),
        (k4, zero),
        (k3, k_i * k1 / k_v),
        (k3, k2),
        (k4, k_i * k3 / k_v),
        (k4, k_p * k2),
        (k1 * k4, k3**2),
    )
    return tuple(
        Condition(name=name, lhs=lhs, rhs=rhs, kind=kind, source=source)
        for name, (lhs, rhs), kind, source in zip(CONDITION_NAMES, pairs, _KINDS, _SOURCES)
    )


def check_k_conditions(k_p: Any, k_i: Any, k_v: Any, k1: Any, k2: Any, k3: Any, k4: Any) -> tuple[Condition, ...]:
    """Verify every condition exactly and return them; raise if any fails.

    All seven arguments are converted with :func:`~symbolic_friction.to_rational`
    (decimal strings and floats through their decimal form), so the decision
    uses exact rational arithmetic only.

    Raises
    ------
    InvalidNumberError, NonFiniteError
        If an argument is not a finite number.
    CertificateError
        If a condition fails; the message lists every failing condition
        with its exact numbers, e.g. ``"k3 > k2: 1/2 > 3/5 is false"``.

    Examples
    --------
    >>> check_k_conditions(3, 4, "6.4", 1, "3/5", "1/2", 8)
    Traceback (most recent call last):
    ...
    symbolic_friction._infra.errors.CertificateError: k-conditions of Lemma 3 violated: k3 > (k_i/k_v)·k1: 1/2 > 5/8 is false; k3 > k2: 1/2 > 3/5 is false
    """
    names = ("k_p", "k_i", "k_v", "k1", "k2", "k3", "k4")
    values = [to_rational(v, name=n) for n, v in zip(names, (k_p, k_i, k_v, k1, k2, k3, k4))]
    if values[2] == 0:
        raise InvalidNumberError("k_v must be nonzero: it divides in k3 > (k_i/k_v)·k1; got k_v = 0")
    conditions = k_conditions(*values)
    failed = [c.describe() for c in conditions if not c.holds()]
    if failed:
        raise CertificateError("k-conditions of Lemma 3 violated: " + "; ".join(failed))
    return conditions
