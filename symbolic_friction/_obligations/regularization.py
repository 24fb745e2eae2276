"""``regularization`` — every branch of eq. (basic)/(vDot) is a selection of the inclusion eq. (xPhDot) (paper §II)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, Undecided, affine_image, decide, interval_partitions_reals, is_zero, latex, sign_of
from ._shared import _mat, sgn_sets

__all__ = ["Regularization", "OBLIGATIONS"]


@dataclass(frozen=True)
class Branch:
    """One branch of eq. (vDot): the sign of ``v``, the set of ``u`` and ``v'``."""

    label: str
    v_sign: int
    u_set: sp.Set
    vdot: sp.Expr
    tex: str = ""


@dataclass(frozen=True)
class RegularizationSubject:
    """Eq. (basic) as printed in the paper, and the package's inclusion data."""

    ei_dot: sp.Expr
    s_dot: sp.Expr
    u_of_z: sp.Expr
    branches: tuple[Branch, ...]
    A_z: sp.ImmutableMatrix
    b: sp.ImmutableMatrix
    z: sp.ImmutableMatrix
    u: sp.Symbol
    sgn: dict


class Regularization(Obligation):
    id = "regularization"
    paper = "eqs. (basic), (vDot), (xPhDot)"
    statement = "each branch of the discontinuous model (basic) is a selection of the inclusion (xPhDot), and the branches partition the state space"
    method = "exhaustive case split over the five branches; the selection w solving u - f_c w = v' is checked to lie in SGN(v) (affine image of the branch's u-interval)"

    def derive(self) -> RegularizationSubject:
        g = G()
        u = sp.Symbol("u", real=True)
        f_c = g.f_c
        branches = (
            Branch("v > 0", 1, sp.S.Reals, u - f_c, "v > 0"),
            Branch("v = 0, u ≥ f_c", 0, sp.Interval(f_c, sp.oo), u - f_c, "v = 0,\\ u \\ge f_c"),
            Branch("v = 0, |u| < f_c", 0, sp.Interval.open(-f_c, f_c), sp.Integer(0), "v = 0,\\ |u| < f_c"),
            Branch("v = 0, u ≤ -f_c", 0, sp.Interval(-sp.oo, -f_c), u + f_c, "v = 0,\\ u \\le -f_c"),
            Branch("v < 0", -1, sp.S.Reals, u + f_c, "v < 0"),
        )
        return RegularizationSubject(
            ei_dot=g.s,
            s_dot=g.v,
            u_of_z=-g.k_p * g.s - g.k_v * g.v - g.k_i * g.e_i,
            branches=branches,
            A_z=_mat(_symbolic.A_z(g)),
            b=_mat(_symbolic.b(g)),
            z=_mat([g.e_i, g.s, g.v]),
            u=u,
            sgn=sgn_sets(),
        )

    def verify(self, subject: RegularizationSubject) -> Outcome:
        S = subject
        rhs = S.A_z * S.z
        if not (is_zero(rhs[0] - S.ei_dot) and is_zero(rhs[1] - S.s_dot) and S.b[0] == 0 and S.b[1] == 0):
            return Outcome.fail(f"the first two rows of (xPhDot) {list(rhs[:2])} differ from e_i' = {S.ei_dot}, s' = {S.s_dot}")
        if not is_zero(rhs[2] - S.u_of_z):
            return Outcome.fail(f"the third row of A_z z is {rhs[2]}, not u = {S.u_of_z}")
        f = S.b[2]
        if sign_of(f) != 1:
            return Outcome.fail(f"the friction level b_3 = {f} is not positive")
        w = sp.Symbol("w", real=True)
        details = [("u", latex(S.u_of_z))]
        for br in S.branches:
            # u - f_c w = v' is affine in w: its one solution when the slope is nonzero (no general solver needed)
            eq = sp.expand(S.u - f * w - br.vdot)
            slope = sp.expand(sp.diff(eq, w))
            if sp.diff(slope, w) != 0 or sign_of(slope) not in (1, -1):
                return Outcome.fail(f"branch '{br.label}': no unique selection w with u - f_c w = {br.vdot}")
            w_sel = fp.cancel(-eq.subs(w, 0) / slope)
            allowed = S.sgn[br.v_sign]
            try:
                if isinstance(allowed, sp.FiniteSet):
                    ok = any(is_zero(w_sel - a) for a in allowed.args)
                    image: Any = w_sel
                elif is_zero(sp.diff(w_sel, S.u)):
                    image = w_sel
                    ok = decide(sp.And(sp.Le(allowed.start, w_sel), sp.Le(w_sel, allowed.end))) is True
                else:
                    if not (br.u_set.start.is_finite and br.u_set.end.is_finite):
                        raise Undecided(f"w = {w_sel} is unbounded on u ∈ {br.u_set}")
                    closure = sp.Interval(br.u_set.start, br.u_set.end)
                    image = affine_image(w_sel, S.u, closure)
                    ok = decide(sp.And(sp.Le(allowed.start, image.start), sp.Le(image.end, allowed.end))) is True
            except Undecided as exc:
                return Outcome.fail(f"branch '{br.label}': {exc}", tuple(details))
            if not ok:
                return Outcome.fail(
                    f"branch '{br.label}': v' = {br.vdot} needs w = {w_sel} (range {image}), not in SGN = {allowed}",
                    tuple(details),
                )
            details.append((f"{br.tex}:\\ \\dot v = {latex(br.vdot)} = u - f_c w", f"w = {latex(w_sel)} \\in {latex(allowed)}"))
        # The branches must cover every (v, u) exactly once: v > 0, v < 0 whole lines, v = 0 a partition of u.
        for sgn_v in (1, -1):
            sets = [br.u_set for br in S.branches if br.v_sign == sgn_v]
            if sets != [sp.S.Reals]:
                return Outcome.fail(f"v with sign {sgn_v} is covered by the u-sets {sets}, not exactly once by all of ℝ")
        stick = [br.u_set for br in S.branches if br.v_sign == 0]
        ok, why = interval_partitions_reals(stick)
        if not ok:
            return Outcome.fail(f"the v = 0 branches do not partition u ∈ ℝ: {why}", tuple(details))
        return Outcome(True, "all five branches are selections; the v = 0 branches partition ℝ", tuple(details))


OBLIGATIONS = (Regularization,)
