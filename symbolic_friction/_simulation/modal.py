"""The two time scales of a slip on stiff gains: its fast mode and its slow pair.

:class:`ModalScan` splits ``e^{At}`` into the isolated root's spectral part and
the pair's, for the event kernel's search (:mod:`.search`) and flow
(:mod:`._kernel_flow`).  Its roots come from :func:`.affine.split_roots_exact`,
its matrix ``A`` from the package's model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from .._model.coordinates import system_matrix_entries
from .affine import MatrixExponential, _Grid, split_roots_exact

__all__ = ["ModalScan"]


def _pair_radius(alpha: float, beta2: float) -> float:
    """``max |λ|`` over the pair ``α ± β``."""
    return math.sqrt(alpha * alpha - beta2) if beta2 < 0 else abs(alpha) + math.sqrt(beta2)


@dataclass(frozen=True, eq=False)
class ModalScan(_Grid):
    r"""The two time scales of a slip, to find its event and to flow it at a cost and an accuracy set by the slow one.

    With the isolated root ``r`` and the pair ``α ± β`` of :class:`MatrixExponential`,
    ``P_r = (A² - 2αA + qI)/den`` (``q = α² - β²``, ``den = (r - α)² - β²``) is the
    spectral projector on ``r``'s eigenvector, and on the pair's invariant plane
    ``e^{Aτ} = C I + D (A - αI)`` (``C = e^{ατ} cosh βτ``, ``D = e^{ατ} sinh(βτ)/β``),
    so

    .. math:: e^{Aτ} y = e^{rτ} M_F y + C(τ)\, M_C y + D(τ)\, M_D y,\qquad
        M_F = P_r,\quad M_C = I - P_r,\quad M_D = A - αI - (r - α) P_r,

    with the three matrices computed exactly on the float constants and rounded
    once.  Along a slip ``v(τ) = c e^{rτ} + S(τ)``, ``S = c₁ C + c₂ D``, where
    ``(c, c₁, c₂)`` are the third rows applied to the offset.  Each part has a
    bound that does not grow: ``|(c e^{rτ})⁽ʲ⁾| = |c| |r|ʲ e^{rτ}``, and ``S``
    solves ``S'' = 2α S' - q S``, so ``E = q S² + S'²`` has ``E' = 4α S'² ≤ 0``
    and ``|S⁽ʲ⁾| ≤ μⱼ √E`` with ``μⱼ² = gⱼ₁²/q + gⱼ₂²``, ``gⱼᵀ = e₁ᵀ Mʲ``,
    ``M = [[0, 1], [-q, 2α]]`` (exact on the float constants, rounded up).

    On *stiff* gains (``|r| ≥ 8·max|α ± β|``; ``r ≈ -k_v``):

    * the flow of a slip is this form (:func:`._kernel.slip_q`): on the slow
      manifold ``v ≈ p/k_v``, and the terms of the Cayley–Hamilton form
      ``w'' y + w' B1 y + w B2 y`` are ``|y|``, so ``v`` would lose
      ``log₁₀(k_v |y|/|v|)`` digits to cancellation;
    * the fast part has decayed below double precision after ``40/|r|``; from
      then on the scan (:func:`._kernel_flow.first_zero`) tabulates ``C, D`` and
      ``C'', D''`` on cells ``Δ = 1/(8·max|α ± β|)`` set by the pair alone, and
      adds ``|c| e^{rτ}`` as a rigorous term to each cell's slack, and the march
      takes the sharper of these bounds and the ``P``-norm ones of
      :class:`SlipBounds`.

    Attributes
    ----------
    usable : bool
        ``den ≠ 0`` and ``q > 0``, all constants finite.
    stiff : bool
        The split flows the slips, and the slow table is used after :attr:`t_fast`.
    t_fast : float
        ``40/|r|``.
    matrices : tuple of float
        ``M_F``, ``M_C``, ``M_D``, each 3×3 row-major (27 floats).
    q : float
    mu : tuple of float
        ``μ₀ … μ₄``.
    dt : float
        ``Δ`` of the slow table.
    values : ndarray, shape (5, G + 1)
        Rows ``C, D, C'', D''`` and ``e^{rτ}`` (rounded up) at ``τ_j = jΔ``.
    noise : ndarray, shape (2, G)
        Per cell, ``max|C| + Δ² max|C''|/8`` and the same for ``D``: what
        multiplies the rounding of ``c₁`` and ``c₂``.
    """

    usable: bool
    stiff: bool
    t_fast: float
    matrices: tuple[float, ...]
    q: float
    mu: tuple[float, ...]
    dt: float
    values: np.ndarray = field(repr=False)
    noise: np.ndarray = field(repr=False)

    @classmethod
    def build(cls, expm: MatrixExponential, *, cells: int = 128) -> "ModalScan":
        """The split of ``expm``'s gain set and, when stiff, its slow table of ``cells`` cells."""
        r, alpha, beta2 = expm.r, expm.alpha, expm.beta2
        fr, fa, fb2 = split_roots_exact(float(expm.k_p), float(expm.k_i), float(expm.k_v))
        qf = fa * fa - fb2
        den = (fr - fa) ** 2 - fb2
        usable = den != 0 and qf > 0
        q = float(qf)
        matrices = (0.0,) * 27
        mu = [math.inf] * 5
        if usable:
            a = system_matrix_entries(*(Fraction(x) for x in (expm.k_p, expm.k_i, expm.k_v)))
            a2 = [[sum(a[i][m] * a[m][j] for m in range(3)) for j in range(3)] for i in range(3)]
            eye = [[Fraction(int(i == j)) for j in range(3)] for i in range(3)]
            pr = [[(a2[i][j] - 2 * fa * a[i][j] + qf * eye[i][j]) / den for j in range(3)] for i in range(3)]
            mc = [[eye[i][j] - pr[i][j] for j in range(3)] for i in range(3)]
            md = [[a[i][j] - fa * eye[i][j] - (fr - fa) * pr[i][j] for j in range(3)] for i in range(3)]
            matrices = tuple(float(x) for m in (pr, mc, md) for row in m for x in row)
            usable = all(math.isfinite(x) for x in matrices)
            g = (Fraction(1), Fraction(0))
            for j in range(5):
                mu[j] = math.sqrt(float(g[0] * g[0] / qf + g[1] * g[1])) * (1.0 + 1e-12)
                g = (-qf * g[1], g[0] + 2 * fa * g[1])  # gᵀ ← gᵀ M
        rho = _pair_radius(alpha, beta2)
        stiff = usable and r < 0 and abs(r) >= 8.0 * rho > 0.0
        dt = 1.0 / (8.0 * rho) if stiff else 0.0
        values = np.zeros((5, cells + 1))
        noise = np.zeros((2, cells))
        if stiff:
            from . import _kernel as k

            consts = expm._constants.tolist()
            tau = dt * np.arange(cells + 1)
            cd = np.array([k.pair_cd(consts, float(t)) for t in tau]).T
            c, d = cd[0], cd[1]
            values[0], values[1] = c, d
            values[2] = (alpha * alpha + beta2) * c + 2.0 * alpha * beta2 * d  # C'' (C' = αC + β²D)
            values[3] = 2.0 * alpha * c + (alpha * alpha + beta2) * d  # D'' (D' = αD + C)
            values[4] = np.exp(r * tau) * (1.0 + 4.0 * 2.220446049250313e-16)
            grow = 0.125 * dt * dt
            top = np.maximum(np.abs(values[:4, :-1]), np.abs(values[:4, 1:]))
            noise[0] = top[0] + grow * top[2]
            noise[1] = top[1] + grow * top[3]
        values.flags.writeable = False
        noise.flags.writeable = False
        return cls(
            usable=usable, stiff=stiff, t_fast=40.0 / abs(r) if stiff else math.inf, matrices=matrices,
            q=q, mu=tuple(mu), dt=dt, values=values, noise=noise,
        )
