"""Reset PID (beyond the paper): the jump half of the hybrid closed loop of :mod:`symbolic_friction._model.reset`.

* ``reset.V_jump`` — ``V`` of eq. (lyapLikeV) does not increase across a jump: it
  is unchanged from ``|φ| ≤ f_c`` and decreases from ``|φ| > f_c`` (static friction).
* ``reset.no_second_jump`` — the post-jump state is not in ``D`` (the timer rules it
  out; for ``σ ≠ 0`` the law leaves ``φ`` on the boundary ``σφ = f_c|σ|``, where the
  kernel's strict rule does not jump again).
* ``reset.attractor`` — jumps map 𝒜 (eq. A) into itself.
* ``reset.basic_conditions`` — the hybrid basic conditions (Goebel, Sanfelice and
  Teel, *Hybrid Dynamical Systems*, 2012, Assumption 6.5): ``C`` and ``D`` closed
  (non-strict inequalities of continuous margins), ``G`` outer semicontinuous
  (the graph of ``SGN`` is closed), ``G(D)`` bounded on bounded sets.
* ``reset.leaves_stick`` — after a jump at ``σ ≠ 0`` the package's mode table
  (the appendix's rows iii/ix, ``model.modes_runtime``) starts a slip toward the
  setpoint at once, during which Lemma 2 (``lemma2.dVdt``, ``V' ≤ -c v²``) makes
  ``V`` decrease strictly: no solution with a jump keeps ``V`` constant off 𝒜.
* ``reset.same_stick_exits`` — a jump keeps ``σ`` and the stick still ends at
  ``(σ, sign(σ) f_s, 0)``, no later than without it: PID and reset PID pass through
  the same stick exits (with ``f_s > f_c``, the same hunting map, so PID's proved
  cycle is reset PID's), and resets never slow the approach.
* ``reset.kernel_binding`` — the event kernel's resets are the model's: from exact
  stick states it jumps exactly when the model's ``D`` says so, to ``G(x)``.

The flow part is the paper's own: Lemma 2 (``lemma2.*``) and Claim 1
(``claim1.cases``) are the obligations ``check`` already runs; nothing of them
is copied here.  With them the hybrid invariance principle (Goebel, Sanfelice
and Teel 2012, Corollary 8.4; cited, not mechanised) gives attractivity of
𝒜 × [0, τ_d] for every gain set of Assumption 1 with ``f_s = f_c`` and every
dwell ``τ_d > 0``; stability follows from ``V`` nonincreasing along flows and
jumps with the bounds of Lemma 2 and Lemma 3 as in Proposition 1 (jumps happen
at ``v = 0``, where ``V = (k_v/k_i)σ²`` and ``|x|_𝒜 = |σ|``).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Callable

import sympy as sp

from .._model import reset as _reset
from . import _fastforms as ff
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, Undecided, is_zero, latex, phi_classes, pos, sign_classes, sign_of
from ._shared import attractor_x, sgn_sets
from .lemma2 import friction_form, friction_minimum

__all__ = ["ResetVJump", "ResetNoSecondJump", "ResetAttractor", "ResetBasicConditions", "ResetLeavesStick",
           "ResetSameStickExits", "ResetKernelBinding", "OBLIGATIONS"]


@dataclass(frozen=True)
class JumpSubject:
    """The jump map and margins of :mod:`._model.reset` and ``V``'s form, for symbolic gains."""

    jump_map_x: Callable[..., tuple[Any, Any, Any]]
    jump_map_z: Callable[..., tuple[Any, Any, Any]]
    margins: Callable[..., tuple[Any, ...]]
    form: sp.Expr
    y: sp.Symbol
    g: Any


def _subject() -> JumpSubject:
    g = G()
    form, y = friction_form(g)
    return JumpSubject(_reset.jump_map_x, _reset.jump_map_z, _reset.jump_set_margins, form, y, g)


