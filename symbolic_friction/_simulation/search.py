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

Everything is written twice: with plain floats for one trajectory
(:func:`first_zero`) and vectorised over many (:func:`first_zeros`, used by
:func:`~symbolic_friction._simulation.batch.simulate_batch`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

from fractions import Fraction

import numpy as np

from .._coordinates import system_matrix_entries
from .._lyapunov import lyapunov_matrix_entries
from .._parameters import Parameters
from .affine import MatrixExponential, ScanTable, SlipBounds  # noqa: F401 (ScanTable in annotations)

__all__ = ["SlipModel", "slip_model", "first_zero", "first_zeros", "UNDERFLOW"]

_EPS = 2.220446049250313e-16
# The Taylor march is only run on one grid cell at a time; this cap is reached
# only at an exact tangency, where the steps shrink geometrically.
_MAX_STEPS = 2_000
# A slip that has decayed to within this (absolute) distance of its equilibrium
# x*_k = (0, k f_c, 0), a point of 𝒜, cannot be followed further in double
# precision (the closed form's products become subnormal and v = 0 by
# underflow).  The search reports a zero there, and the event loop puts the
# state on x*_k, an equilibrium.
UNDERFLOW = 1e-280


@dataclass(frozen=True, eq=False)
class SlipModel:
    """Everything the search needs for one parameter set."""

    expm: MatrixExponential
    bounds: SlipBounds
    table: ScanTable
    f_c: float


@lru_cache(maxsize=64)
def slip_model(params: Parameters) -> SlipModel:
    """The closed form, the bounds and the scan table of ``params`` (cached)."""
    expm = MatrixExponential.from_params(params)
    bounds = SlipBounds.from_params(params)
    return SlipModel(expm=expm, bounds=bounds, table=ScanTable.build(expm), f_c=float(params.f_c))


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


def p_norm_vec(s: np.ndarray, p: np.ndarray, v: np.ndarray, kv_ki: float, k_p: float) -> np.ndarray:
    """Vectorised :func:`p_norm`."""
    m = np.maximum(np.maximum(np.abs(s), np.abs(p)), np.abs(v))
    safe = np.where(m > 0.0, m, 1.0)
    s, p, v = s / safe, p / safe, v / safe
    return m * np.sqrt(np.maximum(kv_ki * s * s - 2.0 * s * v + k_p * v * v + p * p, 0.0))


# ---------------------------------------------------------------------------
# One trajectory
# ---------------------------------------------------------------------------
class _Slip:
    """``y(τ) = e^{Aτ} y0`` from the slip's start, in closed form."""

    __slots__ = ("w_scalar", "d", "q0", "q1", "q2")

    def __init__(self, expm: MatrixExponential, y0: tuple[float, float, float], direction: int) -> None:
        self.w_scalar = expm.w_scalar
        self.d = direction
        # e^{Aτ} y0 = w'' y0 + w' B1 y0 + w B2 y0 (see affine.MatrixExponential)
        self.q0 = tuple(y0)
        self.q1 = tuple(float(x) for x in expm.B1 @ np.asarray(y0, dtype=float))
        self.q2 = tuple(float(x) for x in expm.B2 @ np.asarray(y0, dtype=float))

    def state(self, tau: float) -> tuple[float, float, float]:
        w0, w1, w2 = self.w_scalar(tau)
        q0, q1, q2 = self.q0, self.q1, self.q2
        return (
            w2 * q0[0] + w1 * q1[0] + w0 * q2[0],
            w2 * q0[1] + w1 * q1[1] + w0 * q2[1],
            w2 * q0[2] + w1 * q1[2] + w0 * q2[2],
        )

    def u(self, tau: float) -> float:
        return self.d * self.state(tau)[2]


def _newton(slip: "_Slip", a1: tuple[float, float], lo: float, hi: float) -> float:
    """Zero of ``u`` in ``[lo, hi]`` where ``u`` decreases strictly from ``u(lo) ≥ 0`` to ``u(hi) ≤ 0``.

    Newton's method on the closed form, kept inside the bracket (bisection
    when a step leaves it), until the step is below two ulps or ``|u|`` is
    below the rounding error of its own evaluation.  ``a1 = (A₃₂, A₃₃)``, so
    that ``v' = A₃₂φ + A₃₃v`` along the slip (:func:`v_rows`).
    """
    d = slip.d
    a11, a12 = a1
    (_, p0, v0), (_, p1, v1), (_, p2, v2) = slip.q0, slip.q1, slip.q2
    x = 0.5 * (lo + hi)
    for _ in range(100):
        w0, w1, w2 = slip.w_scalar(x)
        v = w2 * v0 + w1 * v1 + w0 * v2
        u = d * v
        if abs(u) <= 8.0 * _EPS * (abs(w2 * v0) + abs(w1 * v1) + abs(w0 * v2)):
            return x  # a zero to the precision u can be computed with
        if u > 0.0:
            lo = x
        else:
            hi = x
        du = d * (a11 * (w2 * p0 + w1 * p1 + w0 * p2) + a12 * v)
        x_new = x - u / du if du < 0.0 else 0.5 * (lo + hi)
        if not lo <= x_new <= hi:
            x_new = 0.5 * (lo + hi)
        if abs(x_new - x) <= 2.0 * _EPS * abs(x) or hi - lo <= 2.0 * _EPS * abs(hi):
            return x_new
        x = x_new
    return x


def _march(
    slip: _Slip, model: SlipModel, a: float, y: tuple[float, float, float], stop: float
) -> tuple[float | None, tuple[float, float, float]]:
    """Certified Taylor march from ``a`` (state ``y``) to ``stop``; first zero of ``u`` or None."""
    expm = model.expm
    kv_ki, k_p = p_weights(expm)
    (_, a11, a12), (a20, a21, a22) = v_rows(expm)
    m2, m3 = model.bounds.m[2], model.bounds.m[3]
    d = slip.d
    fresh = a == 0.0
    for _ in range(_MAX_STEPS):
        s, p, v = y
        u = d * v
        if u <= 0.0 and not fresh:
            return a, y  # reached by a certified step: a zero up to rounding
        if max(abs(s), abs(p), abs(v)) <= UNDERFLOW:
            return a, y  # at the slip's equilibrium to double precision
        fresh = False
        r_p = p_norm(s, p, v, kv_ki, k_p)
        if r_p == 0.0:
            return (a, y) if a > 0.0 else (None, y)  # y = 0: the slip's equilibrium
        # everything below is homogeneous in y: work with y/|y|_P (no overflow)
        u = u / r_p
        du = d * (a11 * p + a12 * v) / r_p
        dd = d * (a20 * s + a21 * p + a22 * v) / r_p
        # |u''| on [a, stop]: globally ≤ m2|y|_P, and ≤ |u''(a)| + m3|y|_P (stop - a)
        big_m2 = max(min(m2, abs(dd) + m3 * (stop - a)), 1e-300)
        root = math.sqrt(du * du + 2.0 * big_m2 * u)
        # u > 0 on [a, a + step): the first root of u + du τ - M2 τ²/2
        if du > 0.0:
            step = (du + root) / big_m2
        else:
            step = 2.0 * u / (root - du) if root - du > 0.0 else 0.0
        if du < 0.0 and 2.0 * big_m2 * u <= du * du:
            # u + du τ + M2 τ²/2 vanishes too: one strictly decreasing crossing in [lo, hi]
            lo = a + step
            hi = a + 2.0 * u / (math.sqrt(du * du - 2.0 * big_m2 * u) - du)
            if lo >= stop:
                return None, y
            if hi > stop:
                if slip.u(stop) > 0.0:
                    return None, y
                hi = stop
            tau = _newton(slip, (a11, a12), lo, hi)
            return tau, slip.state(tau)
        if du >= 0.0:
            if dd > 0.0:
                # u + du τ + dd τ²/2 - M3 τ³/6 ≥ τ² (dd/2 - M3 τ/6) > 0 below 3 dd/M3
                step = max(step, 2.9 * dd / m3)
        a_next = a + step
        if a_next >= stop:
            return None, y
        if a_next == a:
            return a, y  # no certified progress: a tangential contact (v = v' = 0 within rounding)
        a = a_next
        y = slip.state(a)
    return a, y


def _blocked(table: "ScanTable", last: int, y: np.ndarray, d, r_p, m4: float) -> np.ndarray:
    """Cells ``0 … last-1`` of a window that the scan cannot clear.

    ``y`` is the offset ``(σ, p, v)`` at the window's start, shape (3,) for one
    trajectory or (R, 3); ``d`` and ``r_p`` (its P-norm) are floats or
    columns (R, 1).  The result has shape (last,) or (R, last).
    """
    w = table.values[:, : last + 1]
    dt = table.dt
    u = d * (y @ w[0:3])  # v on the grid, from rows w, w', w''
    u2 = np.abs(y @ w[2:5])  # v'' on the grid, from rows w'', w''', w⁗
    # |u''| on a cell ≤ max of its ends + Δ² max|u⁗| / 8, with |u⁗| ≤ m4 |y|_P
    slack = 0.125 * dt * dt * (np.maximum(u2[..., :-1], u2[..., 1:]) + 0.125 * dt * dt * m4 * r_p)
    # plus the rounding of the products that gave u and u''
    noise = np.abs(y) @ table.noise[:, :last]
    return ~(np.minimum(u[..., :-1], u[..., 1:]) > slack + noise)


def first_zero(
    model: SlipModel, y0: tuple[float, float, float], direction: int, horizon: float
) -> tuple[float | None, tuple[float, float, float]]:
    """First ``τ ∈ (0, horizon]`` with ``v(τ) = 0`` along the slip from offset ``y0``.

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
    slip = _Slip(model.expm, y0, direction)
    table = model.table
    dt, n_cells = table.dt, table.cells
    kv_ki, k_p = p_weights(model.expm)
    m4 = model.bounds.m[4]
    d = direction
    # windows of `cells` cells, each anchored at the exact state at its start, so that
    # the bound m4 |y(a)|_P follows the decay of the solution
    a_w, y_w = 0.0, y0
    while a_w < horizon:
        s, p, v = y_w
        r_p = p_norm(s, p, v, kv_ki, k_p)
        last = min(n_cells, math.ceil((horizon - a_w) / dt))
        for j in np.flatnonzero(_blocked(table, last, np.array(y_w), d, r_p, m4)):
            a0 = a_w + float(j) * dt
            y_a0 = y_w if j == 0 else slip.state(a0)
            tau, y = _march(slip, model, a0, y_a0, min(a0 + dt, horizon))
            if tau is not None:
                return tau, y
        a_w += table.window
        if a_w < horizon:
            y_w = slip.state(a_w)
    return None, slip.state(horizon)


# ---------------------------------------------------------------------------
# Many trajectories at once
# ---------------------------------------------------------------------------
def _states(expm: MatrixExponential, q0: np.ndarray, q1: np.ndarray, q2: np.ndarray, tau: np.ndarray) -> np.ndarray:
    w0, w1, w2 = expm.w(tau)
    return w2[:, None] * q0 + w1[:, None] * q1 + w0[:, None] * q2


def first_zeros(
    model: SlipModel, y0: np.ndarray, direction: np.ndarray, horizon: np.ndarray, *, chunk: int = 4096
) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised :func:`first_zero` for offsets ``y0`` (N, 3), directions and horizons (N,).

    Returns ``tau`` (N,), NaN where there is no zero before the horizon, and
    the offsets ``y`` (N, 3) at ``tau`` (or at the horizon).
    """
    expm = model.expm
    y0 = np.asarray(y0, dtype=float)
    d = np.asarray(direction, dtype=float)
    horizon = np.asarray(horizon, dtype=float)
    n = y0.shape[0]
    q0 = y0
    q1 = y0 @ expm.B1.T
    q2 = y0 @ expm.B2.T
    table = model.table
    dt, n_cells = table.dt, table.cells
    kv_ki, k_p = p_weights(expm)
    m4 = model.bounds.m[4]
    cells = np.arange(n_cells)

    tau = np.full(n, np.nan)
    open_ = np.ones(n, dtype=bool)  # still searching
    a_w = np.zeros(n)
    y_w = y0.copy()
    while True:
        rows = np.flatnonzero(open_ & (a_w < horizon))
        if rows.size == 0:
            break
        last = np.minimum(n_cells, np.ceil((horizon - a_w) / dt)).astype(int)
        for lo in range(0, rows.size, chunk):
            part = rows[lo : lo + chunk]
            yp = y_w[part]
            r_p = p_norm_vec(yp[:, 0:1], yp[:, 1:2], yp[:, 2:3], kv_ki, k_p)
            blocked = _blocked(table, n_cells, yp, d[part, None], r_p, m4)
            blocked &= cells[None, :] < last[part, None]
            _march_cells(model, q0, q1, q2, d, horizon, part, a_w, blocked, tau, open_)
        a_w = np.where(open_, a_w + table.window, a_w)
        moving = np.flatnonzero(open_ & (a_w < horizon))
        if moving.size:
            y_w[moving] = _states(expm, q0[moving], q1[moving], q2[moving], a_w[moving])
    at = np.where(np.isnan(tau), horizon, tau)
    return tau, _states(expm, q0, q1, q2, at)


def _march_cells(model, q0, q1, q2, d, horizon, part, a_w, blocked, tau, open_) -> None:
    """Run the Taylor march, vectorised, on each row's blocked cells in order."""
    dt = model.table.dt
    pending = blocked.copy()
    local = np.arange(part.size)
    while True:
        has = pending.any(axis=1)
        if not has.any():
            return
        idx = local[has]
        j = np.argmax(pending[idx], axis=1)
        pending[idx, j] = False
        rows = part[idx]
        a0 = a_w[rows] + j * dt
        stop = np.minimum(a0 + dt, horizon[rows])
        found, where = _march_vec(model, q0[rows], q1[rows], q2[rows], d[rows], a0, stop)
        hit = rows[found]
        tau[hit] = where[found]
        open_[hit] = False
        pending[idx[found]] = False


def _march_vec(model, q0, q1, q2, d, a, stop):
    """Vectorised :func:`_march` (each row from ``a`` to ``stop``)."""
    expm = model.expm
    kv_ki, k_p = p_weights(expm)
    (_, a11, a12), (a20, a21, a22) = v_rows(expm)
    m2, m3 = model.bounds.m[2], model.bounds.m[3]
    n = a.size
    a = a.copy()
    found = np.zeros(n, dtype=bool)
    where = np.full(n, np.nan)
    active = np.ones(n, dtype=bool)
    fresh = a == 0.0
    for _ in range(_MAX_STEPS):
        act = np.flatnonzero(active)
        if act.size == 0:
            break
        aa = a[act]
        y = _states(expm, q0[act], q1[act], q2[act], aa)
        s, p, v = y[:, 0], y[:, 1], y[:, 2]
        dd_ = d[act]
        u = dd_ * v
        # a zero reached by a certified step (not at a slip's start), or underflow
        reached = ((u <= 0.0) & ~fresh[act]) | (np.max(np.abs(y), axis=1) <= UNDERFLOW)
        fresh[act] = False
        r_p = p_norm_vec(s, p, v, kv_ki, k_p)
        degenerate = r_p == 0.0  # y = 0: the slip's equilibrium
        scale = np.where(degenerate, 1.0, r_p)
        # homogeneous in y: work with y/|y|_P (no overflow)
        u = u / scale
        du = dd_ * (a11 * p + a12 * v) / scale
        dd2 = dd_ * (a20 * s + a21 * p + a22 * v) / scale
        safe_m2 = np.maximum(np.minimum(m2, np.abs(dd2) + m3 * (stop[act] - aa)), 1e-300)
        root = np.sqrt(np.maximum(du * du + 2.0 * safe_m2 * u, 0.0))  # u < 0 only where reached
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(du > 0.0, (du + root) / safe_m2, 2.0 * u / (root - du))
        step = np.where(np.isfinite(step) & (step > 0.0), step, 0.0)
        grow = (du >= 0.0) & ~degenerate
        step3 = np.where(grow & (dd2 > 0.0), 2.9 * dd2 / m3, 0.0)
        step = np.maximum(step, step3)
        endgame = (du < 0.0) & (2.0 * safe_m2 * u <= du * du) & ~degenerate & ~reached
        stp = stop[act]

        # rows resolved now
        done_zero = reached | (degenerate & (aa > 0.0))
        done_none = degenerate & ~(aa > 0.0)
        a_next = aa + step
        plain = ~(done_zero | done_none | endgame)
        done_none |= plain & (a_next >= stp)
        done_zero |= plain & (a_next < stp) & (a_next == aa)  # a tangential contact
        moving = plain & (a_next < stp) & (a_next > aa)

        rows_z = act[done_zero]
        found[rows_z] = True
        where[rows_z] = aa[done_zero]
        active[act[done_zero | done_none]] = False
        a[act[moving]] = a_next[moving]

        eg = np.flatnonzero(endgame)
        if eg.size:
            rows_e = act[eg]
            lo = aa[eg] + step[eg]
            hi = aa[eg] + 2.0 * u[eg] / (np.sqrt(du[eg] ** 2 - 2.0 * safe_m2[eg] * u[eg]) - du[eg])
            s_e = stp[eg]
            active[rows_e] = False
            beyond = lo >= s_e
            check = ~beyond & (hi > s_e)
            if check.any():
                rc = rows_e[check]
                u_stop = d[rc] * _states(expm, q0[rc], q1[rc], q2[rc], s_e[check])[:, 2]
                none_now = np.zeros(eg.size, dtype=bool)
                none_now[np.flatnonzero(check)[u_stop > 0.0]] = True
                beyond |= none_now
                hi = np.where(check, s_e, hi)
            keep = ~beyond
            if keep.any():
                rk = rows_e[keep]
                found[rk] = True
                where[rk] = _newton_vec(expm, q0[rk], q1[rk], q2[rk], d[rk], lo[keep], hi[keep])
    # rows still active after the cap: a tangency; return the contact point
    rest = np.flatnonzero(active)
    found[rest] = a[rest] > 0.0
    where[rest] = a[rest]
    return found, where


def _newton_vec(expm, q0, q1, q2, d, lo, hi):
    """Vectorised :func:`_newton` on brackets ``[lo, hi]`` (one row each)."""
    (_, a11, a12), _ = v_rows(expm)
    lo, hi = lo.copy(), hi.copy()
    x = 0.5 * (lo + hi)
    result = np.full(lo.size, np.nan)
    idx = np.arange(lo.size)
    for _ in range(100):
        if idx.size == 0:
            break
        xi = x[idx]
        w0, w1, w2 = expm.w(xi)
        a, b, c = w2[:, None] * q0[idx], w1[:, None] * q1[idx], w0[:, None] * q2[idx]
        y = a + b + c
        di = d[idx]
        u = di * y[:, 2]
        noise = 8.0 * _EPS * (np.abs(a[:, 2]) + np.abs(b[:, 2]) + np.abs(c[:, 2]))
        du = di * (a11 * y[:, 1] + a12 * y[:, 2])
        pos = u > 0.0
        lo[idx] = np.where(pos, xi, lo[idx])
        hi[idx] = np.where(pos, hi[idx], xi)
        l, h = lo[idx], hi[idx]
        with np.errstate(divide="ignore", invalid="ignore"):
            x_new = np.where(du < 0.0, xi - u / du, 0.5 * (l + h))
        x_new = np.where((l <= x_new) & (x_new <= h), x_new, 0.5 * (l + h))
        at_zero = np.abs(u) <= noise
        done = at_zero | (np.abs(x_new - xi) <= 2.0 * _EPS * np.abs(xi)) | (h - l <= 2.0 * _EPS * np.abs(h))
        result[idx[done]] = np.where(at_zero[done], xi[done], x_new[done])
        x[idx] = x_new
        idx = idx[~done]
    result[idx] = x[idx]
    return result
