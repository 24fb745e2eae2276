"""The exact event-driven solution of one trajectory, written once.

This module and :mod:`._kernel_flow` are the whole closed-form simulator of
the inclusion ``x' ∈ A x - b SGN(v)`` (eq. xDot; unique solution by Lemma 1):

* from :mod:`._kernel_flow`, the closed form of a slip (:func:`w3`,
  :func:`flow`) and the certified search for its end (:func:`first_zero`),
  imported here;
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
of floats) and, unchanged, compiled by numba (:mod:`._jit` loads both files
a second time with ``_JIT = True``).  The two give the same results bit
for bit (``tests/simulation/test_kernel.py``).

Every constant the kernel needs for one gain set sits in three arrays built
by :func:`.search.slip_model` from the package's model (``A``, ``P``, the
coordinate change, the split of :class:`.modal.ModalScan`): ``K`` (scalars),
``W`` (the scan tables) and ``N`` (their rounding bounds), laid out as
:mod:`._kernel_layout` says.
"""

from __future__ import annotations

import numpy as np

from ._kernel_layout import *  # noqa: F403 - the layout of K, W, N and the codes
from ._kernel_layout import decorators

try:  # set by ._jit when it loads this file as the compiled variant
    _JIT  # type: ignore[used-before-def]  # noqa: B018
except NameError:
    _JIT = False

kernel, parallel, prange = decorators(_JIT)

if _JIT:  # the compiled closed form and search: ._jit loads it first
    from ._kernel_flow_jit import *  # noqa: F403
else:
    from ._kernel_flow import *  # noqa: F403
from .modes import mode_at_rest as _mode_at_rest_py

mode_at_rest = kernel(_mode_at_rest_py)


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
def _keep(state, spacing, e00, e01, e02, e10, e11, e12, e20, e21, e22):
    """Keep the propagator of ``spacing`` in ``state`` for the next slip (:func:`_emit`)."""
    e = S_E
    state[S_SPACING] = spacing
    state[e], state[e + 1], state[e + 2] = e00, e01, e02
    state[e + 3], state[e + 4], state[e + 5] = e10, e11, e12
    state[e + 6], state[e + 7], state[e + 8] = e20, e21, e22


@kernel
def _emit(K, q, t0, t1, final, mode, sigma, base, offset, ts, i, out_x, out_z, out_mode, state):
    """Dense output of one segment: the samples ``t0 ≤ ts[i] < t1`` (``≤ t1`` when ``final``).

    A sample at an event time belongs to the segment that starts there.
    Returns the index of the first sample not written.

    Along a slip, a sample at ``τ`` is ``e^{Aτ} y0`` in closed form (:func:`flow`:
    four transcendental functions).  When samples are equally spaced, ``Δ`` apart
    (to within the rounding of the times themselves), up to :data:`STEP_RUN` of
    them are instead stepped from the previous one with the exact propagator
    ``e^{AΔ} = w''(Δ) I + w'(Δ) B1 + w(Δ) B2`` (nine products); the closed form
    restarts every run, so rounding never accumulates over more than a few steps.
    The propagator of a spacing is computed when a sample is first stepped with
    it (a slip with one or two samples, or on stiff gains, where the closed form
    always runs, never needs it), and kept in ``state`` (``S_SPACING``, ``S_E``)
    for the next slip with the same spacing to the last bit: reset PID's
    trajectories are slip after slip, each on the same grid.
    """
    f_c = K[I_FC]
    m = ts.size
    c = I_TINV
    b1, b2 = I_B1, I_B2
    run = STEP_RUN  # the first slip sample is always in closed form
    prev = 0.0
    spacing = -1.0
    ready = False  # whether e00 … e22 are the propagator of spacing
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
                if not ready and state[S_SPACING] == spacing:
                    # computed for an earlier slip, from the same w3(K, spacing): the same numbers
                    e = S_E
                    e00, e01, e02 = float(state[e]), float(state[e + 1]), float(state[e + 2])
                    e10, e11, e12 = float(state[e + 3]), float(state[e + 4]), float(state[e + 5])
                    e20, e21, e22 = float(state[e + 6]), float(state[e + 7]), float(state[e + 8])
                    ready = True
                if not ready:
                    # the spacing's propagator, from the same w as the closed form
                    w0, w1, w2 = w3(K, spacing)
                    e00 = w2 + w1 * K[b1] + w0 * K[b2]
                    e01 = w1 * K[b1 + 1] + w0 * K[b2 + 1]
                    e02 = w1 * K[b1 + 2] + w0 * K[b2 + 2]
                    e10 = w1 * K[b1 + 3] + w0 * K[b2 + 3]
                    e11 = w2 + w1 * K[b1 + 4] + w0 * K[b2 + 4]
                    e12 = w1 * K[b1 + 5] + w0 * K[b2 + 5]
                    e20 = w1 * K[b1 + 6] + w0 * K[b2 + 6]
                    e21 = w1 * K[b1 + 7] + w0 * K[b2 + 7]
                    e22 = w2 + w1 * K[b1 + 8] + w0 * K[b2 + 8]
                    ready = True
                    _keep(state, spacing, e00, e01, e02, e10, e11, e12, e20, e21, e22)
                ys, yp, yv = (
                    e00 * ys + e01 * yp + e02 * yv,
                    e10 * ys + e11 * yp + e12 * yv,
                    e20 * ys + e21 * yp + e22 * yv,
                )
                run += 1
            else:
                ys, yp, yv = flow(K, q, tau)
                if not same and step > 0.0:
                    spacing = step  # a new spacing
                    ready = False
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
def _flow_star(g0, g1, g2, q):
    """:func:`flow` from ``(g0, g1, g2) = _basis(K, τ)`` computed before: the same products, in the same order."""
    return (
        g0 * q[0] + g1 * q[3] + g2 * q[6],
        g0 * q[1] + g1 * q[4] + g2 * q[7],
        g0 * q[2] + g1 * q[5] + g2 * q[8],
    )


