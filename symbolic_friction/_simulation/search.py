"""The event of a slip: the *first* zero of ``v`` along ``x' = A x ∓ b``
(eq. subcasesAffine:f1 / f-1), found without ever skipping a crossing.

Along a slip in direction ``k = ±1`` let ``y = x - x*_k`` (so ``y' = A y``)
and ``u = k v``, positive inside the slip.  Two rigorous tools are combined:

1. **A certified scan** (:class:`.affine.ScanTable`).  From a window start
   ``a`` with offset ``y(a) = (σ, p, v)`` (computed in closed form from the
   slip's start), ``u`` and ``u''`` are evaluated on the window's grid
   ``a + jΔ``, ``j ≤ 128``, by two products with a precomputed table of ``w``
   and its derivatives.  On a cell ``|u''| ≤ max(|u''_j|, |u''_{j+1}|) +
   Δ² m₄ |y(a)|_P / 8`` (``|u⁗| ≤ m₄|y(a)|_P`` after ``a``), and a cell
   with ``min(u_j, u_{j+1})`` above the interpolation error
   ``Δ² max|u''| / 8`` (plus rounding) has no zero.
2. **A certified Taylor march** on the first cell that the scan could not
   clear.  ``|y(t)|_P`` does not increase along the slip (``P`` of
   eq. lyapLikeP, :class:`.affine.SlipBounds`), so with
   ``M₂ = m₂|y(a)|_P`` the lower bound ``u + u'τ - ½M₂τ²`` is positive up to
   its first root: that is the next step (``u + u'τ + ½u''τ² - ⅙M₃τ³`` where
   ``u' ≥ 0 < u''``, needed at a start on rows (iii)/(ix) where
   ``u = u' = 0``).  As soon as the upper bound ``u + u'τ + ½M₂τ²`` has a
   root too, ``u`` decreases strictly between the two roots and vanishes
   exactly once there; Newton's method on the closed form, kept inside the
   bracket, refines that zero to machine precision.  At an exact tangency
   the steps shrink geometrically and the contact point is returned.

The search is written once, for one slip, in the simulation kernel
(:func:`._kernel.first_zero`, compiled by numba when available); this module
holds its mathematics, its constants (:func:`slip_model`) and the written-out
``|y|_P`` it calls.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

from fractions import Fraction

import numpy as np

from .._model.coordinates import coc_entries, coc_inverse_entries, system_matrix_entries
from .._model.lyapunov import lyapunov_matrix_entries
from .._model.parameters import Parameters
from .affine import MatrixExponential, ScanTable, SlipBounds  # noqa: F401 (ScanTable in annotations)

__all__ = ["SlipModel", "slip_model", "first_zero", "p_norm", "UNDERFLOW"]

# A slip that has decayed to within this (absolute) distance of its equilibrium
# x*_k = (0, k f_c, 0), a point of 𝒜, cannot be followed further in double
# precision (the closed form's products become subnormal and v = 0 by
# underflow).  The search reports a zero there, and the event loop puts the
# state on x*_k, an equilibrium.
UNDERFLOW = 1e-280

# The cached length of a slip that leaves a stick is searched over at most this many scan
# windows of the gain set's table (see _pack): a bounded cost, whatever the spread of the roots.
STICK_SLIP_WINDOWS = 256


@dataclass(frozen=True, eq=False)
class SlipModel:
    """Everything the search needs for one parameter set."""

    expm: MatrixExponential
    bounds: SlipBounds
    table: ScanTable
    f_c: float
    K: np.ndarray = field(repr=False)
    W: np.ndarray = field(repr=False)
    N: np.ndarray = field(repr=False)

    def constants(self, compiled: bool) -> tuple:
        """``(K, W, N)`` for the kernel: arrays when compiled, lists of floats for plain Python."""
        if compiled:
            return self.K, self.W, self.N
        if "_lists" not in self.__dict__:
            # plain Python is several times faster on floats than on numpy scalars
            object.__setattr__(self, "_lists", (self.K.tolist(), self.W.tolist(), self.N.tolist()))
        return self.__dict__["_lists"]


@lru_cache(maxsize=64)
def slip_model(params: Parameters) -> SlipModel:
    """The closed form, the bounds and the scan table of ``params`` (cached), packed for the kernel."""
    expm = MatrixExponential.from_params(params)
    bounds = SlipBounds.from_params(params)
    table = ScanTable.build(expm)
    f_c = float(params.f_c)
    K = _pack(expm, bounds, table, f_c, f_s=float(params.f_s), excess=float(params.f_s - params.f_c))
    W = np.ascontiguousarray(table.values)
    N = np.ascontiguousarray(table.noise)
    for a in (K, W, N):
        a.flags.writeable = False
    return SlipModel(expm=expm, bounds=bounds, table=table, f_c=f_c, K=K, W=W, N=N)


def _pack(
    expm: MatrixExponential, bounds: SlipBounds, table: ScanTable, f_c: float, *, f_s: float | None = None, excess: float = 0.0
) -> np.ndarray:
    """The scalars of :mod:`._kernel` (its ``I_*`` layout), all generated from the package's ``A`` and ``P``.

    ``f_s`` (default ``f_c``) and ``excess = f_s - f_c`` (rounded once from the exact
    rationals) are the static friction level and its excess over the Coulomb level.
    """
    from . import _kernel as k

    K = np.zeros(k.K_SIZE)
    K[k.I_R], K[k.I_ALPHA], K[k.I_BETA2] = expm.r, expm.alpha, expm.beta2
    K[k.I_DELTA] = expm.r - expm.alpha
    K[k.I_DEN] = K[k.I_DELTA] ** 2 - expm.beta2
    K[k.I_BW] = math.sqrt(abs(expm.beta2))
    K[k.I_B1 : k.I_B1 + 9] = expm.B1.reshape(-1)
    K[k.I_B2 : k.I_B2 + 9] = expm.B2.reshape(-1)
    K[k.I_M2], K[k.I_M3], K[k.I_M4] = bounds.m[2], bounds.m[3], bounds.m[4]
    K[k.I_KVKI], K[k.I_KP] = p_weights(expm)
    (_, a11, a12), (a20, a21, a22) = v_rows(expm)
    K[k.I_A11], K[k.I_A12], K[k.I_A20], K[k.I_A21], K[k.I_A22] = a11, a12, a20, a21, a22
    K[k.I_FC] = f_c
    K[k.I_FS], K[k.I_EXCESS] = (f_c if f_s is None else f_s), excess
    K[k.I_DT], K[k.I_CELLS], K[k.I_WINDOW] = table.dt, table.cells, table.window
    K[k.I_GAIN_KP], K[k.I_GAIN_KI] = expm.k_p, expm.k_i
    K[k.I_TINV : k.I_TINV + 9] = np.array(coc_inverse_entries(expm.k_p, expm.k_i), dtype=float).reshape(-1)
    K[k.I_T : k.I_T + 9] = np.array(coc_entries(expm.k_p, expm.k_i), dtype=float).reshape(-1)
    # The length of a slip that leaves a stick: the first zero of w (the slip from y0 = e₁),
    # searched once, as the kernel would, over 60 time constants of the slowest root (a
    # later zero would come when the state has decayed by e⁻⁶⁰; past that the kernel searches),
    # but over at most STICK_SLIP_WINDOWS scan windows: with roots spread 10⁶ those 60 time
    # constants are millions of windows, and the kernel's own search covers what lies beyond.
    K[k.I_STICK_SLIP_H] = min(60.0 / expm.slowest_rate, STICK_SLIP_WINDOWS * table.window)
    K[k.I_STICK_SLIP_T] = math.inf  # not used while searching for it
    found, tau, *_ = k.first_zero(K.tolist(), table.values.tolist(), table.noise.tolist(), 1.0, 0.0, 0.0, 1, K[k.I_STICK_SLIP_H])
    K[k.I_STICK_SLIP_T] = tau if found else math.inf
    return K


def p_weights(expm: MatrixExponential) -> tuple[float, float]:
    """``(P₁₁, P₃₃) = (k_v/k_i, k_p)`` of eq. (lyapLikeP), from the package's ``P``, for :func:`p_norm`."""
    P = lyapunov_matrix_entries(expm.k_p, expm.k_i, expm.k_v)
    return P[0][0], P[2][2]


