"""The closed-form certificate proved for all gains, and the monotonicity that makes box certificates work.

* ``closed_form.all_gains`` — for symbolic gains with ``k_v·k_p > k_i > 0``,
  ``f_c > 0``, symbolic ``μ > 0`` and symbolic ``S``, ``S′`` satisfying their
  defining inequalities, the constants of
  :func:`~symbolic_friction._certify.closed_form.closed_form_formulas` (run
  here with symbolic operations, so the package's own code is what is
  proved) satisfy *every* premise that the exact verifier's
  :func:`~symbolic_friction._certify.verify.premises` builds.  This writes
  down the ``k₁ … k₄`` whose existence the paper (Lemma 3) argues.
  The verification splits into cases, each written with fresh positive
  symbols that cover it exactly (boundaries included, as their own cases):

  - which argument wins in ``ρ = max(r, 1)`` (``r > 1``, ``r = 1``, ``r < 1``)
    and in ``k₄ = (1+μ)·max(2k_p, k₃²/2)``;
  - the gains ``a = k_v/k_i``, ``k_p`` with ``a·k_p > 1`` as ``a = 2/p + τ/2``,
    ``k_p = (p + τ)/2`` (``p, τ > 0``; a bijection: ``p = ℓ − (a − k_p)``,
    ``τ = a + k_p − ℓ`` with ``ℓ = √((a − k_p)² + 4)``), which makes
    ``ℓ = (4 + p²)/(2p)`` rational and ``λ_min(B) = τ/2``; ``p`` is split at 2
    (the sign of ``a − k_p``);
  - ``S = ℓ + σ`` (``σ ≥ 0``: every ``S ≥ 0`` with ``S² ≥ ℓ²``), and which
    argument wins in ``c₁ = min(1, (a·k_p − 1)/c₂)``, with its rounding down
    ``c₁ = m/(1 + ε)``, ``ε ≥ 0``;
  - ``S′ = R`` with ``R > 0``, ``R² = q′ + u``, ``u ≥ 0``: a premise that is
    then ``A + B·R`` is decided from the signs of ``A``, ``B`` and
    ``B²R² − A²`` (``B ≥ 0`` and ``B²R² ≥ A²`` give ``B·R ≥ |A|``);
  - ``κ = √(c₂ĉ₂/(c₁ĉ₁) + ε_κ)``, ``ε_κ ≥ 0`` (rounded up).

  Every sign is decided by :func:`._decide.sign_of` (coefficients of one sign).
* ``closed_form.monotone`` — every premise's margin, with the constants fixed
  (positive symbols), depends on the gains through ``a`` and ``k_p`` only
  (after dividing by a power of ``k_i > 0``), and is monotone in each:
  scalar premises by the sign of the partial derivatives, semidefinite
  premises by the Loewner order of the derivative matrices (``⪰ 0`` or
  ``⪯ 0``, all principal minors).  So the least margin over a box
  ``[a_lo, a_hi] × [kp_lo, kp_hi]`` is at one of its four corners, and a box
  certificate that holds at the four corners holds on the whole box.
* ``closed_form.balanced`` — the variant
  :func:`~symbolic_friction._certify.closed_form.balanced` (``k₁ = k₄ = T``,
  ``ĉ₂ = (T + k₃)/2``, ``T² ≥ (1+μ)k₃²``) where the two conditions of
  :func:`~symbolic_friction._certify.closed_form.balanced_conditions` hold:
  those functions and ``premises`` run on symbols; for ``r = k_i/k_v > 1`` the
  second condition fails (so ``ρ = 1`` wherever the variant applies, and the
  code's ``max(r, 1)`` picks 1 there); where they hold, parametrised exactly by
  :func:`._closed_form_cases.balanced_cases` (boundaries as their own cases),
  every premise holds: a row equal to the ``k₁ = 2`` form's (those on ``P``,
  ``c₁``, ``c₂``, which the variant does not change) is
  ``closed_form.all_gains``'; every other row is decided here, ``T`` entering
  as ``A + B·T`` with ``T² = (1+μ)k₃² + v``; and the numeric builder gives
  these constants at sample gains.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import sympy as sp

from .._certify import verify as _verify
from .._certify.certificate import kappa_squared
from .._certify.closed_form import (
    balanced,
    balanced_conditions,
    balanced_formulas,
    balanced_radicand,
    closed_form_constants,
    closed_form_formulas,
)
from ._base import Obligation, Outcome
from ._decide import is_zero, sign_of
from .certificate import SymbolicCertificate

__all__ = ["OBLIGATIONS", "ClosedFormAllGains", "ClosedFormMonotone", "ClosedFormBalanced", "AllGainsSubject", "MonotoneSubject"]

from . import _fastforms as ff
from . import _fastpoly as fp
from ._closed_form_balanced import BALANCED_SAMPLES, BalancedSubject, stated_mismatch
from ._closed_form_cases import (
    BASE,
    K_SYMBOLS,
    P_SYMBOLS,
    balanced_cases,
    decide_cases,
    decide_group,
    decide_in,
    evaluate,
    frac_sign,
    k_cases,
    p_cases,
)


class _SymOps:
    """The operations of :func:`closed_form_formulas` for one choice of the winning ``max``/``min`` arguments."""

    def __init__(self, choice: dict[str, int]) -> None:
        self.choice = choice
        self.picks: list[tuple[str, str, sp.Expr, sp.Expr]] = []  # (name, "max"|"min", chosen, other)
        self.roots: list[tuple[str, sp.Expr]] = []

    def _pick(self, kind: str, name: str, x: Any, y: Any) -> Any:
        chosen, other = (x, y) if self.choice[name] == 0 else (y, x)
        self.picks.append((name, kind, sp.sympify(chosen), sp.sympify(other)))
        return chosen

    def max(self, name: str, x: Any, y: Any) -> Any:
        return self._pick("max", name, x, y)

    def min(self, name: str, x: Any, y: Any) -> Any:
        return self._pick("min", name, x, y)

    def sqrt_up(self, name: str, q: Any) -> Any:
        self.roots.append((name, sp.sympify(q)))
        return BASE["R"] if name == "S_hat" else BASE["S"]  # S and S_lo: the same number at a point

    def round_down(self, name: str, q: Any) -> Any:
        return q / (1 + BASE["eps"])


@dataclass(frozen=True)
class AllGainsSubject:
    """Per choice of the winning arguments: the premises' rows, the picks, the square roots and the constants;
    and the numeric builder's constants at sample gains ``(a, k_p, μ)``."""

    branches: tuple[tuple[dict[str, int], tuple[tuple[str, sp.Expr, str], ...], tuple, tuple], ...]
    constants: tuple[dict[str, Any], ...] = ()
    samples: tuple[tuple[Fraction, Fraction, Fraction, Any], ...] = ()


