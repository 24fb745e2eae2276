"""Claim 1 and its appendix proof: the eleven-row case table.

For each initial condition ``(σ̄, φ̄, v̄)`` the appendix picks ``k ∈ {-1, 0, 1}``
and shows that the solution of the affine system ``ξ' = f_k(ξ)`` (eq.
subcasesAffine) is a solution of the inclusion eq. (xDot) on some ``[0, T]``,
``T > 0``, along which ``V = V_k`` and ``d/dt V_k ≤ -c ξ_v²`` (eq. dVdt).

The paper writes out rows (i)-(v) and leaves (vi)-(xi) to "parallel
arguments"; here every row is checked:

* ``k = ±1``: the first non-zero derivative of ``ξ_v`` at 0 (computed from
  ``f_k``) has the sign ``k``, so ``SGN(ξ_v(t)) = {k}`` on ``(0, T]`` and
  ``f_k = A ξ - b k`` is a selection of the inclusion; ``v''(0) = σ̄`` in rows
  (iii) and (ix).
* ``k = 0``: the explicit stick solution ``ξ(t) = (σ̄, φ̄ + σ̄ t, 0)`` solves
  ``f_0``; the friction selection it needs stays in ``[-1, 1]`` on
  ``[0, T]`` (e.g. ``T = -2f_c/σ̄`` in row (v)); equilibria in rows (iv),
  (viii) and (vi) with ``σ̄ = 0``.
* ``V = V_k``: ``V`` is evaluated from its definition (eq. lyapLikeV) as an
  exact minimum over ``f ∈ f_c SGN(v)``, at ``t = 0`` and on ``(0, T]``.

The rows are also checked to partition the initial conditions.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from . import _fastforms as ff
from . import _fastpoly as fp
from ._base import Erratum, Obligation, Outcome
from ._decide import G, Undecided, decide, is_zero, latex, phi_classes, pos, sign_classes, sign_of
from ._shared import derivative, sgn_sets
from .lemma2 import affine_fields, decrease_rate, friction_form, friction_minimum, lyapunov_pieces, under_assumption1

__all__ = ["Row", "StickBranch", "Claim1Cases", "OBLIGATIONS", "ROWS", "stick_duration_error"]

V_CLASSES = ("> 0", "= 0", "< 0")
PHI_CLASSES = ("φ > f_c", "φ = f_c", "|φ| < f_c", "φ = -f_c", "φ < -f_c")
SIGMA_CLASSES = ("> 0", "= 0", "< 0")


@dataclass(frozen=True)
class StickBranch:
    """Explicit solution of ``f_0`` for the ``σ̄`` class ``sigma`` (``None``: any), valid on ``[0, T]``."""

    sigma: str | None
    xi: sp.ImmutableMatrix
    T: sp.Expr


@dataclass(frozen=True)
class Row:
    """One row of the appendix table.

    ``v``, ``phi`` and ``sigma`` are class labels (``None``: any value);
    ``claims`` are the paper's statements ``d^n ξ_v/dt^n (0) = value``.
    """

    label: str
    v: str
    phi: str | None
    sigma: str | None
    k: int
    stick: tuple[StickBranch, ...] = ()
    claims: tuple[tuple[int, sp.Expr], ...] = ()


@dataclass(frozen=True)
class Claim1Subject:
    """The table, the inclusion, the affine fields, ``V_k``, ``V``'s quadratic form and ``c``."""

    rows: tuple[Row, ...]
    A: sp.ImmutableMatrix
    b: sp.ImmutableMatrix
    f: dict
    V: dict
    form: sp.Expr
    c: sp.Expr
    sgn: dict
    state: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    y: sp.Symbol
    bar: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    t: sp.Symbol
    f_c: sp.Symbol


def _bar_symbols() -> tuple[sp.Symbol, sp.Symbol, sp.Symbol, sp.Symbol]:
    sb, pb, vb = sp.symbols("sigmabar phibar vbar", real=True)
    return sb, pb, vb, sp.Symbol("t", nonnegative=True)


