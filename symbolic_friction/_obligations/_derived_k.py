"""The conditions on ``k₁ … k₄`` that ``lemma3.hatV_derivative`` derives from eq. (hatVdot), compared with the paper's (Lemma 3) and with :mod:`symbolic_friction._model.kconditions`; used by :mod:`.lemma3` and :mod:`.certificate`."""

from __future__ import annotations

import contextlib
import dataclasses
import itertools
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.kconditions import Condition, k_conditions
from . import _fastforms as ff
from . import _fastpoly as fp
from ._decide import Undecided, is_zero, remembering, resolve_piecewise, sign_of
from ._inequalities import Case, canonical, is_nonneg
from ._region import pieces_of
from ._shared import _SHARED as _shared_stack
from ._shared import derivative, shared_value
from ._statements import lemma3_hatV_nonincreasing


@dataclass(frozen=True)
class HatVDerivativeSubject:
    """What ``lemma3.hatV_derivative`` checks.

    Attributes
    ----------
    sigma, phi, v, f_c : Symbol
    gains : (k_p, k_i, k_v)
    k : (k₁, k₂, k₃, k₄)
    zeta : Symbol
        Selection of the Clarke gradient ``∂|σ| = SGN(σ)``; it replaces
        ``sign(σ)`` in the derivative of ``|σ|``.
    Vhat : Expr
        eq. (Vhat).
    F : tuple of Expr
        ``A x - b sign(v)``: the inclusion (eq. xDot) on ``v ≠ 0``.
    region : Expr
        ``R̂ = {region < 0}``.
    K : Matrix
        ``K`` of ``V̂ = ½wᵀKw`` (for the definiteness condition).
    stated : tuple of Condition
        :func:`symbolic_friction._model.kconditions.k_conditions` on the symbols.
    paper_bound : Expr
        The paper's bracketed upper bound of ``V̂°`` on ``R̂_>``.
    paper_pairs : tuple of (Expr, Expr, Expr)
        ``(bracket, coefficient, monomial)``: the paper's pairing argument
        ``bracket ≤ coefficient·monomial``.
    f_v_bound : Expr
        The paper's ``-k_v|v| - |dz(φ)|``, claimed ``≥ sign(v)·f_v``.
    zeta_claim : Expr
        The paper's ``max_{ζ ∈ ∂|σ|}(-k_i k₃|v|²ζ) = k_i k₃|v|²``, right side.
    cases : tuple of Case
        Split of ``(v, σ, φ)``.
    """

    sigma: sp.Symbol
    phi: sp.Symbol
    v: sp.Symbol
    f_c: sp.Symbol
    gains: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    k: tuple[sp.Symbol, sp.Symbol, sp.Symbol, sp.Symbol]
    zeta: sp.Symbol
    Vhat: sp.Expr
    F: tuple[sp.Expr, sp.Expr, sp.Expr]
    region: sp.Expr
    K: sp.Matrix
    stated: tuple[Condition, ...]
    paper_bound: sp.Expr
    paper_pairs: tuple[tuple[sp.Expr, sp.Expr, sp.Expr], ...]
    f_v_bound: sp.Expr
    zeta_claim: sp.Expr
    cases: tuple[Case, ...]
    statement: Any = lemma3_hatV_nonincreasing
    """The conclusion Proposition 1 uses (:func:`._statements.lemma3_hatV_nonincreasing`)."""


@dataclass(frozen=True)
class _Derived:
    """One derived condition ``expr ≥ 0`` (or ``> 0`` when ``strict``)."""

    expr: sp.Expr
    strict: bool
    origin: str
    necessary: bool = False


def _paper_pairs(g: _symbolic.Gains, k: tuple[sp.Symbol, ...]) -> tuple[tuple[sp.Expr, sp.Expr, sp.Expr], ...]:
    k1, k2, k3, k4 = k
    a_s, a_v = sp.Abs(g.sigma), sp.Abs(g.v)
    dz = shared_value(_symbolic.dz, g.phi, g.f_c)
    a_d = sp.Abs(dz)
    # the four brackets of the displayed inequality in the proof of Lemma 3
    return (
        (g.k_i * k3 * a_v**2 - k4 * g.k_v * a_v**2, g.k_i * k3 - k4 * g.k_v, a_v**2),
        (k2 * g.sigma * dz - k3 * a_s * a_d, k2 - k3, a_s * a_d),
        (-k1 * g.k_i * g.sigma * g.v - k3 * g.k_v * a_v * a_s, k1 * g.k_i - k3 * g.k_v, a_s * a_v),
        (k2 * g.k_p * a_v * a_d - k4 * a_v * a_d, k2 * g.k_p - k4, a_v * a_d),
    )


