"""Exact case splits for ``closed_form.all_gains``: each case a substitution of the base symbols by
fractions of sparse polynomials over ℚ, and the sign rule of :func:`._decide.sign_of` applied to them.

A case's values cover its piece of the parameter space exactly as its positive symbols range over
``(0, ∞)`` (the convention of :mod:`._decide`), so a sign decided on the parametrisation holds on the
whole piece.  A fraction is kept as numerator and denominator, never cancelled (as ``together`` in
:func:`._decide.sign_of`): it has a sign when both have coefficients of one sign.  The polynomials
are python-flint's ``fmpz_mpoly`` (exact integers; a rational constant ``p/q`` is the fraction of two
constant polynomials; the same rule on sympy expressions took minutes here).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from ._decide import is_zero

__all__ = ["BASE", "SLACK", "K_SYMBOLS", "P_SYMBOLS", "p_cases", "k_cases", "balanced_cases", "evaluate", "frac_sign", "decide_in", "decide_group", "decide_cases"]

BASE = {n: sp.Symbol(n, positive=True) for n in ("a", "k_p", "k_i", "f_c", "mu", "S", "R", "eps", "eps_kappa")}
SLACK = {n: sp.Symbol(n, positive=True) for n in ("p", "tau", "x", "h", "b", "s", "t", "u", "w")}


# -- the cases ------------------------------------------------------------------------------
# Every case is a substitution of the base symbols by elements of one sparse rational-function
# field over ℚ (sympy's ``field``): exact, and far faster than rewriting expressions.

_GENS = ("p", "tau", "x", "h", "b", "s", "t", "u", "w", "k_i", "f_c", "mu", "R", "eps_kappa")


@functools.lru_cache(maxsize=1)
def _field() -> tuple[Any, dict[str, Any]]:
    """``(F, generators)``: ``F(q)`` is the fraction of a rational ``q``; the generators are fractions.

    The polynomials are python-flint's ``fmpz_mpoly`` (exact, sparse, over ℤ).
    """
    import flint

    ctx = flint.fmpz_mpoly_ctx.get(_GENS, "lex")

    @functools.lru_cache(maxsize=4096)
    def make(q: Any) -> _Frac:
        q = sp.Rational(q)  # p/q: integer polynomials over a positive integer denominator
        return _Frac(ctx.constant(int(q.p)), ctx.constant(int(q.q)))

    return make, {n: _Frac(g, ctx.constant(1)) for n, g in zip(_GENS, ctx.gens())}


class _Frac:
    """A fraction ``num/den`` of sparse polynomials over ℚ, never cancelled (like ``together`` in :func:`._decide.sign_of`).

    Sums over equal denominators keep the denominator; otherwise the product of denominators.
    """

    __slots__ = ("numer", "denom")

    def __init__(self, numer: Any, denom: Any) -> None:
        self.numer, self.denom = numer, denom

    def _lift(self, other: Any) -> "_Frac":
        if isinstance(other, _Frac):
            return other
        return _field()[0](other)

    def __add__(self, other: Any) -> "_Frac":
        o = self._lift(other)
        if self.denom == o.denom:
            return _Frac(self.numer + o.numer, self.denom)
        return _Frac(self.numer * o.denom + o.numer * self.denom, self.denom * o.denom)

    __radd__ = __add__

    def __neg__(self) -> "_Frac":
        return _Frac(-self.numer, self.denom)

    def __sub__(self, other: Any) -> "_Frac":
        return self + (-self._lift(other))

    def __rsub__(self, other: Any) -> "_Frac":
        return self._lift(other) - self

    def __mul__(self, other: Any) -> "_Frac":
        o = self._lift(other)
        return _Frac(self.numer * o.numer, self.denom * o.denom)

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> "_Frac":
        o = self._lift(other)
        if o.numer == 0:
            raise ZeroDivisionError("division by a zero fraction")
        return _Frac(self.numer * o.denom, self.denom * o.numer)

    def __rtruediv__(self, other: Any) -> "_Frac":
        return self._lift(other) / self

    def __pow__(self, n: int) -> "_Frac":
        if n < 0:
            return _Frac(self.denom, self.numer) ** (-n)
        return _Frac(self.numer**n, self.denom**n)

    def __eq__(self, other: object) -> bool:
        o = self._lift(other)
        return self.numer * o.denom == o.numer * self.denom

    __hash__ = None  # type: ignore[assignment]


@dataclass(frozen=True)
class _Case:
    """One case: its label, its group (``"P"`` or ``"K"``) and the field values of the base symbols."""

    label: str
    group: str
    values: dict
    radicand_extra: Any = None  # K group: u in R² = q′ + u
    memo: dict = field(default_factory=dict, compare=False, repr=False)  # subterm → its fraction in this case


def _with_base(values: dict) -> dict:
    F, g = _field()
    base = {BASE[n]: g[n] for n in ("k_i", "f_c", "mu", "R", "eps_kappa")}
    base.update(values)
    return base


@functools.lru_cache(maxsize=None)
def p_cases(c1_branch: int | None) -> list[_Case]:
    """Cases of the premises on ``P`` (gains, ``S``, ``c₁``): values of ``a, k_p, S, ε``."""
    F, g = _field()
    tau, x, h, b, s, w = (g[n] for n in ("tau", "x", "h", "b", "s", "w"))
    out = []
    for glabel, pv in (("a > k_p", 2 / (1 + x)), ("a = k_p", F(2)), ("a < k_p", 2 + x)):
        ell = (4 + pv**2) / (2 * pv)
        if c1_branch is None:  # c₁ not involved: τ free, σ = 0 or σ > 0
            shapes = [("σ = 0", tau, F(0)), ("σ > 0", tau, s)]
        else:
            lam = ell + 1 + h  # λ_max(B) when λ_min(B) = τ/2 = 1 + h
            if c1_branch == 0:  # c₁ = 1 wins: a·k_p − 1 ≥ c₂, i.e. σ ≤ σ* = 2λ_max(λ_min − 1)
                shapes = [("λ_min > 1, σ = 0", 2 + 2 * h, F(0)), ("λ_min > 1, 0 < σ < σ*", 2 + 2 * h, 2 * lam * h / (1 + b)),
                          ("λ_min > 1, σ = σ*", 2 + 2 * h, 2 * lam * h), ("λ_min = 1, σ = 0", F(2), F(0))]
            else:  # (a·k_p − 1)/c₂ wins
                shapes = [("λ_min > 1, σ > σ*", 2 + 2 * h, 2 * lam * h + s), ("λ_min = 1, σ > 0", F(2), s),
                          ("λ_min < 1, σ = 0", 2 / (1 + h), F(0)), ("λ_min < 1, σ > 0", 2 / (1 + h), s)]
        for slabel, tv, sigma in shapes:
            for elabel, ev in (("ε = 0", F(0)), ("ε > 0", w)):
                values = {BASE["a"]: 2 / pv + tv / 2, BASE["k_p"]: (pv + tv) / 2, BASE["S"]: ell + sigma, BASE["eps"]: ev}
                out.append(_Case(f"{glabel}, {slabel}, {elabel}", "P", _with_base(values)))
    return out


@functools.lru_cache(maxsize=None)
def k_cases(rho_branch: int, k4_branch: int) -> list[_Case]:
    """Cases of the premises on ``K`` (``r``, ``k_p``, ``μ``, ``S′``): values of ``a, k_p`` and ``u``."""
    F, g = _field()
    t, s, u, mu = g["t"], g["s"], g["u"], g["mu"]
    rs = [("r > 1", 1 + t, 1 + t)] if rho_branch == 0 else [("r = 1", F(1), F(1)), ("r < 1", 1 / (1 + t), F(1))]
    out = []
    for rlabel, r, rho in rs:
        bound = (1 + mu) ** 2 * rho**2  # 2k_p against k₃²/2 = 2(1+μ)²ρ²
        kps = [("k_p > (1+μ)²ρ²", bound + s)] if k4_branch == 0 else [("k_p = (1+μ)²ρ²", bound), ("k_p < (1+μ)²ρ²", bound / (1 + s))]
        for klabel, kp in kps:
            for ulabel, uv in (("u = 0", F(0)), ("u > 0", u)):
                out.append(_Case(f"{rlabel}, {klabel}, {ulabel}", "K", _with_base({BASE["a"]: 1 / r, BASE["k_p"]: kp}), uv))
    return out


@functools.lru_cache(maxsize=None)
def balanced_cases(rho_branch: int) -> list[_Case]:
    """Cases of the closed form with ``k₁ = k₄ = T`` (``T`` is the generator ``R``, ``T² = (1+μ)k₃² + v``).

    ``rho_branch`` 1 (``ρ = 1``, ``k₃ = 2(1+μ)``): the set where both conditions of
    :func:`~.._certify.closed_form.balanced_conditions` hold, exactly: ``k_p = T/(2(1+μ)(1+α))``
    and ``a = T(1+β)/2`` with ``α, β, v ≥ 0`` (each ``= 0`` or ``> 0``; the inverse is
    ``α = T/(2(1+μ)k_p) − 1``, ``β = 2a/T − 1``, ``v = T² − (1+μ)k₃²``).  ``rho_branch`` 0
    (``r > 1``): ``a = 1/(1+t)`` and any ``k_p > 0``, where the conditions must fail.
    """
    F, g = _field()
    T, mu = g["R"], g["mu"]
    v_shapes = (("T² = (1+μ)k₃²", F(0)), ("T² > (1+μ)k₃²", g["u"]))
    out = []
    if rho_branch == 0:
        for vlabel, v in v_shapes:
            out.append(_Case(f"r > 1, {vlabel}", "K", _with_base({BASE["a"]: 1 / (1 + g["t"]), BASE["k_p"]: g["s"]}), v))
        return out
    for alabel, alpha in (("T = (1+μ)·2k_p", F(0)), ("T > (1+μ)·2k_p", g["h"])):
        for blabel, beta in (("(1+μ)·T = k₃·a", F(0)), ("(1+μ)·T < k₃·a", g["b"])):
            for vlabel, v in v_shapes:
                values = {BASE["a"]: T * (1 + beta) / 2, BASE["k_p"]: T / (2 * (1 + mu) * (1 + alpha))}
                out.append(_Case(f"{alabel}, {blabel}, {vlabel}", "K", _with_base(values), v))
    return out


# -- deciding -------------------------------------------------------------------------------

def evaluate(expr: Any, values: dict, memo: dict | None = None) -> Any:
    """``expr`` (+, ×, integer powers of the base symbols) as a :class:`_Frac`, exactly (shared subterms once)."""
    F, _ = _field()
    expr = sp.sympify(expr)
    memo = {} if memo is None else memo
    if expr in memo:
        return memo[expr]
    if expr.is_Rational:
        out = F(sp.Rational(expr))
    elif expr.is_Symbol:
        out = values[expr]
    elif isinstance(expr, sp.Add):
        out = F(0)
        for arg in expr.args:
            out = out + evaluate(arg, values, memo)
    elif isinstance(expr, sp.Mul):
        out = F(1)
        for arg in expr.args:
            out = out * evaluate(arg, values, memo)
    elif isinstance(expr, sp.Pow) and expr.exp.is_Integer:
        out = evaluate(expr.base, values, memo) ** int(expr.exp)
    else:
        raise ValueError(f"not a rational function of the base symbols: {expr}")
    memo[expr] = out
    return out


def _coefficient_sign(poly: Any) -> int | None:
    """The rule of :func:`._decide.sign_of`: a polynomial whose coefficients all have one sign has that sign."""
    coeffs = poly.coeffs()
    if not coeffs:
        return 0
    if min(coeffs) > 0:
        return 1
    if max(coeffs) < 0:
        return -1
    return None


def frac_sign(frac: Any) -> int | None:
    sn, sd = _coefficient_sign(frac.numer), _coefficient_sign(frac.denom)
    if sn is None or sd is None or sd == 0:
        return None
    return sn * sd


def _without_root_power(frac: Any, iR: int) -> Any:
    """``frac`` with a denominator ``R^m·D`` (``D`` free of ``R``) replaced by ``numer/D``: the same sign, as ``R > 0``.

    None if the denominator's terms have different powers of ``R`` (then no sign is read from it).
    """
    powers = {monom[iR] for monom in frac.denom.monoms()}
    if powers == {0}:
        return frac
    if len(powers) != 1:
        return None
    ctx = frac.denom.context()
    terms = {tuple(0 if i == iR else e for i, e in enumerate(monom)): c for monom, c in zip(frac.denom.monoms(), frac.denom.coeffs())}
    return _Frac(frac.numer, ctx.from_dict(terms))


def _root_sign(frac: Any, radicand: Any) -> int | None:
    """A certified lower sign of ``frac`` (1: > 0, 0: ≥ 0) where the generator ``R`` is ``√radicand``, or None."""
    F, g = _field()
    iR = _GENS.index("R")
    frac = _without_root_power(frac, iR)
    if frac is None or _coefficient_sign(frac.denom) not in (1, -1):
        return None
    if _coefficient_sign(frac.denom) == -1:
        frac = _Frac(-frac.numer, -frac.denom)
    A, B = F(0), F(0)
    ctx = frac.numer.context()
    for monom, coeff in zip(frac.numer.monoms(), frac.numer.coeffs()):
        k = monom[iR]
        rest = list(monom)
        rest[iR] = 0
        term = _Frac(ctx.from_dict({tuple(rest): coeff}), ctx.constant(1))
        if k > 1:
            term *= radicand ** (k // 2)
        if k % 2:
            B += term
        else:
            A += term
    sa, sb = frac_sign(A), frac_sign(B)
    if sa is not None and sb is not None and sa >= 0 and sb >= 0:
        return 1 if (sa == 1 or sb == 1) else 0  # R > 0
    if sb is not None and sb >= 0:  # B ≥ 0 and B²R² ≥ A²: B·R ≥ |A|
        sq = frac_sign(B**2 * radicand - A**2)
        if sq is not None and sq >= 0:
            return sq
    if sa is not None and sa >= 0:  # A ≥ 0 and A² ≥ B²R²: A ≥ |B|·R
        sq = frac_sign(A**2 - B**2 * radicand)
        if sq is not None and sq >= 0:
            return sq
    return None


def _holds(lower: int | None, kind: str) -> bool:
    return lower is not None and (lower == 1 if kind == ">" else lower >= 0)


K_SYMBOLS = {BASE["R"], BASE["mu"]}
P_SYMBOLS = {BASE["S"], BASE["eps"]}


def _decide_cases(expr: Any, kind: str, cases: list[_Case], radicand: Any = None) -> str:
    """``""`` if ``expr kind 0`` holds in every case, else the first failing case's label."""
    for case in cases:
        value = evaluate(expr, case.values, case.memo)
        if case.group == "K":
            lower = _root_sign(value, evaluate(radicand, case.values, case.memo) + case.radicand_extra)
        else:
            lower = frac_sign(value)
        if not _holds(lower, kind):
            return case.label
    return ""


