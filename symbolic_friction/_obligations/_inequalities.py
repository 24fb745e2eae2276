"""Exact tools for the obligations of Lemma 3, Proposition 1 (stability) and
Corollary 1: case grids, nonnegativity certificates and the eigenvalue
bounds of a symmetric matrix whose middle row and column are decoupled.

Everything here is exact (sympy rationals and symbols, no floats) and errs on
the side of "not proved": a function answers ``True`` only when it has a
certificate, and ``False`` means "no certificate found", which makes the
calling obligation fail rather than guess.

* Signs, relations and ``Piecewise`` branches are decided by
  :func:`._decide.sign_of`, :func:`._decide.decide` and
  :func:`._decide.resolve_piecewise` (numerator and denominator with
  coefficients of one sign).
* :func:`is_nonneg` proves ``expr ≥ 0`` for every value of its free symbols
  allowed by their sympy assumptions (positive, nonnegative or merely real)
  by one of three *sign-definite decompositions* of the numerator: all
  monomials nonnegative (coefficient ``> 0`` and odd powers only of
  nonnegative symbols); a factorisation whose odd-power factors are sign
  definite in that sense; or a homogeneous quadratic form with a rational,
  positive semidefinite Gram matrix (all principal minors ``≥ 0``).  The
  denominator must be positive by :func:`sign_of`.
* :class:`Case` and :func:`line_cases` split a variable at ordered
  breakpoints into open pieces and boundary points, each written with fresh
  positive symbols so that a sign decided on the parametrisation holds on the
  whole piece (an open piece ``(b, b')`` is ``(u b + w b')/(u + w)``,
  ``u, w > 0``; the piece ``|x| < c`` of a positive symbol ``c`` is the
  polynomial ``c = (u + w)/2, x = (w - u)/2``).  :func:`case_grid` takes the
  product of several splits.
* :func:`block_eigen_bounds` checks, for ``M = [[a, 0, c], [0, m, 0], [c, 0, e]]``,
  that ``μ± = (a + e ± √((a-e)² + 4c²))/2`` and ``m`` are its eigenvalues and
  that ``μ₋|u|² ≤ uᵀBu ≤ μ₊|u|²`` for the outer ``2×2`` block ``B``, which gives
  the Rayleigh bounds ``min(m, μ₋)|x|² ≤ xᵀMx ≤ max(m, μ₊)|x|²``.
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from . import _fastforms as ff
from . import _fastpoly as fp
from ._decide import _has_denominator, is_zero, sign_of

__all__ = [
    "is_nonneg",
    "is_nonpos",
    "canonical",
    "Case",
    "line_cases",
    "sign_cases",
    "phi_cases",
    "case_grid",
    "block_eigen_bounds",
    "extremum",
    "is_upper_bound_of",
    "is_lower_bound_of",
    "label_latex",
    "rows_latex",
]


# --------------------------------------------------------------------------
# nonnegativity certificates
# --------------------------------------------------------------------------


def _form_nonneg(expr: sp.Expr) -> bool:
    """Nonnegative by its written form: sums and products of nonnegative
    numbers, nonnegative symbols, even powers of real expressions and
    nonnegative powers of such forms (e.g. ``(a - e)**2 + 4*c**2``)."""
    if expr.is_number:
        return bool(expr.is_nonnegative)
    if expr.is_Symbol:
        return expr.is_nonnegative is True
    if isinstance(expr, sp.Pow):
        if expr.exp.is_Integer and expr.exp.is_even and expr.base.is_extended_real:
            return True
        return bool(expr.exp.is_Rational) and _form_nonneg(expr.base)
    if isinstance(expr, (sp.Add, sp.Mul)):
        return all(_form_nonneg(a) for a in expr.args)
    return False


def _monomials_nonneg(poly_expr: sp.Expr) -> bool:
    """All monomials of the expanded polynomial are ``≥ 0`` by their form."""
    p = fp.expand(poly_expr)  # sympy.expand, the same expression (flint for a polynomial)
    if p == 0:
        return True
    if p.is_number:
        return bool(p.is_nonnegative)
    gens = sorted(p.free_symbols, key=sp.default_sort_key)
    try:
        poly = sp.Poly(p, *gens)
    except sp.PolynomialError:
        return False
    for exps, coeff in poly.terms():
        if not (coeff.is_Rational and coeff > 0):
            return False
        for sym, k in zip(gens, exps):
            # an odd power of a sign-unknown symbol can be negative
            if k % 2 == 1 and sym.is_nonnegative is not True:
                return False
    return True


def _gram_psd(poly_expr: sp.Expr) -> bool:
    """Homogeneous quadratic with a rational PSD Gram matrix (all principal minors ≥ 0)."""
    p = sp.expand(poly_expr)
    gens = sorted(p.free_symbols, key=sp.default_sort_key)
    if not gens:
        return False
    try:
        poly = sp.Poly(p, *gens)
    except sp.PolynomialError:
        return False
    if not poly.is_homogeneous or poly.total_degree() != 2:
        return False
    n = len(gens)
    G = sp.zeros(n, n)
    for exps, coeff in poly.terms():
        if not coeff.is_Rational:
            return False
        idx = [i for i, k in enumerate(exps) for _ in range(k)]
        i, j = idx
        if i == j:
            G[i, i] += coeff
        else:
            G[i, j] += coeff / 2
            G[j, i] += coeff / 2
    for size in range(1, n + 1):
        for rows in itertools.combinations(range(n), size):
            if G.extract(list(rows), list(rows)).det() < 0:
                return False
    return True


def _factor_nonneg(poly_expr: sp.Expr) -> bool:
    """A factorisation in which every odd-power factor is sign definite."""
    const, factors = fp.factor_list(sp.expand(poly_expr))
    if not const.is_Rational or const == 0:
        return False
    sign = 1 if const > 0 else -1
    for f, k in factors:
        if k % 2 == 0:
            continue
        if _monomials_nonneg(f) or _gram_psd(f):
            continue
        if _monomials_nonneg(-f) or _gram_psd(-f):
            sign = -sign
            continue
        return False
    return sign > 0


def is_nonneg(expr: Any) -> bool:
    """Whether ``expr ≥ 0`` is proved for all admissible values of its symbols.

    Parameters
    ----------
    expr : sympy expression
        A rational function.  Symbols declared ``positive`` or
        ``nonnegative`` are taken as such; other symbols are real.

    Returns
    -------
    bool
        ``True`` with a certificate (see the module docstring); ``False`` if
        none was found (the expression may still be nonnegative).

    Examples
    --------
    >>> x = sp.Symbol("x", real=True); t = sp.Symbol("t", positive=True)
    >>> is_nonneg(x**2 - 2*x*t + t**2), is_nonneg(x*t)
    (True, False)
    """
    expr = sp.sympify(expr)
    if expr.has(sp.Piecewise, sp.Abs, sp.sign, sp.Max, sp.Min):
        return False
    if expr.is_number:
        return bool(expr.is_nonnegative)
    if _form_nonneg(expr):
        return True
    if _has_denominator(expr):
        num, den = sp.fraction(ff.together(expr))
    else:  # a polynomial is its own numerator (together would only regroup it; every test below expands it)
        num, den = expr, sp.Integer(1)
    den = sp.expand(den)
    if not (den.is_number and den > 0):
        if any(s.is_positive is not True for s in den.free_symbols) or sign_of(den) != 1:
            return False
    if num.has(sp.Pow) and any(isinstance(a, sp.Pow) and not a.exp.is_Integer for a in sp.preorder_traversal(num)):
        return False  # radicals: not a polynomial certificate
    return _monomials_nonneg(num) or _gram_psd(num) or _factor_nonneg(num)


def is_nonpos(expr: Any) -> bool:
    """Whether ``expr ≤ 0`` is proved (see :func:`is_nonneg`)."""
    return is_nonneg(-sp.sympify(expr))


def canonical(expr: Any) -> sp.Expr:
    """Canonical form of the condition ``expr > 0`` (or ``≥ 0``) for positive symbols.

    The numerator of ``together(expr)`` is factored; factors (and the
    denominator) that are positive by :func:`sign_of` are dropped,
    the integer content is divided out, and the leading sign is kept.  Two
    conditions with equal canonical forms are the same condition.

    Examples
    --------
    >>> k3, k_v, k1, k_i = sp.symbols("k3 k_v k1 k_i", positive=True)
    >>> canonical(k3 - k_i*k1/k_v)
    -k1*k_i + k3*k_v
    >>> canonical(6*k3*(k3*k_v - k_i*k1))
    -k1*k_i + k3*k_v
    """
    num, den = sp.fraction(ff.together(sp.sympify(expr)))
    if sign_of(den) != 1:
        raise ValueError(f"the denominator {den} of the condition is not positive")
    const, factors = fp.factor_list(sp.expand(num))
    kept = sp.Integer(1 if const > 0 else -1)
    for f, k in factors:
        if sign_of(f) == 1:
            continue
        if sign_of(f) == -1:
            kept = -kept if k % 2 else kept
            continue
        kept *= f**k
    return sp.expand(kept)


# --------------------------------------------------------------------------
# case grids
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Case:
    """A piece of a case split, written with fresh positive symbols.

    Attributes
    ----------
    label : str
        E.g. ``"v > 0, σ < 0, φ < -f_c"``.
    values : tuple of (Symbol, Expr)
        Simultaneous substitution of the split variables.
    slacks : tuple of Symbol
        The fresh positive symbols used (ranging over ``(0, ∞)`` they cover
        the piece exactly).
    """

    label: str
    values: tuple[tuple[sp.Symbol, sp.Expr], ...]
    slacks: tuple[sp.Symbol, ...] = ()

    def __call__(self, expr: Any) -> Any:
        """Substitute the case's parametrisation into ``expr``."""
        mapping = dict(self.values)
        if isinstance(expr, (tuple, list)):
            return type(expr)(self(e) for e in expr)
        return sp.sympify(expr).xreplace(mapping)

    def value(self, var: sp.Symbol) -> sp.Expr:
        """The parametrised value of ``var`` in this case."""
        return dict(self.values)[var]