def table_rows(f_c: sp.Expr) -> tuple[Row, ...]:
    """The appendix table as printed, with the explicit solutions the text gives."""
    sb, pb, _vb, t = _bar_symbols()
    ramp = sp.ImmutableMatrix([sb, pb + sb * t, 0])  # σ constant, φ ramps at rate σ̄, v = 0
    return (
        Row("i", "> 0", None, None, 1, claims=((0, _vb),)),
        Row("ii", "= 0", "φ > f_c", None, 1, claims=((1, pb - f_c),)),
        Row("iii", "= 0", "φ = f_c", "> 0", 1, claims=((1, sp.Integer(0)), (2, sb))),
        Row("iv", "= 0", "φ = f_c", "= 0", 0, stick=(StickBranch(None, ramp, sp.oo),)),
        Row("v", "= 0", "φ = f_c", "< 0", 0, stick=(StickBranch(None, ramp, -2 * f_c / sb),)),
        Row(
            "vi",
            "= 0",
            "|φ| < f_c",
            None,
            0,
            stick=(
                StickBranch("> 0", ramp, (f_c - pb) / sb),
                StickBranch("= 0", ramp, sp.oo),
                StickBranch("< 0", ramp, (-f_c - pb) / sb),
            ),
        ),
        Row("vii", "= 0", "φ = -f_c", "> 0", 0, stick=(StickBranch(None, ramp, 2 * f_c / sb),)),
        Row("viii", "= 0", "φ = -f_c", "= 0", 0, stick=(StickBranch(None, ramp, sp.oo),)),
        Row("ix", "= 0", "φ = -f_c", "< 0", -1, claims=((1, sp.Integer(0)), (2, sb))),
        Row("x", "= 0", "φ < -f_c", None, -1, claims=((1, pb + f_c),)),
        Row("xi", "< 0", None, None, -1, claims=((0, _vb),)),
    )


ROWS = ("i", "ii", "iii", "iv", "v", "vi", "vii", "viii", "ix", "x", "xi")


def stick_duration_error(T: sp.Expr) -> str | None:
    """Why a stick branch's duration ``T`` does not give an interval ``[0, T]``, ``T > 0`` (``None``: it does).

    Claim 1 needs a solution on some ``[0, T]`` with ``T > 0``: ``T = ∞`` (an
    equilibrium, rows (iv), (viii)) does, and a finite ``T`` (e.g. ``T = -2f_c/σ̄``
    in row (v)) must be *shown* positive by :func:`~._decide.sign_of` on the
    row's region.  A sign that is zero, negative or undecided refuses it: an
    undecided ``T`` may be ``≤ 0`` for some initial condition of the row, and
    undecided never means proved.  ``check`` decides this on built inputs
    (:func:`~._decide_cases.decision_cases`).
    """
    finite = T != sp.oo
    if finite and sign_of(T) != 1:
        return f"the duration T = {T} is not shown positive"
    return None


def _at(expr: Any, values: dict) -> sp.Expr:
    """``expr`` with its symbols replaced by ``values`` (which hold none of those symbols): what ``subs`` gives then,
    built by ``xreplace`` without ``subs``'s bookkeeping."""
    return sp.sympify(expr).xreplace({k: sp.sympify(v) for k, v in values.items()})


def _matches(row_value: str | None, value: str) -> bool:
    return row_value is None or row_value == value


