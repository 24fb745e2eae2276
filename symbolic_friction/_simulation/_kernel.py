"""The exact event-driven solution of one trajectory, written once.

This module is the whole closed-form simulator of the inclusion
``x' ∈ A x - b SGN(v)`` (eq. xDot; unique solution by Lemma 1):

* :func:`w3`: ``(w, w', w'')``, the scalar functions of ``e^{At}`` (see
  :mod:`.affine` for the formulas and their robustness at repeated roots);
* :func:`first_zero`: the certified search for the end of a slip (see
  :mod:`.search`: a certified scan of a precomputed table, a certified Taylor
  march on the first cell the scan cannot clear, Newton's method inside a
  proved bracket);
* :func:`trajectory`: the event loop over the modes of Claim 1 (the
  appendix's table, :func:`.modes.mode_at_rest`), with the dense output at the
  requested sample times and every event's time, modes and state;
* :func:`trajectories`: that loop over many initial states, in parallel.

With static friction above Coulomb (``f_s > f_c``, ``K[I_EXCESS] > 0``) a stick
ends at ``φ = ±f_s`` and the mode table decides at rest with the stick boundary
``±f_s`` (:func:`.modes.mode_at_rest` with ``excess``); with ``f_s = f_c`` every
operation is the Coulomb one, bit for bit.

It is plain Python on scalars and preallocated arrays, so that it runs as it
is (the pure-Python fallback, which is given the constants as Python lists
of floats) and, unchanged, compiled by numba (:mod:`._jit` loads this same
file a second time with ``_JIT = True``).  The two give the same results bit
for bit (``tests/simulation/test_kernel.py``).

Every constant the kernel needs for one gain set sits in three arrays built
by :func:`.constants.kernel_constants` from the package's model (``A``, ``P``,
the coordinate change): ``K`` (scalars, indexed by the ``I_*`` names below),
``W`` (the scan table ``w … w⁗``) and ``N`` (its rounding bounds).
"""

from __future__ import annotations

import math

import numpy as np

try:  # set by ._jit when it loads this file as the compiled variant
    _JIT  # type: ignore[used-before-def]  # noqa: B018
except NameError:
    _JIT = False

if _JIT:  # pragma: no cover - exercised in the compiled variant only
    import numba

    kernel = numba.njit(cache=True, nogil=True)
    parallel = numba.njit(cache=True, nogil=True, parallel=True)
    prange = numba.prange
else:

    def kernel(f):
        return f

    parallel = kernel
    prange = range

from .modes import mode_at_rest as _mode_at_rest_py
from .search import UNDERFLOW
from .search import p_norm as _p_norm_py

mode_at_rest = kernel(_mode_at_rest_py)
p_norm = kernel(_p_norm_py)

@kernel
def mode_after_slip(sigma, offset, direction, f_c, tol, excess=0.0):
    """:func:`.modes.mode_at_rest` at the end of a slip in ``direction`` (``v`` has just reached 0).

    ``offset = φ - direction·f_c`` as the closed form gives it.  A solution
    can only leave the slip through ``v = 0`` with ``direction·v' =
    direction·offset ≤ 0``; a computed offset of the other sign is a
    rounding error and is set to 0 (a tolerance-free rule).  The mode may
    equal ``direction`` (a grazing contact, row (iii) or (ix)): the slip then
    simply goes on.  With static friction (``excess = f_s - f_c > 0``) the
    mass at rest sticks while ``|φ| ≤ f_s``, so a slip that ends with ``|φ|``
    in ``(f_c, f_s]`` sticks, and a grazing contact sticks too.
    ``model.modes_runtime`` binds it to the table.
    """
    if direction * offset > 0.0:
        offset = 0.0 * offset
    return mode_at_rest(sigma, direction, offset, f_c, tol, excess)


