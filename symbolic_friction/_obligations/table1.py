"""Table I: the gains of the simulations and the roots of
``s³ + k_v s² + k_p s + k_i`` printed next to them.

=====  =====  =====  =====  ==========================
Case   k_v    k_p    k_i    Roots (as printed)
=====  =====  =====  =====  ==========================
(a)    6.4    3      4      −6.01, −0.19 ± i0.79
(b)    1.5    0.66   0.08   −0.8, −0.5, −0.2
=====  =====  =====  =====  ==========================

The polynomial is ``det(sI − A)`` with the exact gains of
:meth:`~symbolic_friction.Parameters.table_i`.  Its roots are isolated in
rational intervals/rectangles (sympy's exact real and complex root
isolation), refined until each lies inside the set of numbers that round to a
printed value, so the match is decided exactly, whatever the rounding of
ties.  Case (b)'s polynomial factors over ℚ as
``(s + 4/5)(s + 1/2)(s + 1/5)``: its printed roots are exact.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.parameters import Parameters
from . import _fastforms as ff
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import latex

__all__ = ["OBLIGATIONS", "TableI", "Table1Subject", "Table1Case", "PRINTED_ROOTS", "parse_printed_root"]

PRINTED_ROOTS: dict[str, tuple[str, ...]] = {
    "a": ("-6.01", "-0.19+0.79i", "-0.19-0.79i"),
    "b": ("-0.8", "-0.5", "-0.2"),
}
"""Table I's root column, one string per root (``-0.19 ± i0.79`` is two roots)."""


def parse_printed_root(text: str) -> tuple[Fraction, int, Fraction, int]:
    """``"-0.19+0.79i"`` → ``(re, decimals of re, im, decimals of im)``, exactly.

    Raises
    ------
    ValueError
        If ``text`` is not ``"<decimal>"`` or ``"<decimal>±<decimal>i"``.

    Examples
    --------
    >>> parse_printed_root("-0.19-0.79i")
    (Fraction(-19, 100), 2, Fraction(-79, 100), 2)
    """
    body = text.replace(" ", "")
    imag_text = "0"
    if body.endswith("i"):
        cut = max(body.rfind("+", 1), body.rfind("-", 1))
        if cut <= 0:
            raise ValueError(f"cannot read the printed root {text!r}")
        body, imag_text = body[:cut], body[cut:-1]
    try:
        re_dec, im_dec = Decimal(body), Decimal(imag_text)
    except ArithmeticError:
        raise ValueError(f"cannot read the printed root {text!r}") from None
    places = [max(0, -d.as_tuple().exponent) for d in (re_dec, im_dec)]  # type: ignore[operator]
    return Fraction(re_dec), places[0], Fraction(im_dec), places[1]


@dataclass(frozen=True)
class Table1Case:
    """One row of Table I.

    Attributes
    ----------
    label : str
        ``"a"`` or ``"b"``.
    k_p, k_i, k_v : sympy Rational
        The exact gains.
    polynomial : sympy Poly
        ``det(sI − A)`` with these gains.
    printed : tuple of str
        The printed roots.
    """

    label: str
    k_p: sp.Rational
    k_i: sp.Rational
    k_v: sp.Rational
    polynomial: sp.Poly
    printed: tuple[str, ...]


@dataclass(frozen=True)
class Table1Subject:
    """The rows of Table I."""

    s: sp.Symbol
    cases: tuple[Table1Case, ...]


def _rat(q: Fraction) -> sp.Rational:
    return sp.Rational(q.numerator, q.denominator)


def _status(box: tuple[sp.Rational, sp.Rational, sp.Rational, sp.Rational], target: tuple[Fraction, int, Fraction, int]) -> str:
    """``"in"`` if the isolating box lies in the rounding box of the printed value, ``"out"`` if disjoint."""
    re_lo, re_hi, im_lo, im_hi = box
    re_p, re_d, im_p, im_d = target
    h_re, h_im = sp.Rational(1, 2 * 10**re_d), sp.Rational(1, 2 * 10**im_d)
    lo_re, hi_re, lo_im, hi_im = _rat(re_p) - h_re, _rat(re_p) + h_re, _rat(im_p) - h_im, _rat(im_p) + h_im
    if lo_re <= re_lo and re_hi <= hi_re and lo_im <= im_lo and im_hi <= hi_im:
        return "in"
    if re_hi < lo_re or re_lo > hi_re or im_hi < lo_im or im_lo > hi_im:
        return "out"
    return "undecided"