def stated_closed_form(choice: dict[str, int]) -> dict[str, sp.Expr]:
    """The closed form as the documentation states it, for one choice of the winning arguments."""
    a, k_p, mu, S, R, eps = (BASE[n] for n in ("a", "k_p", "mu", "S", "R", "eps"))
    rho = 1 / a if choice["rho"] == 0 else sp.Integer(1)
    k3 = 2 * (1 + mu) * rho
    k4 = (1 + mu) * (2 * k_p if choice["k4"] == 0 else k3**2 / 2)
    c2 = (a + k_p + S) / 2
    c1 = (sp.Integer(1) if choice["c1"] == 0 else (a * k_p - 1) / c2) / (1 + eps)
    return {"k1": sp.Integer(2), "k2": sp.Integer(2), "k3": k3, "k4": k4, "c1": c1, "c2": c2,
            "c1_hat": sp.Integer(1), "c2_hat": (1 + k4 / 2 + R) / 2}


_F = Fraction
SAMPLES: tuple[tuple[Fraction, Fraction, Fraction], ...] = (
    (_F(8, 5), _F(3), _F(1, 10**6)),  # Table I, case (a)
    (_F(75, 4), _F(33, 50), _F(1, 10**6)),  # Table I, case (b)
    (_F(1), _F(2), _F(1, 100)),  # r = 1, a = k_p
    (_F(1, 2), 4 * (1 + _F(1, 10**6)) ** 2, _F(1, 10**6)),  # 2k_p = k₃²/2
    (_F(10**12), _F(1, 10**6), _F(1, 10**6)),  # ratios of 10¹²
    (_F(1, 10**6), (1 + _F(1, 10**30)) * 10**6, _F(1, 10**6)),  # Routh margin 1 + 10⁻³⁰
)
"""Gains ``(a, k_p, μ)`` at which the numeric builder is compared with the stated closed form (boundaries included)."""


