"""Binding obligations: the code that runs is the model that is proved.

Every other obligation evaluates the package's model functions in the sympy
kind (:mod:`symbolic_friction._model.kinds`).  Certificates, the simulators and the
cross-check evaluate the *same* functions on exact rationals and on float
arrays, and the simulators read the mode table of Claim 1 through their own
fast code.  The obligations here bind those instantiations to the paper:

* ``model.kinds_runtime`` — the three kinds' ``where``, ``clip``, ``sign``
  and ``abs`` are the paper's (``sign(0) = 0``, ``sat``) at and off boundaries.
* ``model.V_runtime`` — ``V`` of eq. (lyapLike): the package's closed form
  equals the paper's ``min_{f ∈ f_c SGN(v)} |(σ, φ - f, v)|²_P`` on all 45
  sign/φ classes, symbolically; and the exact and float evaluations equal
  the symbolic one at a point of every class (and every boundary).
* ``model.hatV_runtime`` — ``V̂`` of eq. (Vhat) equals ``½wᵀKw`` with
  ``w = (|σ|, |dz(φ)|, |v|)``, ``K`` the package's matrix, ``dz`` the
  paper's dead zone; exact and float agree with it.
* ``model.hatV_rate_runtime`` — ``V̂°`` of eq. (hatVdot) on ``R̂`` (the
  cross-check's growth test) equals the Clarke maximum of the gradient of the
  package's ``V̂`` along ``F``, differentiated by sympy.
* ``model.R_runtime`` — membership in ``R = {v(φ - sign(v) f_c) ≥ 0}``
  (Lemma 3), boundary included, in all three kinds.
* ``model.distance_runtime`` and ``model.distance_z_runtime`` — ``|x|²_𝒜``
  (eq. distFromA) and ``|z|²_𝒜`` (Corollary 1) against the paper's piecewise
  ``dz``, in all three kinds.
* ``model.matrices_runtime`` — the float matrices ``A``, ``b``, ``P``, ``T``,
  ``T⁻¹`` the simulators use equal the symbolic ones.
* ``model.modes_runtime`` — the simulators' mode selection (exact
  ``table_row``/``select_mode``, and the
  ``mode_at_rest``/``mode_after_slip`` the event-driven kernel calls, with
  ``φ`` kept as a boundary plus an offset) equals the appendix table that
  ``claim1.cases`` proves, at a point of every one of its 45 classes.
* ``model.P_norm_runtime`` — the ``|y|_P`` written out for speed in the
  certified root search of the event-driven simulator equals the package's
  quadratic form.

"Exhaustive" here means: one exact point in every open class and on every
boundary of the case split, at gains whose float arithmetic is exact (all
values dyadic), compared with ``==``, never with a tolerance.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from .._model import symbolic as _symbolic
from .._model.attractor import dz, squared_distance_x, squared_distance_z
from .._model.coordinates import input_vector, system_matrix, x_to_z, z_to_x
from .._model.lyapunov import V, V_hat, V_hat_rate, in_R, lyapunov_matrix, quadratic_form
from .._model.parameters import Parameters
from .._simulation._kernel import mode_after_slip
from .._simulation.modes import mode_at_rest, select_mode, table_row
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._binding import (
    INSTANCE,
    K_INSTANCE,
    BindingSubject,
    _as_exact,
    _Binding,
    _gain_values,
    _paper_dz,
    _sign,
    _state_cases,
    _x_subject,
    instance_points,
)
from ._decide import G, Undecided, minimum_on, resolve_piecewise, sign_of
from ._inequalities import Case, case_grid, line_cases, sign_cases
from ._shared import derivative, sgn_sets, shared_value
from .claim1 import table_rows

__all__ = [
    "INSTANCE",
    "K_INSTANCE",
    "instance_points",
    "BindingSubject",
    "VRuntime",
    "HatVRuntime",
    "HatVRateRuntime",
    "RRuntime",
    "DistanceRuntime",
    "DistanceZRuntime",
    "MatricesRuntime",
    "ModesRuntime",
    "PNormRuntime",
    "KindsRuntime",
    "OBLIGATIONS",
]


class VRuntime(_Binding):
    id = "model.V_runtime"
    paper = "eq. (lyapLike), eq. (lyapLikeP)"
    statement = (
        "the package's closed-form V (certificates, simulators, cross-check) is "
        "min_{f ∈ f_c SGN(v)} |(σ, φ − f, v)|²_P, in exact, float and symbolic form"
    )

    def derive(self) -> BindingSubject:
        g = G()
        P = _symbolic.P(g)
        w = sp.Symbol("w", real=True)
        sgn = sgn_sets()

        def paper(case: Case) -> sp.Expr:
            vec = (case(g.sigma), case(g.phi) - g.f_c * w, case(g.v))
            # vᵀPv written out: the same expanded form as the matrix product, without sympy's matrix arithmetic
            form = fp.expand(case(sp.Add(*(P[i, j] * vec[i] * vec[j] for i in range(3) for j in range(3)))))
            return minimum_on(form, w, sgn[_sign(case, g.v)])

        return _x_subject("V", V, paper)


class HatVRuntime(_Binding):
    id = "model.hatV_runtime"
    paper = "eq. (Vhat); Lemma 3, proof of eq. (hatVandHatR)"
    statement = (
        "the package's V̂ is ½k₁σ² + ½k₂dz(φ)² + k₃|σ||v| + ½k₄v² = ½wᵀKw with w = (|σ|, |dz(φ)|, |v|), "
        "in exact, float and symbolic form"
    )

    def derive(self) -> BindingSubject:
        g = G()
        k = tuple(sp.symbols("k_1 k_2 k_3 k_4", positive=True))
        K = _symbolic.K_hat(*k)

        def paper(case: Case) -> sp.Expr:
            w = sp.Matrix([sp.Abs(case(g.sigma)), sp.Abs(_paper_dz(case, g.phi, g.f_c)), sp.Abs(case(g.v))])
            return sp.expand((w.T * K * w)[0] / 2)

        def runtime(p: Parameters, x: Any) -> Any:
            return V_hat(p, x, K_INSTANCE)

        constants = _gain_values(g, INSTANCE)
        constants.update(zip(k, (sp.Rational(q) for q in K_INSTANCE)))
        return _x_subject("V̂", runtime, paper, symbolic=shared_value(V_hat, g, [g.sigma, g.phi, g.v], k),
                           constants=constants)


class HatVRateRuntime(_Binding):
    id = "model.hatV_rate_runtime"
    paper = "Lemma 3, eq. (hatVdot) and eq. (almostEverywhereDerivatives)"
    statement = (
        "the package's V̂° on R̂ (used by the cross-check) is max_{ζ ∈ ∂|σ|} ⟨∂V̂, F⟩ with ∂V̂ differentiated from "
        "the package's V̂ and F = Ax − b sign(v), in exact, float and symbolic form"
    )

    def derive(self) -> BindingSubject:
        g = G()
        k = tuple(sp.symbols("k_1 k_2 k_3 k_4", positive=True))
        zeta = sp.Symbol("zeta", real=True)
        state = (g.sigma, g.phi, g.v)
        Vh = shared_value(V_hat, g, list(state), k)
        F = _symbolic.A(g) * sp.Matrix(state) - _symbolic.b(g) * sp.sign(g.v)
        # Clarke: ∂|σ| = SGN(σ); keep ζ for the element of SGN(σ) that sympy writes sign(σ)
        rate = sum(derivative(Vh, x) * F[i] for i, x in enumerate(state)).xreplace({sp.sign(g.sigma): zeta})

        def paper(case: Case) -> sp.Expr:
            if _sign(case, g.sigma) != 0:
                return case(rate).xreplace({zeta: _sign(case, g.sigma)})
            ends = [resolve_piecewise(case(rate).xreplace({zeta: z})) for z in (1, -1)]
            order = sign_of(sp.expand(ends[0] - ends[1]))
            if order is None:
                raise Undecided(f"cannot compare ζ = ±1 in {ends}")
            return ends[0] if order >= 0 else ends[1]

        def in_rhat(case: Case) -> bool:
            margin = sp.expand(case(g.v) * (case(g.phi) - _sign(case, g.v) * case(g.f_c)))
            return sign_of(margin) == -1

        def runtime(p: Parameters, x: Any) -> Any:
            return V_hat_rate(p, x, K_INSTANCE)

        constants = _gain_values(g, INSTANCE)
        constants.update(zip(k, (sp.Rational(q) for q in K_INSTANCE)))
        cases = tuple(c for c in _state_cases(g) if in_rhat(c))
        points = tuple(p for p in instance_points() if p[2] != 0 and (1 if p[2] > 0 else -1) * p[1] < INSTANCE.f_c)
        return _x_subject(
            "V̂°", runtime, paper, symbolic=shared_value(V_hat_rate, g, list(state), k), constants=constants, cases=cases, points=points
        )


class RRuntime(_Binding):
    id = "model.R_runtime"
    paper = "Lemma 3 (the sets R and R̂)"
    statement = "the package's test x ∈ R is v(φ − sign(v) f_c) ≥ 0, boundary included, in exact, float and symbolic form"

    def derive(self) -> BindingSubject:
        g = G()

        def paper(case: Case) -> Any:
            return sp.GreaterThan(sp.expand(case(g.v) * (case(g.phi) - _sign(case, g.v) * case(g.f_c))), 0)

        return _x_subject("x ∈ R", in_R, paper, relation=True)


class DistanceRuntime(_Binding):
    id = "model.distance_runtime"
    paper = "eq. (distFromA); Notation (dz, sat)"
    statement = "the package's |x|²_𝒜 is σ² + v² + dz(φ)² with dz(y) = y − f_c·sat(y/f_c), in exact, float and symbolic form"

    def derive(self) -> BindingSubject:
        g = G()

        def paper(case: Case) -> sp.Expr:
            return case(g.sigma) ** 2 + case(g.v) ** 2 + _paper_dz(case, g.phi, g.f_c) ** 2

        return _x_subject("|x|²_𝒜", squared_distance_x, paper)


class DistanceZRuntime(_Binding):
    id = "model.distance_z_runtime"
    paper = "Corollary 1, proof (the two distances)"
    statement = "the package's |z|²_𝒜 is s² + v² + dz_{f_c/k_i}(e_i)², in exact, float and symbolic form"

    def derive(self) -> BindingSubject:
        g = G()
        beta = g.f_c / g.k_i
        cases = case_grid(
            sign_cases(g.s, "s", "a_s"),
            sign_cases(g.v, "v", "a_v"),
            line_cases(g.e_i, [-beta, beta], name="e_i", beyond="d_e", weights=("u_e", "w_e"), labels=["-f_c/k_i", "f_c/k_i"]),
        )

        def paper(case: Case) -> sp.Expr:
            return case(g.s) ** 2 + case(g.v) ** 2 + _paper_dz(case, g.e_i, beta) ** 2

        points = tuple((e, s, v) for s, e, v in instance_points(INSTANCE.f_c / INSTANCE.k_i))
        return _x_subject(
            "|z|²_𝒜", squared_distance_z, paper, symbolic=shared_value(squared_distance_z, g, [g.e_i, g.s, g.v]),
            cases=tuple(cases), points=points, state=(g.e_i, g.s, g.v),
        )


@dataclass(frozen=True)
class MatricesSubject:
    """The symbolic matrices and the float (and exact) ones the simulators use."""

    symbolic: dict[str, sp.ImmutableMatrix]
    runtime: dict[str, Callable[[Parameters], Any]]
    params: Parameters
    constants: dict


class MatricesRuntime(Obligation):
    id = "model.matrices_runtime"
    paper = "eq. (CoC), eq. (xDot), eq. (lyapLikeP)"
    statement = "the float A, b, P and the coordinate maps z ↦ x = Tz, x ↦ z = T⁻¹x that the simulators use equal the symbolic ones (exact and float paths)"
    method = "evaluate at dyadic gains (float arithmetic exact) and compare entry by entry with =="

    def derive(self) -> MatricesSubject:
        g = G()
        basis_f = np.eye(3)
        basis_q = np.array([[Fraction(int(i == j)) for j in range(3)] for i in range(3)], dtype=object)
        return MatricesSubject(
            symbolic={
                "A": sp.ImmutableMatrix(_symbolic.A(g)),
                "b": sp.ImmutableMatrix(_symbolic.b(g)).T,
                "P": sp.ImmutableMatrix(_symbolic.P(g)),
                # rows of z_to_x(eᵢ) are the columns of T: compare with Tᵀ
                "T (float)": sp.ImmutableMatrix(_symbolic.T(g)).T,
                "T (exact)": sp.ImmutableMatrix(_symbolic.T(g)).T,
                "T⁻¹ (float)": sp.ImmutableMatrix(_symbolic.T_inv(g)).T,
                "T⁻¹ (exact)": sp.ImmutableMatrix(_symbolic.T_inv(g)).T,
            },
            runtime={
                "A": system_matrix,
                "b": lambda p: input_vector(p).reshape(1, 3),
                "P": lyapunov_matrix,
                "T (float)": lambda p: z_to_x(p, basis_f),
                "T (exact)": lambda p: z_to_x(p, basis_q),
                "T⁻¹ (float)": lambda p: x_to_z(p, basis_f),
                "T⁻¹ (exact)": lambda p: x_to_z(p, basis_q),
            },
            params=INSTANCE,
            constants=_gain_values(g, INSTANCE),
        )

    def verify(self, subject: MatricesSubject) -> Outcome:
        for name, M in subject.symbolic.items():
            want = M.xreplace(subject.constants)
            got = np.asarray(subject.runtime[name](subject.params))
            if got.shape != want.shape:
                return Outcome.fail(f"{name}: shape {got.shape}, expected {want.shape}")
            exact = "exact" in name
            for i, j in itertools.product(range(want.shape[0]), range(want.shape[1])):
                w, x = want[i, j], got[i, j]
                same = (x == _as_exact(w) and isinstance(x, (Fraction, int))) if exact else float(x) == float(w)
                if not same:
                    return Outcome.fail(f"{name}[{i + 1},{j + 1}] = {x!r} at the instance gains; symbolically {w}")
        return Outcome(True, f"{len(subject.symbolic)} matrices equal entry by entry at dyadic gains")


@dataclass(frozen=True)
class ModesSubject:
    """The appendix table proved by ``claim1.cases`` and the simulators' mode selection."""

    rows: tuple[Any, ...]
    table_row: Callable[..., str]
    select_mode: Callable[..., int]
    mode_at_rest: Callable[..., Any]
    mode_after_slip: Callable[..., Any]
    f_c: Fraction
    points: tuple[tuple[Fraction, Fraction, Fraction], ...]


