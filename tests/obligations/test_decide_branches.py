"""Every branch of the decision procedures, reached with an input for which the wrong answer would be accepted.

Each ``refuses_*``/``keeps_*`` function below asserts what a sound procedure says on an input where a weaker
one would prove something false (``x + 1 > 0`` for a real ``x``, ``xz + yz + z² ≥ 0`` whose leading
principal minors are all 0, a case split without its boundary points …).  ``test_each_negative_case`` runs
them; ``test_each_weakened_branch_is_caught`` applies, one at a time, the weakened branch each targets
(a source-level mutant of the procedure) and sees its case fail.
"""

from __future__ import annotations

import inspect
import textwrap

import pytest
import sympy as sp

from symbolic_friction._obligations import _decide, _fastpoly, _inequalities, _region
from symbolic_friction._obligations._decide import pos
from symbolic_friction._obligations._inequalities import Case

a, b = pos("a"), pos("b")
n = sp.Symbol("n", nonnegative=True)
x, y, z = sp.symbols("x y z", real=True)


# the procedures are called through their modules, so that a weakened one patched in is the one run


def _gt(lhs, rhs):
    return sp.StrictGreaterThan(lhs, rhs, evaluate=False)


def refuses_real_symbols():
    assert _decide.sign_of(x + 1) is None  # all coefficients positive, but x = -2 makes it negative
    assert _decide.sign_of(n) is None  # nonnegative is not positive: n = 0
    assert _decide.sign_of(a + 1) == 1


def refuses_an_and_with_an_undecided_conjunct():
    assert _decide.decide(sp.And(_gt(a, 0), _gt(a, b), evaluate=False)) is None  # a > b is false for a = 1, b = 2
    assert _decide.decide(sp.And(_gt(a, 0), _gt(b, 0), evaluate=False)) is True


def refuses_an_or_of_undecided_and_false():
    assert _decide.decide(sp.Or(_gt(-a, 0), _gt(a, b), evaluate=False)) is None  # true for a = 2, b = 1
    assert _decide.decide(sp.Or(_gt(-a, 0), _gt(b, 0), evaluate=False)) is True


def refuses_the_negation_of_an_undecided_relation():
    assert _decide.decide(sp.Not(_gt(a, b), evaluate=False)) is None


def refuses_a_gram_matrix_with_a_negative_non_leading_minor():
    # Gram matrix [[0, 0, ½], [0, 0, ½], [½, ½, 1]]: leading minors 0, 0, 0; the minor {1, 3} is -1/4
    assert not _inequalities.is_nonneg(x * z + y * z + z**2)  # x = -2, y = 0, z = 1 gives -1
    assert _inequalities.is_nonneg(x**2 - 2 * x * y + y**2)


def refuses_odd_powers_of_sign_unknown_symbols():
    assert not _inequalities.is_nonneg(a * x**3 + a)  # x = -2
    assert not _inequalities.is_nonneg(x * a)
    assert _inequalities.is_nonneg(n**3 * a + a)  # an odd power of a nonnegative symbol is fine


def refuses_an_undecided_denominator():
    assert not _inequalities.is_nonneg(1 / (a - b))  # a = 1, b = 2
    assert not _inequalities.is_nonneg(a / x)
    assert _decide.sign_of(1 / (a - b)) is None
    assert _inequalities.is_nonneg(1 / (a + b)) and _decide.sign_of(-1 / (a + b)) == -1


def refuses_a_factorisation_with_a_negative_constant():
    assert not _inequalities.is_nonneg(sp.expand(-(a + 1) * (x**2 + 1)))
    assert _inequalities.is_nonneg(sp.expand((a + 1) * (x - b) ** 2))


def keeps_every_boundary_class():
    c = pos("c")
    regions = [region for *_, region in _decide.phi_classes(c, "_t")]
    for point in (-c - 1, -c, 0, c, c + 1):
        assert sum(1 for r in regions if r.contains(point) == sp.true) == 1, point
    assert sorted(sign for _, sign, _ in _decide.sign_classes("q")) == [-1, 0, 1]
    for _, sign, value in _decide.sign_classes("q"):
        assert _decide.sign_of(value) == sign
    cases = _inequalities.line_cases(x, [-c, c], name="x", beyond="t", labels=["-c", "c"])
    values = [cs.value(x) for cs in cases]
    assert -c in values and c in values and len(cases) == 5