def _leading_witness(num: sp.Expr, coeff: sp.Expr, slacks: tuple[sp.Symbol, ...]) -> tuple[int, ...] | None:
    """Exponents ``e`` such that ``num(slack = λ^e)`` has leading coefficient ``coeff × (positive)``.

    Then ``coeff > 0`` makes ``num`` positive for large ``λ``: the
    condition ``coeff ≤ 0`` is necessary.
    """
    lam = sp.Symbol("lambda", positive=True)
    for exps in itertools.product(range(3), repeat=len(slacks)):
        scaled = fp.expand(num.xreplace({s: lam**e for s, e in zip(slacks, exps)}))
        lc = ff.poly_terms(scaled, (lam,))[0][1]  # Poly(scaled, lam).LC()
        if sign_of(fp.cancel(lc / coeff)) == 1:
            return exps
    return None


_SHARED = _shared_stack  # the blocks of shared_derivations (also what _shared.shared_value shares within)


@contextlib.contextmanager
def shared_derivations() -> Iterator[None]:
    """Within the block, :func:`derived_k_conditions` derives once per subject (``lemma3.hatV_derivative`` and
    ``certificate.verifier`` derive from equal subjects in one ``check`` run), and the decision procedures convert
    each expression into its fraction of polynomials once (:func:`._decide.remembering`); outside it, every call
    derives and converts."""
    _SHARED.append({})
    try:
        with remembering():
            yield
    finally:
        _SHARED.pop()


def _frozen(value: Any) -> Any:
    """``value`` as a hashable key with its type: sympy objects compare by structure, and a symbol's assumptions
    are part of it (``Symbol('z', real=True) != Symbol('z')``); a mutable matrix is keyed as an immutable one."""
    if isinstance(value, sp.MatrixBase):
        return ("matrix", sp.ImmutableMatrix(value))
    if isinstance(value, (tuple, list)):
        return (type(value).__name__, tuple(_frozen(v) for v in value))
    return (type(value), value)


def _subject_key(subject: HatVDerivativeSubject) -> Any:
    # subjects differing in any field, a symbol's assumptions included, never share a derivation
    key = tuple((f.name, _frozen(getattr(subject, f.name))) for f in dataclasses.fields(subject))
    try:
        hash(key)
    except TypeError:  # an unhashable field: its srepr, which names every symbol's assumptions
        return "|".join(sp.srepr(getattr(subject, f.name)) if isinstance(getattr(subject, f.name), sp.Basic)
                        else repr(getattr(subject, f.name)) for f in dataclasses.fields(subject))
    return key


def derived_k_conditions(subject: HatVDerivativeSubject) -> tuple[list[_Derived], list[str], dict[str, Any]]:
    """The derivation below, shared within :func:`shared_derivations`."""
    if not _SHARED:
        return _derive_k_conditions(subject)
    key = _subject_key(subject)
    memo = _SHARED[-1]
    if key not in memo:
        memo[key] = _derive_k_conditions(subject)
    return memo[key]