def _v_at_rest(S: JumpSubject, sigma: Any, phi: Any) -> sp.Expr:
    """``V(σ, φ, 0)`` of eq. (lyapLikeV): the form at ``y = 0`` plus its exact minimum over ``f ∈ f_c SGN(0)``."""
    # xreplace: the symbols' values, as subs gives them here, without subs's bookkeeping
    stick = S.form.xreplace({S.g.v: sp.Integer(0)}).xreplace({S.g.sigma: sp.sympify(sigma)})
    return fp.factor(stick.xreplace({S.y: sp.Integer(0)}) + friction_minimum(stick, S.y, phi, S.g.f_c, sgn_sets()[0]))


def _sign_sigma(label: str, tag: str) -> sp.Expr:
    """``s ∈ SGN(σ)``: ``±1``, or ``(a - b)/(a + b)`` (all of ``(-1, 1)``; the ends are the ``±1`` cases) at ``σ = 0``."""
    if label == "> 0":
        return sp.Integer(1)
    if label == "< 0":
        return sp.Integer(-1)
    a, b = pos(f"a{tag}"), pos(f"b{tag}")
    return (a - b) / (a + b)


class ResetVJump(Obligation):
    id = "reset.V_jump"
    paper = "beyond the paper: reset PID (future work of §V); eq. (lyapLikeV), Remark after Lemma 2"
    statement = "for x ∈ D (v = 0, |φ| ≤ f_s, σφ ≤ f_c|σ|) and x⁺ ∈ G(x): V(x⁺) = V(x) when |φ| ≤ f_c, V(x⁺) ≤ V(x) when |φ| > f_c"
    method = "V(σ, φ, 0) by the exact minimum over f ∈ f_c SGN(0), for every sign class of σ, every φ-class in D and every s ∈ SGN(σ); the difference is an identity or sign-definite"

    def derive(self) -> JumpSubject:
        return _subject()

    def verify(self, subject: JumpSubject) -> Outcome:
        S = subject
        details = []
        for s_label, _, sigma in sign_classes("sigma_j"):
            for label, tex, phi, _ in phi_classes(S.g.f_c, "_j"):
                abs_sigma, abs_phi = abs(sigma), abs(phi)
                margins = S.margins(sigma, phi, 0, abs_sigma, abs_phi, S.g.f_c, S.g.f_c + pos("excess_j"), 0, 0)
                if sign_of(margins[2]) == -1 or (label in ("φ > f_c", "φ < -f_c") and sign_of(margins[2]) is None):
                    continue  # not in D: φ beyond sign(σ)·f_c on σ's own side
                post = S.jump_map_x(sigma, phi, 0, S.g.f_c, _sign_sigma(s_label, "_j"))
                try:
                    before = _v_at_rest(S, sigma, phi)
                    after = _v_at_rest(S, post[0], post[1])
                except Undecided as exc:
                    return Outcome.fail(f"σ {s_label}, {label}: {exc}")
                if post[0] != sigma or post[2] != 0:
                    return Outcome.fail(f"σ {s_label}, {label}: the jump changes σ or v: {post}")
                change = fp.factor(after - before)
                if label in ("φ = f_c", "|φ| < f_c", "φ = -f_c"):
                    if not is_zero(change):
                        return Outcome.fail(f"σ {s_label}, {label}: V(x⁺) - V(x) = {change}, not 0", tuple(details))
                elif sign_of(-change) not in (0, 1):
                    return Outcome.fail(f"σ {s_label}, {label}: V(x⁺) - V(x) = {change} is not shown ≤ 0", tuple(details))
                details.append((f"\\sigma {s_label},\\ {tex}", f"V(x^+) - V(x) = {latex(change)}"))
        if len(details) < 7:
            return Outcome.fail(f"only {len(details)} (σ, φ) classes of D were decided", tuple(details))
        return Outcome(True, f"{len(details)} classes: V unchanged on the stick band, not increased beyond it", tuple(details))