def _isolating_boxes(poly: sp.Poly, eps: sp.Rational) -> list[tuple[sp.Rational, ...]]:
    real, complex_ = poly.intervals(all=True, eps=eps)
    boxes = []
    for (lo, hi), mult in real:
        boxes += [(sp.Rational(lo), sp.Rational(hi), sp.Integer(0), sp.Integer(0))] * mult
    for (lo, hi), mult in complex_:
        lo, hi = sp.sympify(lo), sp.sympify(hi)
        boxes += [(sp.re(lo), sp.re(hi), sp.im(lo), sp.im(hi))] * mult
    return boxes


class TableI(Obligation):
    """``table1``: the printed roots of Table I, cases (a) and (b), to the printed digits."""

    id = "table1"
    paper = "Table I (Section III) and the characteristic polynomial s³ + k_v s² + k_p s + k_i"
    statement = (
        "The roots of det(sI − A) = s³ + k_v s² + k_p s + k_i for Table I's gains round to the printed values: "
        "(a) −6.01, −0.19 ± i0.79; (b) −0.8, −0.5, −0.2 (exactly: the polynomial factors over ℚ)"
    )
    method = (
        "exact polynomial from A; sympy's exact real/complex root isolation refined until each rational box lies "
        "inside the rounding box of a printed value; factorisation over ℚ; nroots at 40 digits for the report"
    )

    def derive(self) -> Table1Subject:
        g = _symbolic.gains()
        s = sp.Symbol("s")
        cases = []
        for label in ("a", "b"):
            p = Parameters.table_i(label)
            k_p, k_i, k_v = (_rat(q) for q in (p.k_p, p.k_i, p.k_v))
            A = _symbolic.A(g).xreplace({g.k_p: k_p, g.k_i: k_i, g.k_v: k_v})
            cases.append(Table1Case(label, k_p, k_i, k_v, A.charpoly(s).as_expr().as_poly(s), PRINTED_ROOTS[label]))
        return Table1Subject(s, tuple(cases))

    def verify(self, subject: Table1Subject) -> Outcome:
        failures: list[str] = []
        details: list[tuple[str, str]] = []
        s = subject.s
        for case in subject.cases:
            poly = sp.Poly(case.polynomial, s)
            want = sp.Poly(s**3 + case.k_v * s**2 + case.k_p * s + case.k_i, s)
            if poly != want:
                failures.append(f"case ({case.label}): the polynomial {poly.as_expr()} is not s³ + k_v s² + k_p s + k_i")
                continue
            try:
                targets = [parse_printed_root(t) for t in case.printed]
            except ValueError as exc:
                failures.append(f"case ({case.label}): {exc}")
                continue
            if len(targets) != poly.degree():
                failures.append(f"case ({case.label}): {len(targets)} printed roots for a degree-{poly.degree()} polynomial")
                continue
            finest = max(max(t[1], t[3]) for t in targets)
            matched = None
            for extra in (3, 8, 20):
                boxes = _isolating_boxes(poly, sp.Rational(1, 10 ** (finest + extra)))
                table = [[_status(b, t) for t in targets] for b in boxes]
                for perm in itertools.permutations(range(len(targets))):
                    if all(table[i][j] == "in" for i, j in enumerate(perm)):
                        matched = perm
                        break
                if matched is not None or not any("undecided" in row for row in table):
                    break
            numeric = sp.Poly(poly, s).nroots(n=40)
            printed_roots = ",\\ ".join(case.printed)
            details.append(
                (
                    f"\\text{{case ({case.label}): }} k_v = {latex(case.k_v)},\\ k_p = {latex(case.k_p)},\\ k_i = {latex(case.k_i)}",
                    f"{latex(poly.as_expr())} = {latex(fp.factor(poly.as_expr()))}",
                )
            )
            details.append((f"\\text{{roots (40 digits), case ({case.label})}}", ",\\ ".join(sp.latex(r) for r in numeric)))
            if matched is None:
                failures.append(
                    f"case ({case.label}): the roots {[sp.N(r, 6) for r in numeric]} do not round to the printed "
                    f"{list(case.printed)}"
                )
                continue
            _, factors = fp.factor_list(poly.as_expr())
            if all(sp.degree(f, s) == 1 for f, _ in factors):
                exact = sorted((ff.solve(f, s)[0] for f, _ in factors), key=sp.default_sort_key)
                exact_match = all(
                    any(_rat(t[0]) == r and t[2] == 0 for t in targets) for r in exact
                )
                details.append(
                    (
                        f"\\text{{case ({case.label}): rational roots}}",
                        ",\\ ".join(latex(r) for r in exact)
                        + (r"\ \text{(the printed values are exact)}" if exact_match else ""),
                    )
                )
            details.append((f"\\text{{printed, case ({case.label})}}", printed_roots))
        if failures:
            return Outcome.fail("; ".join(failures), tuple(details))
        return Outcome(True, "every root lies in the rounding box of a printed value; case (b) factors over ℚ", tuple(details))


OBLIGATIONS = (TableI,)