def _sample_mismatch(a: Fraction, kp: Fraction, mu: Fraction, c: Any) -> str:
    """Why the numeric constants ``c`` are not the stated closed form at ``(a, k_p, μ)`` (empty if they are)."""
    rho = max(1 / a, Fraction(1))
    k3 = 2 * (1 + mu) * rho
    k4 = (1 + mu) * max(2 * kp, k3 * k3 / 2)
    S, R = 2 * c.c2 - a - kp, 2 * c.c2_hat - 1 - k4 / 2
    wrong = [n for n, want in (("k1", 2), ("k2", 2), ("k3", k3), ("k4", k4), ("c1_hat", 1)) if getattr(c, n) != want]
    if not (S >= 0 and S * S >= (a - kp) ** 2 + 4):
        wrong.append("c2 (its S)")
    if not (R >= 0 and R * R >= (k4 / 2 - 1) ** 2 + k3 * k3):
        wrong.append("c2_hat (its S′)")
    if not 0 < c.c1 <= min(Fraction(1), (a * kp - 1) / c.c2):
        wrong.append("c1")
    return ", ".join(wrong)


def _rows(premises: list[Any]) -> tuple[tuple[str, sp.Expr, str], ...]:
    rows = []
    for p in premises:
        if isinstance(p, _verify.Semidefinite):
            rows += [(f"{p.name} [minor {{{','.join(str(i + 1) for i in idx)}}}]", m, ">=") for idx, m in p.minors()]
        else:
            margin, kind = p.margin()
            rows.append((p.name, sp.sympify(margin), kind))
    return tuple(rows)


def _certificate(constants: dict[str, Any]) -> SymbolicCertificate:
    a, k_p, k_i, f_c = BASE["a"], BASE["k_p"], BASE["k_i"], BASE["f_c"]
    k_v = a * k_i
    c = constants
    # κ rounded up: any κ > 0 with κ² ≥ c₂ĉ₂/(c₁ĉ₁) is √(c₂ĉ₂/(c₁ĉ₁) + ε_κ), ε_κ ≥ 0 (unevaluated: sympy's
    # assumptions on the large radicand cost more than the whole decision)
    kappa = sp.Pow(kappa_squared(c["c1"], c["c2"], c["c1_hat"], c["c2_hat"]) + BASE["eps_kappa"], sp.Rational(1, 2), evaluate=False)
    return SymbolicCertificate(k_p, k_i, k_v, f_c, c["k1"], c["k2"], c["k3"], c["k4"], 2 * (k_v * k_p - k_i),
                               c["c1"], c["c2"], c["c1_hat"], c["c2_hat"], kappa)


_CHOICES = ("rho", "k4", "c1")


