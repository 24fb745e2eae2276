"""``distance`` — eq. (distFromA), ``|x|²_𝒜 = σ² + v² + dz(φ)²``, piecewise (paper §II)."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, Undecided, is_zero, latex, minimum_on, phi_classes, resolve_piecewise
from ._shared import attractor_x, distance_squared

__all__ = ["Distance", "OBLIGATIONS"]


@dataclass(frozen=True)
class DistanceSubject:
    """𝒜 in ``x`` coordinates and the package's formula for ``|x|²_𝒜``."""

    attractor: tuple
    formula: sp.Expr
    state: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    f_c: sp.Symbol


class Distance(Obligation):
    id = "distance"
    paper = "eq. (distFromA)"
    statement = "|x|²_𝒜 = inf_{y ∈ 𝒜} |x - y|² = σ² + v² + dz(φ)², on each piece φ < -f_c, |φ| ≤ f_c, φ > f_c"
    method = "exhaustive case split (five classes of φ); exact minimum over the closed interval (endpoints and stationary points) compared with the formula"

    def derive(self) -> DistanceSubject:
        g = G()
        return DistanceSubject(attractor=attractor_x(g), formula=distance_squared(g), state=(g.sigma, g.phi, g.v), f_c=g.f_c)

    def verify(self, subject: DistanceSubject) -> Outcome:
        S = subject
        x = S.state
        y = sp.Symbol("y", real=True)
        free = [i for i, c in enumerate(S.attractor) if isinstance(c, sp.Set)]
        if len(free) != 1:
            return Outcome.fail(f"𝒜 = {S.attractor} does not have exactly one interval component")
        (j,) = free
        fixed_part = sum(((x[i] - c) ** 2 for i, c in enumerate(S.attractor) if i != j), sp.Integer(0))
        details = []
        for label, tex, value, _region in phi_classes(S.f_c, tag="_phi"):
            try:
                inner = minimum_on((value - y) ** 2, y, S.attractor[j])
                claimed = resolve_piecewise(S.formula.subs(x[j], value))
            except Undecided as exc:
                return Outcome.fail(f"piece {label}: {exc}", tuple(details))
            exact = fixed_part + inner
            if not is_zero(exact - claimed):
                return Outcome.fail(
                    f"piece {label} (φ = {value}): inf |x - y|² = {fp.factor(exact)} but the formula gives {fp.factor(claimed)}",
                    tuple(details),
                )
            details.append((
                f"{tex},\\ \\phi = {latex(value)}",
                f"\\inf_{{y\\in\\mathcal A}}|x-y|^2 = {latex(fp.factor(exact))}",
            ))
        return Outcome(True, "the formula equals the exact infimum on every piece", tuple(details))


OBLIGATIONS = (Distance,)
