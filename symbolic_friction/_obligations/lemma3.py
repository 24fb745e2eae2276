"""Lemma 3 (Section V, "Proof of Prop. 1: stability"): the bounds on ``R`` and
``R̂`` and the Clarke derivative of ``V̂`` (eqs. VandR, hatVandHatR, hatVdot).

.. math::

    \\hat V(x) = \\tfrac12 k_1\\sigma^2 + \\tfrac12 k_2\\,\\mathrm{dz}(\\phi)^2
        + k_3|\\sigma||v| + \\tfrac12 k_4 v^2,\\qquad
    R = \\{x : v(\\phi - \\mathrm{sign}(v) f_c) \\ge 0\\},\\quad \\hat R = \\mathbb R^3\\setminus R.

Three obligations, each for symbolic gains and symbolic ``k₁ … k₄``:

* ``lemma3.R`` — on ``R`` the minimum over ``f ∈ f_c SGN(v)`` in eq. (lyapLike)
  is ``dz(φ)²``, so ``V = wᵀPw`` with ``w = (σ, dz(φ), v)`` and
  ``λ_min(P)|x|²_𝒜 ≤ V ≤ λ_max(P)|x|²_𝒜`` there (eq. VandR).
* ``lemma3.hatV_bounds`` — ``V̂ = ½wᵀKw`` with ``w = (|σ|, |dz(φ)|, |v|)``;
  ``K ≻ 0 ⇔ k₁k₄ > k₃²`` by Sylvester's criterion; the eigenvalue bounds of
  ``K`` and the sharper bound ``½min(k₁,k₂,k₄)|w|²`` valid for nonnegative
  ``w`` give eq. (hatVandHatR).
* ``lemma3.hatV_derivative`` — the conditions on ``k₁ … k₄`` that make
  ``V̂° ≤ 0`` on ``R̂`` (eq. hatVdot) are *derived* from ``V̂`` and ``F`` by an
  exhaustive case split, shown necessary and sufficient, and compared with the
  list stated in :mod:`symbolic_friction._model.kconditions` (the paper's list).
"""

from __future__ import annotations

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.kconditions import k_conditions
from .._model.lyapunov import friction_selection
from . import _fastforms as ff
from . import _fastpoly as fp
from ._base import Erratum, Obligation, Outcome
from ._decide import G, Undecided, decide, is_zero, latex, resolve_piecewise, sign_of
from ._derived_k import (
    HatVDerivativeSubject,
    _c1_failures,
    _condition_key,
    _Derived,
    _paper_claims,
    _paper_pairs,
    derived_k_conditions,
)
from ._inequalities import (
    block_eigen_bounds,
    canonical,
    case_grid,
    is_lower_bound_of,
    is_nonneg,
    is_upper_bound_of,
    label_latex,
    phi_cases,
    rows_latex,
    sign_cases,
)
from ._region import HatVBoundsSubject, RSubject, _fmt_failures, in_R, k_symbols, pieces_of, region_R, vhat_expression
from ._shared import distance_squared, shared_value
from ._statements import statement_failure

__all__ = [
    "OBLIGATIONS",
    "LemmaR",
    "HatVBounds",
    "HatVDerivative",
    "RSubject",
    "HatVBoundsSubject",
    "HatVDerivativeSubject",
    "k_symbols",
    "vhat_expression",
    "derived_k_conditions",
    "region_R",
    "in_R",
    "pieces_of",
]


# --------------------------------------------------------------------------
# shared pieces of the model
# --------------------------------------------------------------------------


# --------------------------------------------------------------------------
# lemma3.R
# --------------------------------------------------------------------------