def v_rows(expm: MatrixExponential) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """Rows ``e₃ᵀA`` and ``e₃ᵀA²`` (so ``v' = e₃ᵀA y``, ``v'' = e₃ᵀA² y`` along a slip), from the package's ``A``.

    Computed exactly on the float gains and rounded once.
    """
    a = system_matrix_entries(*(Fraction(x) for x in (expm.k_p, expm.k_i, expm.k_v)))
    row1 = a[2]
    row2 = tuple(sum(row1[m] * a[m][j] for m in range(3)) for j in range(3))
    return tuple(float(x) for x in row1), tuple(float(x) for x in row2)


def p_norm(s: float, p: float, v: float, kv_ki: float, k_p: float) -> float:
    """``|y|_P`` for ``y = (s, p, v)``, scaled so that squares neither overflow nor underflow.

    Written out for speed (it runs at every step of a certified march); the
    obligation ``model.P_norm_runtime`` binds it to the package's ``P``.
    """
    m = max(abs(s), abs(p), abs(v))
    if m == 0.0 or not math.isfinite(m):
        return m
    s, p, v = s / m, p / m, v / m
    return m * math.sqrt(max(kv_ki * s * s - 2.0 * s * v + k_p * v * v + p * p, 0.0))


def first_zero(
    model: SlipModel, y0: tuple[float, float, float], direction: int, horizon: float
) -> tuple[float | None, tuple[float, float, float]]:
    """First ``τ ∈ (0, horizon]`` with ``v(τ) = 0`` along the slip from offset ``y0``.

    The search itself is :func:`._kernel.first_zero` (compiled when numba is
    available); this is its Python face.

    Parameters
    ----------
    model : SlipModel
        From :func:`slip_model`.
    y0 : tuple of float
        ``x(0) - x*_k`` with ``k·v(0) > 0``, or ``v(0) = 0`` with ``k·v``
        increasing (the table's rows (ii)/(iii), (ix)/(x)).
    direction : {1, -1}
        ``k``.
    horizon : float
        ``> 0``.

    Returns
    -------
    tau : float or None
        ``None`` if ``k·v > 0`` on ``(0, horizon]``.
    y : tuple of float
        The offset ``y(tau)``, or ``y(horizon)`` when ``tau`` is None.
    """
    from ._jit import kernel, plain

    k = kernel()
    K, W, N = model.constants(k is not plain())
    s, p, v = (float(c) for c in y0)
    found, tau, ys, yp, yv = k.first_zero(K, W, N, s, p, v, int(direction), float(horizon))
    return (float(tau) if found else None), (float(ys), float(yp), float(yv))