def _derive_k_conditions(subject: HatVDerivativeSubject) -> tuple[list[_Derived], list[str], dict[str, Any]]:
    """Derive, from ``V̂`` and ``F``, the conditions on ``k`` for ``V̂° ≤ 0`` on ``R̂``.

    For each piece of ``R̂`` (``v ≠ 0``, so ``F`` is single valued) and each
    extreme point ``ζ`` of ``∂|σ|`` (``V̂°`` is affine in ``ζ``, so its max over
    ``[-1, 1]`` is at ``ζ = ±1``), ``⟨∂V̂, F⟩`` is a rational function of the
    positive parameters of the piece.  Its numerator is a polynomial in those
    parameters and ``f_c`` whose coefficients are polynomials in the gains
    and ``k``: a coefficient that is negative for all positive gains imposes
    nothing, a mixed one imposes ``coefficient ≤ 0`` (sufficient, since the
    monomials are positive).  Each such condition is also shown *necessary*
    by a scaling ``λ^e`` of the parameters whose leading term is that
    coefficient times a positive factor.

    Returns
    -------
    derived : list of _Derived
    failures : list of str
    info : dict
        Per-piece data for the details and the paper's claims.
    """
    s = subject
    failures: list[str] = []
    state = (s.sigma, s.phi, s.v)
    grad = [derivative(s.Vhat, x).xreplace({sp.sign(s.sigma): s.zeta}) for x in state]
    if any(gi.has(sp.sign(s.sigma)) for gi in grad):
        failures.append("the gradient still contains sign(σ) after the Clarke selection")
    found: dict[sp.Expr, _Derived] = {}
    witnesses: dict[sp.Expr, list[tuple[Case, sp.Expr, sp.Expr]]] = {}
    pieces: list[tuple[Case, list[tuple[sp.Expr, sp.Expr]]]] = []
    for case in pieces_of(s.cases, s.region, inside=False, failures=failures):
        sigma_val = case.value(s.sigma)
        zetas = [sp.Integer(-1), sp.Integer(1)] if sigma_val == 0 else [sp.sign(sigma_val)]
        try:
            f_vals = [resolve_piecewise(case(fi)) for fi in s.F]
            g_vals = [resolve_piecewise(case(gi)) for gi in grad]
        except Undecided as exc:
            failures.append(f"{case.label}: {exc}")
            continue
        inner = fp.expand(sum(gi * fi for gi, fi in zip(g_vals, f_vals)))
        if any(isinstance(z, sp.sign) for z in zetas) or ff.degree_in(inner, s.zeta) > 1:
            failures.append(f"{case.label}: ⟨∂V̂, F⟩ is not affine in the selection ζ of ∂|σ|")
            continue
        branch_values = []
        for zeta in zetas:
            value = ff.together(inner.xreplace({s.zeta: zeta}))
            branch_values.append((zeta, value))
            num, den = sp.fraction(value)
            if sign_of(den) != 1:
                failures.append(f"{case.label}: cannot show the denominator {den} is positive")
                continue
            gens = tuple(sorted(set(case.slacks) | {s.f_c}, key=sp.default_sort_key))
            for monom, coeff in ff.poly_terms(fp.expand(num), gens):  # Poly(expand(num), *gens).terms()
                sg = sign_of(coeff)
                if sg in (-1, 0):
                    continue
                mono = sp.Mul(*[x**e for x, e in zip(gens, monom)])
                if sg == 1:
                    failures.append(
                        f"{case.label}, ζ = {zeta}: the term {coeff}·{mono} of V̂° is positive for every choice of k"
                    )
                    continue
                key = canonical(-coeff)
                found.setdefault(key, _Derived(key, False, f"V̂° ≤ 0 on {case.label}"))
                witnesses.setdefault(key, []).append((case, num, coeff))
        pieces.append((case, branch_values))
    # necessity of each derived condition
    derived: list[_Derived] = []
    for key in sorted(found, key=sp.default_sort_key):
        necessary = False
        for case, num, coeff in sorted(witnesses[key], key=lambda t: len(t[0].slacks)):
            # a witness must keep f_c fixed: the claim is for each friction level
            if s.f_c in dict(case.values):
                continue
            if _leading_witness(num, coeff, case.slacks) is not None:
                necessary = True
                break
        derived.append(_Derived(key, False, found[key].origin, necessary))
    return derived, failures, {"grad": grad, "pieces": pieces}


def _condition_key(expr: sp.Expr) -> sp.Expr:
    """Key under which a condition ``expr > 0`` is compared.

    A condition that holds by the symbols' assumptions (``k₁ > 0`` for a
    positive symbol) is its own key; any other is :func:`canonical`, which
    drops positive factors and integer content.
    """
    expr = sp.sympify(expr)
    if sign_of(expr) == 1:
        return sp.expand(expr)
    return canonical(expr)


def _c1_failures(s: HatVDerivativeSubject) -> list[str]:
    """``V̂`` and ``∂V̂/∂φ`` are continuous across ``φ = ±f_c`` (so ``½k₂dz²`` is C¹)."""
    out = []
    u = sp.Symbol("u_eps", positive=True)
    eps = 2 * s.f_c * u / (1 + u)  # 0 < ε < 2 f_c, so φ = ±f_c ± ε crosses no other breakpoint
    dphi = derivative(s.Vhat, s.phi)
    for point in (-s.f_c, s.f_c):
        for label, expr in (("V̂", s.Vhat), ("∂V̂/∂φ", dphi)):
            try:
                at = resolve_piecewise(expr.xreplace({s.phi: point}))
                left = resolve_piecewise(expr.xreplace({s.phi: point - eps})).xreplace({u: 0})
                right = resolve_piecewise(expr.xreplace({s.phi: point + eps})).xreplace({u: 0})
            except Undecided as exc:
                out.append(f"continuity of {label} at φ = {point}: {exc}")
                continue
            if not (is_zero(left - at) and is_zero(right - at)):
                out.append(f"{label} jumps at φ = {point}")
    return out