class Claim1Cases(Obligation):
    id = "claim1.cases"
    paper = "Claim 1; Appendix (table of cases (i)-(xi))"
    statement = "for every initial condition the table's k gives an affine solution that solves (xDot) on [0, T], T > 0, with V = V_k and d/dt V_k ≤ -c ξ_v² there; all eleven rows, which partition ℝ³"
    method = "exhaustive case split (45 sign/φ classes → 11 rows, sub-cases by σ̄); Taylor signs of ξ_v at 0 (k = ±1); explicit stick solutions with the selection checked at both ends of [0, T] (k = 0); V from its definition by exact minimisation; sympy identities"
    errata = (
        Erratum(
            where="Appendix (proof of Claim 1), case (v)",
            paper_says="an appropriate selection of the value in SGN(0) obtains ξ_φ(t) - f_c SGN(ξ_v(t)) = ξ_φ(t) - f_c SGN(0) = {0}",
            correct="ξ_φ(t) - f_c SGN(0) = [ξ_φ(t) - f_c, ξ_φ(t) + f_c] is an interval, not {0}; it contains 0 because |ξ_φ(t)| ≤ f_c, i.e. the selection w(t) = ξ_φ(t)/f_c lies in [-1, 1] on [0, -2f_c/σ̄]",
            checked_by="claim1.cases",
        ),
    )

    def derive(self) -> Claim1Subject:
        g = G()
        sb, pb, vb, t = _bar_symbols()
        form, y = friction_form(g)
        return Claim1Subject(
            rows=table_rows(g.f_c),
            A=sp.ImmutableMatrix(_symbolic.A(g)),
            b=sp.ImmutableMatrix(_symbolic.b(g)),
            f=affine_fields(g),
            V=lyapunov_pieces(g),
            form=form,
            c=decrease_rate(g),
            sgn=sgn_sets(),
            state=(g.sigma, g.phi, g.v),
            y=y,
            bar=(sb, pb, vb),
            t=t,
            f_c=g.f_c,
        )

    # ----------------------------------------------------------------- helpers

    def _V(self, S: Claim1Subject, point, v_sign: int) -> sp.Expr:
        """``V`` of eq. (lyapLikeV) at ``point`` whose ``v`` has sign ``v_sign``: exact min over f ∈ f_c SGN(v)."""
        sigma, phi, v = point
        # xreplace is a simultaneous substitution of symbols, as subs(simultaneous=True), without its bookkeeping
        at = S.form.xreplace({S.state[0]: sp.sympify(sigma), S.state[2]: sp.sympify(v)})
        memo = getattr(self, "_minima", {})
        key = (at, phi, v_sign)
        if key not in memo:
            memo[key] = at.xreplace({S.y: sp.Integer(0)}) + friction_minimum(at, S.y, phi, S.f_c, S.sgn[v_sign])
        return memo[key]

    def _Vk(self, S: Claim1Subject, k: int, point) -> sp.Expr:
        return S.V[k].xreplace({s: sp.sympify(p) for s, p in zip(S.state, point)})

    def _initial_points(self, S: Claim1Subject, row: Row):
        """Yield ``(σ̄ class or None, substitution for the bar symbols)`` covering the row's region.

        Unconstrained components stay free real symbols; a sign decision that
        needs them then fails as undecided rather than guessing.
        """
        sb, pb, vb = S.bar
        v_val = {c[0]: c[2] for c in sign_classes("q_v")}[row.v]
        phi_val = pb if row.phi is None else {c[0]: c[2] for c in phi_classes(S.f_c, "_phi")}[row.phi]
        sigmas = [(row.sigma, {c[0]: c[2] for c in sign_classes("s_sigma")}[row.sigma])] if row.sigma else [(None, sb)]
        for sigma_label, sigma_val in sigmas:
            yield sigma_label, {sb: sigma_val, pb: phi_val, vb: v_val}

    # ----------------------------------------------------------------- verify

    def verify(self, subject: Claim1Subject) -> Outcome:
        S = subject
        details: list[tuple[str, str]] = []
        # Exhaustiveness: each (v, φ, σ) class belongs to exactly one row.
        for cv, cp, cs in itertools.product(V_CLASSES, PHI_CLASSES, SIGMA_CLASSES):
            hits = [r.label for r in S.rows if _matches(r.v, cv) and _matches(r.phi, cp) and _matches(r.sigma, cs)]
            if len(hits) != 1:
                return Outcome.fail(f"the initial conditions v̄ {cv}, {cp}, σ̄ {cs} fall in {len(hits)} rows {hits}, not exactly one")
        self._minima: dict = {}  # V at a point, within this verification only (rows share points)
        c_pos = sign_of(under_assumption1(S.c))
        if c_pos != 1:
            return Outcome.fail(f"c = {S.c} is not shown positive under Assumption 1")
        for row in S.rows:
            try:
                outcome = self._row(S, row, details)
            except Undecided as exc:
                return Outcome.fail(f"row ({row.label}): {exc}", tuple(details))
            if outcome is not None:
                return Outcome.fail(f"row ({row.label}): {outcome}", tuple(details))
        return Outcome(True, "all eleven rows hold and partition the initial conditions", tuple(details))

    def _row(self, S: Claim1Subject, row: Row, details: list) -> str | None:
        x = sp.Matrix(S.state)
        k = row.k
        if k not in (1, 0, -1):
            return f"k = {k} is not in {{-1, 0, 1}}"
        f = sp.Matrix(S.f[k])
        if k != 0:
            if not all(is_zero(e) for e in (f - (S.A * x - S.b * k))):
                return f"f_{k} = {list(f)} is not the selection A x - b·({k}) of the inclusion"
            return self._row_slip(S, row, f, details)
        return self._row_stick(S, row, f, details)

    def _row_slip(self, S: Claim1Subject, row: Row, f: sp.Matrix, details: list) -> str | None:
        k = row.k
        J = f.jacobian(sp.Matrix(S.state))
        for _sigma_label, sub in self._initial_points(S, row):
            xb = [_at(e, sub) for e in S.bar]
            derivs = [sp.Matrix(xb)]
            derivs.append(f.xreplace(dict(zip(S.state, xb))))
            for _ in range(2):
                derivs.append(J * derivs[-1])
            vd = [d[2] for d in derivs]  # decided as values (exact, whatever their form); factored where printed
            for order, value in row.claims:
                if not is_zero(vd[order] - _at(value, sub)):
                    return f"the paper's d^{order}ξ_v/dt^{order}(0) = {_at(value, sub)} but f_{k} gives {fp.factor(vd[order])}"
            first = None
            for n, dv in enumerate(vd):
                s = sign_of(dv)
                if s is None:
                    return f"cannot decide the sign of d^{n}ξ_v/dt^{n}(0) = {fp.factor(dv)}"
                if s != 0:
                    first = (n, s)
                    break
            if first is None:
                return f"ξ_v and its first {len(vd) - 1} derivatives vanish at 0; the sign of ξ_v is not determined"
            n, s = first
            if s != k:
                return f"d^{n}ξ_v/dt^{n}(0) = {fp.factor(vd[n])} has sign {s}, so ξ_v leaves 0 with sign {s}, not k = {k}"
            v_sign0 = sign_of(xb[2])
            if decide(sp.Contains(k, S.sgn[v_sign0]).doit()) is not True:
                return f"at t = 0, k = {k} is not in SGN(v̄) = {S.sgn[v_sign0]}"
            # V = V_k at t = 0 (exact minimum) and on (0, T] where sign ξ_v = k.
            V0 = self._V(S, xb, v_sign0)
            if not is_zero(V0 - self._Vk(S, k, xb)):
                return f"V(ξ(0)) = {fp.factor(V0)} but V_{k}(ξ(0)) = {fp.factor(self._Vk(S, k, xb))}"
            vq = pos("v_t") * k
            pt = [S.state[0], S.state[1], vq]
            if not is_zero(self._V(S, pt, k) - self._Vk(S, k, pt)):
                return f"V ≠ V_{k} where sign ξ_v = {k}"
            rate = sp.expand((sp.Matrix([derivative(S.V[k], s) for s in S.state]).T * f)[0] + S.c * S.state[2] ** 2)
            if not is_zero(rate):
                return f"d/dt V_{k} + c ξ_v² = {fp.factor(rate)} along f_{k}, not 0"
            details.append((
                f"\\text{{({row.label})}}\\ {self._tex_region(row)},\\ k = {k}",
                "".join(f"\\xi_v^{{({m})}}(0) = 0,\\ " for m in range(n))
                + f"\\xi_v^{{({n})}}(0) = {latex(fp.factor(vd[n]))}"
                + f";\\ V(\\xi(0)) = V_{{{k}}} = {latex(fp.factor(V0))}",
            ))
        return None

    def _row_stick(self, S: Claim1Subject, row: Row, f0: sp.Matrix, details: list) -> str | None:
        for sigma_label, sub in self._initial_points(S, row):
            # Which explicit branches cover this σ-class; without a σ class in the row, split by sign of σ̄.
            subcases = []
            if sigma_label is not None:
                branches = [br for br in row.stick if br.sigma is None or br.sigma == sigma_label]
                subcases = [(sigma_label, sub, branches)]
            else:
                for lab, _s, val in sign_classes("s_sigma"):
                    sub2 = dict(sub)
                    sub2[S.bar[0]] = val
                    subcases.append((lab, sub2, [br for br in row.stick if br.sigma is None or br.sigma == lab]))
            for lab, sub2, branches in subcases:
                if len(branches) != 1:
                    return f"σ̄ {lab}: {len(branches)} explicit solutions given, expected one"
                (br,) = branches
                err = self._stick_branch(S, row, f0, br, lab, sub2, details)
                if err:
                    return f"σ̄ {lab}: {err}"
        return None

    def _stick_branch(self, S, row, f0, br: StickBranch, lab, sub, details) -> str | None:
        t = S.t
        xb = sp.Matrix([_at(e, sub) for e in S.bar])
        xi = sp.Matrix(br.xi).xreplace(sub)
        T = _at(br.T, sub)
        if not all(is_zero(e) for e in (xi.xreplace({t: sp.Integer(0)}) - xb)):
            return f"ξ(0) = {list(xi.xreplace({t: sp.Integer(0)}))} is not the initial condition {list(xb)}"
        dxi = xi.applyfunc(lambda e: e.diff(t))  # entrywise, as Matrix.diff gives it, without its array machinery
        if not all(is_zero(e) for e in (dxi - f0.xreplace(dict(zip(S.state, xi))))):
            return f"ξ(t) = {list(xi)} does not solve ξ' = f_0(ξ)"
        if not is_zero(xi[2]):
            return f"ξ_v(t) = {xi[2]} is not identically 0 on the stick"
        finite = T != sp.oo
        refused = stick_duration_error(T)
        if refused:
            return refused
        # Friction selection: ξ' - A ξ = -b w(t) with w(t) ∈ SGN(0) = [-1, 1] for t ∈ [0, T].
        r = dxi - S.A * xi
        w = fp.factor(-r[2] / S.b[2])
        if not all(is_zero(r[i] + S.b[i] * w) for i in range(3)):
            return f"ξ' - Aξ = {list(r)} is not a multiple of b"
        lo, hi = S.sgn[0].start, S.sgn[0].end
        if finite:
            if ff.degree_in(sp.expand(sp.numer(ff.together(w))), t) > 1 or ff.together(w).as_numer_denom()[1].has(t):
                return f"the selection w(t) = {w} is not affine in t"
            ends = [_at(w, {t: 0}), fp.factor(_at(w, {t: T}))]
        else:
            if not is_zero(sp.diff(w, t)):
                return f"the selection w(t) = {w} is not constant on an unbounded stick"
            ends = [w]
        for e in ends:
            if decide(sp.And(sp.Le(lo, e), sp.Le(e, hi))) is not True:
                return f"the friction selection w = {e} at an end of [0, T], T = {T}, is not in SGN(0) = [{lo}, {hi}]"
        # V = V_0 on [0, T]: at t = 0, at t = T and inside (t = T·α/(α+β)), or at any t > 0 if T = ∞.
        alpha, beta = pos("alpha_t"), pos("beta_t")
        times = [sp.Integer(0), T, T * alpha / (alpha + beta)] if finite else [sp.Integer(0), pos("tau")]
        for tt in times:
            pt = list(xi.xreplace({t: tt}))
            V = self._V(S, pt, 0)
            if not is_zero(V - self._Vk(S, 0, pt)):
                return f"at t = {tt}: V(ξ) = {fp.factor(V)} but V_0(ξ) = {fp.factor(self._Vk(S, 0, pt))}"
        rate = sp.diff(self._Vk(S, 0, list(xi)), t) + S.c * xi[2] ** 2
        if not is_zero(rate):
            return f"d/dt V_0(ξ(t)) + c ξ_v² = {fp.factor(rate)}, not 0"
        tag = f",\\ \\bar\\sigma {lab}" if lab and not row.sigma else ""
        details.append((
            f"\\text{{({row.label})}}\\ {self._tex_region(row)}{tag},\\ k = 0",
            f"\\xi(t) = {latex(list(xi))},\\ t \\in [0, T],\\ T = {latex(br.T)}"
            + (f" = {latex(fp.factor(T))}" if T != br.T else "")
            + f",\\ w(t) = {latex(fp.factor(w))}"
            f";\\ V = V_0 = {latex(fp.factor(self._Vk(S, 0, list(xi))))}",
        ))
        return None

    @staticmethod
    def _tex_region(row: Row) -> str:
        parts = [f"\\bar v {row.v}"]
        if row.phi:
            parts.append(row.phi.replace("φ", "\\bar\\phi ").replace("f_c", "f_c"))
        if row.sigma:
            parts.append(f"\\bar\\sigma {row.sigma}")
        return ",\\ ".join(parts)


OBLIGATIONS = (Claim1Cases,)