class ClosedFormAllGains(Obligation):
    id = "closed_form.all_gains"
    paper = "Lemma 3 (existence of k₁ … k₄), Lemma 2, Proposition 1; the exact verifier's premises"
    statement = (
        "for all gains with k_v·k_p > k_i > 0, f_c > 0, all μ > 0 and all S, S′ ≥ 0 with S² ≥ (a − k_p)² + 4, "
        "S′² ≥ (k₄/2 − 1)² + k₃², the closed-form constants satisfy every premise of the exact verifier"
    )
    method = (
        "closed_form_formulas and verify.premises run on symbols; case split over the winner of ρ = max(r, 1), "
        "k₄ = (1+μ)max(2k_p, k₃²/2), c₁ = min(1, ·), the sign of a − k_p and the roundings, boundaries included; "
        "each case parametrised by positive symbols, signs decided by sign_of (S′ through A + B·S′)"
    )

    def derive(self) -> AllGainsSubject:
        a, k_p, mu = BASE["a"], BASE["k_p"], BASE["mu"]
        branches, consts = [], []
        for combo in itertools.product((0, 1), repeat=3):
            choice = dict(zip(_CHOICES, combo))
            ops = _SymOps(choice)
            constants = closed_form_formulas(a, a, k_p, k_p, mu, ops)
            rows = _rows(_verify.premises(_certificate(constants)))
            branches.append((choice, rows, tuple(ops.picks), tuple(ops.roots)))
            consts.append(constants)
        samples = tuple((a_, kp, mu_, closed_form_constants(a_, a_, kp, kp, mu=mu_)) for a_, kp, mu_ in SAMPLES)
        return AllGainsSubject(tuple(branches), tuple(consts), samples)

    def verify(self, subject: AllGainsSubject) -> Outcome:
        if len(subject.branches) != 8:
            return Outcome.fail(f"expected the 8 choices of the winning arguments; got {len(subject.branches)}")
        if len(subject.constants) != len(subject.branches) or not subject.samples:
            return Outcome.fail("the subject has no constants or no numeric samples to compare with the stated closed form")
        for (choice, *_), constants in zip(subject.branches, subject.constants):
            stated = stated_closed_form(choice)
            wrong = [n for n in stated if n not in constants or not is_zero(sp.sympify(constants[n]) - stated[n])]
            if wrong:
                return Outcome.fail(f"the code's closed form differs from the stated one in {', '.join(wrong)} ({choice})")
        for a_, kp, mu_, numeric in subject.samples:
            why = _sample_mismatch(a_, kp, mu_, numeric)
            if why:
                return Outcome.fail(f"closed_form_constants at a = {a_}, k_p = {kp}, μ = {mu_} differs from the stated closed form in {why}")
        decided: dict[tuple, str] = {}
        count = 0
        for choice, rows, picks, roots in subject.branches:
            names = sorted(p[0] for p in picks)
            if names != sorted(_CHOICES):
                return Outcome.fail(f"the closed form makes the choices {names}; the case split covers {sorted(_CHOICES)}")
            roots_by = dict(roots)
            if sorted(roots_by) != ["S", "S_hat", "S_lo"] or not is_zero(roots_by["S"] - roots_by["S_lo"]):
                return Outcome.fail(f"the square roots of the closed form are {sorted(roots_by)}; expected S = S_lo (a point) and S_hat")
            cases_p = p_cases(choice["c1"])
            cases_p_free = p_cases(None)
            cases_k = k_cases(choice["rho"], choice["k4"])
            radicand = roots_by["S_hat"]
            for name, kind, chosen, other in picks:
                group, cases = ("P", cases_p) if name == "c1" else ("K", cases_k)
                gap = chosen - other if kind == "max" else other - chosen
                why = decide_group(gap, ">=", group, cases)
                if why:
                    return Outcome.fail(f"{kind}({name}) does not pick {chosen} in the case {why}")
            for case in cases_p_free[::4]:  # σ = 0, ε = 0: S = ℓ, which must be the root itself
                ell = case.values[BASE["S"]]
                if not (evaluate(roots_by["S"], case.values) == ell**2 and frac_sign(ell) == 1):
                    return Outcome.fail(f"S = ℓ + σ does not cover every S ≥ 0 with S² ≥ (a − k_p)² + 4 in the case {case.label}")
            for case in cases_k:
                if frac_sign(evaluate(radicand, case.values) + case.radicand_extra) != 1:
                    return Outcome.fail(f"the radicand of S′ is not positive in the case {case.label}")
            for name, margin, kind in rows:
                free = margin.free_symbols
                key = (name, choice["c1"] if free & P_SYMBOLS else None,
                       (choice["rho"], choice["k4"]) if free & K_SYMBOLS else None)
                if key not in decided:
                    count += 1
                    cases = cases_p if free & {BASE["eps"]} else cases_p_free
                    decided[key] = decide_in(margin, kind, cases, cases_k, radicand)
                if decided[key]:
                    branch = ", ".join(f"{n} picks argument {i + 1}" for n, i in choice.items())
                    return Outcome.fail(f"premise {name} ({kind} 0) is not proved in the case {decided[key]} ({branch})")
        return Outcome(True, f"the stated closed form is the code's (symbolically, and at {len(subject.samples)} sample gains); "
                             f"all premises hold for all gains: {count} premise groups decided over their cases")


