"""The three kinds one model definition is evaluated in (exact, float, sympy)."""

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from symbolic_friction._model.kinds import EXACT, FLOAT, SYMPY, kind_of


def test_kind_of_picks_the_most_general_kind():
    assert kind_of(Fraction(1, 2), 3) is EXACT
    assert kind_of(Fraction(1, 2), 0.5) is FLOAT
    assert kind_of(np.zeros(3), Fraction(1)) is FLOAT
    assert kind_of(sp.Symbol("x"), 0.5) is SYMPY
    assert kind_of(sp.Rational(1, 2)) is SYMPY  # sympy numbers stay sympy


def test_kind_of_rejects_other_types_by_name():
    with pytest.raises(TypeError, match="got str"):
        kind_of(Fraction(1), "1/2")


@pytest.mark.parametrize("y, want", [(Fraction(-3), -1), (Fraction(0), 0), (Fraction(1, 2), Fraction(1, 2)), (Fraction(5), 1)])
def test_the_three_kinds_agree_on_clip_sign_abs_where(y, want):
    x = sp.Symbol("x", real=True)
    sym_clip = SYMPY.clip(x, -1, 1).subs(x, sp.Rational(y))
    assert EXACT.clip(y, -1, 1) == want == Fraction(str(sym_clip)) == Fraction(float(FLOAT.clip(float(y), -1.0, 1.0)))
    assert EXACT.sign(y) == int(SYMPY.sign(sp.Rational(y))) == int(FLOAT.sign(float(y)))
    assert EXACT.abs(y) == Fraction(str(SYMPY.abs(sp.Rational(y)))) == Fraction(float(FLOAT.abs(float(y))))
    assert EXACT.where(y > 0, 1, 2) == int(FLOAT.where(float(y) > 0, 1, 2)) == SYMPY.where(x > 0, 1, 2).subs(x, sp.Rational(y))


def test_exact_kind_keeps_fractions_exact():
    assert isinstance(EXACT.clip(Fraction(1, 3), Fraction(-1), Fraction(1)), Fraction)
    assert EXACT.scalar(Fraction(1, 3)) == Fraction(1, 3)
    assert FLOAT.scalar(Fraction(1, 4)) == 0.25
