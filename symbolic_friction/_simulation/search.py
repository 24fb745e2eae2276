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

3. **Two time scales** (:class:`.modal.ModalScan`).  On stiff gains the
   isolated root ``r ≈ -k_v`` is far faster than the pair, and the ``P``-norm
   bounds above are set by it: the cells of 1 and the steps of 2 would be
   ``1/|r|`` long over the whole slip, a cost that grows like ``k_v·T``.  So
   ``v = c e^{rτ} + S(τ)`` is split into the fast part, whose derivatives are
   bounded by ``|c(0)| |r|ʲ e^{rτ}`` (with ``c(0)`` taken once at the slip's
   start: recomputing it from a later state would only recover its rounding,
   amplified by ``|r|ʲ``), and the pair's part ``S``, whose energy
   ``E = q S² + S'²`` does not increase.  After ``40/|r|`` the scan tabulates
   ``S`` alone on cells set by the pair and adds the fast part's bound to each
   cell's slack; the march takes the sharper of the two bounds.  The cost of
   a slip is then set by the pair, whatever ``k_v``.

The march gives up after a fixed number of steps (a bound too weak to make
progress); it then says so (``UNDECIDED``), never taking the spent budget for
a zero: the event loop stops there and :mod:`.event` finishes the trajectory
with Radau and events, stating it.

The search is written once, for one slip, in the simulation kernel
(:func:`._kernel_flow.first_zero`, compiled by numba when available, with the
written-out ``|y|_P`` it calls, :func:`p_norm`); this module holds its
mathematics and its constants (:func:`slip_model`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import lru_cache

from fractions import Fraction

import numpy as np

from .._infra.errors import SimulationError
from .._model.coordinates import coc_entries, coc_inverse_entries, system_matrix_entries
from .._model.lyapunov import lyapunov_matrix_entries
from .._model.parameters import Parameters
from .affine import MatrixExponential, ScanTable, SlipBounds
from ._kernel_flow import p_norm
from ._kernel_layout import UNDERFLOW
from .modal import ModalScan

__all__ = ["SlipModel", "slip_model", "first_zero", "p_norm", "UNDERFLOW"]


# The cached length of a slip that leaves a stick is searched over at most this many scan
# windows of the gain set's table (see _pack): a bounded cost, whatever the spread of the roots.
STICK_SLIP_WINDOWS = 256


@dataclass(frozen=True, eq=False)
class SlipModel:
    """Everything the search needs for one parameter set."""

    expm: MatrixExponential
    bounds: SlipBounds
    table: ScanTable
    modal: ModalScan
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
    """The closed form, the bounds and the scan table of ``params`` (cached), packed for the kernel.

    Reset PID shares everything with the paper's PID but the dwell time ``K[I_DWELL]``.
    """
    if params.reset:
        from . import _kernel_layout as k

        plain = slip_model(params.without_reset())
        K = plain.K.copy()
        try:
            K[k.I_DWELL] = float(params.reset_dwell)  # a dwell below 1e-308 is 0.0: reset at every stick
        except OverflowError:
            K[k.I_DWELL] = math.inf  # one reset, then never again
        K.flags.writeable = False
        return replace(plain, K=K)
    expm = MatrixExponential.from_params(params)
    bounds = SlipBounds.from_params(params)
    table = ScanTable.build(expm)
    modal = ModalScan.build(expm, cells=table.cells)
    f_c = float(params.f_c)
    W, N = _tables(table, modal)
    K = _pack(expm, bounds, table, modal, f_c, f_s=float(params.f_s), excess=float(params.f_s - params.f_c))
    for a in (K, W, N):
        a.flags.writeable = False
    return SlipModel(expm=expm, bounds=bounds, table=table, modal=modal, f_c=f_c, K=K, W=W, N=N)


def _tables(table: ScanTable, modal: ModalScan) -> tuple[np.ndarray, np.ndarray]:
    """``W`` and ``N`` of the kernel: the scan table of ``w`` above the slow table of the pair."""
    from . import _kernel as k

    W = np.ascontiguousarray(np.vstack([table.values, modal.values]))
    N = np.ascontiguousarray(np.vstack([table.noise, modal.noise]))
    assert W.shape[0] == k.W_SLOW + 5 and N.shape[0] == k.N_SLOW + 2
    return W, N


def _pack(
    expm: MatrixExponential,
    bounds: SlipBounds,
    table: ScanTable,
    modal: ModalScan,
    f_c: float,
    *,
    f_s: float | None = None,
    excess: float = 0.0,
) -> np.ndarray:
    """The scalars of :mod:`._kernel` (its ``I_*`` layout), all generated from the package's ``A`` and ``P``.

    ``f_s`` (default ``f_c``) and ``excess = f_s - f_c`` (rounded once from the exact
    rationals) are the static friction level and its excess over the Coulomb level.
    """
    from . import _kernel as k

    K = np.zeros(k.K_SIZE)
    K[k.I_DWELL] = -1.0  # the paper's PID: no reset
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
    # The split's bounds serve where the P-norm ones are loose, on stiff gains; elsewhere the
    # march keeps its P-norm steps, whose outcome at a rounding-level tangency is the reference's.
    K[k.I_MODAL], K[k.I_STIFF] = float(modal.stiff), float(modal.stiff)
    K[k.I_MF : k.I_MF + 27] = modal.matrices
    K[k.I_PQ] = modal.q
    K[k.I_MU : k.I_MU + 5] = modal.mu
    K[k.I_SDT], K[k.I_SCELLS], K[k.I_SWINDOW], K[k.I_TFAST] = modal.dt, modal.cells, modal.window, modal.t_fast
    # The length of a slip that leaves a stick: the first zero of w (the slip from y0 = e₁),
    # searched once, as the kernel would, over 60 time constants of the slowest root (a
    # later zero would come when the state has decayed by e⁻⁶⁰; past that the kernel searches),
    # but over at most STICK_SLIP_WINDOWS scan windows: with roots spread 10⁶ those 60 time
    # constants are millions of windows, and the kernel's own search covers what lies beyond.
    # (On stiff gains the windows are the slow table's, after the fast part has decayed.)
    K[k.I_STICK_SLIP_H] = min(60.0 / expm.slowest_rate, STICK_SLIP_WINDOWS * max(table.window, modal.window))
    K[k.I_STICK_SLIP_T] = math.inf  # not used while searching for it
    W, N = _tables(table, modal)
    code, tau, *_ = k.first_zero(K.tolist(), W.tolist(), N.tolist(), 1.0, 0.0, 0.0, 1, K[k.I_STICK_SLIP_H])
    if code == k.UNDECIDED:  # not known: the kernel searches each such slip itself
        K[k.I_STICK_SLIP_H] = 0.0
    K[k.I_STICK_SLIP_T] = tau if code == k.FOUND else math.inf
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


def first_zero(
    model: SlipModel, y0: tuple[float, float, float], direction: int, horizon: float
) -> tuple[float | None, tuple[float, float, float]]:
    """First ``τ ∈ (0, horizon]`` with ``v(τ) = 0`` along the slip from offset ``y0``.

    The search itself is :func:`._kernel_flow.first_zero` (compiled when numba is
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
    code, tau, ys, yp, yv = k.first_zero(K, W, N, s, p, v, int(direction), float(horizon))
    if code == k.UNDECIDED:
        raise SimulationError(
            f"the end of the slip from y0 = {tuple(y0)!r} could not be decided beyond τ = {float(tau):g} "
            "(the search's step budget ran out)"
        )
    return (float(tau) if code == k.FOUND else None), (float(ys), float(yp), float(yv))
