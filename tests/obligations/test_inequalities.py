"""The exact tools behind lemma3, prop1 and cor1 (_obligations/_inequalities.py)."""

from __future__ import annotations

import pytest
import sympy as sp

from symbolic_friction._obligations._decide import decide
from symbolic_friction._obligations._inequalities import (
    block_eigen_bounds,
    canonical,
    case_grid,
    is_lower_bound_of,
    is_nonneg,
    is_nonpos,
    is_upper_bound_of,
    label_latex,
    line_cases,
)

a, b, c = sp.symbols("a b c", positive=True)
n = sp.Symbol("n", nonnegative=True)
x, y = sp.symbols("x y", real=True)


@pytest.mark.parametrize(
    "expr",
    [
        a * b + n,  # positive monomials
        x**2 * a + y**4,  # even powers of real symbols
        (x - y) ** 2 + 4 * c**2,  # a sum of squares by its form
        x**2 - 2 * x * y + y**2,  # PSD Gram matrix
        sp.expand((x - a) ** 2 * (b + 1)),  # factor with an even power
        (a + b) / (a * c),
    ],
)
def test_is_nonneg_proves(expr):
    assert is_nonneg(expr)


@pytest.mark.parametrize("expr", [x * a, a - b, x**2 - 3 * x * y + y**2, sp.sqrt(a) - 1, sp.Abs(x), x / (a - b)])
def test_is_nonneg_does_not_prove(expr):
    assert not is_nonneg(expr)


_POLYNOMIALS = [a * b + n, x**2 * a + y**4, x**2 - 2 * x * y + y**2, sp.expand((x - a) ** 2 * (b + 1)), x / 2 + y**2 / 3,
                sp.Rational(1, 2) * (x - y) ** 2 - x * y / 3, x * a, a - b, x**2 - 3 * x * y + y**2, sp.sqrt(a) - 1,
                sp.sqrt(a) * x**2, -(a + 1) * (x**2 + 1)]


@pytest.mark.parametrize("expr", _POLYNOMIALS)
def test_a_polynomial_is_decided_as_its_fraction_would_be(monkeypatch, expr):
    """Without a denominator, is_nonneg takes the polynomial as its own numerator: the answer is the one
    ``together``'s numerator and denominator give."""
    from symbolic_friction._obligations import _inequalities

    fast = is_nonneg(expr)
    monkeypatch.setattr(_inequalities, "_has_denominator", lambda e: True)
    assert fast == is_nonneg(expr)


def test_is_nonpos():
    assert is_nonpos(-(x**2) - a)
    assert not is_nonpos(x)


def test_canonical():
    k1, k3, k_i, k_v = sp.symbols("k1 k3 k_i k_v", positive=True)
    assert canonical(k3 - k_i * k1 / k_v) == sp.expand(k3 * k_v - k_i * k1)
    assert canonical(-6 * a * (b - c)) == sp.expand(c - b)
    with pytest.raises(ValueError, match="the denominator a - b of the condition is not positive"):
        canonical(c / (a - b))


def test_line_cases_cover_the_line_exactly():
    cases = line_cases(x, [-a, a], name="x", beyond="t", labels=["-a", "a"])
    assert [cs.label for cs in cases] == ["x < -a", "x = -a", "-a < x < a", "x = a", "x > a"]
    interior = cases[2]
    # |x| < a is parametrised polynomially, with a itself substituted
    assert dict(interior.values)[a] == (interior.slacks[0] + interior.slacks[1]) / 2
    assert decide(sp.StrictLessThan(interior(x), interior(a))) and decide(sp.StrictGreaterThan(interior(x), -interior(a)))
    general = line_cases(x, [0, a + b], name="x", beyond="t")
    assert decide(sp.StrictGreaterThan(general[2](x), 0)) and decide(sp.StrictLessThan(general[2](x), a + b))
    with pytest.raises(ValueError, match="breakpoints must increase strictly; cannot show b > a"):
        line_cases(x, [a, b], name="x", beyond="t")
    grid = case_grid(line_cases(x, [0], name="x", beyond="s"), cases)
    assert len(grid) == 15 and grid[0].label == "x < 0, x < -a"


def test_block_eigen_bounds():
    M = sp.Matrix([[a, 0, c], [0, b, 0], [c, 0, a + 1]])
    checks, values = block_eigen_bounds(M)
    assert all(ok for _, ok in checks)
    num = M.xreplace({a: 2, b: 1, c: 3})
    eig = sorted(num.eigenvals())
    assert sp.simplify(values["mu_plus"].xreplace({a: 2, c: 3}) - eig[-1]) == 0
    assert sp.simplify(values["mu_minus"].xreplace({a: 2, c: 3}) - eig[0]) == 0
    coupled = sp.Matrix([[a, 1, c], [1, b, 0], [c, 0, a]])
    bad = dict(block_eigen_bounds(coupled)[0])
    assert bad["the middle row and column of M are decoupled"] is False
    asym = sp.Matrix([[a, 0, c], [0, b, 0], [2 * c, 0, a]])
    assert dict(block_eigen_bounds(asym)[0])["M is symmetric"] is False


def test_upper_and_lower_bounds():
    assert is_upper_bound_of(sp.Max(a, b), [a, b])
    assert is_upper_bound_of(a + b, [a, b])
    assert not is_upper_bound_of(sp.Max(a, b) / 2, [a])
    assert is_lower_bound_of(sp.Min(a, b), [b])
    assert not is_lower_bound_of(a, [b])


