"""The paper's objects, numerically: coordinates (eq. CoC, A, b), the attractor 𝒜
(eq. distFromA), V, V_k, V̂ and R (eqs. lyapLike, Vhat) and Lemma 3's k-conditions.

Each function takes :class:`~symbolic_friction.Parameters` and states as
Fractions, float arrays (``(…, 3)``) or sympy symbols; the sympy model for
symbolic gains is :mod:`symbolic_friction.symbolic`.

Examples
--------
>>> from symbolic_friction import Parameters
>>> from symbolic_friction.model import V, distance_x, in_attractor_x, z_to_x
>>> p = Parameters.table_i("a")
>>> x = z_to_x(p, (0, 1, 0))  # eq. (CoC): (σ, φ, v) = (-k_i s, -k_i e_i - k_p s, v)
>>> [float(c) for c in x], float(V(p, x)), round(float(distance_x(p, x)), 4)
([-4.0, -3.0, 0.0], 29.6, 4.4721)
>>> bool(in_attractor_x(p, z_to_x(p, (0.2, 0, 0))))  # |e_i| ≤ f_c/k_i at rest: an equilibrium
True
"""

from __future__ import annotations

from ._namespace import lazy_getattr

# name -> private module that defines it (imported on first use)
_LAZY: dict[str, str] = {
    "PhysicalParameters": "._model.parameters",
    "z_to_x": "._model.coordinates",
    "x_to_z": "._model.coordinates",
    "system_matrix": "._model.coordinates",
    "input_vector": "._model.coordinates",
    "dz": "._model.attractor",
    "distance_x": "._model.attractor",
    "squared_distance_x": "._model.attractor",
    "distance_z": "._model.attractor",
    "in_attractor_x": "._model.attractor",
    "attractor_bound_x": "._model.attractor",
    "attractor_bound_z": "._model.attractor",
    "lyapunov_matrix": "._model.lyapunov",
    "V": "._model.lyapunov",
    "V_k": "._model.lyapunov",
    "V_hat": "._model.lyapunov",
    "in_R": "._model.lyapunov",
    "k_conditions": "._model.kconditions",
    "check_k_conditions": "._model.kconditions",
    "Condition": "._model.kconditions",
}

__all__ = list(_LAZY)

__getattr__ = lazy_getattr("symbolic_friction", globals(), _LAZY)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
