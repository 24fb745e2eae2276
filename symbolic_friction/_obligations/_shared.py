"""Symbolic pieces several obligations share: the sets SGN(v) (eq. xDot), the attractor 𝒜 (eqs. Aph, A) and |x|²_𝒜 (eq. distFromA)."""

from __future__ import annotations

import functools
from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.attractor import attractor_bound_x, attractor_bound_z, squared_distance_x

__all__ = ["sgn_sets", "attractor_x", "attractor_z", "distance_squared", "shared_value", "derivative"]

_SHARED: list[dict[Any, Any]] = []
"""One dict per active :func:`._derived_k.shared_derivations` block (the innermost last): what one ``check`` run
derives once for several obligations."""


def shared_value(function: Any, *args: Any) -> Any:
    """``function(*args)``, computed once per ``check`` run for equal arguments (inside
    :func:`._derived_k.shared_derivations`); outside that block every call computes.

    For the package's model functions evaluated on symbols (``V̂``, ``|x|²_𝒜``, ``dz`` …), which several obligations
    build from the same arguments: a pure construction, and the function itself is part of the key, so a
    replaced function is called anew.  Lists among the arguments are keyed as tuples (they are passed as given).
    """
    if not _SHARED:
        return function(*args)
    key = ("value", function, tuple(tuple(a) if isinstance(a, list) else a for a in args))
    memo = _SHARED[-1]
    try:
        if key in memo:
            return memo[key]
    except TypeError:  # an unhashable argument: nothing to share
        return function(*args)
    memo[key] = value = function(*args)
    return value


def sgn_sets() -> dict[int, sp.Set]:
    """``SGN`` of eq. (frictionforceSetValued), indexed by the sign of ``v``."""
    return dict(_sgn_sets())  # a dict of its own; the (immutable) sets are built once


@functools.lru_cache(maxsize=1)
def _sgn_sets() -> tuple[tuple[int, sp.Set], ...]:
    return ((1, sp.FiniteSet(1)), (0, sp.Interval(-1, 1)), (-1, sp.FiniteSet(-1)))


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
    return shared_value(squared_distance_x, g, [g.sigma, g.phi, g.v])


@functools.lru_cache(maxsize=256)
def derivative(expr: sp.Expr, var: sp.Symbol) -> sp.Expr:
    """``sympy.diff(expr, var)``, remembered: ``V̂``'s gradient is taken by three obligations (a pure function of its
    arguments)."""
    return sp.diff(expr, var)


def _mat(m: Any) -> sp.ImmutableMatrix:
    return sp.ImmutableMatrix(m)
