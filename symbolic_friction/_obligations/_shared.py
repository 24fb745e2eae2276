"""Symbolic pieces several obligations share: the sets SGN(v) (eq. xDot), the attractor 𝒜 (eqs. Aph, A) and |x|²_𝒜 (eq. distFromA)."""

from __future__ import annotations

from typing import Any

import sympy as sp

from .._model import symbolic as _symbolic
from .._model.attractor import attractor_bound_x, attractor_bound_z, squared_distance_x

__all__ = ["sgn_sets", "attractor_x", "attractor_z", "distance_squared"]


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