class ResetNoSecondJump(Obligation):
    id = "reset.no_second_jump"
    paper = "beyond the paper: reset PID; Zeno solutions excluded"
    statement = "after a jump τ = 0 < τ_d, so (x⁺, τ⁺) ∉ D; for σ ≠ 0 the law puts φ⁺ on σφ⁺ = f_c|σ|, where the kernel's strict rule does not jump; successive jumps are ≥ τ_d apart"
    method = "the margins of D at (G(x), 0), exact signs for every sign class of σ"

    def derive(self) -> JumpSubject:
        return _subject()

    def verify(self, subject: JumpSubject) -> Outcome:
        S = subject
        dwell = pos("tau_d")
        details = []
        for s_label, _, sigma in sign_classes("sigma_n"):
            for label, _, phi, _ in phi_classes(S.g.f_c, "_n"):
                post = S.jump_map_x(sigma, phi, 0, S.g.f_c, _sign_sigma(s_label, "_n"))
                margins = S.margins(post[0], post[1], post[2], abs(post[0]), abs(post[1]), S.g.f_c, S.g.f_c, 0, dwell)
                if sign_of(margins[3]) != -1:
                    return Outcome.fail(f"σ {s_label}, {label}: the timer margin after a jump is {margins[3]}, not < 0")
                if s_label != "= 0" and not is_zero(margins[2]):
                    return Outcome.fail(f"σ {s_label}, {label}: after the jump f_c|σ| - σφ⁺ = {fp.factor(margins[2])}, not 0")
            details.append((f"\\sigma {s_label}", "\\tau^+ - \\tau_d = -\\tau_d < 0"))
        return Outcome(True, "the timer margin is -τ_d < 0 after every jump; σφ⁺ = f_c|σ| for σ ≠ 0", tuple(details))


class ResetAttractor(Obligation):
    id = "reset.attractor"
    paper = "beyond the paper: reset PID; eq. (A)"
    statement = "G maps 𝒜 ∩ D into 𝒜: at σ = 0, v = 0, |φ| ≤ f_c every x⁺ ∈ G(x) has σ⁺ = 0, v⁺ = 0, |φ⁺| ≤ f_c"
    method = "G at σ = 0 for s ∈ SGN(0) = [-1, 1] (its ends and its interior), against the package's 𝒜 (attractor_x)"

    def derive(self) -> JumpSubject:
        return _subject()

    def verify(self, subject: JumpSubject) -> Outcome:
        S = subject
        sigma_set, phi_set, v_set = attractor_x(S.g)
        for s in (sp.Integer(1), sp.Integer(-1), _sign_sigma("= 0", "_a")):
            for _, _, phi, region in phi_classes(S.g.f_c, "_a"):
                if not region.is_subset(phi_set):
                    continue
                post = S.jump_map_x(sp.Integer(0), phi, sp.Integer(0), S.g.f_c, s)
                if post[0] != sigma_set or post[2] != v_set:
                    return Outcome.fail(f"G(0, {phi}, 0) = {post} leaves σ = 0 or v = 0")
                bound = phi_set.sup
                if sign_of(bound - post[1]) not in (0, 1) or sign_of(bound + post[1]) not in (0, 1):
                    return Outcome.fail(f"G(0, {phi}, 0) has φ⁺ = {post[1]}, not within ±{bound}")
        return Outcome(True, "G(𝒜 ∩ D) ⊂ 𝒜", (("x \\in \\mathcal{A}", "G(x) \\subset \\{0\\} \\times [-f_c, f_c] \\times \\{0\\}"),))