@dataclass(frozen=True)
class MonotoneSubject:
    """The verifier's premises for symbolic constants and gains ``k_v = a·k_i`` (``c`` the gains' own decrease rate)."""

    rows: tuple[tuple[str, str, Any], ...]  # (name, kind, margin) or (name, "psd", matrix)
    variables: tuple[sp.Symbol, ...]  # a, k_p, f_c
    scale: sp.Symbol  # k_i


def _monotone_certificate() -> SymbolicCertificate:
    a, k_p, k_i, f_c = BASE["a"], BASE["k_p"], BASE["k_i"], BASE["f_c"]
    k_v = a * k_i
    consts = sp.symbols("k1 k2 k3 k4 c_1 c_2 chat_1 chat_2 kappa", positive=True)
    k1, k2, k3, k4, c1, c2, c1h, c2h, kappa = consts
    # in a box, c is not a constant: it is each gain set's own decrease rate 2(k_v·k_p − k_i)
    return SymbolicCertificate(k_p, k_i, k_v, f_c, k1, k2, k3, k4, 2 * (k_v * k_p - k_i), c1, c2, c1h, c2h, kappa)


def _direction(expr: sp.Expr, var: sp.Symbol) -> int | None:
    """The sign of ``∂expr/∂var`` on the positive orthant (1, 0, -1), or None if not decided."""
    return sign_of(ff.together(sp.diff(expr, var)))


def _loewner_direction(matrix: sp.Matrix, var: sp.Symbol) -> int | None:
    """1 if ``∂M/∂var ⪰ 0``, -1 if ``⪯ 0``, 0 if it vanishes (all principal minors decided), else None."""
    d = matrix.diff(var)
    if all(is_zero(x) for x in d):
        return 0
    n = d.shape[0]
    for sgn in (1, -1):
        m = sgn * d
        if all(sign_of(ff.together(m.extract(list(idx), list(idx)).det())) in (0, 1)
               for size in range(1, n + 1) for idx in itertools.combinations(range(n), size)):
            return sgn
    return None