# -- layout of K ---------------------------------------------------------------
I_R, I_ALPHA, I_BETA2, I_DELTA, I_DEN, I_BW = 0, 1, 2, 3, 4, 5
I_B1, I_B2 = 6, 15  # 3×3, row-major
I_M2, I_M3, I_M4 = 24, 25, 26
I_KVKI, I_KP = 27, 28  # P₁₁ = k_v/k_i and P₃₃ = k_p (|y|_P)
I_A11, I_A12, I_A20, I_A21, I_A22 = 29, 30, 31, 32, 33  # v' and v'' rows
I_FC = 34
I_DT, I_CELLS, I_WINDOW = 35, 36, 37
I_GAIN_KP, I_GAIN_KI = 38, 39  # φ = -k_i e_i - k_p s, for the rounding of φ(0)
I_TINV = 40  # T⁻¹ of eq. (CoC), 3×3 row-major: z = T⁻¹ x
I_T = 49  # T of eq. (CoC), 3×3 row-major: x = T z
# A slip that leaves a stick starts at y0 = (σ, 0, 0), so v(τ) = σ w(τ) and its length is
# the first zero of w, whatever σ: found once per gain set (search.slip_model) within
# [0, I_STICK_SLIP_H]; +inf if w has no zero there.
I_STICK_SLIP_T, I_STICK_SLIP_H = 58, 59
# Static friction: f_s and the excess f_s - f_c (rounded once from the exact rationals; 0 in the
# paper's model, where every operation below reduces to the Coulomb one).  A stick ends at φ = ±f_s,
# and the slip that follows starts from the offset y0 = (σ, ±(f_s - f_c), 0).
I_FS, I_EXCESS = 60, 61
# The two time scales of a slip (:class:`.affine.ModalScan`): e^{Aτ} y = e^{rτ} M_F y + C(τ) M_C y + D(τ) M_D y,
# so v(a + τ) = c e^{rτ} + c₁ C(τ) + c₂ D(τ) with (c, c₁, c₂) the third rows of M_F, M_C, M_D applied to y(a),
# and |S⁽ʲ⁾| ≤ μⱼ √E for the pair's part S = c₁ C + c₂ D.
I_MODAL, I_STIFF = 62, 63  # 1.0 when the march and the scan use the split's bounds, and the flow the split
I_PQ = 64  # q = α² - β², E = q S² + S'²
I_MU = 65  # μ₀ … μ₄
I_SDT, I_SCELLS, I_SWINDOW, I_TFAST = 70, 71, 72, 73  # slow table Δ, cells, length; fast part decayed after
I_MF, I_MC, I_MD = 74, 83, 92  # 3×3 row-major each
K_SIZE = 101
# Rows of W and N: the scan table of w (ScanTable) and, below it, the slow table of the pair (ModalScan).
W_FAST, W_SLOW = 0, 5
N_FAST, N_SLOW = 0, 3
# Results of the searches: no zero up to the horizon, a zero, or a bound too weak to decide.
NONE, FOUND, UNDECIDED = 0, 1, 2

# -- statuses --------------------------------------------------------------------
T_END, MAX_EVENTS, EQUILIBRIUM, NONFINITE, BUFFER_FULL, NO_DECISION = 0, 1, 2, 3, 4, 5

EPS = 2.220446049250313e-16
# ulps allowed between a computed φ and ±f_c before σ decides (rows iii/v/vii/ix)
SNAP_ULPS = 8.0
# The Taylor march runs on one grid cell at a time; this cap is reached only
# at an exact tangency, where the steps shrink geometrically.
MAX_STEPS = 2000
# Dense output: at most this many equally spaced slip samples in a row are stepped with the
# exact propagator e^{AΔ} before the closed form is evaluated again (see _emit).
STEP_RUN = 8
N_SERIES = 12
# 1/(2n)! and 1/(2n+1)! for n = 0 … N_SERIES (12 terms reach 1/24! ≈ 1.6e-24)
INV_EVEN_FACT = tuple(1.0 / math.factorial(2 * n) for n in range(N_SERIES + 1))
INV_ODD_FACT = tuple(1.0 / math.factorial(2 * n + 1) for n in range(N_SERIES + 1))


@kernel
def pair_cd(K, t):
    """``(C, D) = e^{αt} (cosh βt, sinh(βt)/β)`` at ``t ≥ 0``: the pair ``α ± β`` (module doc of :mod:`.affine`)."""
    alpha, beta2 = K[I_ALPHA], K[I_BETA2]
    y = beta2 * t * t
    ea = math.exp(alpha * t)
    if abs(y) <= 1.0:
        # C = e^{αt} Ch(y), D = e^{αt} t S(y), Horner
        ch = INV_EVEN_FACT[N_SERIES]
        sh = INV_ODD_FACT[N_SERIES]
        for n in range(N_SERIES - 1, -1, -1):
            ch = ch * y + INV_EVEN_FACT[n]
            sh = sh * y + INV_ODD_FACT[n]
        return ea * ch, ea * t * sh
    if beta2 > 0.0:
        beta = K[I_BW]
        e1 = math.exp((alpha + beta) * t)
        e2 = math.exp((alpha - beta) * t)
        return 0.5 * (e1 + e2), (e1 - e2) / (2.0 * beta)
    omega = K[I_BW]
    return ea * math.cos(omega * t), ea * math.sin(omega * t) / omega


@kernel
def w3(K, t):
    """``(w, w', w'')`` at ``t ≥ 0`` (module doc of :mod:`.affine`)."""
    r, alpha, beta2, delta = K[I_R], K[I_ALPHA], K[I_BETA2], K[I_DELTA]
    x = delta * t
    y = beta2 * t * t
    C, D = pair_cd(K, t)
    if x * x + abs(y) <= 1.0:
        # the three roots are close at this time scale: the cancellation-free series
        x2 = x * x
        h = 1.0
        ypow = 1.0
        acc = 0.0
        for n in range(1, N_SERIES + 1):
            acc += h * (INV_EVEN_FACT[n] + x * INV_ODD_FACT[n])
            ypow *= y
            h = x2 * h + ypow
        w0 = t * t * math.exp(alpha * t) * acc
    else:
        w0 = (math.exp(r * t) - C - delta * D) / K[I_DEN]
    w1 = r * w0 + D
    w2 = r * w1 + alpha * D + C
    return w0, w1, w2


@kernel
def w_many(K, t, out):
    """:func:`w3` at every ``t[j]``, into rows ``out[0:3, j]``."""
    for j in range(t.size):
        w0, w1, w2 = w3(K, t[j])
        out[0, j] = w0
        out[1, j] = w1
        out[2, j] = w2