def line_cases(
    var: sp.Symbol,
    breakpoints: Sequence[Any],
    *,
    name: str,
    beyond: str,
    weights: tuple[str, str] = ("u", "w"),
    labels: Sequence[str] | None = None,
) -> list[Case]:
    """Split the real line of ``var`` at increasing ``breakpoints``.

    Parameters
    ----------
    var : Symbol
        The variable split.
    breakpoints : sequence of expressions
        Strictly increasing (checked exactly with :func:`sign_of`).
    name : str, keyword-only
        How ``var`` is printed in the labels.
    beyond : str, keyword-only
        Name of the positive symbol measuring the distance beyond the
        outermost breakpoints (``var = b₁ - t``, ``var = b_n + t``).
    weights : (str, str), keyword-only
        Names of the two positive weights of the open pieces between
        breakpoints (``var = (u b_i + w b_{i+1})/(u + w)``; for the two
        breakpoints ``±c`` with ``c`` a positive symbol, the polynomial
        ``c = (u + w)/2, var = (w - u)/2`` instead, which also substitutes ``c``).
    labels : sequence of str, optional
        How the breakpoints are printed (default: ``str``).

    Returns
    -------
    list of Case
        ``2n + 1`` pieces, from ``var < b₁`` to ``var > b_n``.

    Raises
    ------
    ValueError
        If the breakpoints are not strictly increasing.
    """
    bps = [sp.sympify(b) for b in breakpoints]
    for lo, hi in zip(bps, bps[1:]):
        if sign_of(hi - lo) != 1:
            raise ValueError(f"breakpoints must increase strictly; cannot show {hi} > {lo}")
    texts = list(labels) if labels is not None else [str(b) for b in bps]
    t = sp.Symbol(beyond, positive=True)
    u, w = (sp.Symbol(n, positive=True) for n in weights)
    # breakpoints ±c with c a positive symbol: the open piece |var| < c is
    # {c = (u + w)/2, var = (w - u)/2}, a polynomial parametrisation (no
    # denominators, so signs are decided without forming common denominators)
    symmetric = len(bps) == 2 and bps[1].is_Symbol and bps[1].is_positive and bps[0] == -bps[1]
    out = [Case(f"{name} < {texts[0]}", ((var, bps[0] - t),), (t,))]
    for i, b in enumerate(bps):
        out.append(Case(f"{name} = {texts[i]}", ((var, b),), ()))
        if i + 1 < len(bps):
            nxt = bps[i + 1]
            label = f"{texts[i]} < {name} < {texts[i + 1]}"
            if symmetric:
                out.append(Case(label, ((nxt, (u + w) / 2), (var, (w - u) / 2)), (u, w)))
            else:
                out.append(Case(label, ((var, (u * b + w * nxt) / (u + w)),), (u, w)))
    out.append(Case(f"{name} > {texts[-1]}", ((var, bps[-1] + t),), (t,)))
    return out