def _classes(point: tuple[Fraction, Fraction, Fraction], f_c: Fraction) -> tuple[str, str, str]:
    """The row-table classes (as :func:`.claim1.table_rows` writes them) of an exact point."""
    sigma, phi, v = point

    def sgn(q: Fraction) -> str:
        return "> 0" if q > 0 else "< 0" if q < 0 else "= 0"

    phi_class = (
        "φ > f_c" if phi > f_c else "φ = f_c" if phi == f_c else "φ = -f_c" if phi == -f_c else "φ < -f_c" if phi < -f_c else "|φ| < f_c"
    )
    return sgn(v), phi_class, sgn(sigma)


class ModesRuntime(Obligation):
    id = "model.modes_runtime"
    paper = "Claim 1; Appendix (table of cases (i)-(xi)); eq. (basic) with a static level f_s"
    statement = (
        "the simulators' mode selection (table_row/select_mode exactly; mode_at_rest from every base and "
        "mode_after_slip in both slip directions, with their named snapping band) gives the row and k of the table "
        "that claim1.cases proves, in every class, for f_c ∈ {1, 2, 1e-6, 1e6} and f_s = f_c or f_s > f_c"
    )
    method = (
        "exact points in each of the 45 sign/φ classes (table_row, select_mode, ==); offsets on ±f_c and ±f_s, "
        "at the adjacent floats and inside/outside the band tol + 4ε(|base∓1|f_c + f_s − f_c), judged against "
        "the exact rational table (points within rounding of the band's edge are not judged)"
    )

    def derive(self) -> ModesSubject:
        f_c = INSTANCE.f_c
        return ModesSubject(
            rows=table_rows(sp.Rational(f_c)),
            table_row=table_row,
            select_mode=select_mode,
            mode_at_rest=mode_at_rest,
            mode_after_slip=mode_after_slip,
            f_c=f_c,
            points=instance_points(f_c),
        )

    def verify(self, subject: ModesSubject) -> Outcome:
        from ._modes_binding import EXCESS, F_CS, verify_modes

        seen: set[str] = set()
        for scale in F_CS:
            for ratio in EXCESS:
                f_c = subject.f_c * Fraction(scale)
                f_s = f_c * (1 + Fraction(ratio)) if ratio else None
                stick = f_c if f_s is None else f_s
                for point in subject.points:  # the instance's points, scaled to this f_c and stick boundary
                    point = (point[0] * Fraction(scale), point[1] * stick / subject.f_c, point[2] * Fraction(scale))
                    v_class, phi_class, sigma_class = _classes(point, stick)
                    rows = [
                        r for r in subject.rows
                        if r.v == v_class and r.phi in (None, phi_class) and r.sigma in (None, sigma_class)
                    ]
                    where = f"f_c = {f_c}, f_s = {stick}: (σ, φ, v) = (" + ", ".join(str(c) for c in point) + ")"
                    if len(rows) != 1:
                        return Outcome.fail(f"{where}: {len(rows)} rows of the proved table apply; expected exactly one")
                    row = rows[0]
                    if scale == 1 and not ratio:
                        seen.add(row.label)
                    extra = () if f_s is None else (f_s,)
                    label = subject.table_row(*point, f_c, *extra)
                    if label != row.label:
                        return Outcome.fail(f"{where}: table_row gives row ({label}), the proved table row ({row.label})")
                    k = subject.select_mode(*point, f_c, *extra)
                    if k != row.k:
                        return Outcome.fail(f"{where}: select_mode gives k = {k}, row ({row.label}) has k = {row.k}")
        missing = [r.label for r in subject.rows if r.label not in seen]
        if missing:
            return Outcome.fail(f"rows {missing} were never reached by a point: the check would be vacuous for them")
        rest = verify_modes(subject.rows, subject.mode_at_rest, subject.mode_after_slip)
        if not rest.holds:
            return rest
        return Outcome(True, f"all {len(subject.rows)} rows agree exactly at the class points; " + rest.reason)


