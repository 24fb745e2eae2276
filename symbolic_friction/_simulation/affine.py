"""Closed-form flows of the three affine modes (eq. subcasesAffine) and a
robust matrix exponential ``e^{At}``.

In ``x = (σ, φ, v)`` coordinates the inclusion ``x' ∈ A x - b SGN(v)``
(eq. xDot) is, in each mode ``k`` of Claim 1, an affine system:

* slip ``k = ±1`` (eq. subcasesAffine:f1 / f-1): ``x' = A x ∓ b``, whose
  equilibrium is ``x*_k = A⁻¹ b k = (0, k f_c, 0)`` exactly, so
  ``x(t) = x*_k + e^{At} (x(0) - x*_k)``.  Writing the flow around the exact
  equilibrium avoids the cancellation of ``e^{At} x(0) - (e^{At} - I) A⁻¹ b``
  when ``|x(0)|`` and ``f_c`` differ by many orders of magnitude;
* stick ``k = 0`` (eq. subcasesAffine:f0): ``σ' = 0, φ' = σ, v' = 0``, so
  ``φ(t) = φ(0) + σ(0) t``.

The matrix exponential
----------------------
``A`` has the characteristic polynomial ``p(s) = s³ + k_v s² + k_p s + k_i``.
With ``w`` the impulse response of ``1/p`` (``w(0) = w'(0) = 0``,
``w''(0) = 1``), the Cayley–Hamilton theorem gives, for *any* root
configuration,

.. math::

    e^{At} = w''(t)\\,I + w'(t)\\,(A + k_v I) + w(t)\\,(A^2 + k_v A + k_p I).

No eigenvector matrix is involved (it becomes singular at the triple root
``k_v = k_p = 3, k_i = 1`` and at double roots).  ``w`` is the second divided
difference of ``z ↦ e^{tz}`` over the roots.  We split the roots into a real
root ``r`` that is *isolated* (farthest from the other two) and a pair
``α ± β`` that is either real (``β² > 0``) or complex (``β² < 0``); ``α`` and
``β²`` come from deflating ``p`` by ``r`` (so only ``r`` is ever computed as a
root, and a double pair needs no root separation).  With ``x = (r - α) t``,
``y = β² t²``, ``C = e^{αt} cosh(β t)``, ``D = e^{αt} sinh(β t)/β``
(``cos``/``sin`` for a complex pair, power series for ``|y| ≤ 1``),

.. math::

    w = \\frac{e^{rt} - C - (r - α) D}{(r - α)^2 - β^2},\\qquad
    w' = r w + D,\\qquad w'' = r w' + α D + C,

and, when ``x² + |y| ≤ 1`` (the three roots are close at the time scale
``t``, including the triple root), the cancellation-free series

.. math::

    w = t^2 e^{αt} \\sum_{n \\ge 1} H_n \\Big(\\frac{1}{(2n)!} + \\frac{x}{(2n+1)!}\\Big),
    \\qquad H_n = \\frac{x^{2n} - y^n}{x^2 - y} = \\sum_{j<n} x^{2j} y^{n-1-j}.

Because ``r`` is isolated, ``|r - α| ≥ 3|β|`` for a real pair, so the
denominator never cancels, and outside the series region the numerator
cancels at most by a small constant factor.  All exponents are
``≤ max Re λ · t < 0`` (Assumption 1 makes ``A`` Hurwitz), so nothing
overflows for large ``t``.

The formulas are written once, in the simulation kernel
(:func:`._kernel_flow.w3`, compiled by numba when available);
:meth:`MatrixExponential.w` evaluates them at many times.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np

from .._model.coordinates import system_matrix_entries
from .._infra.errors import SimulationError
from .._model.lyapunov import lyapunov_matrix_entries
from .._model.parameters import Parameters

__all__ = [
    "MatrixExponential",
    "SlipBounds",
    "ScanTable",
    "slip_equilibrium",
    "slip_flow",
    "stick_flow",
]



# Bits of the ball arithmetic that locates the roots: far more than double precision, so that the
# rounded r, α and β² are correctly rounded up to a few ulps even where computing them in floats
# would cancel (the pair of a stiff gain set, α = -(k_v + r)/2 with r ≈ -k_v).
_ROOT_BITS = 256


def _exact(x) -> Fraction:
    """The midpoint of an arb ball, exactly."""
    man, exp = x.mid().man_exp()
    return Fraction(int(man)) * Fraction(2) ** int(exp)


@functools.lru_cache(maxsize=64)
def split_roots_exact(k_p: float, k_i: float, k_v: float) -> tuple[Fraction, Fraction, Fraction]:
    """``(r, α, β²)`` to :data:`_ROOT_BITS` bits, as exact rationals: see :func:`_split_roots`.

    Consistent with ``A`` to far below double precision, which the split of
    :class:`ModalScan` needs: its matrices ``M_C``, ``M_D`` have entries that
    are differences of ``k_v``-sized terms, where roots rounded to double
    would leave ``10⁻¹⁶ k_v`` of inconsistency.
    """
    import flint

    old = flint.ctx.prec
    flint.ctx.prec = _ROOT_BITS
    try:
        poly = flint.fmpq_poly([flint.fmpq(*Fraction(c).as_integer_ratio()) for c in (k_i, k_p, k_v, 1.0)])
        roots = [z for z, mult in poly.complex_roots() for _ in range(mult)]
        real = [j for j in range(3) if roots[j].imag == 0]
        if len(real) == 3:
            # The isolated root: its nearest neighbour is the farthest away.
            gaps = [min(abs(float((roots[a].real - roots[b].real).mid())) for b in real if b != a) for a in real]
            iso = max(real, key=lambda j: gaps[j])
        else:
            iso = real[0]
        pair = [roots[j] for j in range(3) if j != iso]
        alpha = (pair[0] + pair[1]).real / 2
        half = (pair[0] - pair[1]) / 2
        beta2 = (half * half).real
        return _exact(roots[iso].real), _exact(alpha), _exact(beta2)
    finally:
        flint.ctx.prec = old


def _split_roots(k_p: float, k_i: float, k_v: float) -> tuple[float, float, float]:
    """``(r, α, β²)``: an isolated real root ``r`` and the remaining pair ``α ± β``.

    The roots of ``s³ + k_v s² + k_p s + k_i`` (the float gains, exactly) are
    enclosed in arb balls (python-flint) and rounded once; ``α = Re(λ₂ + λ₃)/2``
    and ``β² = ((λ₂ - λ₃)/2)²`` come from the pair's balls, so neither cancels.
    """
    return tuple(float(x) for x in split_roots_exact(float(k_p), float(k_i), float(k_v)))


def _cofactor_matrices(k_p: float, k_i: float, k_v: float) -> tuple[np.ndarray, np.ndarray]:
    """``B1 = A + k_v I`` and ``B2 = A² + k_v A + k_p I`` (see module doc), from the package's ``A``.

    Computed in exact arithmetic on the float gains and rounded once, so
    entries that cancel (e.g. ``B2[2, 2] = k_v² - k_p - k_v² + k_p``) are exactly 0.
    """
    k_p, k_i, k_v = (Fraction(x) for x in (k_p, k_i, k_v))
    a = system_matrix_entries(k_p, k_i, k_v)
    eye = [[Fraction(int(i == j)) for j in range(3)] for i in range(3)]
    a2 = [[sum(a[i][m] * a[m][j] for m in range(3)) for j in range(3)] for i in range(3)]
    b1 = [[a[i][j] + k_v * eye[i][j] for j in range(3)] for i in range(3)]
    b2 = [[a2[i][j] + k_v * a[i][j] + k_p * eye[i][j] for j in range(3)] for i in range(3)]
    return np.array(b1, dtype=float), np.array(b2, dtype=float)


@dataclass(frozen=True, eq=False)
class MatrixExponential:
    """``t ↦ e^{At}`` for ``A`` of eq. (xDot), robust to repeated roots.

    Parameters
    ----------
    k_p, k_i, k_v : float
        Gains satisfying Assumption 1 (not re-checked here; build it with
        :meth:`from_params`).

    Examples
    --------
    >>> import math
    >>> E = MatrixExponential.from_params(Parameters(k_p=3, k_i=1, k_v=3))  # triple root -1
    >>> abs(float(E(1.0)[2, 0]) - math.exp(-1) / 2) < 1e-16  # w(t) = t² e^{-t} / 2
    True
    """

    k_p: float
    k_i: float
    k_v: float
    r: float = field(init=False)
    alpha: float = field(init=False)
    beta2: float = field(init=False)
    B1: np.ndarray = field(init=False, repr=False)
    B2: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        k_p, k_i, k_v = float(self.k_p), float(self.k_i), float(self.k_v)
        r, alpha, beta2 = _split_roots(k_p, k_i, k_v)
        b1, b2 = _cofactor_matrices(k_p, k_i, k_v)
        b1.flags.writeable = False
        b2.flags.writeable = False
        for name, value in (("r", r), ("alpha", alpha), ("beta2", beta2), ("B1", b1), ("B2", b2)):
            object.__setattr__(self, name, value)

    @property
    def slowest_rate(self) -> float:
        """``min |Re λ|`` over the roots of ``det(sI - A)``: the slowest decay of ``e^{At}``."""
        beta = math.sqrt(abs(self.beta2))
        # -(α + β) for a real pair: a product over a sum, never the difference of close numbers
        pair = -(self.alpha * self.alpha - self.beta2) / (self.alpha - beta) if self.beta2 > 0 else abs(self.alpha)
        return min(abs(self.r), pair)

    @classmethod
    def from_params(cls, params: Parameters) -> "MatrixExponential":
        """Build from :class:`Parameters` (floats of the exact gains)."""
        k_p, k_i, k_v, _ = params.as_floats()
        return cls(k_p, k_i, k_v)

    # -- the scalar functions w, w', w'' ------------------------------------
    # Written once, in the simulation kernel (._kernel_flow.w3): these evaluate it.
    @functools.cached_property
    def _constants(self) -> np.ndarray:
        from . import _kernel as k

        K = np.zeros(k.K_SIZE)
        K[k.I_R], K[k.I_ALPHA], K[k.I_BETA2] = self.r, self.alpha, self.beta2
        K[k.I_DELTA] = self.r - self.alpha
        K[k.I_DEN] = K[k.I_DELTA] ** 2 - self.beta2
        K[k.I_BW] = math.sqrt(abs(self.beta2))
        return K

    def w(self, t: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(w, w', w'')`` at times ``t ≥ 0`` (array_like, any shape)."""
        from ._jit import kernel, plain

        t_in = np.asarray(t, dtype=float)
        flat = np.ascontiguousarray(t_in.reshape(-1))
        out = np.empty((3, flat.size))
        k = kernel(work=flat.size)
        k.w_many(self._constants if k is not plain() else self._constants.tolist(), flat, out)
        return out[0].reshape(t_in.shape), out[1].reshape(t_in.shape), out[2].reshape(t_in.shape)

    def w_scalar(self, t: float) -> tuple[float, float, float]:
        """Same as :meth:`w` for one float ``t ≥ 0``."""
        from . import _kernel

        return _kernel.w3(self._constants.tolist(), float(t))

    # -- the matrix and its action ------------------------------------------
    def __call__(self, t: Any) -> np.ndarray:
        """``e^{At}``, shape ``t.shape + (3, 3)``."""
        w0, w1, w2 = self.w(t)
        eye = np.eye(3)
        return w2[..., None, None] * eye + w1[..., None, None] * self.B1 + w0[..., None, None] * self.B2

    def apply(self, t: Any, y0: Any) -> np.ndarray:
        """``e^{At} y0`` for times ``t`` (shape ``S``) and vectors ``y0`` (shape ``(3,)`` or ``S + (3,)``)."""
        y0 = np.asarray(y0, dtype=float)
        w0, w1, w2 = self.w(t)
        q1 = y0 @ self.B1.T
        q2 = y0 @ self.B2.T
        return w2[..., None] * y0 + w1[..., None] * q1 + w0[..., None] * q2


