"""The machinery of the binding obligations (:mod:`.model`).

Exact instances and their points, and the comparison of one package function
with the paper's definition per sign class.

A binding compares the package's function, evaluated in the sympy kind, with the
paper's definition on every class of the case split (a sympy identity), and its
exact and float evaluations with the symbolic one at a point of every class and
boundary, at gains whose float arithmetic is exact; never with a tolerance."""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from .._model import symbolic as _symbolic
from .._model.attractor import dz
from .._model.lyapunov import V
from .._model.parameters import Parameters
from . import _fastpoly as fp
from ._base import Obligation, Outcome
from ._decide import G, Undecided, decide, is_zero, latex, resolve_piecewise, sign_of
from ._inequalities import Case, case_grid, phi_cases, sign_cases
from ._shared import shared_value

INSTANCE = Parameters(k_p=3, k_i=2, k_v=1, f_c=2)
"""Gains of the exact instances: Assumption 1 holds (1·3 > 2), every
parameter and ``k_v/k_i`` is dyadic and all four differ, so a swapped gain
changes a value and float arithmetic on the points below is exact."""


K_INSTANCE = (Fraction(1), Fraction(2), Fraction(3), Fraction(5))
"""Constants ``k₁ … k₄`` of the ``V̂`` instances (distinct, dyadic)."""


_SIGMAS = (Fraction(-1), Fraction(0), Fraction(1))


_VS = (Fraction(-1, 2), Fraction(0), Fraction(1, 2))


def instance_points(f_c: Fraction = INSTANCE.f_c) -> tuple[tuple[Fraction, Fraction, Fraction], ...]:
    """``(σ, φ, v)`` with a point in every class of ``σ ≷ 0``, ``v ≷ 0`` and ``φ`` against ``±f_c``.

    ``φ`` takes ``-3f_c/2, -f_c, -f_c/2, 0, f_c/2, f_c, 3f_c/2``: both
    boundaries, both outer pieces and the inner piece on both sides of 0.
    """
    phis = tuple(f_c * Fraction(n, 2) for n in (-3, -2, -1, 0, 1, 2, 3))
    return tuple(itertools.product(_SIGMAS, phis, _VS))


def _state_cases(g: _symbolic.Gains) -> list[Case]:
    return case_grid(sign_cases(g.sigma, "σ", "a_sigma"), sign_cases(g.v, "v", "a_v"), phi_cases(g.phi, g.f_c))


def _gain_values(g: _symbolic.Gains, p: Parameters) -> dict[sp.Symbol, sp.Expr]:
    return {g.k_p: sp.Rational(p.k_p), g.k_i: sp.Rational(p.k_i), g.k_v: sp.Rational(p.k_v), g.f_c: sp.Rational(p.f_c)}


def _as_exact(x: Any) -> Fraction | bool:
    x = sp.sympify(x)
    if x in (sp.true, sp.false):
        return bool(x)
    if not x.is_Rational:
        raise Undecided(f"{x} is not an exact rational")
    return Fraction(int(x.p), int(x.q))


class _NotEvaluated(Exception):
    """The tree has a node :func:`_evaluate` does not know; sympy evaluates it instead."""


_RELATIONS = {
    sp.StrictGreaterThan: lambda a, b: a > b, sp.GreaterThan: lambda a, b: a >= b,
    sp.StrictLessThan: lambda a, b: a < b, sp.LessThan: lambda a, b: a <= b,
    sp.Equality: lambda a, b: a == b, sp.Unequality: lambda a, b: a != b,
}


def _evaluate(e: Any, at: dict) -> Fraction | bool:
    """The value of the sympy tree ``e`` with its symbols at the rationals ``at``, in exact ``Fraction`` arithmetic.

    The same value as substituting and letting sympy evaluate (each node means what it means in sympy: a
    ``Piecewise`` is its first branch whose condition holds, ``sign(0) = 0``), without building the
    intermediate sympy trees; a node it does not know raises :class:`_NotEvaluated`.
    """
    if e.is_Symbol:
        if e not in at:
            raise _NotEvaluated(e)
        return at[e]
    if e.is_Rational:
        return Fraction(int(e.p), int(e.q))
    if e.is_Add:
        return sum((_evaluate(a, at) for a in e.args), Fraction(0))
    if e.is_Mul:
        out = Fraction(1)
        for a in e.args:
            out *= _evaluate(a, at)
        return out
    if e.is_Pow:
        if not e.exp.is_Integer:
            raise _NotEvaluated(e)
        base = _evaluate(e.base, at)
        if base == 0 and e.exp < 0:
            raise _NotEvaluated(e)  # sympy's zoo: not a rational; sympy says so
        return base ** int(e.exp)
    if isinstance(e, sp.Piecewise):
        for value, cond in e.args:
            if _evaluate(cond, at):
                return _evaluate(value, at)
        raise Undecided("no branch of a Piecewise applies")
    if isinstance(e, sp.Abs):
        return abs(_evaluate(e.args[0], at))
    if isinstance(e, sp.sign):
        x = _evaluate(e.args[0], at)
        return Fraction((x > 0) - (x < 0))
    if e is sp.true or e is sp.false:
        return bool(e)
    for kind, holds in _RELATIONS.items():
        if type(e) is kind:
            return bool(holds(_evaluate(e.lhs, at), _evaluate(e.rhs, at)))
    if isinstance(e, sp.And):
        return all(_evaluate(a, at) for a in e.args)
    if isinstance(e, sp.Or):
        return any(_evaluate(a, at) for a in e.args)
    if isinstance(e, sp.Not):
        return not _evaluate(e.args[0], at)
    raise _NotEvaluated(e)