def decide_cases(expr: Any, kind: str, cases: list, radicand: Any) -> str:
    """Decide ``expr kind 0`` in every case of ``cases`` (the generator ``R`` being ``√(radicand + extra)``)."""
    return _decide_cases(sp.sympify(expr), kind, cases, radicand)


def decide_in(expr: Any, kind: str, cases_p: list, cases_k: list, radicand: Any) -> str:
    """Decide ``expr kind 0`` in the cases of the group its symbols belong to."""
    expr = sp.sympify(expr)
    free = expr.free_symbols
    if kind == "==":
        return "" if is_zero(expr) else "not an identity"
    if free & K_SYMBOLS and free & (P_SYMBOLS | {BASE["eps_kappa"]}):
        return _decide_mixed(expr, kind, cases_p, cases_k, radicand)
    if free & {BASE["eps_kappa"]}:
        for label, ev in (("ε_κ = 0", sp.Integer(0)), ("ε_κ > 0", BASE["eps_kappa"])):
            reduced = expr.xreplace({BASE["eps_kappa"]: ev})
            cases = cases_k if reduced.free_symbols & K_SYMBOLS else cases_p
            if _decide_cases(reduced, kind, cases, radicand):
                return label
        return ""
    if free & K_SYMBOLS:
        return _decide_cases(expr, kind, cases_k, radicand)
    return _decide_cases(expr, kind, cases_p)