def refuses_a_piece_whose_membership_in_R_is_undecided():
    v, phi, f_c = sp.symbols("v phi f_c", real=True)
    region = v * (phi - f_c)
    decided = Case("v > 0, φ > f_c", ((v, a), (phi, f_c + b)), (a, b))
    boundary = Case("v = 0", ((v, sp.Integer(0)), (phi, b)), (b,))
    undecided = Case("v > 0, φ = b", ((v, a), (phi, b)), (a, b))
    failures: list[str] = []
    inside = [cs.label for cs in _region.pieces_of([decided, boundary, undecided], region, inside=True, failures=failures)]
    assert inside == ["v > 0, φ > f_c", "v = 0"]  # R = {region ≥ 0} holds its boundary
    assert failures == ["cannot decide whether the piece v > 0, φ = b lies in R"]
    failures = []
    outside = list(_region.pieces_of([undecided], region, inside=False, failures=failures))
    assert outside == [] and failures == ["cannot decide whether the piece v > 0, φ = b lies in R̂"]
    failures = []
    branching = sp.Piecewise((v, phi > 1), (-v, True))
    assert list(_region.pieces_of([undecided], branching, inside=True, failures=failures)) == []
    assert len(failures) == 1 and "cannot decide the branch condition" in failures[0]


def finds_the_minimum_of_a_quadratic_wherever_its_vertex_lies():
    w = sp.Symbol("w", real=True)
    box = sp.Interval(-1, 1)
    for c, at in ((-1 - a, -1), ((a - b) / (a + b), None), (1 + a, 1)):  # vertex left of, inside, right of [-1, 1]
        got = _decide.minimum_on((w - c) ** 2 + 3, w, box)
        want = 3 if at is None else (at - c) ** 2 + 3
        assert _decide.is_zero(got - want), (c, got)
    # a concave quadratic is not convex: its vertex is its maximum, the minimum is at an end
    assert _decide.is_zero(_decide.minimum_on(-((w - a / (a + 1)) ** 2), w, box) + (1 + a / (a + 1)) ** 2)


def refuses_a_fraction_with_coefficients_of_both_signs():
    assert _decide.sign_of((a - b) / (a + b)) is None  # negative for a = 1, b = 2
    assert _decide.sign_of(1 / (a - b)) is None
    assert _decide.sign_of((a + b) / (a * b + 1)) == 1 and _decide.sign_of(-a / (b + 1)) == -1


def refuses_a_nonzero_rational_function():
    assert not _decide.is_zero(a / (a + b) - 1)  # b/(a + b) ≠ 0
    assert _decide.is_zero(a / (a + b) + b / (a + b) - 1)


def adds_fractions_over_a_common_denominator():
    """The reduced fraction of a rational function: sums, products, negative powers, rational constants, cancelling."""
    assert not _decide.is_zero(1 / a - 1 / b)  # numerators added without their denominators give 0
    assert _decide.is_zero(1 / a + 1 / b - (a + b) / (a * b))
    assert _decide.is_zero((a**2 - b**2) / (a - b) / (a + b) - 1)  # a product's denominators count
    assert _decide.sign_of(1 / (a + b) - 1 / (a + 2 * b)) == 1  # b/((a + b)(a + 2b)), not (a + b) − (a + 2b)
    assert _decide.is_zero((a + sp.Rational(1, 2)) ** 2 - a**2 - a - sp.Rational(1, 4))  # p/q is not q/p
    assert _decide.sign_of((a**2 - b**2) / (a - b)) == 1  # a + b once the common factor a − b is cancelled


CASES = [
    refuses_real_symbols,
    refuses_an_and_with_an_undecided_conjunct,
    refuses_an_or_of_undecided_and_false,
    refuses_the_negation_of_an_undecided_relation,
    refuses_a_gram_matrix_with_a_negative_non_leading_minor,
    refuses_odd_powers_of_sign_unknown_symbols,
    refuses_an_undecided_denominator,
    refuses_a_factorisation_with_a_negative_constant,
    keeps_every_boundary_class,
    refuses_a_piece_whose_membership_in_R_is_undecided,
    finds_the_minimum_of_a_quadratic_wherever_its_vertex_lies,
    refuses_a_nonzero_rational_function,
    adds_fractions_over_a_common_denominator,
    refuses_a_fraction_with_coefficients_of_both_signs,
]