class ResetBasicConditions(Obligation):
    id = "reset.basic_conditions"
    paper = "beyond the paper: reset PID; Goebel, Sanfelice, Teel (2012), Assumption 6.5"
    statement = "D = {every margin ≥ 0} with continuous margins (closed); C = ℝ³ × [0, τ_d] closed; the graph of σ ↦ f_c SGN(σ) is closed, so G is outer semicontinuous and locally bounded"
    method = "each margin is a polynomial in (σ, φ, v, |σ|, |φ|, τ); the graph of SGN equals {|s| ≤ 1, max(σ,0)(1-s) = 0, max(-σ,0)(1+s) = 0}, a zero set of continuous functions, checked on every sign class of σ"

    def derive(self) -> JumpSubject:
        return _subject()

    def verify(self, subject: JumpSubject) -> Outcome:
        S = subject
        a_s, a_p, tau, dwell, f_s = (sp.Symbol(n, real=True) for n in ("abs_sigma", "abs_phi", "tau", "tau_d", "f_s"))
        margins = S.margins(S.g.sigma, S.g.phi, S.g.v, a_s, a_p, S.g.f_c, f_s, tau, dwell)
        if len(margins) != len(_reset.JUMP_SET_MARGINS):
            return Outcome.fail(f"{len(margins)} margins, but D is documented with {len(_reset.JUMP_SET_MARGINS)}")
        gens = (S.g.sigma, S.g.phi, S.g.v, a_s, a_p, tau, dwell, S.g.f_c, f_s)
        for text, m in zip(_reset.JUMP_SET_MARGINS, margins):
            m = sp.sympify(m)
            if not m.is_polynomial(*gens) or m.has(sp.Abs, sp.sign, sp.floor, sp.Heaviside):
                return Outcome.fail(f"the margin {text!r} = {m} is not a polynomial (continuity unproved)")
        s = sp.Symbol("s", real=True)
        # the graph of SGN as a zero set; on each sign class of σ it must be exactly SGN(σ)
        for label, sign, sigma in sign_classes("sigma_b"):
            eqs = [sp.Max(sigma, 0) * (1 - s), sp.Max(-sigma, 0) * (1 + s)]
            sols = sp.Interval(-1, 1)
            for e in eqs:
                e = ff.simplify(e)  # 0 if identically 0: its zero set is then all of ℝ either way
                if e != 0:
                    sols = sols.intersect(sp.solveset(e, s, sp.S.Reals))
            post = {S.jump_map_x(sigma, 0, 0, 1, t)[1] for t in ((1,) if sign == 1 else (-1,) if sign == -1 else (-1, 0, 1))}
            want = sgn_sets()[sign]
            if sols != want:
                return Outcome.fail(f"σ {label}: the zero set gives s ∈ {sols}, but SGN(σ) = {want}")
            if not all(p in want for p in post):
                return Outcome.fail(f"σ {label}: G puts φ⁺/f_c = {post} outside SGN(σ) = {want}")
        return Outcome(True, f"{len(margins)} polynomial margins; the graph of SGN is closed",
                       tuple((t, "\\ge 0") for t in _reset.JUMP_SET_MARGINS))


class ResetLeavesStick(Obligation):
    id = "reset.leaves_stick"
    paper = "beyond the paper: reset PID; appendix table of Claim 1 (rows iii, ix), Lemma 2 item 2"
    statement = "after a jump at σ ≠ 0 the mode table slips at once in direction sign(σ) (v ≠ 0, where lemma2.dVdt gives V' ≤ -c v² < 0), so no solution with a jump off 𝒜 keeps V constant"
    method = "the package's runtime mode table (model.modes_runtime binds it to the appendix) at G(x) for exact σ ∈ {±10⁻⁶, ±1, ±10⁶}, f_c ∈ {1, 10⁻³, 10³}, with and without static friction"

    def derive(self):
        from .._simulation.modes import select_mode

        return (select_mode, _reset.jump_map_x)

    def verify(self, subject) -> Outcome:
        select_mode, jump = subject
        n = 0
        for f_c in (Fraction(1), Fraction(1, 1000), Fraction(1000)):
            for f_s in (None, f_c * Fraction(6, 5)):
                for sigma in (Fraction(1, 10**6), Fraction(1), Fraction(10**6)):
                    for d in (1, -1):
                        x = jump(d * sigma, Fraction(0), Fraction(0), f_c, d)
                        mode = select_mode(x[0], x[1], x[2], f_c, f_s)
                        want = d if f_s is None else 0  # with f_s > f_c the stick goes on to φ = ±f_s
                        if mode != want:
                            return Outcome.fail(f"after a jump at σ = {d * sigma}, f_c = {f_c}, f_s = {f_s}: mode {mode}, expected {want}")
                        n += 1
        return Outcome(True, f"{n} post-jump states: a slip toward the setpoint at once (f_s = f_c)")