@kernel
def cofactors(K, s, p, v):
    """``(B1 y, B2 y)`` for ``y = (s, p, v)``: ``e^{Aτ} y = w'' y + w' B1 y + w B2 y``."""
    b, c = I_B1, I_B2
    return (
        K[b] * s + K[b + 1] * p + K[b + 2] * v,
        K[b + 3] * s + K[b + 4] * p + K[b + 5] * v,
        K[b + 6] * s + K[b + 7] * p + K[b + 8] * v,
        K[c] * s + K[c + 1] * p + K[c + 2] * v,
        K[c + 3] * s + K[c + 4] * p + K[c + 5] * v,
        K[c + 6] * s + K[c + 7] * p + K[c + 8] * v,
    )


@kernel
def _apply3(K, m, s, p, v):
    """The 3×3 matrix at ``K[m:m + 9]`` (row-major) applied to ``(s, p, v)``."""
    return (
        K[m] * s + K[m + 1] * p + K[m + 2] * v,
        K[m + 3] * s + K[m + 4] * p + K[m + 5] * v,
        K[m + 6] * s + K[m + 7] * p + K[m + 8] * v,
    )


@kernel
def slip_q(K, s, p, v):
    """The nine numbers a slip from offset ``y = (s, p, v)`` is flowed with (:func:`flow`).

    ``(y, B1 y, B2 y)``, for ``e^{Aτ} y = w'' y + w' B1 y + w B2 y``; on stiff
    gains ``(M_F y, M_C y, M_D y)``, for ``e^{Aτ} y = e^{rτ} M_F y + C M_C y +
    D M_D y`` (:class:`.affine.ModalScan`): on the slow manifold the terms of
    the first form are ``|y|`` while ``v`` is ``|y|/k_v``, and would cancel.
    """
    if K[I_STIFF] != 0.0:
        f0, f1, f2 = _apply3(K, I_MF, s, p, v)
        c0, c1, c2 = _apply3(K, I_MC, s, p, v)
        d0, d1, d2 = _apply3(K, I_MD, s, p, v)
        return (f0, f1, f2, c0, c1, c2, d0, d1, d2)
    b1s, b1p, b1v, b2s, b2p, b2v = cofactors(K, s, p, v)
    return (s, p, v, b1s, b1p, b1v, b2s, b2p, b2v)


@kernel
def _basis(K, tau):
    """The three scalar functions that multiply ``q[0:3], q[3:6], q[6:9]`` in :func:`flow`."""
    if K[I_STIFF] != 0.0:
        C, D = pair_cd(K, tau)
        return math.exp(K[I_R] * tau), C, D
    w0, w1, w2 = w3(K, tau)
    return w2, w1, w0


@kernel
def flow(K, q, tau):
    """``e^{Aτ} y0`` from ``q = slip_q(K, *y0)`` (nine floats)."""
    g0, g1, g2 = _basis(K, tau)
    return (
        g0 * q[0] + g1 * q[3] + g2 * q[6],
        g0 * q[1] + g1 * q[4] + g2 * q[7],
        g0 * q[2] + g1 * q[5] + g2 * q[8],
    )


@kernel
def _newton(K, q, d, lo, hi):
    """Zero of ``u = d·v`` in ``[lo, hi]`` where ``u`` decreases strictly from ``u(lo) ≥ 0`` to ``u(hi) ≤ 0``.

    Newton's method on the closed form, kept inside the bracket (bisection
    when a step leaves it), until the step is below two ulps or ``|u|`` is
    below the rounding error of its own evaluation.
    """
    a11, a12 = K[I_A11], K[I_A12]
    x = 0.5 * (lo + hi)
    for _ in range(100):
        g0, g1, g2 = _basis(K, x)
        v = g0 * q[2] + g1 * q[5] + g2 * q[8]
        u = d * v
        if abs(u) <= 8.0 * EPS * (abs(g0 * q[2]) + abs(g1 * q[5]) + abs(g2 * q[8])):
            return x  # a zero to the precision u can be computed with
        if u > 0.0:
            lo = x
        else:
            hi = x
        du = d * (a11 * (g0 * q[1] + g1 * q[4] + g2 * q[7]) + a12 * v)
        x_new = x - u / du if du < 0.0 else 0.5 * (lo + hi)
        if not lo <= x_new <= hi:
            x_new = 0.5 * (lo + hi)
        if abs(x_new - x) <= 2.0 * EPS * abs(x) or hi - lo <= 2.0 * EPS * abs(hi):
            return x_new
        x = x_new
    return x