def sign_cases(var: sp.Symbol, name: str, beyond: str) -> list[Case]:
    """Split ``var`` at 0: ``var < 0``, ``var = 0``, ``var > 0`` (``beyond`` names ``|var|``)."""
    return line_cases(var, [0], name=name, beyond=beyond, labels=["0"])


def phi_cases(phi: sp.Symbol, f_c: sp.Symbol) -> list[Case]:
    """Split ``φ`` at ``±f_c`` (the breakpoints of ``dz``), the open piece ``|φ| < f_c`` polynomially."""
    return line_cases(phi, [-f_c, f_c], name="φ", beyond="d_phi", weights=("u_phi", "w_phi"), labels=["-f_c", "f_c"])


def case_grid(*splits: Sequence[Case]) -> list[Case]:
    """The product of several splits of distinct variables."""
    out = []
    for combo in itertools.product(*splits):
        out.append(
            Case(
                ", ".join(c.label for c in combo),
                tuple(v for c in combo for v in c.values),
                tuple(s for c in combo for s in c.slacks),
            )
        )
    return out


# --------------------------------------------------------------------------
# eigenvalue bounds for a matrix with a decoupled middle entry
# --------------------------------------------------------------------------


def block_eigen_bounds(M: sp.Matrix, *, what: str = "M") -> tuple[list[tuple[str, bool]], dict[str, sp.Expr]]:
    """Exact Rayleigh bounds for ``M = [[a, 0, c], [0, m, 0], [c, 0, e]]``.

    Checks, each as an exact identity or sign certificate:

    1. ``M`` is symmetric and its middle row/column is decoupled;
    2. ``μ₊ + μ₋ = a + e`` and ``μ₊μ₋ = ae - c²`` (so ``μ±`` are the eigenvalues
       of ``B = [[a, c], [c, e]]``; ``(a - e)² + 4c² ≥ 0`` makes them real);
    3. ``μ₊I - B ⪰ 0`` and ``B - μ₋I ⪰ 0``: for each, the determinant is 0
       (identity) and the two diagonal entries have sum ``√((a-e)²+4c²) ≥ 0``
       and product ``c² ≥ 0``, so both are ``≥ 0``.

    Hence ``min(m, μ₋)|x|² ≤ xᵀMx ≤ max(m, μ₊)|x|²`` for every real ``x``,
    with equality at eigenvectors.

    Returns
    -------
    checks : list of (str, bool)
        Each check and whether it holds.
    values : dict
        ``m``, ``mu_minus``, ``mu_plus``, ``lam_min = Min(m, μ₋)``,
        ``lam_max = Max(m, μ₊)``, ``disc``.
    """
    checks: list[tuple[str, bool]] = []
    M = sp.Matrix(M)
    checks.append((f"{what} is symmetric", all(is_zero(M[i, j] - M[j, i]) for i in range(3) for j in range(3))))
    checks.append(
        (f"the middle row and column of {what} are decoupled", all(is_zero(M[i, j]) for i, j in ((0, 1), (1, 0), (1, 2), (2, 1))))
    )
    a, c, e, m = M[0, 0], M[0, 2], M[2, 2], M[1, 1]
    disc = (a - e) ** 2 + 4 * c**2
    root = sp.sqrt(disc)
    mu_p, mu_m = (a + e + root) / 2, (a + e - root) / 2
    checks.append((f"μ₊ + μ₋ = trace of the outer block of {what}", is_zero(mu_p + mu_m - a - e)))
    checks.append((f"μ₊·μ₋ = determinant of the outer block of {what}", is_zero(sp.expand(mu_p * mu_m) - (a * e - c**2))))
    checks.append((f"the discriminant of {what}'s outer block is a sum of squares", is_nonneg(disc)))
    for label, d1, d2 in (("μ₊I - B", mu_p - a, mu_p - e), ("B - μ₋I", a - mu_m, e - mu_m)):
        det_zero = is_zero(sp.expand(d1 * d2) - c**2)
        sum_ok = is_zero(d1 + d2 - root)
        checks.append((f"{label} ⪰ 0 for {what} (det = 0, diagonal sum √disc ≥ 0, diagonal product c² ≥ 0)", det_zero and sum_ok))
    values = {
        "m": m,
        "mu_minus": mu_m,
        "mu_plus": mu_p,
        "lam_min": extremum(sp.Min, m, mu_m),
        "lam_max": extremum(sp.Max, m, mu_p),
        "disc": disc,
    }
    return checks, values


