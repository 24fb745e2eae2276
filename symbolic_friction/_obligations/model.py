"""Obligations about the model itself (paper §II and §IV-A).

* ``coordinates`` — eq. (CoC) is nonsingular iff ``k_i ≠ 0`` and maps eq.
  (xPhDot) onto eq. (xDot), ``x' ∈ A x - b SGN(v)``, for every selection.
* ``regularization`` — every branch of eq. (basic)/(vDot) is a selection of
  the inclusion eq. (xPhDot).
* ``assumption1.routh`` — Assumption 1 ⇔ ``s³ + k_v s² + k_p s + k_i`` is
  Hurwitz, and that polynomial is ``det(sI - A)``.
* ``equilibria`` — the equilibria of the inclusion are exactly 𝒜, eqs. (Aph)
  and (A).
* ``distance`` — eq. (distFromA), ``|x|²_𝒜 = σ² + v² + dz(φ)²``, piecewise.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.attractor import attractor_bound_x, attractor_bound_z, squared_distance_x
from ._base import Erratum, Obligation, Outcome
from ._decide import (
    G,
    Undecided,
    affine_image,
    decide,
    interval_partitions_reals,
    is_zero,
    latex,
    minimum_on,
    phi_classes,
    resolve_piecewise,
    sign_of,
)

__all__ = [
    "Coordinates",
    "Regularization",
    "Assumption1Routh",
    "Equilibria",
    "Distance",
    "OBLIGATIONS",
    "sgn_sets",
    "attractor_x",
    "attractor_z",
    "distance_squared",
]


def sgn_sets() -> dict[int, sp.Set]:
    """``SGN`` of eq. (frictionforceSetValued), indexed by the sign of ``v``."""
    return {1: sp.FiniteSet(1), 0: sp.Interval(-1, 1), -1: sp.FiniteSet(-1)}


def attractor_x(g: _symbolic.Gains) -> tuple[Any, Any, Any]:
    """𝒜 of eq. (A) as ``(σ, φ, v)`` components: a fixed value or an interval.

    The bound comes from the package's :func:`attractor_bound_x`.
    """
    bound = attractor_bound_x(g)
    return (sp.Integer(0), sp.Interval(-bound, bound), sp.Integer(0))


def attractor_z(g: _symbolic.Gains) -> tuple[Any, Any, Any]:
    """𝒜 of eq. (Aph) as ``(e_i, s, v)`` components (bound from :func:`attractor_bound_z`)."""
    bound = attractor_bound_z(g)
    return (sp.Interval(-bound, bound), sp.Integer(0), sp.Integer(0))


def distance_squared(g: _symbolic.Gains) -> sp.Expr:
    """The package's ``|x|²_𝒜`` (:func:`symbolic_friction._model.attractor.squared_distance_x`) for symbolic gains (checked by ``distance``)."""
    return squared_distance_x(g, [g.sigma, g.phi, g.v])


def _mat(m: Any) -> sp.ImmutableMatrix:
    return sp.ImmutableMatrix(m)


# --------------------------------------------------------------------------- coordinates


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
        det = sp.factor(S.T.det())
        const, factors = sp.factor_list(det)
        details = [("T", latex(S.T)), ("\\det T", latex(det))]
        if const == 0 or any(not is_zero(f - S.k_i) and not is_zero(f + S.k_i) for f, _ in factors) or not factors:
            return Outcome.fail(f"det T = {det} does not vanish exactly when {S.k_i} = 0", tuple(details))
        eye = sp.eye(3)
        for name, prod in (("T_inv·T", S.T_inv * S.T), ("T·T_inv", S.T * S.T_inv)):
            residual = (prod - eye).applyfunc(lambda e: sp.cancel(e))
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
            ("T A_z T^{-1}", latex((S.T * S.A_z * S.T_inv).applyfunc(sp.cancel))),
            ("A", latex(S.A)),
            ("T b", latex(S.T * S.b_z)),
            ("T(A_z z - b w) = A\\,Tz - b\\,w", latex((S.T * (S.A_z * S.z - S.b_z * S.w)).applyfunc(sp.expand))),
        ]
        return Outcome(True, "det T = -k_i^2 and the vector fields agree for symbolic w", tuple(details))


# --------------------------------------------------------------------------- regularization


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
            sols = sp.solve(sp.Eq(S.u - f * w, br.vdot), w)
            if len(sols) != 1:
                return Outcome.fail(f"branch '{br.label}': no unique selection w with u - f_c w = {br.vdot}")
            w_sel = sp.simplify(sols[0])
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


# --------------------------------------------------------------------------- assumption 1 / Routh


@dataclass(frozen=True)
class RouthSubject:
    """``A`` and ``A_z`` with real (unsigned) gains, the paper's polynomial and Assumption 1."""

    A: sp.ImmutableMatrix
    A_z: sp.ImmutableMatrix
    paper_polynomial: sp.Expr
    s: sp.Symbol
    assumption: tuple[sp.Expr, ...]
    gains: tuple[sp.Symbol, ...]


def hurwitz_minors(poly: sp.Poly) -> list[sp.Expr]:
    """Leading principal minors of the Hurwitz matrix of ``poly`` (leading coefficient first)."""
    n = poly.degree()
    coeffs = poly.all_coeffs()  # a_n, ..., a_0

    def a(k: int) -> sp.Expr:
        return coeffs[n - k] if 0 <= k <= n else sp.Integer(0)

    H = sp.Matrix(n, n, lambda i, j: a(n - 2 * (j + 1) + (i + 1)))
    return [sp.factor(H[:k, :k].det()) for k in range(1, n + 1)]