@kernel
def modal(K, s, p, v):
    """The two time scales of ``v`` along a slip from offset ``y = (σ, p, v)`` (:class:`.affine.ModalScan`).

    Returns ``(c, c1, c2, ac, e1, e2, sqrt_e)``: ``v(τ) = c e^{rτ} + c1 C(τ) + c2 D(τ)``
    exactly, ``ac ≥ |c|`` and ``e1, e2`` bound the rounding of ``c1, c2``, and
    ``sqrt_e ≥ √E`` with ``E = q S² + S'²`` of the pair's part ``S = c1 C + c2 D``,
    which does not increase, so ``|S⁽ʲ⁾(τ)| ≤ μⱼ sqrt_e`` for every ``τ ≥ 0``.
    """
    alpha = K[I_ALPHA]
    f, m, n = I_MF + 6, I_MC + 6, I_MD + 6  # third rows: v
    tf0, tf1, tf2 = K[f] * s, K[f + 1] * p, K[f + 2] * v
    tc0, tc1, tc2 = K[m] * s, K[m + 1] * p, K[m + 2] * v
    td0, td1, td2 = K[n] * s, K[n + 1] * p, K[n + 2] * v
    c, c1, c2 = tf0 + tf1 + tf2, tc0 + tc1 + tc2, td0 + td1 + td2
    ac = abs(c) + 8.0 * EPS * (abs(tf0) + abs(tf1) + abs(tf2))
    e1 = 8.0 * EPS * (abs(tc0) + abs(tc1) + abs(tc2))
    e2 = 8.0 * EPS * (abs(td0) + abs(td1) + abs(td2))
    a1 = abs(c1) + e1
    a2 = abs(c2) + e2
    d1 = abs(alpha) * a1 + a2  # ≥ |S'(0)| = |α c1 + c2|
    sqrt_e = math.sqrt(K[I_PQ] * a1 * a1 + d1 * d1) * (1.0 + 1e-12)
    return c, c1, c2, ac, e1, e2, sqrt_e


@kernel
def _modal_bound(K, s, p, v, j, fast):
    """``sup_{τ ≥ 0} |v⁽ʲ⁾(τ)|`` along the slip from ``y = (σ, p, v)``, by the split (``+inf`` without it).

    ``fast`` bounds the fast part's coefficient ``|c|`` here as it was known at the
    slip's start, ``|c(0)| e^{ra}``: ``c`` computed again from ``y`` is only known to
    its rounding, which ``|r|ʲ`` would amplify.
    """
    if K[I_MODAL] == 0.0:
        return math.inf
    c, c1, c2, ac, e1, e2, sqrt_e = modal(K, s, p, v)
    bound = min(ac, fast) * abs(K[I_R]) ** j + K[I_MU + j] * sqrt_e
    return bound if bound <= 1.7976931348623157e308 else math.inf


@kernel
def _march(K, q, d, a, s, p, v, stop, fast0):
    """Certified Taylor march from ``a`` (offset ``(s, p, v)``) to ``stop``.

    Returns ``(code, τ, y)``: ``FOUND`` with the first zero of ``u = d·v`` in
    ``(a, stop]`` and the offset there; ``NONE``; or ``UNDECIDED`` when the step
    budget ran out before ``stop`` with ``u > 0`` proved up to ``τ`` (never taken
    for a zero).  See :mod:`.search`.
    """
    kv_ki, k_p = K[I_KVKI], K[I_KP]
    a11, a12, a20, a21, a22 = K[I_A11], K[I_A12], K[I_A20], K[I_A21], K[I_A22]
    m2, m3 = K[I_M2], K[I_M3]
    fresh = a == 0.0
    for _ in range(MAX_STEPS):
        u = d * v
        if u <= 0.0 and not fresh:
            return FOUND, a, s, p, v  # reached by a certified step: a zero up to rounding
        if max(abs(s), abs(p), abs(v)) <= UNDERFLOW:
            return FOUND, a, s, p, v  # at the slip's equilibrium to double precision
        fresh = False
        r_p = p_norm(s, p, v, kv_ki, k_p)
        if r_p == 0.0:  # y = 0: the slip's equilibrium
            return (FOUND if a > 0.0 else NONE), a, s, p, v
        # everything below is homogeneous in y: work with y/|y|_P (no overflow)
        sn, pn, vn = s / r_p, p / r_p, v / r_p
        u = d * vn
        du = d * (a11 * pn + a12 * vn)
        dd = d * (a20 * sn + a21 * pn + a22 * vn)
        # the sharper of two bounds on the derivatives of u after a: the P-norm one (|y|_P does
        # not increase) and the split into the isolated mode and the pair (neither part grows)
        fast = fast0 * math.exp(K[I_R] * a) / r_p
        m3_here = min(m3, _modal_bound(K, sn, pn, vn, 3, fast))
        # |u''| on [a, stop]: globally ≤ m2|y|_P, and ≤ |u''(a)| + m3|y|_P (stop - a)
        big_m2 = max(min(m2, abs(dd) + m3_here * (stop - a), _modal_bound(K, sn, pn, vn, 2, fast)), 1e-300)
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
                return NONE, a, s, p, v
            if hi > stop:
                if d * flow(K, q, stop)[2] > 0.0:
                    return NONE, a, s, p, v
                hi = stop
            tau = _newton(K, q, d, lo, hi)
            ys, yp, yv = flow(K, q, tau)
            return FOUND, tau, ys, yp, yv
        if du >= 0.0 and dd > 0.0:
            # u + du τ + dd τ²/2 - M3 τ³/6 ≥ τ² (dd/2 - M3 τ/6) > 0 below 3 dd/M3
            step = max(step, 2.9 * dd / max(m3_here, 1e-300))
        a_next = a + step
        if a_next >= stop:
            return NONE, a, s, p, v
        if a_next == a:
            return FOUND, a, s, p, v  # no certified progress: a tangential contact
        a = a_next
        s, p, v = flow(K, q, a)
    return UNDECIDED, a, s, p, v


