"""Initial states for the cross-check, drawn in ``x = (σ, φ, v)`` (eq. CoC):
seeded random draws on spheres of several radii, a tensor grid, and
special directions (the coordinate axes, the eigenvectors of ``P`` of
eq. lyapLikeP, and the ends ``(0, ±f_c, 0)`` of the attractor 𝒜).

Radii are in units of ``f_c``: the dynamics are homogeneous far from 𝒜
(``|x| ≫ f_c``) and near it (``|x - x*_k| ≪ f_c``), so the interesting
radii straddle ``f_c``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._model.parameters import Parameters

__all__ = ["InitialStates", "default_initial_states", "DEFAULT_RADII", "sphere_states", "grid_states", "special_states", "directions_to_x"]

DEFAULT_RADII: tuple[float, ...] = (0.1, 0.3, 1.0, 3.0, 10.0, 30.0)
"""Sphere radii in units of ``f_c``."""


@dataclass(frozen=True, eq=False)
class InitialStates:
    """Initial states in ``x`` with a label per state."""

    x: np.ndarray
    source: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "x", np.asarray(self.x, dtype=float).reshape(-1, 3))
        object.__setattr__(self, "source", np.asarray(self.source, dtype=object).reshape(-1))

    def __len__(self) -> int:
        return int(self.x.shape[0])

    @staticmethod
    def concat(parts: "list[InitialStates]") -> "InitialStates":
        if not parts:
            return InitialStates(np.zeros((0, 3)), np.zeros(0, dtype=object))
        return InitialStates(np.concatenate([p.x for p in parts]), np.concatenate([p.source for p in parts]))


def directions_to_x(u: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Spherical angles ``u = (a, b)`` (rows) and radii to points ``r·(cos a, sin a cos b, sin a sin b)``."""
    a, b = u[..., 0], u[..., 1]
    return np.stack([np.cos(a), np.sin(a) * np.cos(b), np.sin(a) * np.sin(b)], axis=-1) * np.asarray(radius)[..., None]


def sphere_states(params: Parameters, n: int, rng: np.random.Generator, *, radii=DEFAULT_RADII) -> InitialStates:
    """``n`` states uniform on the spheres ``|x| = r f_c`` (equal shares per radius)."""
    f_c = float(params.f_c)
    if n <= 0:
        return InitialStates.concat([])
    g = rng.standard_normal((n, 3))
    g /= np.linalg.norm(g, axis=1)[:, None]
    which = np.arange(n) % len(radii)
    r = np.asarray(radii, dtype=float)[which] * f_c
    labels = np.array([f"sphere r={radii[i]:g}f_c" for i in which], dtype=object)
    return InitialStates(g * r[:, None], labels)


def grid_states(params: Parameters, n: int, *, half_width: float = 3.0) -> InitialStates:
    """About ``n`` points of a tensor grid on ``[-w, w]³·f_c`` (odd size: contains the axes)."""
    if n <= 0:
        return InitialStates.concat([])
    g = max(3, int(round(n ** (1 / 3))))
    if g % 2 == 0:
        g -= 1
    axis = np.linspace(-half_width, half_width, g) * float(params.f_c)
    pts = np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), axis=-1).reshape(-1, 3)
    return InitialStates(pts, np.full(len(pts), f"grid {g}^3", dtype=object))


def special_states(params: Parameters, *, radii=DEFAULT_RADII) -> InitialStates:
    """Axes, eigenvectors of ``P`` and the ends of 𝒜, at every radius (and just outside 𝒜's ends)."""
    from .._model.lyapunov import lyapunov_matrix

    f_c = float(params.f_c)
    _, vecs = np.linalg.eigh(lyapunov_matrix(params))
    dirs = np.concatenate([np.eye(3), vecs.T])
    dirs = np.concatenate([dirs, -dirs])
    pts = [r * f_c * dirs for r in radii]
    ends = []
    for sgn in (1.0, -1.0):
        for eps in (1e-3, 1e-1, 1.0):
            # just outside an end of 𝒜: stick exits (σ ≠ 0) and slips starting on its boundary
            ends.append([0.0, sgn * (1 + eps) * f_c, 0.0])
            ends.append([eps * f_c, sgn * f_c, 0.0])
            ends.append([-eps * f_c, sgn * f_c, 0.0])
            ends.append([0.0, sgn * f_c, eps * f_c])
            ends.append([0.0, sgn * f_c, -eps * f_c])
    x = np.concatenate(pts + [np.array(ends)])
    return InitialStates(x, np.full(len(x), "special", dtype=object))


def default_initial_states(params: Parameters) -> np.ndarray:
    """Corollary 1's initial states: the two ends and the centre of 𝒜, and three states outside 𝒜 with ``|z(0)|_𝒜`` between 0.5 and 1."""
    from .._model.attractor import attractor_bound_z

    e = float(attractor_bound_z(params))
    return np.array([[e, 0.0, 0.0], [0.0, 0.0, 0.0], [-e, 0.0, 0.0], [e, 0.0, 0.5], [0.0, 0.5, 0.0], [-e, -0.5, 0.5]])