def _symbolic_value(symbolic: Any, at: dict) -> Fraction | bool:
    """``symbolic`` at the point ``at`` (symbol → rational): a ``Fraction``, or a ``bool`` for a relation.

    Exact arithmetic on the tree (:func:`_evaluate`); a tree it does not know is substituted and
    evaluated by sympy (:func:`._decide.resolve_piecewise`), which is what :func:`_evaluate` computes
    faster.  A value that is not a rational raises :class:`Undecided`.
    """
    e = sp.sympify(symbolic)
    try:
        if not all(getattr(v, "is_Rational", False) for v in at.values()):
            raise _NotEvaluated(at)
        value = _evaluate(e, {k: Fraction(int(v.p), int(v.q)) for k, v in at.items()})
    except (_NotEvaluated, ZeroDivisionError):
        return _as_exact(resolve_piecewise(e.xreplace(at)))
    if isinstance(value, bool) or isinstance(e, (sp.core.relational.Relational, sp.logic.boolalg.Boolean)):
        return bool(value)  # a truth value, as sympy's true/false read by _as_exact
    return Fraction(value)


def _sign(case: Case, var: sp.Symbol) -> int:
    value = sign_of(case(var))
    if value is None:
        raise Undecided(f"cannot decide the sign of {case(var)}")
    return value


@dataclass(frozen=True)
class BindingSubject:
    """A runtime model function in its three kinds, and the paper's definition.

    Attributes
    ----------
    name : str
        The paper object, e.g. ``"V"``.
    symbolic : sympy expression or relational
        The package function evaluated in the sympy kind on ``state``.
    paper : callable
        ``paper(case) -> expr``: the paper's definition on one case of the split.
    cases : tuple of Case
        The case split (every sign class and every piece of ``dz``).
    exact, floats : callable
        ``exact(params, point)`` evaluates the package function on one exact
        point (a list of Fractions); ``floats(params, array)`` on an ``(n, 3)``
        float array, vectorised.
    params : Parameters
        The instance gains.
    constants : dict
        Symbol → exact value at the instance (gains, and ``k₁ … k₄`` for ``V̂``).
    points : tuple
        Exact states, one in every class and on every boundary.
    state : tuple of Symbol
        The state symbols ``symbolic`` is written in.
    relation : bool
        The object is a set: compare truth values, not values.
    """

    name: str
    symbolic: Any
    paper: Callable[[Case], Any]
    cases: tuple[Case, ...]
    exact: Callable[[Parameters, Any], Any]
    floats: Callable[[Parameters, np.ndarray], Any]
    params: Parameters
    constants: dict
    points: tuple[tuple[Fraction, Fraction, Fraction], ...]
    state: tuple[sp.Symbol, sp.Symbol, sp.Symbol]
    relation: bool = False
    degree: int = 2
    scales: tuple[Fraction, ...] = ()


SCALES = (Fraction(1, 2), Fraction(1, 2**21), Fraction(2**19))
"""``f_c`` and the states scaled from the instance's ``f_c = 2`` to 1, about 1e-6 and about 1e6 (powers of two: the
float arithmetic stays exact)."""


