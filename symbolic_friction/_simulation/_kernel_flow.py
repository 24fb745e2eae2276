"""The closed form of a slip and the search for its end, written once for the event kernel.

* :func:`w3`, :func:`pair_cd`: ``(w, w', w'')`` and the pair's ``(C, D)``,
  the scalar functions of ``e^{At}`` (see :mod:`.affine` for the formulas and
  their robustness at repeated roots);
* :func:`slip_q`, :func:`flow`: ``e^{Aτ} y0`` in the Cayley–Hamilton form, or,
  on stiff gains, split into the fast mode and the slow pair
  (:class:`.modal.ModalScan`), where the first form would cancel;
* :func:`first_zero`: the certified search for the end of a slip (see
  :mod:`.search`: a certified scan of a precomputed table, of the pair's slow
  table once a stiff slip's fast part has decayed, a certified Taylor march on
  the first cell the scan cannot clear, Newton's method inside a proved
  bracket).  It never takes a spent step budget for a zero: it says
  ``UNDECIDED``.

Plain Python on scalars and preallocated arrays, so that it runs as it is
(the pure-Python fallback) and, unchanged, compiled by numba (:mod:`._jit`
loads this file a second time with ``_JIT = True``).  The constants' layout
is :mod:`._kernel_layout`.
"""

from __future__ import annotations

import math

from ._kernel_layout import *  # noqa: F403 - the layout of K, W, N and the codes
from ._kernel_layout import decorators

try:  # set by ._jit when it loads this file as the compiled variant
    _JIT  # type: ignore[used-before-def]  # noqa: B018
except NameError:
    _JIT = False

kernel, parallel, prange = decorators(_JIT)


# The Taylor march runs on one grid cell at a time and gives up (UNDECIDED) after this many steps.
MAX_STEPS = 2000

__all__ = [
    "p_norm", "MAX_STEPS", "pair_cd", "w3", "w_many", "cofactors", "slip_q", "flow", "modal",
    "first_zero", "_apply3", "_basis", "_newton", "_modal_bound", "_march", "_march_cell", "_scan_cells",
    "_scan_fast", "_scan_slow",
]


@kernel
def p_norm(s, p, v, kv_ki, k_p):
    """``|y|_P`` for ``y = (s, p, v)``, scaled so that squares neither overflow nor underflow.

    Written out for speed (it runs at every step of a certified march); the
    obligation ``model.P_norm_runtime`` binds it to the package's ``P``.
    """
    m = max(abs(s), abs(p), abs(v))
    if m == 0.0 or not math.isfinite(m):
        return m
    s, p, v = s / m, p / m, v / m
    return m * math.sqrt(max(kv_ki * s * s - 2.0 * s * v + k_p * v * v + p * p, 0.0))


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
    D M_D y`` (:class:`.modal.ModalScan`): on the slow manifold the terms of
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
    """The two time scales of ``v`` along a slip from offset ``y = (σ, p, v)`` (:class:`.modal.ModalScan`).

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
def _scan_cells(K, q, d, a_w, s, p, v, horizon, fast0, dt, last, grow, extra, cu, U0, U1, U2, V0, V1, V2, cn, N0, N1, N2):
    """The cells ``j < last`` of one window from ``a_w`` (offset ``(s, p, v)`` there): the first zero, or ``NONE``.

    On the cell's ends ``u_j = d Σ cuₖ Uₖ[j]`` and ``u''_j = Σ cuₖ Vₖ[j]``; ``|u''|`` on
    the cell is at most the larger end plus ``extra/grow``, ``u`` is within
    ``grow·max|u''|`` of its chord, and ``Σ cnₖ Nₖ[j]`` bounds the rounding (and,
    on the slow table, the decayed fast part).  A cell whose ends both exceed
    the sum has no zero; the first one that does not is marched.
    """
    c0, c1, c2 = cu
    m0, m1, m2 = cn
    u_prev = d * (c0 * U0[0] + c1 * U1[0] + c2 * U2[0])
    u2_prev = abs(c0 * V0[0] + c1 * V1[0] + c2 * V2[0])
    for j in range(last):
        u_next = d * (c0 * U0[j + 1] + c1 * U1[j + 1] + c2 * U2[j + 1])
        u2_next = abs(c0 * V0[j + 1] + c1 * V1[j + 1] + c2 * V2[j + 1])
        slack = grow * (max(u2_prev, u2_next) + extra)
        noise = m0 * N0[j] + m1 * N1[j] + m2 * N2[j]
        if not min(u_prev, u_next) > slack + noise:
            code, tau, ys, yp, yv = _march_cell(K, q, d, a_w, j, dt, s, p, v, horizon, fast0)
            if code != NONE:
                return code, tau, ys, yp, yv
        u_prev, u2_prev = u_next, u2_next
    return NONE, a_w, s, p, v


@kernel
def _scan_fast(K, W, N, q, d, a_w, s, p, v, horizon, fast0):
    """One window of the scan of ``w`` (:class:`.affine.ScanTable`) from ``a_w``, offset ``(s, p, v)`` there.

    ``u = d(σ w + p w' + v w'')`` and ``u'' = d(σ w'' + p w⁽³⁾ + v w⁽⁴⁾)`` on the
    table's grid; ``|u⁽⁴⁾| ≤ m₄|y|_P`` (or the split's bound on stiff gains).
    """
    dt, n_cells = K[I_DT], int(K[I_CELLS])
    kv_ki, k_p, m4 = K[I_KVKI], K[I_KP], K[I_M4]
    grow = 0.125 * dt * dt
    # rows of the table (views when compiled, lists when plain: no indexing of numpy scalars)
    W0, W1, W2, W3, W4 = W[W_FAST], W[W_FAST + 1], W[W_FAST + 2], W[W_FAST + 3], W[W_FAST + 4]
    N0, N1, N2 = N[N_FAST], N[N_FAST + 1], N[N_FAST + 2]
    r_p = p_norm(s, p, v, kv_ki, k_p)
    last = min(n_cells, int(math.ceil((horizon - a_w) / dt)))
    extra = grow * min(m4 * r_p, _modal_bound(K, s, p, v, 4, fast0 * math.exp(K[I_R] * a_w)))
    return _scan_cells(
        K, q, d, a_w, s, p, v, horizon, fast0, dt, last, grow, extra,
        (s, p, v), W0, W1, W2, W2, W3, W4, (abs(s), abs(p), abs(v)), N0, N1, N2,
    )


@kernel
def _scan_slow(K, W, N, q, d, a_w, s, p, v, horizon, fast0):
    """One window of the slow scan (:class:`.modal.ModalScan`) from ``a_w``, offset ``(s, p, v)`` there.

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
    # S = c₁C + c₂D (no third term); the rounding of c₁, c₂, and |c| e^{rτ} on the cell
    return _scan_cells(
        K, q, d, a_w, s, p, v, horizon, fast0, dt, last, grow, extra,
        (c1, c2, 0.0), WC, WD, WC, WC2, WD2, WC2, (8.0 * EPS * abs(c1) + e1, 8.0 * EPS * abs(c2) + e2, ac), NC, ND, WF,
    )


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