@kernel
def _finite(a, b, c):
    return abs(a) <= 1.7976931348623157e308 and abs(b) <= 1.7976931348623157e308 and abs(c) <= 1.7976931348623157e308


@kernel
def _slip_numbers(K, q, mode, sigma, base, offset, v):
    """The numbers (:func:`slip_q`) of the slip the loop's state starts in mode ``mode``; ``q`` in a stick.

    For the last sample at a stop: after an event that starts a slip (a stick's end, a reversal,
    a grazing contact) ``q`` is still the previous slip's; the offset is the slip branch's own.
    """
    if mode == 0:
        return q
    p0 = offset if base == mode else (base - mode) * K[I_FC] + offset
    return slip_q(K, sigma, p0, v)


@kernel
def _save(state, turn, i, n_ev, t, sigma, v, base, offset, mode, n_resets, t_reset, q):
    """Write the event loop's state into ``state`` (the layout ``S_*`` of :mod:`._kernel_layout`)."""
    state[S_SAVED] = 1.0
    state[S_TURN] = turn
    state[S_I] = i
    state[S_N_EV] = n_ev
    state[S_T] = t
    state[S_SIGMA] = sigma
    state[S_V] = v
    state[S_BASE] = base
    state[S_OFFSET] = offset
    state[S_MODE] = mode
    state[S_RESETS] = n_resets
    state[S_T_RESET] = t_reset
    for c in range(9):
        state[S_Q + c] = q[c]