def _verify_binding(s: BindingSubject) -> Outcome:
    """Symbolic equality with the paper on every case, then the three kinds at every point."""
    for case in s.cases:
        try:
            got = resolve_piecewise(case(s.symbolic))
            want = resolve_piecewise(s.paper(case))
            if s.relation:
                a, b = decide(got), decide(want)
                if a is None or b is None or a != b:
                    return Outcome.fail(f"{case.label}: the package's {s.name} gives {got} ({a}), the paper {want} ({b})")
            elif not is_zero(fp.expand(got - want)):
                return Outcome.fail(f"{case.label}: the package's {s.name} = {got} differs from the paper's {want}")
        except Undecided as exc:
            return Outcome.fail(f"{case.label}: {exc}")
    floats = s.floats(s.params, np.array([[float(c) for c in p] for p in s.points]))
    floats = np.broadcast_to(np.asarray(floats), (len(s.points),))
    wants: list[Any] = []
    for i, point in enumerate(s.points):
        where = "(" + ", ".join(str(c) for c in point) + ")"
        at = dict(s.constants)
        at.update(dict(zip(s.state, (sp.Rational(c) for c in point))))
        try:
            want = _symbolic_value(s.symbolic, at)
        except Undecided as exc:
            return Outcome.fail(f"at {where}: {exc}")
        got = s.exact(s.params, list(point))
        kind_ok = isinstance(got, bool) if s.relation else isinstance(got, (Fraction, int)) and not isinstance(got, bool)
        if not kind_ok or got != want:
            return Outcome.fail(f"at {where}: the exact {s.name} is {got!r}, the symbolic one {want}")
        f = floats[i]
        if (bool(f) != want) if s.relation else (float(f) != float(want)):
            return Outcome.fail(f"at {where}: the float {s.name} is {f!r}, the exact one {want}")
        wants.append(want)
    for lam in s.scales:
        # the objects are homogeneous in (state, f_c): value(λx; λf_c) = λ^degree · value(x; f_c)
        params = Parameters(k_p=s.params.k_p, k_i=s.params.k_i, k_v=s.params.k_v, f_c=s.params.f_c * lam)
        pts = [[c * lam for c in p] for p in s.points]
        floats = np.broadcast_to(np.asarray(s.floats(params, np.array(pts, dtype=float))), (len(pts),))
        for i, (point, want) in enumerate(zip(pts, wants)):
            want = want if s.relation else want * lam**s.degree
            where = f"f_c = {params.f_c}, (" + ", ".join(str(c) for c in point) + ")"
            got = s.exact(params, list(point))
            if got != want:
                return Outcome.fail(f"at {where}: the exact {s.name} is {got!r}; scaled from f_c = {s.params.f_c}: {want}")
            if (bool(floats[i]) != want) if s.relation else (float(floats[i]) != float(want)):
                return Outcome.fail(f"at {where}: the float {s.name} is {floats[i]!r}; scaled from f_c = {s.params.f_c}: {want}")
    details = (
        (f"{s.name}\\ \\text{{(package, sympy kind)}}", latex(s.symbolic)),
        ("\\text{classes, exact points}", f"{len(s.cases)},\\ {len(s.points)}"),
    )
    scaled = f"; and at f_c·{{{', '.join(str(q) for q in s.scales)}}} by homogeneity" if s.scales else ""
    return Outcome(
        True,
        f"equal to the paper on {len(s.cases)} classes; exact, float and sympy agree at {len(s.points)} points{scaled}",
        details,
    )


class _Binding(Obligation):
    """A binding obligation: subclasses build a :class:`BindingSubject`."""

    method = (
        "sympy identity per class of the case split; the package function evaluated exactly and on "
        "float arrays at a dyadic point of every class and boundary, compared with == (no tolerance)"
    )

    def verify(self, subject: BindingSubject) -> Outcome:
        return _verify_binding(subject)


def _paper_dz(case: Case, y: sp.Expr, c: sp.Expr) -> sp.Expr:
    """``dz_c(y) = y - c·sat(y/c)`` (Notation, §I), by the class of ``y`` in the case."""
    value, bound = case(y), case(c)
    above, below = decide(sp.StrictGreaterThan(value, bound)), decide(sp.StrictLessThan(value, -bound))
    if above is None or below is None:
        raise Undecided(f"cannot place {value} against ±{bound}")
    return value - bound if above else value + bound if below else sp.Integer(0)


def _x_subject(name: str, function: Callable[[Any, Any], Any], paper: Callable[[Case], Any], **fields: Any) -> BindingSubject:
    """The subject binding ``function(params, x)`` of the state ``x = (σ, φ, v)`` to ``paper``."""
    g = G()
    state = [g.sigma, g.phi, g.v]
    defaults = dict(
        symbolic=shared_value(function, g, state), exact=function, floats=function, params=INSTANCE,
        constants=_gain_values(g, INSTANCE), cases=tuple(_state_cases(g)), points=instance_points(), state=tuple(state),
        scales=SCALES,
    )
    defaults.update(fields)
    return BindingSubject(name=name, paper=paper, **defaults)