class ClosedFormMonotone(Obligation):
    id = "closed_form.monotone"
    paper = "Lemma 2, Lemma 3, Proposition 1 for a box of gains (beyond the paper)"
    statement = (
        "with the constants fixed, every premise of the exact verifier depends on the gains through a = k_v/k_i, "
        "k_p and f_c only (up to a positive power of k_i) and monotonically in each, so its least margin over a box "
        "is at a corner: the 4 corners {k_p lo, hi} × {(k_i hi, k_v lo), (k_i lo, k_v hi)} at the lowest f_c decide a box"
    )
    method = (
        "verify.premises run on symbols; scalar premises: the sign of each partial derivative by sign_of; "
        "semidefinite premises: the derivative matrices ⪰ 0 or ⪯ 0 by all principal minors (Loewner order)"
    )

    def derive(self) -> MonotoneSubject:
        rows: list[tuple[str, str, Any]] = []
        for premise in _verify.premises(_monotone_certificate()):
            if isinstance(premise, _verify.Semidefinite):
                rows.append((premise.name, "psd", sp.Matrix(premise.matrix)))
            else:
                margin, kind = premise.margin()
                rows.append((premise.name, kind, sp.sympify(margin)))
        return MonotoneSubject(tuple(rows), (BASE["a"], BASE["k_p"], BASE["f_c"]), BASE["k_i"])

    def verify(self, subject: MonotoneSubject) -> Outcome:
        if not subject.rows:
            return Outcome.fail("no premise to check")
        words = {1: "increasing", -1: "decreasing", 0: "constant"}
        directions = []
        for name, kind, value in subject.rows:
            if kind == "==":
                if not is_zero(value):
                    return Outcome.fail(f"premise {name} is an equation that does not hold identically on a box")
                continue
            if kind == "psd":
                if subject.scale in value.free_symbols:
                    return Outcome.fail(f"premise {name} depends on k_i beyond a = k_v/k_i")
                dirs = [_loewner_direction(value, v) for v in subject.variables]
            else:
                reduced = next((r for j in range(3) if subject.scale not in (r := fp.cancel(value / subject.scale**j)).free_symbols), None)
                if reduced is None:
                    return Outcome.fail(f"premise {name} depends on k_i beyond a = k_v/k_i and a positive power of k_i")
                dirs = [_direction(reduced, v) for v in subject.variables]
            bad = [str(v) for v, d in zip(subject.variables, dirs) if d is None]
            if bad:
                return Outcome.fail(f"premise {name} is not shown monotone in {', '.join(bad)}")
            directions.append(f"{name}: " + ", ".join(f"{words[d]} in {v}" for v, d in zip(subject.variables, dirs) if d))
        return Outcome(True, f"all {len(subject.rows)} premises are monotone in a, k_p and f_c",
                       (("\\text{premises}", str(len(subject.rows))),))