@pytest.mark.parametrize("case", CASES, ids=lambda f: f.__name__)
def test_each_negative_case(case):
    case()


def _mutant(module, name, replacements):
    source = textwrap.dedent(inspect.getsource(getattr(module, name)))
    for old, new in replacements:
        assert old in source, old
        source = source.replace(old, new, 1)
    namespace = dict(vars(module))
    exec(compile(source, f"<mutant of {name}>", "exec"), namespace)
    return namespace[name]


MUTANTS = [
    (_decide, "_convex_quadratic_minimum", [("-beta / (2 * alpha)", "beta / (2 * alpha)")],
     finds_the_minimum_of_a_quadratic_wherever_its_vertex_lies),
    (_decide, "_convex_quadratic_minimum", [("sign_of(alpha) != 1", "sign_of(alpha) == 0")],
     finds_the_minimum_of_a_quadratic_wherever_its_vertex_lies),
    (_decide, "_convex_quadratic_minimum", [("return f.xreplace({var: s.start})", "return f.xreplace({var: s.end})")],
     finds_the_minimum_of_a_quadratic_wherever_its_vertex_lies),
    (_decide, "_convex_quadratic_minimum", [("sp.LessThan(vertex, s.start)", "sp.GreaterThan(vertex, s.start)")],
     finds_the_minimum_of_a_quadratic_wherever_its_vertex_lies),
    (_decide, "sign_of", [("(_coefficient_sign(list(p.coeffs())) for p in (element.numer, element.denom))",
                          "(_coefficient_sign(list(map(abs, p.coeffs()))) for p in (element.numer, element.denom))")],
     refuses_a_fraction_with_coefficients_of_both_signs),
    (_decide, "is_zero", [("return _field_element(expr).numer.is_zero()", "return True")], refuses_a_nonzero_rational_function),
    (_fastpoly, "rational_pair", [("n * (ad / g) + an * (d / g)", "n + an")], adds_fractions_over_a_common_denominator),
    (_fastpoly, "rational_pair", [("n, d = n * an, d * ad", "n, d = n * an, d")], adds_fractions_over_a_common_denominator),
    (_fastpoly, "rational_pair", [("(bd ** -k, bn ** -k)", "(bn ** -k, bd ** -k)")], adds_fractions_over_a_common_denominator),
    (_fastpoly, "rational_pair", [("(ctx.constant(int(e.p)), ctx.constant(int(e.q)))",
                                  "(ctx.constant(int(e.q)), ctx.constant(int(e.p)))")], adds_fractions_over_a_common_denominator),
    (_fastpoly, "rational_pair", [("return numer / g, denom / g", "return numer, denom")],
     adds_fractions_over_a_common_denominator),
    (_decide, "sign_of", [("s.is_positive is not True", "s.is_nonnegative is not True")], refuses_real_symbols),
    (_decide, "sign_of", [("s.is_positive is not True", "s.is_real is not True")], refuses_real_symbols),
    (_decide, "decide", [("(None if None in vals else True)", "True")], refuses_an_and_with_an_undecided_conjunct),
    (_decide, "decide", [("(None if None in vals else False)", "False")], refuses_an_or_of_undecided_and_false),
    (_decide, "decide", [("None if val is None else not val", "not val")], refuses_the_negation_of_an_undecided_relation),
    (_inequalities, "_gram_psd", [("itertools.combinations(range(n), size)", "[tuple(range(size))]")],
     refuses_a_gram_matrix_with_a_negative_non_leading_minor),
    (_inequalities, "_monomials_nonneg", [("k % 2 == 1 and sym.is_nonnegative is not True", "False")],
     refuses_odd_powers_of_sign_unknown_symbols),
    (_inequalities, "is_nonneg", [("if not (den.is_number and den > 0):", "if False:")], refuses_an_undecided_denominator),
    (_decide, "sign_of", [("sn is None or sd is None or sd == 0", "sn is None"), ("return sn * sd", "return sn")],
     refuses_an_undecided_denominator),
    (_inequalities, "_factor_nonneg", [("sign = 1 if const > 0 else -1", "sign = 1")],
     refuses_a_factorisation_with_a_negative_constant),
    (_decide, "phi_classes", [('("φ = f_c", "\\\\phi = f_c", c, sp.FiniteSet(c)),', "")], keeps_every_boundary_class),
    (_decide, "sign_classes", [('("= 0", 0, sp.Integer(0)), ', "")], keeps_every_boundary_class),
    (_inequalities, "line_cases", [('out.append(Case(f"{name} = {texts[i]}", ((var, b),), ()))', "pass")],
     keeps_every_boundary_class),
    (_region, "pieces_of", [('failures.append(f"cannot decide whether the piece {case.label} lies in {name}")', "pass")],
     refuses_a_piece_whose_membership_in_R_is_undecided),
    (_region, "pieces_of", [('failures.append(f"{case.label}: {exc}")', "pass")],
     refuses_a_piece_whose_membership_in_R_is_undecided),
    (_region, "in_R", [("sp.GreaterThan(", "sp.StrictGreaterThan(")], refuses_a_piece_whose_membership_in_R_is_undecided),
]