@kernel
def _march_cell(K, q, d, a_w, j, dt, s, p, v, horizon, fast0):
    """:func:`_march` over cell ``j`` of a window that starts at ``a_w`` with offset ``(s, p, v)``."""
    a0 = a_w + float(j) * dt
    if j == 0:
        ys, yp, yv = s, p, v
    else:
        ys, yp, yv = flow(K, q, a0)
    return _march(K, q, d, a0, ys, yp, yv, min(a0 + dt, horizon), fast0)


@kernel
def _scan_fast(K, W, N, q, d, a_w, s, p, v, horizon, fast0):
    """One window of the scan of ``w`` (:class:`.affine.ScanTable`) from ``a_w``, offset ``(s, p, v)`` there."""
    dt, n_cells = K[I_DT], int(K[I_CELLS])
    kv_ki, k_p, m4 = K[I_KVKI], K[I_KP], K[I_M4]
    grow = 0.125 * dt * dt
    # rows of the table (views when compiled, lists when plain: no indexing of numpy scalars)
    W0, W1, W2, W3, W4 = W[W_FAST], W[W_FAST + 1], W[W_FAST + 2], W[W_FAST + 3], W[W_FAST + 4]
    N0, N1, N2 = N[N_FAST], N[N_FAST + 1], N[N_FAST + 2]
    r_p = p_norm(s, p, v, kv_ki, k_p)
    last = min(n_cells, int(math.ceil((horizon - a_w) / dt)))
    extra = grow * min(m4 * r_p, _modal_bound(K, s, p, v, 4, fast0 * math.exp(K[I_R] * a_w)))
    abs_s, abs_p, abs_v = abs(s), abs(p), abs(v)
    u_prev = d * (s * W0[0] + p * W1[0] + v * W2[0])
    u2_prev = abs(s * W2[0] + p * W3[0] + v * W4[0])
    for j in range(last):
        u_next = d * (s * W0[j + 1] + p * W1[j + 1] + v * W2[j + 1])
        u2_next = abs(s * W2[j + 1] + p * W3[j + 1] + v * W4[j + 1])
        # |u''| on the cell ≤ max of its ends + Δ² max|u⁗|/8; u is within Δ² max|u''|/8
        # of its chord; plus the rounding of the products that gave u and u''
        slack = grow * (max(u2_prev, u2_next) + extra)
        noise = abs_s * N0[j] + abs_p * N1[j] + abs_v * N2[j]
        if not min(u_prev, u_next) > slack + noise:
            code, tau, ys, yp, yv = _march_cell(K, q, d, a_w, j, dt, s, p, v, horizon, fast0)
            if code != NONE:
                return code, tau, ys, yp, yv
        u_prev, u2_prev = u_next, u2_next
    return NONE, a_w, s, p, v


@kernel
def _scan_slow(K, W, N, q, d, a_w, s, p, v, horizon, fast0):
    """One window of the slow scan (:class:`.affine.ModalScan`) from ``a_w``, offset ``(s, p, v)`` there.

    ``u = d (c e^{rτ} + S(τ))``: a cell is cleared when the pair's part ``d·S``
    exceeds, at both ends, its interpolation error, the rounding and the
    largest ``|c| e^{rτ}`` on the cell.
    """
    dt, n_cells = K[I_SDT], int(K[I_SCELLS])
    grow = 0.125 * dt * dt
    WC, WD, WC2, WD2, WF = W[W_SLOW], W[W_SLOW + 1], W[W_SLOW + 2], W[W_SLOW + 3], W[W_SLOW + 4]
    NC, ND = N[N_SLOW], N[N_SLOW + 1]
    last = min(n_cells, int(math.ceil((horizon - a_w) / dt)))
    # homogeneous in y: scale it to 1 (no overflow in the split's products)
    size = max(abs(s), abs(p), abs(v))
    if size == 0.0:
        return _march(K, q, d, a_w, s, p, v, min(a_w + dt, horizon), fast0)
    c, c1, c2, ac, e1, e2, sqrt_e = modal(K, s / size, p / size, v / size)
    ac = min(ac, fast0 * math.exp(K[I_R] * a_w) / size)
    extra = grow * K[I_MU + 4] * sqrt_e
    n1 = 8.0 * EPS * abs(c1) + e1
    n2 = 8.0 * EPS * abs(c2) + e2
    u_prev = d * (c1 * WC[0] + c2 * WD[0])
    u2_prev = abs(c1 * WC2[0] + c2 * WD2[0])
    for j in range(last):
        u_next = d * (c1 * WC[j + 1] + c2 * WD[j + 1])
        u2_next = abs(c1 * WC2[j + 1] + c2 * WD2[j + 1])
        slack = grow * (max(u2_prev, u2_next) + extra)
        noise = n1 * NC[j] + n2 * ND[j] + ac * WF[j]
        if not min(u_prev, u_next) > slack + noise:
            code, tau, ys, yp, yv = _march_cell(K, q, d, a_w, j, dt, s, p, v, horizon, fast0)
            if code != NONE:
                return code, tau, ys, yp, yv
        u_prev, u2_prev = u_next, u2_next
    return NONE, a_w, s, p, v


