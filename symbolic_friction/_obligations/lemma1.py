"""Lemma 1 (uniqueness of solutions of eq. (xPhDot)): the friction term of
``d/dt |δ|²/2`` is never positive.

For two solutions ``z_1, z_2`` and ``δ = z_1 - z_2`` the proof bounds
``δᵀδ' ≤ λ_δ|δ|² + M(t)`` with

.. math::

    M(t) = \\max_{f_1 \\in f_c\\mathrm{SGN}(z_{1,v}),\\ f_2 \\in f_c\\mathrm{SGN}(z_{1,v}-\\delta_v)}
           \\delta_v (f_2 - f_1),

and states ``M(t) ≤ 0`` "by trivial inspection of all the cases".  The
obligation derives the friction term from the package's ``A_z`` and ``b``
and inspects all nine sign cases.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import sympy as sp

from .._model import symbolic as _symbolic
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, Undecided, is_zero, latex, sign_classes, sign_of, vertices
from ._shared import sgn_sets

__all__ = ["Lemma1Uniqueness", "OBLIGATIONS"]


@dataclass(frozen=True)
class UniquenessSubject:
    """The inclusion's data and the SGN map."""

    A_z: sp.ImmutableMatrix
    b: sp.ImmutableMatrix
    sgn: dict


class Lemma1Uniqueness(Obligation):
    id = "lemma1.uniqueness"
    paper = "Lemma 1, proof (M(t) ≤ 0)"
    statement = "δᵀ(F(z_1) - F(z_2)) = δᵀA_δδ + δ_v(f_2 - f_1), and M(t) = max δ_v(f_2 - f_1) ≤ 0 in all 9 sign cases of z_{1,v} and z_{1,v} - δ_v"
    method = "sympy identity for the friction term; exhaustive case split (9 cases), maximum of a multi-affine function at the vertices of the SGN sets, sign-definite decomposition"

    def derive(self) -> UniquenessSubject:
        g = G()
        return UniquenessSubject(A_z=sp.ImmutableMatrix(_symbolic.A_z(g)), b=sp.ImmutableMatrix(_symbolic.b(g)), sgn=sgn_sets())

    def verify(self, subject: UniquenessSubject) -> Outcome:
        S = subject
        z1 = sp.Matrix(sp.symbols("z_1e z_1s z_1v", real=True))
        z2 = sp.Matrix(sp.symbols("z_2e z_2s z_2v", real=True))
        w1, w2 = sp.symbols("w_1 w_2", real=True)
        delta = z1 - z2
        # Friction part of δᵀδ': everything in δᵀ(F(z_1) - F(z_2)) beyond the linear term δᵀ A_z δ.
        friction = fp.expand((delta.T * ((S.A_z * z1 - S.b * w1) - (S.A_z * z2 - S.b * w2)))[0] - (delta.T * S.A_z * delta)[0])
        f_c = S.b[2]
        paper_form = sp.expand(delta[2] * (f_c * w2 - f_c * w1))  # δ_v (f_2 - f_1) with f_j = f_c w_j
        details = [("\\delta^T(F(z_1)-F(z_2)) - \\delta^T A_\\delta \\delta", latex(fp.factor(friction)))]
        if not is_zero(friction - paper_form):
            return Outcome.fail(f"the friction term is {fp.factor(friction)}, not δ_v(f_2 - f_1) = {fp.factor(paper_form)}", tuple(details))
        if sp.Poly(friction, w1, w2).degree(w1) > 1 or sp.Poly(friction, w1, w2).degree(w2) > 1:
            return Outcome.fail(f"the friction term {friction} is not multi-affine in the selections")
        # z_{1,v} = a and z_{2,v} = z_{1,v} - δ_v = bb, each of sign 1, 0 or -1
        for (_, s1, a), (_, s2, bb) in itertools.product(sign_classes("p"), sign_classes("q")):
            case = {z1[2]: a, z2[2]: bb}
            h = friction.xreplace(case)  # as subs(case) gives it (the values hold no z), without its bookkeeping
            # h is multi-affine in (w_1, w_2), so its maximum over the product of
            # SGN sets is attained at a pair of vertices: checking those is exhaustive.
            try:
                values = [h.xreplace({w1: v1, w2: v2}) for v1 in vertices(S.sgn[s1]) for v2 in vertices(S.sgn[s2])]
            except Undecided as exc:
                return Outcome.fail(f"case sign(z_1v) = {s1}, sign(z_1v - δ_v) = {s2}: {exc}", tuple(details))
            signs = [sign_of(v) for v in values]
            label = f"\\operatorname{{sign}} z_{{1,v}} = {s1},\\ \\operatorname{{sign}}(z_{{1,v}}-\\delta_v) = {s2}"
            if any(s is None for s in signs):
                bad = values[signs.index(None)]
                return Outcome.fail(
                    f"case sign(z_1v) = {s1}, sign(z_1v - δ_v) = {s2}: cannot decide the sign of the vertex value {bad}",
                    tuple(details),
                )
            if any(s == 1 for s in signs):
                bad = values[signs.index(1)]
                return Outcome.fail(
                    f"case sign(z_1v) = {s1}, sign(z_1v - δ_v) = {s2} (z_1v = {a}, z_2v = {bb}): "
                    f"M(t) ≥ {fp.factor(bad)} > 0",
                    tuple(details),
                )
            shown = ", ".join(sorted({latex(fp.factor(v)) for v in values}))
            details.append((label, f"M = \\max\\{{{shown}\\}} \\le 0"))
        return Outcome(True, "M(t) ≤ 0 in all nine sign cases", tuple(details))


OBLIGATIONS = (Lemma1Uniqueness,)