class ClosedFormBalanced(Obligation):
    id = "closed_form.balanced"
    paper = "Lemma 3 (k₁ … k₄), Lemma 2, Proposition 1; the exact verifier's premises"
    statement = (
        "for all gains with k_v·k_p > k_i > 0, f_c > 0, all μ > 0 and all T ≥ 0 with T² ≥ (1+μ)k₃²: where "
        "T ≥ (1+μ)·2k_p and (1+μ)·T ≤ k₃·a, the closed form with k₁ = k₄ = T, ĉ₂ = (T + k₃)/2 satisfies every premise "
        "of the exact verifier; for k_i/k_v > 1 those conditions never hold"
    )
    method = (
        "balanced_formulas, balanced_conditions and verify.premises run on symbols; the conditions' set "
        "parametrised exactly (k_p = T/(2(1+μ)(1+α)), a = T(1+β)/2, T² = (1+μ)k₃² + v, each slack = 0 or > 0); "
        "rows unchanged from the k₁ = 2 form are closed_form.all_gains'; the others decided as A + B·T"
    )

    def derive(self) -> BalancedSubject:
        a, k_p, mu, T = BASE["a"], BASE["k_p"], BASE["mu"], BASE["R"]
        rows = []
        for c1_choice in (0, 1):  # c₁'s choice changes only rows of P, which the variant keeps
            ops = _SymOps({"rho": 1, "k4": 0, "c1": c1_choice})
            base = closed_form_formulas(a, a, k_p, k_p, mu, ops)
            constants = {**base, **balanced_formulas(base["k3"], T)}
            rows.append((c1_choice, _rows(_verify.premises(_certificate(constants))), _rows(_verify.premises(_certificate(base)))))
        # k₃ and the ρ pick do not depend on c₁'s choice: read them from the last
        region = tuple((n, sp.sympify(m)) for n, m in balanced_conditions(a, k_p, base["k3"], mu, T))
        rho_pick = next(chosen - other for name, _, chosen, other in ops.picks if name == "rho")
        radicand = sp.sympify(balanced_radicand(base["k3"], mu))
        ops = _SymOps({"rho": 0, "k4": 0, "c1": 0})
        base = closed_form_formulas(a, a, k_p, k_p, mu, ops)
        above = tuple((n, sp.sympify(m)) for n, m in balanced_conditions(a, k_p, base["k3"], mu, T))
        samples = []
        for a_, kp, mu_, loose in BALANCED_SAMPLES:
            c = closed_form_constants(a_, a_, kp, kp, mu=mu_, loose=loose)
            samples.append((a_, kp, mu_, loose, c, balanced(c, a_, kp)))
        return BalancedSubject(tuple(rows), region, sp.sympify(rho_pick), radicand, above,
                               sp.sympify(balanced_radicand(base["k3"], mu)), tuple(samples))

    def verify(self, subject: BalancedSubject) -> Outcome:
        if not subject.rows or not subject.region or not subject.samples:
            return Outcome.fail("the subject has no premise rows, no conditions or no numeric samples")
        # the cases are written for the stated conditions: the code's must be those, or the cases would not cover them
        a, k_p, mu, T = BASE["a"], BASE["k_p"], BASE["mu"], BASE["R"]
        stated = (T - (1 + mu) * 2 * k_p, 2 * (1 + mu) * a - (1 + mu) * T)  # k₃ = 2(1+μ) where ρ = 1
        if len(subject.region) != 2 or any(not is_zero(m - want) for (_, m), want in zip(subject.region, stated)):
            return Outcome.fail("the code's conditions are not the stated T ≥ (1+μ)·2k_p and (1+μ)·T ≤ k₃·a: "
                                + "; ".join(f"{n}: {m} ≥ 0" for n, m in subject.region))
        cases, cases_above = balanced_cases(1), balanced_cases(0)
        # r > 1: the second condition (1+μ)·T ≤ k₃·a fails, so the form never applies there
        name, margin = subject.above[-1]
        why = decide_cases(-margin, ">", cases_above, subject.radicand_above)
        if why:
            return Outcome.fail(f"for r > 1 the condition {name} is not shown to fail in the case {why}")
        # ρ = 1: the cases lie in the conditions' set, and the code's max(r, 1) picks 1 there
        for name, margin in subject.region:
            why = decide_cases(margin, ">=", cases, subject.radicand)
            if why:
                return Outcome.fail(f"the case {why} is not inside the condition {name}")
        why = decide_cases(subject.rho_pick, ">=", cases, subject.radicand)
        if why:
            return Outcome.fail(f"ρ = max(r, 1) does not pick 1 in the case {why}")
        decided = kept = 0
        for c1_choice, rows, base_rows in subject.rows:
            same = {(n, k): m for n, m, k in base_rows}
            cases_p = p_cases(c1_choice)
            for name, margin, kind in rows:
                if BASE["R"] not in margin.free_symbols and (name, kind) in same and is_zero(margin - same[(name, kind)]):
                    kept += 1  # the k₁ = 2 form's own row: closed_form.all_gains
                    continue
                decided += 1
                why = decide_in(margin, kind, cases_p, cases, subject.radicand)
                if why:
                    return Outcome.fail(f"premise {name} ({kind} 0) is not proved in the case {why} (c₁ choice {c1_choice + 1})")
        if not decided:
            return Outcome.fail("no premise row differs from the k₁ = 2 form: nothing was decided")
        for a_, kp, mu_, loose, base, got in subject.samples:
            why = stated_mismatch(base, got)
            if why:
                return Outcome.fail(f"balanced() at a = {a_}, k_p = {kp}, μ = {mu_} differs from the stated form in {why}")
        return Outcome(True, f"{decided} premise rows decided over {len(cases)} cases of the conditions' set, "
                             f"{kept} unchanged from closed_form.all_gains; for r > 1 the conditions fail "
                             f"({len(cases_above)} cases); the numeric builder is the stated form at {len(subject.samples)} gains")


OBLIGATIONS: tuple[type[Obligation], ...] = (ClosedFormAllGains, ClosedFormMonotone, ClosedFormBalanced)