class ResetSameStickExits(Obligation):
    id = "reset.same_stick_exits"
    paper = "beyond the paper: reset PID; the stick of eq. (subcasesAffine:f0) with a static level f_s ≥ f_c"
    statement = ("a jump during a stick keeps σ and leaves φ⁺ short of or at sign(σ) f_s, so the stick still ends at "
                 "(σ, sign(σ) f_s, 0): PID and reset PID have the same stick exits (the same hunting map when f_s > f_c), "
                 "and a jump only shortens the stick")
    method = ("in a stick σ' = 0, φ' = σ; from the jump's φ⁺ = f_c s (s = sign σ) the exit φ = s f_s is reached after "
              "(s f_s − φ⁺)/σ ≥ 0, and from any φ in D after (s f_s − φ)/σ ≥ that: exact signs for σ ≷ 0 and f_s = f_c + e, e ≥ 0")

    def derive(self) -> JumpSubject:
        return _subject()

    def verify(self, subject: JumpSubject) -> Outcome:
        S = subject
        excess = pos("e_x")
        details = []
        for f_s, f_label in ((S.g.f_c, "f_s = f_c"), (S.g.f_c + excess, "f_s > f_c")):
            for s_label, sign, sigma in sign_classes("sigma_x"):
                if sign == 0:
                    continue  # σ = 0: no exit (an equilibrium in 𝒜)
                for label, _, phi, _ in phi_classes(S.g.f_c, "_x"):
                    margins = S.margins(sigma, phi, 0, abs(sigma), abs(phi), S.g.f_c, f_s, 0, 0)
                    if sign_of(margins[2]) == -1:
                        continue  # not in D
                    post = S.jump_map_x(sigma, phi, 0, S.g.f_c, sp.Integer(sign))
                    if post[0] != sigma or post[2] != 0:
                        return Outcome.fail(f"{f_label}, σ {s_label}, {label}: the jump changes σ or v: {post}")
                    after = fp.factor((sign * f_s - post[1]) / sigma)  # stick time left after the jump
                    before = fp.factor((sign * f_s - phi) / sigma)  # without it
                    if sign_of(after) not in (0, 1):
                        return Outcome.fail(f"{f_label}, σ {s_label}, {label}: after the jump the exit is {after} time units away, not ≥ 0")
                    if sign_of(fp.factor(before - after)) not in (0, 1):
                        return Outcome.fail(f"{f_label}, σ {s_label}, {label}: the jump lengthens the stick by {fp.factor(after - before)}")
                details.append((rf"{f_label},\ \sigma {s_label}",
                                rf"x_{{exit}} = (\sigma, {latex(sign * f_s)}, 0),\ t_{{left}} = {latex(fp.factor((sign * f_s - S.jump_map_x(sigma, 0, 0, S.g.f_c, sign)[1]) / sigma))}"))
        return Outcome(True, "the stick ends at (σ, sign(σ) f_s, 0) with or without a jump, no later with it", tuple(details))