class LemmaR(Obligation):
    """``lemma3.R``: on ``R``, ``min_f (φ - f)² = dz(φ)²`` and eq. (VandR) with ``c₂ = λ_max(P)``."""

    id = "lemma3.R"
    paper = "Lemma 3, eq. (VandR) and first lines of its proof"
    statement = (
        "On R = {v(φ − sign(v) f_c) ≥ 0}: min over f ∈ f_c·SGN(v) of (φ − f)² equals dz(φ)², "
        "so V = [σ, dz(φ), v] P [σ, dz(φ), v]ᵀ and λ_min(P)|x|²_𝒜 ≤ V ≤ λ_max(P)|x|²_𝒜 there"
    )
    method = (
        "exhaustive case split (v ≷ 0, φ against ±f_c, positive parametrisations); minimiser checked "
        "admissible and optimal by sign-definite decomposition; Rayleigh bounds from exact eigenvalue identities of P"
    )

    def derive(self) -> RSubject:
        g = G()
        fc = g.f_c
        nonzero = sp.Ne(g.v, 0)
        P = _symbolic.P(g)
        _, eig = block_eigen_bounds(P, what="P")
        dz = shared_value(_symbolic.dz, g.phi, fc)
        return RSubject(
            sigma=g.sigma,
            phi=g.phi,
            v=g.v,
            f_c=fc,
            region=shared_value(region_R, g),
            sgn_lo=sp.Piecewise((fc * sp.sign(g.v), nonzero), (-fc, True)),
            sgn_hi=sp.Piecewise((fc * sp.sign(g.v), nonzero), (fc, True)),
            # the closed form _lyapunov.V uses: the projection of φ on f_c·SGN(v)
            minimizer=sp.piecewise_fold(friction_selection(g, g.phi, g.v)),
            P=P,
            dz=dz,
            dist2=distance_squared(g),
            c1=eig["lam_min"],
            c2=eig["lam_max"],
            assumption=tuple(_symbolic.assumption1_substitution(g).items()),
            cases=tuple(case_grid(sign_cases(g.v, "v", "a_v"), phi_cases(g.phi, g.f_c))),
        )

    def verify(self, subject: RSubject) -> Outcome:
        problem = statement_failure(subject.statement, lambda c1, c2, dist2, V: (V - c1 * dist2, c2 * dist2 - V))
        if problem:
            return Outcome.fail(f"eq. (VandR) as Proposition 1 uses it: {problem}")
        s = subject
        failures: list[str] = []
        rows: list[str] = []
        fa, fb = sp.symbols("alpha_f beta_f", positive=True)  # weights of an interior point of [lo, hi]
        pieces_in_R = 0
        for case in pieces_of(s.cases, s.region, inside=True, failures=failures):
            pieces_in_R += 1
            try:
                lo, hi, fstar = (resolve_piecewise(case(e)) for e in (s.sgn_lo, s.sgn_hi, s.minimizer))
                phi = case.value(s.phi)
                dz = resolve_piecewise(case(s.dz))
            except Undecided as exc:
                failures.append(f"{case.label}: {exc}")
                continue
            if not (decide(sp.LessThan(lo, fstar)) and decide(sp.LessThan(fstar, hi))):
                failures.append(f"{case.label}: the minimiser {fstar} is not in f_c·SGN(v) = [{lo}, {hi}]")
                continue
            candidates = [lo] if is_zero(hi - lo) else [lo, hi, (fa * lo + fb * hi) / (fa + fb)]
            gap = [(phi - f) ** 2 - (phi - fstar) ** 2 for f in candidates]
            if not all(is_nonneg(d) for d in gap):
                failures.append(f"{case.label}: f = {fstar} does not minimise (φ − f)² over [{lo}, {hi}]")
                continue
            if not is_zero(phi - fstar - dz):
                failures.append(f"{case.label}: φ − f* = {sp.simplify(phi - fstar)} differs from dz(φ) = {dz}")
                continue
            # V = (σ, φ − f*, v) P (σ, φ − f*, v)ᵀ must be wᵀPw with w = (σ, dz, v)
            y = sp.Matrix([case(s.sigma), phi - fstar, case(s.v)])
            w = sp.Matrix([case(s.sigma), dz, case(s.v)])
            if not is_zero((y.T * s.P * y)[0] - (w.T * s.P * w)[0]):
                failures.append(f"{case.label}: V is not [σ, dz, v] P [σ, dz, v]ᵀ")
                continue
            if not is_zero(resolve_piecewise(case(s.dist2)) - (w.T * w)[0]):
                failures.append(f"{case.label}: |x|²_𝒜 ≠ σ² + dz(φ)² + v²")
                continue
            rows.append(f"{label_latex(case.label)}: f^* = {latex(fstar)},\\ \\mathrm{{dz}} = {latex(dz)}")
        if pieces_in_R == 0:
            failures.append("no piece of the case split lies in R")
        checks, eig = block_eigen_bounds(s.P, what="P")
        failures += [f"eigenvalue bound: {label} fails" for label, ok in checks if not ok]
        if not is_upper_bound_of(s.c2, [eig["m"], eig["mu_plus"]]):
            failures.append(f"c₂ = {s.c2} is not ≥ every eigenvalue of P ({eig['m']}, {eig['mu_plus']})")
        if not is_lower_bound_of(s.c1, [eig["m"], eig["mu_minus"]]):
            failures.append(f"c₁ = {s.c1} is not ≤ every eigenvalue of P ({eig['m']}, {eig['mu_minus']})")
        # c₁ > 0: μ₋ = det(B)/μ₊ with μ₊ ≥ P₁₁ > 0, and det(B) > 0 under Assumption 1
        det_b = (s.P[0, 0] * s.P[2, 2] - s.P[0, 2] ** 2).xreplace(dict(s.assumption))
        positive_c1 = sign_of(s.P[0, 0]) == 1 and sign_of(det_b) == 1 and sign_of(eig["m"]) == 1
        if not positive_c1:
            failures.append(f"cannot show λ_min(P) > 0 under Assumption 1 (det of the outer block: {det_b})")
        elif not (isinstance(s.c1, sp.Min) or sign_of(s.c1) == 1):
            failures.append(f"cannot show c₁ = {s.c1} > 0")
        details = (
            ("\\text{pieces of } R\\ (\\sigma \\text{ free})", rows_latex(rows)),
            ("P", latex(s.P)),
            ("\\text{eigenvalues of } P", f"1,\\ {latex(eig['mu_minus'])},\\ {latex(eig['mu_plus'])}"),
            ("c_1 = \\lambda_{min}(P),\\ c_2 = \\lambda_{max}(P)", f"{latex(s.c1)},\\quad {latex(s.c2)}"),
            ("\\det(\\text{outer block of }P)\\text{ under Assumption 1}", latex(fp.factor(det_b))),
        )
        if failures:
            return Outcome.fail(_fmt_failures(failures), details)
        return Outcome(True, f"{pieces_in_R} pieces of R checked; c₁ > 0 under Assumption 1", details)