def test_label_latex():
    assert label_latex("v > 0, σ < 0, φ < -f_c") == "v > 0,\\  \\sigma  < 0,\\  \\phi  < -f_c"


def test_an_extremum_bounds_its_own_argument_without_simplify(monkeypatch):
    """``Max(m, μ) ≥ μ`` by definition: the argument equal to the value is found before the others are compared
    with it (a comparison of two radicals falls back to simplify, the costliest step of lemma3's bounds)."""
    mu = a - sp.sqrt(a**2 + b**2)
    m = b - sp.sqrt(a**2 + 4 * b**2)
    monkeypatch.setattr(sp, "simplify", lambda *args, **kw: (_ for _ in ()).throw(AssertionError("simplify called")))
    assert is_upper_bound_of(sp.Max(m, mu), [m, mu]) and is_lower_bound_of(sp.Min(m, mu), [m, mu])


def test_a_bound_must_bound_every_value_not_only_the_first():
    from symbolic_friction._obligations._decide import pos
    from symbolic_friction._obligations._inequalities import is_lower_bound_of, is_upper_bound_of

    a, b = pos("a"), pos("b")
    assert is_upper_bound_of(a, [a, a + 1]) is False  # the first is the bound itself, the second is above it
    assert is_upper_bound_of(sp.Max(a, b), [a, b + 1]) is False  # the first is an argument of the max
    assert is_upper_bound_of(sp.Max(a, b), [a, b]) is True


def test_a_bound_compares_in_its_own_direction():
    from symbolic_friction._obligations._decide import pos
    from symbolic_friction._obligations._inequalities import is_lower_bound_of, is_upper_bound_of

    a = pos("a")
    assert is_lower_bound_of(a + 1, [a]) is False and is_lower_bound_of(a, [a + 1]) is True
    assert is_upper_bound_of(a, [a + 1]) is False and is_upper_bound_of(a + 1, [a]) is True
    assert is_upper_bound_of(a - 1, [a]) is False  # a is an argument of a − 1, which is no maximum


def test_an_argument_of_the_extremum_equal_only_as_a_value_is_found():
    from symbolic_friction._obligations._decide import pos
    from symbolic_friction._obligations._inequalities import is_upper_bound_of

    a, b = pos("a"), pos("b")
    assert is_upper_bound_of(sp.Max((a + 1) ** 2, b), [a**2 + 2 * a + 1]) is True



@pytest.mark.parametrize(
    "expr",
    [
        (y + sp.Piecewise((x, x > 0))) ** 2,  # undefined (nan) for x ≤ 0, though a square by its form
        sp.Abs(sp.Symbol("z")) ** 2,  # |z|² of a complex z: sympy keeps it, and Abs is real
        sp.sign(x) ** 2,
        sp.Max(0, x) ** 2,
        sp.Min(0, x) ** 2,
    ],
)
def test_is_nonneg_certifies_rational_functions_only(expr):
    """A Piecewise, Abs, sign, Max or Min is split into cases first (``resolve_piecewise``, ``line_cases``): is_nonneg
    refuses it even where its written form is an even power of a real expression, each of the five on its own."""
    assert is_nonneg(expr) is False


def test_is_nonneg_does_not_certify_an_undefined_piecewise():
    expr = (y + sp.Piecewise((x, x > 0))) ** 2
    assert expr.subs({x: -1, y: 0}) is sp.nan and is_nonneg(expr) is False


def test_a_number_denominator_must_be_positive_not_only_nonnegative():
    zero = (1 + sp.sqrt(2)) * (sp.sqrt(2) - 1) - 1  # 0, visible only once expanded
    assert sp.expand(zero) == 0
    assert is_nonneg(x**2 / zero) is False  # x²/0 is no certificate
    assert is_nonneg(x**2 / (sp.sqrt(2) - 1)) is True  # a positive number below 1 is a positive denominator


def test_a_positive_symbol_denominator_is_accepted():
    """``(x − y)²/a`` expanded: not nonnegative by its written form (−2xy), so the denominator ``a`` (positive,
    sign 1) is checked and the numerator's Gram matrix proves it."""
    assert is_nonneg((x**2 - 2 * x * y + y**2) / a) is True
    assert is_nonneg((x**2 - 2 * x * y + y**2) / (a - b)) is False  # a − b has no sign


def test_is_nonneg_refuses_radicals_of_a_real_symbol():
    """``(x^{1/3} − 1)²`` expanded factors as a square over the radical, but sympy's x^{1/3} is the principal root:
    at x = −1 the value is −1/2 − (√3/2)i, not a nonnegative number."""
    expr = x ** sp.Rational(2, 3) - 2 * x ** sp.Rational(1, 3) + 1
    assert sp.expand_complex(expr.subs(x, -1)) == -sp.Rational(1, 2) - sp.sqrt(3) * sp.I / 2
    assert is_nonneg(expr) is False


def test_nonnegative_monomials_alone_prove_a_polynomial():
    """``(n + 1)(n² − n + 1) = n³ + 1``: not by its written form (−n), no Gram matrix (degree 3) and its factor
    ``n² − n + 1`` has no sign by its monomials; the expanded monomials alone prove it."""
    n3 = (n + 1) * (n**2 - n + 1)
    assert is_nonneg(n3) is True