def _inverse3(m: tuple[tuple[Fraction, ...], ...]) -> tuple[tuple[Fraction, ...], ...]:
    """Exact inverse of a nonsingular 3×3 matrix of Fractions (adjugate over determinant)."""

    def cof(i: int, j: int) -> Fraction:
        r = [a for a in range(3) if a != i]
        c = [b for b in range(3) if b != j]
        return (-1) ** (i + j) * (m[r[0]][c[0]] * m[r[1]][c[1]] - m[r[0]][c[1]] * m[r[1]][c[0]])

    det = sum(m[0][j] * cof(0, j) for j in range(3))
    return tuple(tuple(cof(j, i) / det for j in range(3)) for i in range(3))


def _quad_bound(g: tuple[Fraction, ...], params: Parameters) -> float:
    """``sqrt(gᵀ P⁻¹ g)`` rounded up: the largest ``|gᵀ y|`` over ``yᵀ P y ≤ 1`` (``P`` of eq. lyapLikeP)."""
    P = tuple(tuple(Fraction(e) for e in row) for row in lyapunov_matrix_entries(params.k_p, params.k_i, params.k_v))
    inv = _inverse3(P)
    val = sum(g[i] * inv[i][j] * g[j] for i in range(3) for j in range(3))
    return math.sqrt(float(val)) * (1.0 + 1e-12)