# --------------------------------------------------------------------------
# lemma3.hatV_bounds
# --------------------------------------------------------------------------


class HatVBounds(Obligation):
    """``lemma3.hatV_bounds``: eq. (hatVandHatR) and ``K ≻ 0 ⇔ k₁k₄ > k₃²``."""

    id = "lemma3.hatV_bounds"
    paper = "Lemma 3, eq. (hatVandHatR) and its proof"
    statement = (
        "V̂ = ½wᵀKw with w = (|σ|, |dz(φ)|, |v|); for positive k: K ≻ 0 ⇔ k₁k₄ > k₃², and "
        "ĉ₁|x|²_𝒜 ≤ V̂ ≤ ĉ₂|x|²_𝒜 with ĉ₂ = ½λ_max(K) and ĉ₁ = ½λ_min(K) (> 0 iff k₁k₄ > k₃²) "
        "or the sharper ĉ₁ = ½min(k₁,k₂,k₄), valid for every positive k because w ≥ 0"
    )
    method = (
        "sympy identity per piece of φ; Sylvester's criterion (leading principal minors, factored); "
        "exact eigenvalue identities of K; sign-definite decomposition over the three cases of min(k₁,k₂,k₄)"
    )

    def derive(self) -> HatVBoundsSubject:
        g = G()
        k = k_symbols()
        K = _symbolic.K_hat(*k)
        _, eig = block_eigen_bounds(K, what="K")
        dz = shared_value(_symbolic.dz, g.phi, g.f_c)
        definiteness = next(c for c in k_conditions(g.k_p, g.k_i, g.k_v, *k) if c.kind == "definiteness")
        return HatVBoundsSubject(
            sigma=g.sigma,
            phi=g.phi,
            v=g.v,
            f_c=g.f_c,
            k=k,
            Vhat=shared_value(vhat_expression, g, k),
            K=K,
            w=(sp.Abs(g.sigma), sp.Abs(dz), sp.Abs(g.v)),
            dist2=distance_squared(g),
            definiteness=definiteness.margin,
            c1_hat=sp.Min(k[0], k[1], k[3]) / 2,
            c1_hat_eig=eig["lam_min"] / 2,
            c2_hat=eig["lam_max"] / 2,
            cases=tuple(phi_cases(g.phi, g.f_c)),
        )

    def verify(self, subject: HatVBoundsSubject) -> Outcome:
        problem = statement_failure(subject.statement, lambda c1, c2, dist2, Vh: (Vh - c1 * dist2, c2 * dist2 - Vh))
        if problem:
            return Outcome.fail(f"eq. (hatVandHatR) as Proposition 1 uses it: {problem}")
        s = subject
        failures: list[str] = []
        half = sp.Rational(1, 2)
        w = sp.Matrix(s.w)
        for case in s.cases:
            try:
                quad = resolve_piecewise(case((half * w.T * s.K * w)[0]))
                vhat = resolve_piecewise(case(s.Vhat))
                dist = resolve_piecewise(case(s.dist2))
                norm = resolve_piecewise(case((w.T * w)[0]))
            except Undecided as exc:
                failures.append(f"{case.label}: {exc}")
                continue
            if not is_zero(vhat - quad):
                failures.append(f"{case.label}: V̂ − ½wᵀKw = {fp.factor(vhat - quad)} ≠ 0")
            if not is_zero(dist - norm):
                failures.append(f"{case.label}: |x|²_𝒜 − |w|² = {fp.factor(dist - norm)} ≠ 0")
        # Sylvester's criterion: K ≻ 0 iff its leading principal minors are positive
        minors = [s.K[:n, :n].det() for n in (1, 2, 3)]
        for n, m in enumerate(minors[:2], start=1):
            if sign_of(m) != 1:
                failures.append(f"leading minor {n} of K, {m}, is not positive for positive k")
        third = canonical(minors[2]) if sign_of(minors[2]) is None else None
        if third is None or third != canonical(s.definiteness):
            failures.append(
                f"det K = {fp.factor(minors[2])} is not a positive multiple of the stated condition "
                f"{s.definiteness} > 0"
            )
        checks, eig = block_eigen_bounds(s.K, what="K")
        failures += [f"eigenvalue bound: {label} fails" for label, ok in checks if not ok]
        if not is_upper_bound_of(2 * s.c2_hat, [eig["m"], eig["mu_plus"]]):
            failures.append(f"2ĉ₂ = {2 * s.c2_hat} is not ≥ every eigenvalue of K")
        if not is_lower_bound_of(2 * s.c1_hat_eig, [eig["m"], eig["mu_minus"]]):
            failures.append(f"2ĉ₁ = {2 * s.c1_hat_eig} (eigenvalue route) is not ≤ every eigenvalue of K")
        det_outer = s.K[0, 0] * s.K[2, 2] - s.K[0, 2] ** 2
        if canonical(det_outer) != canonical(s.definiteness):
            failures.append("λ_min(K) > 0 is not equivalent to the stated condition (outer determinant differs)")
        # the sharper bound on nonnegative vectors, one case per index of min(k₁, k₂, k₄)
        W = sp.symbols("w_1 w_2 w_3", nonnegative=True)
        Wv = sp.Matrix(W)
        diag = {0: s.K[0, 0], 1: s.K[1, 1], 2: s.K[2, 2]}
        slack = sp.symbols("s_1 s_2 s_3", nonnegative=True)
        tight_rows = []
        for j in range(3):
            # k_j is the smallest diagonal entry: the others are k_j + s with s ≥ 0
            sub = {}
            for i in range(3):
                if i != j and diag[i].is_Symbol:
                    sub[diag[i]] = diag[j] + slack[i]
            if len(sub) != 2 or not diag[j].is_Symbol:
                failures.append("the diagonal of K is not (k₁, k₂, k₄)")
                break
            gap = ((half * Wv.T * s.K * Wv)[0] - s.c1_hat * (Wv.T * Wv)[0]).xreplace(sub)
            if not is_nonneg(gap):
                failures.append(
                    f"½wᵀKw ≥ ĉ₁|w|² not shown for w ≥ 0 when {diag[j]} is the smallest diagonal entry "
                    f"(gap {sp.expand(gap)})"
                )
                continue
            at_unit = gap.xreplace({W[i]: (1 if i == j else 0) for i in range(3)})
            tight_rows.append(f"e_{j + 1}: {latex(ff.simplify(at_unit))}")
        details = (
            ("K", latex(s.K)),
            ("\\text{leading principal minors of } K", ",\\ ".join(latex(fp.factor(m)) for m in minors)),
            ("K \\succ 0 \\iff", f"{latex(s.definiteness)} > 0"),
            ("\\hat c_1 \\text{ (nonnegative } w)", latex(s.c1_hat)),
            ("\\hat c_1 = \\tfrac12\\lambda_{min}(K),\\ \\hat c_2 = \\tfrac12\\lambda_{max}(K)", f"{latex(s.c1_hat_eig)},\\quad {latex(s.c2_hat)}"),
            ("\\tfrac12 w^TKw - \\hat c_1|w|^2 \\text{ at the minimising unit vector}", rows_latex(tight_rows)),
        )
        if failures:
            return Outcome.fail(_fmt_failures(failures), details)
        return Outcome(
            True,
            "ĉ₁ = ½min(k₁,k₂,k₄) is tight on nonnegative w (attained at a unit vector) and needs no k₁k₄ > k₃²",
            details,
        )