@dataclass(frozen=True)
class PNormSubject:
    """The simulation kernel's written-out ``|y|_P`` and the package's quadratic form, per gain set."""

    p_norm: Callable[..., float]
    weights: tuple[tuple[float, float], ...]
    params: tuple[Parameters, ...]
    points: tuple[tuple[Fraction, Fraction, Fraction], ...]
    scales: tuple[float, ...] = (1.0, 2.0, 1e-6, 1e6)


P_NORM_TOLERANCE = Fraction(8, 2**52)
"""The relative error ``model.P_norm_runtime`` allows on ``p_norm²``: the rounding of its few products and sums."""


class PNormRuntime(Obligation):
    id = "model.P_norm_runtime"
    paper = "eq. (lyapLikeP); eq. (dVdt) (|y|_P is nonincreasing along a slip)"
    statement = "the certified root search's written-out |y|_P squares to the package's (σ, φ, v)P(σ, φ, v)ᵀ"
    method = (
        "a point of every class (63), scaled by 1, 2, 1e-6 and 1e6, at two dyadic gain sets, against the exact form "
        "at the float inputs; p_norm² may differ by 8·2⁻⁵² relative"
    )

    def derive(self) -> PNormSubject:
        from .._simulation.affine import MatrixExponential
        from .._simulation.search import p_norm, p_weights

        params = (INSTANCE, Parameters(k_p=Fraction(1, 2), k_i=Fraction(1, 4), k_v=8, f_c=Fraction(1, 8)))
        return PNormSubject(
            p_norm=p_norm,
            weights=tuple(p_weights(MatrixExponential.from_params(p)) for p in params),
            params=params,
            points=instance_points(),
        )

    def verify(self, subject: PNormSubject) -> Outcome:
        n = 0
        for params, weights in zip(subject.params, subject.weights):
            for scale in subject.scales:
                for point in subject.points:
                    x = [float(c) * scale for c in point]
                    want = quadratic_form(params, *(Fraction(c) for c in x))
                    got2 = Fraction(float(subject.p_norm(*x, *weights))) ** 2
                    n += 1
                    if abs(got2 - want) > P_NORM_TOLERANCE * want:
                        return Outcome.fail(
                            f"at {tuple(x)} ({params.gains_text() if hasattr(params, 'gains_text') else params}): "
                            f"p_norm² = {float(got2)!r}, the package's |y|²_P = {float(want)!r} "
                            f"(allowed: {float(P_NORM_TOLERANCE):.3g} relative)"
                        )
        return Outcome(True, f"the kernel's |y|_P agrees with the package's P at {n} points "
                             f"(within {float(P_NORM_TOLERANCE):.3g} relative on the square)")