@dataclass(frozen=True)
class SlipBounds:
    r"""Constants bounding the derivatives of ``v`` along a slip (used to bracket events).

    Along a slip ``y = x - x*_k`` solves ``y' = A y`` and, by the paper's own
    identity behind eq. (dVdt), ``AᵀP + PA = -c e₃e₃ᵀ``, so
    ``d/dt (yᵀ P y) = -c v² ≤ 0`` with ``P`` of eq. (lyapLikeP).  Hence
    ``|y(t)|_P ≤ |y(a)|_P`` for ``t ≥ a`` and

    .. math:: |v^{(j)}(t)| = |e_3^\top A^j y(t)| \le m_j\, |y(a)|_P,
        \qquad m_j = \sqrt{g_j^\top P^{-1} g_j},\quad g_j = (A^j)^\top e_3,

    with ``m_j`` computed from the exact gains (rounded up).

    Attributes
    ----------
    m : tuple of float
        ``(m_0, …, m_5)``.
    e1_norm : float
        ``|e₁|_P = sqrt(k_v/k_i)``: ``w`` of :class:`MatrixExponential` is
        ``v`` along the flow from ``y = e₁``, so ``|w^{(j)}| ≤ m_j |e₁|_P``.
    """

    m: tuple[float, ...]
    e1_norm: float

    @property
    def m2(self) -> float:
        return self.m[2]

    @property
    def m3(self) -> float:
        return self.m[3]

    @classmethod
    def from_params(cls, params: Parameters) -> "SlipBounds":
        a = system_matrix_entries(params.k_p, params.k_i, params.k_v)
        g = (Fraction(0), Fraction(0), Fraction(1))
        m = []
        for _ in range(6):
            m.append(_quad_bound(g, params))
            g = tuple(sum(g[i] * a[i][j] for i in range(3)) for j in range(3))  # gᵀ ← gᵀ A
        p11 = lyapunov_matrix_entries(params.k_p, params.k_i, params.k_v)[0][0]  # |e₁|²_P
        return cls(m=tuple(m), e1_norm=math.sqrt(float(p11)) * (1.0 + 1e-12))