@functools.lru_cache(maxsize=64)
def extremum(kind: type, a: sp.Expr, b: sp.Expr) -> sp.Expr:
    """``kind(a, b)`` (``Min`` or ``Max``), remembered: sympy compares the arguments through their assumptions when it
    builds one (tens of milliseconds with a radical), and the same matrices' bounds are built by several obligations."""
    return kind(a, b)


def _same(a: Any, b: Any) -> bool:
    return is_zero(sp.sympify(a) - sp.sympify(b))


def _is_bound_of(c: Any, values: Sequence[Any], *, extremum: type, upper: bool) -> bool:
    """Whether ``c`` bounds every value (``c ≥ v`` if ``upper``, else ``c ≤ v``).

    ``c`` may be an ``extremum`` (``Max`` for an upper bound, ``Min`` for a
    lower one) that lists the value among its arguments, which bounds it by
    definition; otherwise ``c`` must equal the value or the gap must be proved
    by :func:`is_nonneg`.
    """
    c = sp.sympify(c)
    for v in values:
        # an argument that is the value itself first (equal trees differ by 0): the others may need simplify
        if isinstance(c, extremum) and (v in c.args or any(_same(arg, v) for arg in c.args)):
            continue
        if _same(c, v) or is_nonneg(c - v if upper else v - c):
            continue
        return False
    return True


def is_upper_bound_of(c: Any, values: Sequence[Any]) -> bool:
    """Whether ``c ≥ v`` for every ``v`` in ``values`` (``Max`` or :func:`is_nonneg`)."""
    return _is_bound_of(c, values, extremum=sp.Max, upper=True)


def is_lower_bound_of(c: Any, values: Sequence[Any]) -> bool:
    """Whether ``c ≤ v`` for every ``v`` in ``values`` (``Min`` or :func:`is_nonneg`)."""
    return _is_bound_of(c, values, extremum=sp.Min, upper=False)


_LABEL_TEX = {"σ": "\\sigma ", "φ": "\\phi ", "ρ": "\\rho ", "≤": "\\le ", "≥": "\\ge ", ",": ",\\ "}


def label_latex(label: str) -> str:
    """A case label such as ``"v > 0, σ < 0, φ < -f_c"`` as LaTeX (math mode)."""
    return "".join(_LABEL_TEX.get(ch, ch) for ch in label)


def rows_latex(rows: Sequence[str]) -> str:
    """Several LaTeX rows as one display block (``gathered``), for an obligation's details."""
    if not rows:
        return "\\text{none}"
    return "\\begin{gathered}" + r" \\ ".join(rows) + "\\end{gathered}"