@kernel
def trajectory(K, W, N, z0, x0, t_end, max_events, ts, out_x, out_z, out_mode, ev_t, ev_x, ev_m, ev_res, state):
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
        ``E < max_events`` events occur, the status is ``BUFFER_FULL``: call
        again with room for more, the events so far copied into it, the same
        samples and ``state``, and the loop goes on where it stopped.
    state : ndarray, shape (S_SIZE,)
        Zeros for a fresh start; after ``BUFFER_FULL``, the loop's state
        (``S_*`` of :mod:`._kernel_layout`), nothing else filled or padded yet.

    Returns
    -------
    status, n_events, t_stop
    """
    f_c = K[I_FC]
    f_s, excess = K[I_FS], K[I_EXCESS]
    dwell = K[I_DWELL]  # < 0: the paper's PID
    cap = ev_t.size
    m = ts.size
    status = T_END
    if state[S_SAVED] != 0.0:
        # resumed after BUFFER_FULL with a larger event buffer: x0 and the samples before i are filled
        first = int(state[S_TURN])
        i, n_ev = int(state[S_I]), int(state[S_N_EV])
        n_resets, t_reset = int(state[S_RESETS]), float(state[S_T_RESET])
        t, sigma, v = float(state[S_T]), float(state[S_SIGMA]), float(state[S_V])
        base, offset, mode = int(state[S_BASE]), float(state[S_OFFSET]), int(state[S_MODE])
        c = S_Q
        q = (float(state[c]), float(state[c + 1]), float(state[c + 2]), float(state[c + 3]), float(state[c + 4]),
             float(state[c + 5]), float(state[c + 6]), float(state[c + 7]), float(state[c + 8]))
    else:
        first = 0
        n_resets = 0
        t_reset = 0.0
        i = 0
        n_ev = 0
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
    # e^{Aτ*}'s three scalar functions at τ* = K[I_STICK_SLIP_T], the length of every slip that leaves a stick:
    # evaluated at the first such slip of the call, then reused (reset PID slips from a stick after every reset)
    star = False
    g0_star = g1_star = g2_star = 0.0
    if status == T_END:
        # grazing contacts continue a slip without an event; bound the loop anyway
        for turn in range(first, 4 * max_events + 16):
            if n_ev >= cap:
                # a turn writes at most one event: with none left, save the state for a call with more room
                _save(state, turn, i, n_ev, t, sigma, v, base, offset, mode, n_resets, t_reset, q)
                return BUFFER_FULL, n_ev, t
            if mode == 0:
                if sigma == 0.0:
                    i = _emit(K, q, t, t_end, True, 0, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
                    status = EQUILIBRIUM
                    t = t_end
                    break
                d = 1 if sigma > 0.0 else -1
                if dwell >= 0.0:
                    # reset PID: while φ is short of d·f_c (it moves there at the rate σ) and the timer
                    # allows, e_i jumps so that φ⁺ = d·f_c (σ, v unchanged): the stick ends at once in the
                    # paper's model; V of eq. (lyapLikeV) is unchanged (model.reset)
                    phi_now = base * f_c + offset
                    if abs(sigma) <= UNDERFLOW:
                        # resets converge exponentially: a σ this small is 𝒜 in double precision (as a slip's
                        # UNDERFLOW), and following it further would only compute with subnormal numbers
                        sigma = 0.0
                        continue
                    if d * phi_now < f_c:
                        t_allow = t if n_resets == 0 else max(t, t_reset + dwell)
                        t_cross = t + (d * f_c - phi_now) / sigma
                        if t_allow < t_cross and t_allow < t_end:
                            if i < m and ts[i] < t_allow:  # a reset right after a slip: usually no sample
                                i = _emit(K, q, t, t_allow, False, 0, sigma, base, offset, ts, i,
                                          out_x, out_z, out_mode, state)
                            ev_t[n_ev] = t_allow
                            ev_x[n_ev, 0] = sigma
                            ev_x[n_ev, 1] = phi_now + sigma * (t_allow - t)
                            ev_x[n_ev, 2] = 0.0
                            ev_m[n_ev, 0] = 0
                            ev_m[n_ev, 1] = 0
                            ev_res[n_ev] = 0.0
                            n_ev += 1
                            n_resets += 1
                            t = t_allow
                            t_reset = t
                            base, offset = d, 0.0
                            if n_ev >= max_events:
                                i = _emit(K, q, t, t, True, mode, sigma, base, offset, ts, i,
                                          out_x, out_z, out_mode, state)
                                status = MAX_EVENTS
                                break
                            continue
                # distance to the exit d·f_s: exactly -offset when leaving where the last slip ended
                gap = -offset if base == d else (d - base) * f_c - offset
                if excess != 0.0:
                    gap += d * excess
                t_next = t + gap / sigma
                if t_next >= t_end:
                    i = _emit(K, q, t, t_end, True, 0, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
                    t = t_end
                    break
                if i < m and ts[i] < t_next:  # after a reset the stick ends at once: no sample
                    i = _emit(K, q, t, t_next, False, 0, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
                # rows (iii)/(ix): slip d; with stiction from φ = d·f_s, with a jump in v' to d·(f_s - f_c)
                t, base, offset, mode = t_next, d, (d * excess if excess != 0.0 else 0.0), d
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
                    if found == FOUND:
                        if not star:
                            g0_star, g1_star, g2_star = _basis(K, tau)
                            star = True
                        ys, yp, yv = _flow_star(g0_star, g1_star, g2_star, q)
                    else:
                        ys, yp, yv = flow(K, q, horizon)
                elif p0 == 0.0 and v0 == 0.0 and horizon <= K[I_STICK_SLIP_H]:
                    found, tau = NONE, horizon  # w has no zero within the cached horizon
                    ys, yp, yv = flow(K, q, horizon)
                else:
                    found, tau, ys, yp, yv = first_zero(K, W, N, s0, p0, v0, d, horizon)
                if found == UNDECIDED:
                    # the search could not decide where this slip ends: stop at its start, never guess
                    i = _emit(K, q, t, t, True, d, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
                    status = NO_DECISION
                    break
                if found == NONE:
                    i = _emit(K, q, t, t_end, True, d, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
                    t = t_end
                    break
                t_next = t + tau
                i = _emit(K, q, t, t_next, False, d, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
                residual = abs(yv)
                if max(abs(ys), abs(yp), abs(yv)) <= UNDERFLOW:  # decayed onto x*_k ∈ 𝒜
                    ys, yp = 0.0, 0.0
                tol = SNAP_ULPS * EPS * max(abs(s0), abs(p0), abs(v0))
                base, offset, new_mode = mode_after_slip(ys, yp, d, f_c, tol, excess)
                t, sigma, v = t_next, ys, 0.0
                if new_mode != d:  # else a grazing contact: the slip goes on
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
                    q = _slip_numbers(K, q, mode, sigma, base, offset, v)
                    i = _emit(K, q, t, t_end, True, mode, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
                    t = t_end
                    break
            if n_ev >= max_events:
                q = _slip_numbers(K, q, mode, sigma, base, offset, v)
                i = _emit(K, q, t, t, True, mode, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
                status = MAX_EVENTS
                break
        else:
            q = _slip_numbers(K, q, mode, sigma, base, offset, v)
            i = _emit(K, q, t, t, True, mode, sigma, base, offset, ts, i, out_x, out_z, out_mode, state)
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
    # a reset at t = 0: the samples at 0 are the given state, before the jump (a hybrid solution's first point)
    jumped_at_0 = n_ev > 0 and ev_t[0] == 0.0 and ev_m[0, 0] == 0 and ev_m[0, 1] == 0
    for j in range(m):  # the given state, not its round trip through x
        if ts[j] != 0.0:
            break
        if status != NONFINITE:
            for c in range(3):
                out_z[j, c] = z0[c]
                if jumped_at_0:
                    out_x[j, c] = x0[c]
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
    K, W, N, Z0, X0, t_end, max_events, ts, out_x, out_z, out_mode, ev_t, ev_x, ev_m, ev_res, state,
    status, n_ev, t_stop, rows,
):
    """:func:`trajectory` for the rows ``rows`` of ``Z0``, ``X0``, ``out_*``, ``state`` (shape (N, S_SIZE)),
    ``status``, ``n_ev`` and ``t_stop`` (in parallel when compiled).

    Row ``rows[r]`` has its events in row ``r`` of ``ev_t``, ``ev_x``, ``ev_m``,
    ``ev_res``, so that the trajectories that go on after ``BUFFER_FULL`` get
    larger event buffers while their samples stay where they are.
    """
    for r in prange(rows.size):
        j = rows[r]
        st, ne, ts_ = trajectory(
            K, W, N, Z0[j], X0[j], t_end, max_events, ts,
            out_x[j], out_z[j], out_mode[j], ev_t[r], ev_x[r], ev_m[r], ev_res[r], state[j],
        )
        status[j] = st
        n_ev[j] = ne
        t_stop[j] = ts_