class _Grid:
    """A table on the grid ``τ_j = jΔ``, ``j = 0 … G`` (``values`` has ``G + 1`` columns)."""

    dt: float
    values: np.ndarray

    @property
    def cells(self) -> int:
        """Number ``G`` of cells."""
        return self.values.shape[1] - 1

    @property
    def window(self) -> float:
        """Length ``GΔ`` of the grid (``16/ρ`` for :class:`ScanTable`; 0 for a :class:`ModalScan` that is not stiff)."""
        return self.dt * self.cells


@dataclass(frozen=True, eq=False)
class ScanTable(_Grid):
    r"""``w`` and its first four derivatives on a fine grid, to scan a slip for its event.

    Along a slip, from any time ``a`` with offset ``y(a) = (σ, p, v)``,

    .. math:: v(a + τ) = σ\, w(τ) + p\, w'(τ) + v\, w''(τ),
        \qquad v''(a + τ) = σ\, w''(τ) + p\, w'''(τ) + v\, w^{(4)}(τ)

    (the third rows of ``e^{Aτ}`` and ``A² e^{Aτ}``), so two products with
    this table give ``v`` and ``v''`` on the whole grid ``τ_j = jΔ``,
    ``Δ = 1/(8ρ)`` with ``ρ`` the spectral radius of ``A``.  With
    :class:`SlipBounds`, ``|v^{(4)}| ≤ m₄ |y(a)|_P`` after ``a``, so on a cell
    ``|v''| ≤ max(|v''_j|, |v''_{j+1}|) + Δ² m₄ |y(a)|_P / 8``, and ``v`` stays
    within ``Δ² max|v''| / 8`` of its linear interpolation: a cell whose end
    values both exceed that bound has no zero (see :mod:`.search`).

    Attributes
    ----------
    dt : float
        ``Δ``.
    values : ndarray, shape (5, G + 1)
        Rows ``w, w', w'', w''', w⁗`` at ``τ_j``.
    noise : ndarray, shape (3, G)
        Per cell, the factors of ``|σ|, |p|, |v|`` in a bound on the rounding
        errors of the scanned values of ``v`` and ``Δ² v''/8``.
    """

    dt: float
    values: np.ndarray = field(repr=False)
    noise: np.ndarray = field(repr=False)

    @classmethod
    def build(cls, expm: MatrixExponential, *, cells: int = 128) -> "ScanTable":
        """Tabulate ``w, …, w⁗`` on ``cells + 1`` points."""
        k_p, k_i, k_v = expm.k_p, expm.k_i, expm.k_v
        r, alpha, beta2 = expm.r, expm.alpha, expm.beta2
        rho = max(abs(r), math.sqrt(alpha * alpha - beta2) if beta2 < 0 else abs(alpha) + math.sqrt(beta2))
        dt = 1.0 / (8.0 * rho)
        tau = dt * np.arange(cells + 1)
        w0, w1, w2 = expm.w(tau)
        w3 = -k_v * w2 - k_p * w1 - k_i * w0  # w solves p(d/dt) w = 0
        w4 = -k_v * w3 - k_p * w2 - k_i * w1
        values = np.array([w0, w1, w2, w3, w4])
        # Per cell, what multiplies |σ|, |p|, |v| in a bound on the rounding of
        # u (from w, w1, w2) and of the (Δ²/8)-scaled u2 (from w2, w3, w4).
        top = np.maximum(np.abs(values[:, :-1]), np.abs(values[:, 1:]))
        noise = 8.0 * 2.220446049250313e-16 * np.array(
            [top[0] + dt * dt * top[2], top[1] + dt * dt * top[3], top[2] + dt * dt * top[4]]
        )
        values.flags.writeable = False
        noise.flags.writeable = False
        return cls(dt=dt, values=values, noise=noise)


def slip_equilibrium(f_c: float, direction: int) -> np.ndarray:
    """``x*_k = (0, k f_c, 0)``, the equilibrium of slip mode ``k = ±1``."""
    return np.array([0.0, direction * f_c, 0.0])


def slip_flow(expm: MatrixExponential, f_c: float, x0: Any, t: Any, direction: int) -> np.ndarray:
    """States ``x(t)`` of ``x' = A x - k b`` (``k = direction = ±1``) from ``x0``, shape ``t.shape + (3,)``."""
    if direction not in (1, -1):
        raise SimulationError(f"a slip direction must be +1 or -1; got {direction!r}")
    star = slip_equilibrium(f_c, direction)
    y0 = np.asarray(x0, dtype=float) - star
    return star + expm.apply(t, y0)


def stick_flow(x0: Any, t: Any) -> np.ndarray:
    """States of the stick mode ``σ' = 0, φ' = σ, v' = 0`` from ``x0`` (``v`` is set to 0)."""
    x0 = np.asarray(x0, dtype=float)
    t = np.asarray(t, dtype=float)
    out = np.empty(t.shape + (3,))
    out[..., 0] = x0[0]
    out[..., 1] = x0[1] + x0[0] * t
    out[..., 2] = 0.0
    return out