@dataclass(frozen=True)
class KindsSubject:
    """The three kinds' non-arithmetic operations (:mod:`symbolic_friction._model.kinds`)."""

    kinds: tuple[Any, ...]


class KindsRuntime(Obligation):
    id = "model.kinds_runtime"
    paper = "Notation (sign, sat, dz); eq. (frictionforceSetValued)"
    statement = "where, clip (c·sat), sign and abs agree with the paper's definitions in the exact, float and sympy kinds, boundaries included"
    method = "each operation at -2, -1, -1/2, 0, 1/2, 1, 2 against the definition, compared with =="

    def derive(self) -> KindsSubject:
        from .._model.kinds import EXACT, FLOAT, SYMPY

        return KindsSubject((EXACT, FLOAT, SYMPY))

    def verify(self, subject: KindsSubject) -> Outcome:
        points = [Fraction(n, 2) for n in (-4, -2, -1, 0, 1, 2, 4)]
        one = Fraction(1)
        for kind in subject.kinds:
            cast = {"exact": lambda q: q, "float": float, "sympy": sp.Rational}.get(kind.name, lambda q: q)
            for y in points:
                yk = cast(y)
                # the paper's Notation: sign(0) = 0, sat(y) = y on [-1, 1], ±1 outside
                want = {
                    "sign": (y > 0) - (y < 0),
                    "clip": -one if y < -1 else one if y > 1 else y,
                    "abs": abs(y),
                    "where": 1 if y > 0 else 2,
                }
                got = {
                    "sign": kind.sign(yk),
                    "clip": kind.clip(yk, cast(-one), cast(one)),
                    "abs": kind.abs(yk),
                    "where": kind.where(yk > 0, 1, 2),
                }
                for name, value in got.items():
                    if Fraction(str(value if kind.name != "float" else float(value))) != want[name]:
                        return Outcome.fail(f"the {kind.name} kind's {name}({y}) is {value!r}; the definition gives {want[name]}")
        return Outcome(True, f"{len(subject.kinds)} kinds × 4 operations agree at {len(points)} points")


OBLIGATIONS = (KindsRuntime, VRuntime, HatVRuntime, HatVRateRuntime, RRuntime, DistanceRuntime, DistanceZRuntime, MatricesRuntime, ModesRuntime, PNormRuntime)