class Assumption1Routh(Obligation):
    id = "assumption1.routh"
    paper = "Assumption 1; §II-B and §III (Routh test)"
    statement = "k_i > 0, k_p > 0, k_v k_p > k_i ⇔ s³ + k_v s² + k_p s + k_i is Hurwitz, and this polynomial is det(sI - A) = det(sI - A_z)"
    method = "charpoly identity; Hurwitz determinants (Routh-Hurwitz theorem) with each direction proved by solving one side for the gains and a sign-definite decomposition of the other"

    def derive(self) -> RouthSubject:
        k_p, k_i, k_v = sp.symbols("k_p k_i k_v", real=True)
        g = _symbolic.Gains(k_p, k_i, k_v, *(getattr(G(), n) for n in ("f_c", "sigma", "phi", "v", "e_i", "s", "delta")))
        s = sp.Symbol("s")
        return RouthSubject(
            A=_mat(_symbolic.A(g)),
            A_z=_mat(_symbolic.A_z(g)),
            paper_polynomial=s**3 + k_v * s**2 + k_p * s + k_i,
            s=s,
            assumption=(k_i, k_p, k_v * k_p - k_i),
            gains=(k_p, k_i, k_v),
        )

    def verify(self, subject: RouthSubject) -> Outcome:
        S = subject
        details: list[tuple[str, str]] = []
        for name, M in (("A", S.A), ("A_z", S.A_z)):
            cp = sp.expand((S.s * sp.eye(3) - M).det())
            if not is_zero(cp - S.paper_polynomial):
                return Outcome.fail(f"det(sI - {name}) = {cp} differs from the paper's {S.paper_polynomial}")
        details.append(("\\det(sI - A) = \\det(sI - A_z)", latex(S.paper_polynomial)))
        poly = sp.Poly(S.paper_polynomial, S.s)
        if sign_of(poly.LC()) != 1:
            return Outcome.fail(f"leading coefficient {poly.LC()} is not positive")
        minors = hurwitz_minors(poly)
        details.append(("\\text{Hurwitz minors } \\Delta_k", latex(sp.Matrix(minors).T)))
        # (⇐) every point of Assumption 1 is (a_1, a_2, a_3) = (positive, positive, positive); solve for the gains.
        alphas = sp.symbols(f"alpha_1:{len(S.assumption) + 1}", positive=True)
        back = sp.solve([e - a for e, a in zip(S.assumption, alphas)], S.gains, dict=True)
        if not back:
            return Outcome.fail(f"cannot solve Assumption 1's expressions {S.assumption} for the gains")
        for sol in back:
            for k, m in enumerate(minors, 1):
                if sign_of(m.subs(sol)) != 1:
                    return Outcome.fail(
                        f"(⇐) fails: on Assumption 1 ({sol}), Hurwitz minor Δ_{k} = {sp.factor(m.subs(sol))} is not shown positive",
                        tuple(details),
                    )
        # (⇒) every Hurwitz point has positive minors d_k; solve the minors for the gains.
        ds = sp.symbols(f"d_1:{len(minors) + 1}", positive=True)
        forth = sp.solve([m - d for m, d in zip(minors, ds)], S.gains, dict=True)
        if not forth:
            return Outcome.fail(f"cannot solve the Hurwitz minors {minors} for the gains")
        for sol in forth:
            for e in S.assumption:
                val = sp.factor(e.subs(sol))
                if sign_of(val) != 1:
                    return Outcome.fail(
                        f"(⇒) fails: with Hurwitz minors d_k > 0 ({sol}), Assumption 1's {e} = {val} is not shown positive",
                        tuple(details),
                    )
        details.append(("\\Leftarrow\\ \\text{on Assumption 1}", latex([sp.factor(m.subs(back[0])) for m in minors])))
        details.append(("\\Rightarrow\\ \\text{from } \\Delta_k = d_k", latex([sp.factor(e.subs(forth[0])) for e in S.assumption])))
        return Outcome(True, "both directions hold for real gains", tuple(details))


# --------------------------------------------------------------------------- equilibria


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
        sol = M.LUsolve(b * wv).applyfunc(sp.cancel)
        # The unique solution is an equilibrium only if its v really has the sign assumed.
        consistent = sign_of(sgn_v * sol[2])
        if consistent == 1:
            return False, f"x = {list(sol)} is an equilibrium with {names[2]} of sign {sgn_v}", details
        if consistent is None:
            return False, f"cannot exclude an equilibrium with {names[2]} of sign {sgn_v}: {list(sol)}", details
    # v = 0: solve M x = b w for the other two components, w ∈ SGN(0).
    eqs = list(M * X.subs(xs[2], 0) - b * w)
    sols = sp.solve(eqs, xs[:2], dict=True)
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


# --------------------------------------------------------------------------- distance


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
                    f"piece {label} (φ = {value}): inf |x - y|² = {sp.factor(exact)} but the formula gives {sp.factor(claimed)}",
                    tuple(details),
                )
            details.append((
                f"{tex},\\ \\phi = {latex(value)}",
                f"\\inf_{{y\\in\\mathcal A}}|x-y|^2 = {latex(sp.factor(exact))}",
            ))
        return Outcome(True, "the formula equals the exact infimum on every piece", tuple(details))


OBLIGATIONS = (Coordinates, Regularization, Assumption1Routh, Equilibria, Distance)
