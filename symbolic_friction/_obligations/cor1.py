"""Corollary 1 (ISS from the inflation ``ρ_v``) and its proof: the inflated
sign map of eq. (perturbed) and the two distances of the proof.

.. math::

    \\mathrm{SGN}_{\\rho}(v) = \\begin{cases}
        [\\mathrm{sign}(v) - |\\rho|,\\ \\mathrm{sign}(v) + |\\rho|] & |v| > |\\rho| \\\\
        [-1 - |\\rho|,\\ 1 + |\\rho|] & |v| \\le |\\rho|
    \\end{cases}
    \\;=\\; \\mathrm{SGN}(v + |\\rho|\\mathbb B) + |\\rho|\\mathbb B,

and, with ``|z|²_𝒜 = s² + v² + dz_{f_c/k_i}(e_i)²`` and ``|z|² = s² + v² + e_i²``,

.. math::

    |z|_{\\mathcal A} \\le |z|,\\qquad |z|^2 \\le 2|z|^2_{\\mathcal A} + 2(f_c/k_i)^2
    \\ \\Rightarrow\\ |z| \\le \\sqrt2\\,(|z|_{\\mathcal A} + f_c/k_i).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.attractor import attractor_bound_z, squared_distance_z
from . import _fastpoly as fp
from ._base import Erratum, Obligation, Outcome
from ._decide import G, Undecided, decide, is_zero, latex, resolve_piecewise
from ._inequalities import Case, is_nonneg, label_latex, line_cases, rows_latex, sign_cases
from ._shared import shared_value

__all__ = ["OBLIGATIONS", "Inflation", "Distances", "InflationSubject", "DistancesSubject"]


def _expand_abs_relations(expr: Any) -> Any:
    """Rewrite ``|y| ⋈ c`` as conditions on ``y`` so that they can be decided piece by piece."""

    def is_abs_rel(e: Any) -> bool:
        return isinstance(e, sp.core.relational.Relational) and (isinstance(e.lhs, sp.Abs) or isinstance(e.rhs, sp.Abs))

    def rewrite(rel: Any) -> Any:
        if isinstance(rel.rhs, sp.Abs) and not isinstance(rel.lhs, sp.Abs):
            rel = rel.reversed
        y, c = rel.lhs.args[0], rel.rhs
        if isinstance(rel, sp.StrictGreaterThan):
            return sp.Or(y > c, y < -c)
        if isinstance(rel, sp.GreaterThan):
            return sp.Or(y >= c, y <= -c)
        if isinstance(rel, sp.StrictLessThan):
            return sp.And(y < c, y > -c)
        if isinstance(rel, sp.LessThan):
            return sp.And(y <= c, y >= -c)
        return rel

    expr = sp.sympify(expr)
    if not expr.has(sp.Abs):  # nothing to rewrite: replace() would walk the whole tree to return it unchanged
        return expr
    return expr.replace(is_abs_rel, rewrite)


def _resolve(expr: Any) -> sp.Expr:
    return resolve_piecewise(_expand_abs_relations(expr))


def _counterexample(expr: sp.Expr) -> dict | None:
    """A point where ``expr < 0`` (exact), searched on a small grid of its symbols."""
    syms = sorted(sp.sympify(expr).free_symbols, key=sp.default_sort_key)
    grid_pos = [sp.Rational(1, 2), 1, 2, 5]
    grid_real = [-2, -1, 0, 1, 2]
    choices = [grid_pos if s.is_positive or s.is_nonnegative else grid_real for s in syms]
    for values in itertools.product(*choices):
        val = sp.sympify(expr).xreplace(dict(zip(syms, values)))
        if val.is_number and val < 0:
            return dict(zip(syms, values))
    return None


# --------------------------------------------------------------------------
# cor1.inflation
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class InflationSubject:
    """What ``cor1.inflation`` checks.

    Attributes
    ----------
    v : Symbol
        The velocity (real).
    r : Symbol
        ``|ρ_v|`` (nonnegative).
    u : Symbol
        Argument of ``SGN`` in its definition.
    sgn_lo, sgn_hi : Expr
        ``SGN(u) = [sgn_lo, sgn_hi]`` (eq. frictionforceSetValued).
    inflated_lo, inflated_hi : Expr
        The paper's ``SGN_ρ(v)`` endpoints (eq. perturbed).
    cases : tuple of Case
        ``r = 0`` with ``v`` against 0, and ``r > 0`` with ``v`` against ``±r``.
    """

    v: sp.Symbol
    r: sp.Symbol
    u: sp.Symbol
    sgn_lo: sp.Expr
    sgn_hi: sp.Expr
    inflated_lo: sp.Expr
    inflated_hi: sp.Expr
    cases: tuple[Case, ...]


class Inflation(Obligation):
    """``cor1.inflation``: ``SGN_ρ(v) = SGN(v + |ρ|𝔹) + |ρ|𝔹`` as intervals."""

    id = "cor1.inflation"
    paper = "eq. (perturbed) and the sentence after it (inflation of SGN), Corollary 1"
    statement = (
        "SGN_ρ(v) of eq. (perturbed) equals the inflation SGN(v + |ρ|𝔹) + |ρ|𝔹 for every v and ρ, "
        "including v = ±|ρ|; for ρ = 0 it is SGN; and SGN_ρ(v) ⊂ [−1 − |ρ|, 1 + |ρ|]"
    )
    errata = (
        Erratum(
            where="Corollary 1, proof, first sentence",
            paper_says="m(t) ≤ 1 + |ρ_v| because, for all t, SGN_ρv(v(t)) ≤ 1 + |ρ_v|",
            correct=(
                "|m(t)| ≤ 1 + |ρ_v| because SGN_ρv(v) ⊂ [−1 − |ρ_v|, 1 + |ρ_v|] for every v; the one-sided bound "
                "as written does not make the input m bounded, which BIBO stability needs"
            ),
            checked_by="cor1.inflation",
        ),
    )
    method = (
        "exhaustive case split (|ρ| = 0 or > 0; v against ±|ρ|, boundaries included) with exact interval "
        "endpoints: SGN of an interval from its pieces u < 0, u = 0, u > 0, then the Minkowski sum"
    )

    def derive(self) -> InflationSubject:
        v = sp.Symbol("v", real=True)
        u = sp.Symbol("u", real=True)
        r = sp.Symbol("r", nonnegative=True)  # r = |ρ_v|
        r_pos = sp.Symbol("r", positive=True)
        nonzero = sp.Ne(u, 0)
        big = sp.Abs(v) > r
        v_at_zero = sign_cases(v, "v", "t_v")
        v_at_r = line_cases(v, [-r_pos, r_pos], name="v", beyond="t_v", weights=("p_v", "q_v"), labels=["-|ρ|", "|ρ|"])
        cases = [Case(f"|ρ| = 0, {c.label}", ((r, sp.Integer(0)),) + c.values, c.slacks) for c in v_at_zero]
        for c in v_at_r:
            values = dict(c.values)
            r_value = values.pop(r_pos, r_pos)  # the open piece |v| < |ρ| parametrises |ρ| itself
            slacks = c.slacks if r_value != r_pos else (r_pos,) + c.slacks
            cases.append(Case(f"|ρ| > 0, {c.label}", ((r, r_value),) + tuple(values.items()), slacks))
        return InflationSubject(
            v=v,
            r=r,
            u=u,
            sgn_lo=sp.Piecewise((sp.sign(u), nonzero), (-1, True)),
            sgn_hi=sp.Piecewise((sp.sign(u), nonzero), (1, True)),
            inflated_lo=sp.Piecewise((sp.sign(v) - r, big), (-1 - r, True)),
            inflated_hi=sp.Piecewise((sp.sign(v) + r, big), (1 + r, True)),
            cases=tuple(cases),
        )

    def verify(self, subject: InflationSubject) -> Outcome:
        s = subject
        failures: list[str] = []
        rows: list[str] = []
        t = sp.Symbol("t_u", positive=True)
        for case in s.cases:
            lo, hi = case(s.v - s.r), case(s.v + s.r)  # v + |ρ|𝔹 = [lo, hi]
            try:
                pieces = []  # SGN over the parts of [lo, hi] in u < 0, u = 0, u > 0
                for where, u_val, meets in (
                    ("u < 0", -t, decide(sp.StrictLessThan(lo, 0))),
                    ("u = 0", sp.Integer(0), decide(sp.And(sp.LessThan(lo, 0), sp.GreaterThan(hi, 0)))),
                    ("u > 0", t, decide(sp.StrictGreaterThan(hi, 0))),
                ):
                    if meets is None:
                        raise Undecided(f"cannot decide whether v + |ρ|𝔹 meets {where}")
                    if not meets:
                        continue
                    a, b = (_resolve(e.xreplace({s.u: u_val})) for e in (s.sgn_lo, s.sgn_hi))
                    if a.has(t) or b.has(t):
                        raise Undecided(f"SGN is not constant on {where}")
                    pieces.append(sp.Interval(a, b))
                union = sp.Union(*pieces)
                if not isinstance(union, (sp.Interval, sp.FiniteSet)) or union is sp.S.EmptySet:
                    raise Undecided(f"SGN(v + |ρ|𝔹) = {union} is not an interval")
                a, b = (union.inf, union.sup)
                want_lo, want_hi = a - case.value(s.r), b + case.value(s.r)
                got_lo, got_hi = (_resolve(case(_expand_abs_relations(e))) for e in (s.inflated_lo, s.inflated_hi))
            except Undecided as exc:
                failures.append(f"{case.label}: {exc}")
                continue
            if not (is_zero(got_lo - want_lo) and is_zero(got_hi - want_hi)):
                failures.append(
                    f"{case.label}: SGN_ρ(v) = [{got_lo}, {got_hi}] but SGN(v + |ρ|𝔹) + |ρ|𝔹 = [{want_lo}, {want_hi}]"
                )
                continue
            # the proof of Corollary 1 needs the input m(t) ∈ SGN_ρ(v(t)) bounded: |m(t)| ≤ 1 + |ρ|
            r_val = case.value(s.r)
            if not (is_nonneg(want_lo + 1 + r_val) and is_nonneg(1 + r_val - want_hi)):
                failures.append(f"{case.label}: SGN_ρ(v) = [{want_lo}, {want_hi}] is not inside [−1 − |ρ|, 1 + |ρ|]")
                continue
            rows.append(f"{label_latex(case.label)}: [{latex(want_lo)}, {latex(want_hi)}]")
        details = (("\\mathrm{SGN}(v + |\\rho|\\mathbb B) + |\\rho|\\mathbb B", rows_latex(rows)),)
        if failures:
            return Outcome.fail("; ".join(failures[:6]), details)
        return Outcome(True, f"{len(s.cases)} pieces, endpoints equal exactly", details)


# --------------------------------------------------------------------------
# cor1.distances
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class DistancesSubject:
    """What ``cor1.distances`` checks.

    Attributes
    ----------
    e_i, s, v : Symbol
        The state ``z`` (real).
    f_c, k_i : Symbol
        Positive; the attractor is ``|e_i| ≤ f_c/k_i``.
    dist2 : Expr
        ``|z|²_𝒜 = s² + v² + dz_{f_c/k_i}(e_i)²``.
    norm2 : Expr
        ``|z|² = s² + v² + e_i²``.
    bound2 : Expr
        ``2|z|²_𝒜 + 2(f_c/k_i)²``.
    offset : Expr
        ``f_c/k_i`` in ``|z| ≤ √2(|z|_𝒜 + offset)``.
    cases : tuple of Case
        ``e_i`` against ``±f_c/k_i``.
    """

    e_i: sp.Symbol
    s: sp.Symbol
    v: sp.Symbol
    f_c: sp.Symbol
    k_i: sp.Symbol
    dist2: sp.Expr
    norm2: sp.Expr
    bound2: sp.Expr
    offset: sp.Expr
    cases: tuple[Case, ...]


class Distances(Obligation):
    """``cor1.distances``: ``|z|_𝒜 ≤ |z|`` and ``|z|² ≤ 2|z|²_𝒜 + 2(f_c/k_i)²``."""

    id = "cor1.distances"
    paper = "Corollary 1, proof (the two distances before eq. KL+N)"
    statement = (
        "|z|_𝒜 ≤ |z| and |z|² ≤ 2|z|²_𝒜 + 2(f_c/k_i)² for every z, hence |z| ≤ √2(|z|_𝒜 + f_c/k_i)"
    )
    method = (
        "exhaustive case split of e_i against ±f_c/k_i (|e_i| ≥ f_c/k_i and |e_i| < f_c/k_i); "
        "sign-definite decomposition (positive monomials, or a PSD Gram matrix in β = f_c/k_i)"
    )

    def derive(self) -> DistancesSubject:
        g = G()
        beta = attractor_bound_z(g)
        # the package's |z|²_𝒜, the distance the ISS estimate and the cross-check measure
        dist2 = shared_value(squared_distance_z, g, [g.e_i, g.s, g.v])
        return DistancesSubject(
            e_i=g.e_i,
            s=g.s,
            v=g.v,
            f_c=g.f_c,
            k_i=g.k_i,
            dist2=dist2,
            norm2=g.s**2 + g.v**2 + g.e_i**2,
            bound2=2 * dist2 + 2 * beta**2,
            offset=beta,
            cases=tuple(
                line_cases(g.e_i, [-beta, beta], name="e_i", beyond="t_e", weights=("p_e", "q_e"), labels=["-f_c/k_i", "f_c/k_i"])
            ),
        )

    def verify(self, subject: DistancesSubject) -> Outcome:
        s = subject
        failures: list[str] = []
        rows: list[str] = []
        # f_c and k_i enter only through β = f_c/k_i; f_c = β k_i is a bijective reparametrisation
        beta = sp.Symbol("beta", positive=True)
        rep = {s.f_c: beta * s.k_i}
        for case in s.cases:
            try:
                dist2, norm2, bound2 = (fp.cancel(_resolve(case(e)).xreplace(rep)) for e in (s.dist2, s.norm2, s.bound2))
            except Undecided as exc:
                failures.append(f"{case.label}: {exc}")
                continue
            for label, gap in (("|z|_𝒜² ≤ |z|²", norm2 - dist2), ("|z|² ≤ 2|z|_𝒜² + 2(f_c/k_i)²", bound2 - norm2)):
                if is_nonneg(gap):
                    continue
                witness = _counterexample(gap)
                extra = f"; it is negative at {witness}" if witness else ""
                failures.append(f"{case.label}: {label} not shown (gap {fp.factor(gap)}){extra}")
            rows.append(
                f"{label_latex(case.label)}: |z|^2 - |z|_{{\\mathcal A}}^2 = {latex(fp.factor(norm2 - dist2))},\\ "
                f"2|z|_{{\\mathcal A}}^2 + 2\\beta^2 - |z|^2 = {latex(fp.factor(bound2 - norm2))}"
            )
        # |z|² ≤ 2D² + 2β² ≤ 2(D + β)² for D = |z|_𝒜 ≥ 0
        d = sp.Symbol("D", nonnegative=True)
        offset = fp.cancel(sp.sympify(s.offset).xreplace(rep))
        last = 2 * (d + offset) ** 2 - (2 * d**2 + 2 * offset**2)
        if not is_zero(offset - beta) or not is_nonneg(last):
            failures.append(f"2(|z|_𝒜 + {s.offset})² ≥ 2|z|_𝒜² + 2(f_c/k_i)² not shown (gap {sp.expand(last)})")
        details = (
            ("\\text{pieces } (\\beta = f_c/k_i)", rows_latex(rows)),
            ("2(|z|_{\\mathcal A} + \\beta)^2 - 2|z|_{\\mathcal A}^2 - 2\\beta^2", latex(sp.expand(last))),
        )
        if failures:
            return Outcome.fail("; ".join(failures[:6]), details)
        return Outcome(True, f"{len(s.cases)} pieces of e_i", details)


OBLIGATIONS = (Inflation, Distances)