class ResetKernelBinding(Obligation):
    id = "reset.kernel_binding"
    paper = "beyond the paper: reset PID; binds the event kernel to _model.reset"
    statement = "the event kernel resets exactly when the model's D (strictly short of sign(σ) f_c, dwell elapsed) says so, at that time, and to G(x)"
    method = ("the kernel from 8 exact stick states of Table I (a) (inside and outside D, both signs of σ): first event, its "
              "state and the state after it; and along 3 trajectories with dwell 1/100 and 6, every stick start's reset "
              "predicted from the model (time, or none) against the kernel's events")

    def derive(self):
        from .._model.parameters import Parameters
        from .._simulation import simulate

        return (simulate, Parameters(k_p=3, k_i=4, k_v=Fraction(32, 5), f_c=1, reset_dwell=Fraction(1, 100)))

    def verify(self, subject) -> Outcome:
        simulate, params = subject
        f_c, k_i, k_p = params.f_c, params.k_i, params.k_p
        n = 0
        for sigma in (Fraction(1, 2), Fraction(-3, 4)):
            for phi in (Fraction(-9, 10), Fraction(0), Fraction(1, 2), Fraction(99, 100)):
                phi = phi if sigma > 0 else -phi
                s = -sigma / k_i
                e_i = (-phi - k_p * s) / k_i
                sol = simulate(params, (float(e_i), float(s), 0.0), 1e-6, t_eval=[0.0, 1e-12])
                d = 1 if sigma > 0 else -1
                margins = _reset.jump_set_margins(sigma, phi, 0, abs(sigma), abs(phi), f_c, f_c, 0, 0)
                want = all(m >= 0 for m in margins) and d * phi < f_c
                got = bool(sol.events) and sol.events[0][1:] == (0, 0) and sol.events[0][0] == 0.0
                if got != want:
                    return Outcome.fail(f"σ = {sigma}, φ = {phi}: the kernel {'resets' if got else 'does not reset'}; D says {want}")
                if want:
                    post = _reset.jump_map_x(float(sigma), float(phi), 0.0, float(f_c), d)
                    after = sol.x[1]
                    if abs(after[0] - post[0]) > 1e-12 or abs(after[1] - post[1]) > 1e-9:
                        return Outcome.fail(f"σ = {sigma}, φ = {phi}: the kernel jumps to {tuple(after)}, G gives {post}")
                n += 1
        walked = 0
        # dwell 6 is longer than a slip from a stick (τ* = 4.136): there the timer, not the law, decides
        for dwell, z0 in ((Fraction(1, 100), (0.0, 3.0, 0.0)), (Fraction(6), (0.0, 3.0, 0.0)), (Fraction(6), (-1.0, 2.0, -0.5))):
            sol = simulate(dataclasses.replace(params, reset_dwell=dwell), z0, 60.0)
            events, states = sol.events, sol.event_x
            last = None
            for j, ((t, a, b), x) in enumerate(zip(events, states)):
                if (a, b) == (0, 0):
                    last = t
                if a == 0 or b != 0 or j + 1 >= len(events):
                    continue
                sigma, phi = float(x[0]), float(x[1])
                d = 1.0 if sigma > 0 else -1.0
                margins = _reset.jump_set_margins(sigma, phi, 0.0, abs(sigma), abs(phi), float(f_c), float(f_c), 1.0, 0.0)
                allowed = t if last is None else max(t, last + float(dwell))
                natural = t + (d * float(f_c) - phi) / sigma
                predicted = allowed if all(m >= 0 for m in margins) and d * phi < float(f_c) and allowed < natural else None
                t_next, a_next, b_next = events[j + 1]
                is_reset = (a_next, b_next) == (0, 0)
                if (predicted is None) == is_reset or (is_reset and abs(t_next - predicted) > 1e-9 * max(1.0, t_next)):
                    return Outcome.fail(f"dwell {dwell}, stick from t = {t:.12g}: the model resets at {predicted}, "
                                        f"the kernel's next event is {(t_next, a_next, b_next)}")
                walked += 1
        if walked < 20:
            return Outcome.fail(f"only {walked} stick starts were walked: the binding would pass vacuously")
        return Outcome(True, f"{n} stick states and {walked} stick starts along trajectories: the kernel's resets are the model's")


OBLIGATIONS = (ResetVJump, ResetNoSecondJump, ResetAttractor, ResetBasicConditions, ResetLeavesStick, ResetSameStickExits,
               ResetKernelBinding)
