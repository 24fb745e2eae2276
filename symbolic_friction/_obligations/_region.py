"""Lemma 3's region ``R = {v(φ − sign(v) f_c) ≥ 0}`` and ``V̂`` of eq. (Vhat) for symbolic constants ``k₁ … k₄``: the symbols, the region, the case pieces inside and outside it, and the subject of ``lemma3.hatV_bounds``; used by :mod:`.lemma3`, :mod:`.prop1` and :mod:`.certificate`."""

from __future__ import annotations

import functools
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.lyapunov import R_margin, V_hat
from ._statements import lemma3_hatV_bounds, lemma3_V_bounds
from ._decide import Undecided, decide, resolve_piecewise
from ._inequalities import Case


@functools.lru_cache(maxsize=None)
def k_symbols() -> tuple[sp.Symbol, sp.Symbol, sp.Symbol, sp.Symbol]:
    """Positive symbols ``k_1 … k_4`` of eq. (Vhat)."""
    return tuple(sp.symbols("k_1 k_2 k_3 k_4", positive=True))  # type: ignore[return-value]


def vhat_expression(g: _symbolic.Gains, k: tuple[Any, Any, Any, Any]) -> sp.Expr:
    """The package's ``V̂`` of eq. (Vhat) (:func:`symbolic_friction._model.lyapunov.V_hat`), for symbolic gains."""
    return V_hat(g, [g.sigma, g.phi, g.v], k)


def _fmt_failures(failures: list[str]) -> str:
    head = failures[:6]
    more = f" (and {len(failures) - 6} more)" if len(failures) > 6 else ""
    return "; ".join(head) + more


@dataclass(frozen=True)
class RSubject:
    """What ``lemma3.R`` checks.

    Attributes
    ----------
    sigma, phi, v, f_c : Symbol
    region : Expr
        ``R = {region ≥ 0}``; the paper's ``v(φ - sign(v) f_c)``.
    sgn_lo, sgn_hi : Expr
        ``f_c SGN(v) = [sgn_lo, sgn_hi]`` (Piecewise in ``v``).
    minimizer : Expr
        The closed-form minimiser used by ``V`` (``_lyapunov.V``):
        ``f_c sign(v)`` if ``v ≠ 0``, else ``sat_{f_c}(φ)``.
    P : Matrix
        ``P`` of eq. (lyapLikeP).
    dz : Expr
        ``dz_{f_c}(φ)``.
    dist2 : Expr
        ``|x|²_𝒜`` of eq. (distFromA).
    c1, c2 : Expr
        Claimed constants of eq. (VandR).
    assumption : tuple of (Symbol, Expr)
        Substitution encoding Assumption 1 (``k_v = (k_i + δ)/k_p``).
    cases : tuple of Case
        Split of ``(φ, v)`` (``σ`` stays a free real symbol).
    """

    sigma: sp.Symbol
    phi: sp.Symbol
    v: sp.Symbol
    f_c: sp.Symbol
    region: sp.Expr
    sgn_lo: sp.Expr
    sgn_hi: sp.Expr
    minimizer: sp.Expr
    P: sp.Matrix
    dz: sp.Expr
    dist2: sp.Expr
    c1: sp.Expr
    c2: sp.Expr
    assumption: tuple[tuple[sp.Symbol, sp.Expr], ...]
    cases: tuple[Case, ...]
    statement: Any = lemma3_V_bounds
    """The conclusion Proposition 1 uses (:func:`._statements.lemma3_V_bounds`)."""


def region_R(g: _symbolic.Gains) -> sp.Expr:
    """``R = {region_R ≥ 0}``: the package's margin ``v(φ - sign(v) f_c)`` (:func:`symbolic_friction._model.lyapunov.R_margin`)."""
    return R_margin(g, [g.sigma, g.phi, g.v])


def in_R(region: sp.Expr) -> bool | None:
    """Whether a point (or a parametrised piece) lies in ``R``, given ``region_R`` there; ``None`` if undecided.

    Raises
    ------
    Undecided
        If a branch of ``sign(v)`` cannot be decided.
    """
    return decide(sp.GreaterThan(resolve_piecewise(region), 0))


def pieces_of(cases: Sequence[Case], region: sp.Expr, *, inside: bool, failures: list[str]) -> Iterator[Case]:
    """The pieces that lie in ``R`` (``inside``) or in ``R̂ = ℝ³ \\ R``, in order.

    A piece whose membership cannot be decided is skipped and recorded in
    ``failures``, so the calling obligation fails instead of guessing.
    """
    name = "R" if inside else "R̂"
    for case in cases:
        try:
            member = in_R(case(region))
        except Undecided as exc:
            failures.append(f"{case.label}: {exc}")
            continue
        if member is None:
            failures.append(f"cannot decide whether the piece {case.label} lies in {name}")
            continue
        if member == inside:
            yield case


@dataclass(frozen=True)
class HatVBoundsSubject:
    """What ``lemma3.hatV_bounds`` checks.

    Attributes
    ----------
    sigma, phi, v, f_c : Symbol
    k : tuple of Symbol
        ``k₁ … k₄`` (positive).
    Vhat : Expr
        eq. (Vhat).
    K : Matrix
        ``K`` with ``V̂ = ½wᵀKw`` (``_lyapunov.vhat_matrix_entries``).
    w : tuple of Expr
        ``(|σ|, |dz(φ)|, |v|)``.
    dist2 : Expr
        ``|x|²_𝒜``.
    definiteness : Expr
        The stated condition for ``K ≻ 0`` (``k₁k₄ - k₃² > 0``, from
        :mod:`._kconditions`).
    c1_hat, c1_hat_eig, c2_hat : Expr
        ``½min(k₁,k₂,k₄)`` (nonnegative ``w``), ``½λ_min(K)`` and ``½λ_max(K)``.
    cases : tuple of Case
        Split of ``φ`` against ``±f_c``.
    """

    sigma: sp.Symbol
    phi: sp.Symbol
    v: sp.Symbol
    f_c: sp.Symbol
    k: tuple[sp.Symbol, sp.Symbol, sp.Symbol, sp.Symbol]
    Vhat: sp.Expr
    K: sp.Matrix
    w: tuple[sp.Expr, sp.Expr, sp.Expr]
    dist2: sp.Expr
    definiteness: sp.Expr
    c1_hat: sp.Expr
    c1_hat_eig: sp.Expr
    c2_hat: sp.Expr
    cases: tuple[Case, ...]
    statement: Any = lemma3_hatV_bounds
    """The conclusion Proposition 1 uses (:func:`._statements.lemma3_hatV_bounds`)."""