# --------------------------------------------------------------------------
# lemma3.hatV_derivative
# --------------------------------------------------------------------------


class HatVDerivative(Obligation):
    """``lemma3.hatV_derivative``: derive the ``k``-conditions of ``V̂° ≤ 0`` and compare with the stated list."""

    id = "lemma3.hatV_derivative"
    paper = "Lemma 3, eq. (hatVdot) and its proof (eqs. diffEqForHatV, almostEverywhereDerivatives)"
    statement = (
        "On R̂∩{v>0} and R̂∩{v<0}, for σ ≷ 0 and σ = 0 (Clarke ∂|σ| = [−1, 1]), V̂° ≤ 0 holds iff "
        "k₃k_v ≥ k_i k₁, k₃ ≥ k₂, k₄k_v ≥ k_i k₃, k₄ ≥ k_p k₂ (derived from V̂ and F, each shown necessary); "
        "with K ≻ 0 ⇔ k₁k₄ > k₃² these are exactly the paper's k₃ > max{(k_i/k_v)k₁, k₂}, "
        "k₄ > max{(k_i/k_v)k₃, k_p k₂, k₃²/k₁} (stated strictly; non-strict suffices for V̂° ≤ 0)"
    )
    method = (
        "exhaustive case split of R̂ (v ≷ 0, σ ≷ 0 or = 0, φ against ±f_c) with positive parametrisations; "
        "Clarke gradient (max of C¹ functions) at σ = 0; coefficientwise sign-definite decomposition of V̂°; "
        "necessity by leading-term scaling; canonical comparison of condition sets"
    )
    errata = (
        Erratum(
            where="Lemma 3, proof of eq. (hatVdot), sentence before the bracketed bound",
            paper_says="max_{ζ∈∂|σ|}(−k_i k₃|v|²ζ) = k_i k₃|v|² for all x ∈ R̂_>",
            correct=(
                "max_{ζ∈∂|σ|}(−k_i k₃|v|²ζ) ≤ k_i k₃|v|², with equality iff σ ≤ 0; for σ > 0, ∂|σ| = {1} and "
                "the max is −k_i k₃|v|². The bound that follows only needs ≤, so the proof stands"
            ),
            checked_by="lemma3.hatV_derivative",
        ),
    )

    def derive(self) -> HatVDerivativeSubject:
        g = G()
        k = k_symbols()
        x = sp.Matrix([g.sigma, g.phi, g.v])
        F = _symbolic.A(g) * x - _symbolic.b(g) * sp.sign(g.v)
        dz = shared_value(_symbolic.dz, g.phi, g.f_c)
        pairs = _paper_pairs(g, k)
        return HatVDerivativeSubject(
            sigma=g.sigma,
            phi=g.phi,
            v=g.v,
            f_c=g.f_c,
            gains=(g.k_p, g.k_i, g.k_v),
            k=k,
            zeta=sp.Symbol("zeta", real=True),
            Vhat=shared_value(vhat_expression, g, k),
            F=tuple(F),
            region=shared_value(region_R, g),
            K=_symbolic.K_hat(*k),
            stated=k_conditions(g.k_p, g.k_i, g.k_v, *k),
            paper_bound=sp.Add(*[p[0] for p in pairs]),
            paper_pairs=pairs,
            f_v_bound=-g.k_v * sp.Abs(g.v) - sp.Abs(dz),
            zeta_claim=g.k_i * k[2] * sp.Abs(g.v) ** 2,
            cases=tuple(
                case_grid(sign_cases(g.v, "v", "a_v"), sign_cases(g.sigma, "σ", "a_sigma"), phi_cases(g.phi, g.f_c))
            ),
        )

    def verify(self, subject: HatVDerivativeSubject) -> Outcome:
        # V̂° ≤ 0 on R̂ gives, by Fact 2 (Dini derivative bound), V̂(t₂) ≤ V̂(t₁) while in R̂
        problem = statement_failure(subject.statement, lambda later, earlier: earlier - later)
        if problem:
            return Outcome.fail(f"eq. (hatVdot) as Proposition 1 uses it: {problem}")
        s = subject
        # ½dz(φ)² must be C¹ for its piecewise derivative to be the gradient
        failures = _c1_failures(s)
        derived, more, info = derived_k_conditions(s)
        failures += more
        notes: list[str] = []
        # the definiteness condition (K ≻ 0), as in the paper's list
        minors = [s.K[:n, :n].det() for n in (1, 2, 3)]
        if not all(sign_of(m) == 1 for m in minors[:2]) or sign_of(minors[2]) is not None:
            failures.append("the leading minors of K do not reduce K ≻ 0 to one condition")
            definiteness = None
        else:
            definiteness = _Derived(canonical(minors[2]), True, "K ≻ 0 (Sylvester)", True)
        premise = [_Derived(_condition_key(kj), True, "premise: k₁ … k₄ positive") for kj in s.k]
        all_derived = premise + derived + ([definiteness] if definiteness else [])
        if any(not d.necessary for d in derived):
            notes.append(
                "only sufficient: " + ", ".join(f"{d.expr} ≥ 0" for d in derived if not d.necessary)
            )
        # compare with the stated list
        stated = {}
        for cond in s.stated:
            try:
                stated[_condition_key(cond.margin)] = cond
            except ValueError as exc:
                failures.append(f"stated condition {cond.name}: {exc}")
        derived_map = {d.expr: d for d in all_derived}
        for key, d in derived_map.items():
            if key not in stated:
                failures.append(f"derived condition {key} {'>' if d.strict else '≥'} 0 ({d.origin}) is not stated")
            elif d.strict and not stated[key].strict:
                failures.append(f"stated {stated[key].name} must be strict")
        for key, cond in stated.items():
            if key not in derived_map:
                failures.append(f"stated condition {cond.name} (i.e. {key} > 0) is not derived from V̂ and F")
        # the paper's intermediate claims
        claim_rows, claim_failures, eq_cases, strict_cases = _paper_claims(s, info, derived)
        failures += claim_failures
        deriv_rows = [f"{latex(d.expr)} \\ge 0" + ("" if d.necessary else r"\ (\text{sufficient only})") for d in derived]
        rep = next(
            (
                (c, vals)
                for c, vals in info["pieces"]
                if c.label.startswith("v > 0") and "σ < 0" in c.label and "φ < -f_c" in c.label
            ),
            None,
        )
        details = [
            ("\\partial \\hat V \\ (\\zeta \\in \\mathrm{SGN}(\\sigma))", latex(sp.Matrix(info["grad"]))),
            ("F \\text{ on } \\hat R", latex(sp.Matrix(s.F))),
        ]
        if rep is not None:
            details.append(
                (
                    "\\hat V^\\circ \\text{ on } \\hat R \\cap \\{v>0, \\sigma<0, \\phi<-f_c\\}\\ "
                    "(|\\sigma| = a_\\sigma, |\\mathrm{dz}| = d_\\phi, |v| = a_v)",
                    latex(sp.collect(sp.expand(rep[1][0][1]), [rep[0].slacks[0]])),
                )
            )
        details += [
            ("\\text{derived from } \\hat V^\\circ \\le 0 \\text{ (necessary and sufficient)}", rows_latex(deriv_rows)),
            ("\\text{derived from } K \\succ 0", f"{latex(definiteness.expr)} > 0" if definiteness else "-"),
            ("\\text{stated in the paper}", rows_latex([f"{latex(c.lhs)} > {latex(c.rhs)}" for c in s.stated])),
        ]
        comparison = []
        for key, d in sorted(derived_map.items(), key=lambda kv: sp.default_sort_key(kv[0])):
            cond = stated.get(key)
            if cond is None:
                continue
            need = ">" if d.strict else "\\ge"
            comparison.append(
                f"{latex(cond.lhs)} > {latex(cond.rhs)}:\\ \\text{{derived with }} {need}"
                + ("\\ (\\text{stated strictly: sufficient, with a margin})" if not d.strict else "")
            )
        details.append(("\\text{stated vs derived}", rows_latex(comparison)))
        details += claim_rows
        if failures:
            return Outcome.fail(_fmt_failures(failures), tuple(details))
        remark = (
            f"derived set = stated set ({len(stated)} conditions); the four V̂° conditions are necessary and "
            "sufficient in non-strict form, the stated strict form is sufficient; "
            f"max over ∂|σ| equals k_i k₃|v|² in {eq_cases} pieces and is smaller in {strict_cases}"
        )
        if notes:
            remark += "; " + "; ".join(notes)
        return Outcome(True, remark, tuple(details))


OBLIGATIONS = (LemmaR, HatVBounds, HatVDerivative)
