"""Negative cases for the hunting proof's decisions, on inputs built so that the wrong answer would be accepted.

The shipped false certificates (:mod:`.self_check`) break the proof's
premises with real boxes; the steps below decide things no rational box
reaches on its own, so each is fed an input where a weaker decision would
say yes:

* the Krawczyk inclusion (:func:`.hunting_proof._inside`): a ball that
  touches an end exactly, or crosses it, is not in the open box (both ends);
* the first-zero search (:func:`.hunting_proof._positive_on`): a value that
  touches 0 (a ball containing 0 is not positive, and giving up is *not
  shown*), a value negative on the first or on the last of its pieces only
  (every piece is decided), and a positive value (shown);
* the stick test (:func:`.hunting_proof._sticks`): ``φ = ±f_s`` exactly is not inside;
* the shape: ``σ_lo = 0`` is refused (``σ > 0``);
* outward rounding: every ball :meth:`.hunting_proof._Arb.ball` draws holds
  both ends of its interval, the floats of the reported multiplier bound the
  ball, and the ends :mod:`.hunting_cycle` writes bound the values they round.

:func:`rigour_cases` returns one :class:`RigourCase` per input; ``check``
fails unless each is decided as expected.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

__all__ = ["RigourCase", "rigour_cases"]


@dataclass(frozen=True)
class RigourCase:
    """One decision on one built input: what it must say and what it said."""

    name: str
    expected: str
    got: str

    @property
    def ok(self) -> bool:
        return self.expected == self.got


def _say(flag: bool, yes: str, no: str) -> str:
    return yes if flag else no


def rigour_cases() -> tuple[RigourCase, ...]:
    """Decide every built input (module docstring) at the proof's precision."""
    from flint import ctx

    from .hunting_proof import PRECISION

    saved = ctx.prec
    ctx.prec = PRECISION
    try:
        return _cases()
    finally:
        ctx.prec = saved


def _cases() -> tuple[RigourCase, ...]:
    from flint import arb

    from .._model.parameters import Parameters
    from . import hunting_cycle as cyc
    from . import hunting_proof as hp

    params = Parameters(k_p=3, k_i=4, k_v="32/5", f_c=1, f_s="6/5")
    M = hp._Arb(params)
    q = M.q
    out: list[RigourCase] = []
    lo, hi = q(Fraction(1, 3)), q(Fraction(2, 3))
    exact_lo, exact_hi = arb(lo.mid()), arb(hi.mid())
    inside = [
        ("krawczyk: K touching the lower end", exact_lo, "refused"),
        ("krawczyk: K touching the upper end", exact_hi, "refused"),
        ("krawczyk: K across the lower end", q(Fraction(1, 3)) + arb(0, q(Fraction(1, 1000))), "refused"),
        ("krawczyk: K across the upper end", q(Fraction(2, 3)) + arb(0, q(Fraction(1, 1000))), "refused"),
        ("krawczyk: K in the open box", q(Fraction(1, 2)) + arb(0, q(Fraction(1, 10))), "accepted"),
    ]
    for name, k, expected in inside:
        out.append(RigourCase(name, expected, _say(hp._inside(k, exact_lo, exact_hi), "accepted", "refused")))

    a, b = Fraction(0), Fraction(1)
    floor = Fraction(1, 10**15)

    def square(c: Fraction, minus: Fraction):
        def value(x: Fraction, y: Fraction):
            t = M.ball(x, y) - q(c)
            return t * t - q(minus)
        return value

    positive = [
        ("first zero: a value touching 0 (every ball near it holds 0)", square(Fraction(1, 3), Fraction(0)), "not shown"),
        ("first zero: negative on the last piece only", square(Fraction(127, 128), Fraction(1, 10**6)), "not shown"),
        ("first zero: negative on the first piece only", square(Fraction(1, 128), Fraction(1, 10**6)), "not shown"),
        ("first zero: a ball holding 0 on every piece (gives up)", lambda x, y: arb(0, 1), "not shown"),
        ("first zero: a positive value", lambda x, y: M.ball(x, y) + 1, "shown"),
    ]
    for name, value, expected in positive:
        shown, _ = hp._positive_on(value, a, b, floor=floor)
        out.append(RigourCase(name, expected, _say(shown, "shown", "not shown")))

    f_s = arb(M.f_s.mid())  # exact, so that φ = f_s is equality, not two overlapping balls
    for name, phi, expected in [("stick: φ = f_s exactly", f_s, "slips"), ("stick: φ = -f_s exactly", -f_s, "slips"),
                                ("stick: φ across f_s", f_s + arb(0, q(Fraction(1, 10**20))), "slips"),
                                ("stick: |φ| < f_s", q(Fraction(1, 2)), "sticks")]:
        out.append(RigourCase(name, expected, _say(hp._sticks(phi, f_s), "sticks", "slips")))

    box = hp.Box(sigma=(Fraction(0), Fraction(1, 10)), tau=(Fraction(2), Fraction(3)), monotone_from=Fraction(1))
    out.append(RigourCase("shape: σ_lo = 0", "refused", _say(hp._shape_ok(params, box), "accepted", "refused")))
    box = hp.Box(sigma=(Fraction(1, 10**30), Fraction(1, 10)), tau=(Fraction(2), Fraction(3)), monotone_from=Fraction(1))
    out.append(RigourCase("shape: σ_lo > 0", "accepted", _say(hp._shape_ok(params, box), "accepted", "refused")))

    pairs = [(Fraction(1, 3), Fraction(2, 3)), (Fraction(1, 3), Fraction(1, 3) + Fraction(1, 10**40)),
             (Fraction(1, 7 * 10**30), Fraction(1, 7 * 10**30) + Fraction(1, 3 * 10**60)), (Fraction(-5, 3), Fraction(-4, 3))]
    held = all(_holds(M.ball(x, y), x) and _holds(M.ball(x, y), y) for x, y in pairs)
    out.append(RigourCase("outward: a box's ball holds both ends", "holds", _say(held, "holds", "lost")))
    # exact points just past the midpoint between two doubles: rounding to nearest would step inwards
    tie = Fraction(1) + Fraction(1, 2**53)
    balls = [q(Fraction(1, 3)) + arb(0, q(Fraction(1, 10**30))), q(Fraction(-10**20, 7)),
             q(tie + Fraction(1, 2**60)), q(tie - Fraction(1, 2**60)), q(-tie - Fraction(1, 2**60))]
    floats = all(Fraction(hp._lower(x)) <= hp._exact_mid(x.lower()) and hp._exact_mid(x.upper()) <= Fraction(hp._upper(x))
                 for x in balls)
    out.append(RigourCase("outward: the multiplier's floats bound its ball", "holds", _say(floats, "holds", "lost")))
    values = [Fraction(1, 3), Fraction(-2, 3), Fraction(10**20, 7), Fraction(1, 7 * 10**20), Fraction(123456789012345, 10**14)]
    rounded = all(cyc._round(x, up=False) <= x <= cyc._round(x, up=True) for x in values)
    out.append(RigourCase("outward: a written interval bounds the value it rounds", "holds", _say(rounded, "holds", "lost")))
    return tuple(out)


def _holds(ball, x: Fraction) -> bool:
    """Whether ``ball`` holds the rational ``x`` exactly."""
    from flint import fmpq

    return bool(ball.contains(fmpq(x.numerator, x.denominator)))
