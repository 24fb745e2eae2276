"""``coordinates`` — eq. (CoC) is nonsingular iff ``k_i ≠ 0`` and maps eq. (xPhDot) onto eq. (xDot), ``x′ ∈ A x − b SGN(v)``, for every selection (paper §II)."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .._model import symbolic as _symbolic
from . import _fastpoly as fp
from ._base import Erratum, Obligation, Outcome
from ._decide import G, is_zero, latex
from ._shared import _mat

__all__ = ["Coordinates", "OBLIGATIONS"]


@dataclass(frozen=True)
class CoordinatesSubject:
    """``T`` (x = T z), its package inverse, and both forms of the dynamics."""

    T: sp.ImmutableMatrix
    T_inv: sp.ImmutableMatrix
    A_z: sp.ImmutableMatrix
    b_z: sp.ImmutableMatrix
    A: sp.ImmutableMatrix
    b: sp.ImmutableMatrix
    z: sp.ImmutableMatrix
    w: sp.Symbol
    k_i: sp.Symbol


class Coordinates(Obligation):
    id = "coordinates"
    paper = "eq. (CoC), eq. (xDot)"
    statement = "x = T z is nonsingular iff k_i ≠ 0 and maps z' = A_z z - b w onto x' = A x - b w for every selection w of SGN(v)"
    method = "sympy identity (expand(T(A_z z - b w) - (A T z - b w)) == 0 for symbolic w; factorisation of det T)"
    errata = (
        Erratum(
            where="§IV-A, after eq. (CoC)",
            paper_says="the change of coordinates is nonsingular thanks to Assumption 1 (k_i, k_p strictly positive)",
            correct="det T = -k_i², so T is nonsingular iff k_i ≠ 0; k_p plays no role",
            checked_by="coordinates",
        ),
    )

    def derive(self) -> CoordinatesSubject:
        g = G()
        return CoordinatesSubject(
            T=_mat(_symbolic.T(g)),
            T_inv=_mat(_symbolic.T_inv(g)),
            A_z=_mat(_symbolic.A_z(g)),
            b_z=_mat(_symbolic.b(g)),
            A=_mat(_symbolic.A(g)),
            b=_mat(_symbolic.b(g)),
            z=_mat([g.e_i, g.s, g.v]),
            w=sp.Symbol("w", real=True),
            k_i=g.k_i,
        )

    def verify(self, subject: CoordinatesSubject) -> Outcome:
        S = subject
        det = fp.factored_det(S.T)
        const, factors = fp.factor_list(det)
        details = [("T", latex(S.T)), ("\\det T", latex(det))]
        if const == 0 or any(not is_zero(f - S.k_i) and not is_zero(f + S.k_i) for f, _ in factors) or not factors:
            return Outcome.fail(f"det T = {det} does not vanish exactly when {S.k_i} = 0", tuple(details))
        eye = sp.eye(3)
        for name, prod in (("T_inv·T", S.T_inv * S.T), ("T·T_inv", S.T * S.T_inv)):
            residual = (prod - eye).applyfunc(lambda e: fp.cancel(e))
            if not all(is_zero(e) for e in residual):
                return Outcome.fail(f"{name} - I = {residual.tolist()} is not zero", tuple(details))
        if list(S.T[2, :]) != [0, 0, 1]:
            return Outcome.fail(f"T changes v (third row {list(S.T[2, :])}), so SGN(v) would not carry over", tuple(details))
        x = S.T * S.z
        residual = S.T * (S.A_z * S.z - S.b_z * S.w) - (S.A * x - S.b * S.w)
        residual = residual.applyfunc(sp.expand)
        if not all(is_zero(e) for e in residual):
            return Outcome.fail(
                f"T(A_z z - b w) - (A T z - b w) = {list(residual)} is not identically zero", tuple(details)
            )
        details += [
            ("x = T z", latex(x)),
            ("T A_z T^{-1}", latex((S.T * S.A_z * S.T_inv).applyfunc(fp.cancel))),
            ("A", latex(S.A)),
            ("T b", latex(S.T * S.b_z)),
            ("T(A_z z - b w) = A\\,Tz - b\\,w", latex((S.T * (S.A_z * S.z - S.b_z * S.w)).applyfunc(sp.expand))),
        ]
        return Outcome(True, "det T = -k_i^2 and the vector fields agree for symbolic w", tuple(details))


OBLIGATIONS = (Coordinates,)
