"""The sup-flow verifier's fast paths give the model's balls and the exact decisions, bit for bit.

``_certify/sup_flow_forms.py`` evaluates the model's exit forms without their products of zeros; the refutation
at a point asks arb before it builds Fractions (``sup_flow_enclosure._upper_ends_clearly_copositive``); a float
becomes an arb point without a Fraction.  None of them may change a ball or a verdict.
"""

from __future__ import annotations

import random
from fractions import Fraction

import pytest

flint = pytest.importorskip("flint")

from symbolic_friction._certify import sup_flow_enclosure as E  # noqa: E402
from symbolic_friction._certify import sup_flow_forms as F  # noqa: E402
from symbolic_friction._certify.copositive import decide_copositive  # noqa: E402
from symbolic_friction._model import sup_flow as model  # noqa: E402


def _same(x, y) -> bool:
    """The same ball, to the last bit of its midpoint and radius."""
    return x.mid().man_exp() == y.mid().man_exp() and x.rad().man_exp() == y.rad().man_exp()


def _ball(rng: random.Random):
    mid = Fraction(rng.randint(-10**12, 10**12), rng.randint(1, 10**9))
    return flint.arb(E._arb(mid), E._arb(Fraction(rng.randint(0, 1000), 10**rng.randint(3, 30))))


@pytest.fixture
def precision():
    old = flint.ctx.prec
    flint.ctx.prec = E.PRECISION
    yield
    flint.ctx.prec = old


def test_exit_forms_are_the_models_balls_bit_for_bit(precision):
    rng = random.Random(11)
    for _ in range(200):
        k = tuple(tuple(_ball(rng) for _ in range(3)) for _ in range(3))
        gram = tuple(tuple(_ball(rng) for _ in range(3)) for _ in range(3))
        # a gram of products (as the verifier's e^{At}ᵀe^{At}): midpoints of the full precision
        gram = E._rows(flint.arb_mat([list(r) for r in gram]).transpose() * flint.arb_mat([list(r) for r in gram]))
        for s in (1, -1):
            fast, model_forms = F.exit_forms(k, gram, s), model.exit_forms(k, gram, E._arb(Fraction(s)))
            assert len(fast) == len(model_forms) == 2
            for a, b in zip(fast, model_forms):
                assert all(_same(x, y) for ra, rb in zip(a, b) for x, y in zip(ra, rb))


def test_a_non_finite_gram_is_the_models_function(precision):
    k = tuple(tuple(E._arb(Fraction(i + j)) for j in range(3)) for i in range(3))
    gram = tuple(tuple(flint.arb("nan") if (i, j) == (2, 2) else E._arb(Fraction(1, 3)) for j in range(3)) for i in range(3))
    for s in (1, -1):
        fast, model_forms = F.exit_forms(k, gram, s), model.exit_forms(k, gram, E._arb(Fraction(s)))
        assert [[str(x) for x in row] for form in fast for row in form] == \
               [[str(x) for x in row] for form in model_forms for row in form]


def test_a_replaced_model_function_is_read_again(monkeypatch, precision):
    k = tuple(tuple(E._arb(Fraction(i + 2 * j + 1)) for j in range(3)) for i in range(3))
    gram = tuple(tuple(E._arb(Fraction(1, 1 + i + j)) for j in range(3)) for i in range(3))
    F.exit_forms(k, gram, 1)  # the real model's plan is kept
    real = model.exit_forms
    monkeypatch.setattr(model, "exit_forms", lambda k, gram, s: tuple(reversed(real(k, gram, s))))  # planes swapped
    fast, model_forms = F.exit_forms(k, gram, 1), model.exit_forms(k, gram, E._arb(Fraction(1)))
    assert all(_same(x, y) for a, b in zip(fast, model_forms) for ra, rb in zip(a, b) for x, y in zip(ra, rb))
    monkeypatch.setattr(model, "exit_forms", lambda k, gram, s: real(k, tuple(tuple(2 * x for x in r) for r in gram), s))
    assert F._exit_plan(1) is None  # not of the shape K_ij − d·G_mn·d': the model's function on every call
    fast, model_forms = F.exit_forms(k, gram, 1), model.exit_forms(k, gram, E._arb(Fraction(1)))
    assert all(_same(x, y) for a, b in zip(fast, model_forms) for ra, rb in zip(a, b) for x, y in zip(ra, rb))


def _exact_upper_ends(form) -> bool | None:
    off = max(E._upper(form[0][1]), E._upper(form[1][0]))  # as _exit_holds builds it with end=_upper
    return decide_copositive(((E._upper(form[0][0]), off), (off, E._upper(form[1][1])))).holds


def test_the_upper_shortcut_says_copositive_only_where_the_exact_decision_does(precision):
    rng = random.Random(5)
    agree = 0
    for _ in range(600):
        a, b, c, d = (Fraction(rng.randint(-40, 400), rng.randint(1, 50)) for _ in range(4))
        radius = Fraction(rng.randint(0, 5), 1000)
        ball = lambda q: flint.arb(E._arb(q), E._arb(radius))  # noqa: E731
        form = ((ball(a), ball(b)), (ball(d if rng.random() < 0.3 else b), ball(c)))
        fast, exact = E._upper_ends_clearly_copositive(form), _exact_upper_ends(form) is True
        assert not fast or exact, (a, b, c, d, radius)
        agree += fast == exact
    assert agree >= 590


def test_the_upper_shortcut_leaves_huge_ends_and_3x3_forms_to_the_exact_path(precision):
    huge = flint.arb(2) ** E.EXPONENT_LIMIT
    assert not E._upper_ends_clearly_copositive(((huge, flint.arb(0)), (flint.arb(0), flint.arb(1))))
    assert not E._upper_ends_clearly_copositive(((flint.arb(1), -huge), (-huge, flint.arb(1))))
    assert E._upper_ends_clearly_copositive(((huge / 2, flint.arb(0)), (flint.arb(0), flint.arb(1))))
    eye = tuple(tuple(flint.arb(int(i == j)) for j in range(3)) for i in range(3))
    assert not E._upper_ends_clearly_copositive(eye)


@pytest.mark.parametrize("x", [0.0, -0.0, 1.0, -2.5, 1e-300, 5e-324, 1.7976931348623157e308, 0.1, -1 / 3])
def test_a_float_is_the_same_arb_point_as_its_fraction(x, precision):
    assert _same(E._arb_of_float(x), E._arb(Fraction(x)))


@pytest.mark.parametrize("x", [float("nan"), float("inf")])
def test_a_float_that_is_not_a_number_is_refused_as_before(x, precision):
    with pytest.raises((ValueError, OverflowError)):
        E._arb_of_float(x)