def _decide_mixed(expr: sp.Expr, kind: str, cases_p: list, cases_k: list, radicand: Any) -> str:
    """A premise on both groups (only ``κ > 0``): decided factor by factor, term by term."""
    if isinstance(expr, sp.Pow) and expr.exp == sp.Rational(1, 2):
        return _decide_mixed(expr.base, ">", cases_p, cases_k, radicand)
    if isinstance(expr, sp.Pow) and expr.exp.is_Integer:
        return decide_in(expr.base, ">", cases_p, cases_k, radicand)
    if isinstance(expr, sp.Mul):
        for f in expr.args:
            why = decide_in(f, ">", cases_p, cases_k, radicand)
            if why:
                return why
        return ""
    if isinstance(expr, sp.Add):
        # every term ≥ 0 and (for > 0) one term > 0
        strict = [decide_in(t, ">", cases_p, cases_k, radicand) == "" for t in expr.args]
        if any(strict) and all(s or decide_in(t, ">=", cases_p, cases_k, radicand) == "" for s, t in zip(strict, expr.args)):
            return ""
        return "a term of a mixed premise"
    return "a mixed premise of unknown form"


def decide_group(expr: sp.Expr, kind: str, group: str, cases: list) -> str:
    """Decide ``expr kind 0`` in every case of one group (``"P"`` or ``"K"``)."""
    return _decide_cases(expr, kind, cases, None if group == "P" else sp.Integer(0))