@kernel
def first_zero(K, W, N, s0, p0, v0, d, horizon):
    """First ``τ ∈ (0, horizon]`` with ``v(τ) = 0`` along the slip ``d`` from offset ``y0 = (s0, p0, v0)``.

    Returns ``(code, τ, y)``: ``FOUND``; ``NONE`` with ``τ = horizon`` and
    ``y = y(horizon)``; or ``UNDECIDED`` with ``d·v > 0`` proved up to ``τ``.
    The scan runs window by window (each anchored at the exact state at its
    start, so that its bounds follow the decay), cell by cell, and marches the
    first cells it cannot clear.  On stiff gains (``K[I_STIFF]``) the windows
    after the fast mode has decayed use the slow table, whose cells are set by
    the pair, not by the fast root: the cost no longer grows with ``|r|·horizon``.
    """
    q = slip_q(K, s0, p0, v0)
    stiff = K[I_STIFF] != 0.0
    # the fast part's coefficient at the start, |c(0)|: it decays as e^{rτ} (see _modal_bound)
    fast0 = modal(K, s0, p0, v0)[3] if K[I_MODAL] != 0.0 else math.inf
    a_w = 0.0
    s, p, v = s0, p0, v0
    while a_w < horizon:
        if stiff and a_w >= K[I_TFAST]:
            code, tau, ys, yp, yv = _scan_slow(K, W, N, q, d, a_w, s, p, v, horizon, fast0)
            a_w += K[I_SWINDOW]
        else:
            code, tau, ys, yp, yv = _scan_fast(K, W, N, q, d, a_w, s, p, v, horizon, fast0)
            a_w += K[I_WINDOW]
        if code != NONE:
            return code, tau, ys, yp, yv
        if a_w < horizon:
            s, p, v = flow(K, q, a_w)
    s, p, v = flow(K, q, horizon)
    return NONE, horizon, s, p, v


@kernel
def to_z(K, x, z):
    """``z = T⁻¹ x`` (eq. CoC) for one state, written into ``z``."""
    c = I_TINV
    z[0] = K[c] * x[0] + K[c + 1] * x[1] + K[c + 2] * x[2]
    z[1] = K[c + 3] * x[0] + K[c + 4] * x[1] + K[c + 5] * x[2]
    z[2] = K[c + 6] * x[0] + K[c + 7] * x[1] + K[c + 8] * x[2]


@kernel
def to_x(K, z, x):
    """``x = T z`` (eq. CoC) for one state, written into ``x``."""
    c = I_T
    x[0] = K[c] * z[0] + K[c + 1] * z[1] + K[c + 2] * z[2]
    x[1] = K[c + 3] * z[0] + K[c + 4] * z[1] + K[c + 5] * z[2]
    x[2] = K[c + 6] * z[0] + K[c + 7] * z[1] + K[c + 8] * z[2]


@kernel
def _emit(K, q, t0, t1, final, mode, sigma, base, offset, ts, i, out_x, out_z, out_mode):
    """Dense output of one segment: the samples ``t0 ≤ ts[i] < t1`` (``≤ t1`` when ``final``).

    A sample at an event time belongs to the segment that starts there.
    Returns the index of the first sample not written.

    Along a slip, a sample at ``τ`` is ``e^{Aτ} y0`` in closed form (:func:`flow`:
    four transcendental functions).  When samples are equally spaced, ``Δ`` apart
    (to within the rounding of the times themselves), up to :data:`STEP_RUN` of
    them are instead stepped from the previous one with the exact propagator
    ``e^{AΔ} = w''(Δ) I + w'(Δ) B1 + w(Δ) B2`` (nine products); the closed form
    restarts every run, so rounding never accumulates over more than a few steps.
    """
    f_c = K[I_FC]
    m = ts.size
    c = I_TINV
    b1, b2 = I_B1, I_B2
    run = STEP_RUN  # the first slip sample is always in closed form
    prev = 0.0
    spacing = -1.0
    e00 = e01 = e02 = e10 = e11 = e12 = e20 = e21 = e22 = 0.0
    ys = yp = yv = 0.0
    while i < m and (ts[i] < t1 or (final and ts[i] <= t1)):
        t_i = float(ts[i])  # float(): plain Python on floats, not numpy scalars
        tau = t_i - t0
        if mode == 0:
            x0, x1, x2 = sigma, base * f_c + (offset + sigma * tau), 0.0
        else:
            step = tau - prev
            same = abs(step - spacing) <= 8.0 * EPS * (abs(t_i) + abs(t0))
            if run < STEP_RUN and same and K[I_STIFF] == 0.0:
                ys, yp, yv = (
                    e00 * ys + e01 * yp + e02 * yv,
                    e10 * ys + e11 * yp + e12 * yv,
                    e20 * ys + e21 * yp + e22 * yv,
                )
                run += 1
            else:
                ys, yp, yv = flow(K, q, tau)
                if not same and step > 0.0:
                    # a new spacing: its propagator, from the same w as the closed form
                    w0, w1, w2 = w3(K, step)
                    e00 = w2 + w1 * K[b1] + w0 * K[b2]
                    e01 = w1 * K[b1 + 1] + w0 * K[b2 + 1]
                    e02 = w1 * K[b1 + 2] + w0 * K[b2 + 2]
                    e10 = w1 * K[b1 + 3] + w0 * K[b2 + 3]
                    e11 = w2 + w1 * K[b1 + 4] + w0 * K[b2 + 4]
                    e12 = w1 * K[b1 + 5] + w0 * K[b2 + 5]
                    e20 = w1 * K[b1 + 6] + w0 * K[b2 + 6]
                    e21 = w1 * K[b1 + 7] + w0 * K[b2 + 7]
                    e22 = w2 + w1 * K[b1 + 8] + w0 * K[b2 + 8]
                    spacing = step
                run = 0
            prev = tau
            # the closed form keeps v's sign up to rounding; the mode fixes it
            x0, x1, x2 = ys, yp + mode * f_c, mode * max(mode * yv, 0.0)
        out_x[i, 0] = x0
        out_x[i, 1] = x1
        out_x[i, 2] = x2
        # z = T⁻¹ x (eq. CoC), as to_z
        out_z[i, 0] = K[c] * x0 + K[c + 1] * x1 + K[c + 2] * x2
        out_z[i, 1] = K[c + 3] * x0 + K[c + 4] * x1 + K[c + 5] * x2
        out_z[i, 2] = K[c + 6] * x0 + K[c + 7] * x1 + K[c + 8] * x2
        out_mode[i] = mode
        i += 1
    return i