@pytest.mark.parametrize("module, name, replacements, case", MUTANTS,
                         ids=[f"{m[1]}-{i}" for i, m in enumerate(MUTANTS)])
def test_each_weakened_branch_is_caught(monkeypatch, module, name, replacements, case):
    mutant = _mutant(module, name, replacements)
    monkeypatch.setattr(module, name, mutant)
    for other in (_decide, _inequalities, _region):  # names imported into the other modules
        if other is not module and getattr(other, name, None) is not None:
            monkeypatch.setattr(other, name, mutant)
    with pytest.raises((AssertionError, TypeError)):
        case()


def test_check_runs_the_same_cases_and_a_broken_sympy_fails_them(monkeypatch):
    """``check``'s self-check decides these inputs too: a sympy whose polynomials report only positive
    coefficients (a broken or patched install) makes the procedures prove false statements, and ``check`` fails."""
    from symbolic_friction._obligations._decide_cases import decision_cases

    cases = decision_cases()
    assert len(cases) == 24 and all(c.ok for c in cases), [(c.name, c.got) for c in cases if not c.ok]
    real = sp.Poly.coeffs
    monkeypatch.setattr(sp.Poly, "coeffs", lambda self, order=None: [abs(c) for c in real(self, order)])
    real_terms = sp.Poly.terms
    monkeypatch.setattr(sp.Poly, "terms", lambda self, order=None: [(m, abs(c)) for m, c in real_terms(self, order)])
    wrong = [c.name for c in decision_cases() if not c.ok]
    assert "is_nonneg(−(a + 1)(x² + 1))" in wrong


def _forward(name):
    def op(self, other):
        result = getattr(self.p, name)(other.p if isinstance(other, _BrokenPolynomial) else other)
        return result if isinstance(result, bool) else _BrokenPolynomial(result)
    return op


class _BrokenPolynomial:
    """A python-flint polynomial whose coefficients all read as positive (a broken or patched install)."""

    def __init__(self, p):
        self.p = p

    __add__, __mul__, __truediv__, __pow__, __eq__, gcd = map(_forward, ("__add__", "__mul__", "__truediv__", "__pow__",
                                                                         "__eq__", "gcd"))

    def is_zero(self):
        return self.p.is_zero()

    def coeffs(self):
        return [abs(c) for c in self.p.coeffs()]


def test_a_broken_python_flint_fails_the_cases_check_runs(monkeypatch):
    """The rational functions of :func:`_decide.sign_of` are python-flint polynomials: a python-flint whose
    coefficients all read as positive makes ``sign_of(1/(a − b))`` a proof of a false statement, and ``check`` fails."""
    import types

    import flint

    from symbolic_friction._obligations._decide_cases import decision_cases

    class Context:
        def __init__(self, ctx):
            self.ctx = ctx

        def constant(self, c):
            return _BrokenPolynomial(self.ctx.constant(c))

        def gens(self):
            return tuple(_BrokenPolynomial(g) for g in self.ctx.gens())

    fake = types.ModuleType("flint")
    fake.__dict__.update(vars(flint))
    fake.fmpz_mpoly_ctx = types.SimpleNamespace(get=lambda *a: Context(flint.fmpz_mpoly_ctx.get(*a)))
    monkeypatch.setitem(__import__("sys").modules, "flint", fake)
    wrong = [c.name for c in decision_cases() if not c.ok]
    assert "sign_of(1/(a − b))" in wrong
