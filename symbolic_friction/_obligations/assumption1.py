"""Assumption 1 (paper §II-A): ``k_p, k_i > 0`` and ``k_v k_p > k_i``.

* ``assumption1.routh`` — Assumption 1 ⇔ ``s³ + k_v s² + k_p s + k_i`` is
  Hurwitz, and that polynomial is ``det(sI − A)``.
* ``assumption1.encoding`` — the substitution ``k_v = (k_i + δ)/k_p``, ``δ > 0``,
  that the symbolic obligations use is exactly Assumption 1."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .._model import symbolic as _symbolic
from . import _fastforms as ff
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, is_zero, latex, sign_of
from ._shared import _mat

__all__ = ["Assumption1Routh", "Assumption1Encoding", "hurwitz_minors", "OBLIGATIONS"]


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
    return [fp.factored_det(H[:k, :k]) for k in range(1, n + 1)]


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
            cp = fp.expanded_det(S.s * sp.eye(3) - M)
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
        back = ff.solve([e - a for e, a in zip(S.assumption, alphas)], S.gains, dict=True)
        if not back:
            return Outcome.fail(f"cannot solve Assumption 1's expressions {S.assumption} for the gains")
        for sol in back:
            for k, m in enumerate(minors, 1):
                if sign_of(m.subs(sol)) != 1:
                    return Outcome.fail(
                        f"(⇐) fails: on Assumption 1 ({sol}), Hurwitz minor Δ_{k} = {fp.factor(m.subs(sol))} is not shown positive",
                        tuple(details),
                    )
        # (⇒) every Hurwitz point has positive minors d_k; solve the minors for the gains.
        ds = sp.symbols(f"d_1:{len(minors) + 1}", positive=True)
        forth = ff.solve([m - d for m, d in zip(minors, ds)], S.gains, dict=True)
        if not forth:
            return Outcome.fail(f"cannot solve the Hurwitz minors {minors} for the gains")
        for sol in forth:
            for e in S.assumption:
                val = fp.factor(e.subs(sol))
                if sign_of(val) != 1:
                    return Outcome.fail(
                        f"(⇒) fails: with Hurwitz minors d_k > 0 ({sol}), Assumption 1's {e} = {val} is not shown positive",
                        tuple(details),
                    )
        details.append(("\\Leftarrow\\ \\text{on Assumption 1}", latex([fp.factor(m.subs(back[0])) for m in minors])))
        details.append(("\\Rightarrow\\ \\text{from } \\Delta_k = d_k", latex([fp.factor(e.subs(forth[0])) for e in S.assumption])))
        return Outcome(True, "both directions hold for real gains", tuple(details))


@dataclass(frozen=True)
class EncodingSubject:
    """The substitution the symbolic obligations use for Assumption 1."""

    substitution: dict
    k_p: sp.Symbol
    k_i: sp.Symbol
    k_v: sp.Symbol
    delta: sp.Symbol


class Assumption1Encoding(Obligation):
    id = "assumption1.encoding"
    paper = "Assumption 1"
    statement = "k_v = (k_i + δ)/k_p with δ > 0 is, for k_i, k_p > 0, exactly k_v k_p > k_i (both directions), and keeps k_v > 0"
    method = "sympy identities: the substitution gives k_v k_p − k_i = δ; its inverse δ = k_v k_p − k_i returns k_v; positivity of (k_i + δ)/k_p by sign"

    def derive(self) -> EncodingSubject:
        g = G()
        return EncodingSubject(_symbolic.assumption1_substitution(g), g.k_p, g.k_i, g.k_v, g.delta)

    def verify(self, s: EncodingSubject) -> Outcome:
        if set(s.substitution) != {s.k_v}:
            return Outcome.fail(f"the substitution must replace k_v only; it replaces {sorted(map(str, s.substitution))}")
        image = s.substitution[s.k_v]
        if image.has(s.k_v):
            return Outcome.fail(f"k_v = {image} is not explicit")
        # (⇒) every δ > 0 gives Assumption 1 with margin exactly δ
        if not is_zero(sp.expand(image * s.k_p - s.k_i - s.delta)):
            return Outcome.fail(f"with k_v = {image}, k_v k_p − k_i = {sp.simplify(image * s.k_p - s.k_i)}, not δ")
        if sign_of(image) != 1:
            return Outcome.fail(f"k_v = {image} is not shown positive for δ, k_i, k_p > 0")
        # (⇐) every k_v with k_v k_p > k_i is reached, by δ = k_v k_p − k_i > 0
        kv = sp.Symbol("k_v", real=True)
        back = image.xreplace({s.delta: kv * s.k_p - s.k_i})
        if not is_zero(ff.simplify(back - kv)):
            return Outcome.fail(f"δ = k_v k_p − k_i does not give back k_v: {back}")
        return Outcome(True, "δ = k_v k_p − k_i > 0 is a bijection onto {k_v : k_v k_p > k_i}", (("k_v", latex(image)),))


OBLIGATIONS = (Assumption1Routh, Assumption1Encoding)