@kernel
def _finite(a, b, c):
    return abs(a) <= 1.7976931348623157e308 and abs(b) <= 1.7976931348623157e308 and abs(c) <= 1.7976931348623157e308


@kernel
def trajectory(K, W, N, z0, x0, t_end, max_events, ts, out_x, out_z, out_mode, ev_t, ev_x, ev_m, ev_res):
    """The solution from ``x0 = T z0`` on ``[0, t_end]``: samples at ``ts`` and every event.

    Parameters
    ----------
    K, W, N : ndarray
        Constants of one gain set (module doc).
    z0 : ndarray, shape (3,)
        The initial state in ``z = (e_i, s, v)``.
    x0 : ndarray, shape (3,)
        Filled with the initial state in ``x = (σ, φ, v)``, ``T z0``.
    t_end : float
    max_events : int
        Stop (status ``MAX_EVENTS``) after this many mode changes.
    ts : ndarray, shape (m,)
        Sorted sample times in ``[0, t_end]``.
    out_x, out_z : ndarray, shape (m, 3); out_mode : ndarray of int8, shape (m,)
        Filled with the states in ``x`` and in ``z``, and the modes; NaN and
        0 after the stop.  A sample at ``t = 0`` holds ``z0`` itself.
    ev_t, ev_x, ev_m, ev_res : ndarray, shapes (E,), (E, 3), (E, 2), (E,)
        Filled with each event's time, state (``v = 0``), modes before and
        after, and ``|v|`` that the closed form gave at the event before it
        was set to 0; padded with NaN, NaN, 0, 0.  If more than
        ``E < max_events`` events occur, the status is ``BUFFER_FULL`` (call
        again with room for more).

    Returns
    -------
    status, n_events, t_stop
    """
    f_c = K[I_FC]
    f_s, excess = K[I_FS], K[I_EXCESS]
    cap = ev_t.size
    m = ts.size
    i = 0
    n_ev = 0
    status = T_END
    t = 0.0
    q = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    to_x(K, z0, x0)
    sigma, phi, v = float(x0[0]), float(x0[1]), float(x0[2])
    if not _finite(sigma, phi, v):
        status = NONFINITE
        base, offset, mode = 0, 0.0, 0
    elif v != 0.0:
        base, offset, mode = 0, phi, (1 if v > 0.0 else -1)
    else:
        # φ = -k_i e_i - k_p s is rounded: a few ulps of its terms
        tol = SNAP_ULPS * EPS * (K[I_GAIN_KI] * abs(float(z0[0])) + K[I_GAIN_KP] * abs(float(z0[1])))
        base, offset, mode = mode_at_rest(sigma, 0, phi, f_c, tol, excess)
    if status == T_END:
        # grazing contacts continue a slip without an event; bound the loop anyway
        for _ in range(4 * max_events + 16):
            if mode == 0:
                if sigma == 0.0:
                    i = _emit(K, q, t, t_end, True, 0, sigma, base, offset, ts, i, out_x, out_z, out_mode)
                    status = EQUILIBRIUM
                    t = t_end
                    break
                d = 1 if sigma > 0.0 else -1
                # distance to the exit d·f_s: exactly -offset when leaving where the last slip ended
                gap = -offset if base == d else (d - base) * f_c - offset
                if excess != 0.0:
                    gap += d * excess
                t_next = t + gap / sigma
                if t_next >= t_end:
                    i = _emit(K, q, t, t_end, True, 0, sigma, base, offset, ts, i, out_x, out_z, out_mode)
                    t = t_end
                    break
                i = _emit(K, q, t, t_next, False, 0, sigma, base, offset, ts, i, out_x, out_z, out_mode)
                # rows (iii)/(ix): slip d; with stiction from φ = d·f_s, with a jump in v' to d·(f_s - f_c)
                t, base, offset, mode = t_next, d, (d * excess if excess != 0.0 else 0.0), d
                if n_ev >= cap:
                    status = BUFFER_FULL
                    break
                ev_t[n_ev] = t
                ev_x[n_ev, 0] = sigma
                ev_x[n_ev, 1] = d * f_s
                ev_x[n_ev, 2] = 0.0
                ev_m[n_ev, 0] = 0
                ev_m[n_ev, 1] = d
                ev_res[n_ev] = 0.0
                n_ev += 1
            else:
                d = mode
                s0, p0, v0 = sigma, (offset if base == d else (base - d) * f_c + offset), v
                q = slip_q(K, s0, p0, v0)
                if not (_finite(s0, p0, v0) and _finite(q[0], q[1], q[2]) and _finite(q[3], q[4], q[5])
                        and _finite(q[6], q[7], q[8])):
                    status = NONFINITE
                    break
                horizon = t_end - t
                if p0 == 0.0 and v0 == 0.0 and K[I_STICK_SLIP_T] <= K[I_STICK_SLIP_H]:
                    # leaving a stick (rows iii/ix): the slip's length is known for this gain set
                    tau = K[I_STICK_SLIP_T]
                    found = FOUND if tau <= horizon else NONE
                    ys, yp, yv = flow(K, q, min(tau, horizon))
                elif p0 == 0.0 and v0 == 0.0 and horizon <= K[I_STICK_SLIP_H]:
                    found, tau = NONE, horizon  # w has no zero within the cached horizon
                    ys, yp, yv = flow(K, q, horizon)
                else:
                    found, tau, ys, yp, yv = first_zero(K, W, N, s0, p0, v0, d, horizon)
                if found == UNDECIDED:
                    # the search could not decide where this slip ends: stop at its start, never guess
                    i = _emit(K, q, t, t, True, d, sigma, base, offset, ts, i, out_x, out_z, out_mode)
                    status = NO_DECISION
                    break
                if found == NONE:
                    i = _emit(K, q, t, t_end, True, d, sigma, base, offset, ts, i, out_x, out_z, out_mode)
                    t = t_end
                    break
                t_next = t + tau
                i = _emit(K, q, t, t_next, False, d, sigma, base, offset, ts, i, out_x, out_z, out_mode)
                residual = abs(yv)
                if max(abs(ys), abs(yp), abs(yv)) <= UNDERFLOW:  # decayed onto x*_k ∈ 𝒜
                    ys, yp = 0.0, 0.0
                tol = SNAP_ULPS * EPS * max(abs(s0), abs(p0), abs(v0))
                base, offset, new_mode = mode_after_slip(ys, yp, d, f_c, tol, excess)
                t, sigma, v = t_next, ys, 0.0
                if new_mode != d:  # else a grazing contact: the slip goes on
                    if n_ev >= cap:
                        status = BUFFER_FULL
                        break
                    ev_t[n_ev] = t
                    ev_x[n_ev, 0] = sigma
                    ev_x[n_ev, 1] = base * f_c + offset
                    ev_x[n_ev, 2] = 0.0
                    ev_m[n_ev, 0] = d
                    ev_m[n_ev, 1] = new_mode
                    ev_res[n_ev] = residual
                    n_ev += 1
                    mode = new_mode
                if t >= t_end:
                    i = _emit(K, q, t, t_end, True, mode, sigma, base, offset, ts, i, out_x, out_z, out_mode)
                    t = t_end
                    break
            if n_ev >= max_events:
                i = _emit(K, q, t, t, True, mode, sigma, base, offset, ts, i, out_x, out_z, out_mode)
                status = MAX_EVENTS
                break
        else:
            i = _emit(K, q, t, t, True, mode, sigma, base, offset, ts, i, out_x, out_z, out_mode)
            status = MAX_EVENTS
    if status == T_END or status == EQUILIBRIUM:
        # x finite but z = T⁻¹ x overflowing is leaving the range of float64 too
        for j in range(i):
            if not _finite(out_z[j, 0], out_z[j, 1], out_z[j, 2]):
                status = NONFINITE
                break
    for j in range(i, m):  # after a stop: never made up
        for c in range(3):
            out_x[j, c] = np.nan
            out_z[j, c] = np.nan
        out_mode[j] = 0
    for j in range(m):  # the given state, not its round trip through x
        if ts[j] != 0.0:
            break
        if status != NONFINITE:
            for c in range(3):
                out_z[j, c] = z0[c]
    for j in range(n_ev, cap):
        ev_t[j] = np.nan
        for c in range(3):
            ev_x[j, c] = np.nan
        ev_m[j, 0] = 0
        ev_m[j, 1] = 0
        ev_res[j] = 0.0
    return status, n_ev, t


@parallel
def trajectories(
    K, W, N, Z0, X0, t_end, max_events, ts, out_x, out_z, out_mode, ev_t, ev_x, ev_m, ev_res, status, n_ev, t_stop
):
    """:func:`trajectory` for every row of ``Z0``/``X0`` (in parallel when compiled)."""
    for j in prange(Z0.shape[0]):
        st, ne, ts_ = trajectory(
            K, W, N, Z0[j], X0[j], t_end, max_events, ts,
            out_x[j], out_z[j], out_mode[j], ev_t[j], ev_x[j], ev_m[j], ev_res[j],
        )
        status[j] = st
        n_ev[j] = ne
        t_stop[j] = ts_
