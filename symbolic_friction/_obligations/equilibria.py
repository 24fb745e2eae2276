"""``equilibria`` — the equilibria of the inclusion are exactly 𝒜, eqs. (Aph) and (A) (paper §II)."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .._model import symbolic as _symbolic
from . import _fastforms as ff
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, Undecided, affine_image, is_zero, latex, sign_of
from ._shared import _mat, attractor_x, attractor_z, sgn_sets

__all__ = ["Equilibria", "OBLIGATIONS"]


@dataclass(frozen=True)
class EquilibriaSubject:
    """The inclusion in both coordinates and 𝒜 in both (eqs. Aph and A)."""

    A: sp.ImmutableMatrix
    b: sp.ImmutableMatrix
    attractor_x: tuple
    A_z: sp.ImmutableMatrix
    b_z: sp.ImmutableMatrix
    attractor_z: tuple
    sgn: dict


def _equilibria_match(M: sp.ImmutableMatrix, b: sp.ImmutableMatrix, target: tuple, sgn: dict, names: tuple[str, ...]):
    """Decide ``{x : 0 ∈ M x - b SGN(x_3)} == target``; return (ok, reason, details)."""
    w = sp.Symbol("w", real=True)
    xs = sp.symbols("x_1:4", real=True)
    X = sp.Matrix(xs)
    details = []
    # v ≠ 0: the only selection is w = sign(v); M x = b w must then force v = 0, a contradiction.
    if is_zero(M.det()):
        return False, f"M = {M.tolist()} is singular, so the v ≠ 0 case is not settled", details
    for sgn_v in (1, -1):
        (wv,) = sgn[sgn_v].args
        sol = M.LUsolve(b * wv).applyfunc(fp.cancel)
        # The unique solution is an equilibrium only if its v really has the sign assumed.
        consistent = sign_of(sgn_v * sol[2])
        if consistent == 1:
            return False, f"x = {list(sol)} is an equilibrium with {names[2]} of sign {sgn_v}", details
        if consistent is None:
            return False, f"cannot exclude an equilibrium with {names[2]} of sign {sgn_v}: {list(sol)}", details
    # v = 0: solve M x = b w for the other two components, w ∈ SGN(0).
    eqs = list(M * X.subs(xs[2], 0) - b * w)
    sols = ff.solve(eqs, xs[:2], dict=True)
    if len(sols) != 1 or set(sols[0]) != set(xs[:2]):
        return False, f"the equilibria with {names[2]} = 0 are not a curve parametrised by w: {sols}", details
    sol = sols[0]
    comps = [sol[xs[0]], sol[xs[1]], sp.Integer(0)]
    for i, (comp, want) in enumerate(zip(comps, target)):
        if isinstance(want, sp.Set):
            image = affine_image(comp, w, sgn[0])
            if not (is_zero(image.start - want.start) and is_zero(image.end - want.end) and type(image) is type(want)
                    and image.left_open == want.left_open and image.right_open == want.right_open):
                return False, f"equilibria have {names[i]} ∈ {image}, but 𝒜 says {want}", details
            details.append((names[i], f"{latex(comp)},\\ w \\in [-1,1] \\;\\Rightarrow\\; {latex(image)}"))
        else:
            if not is_zero(comp - want):
                return False, f"equilibria have {names[i]} = {comp}, but 𝒜 says {want}", details
            details.append((names[i], latex(comp)))
    return True, "", details


class Equilibria(Obligation):
    id = "equilibria"
    paper = "eqs. (Aph), (A); §II-B"
    statement = "the equilibria of the inclusion, {x : 0 ∈ A x - b SGN(v)}, are exactly 𝒜, in x = (σ, φ, v) and in z = (e_i, s, v)"
    method = "exhaustive case split on sign(v): v ≠ 0 gives v = 0 (contradiction); v = 0 solved exactly for w ∈ [-1, 1] and the affine image compared with 𝒜"

    def derive(self) -> EquilibriaSubject:
        g = G()
        return EquilibriaSubject(
            A=_mat(_symbolic.A(g)),
            b=_mat(_symbolic.b(g)),
            attractor_x=attractor_x(g),
            A_z=_mat(_symbolic.A_z(g)),
            b_z=_mat(_symbolic.b(g)),
            attractor_z=attractor_z(g),
            sgn=sgn_sets(),
        )

    def verify(self, subject: EquilibriaSubject) -> Outcome:
        S = subject
        details: list[tuple[str, str]] = []
        for M, b, target, names in (
            (S.A, S.b, S.attractor_x, ("\\sigma", "\\phi", "v")),
            (S.A_z, S.b_z, S.attractor_z, ("e_i", "s", "v")),
        ):
            try:
                ok, why, det = _equilibria_match(M, b, target, S.sgn, names)
            except Undecided as exc:
                ok, why, det = False, str(exc), []
            details += det
            if not ok:
                return Outcome.fail(why, tuple(details))
        return Outcome(True, "no equilibrium with v ≠ 0; with v = 0 the equilibria sweep 𝒜 exactly", tuple(details))


OBLIGATIONS = (Equilibria,)