def _paper_claims(
    s: HatVDerivativeSubject, info: dict[str, Any], derived: list[_Derived]
) -> tuple[list[tuple[str, str]], list[str], int, int]:
    """Check the paper's f_v bound, the max over ∂|σ|, the bracketed bound and the pairing argument."""
    failures: list[str] = []
    eq_cases = strict_cases = 0
    fv_ok = bound_ok = pairs_ok = True
    pair_keys = set()
    for _, coeff, _ in s.paper_pairs:
        try:
            pair_keys.add(canonical(-coeff))
        except ValueError:
            failures.append(f"pair coefficient {coeff} has no positive denominator")
    for case, branches in info["pieces"]:
        v_val = case.value(s.v)
        sign_v = sp.sign(v_val)
        try:
            f_v = resolve_piecewise(case(s.F[2]))
            fv_gap = resolve_piecewise(case(s.f_v_bound)) - sign_v * f_v
            paper = resolve_piecewise(case(s.paper_bound))
            claim = resolve_piecewise(case(s.zeta_claim))
            pairs = [(resolve_piecewise(case(b)), resolve_piecewise(case(c * m))) for b, c, m in s.paper_pairs]
        except Undecided as exc:
            failures.append(f"{case.label}: {exc}")
            continue
        if not is_nonneg(fv_gap):
            fv_ok = False
            failures.append(f"{case.label}: sign(v)·f_v ≤ −k_v|v| − |dz(φ)| fails (gap {fp.factor(fv_gap)})")
        # max over ζ ∈ SGN(σ) of the ζ-term −k_i k₃|v| v ζ of ⟨∂V̂, F⟩
        k3 = s.k[2]
        term = -s.gains[1] * k3 * sp.Abs(v_val) * v_val
        values = [term * z for z, _ in branches]
        top = next((a for a in values if all(is_nonneg(a - b) for b in values)), None)
        if top is None or not is_nonneg(claim - top):
            failures.append(f"{case.label}: max over ∂|σ| exceeds k_i k₃|v|²")
        elif is_zero(claim - top):
            eq_cases += 1
        else:
            strict_cases += 1
        for zeta, value in branches:
            if not is_nonneg(paper - value):
                bound_ok = False
                failures.append(f"{case.label}, ζ = {zeta}: the paper's bracketed bound is below V̂°")
        for bracket, cm in pairs:
            if not is_nonneg(cm - bracket):
                pairs_ok = False
                failures.append(f"{case.label}: the bracket {bracket} is not ≤ {cm}")
    derivative_keys = {d.expr for d in derived}
    if pair_keys != derivative_keys:
        failures.append(
            "the paper's pairing gives the conditions "
            + ", ".join(str(k) for k in sorted(pair_keys, key=sp.default_sort_key))
            + " ≥ 0, not the derived ones"
        )
    rows = [
        (
            "\\text{paper: } \\mathrm{sign}(v) f_v \\le -k_v|v| - |\\mathrm{dz}(\\phi)| \\text{ on } \\hat R",
            r"\text{holds in every piece}" if fv_ok else r"\text{fails}",
        ),
        (
            "\\text{paper: } \\max_{\\zeta}(-k_i k_3 |v|^2\\zeta) = k_i k_3|v|^2",
            f"\\text{{equality in {eq_cases} pieces, strict }} < \\text{{ in {strict_cases} (}}\\sigma v > 0\\text{{)}}",
        ),
        (
            "\\text{paper's bracketed bound} \\ge \\hat V^\\circ",
            r"\text{holds in every piece}" if bound_ok else r"\text{fails}",
        ),
        (
            "\\text{pairing: bracket} \\le \\text{coefficient} \\cdot \\text{monomial}",
            (r"\text{holds; the coefficients give exactly the derived conditions}" if pairs_ok else r"\text{fails}"),
        ),
    ]
    return rows, failures, eq_cases, strict_cases
