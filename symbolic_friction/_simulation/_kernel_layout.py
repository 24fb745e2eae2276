"""The layout of the event kernel's constants, and how its functions are compiled.

:mod:`._kernel_flow` (the closed form and the search for a slip's end) and
:mod:`._kernel` (the event loop) are written once, in the subset of Python
that numba compiles; :mod:`._jit` loads each file a second time, with
``_JIT = True``, for the compiled variant.  What both variants share is here:
where each constant of a gain set sits in the arrays ``K``, ``W``, ``N``
(built by :func:`.search.slip_model` from the package's model), the codes the
kernel returns, and :func:`decorators`.
"""

from __future__ import annotations

import math

def decorators(jit: bool):
    """``(kernel, parallel, prange)``: numba's ``njit`` (cached, no GIL) when ``jit``, else the identity."""
    if jit:  # pragma: no cover - exercised in the compiled variant only
        import numba

        return (
            numba.njit(cache=True, nogil=True),
            numba.njit(cache=True, nogil=True, parallel=True),
            numba.prange,
        )

    def identity(f):
        return f

    return identity, identity, range


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
# The two time scales of a slip (:class:`.modal.ModalScan`): e^{Aτ} y = e^{rτ} M_F y + C(τ) M_C y + D(τ) M_D y,
# so v(a + τ) = c e^{rτ} + c₁ C(τ) + c₂ D(τ) with (c, c₁, c₂) the third rows of M_F, M_C, M_D applied to y(a),
# and |S⁽ʲ⁾| ≤ μⱼ √E for the pair's part S = c₁ C + c₂ D.
I_MODAL, I_STIFF = 62, 63  # 1.0 when the march and the scan use the split's bounds, and the flow the split
I_PQ = 64  # q = α² - β², E = q S² + S'²
I_MU = 65  # μ₀ … μ₄
I_SDT, I_SCELLS, I_SWINDOW, I_TFAST = 70, 71, 72, 73  # slow table Δ, cells, length; fast part decayed after
I_MF, I_MC, I_MD = 74, 83, 92  # 3×3 row-major each
# Reset PID (Parameters.reset_dwell): the dwell time τ_d between resets, or -1 for the paper's PID, where
# the event loop takes exactly the paper's path.  A reset is an event with modes (0, 0).
I_DWELL = 101
K_SIZE = 102
# Rows of W and N: the scan table of w (ScanTable) and, below it, the slow table of the pair (ModalScan).
W_FAST, W_SLOW = 0, 5
N_FAST, N_SLOW = 0, 3
# Results of the searches: no zero up to the horizon, a zero, or a bound too weak to decide.
NONE, FOUND, UNDECIDED = 0, 1, 2

# -- statuses --------------------------------------------------------------------
T_END, MAX_EVENTS, EQUILIBRIUM, NONFINITE, BUFFER_FULL, NO_DECISION = 0, 1, 2, 3, 4, 5

# -- the event loop's state, saved when its event buffer is full ------------------
# A call of the loop that stops with BUFFER_FULL writes here everything the loop carries from one turn to
# the next; called again with the same samples, its events so far in a larger buffer and this state, it
# goes on where it stopped, so the trajectory is the one a single call with the larger buffer gives, bit
# for bit, and nothing is computed twice (event.run).  S_SAVED is 0 for a fresh start; integers are
# stored as floats (exact below 2⁵³).
S_SAVED, S_TURN, S_I, S_N_EV, S_T, S_SIGMA, S_V, S_BASE, S_OFFSET, S_MODE, S_RESETS, S_T_RESET = range(12)
S_Q = 12  # the nine numbers of the last slip (slip_q), carried with the rest (a stop's last sample in a slip
# mode computes the numbers of the slip it is in from the state, _kernel._slip_numbers: q may be an earlier slip's)
# The dense output's propagator e^{AΔ} (nine entries, row-major) for the spacing Δ at S_SPACING (0: none yet),
# kept from one slip to the next: the samples of a uniform grid have one Δ, to the last bit, in every slip.
S_SPACING, S_E = 21, 22
S_SIZE = 31

# A slip that has decayed to within this (absolute) distance of its equilibrium
# x*_k = (0, k f_c, 0), a point of 𝒜, cannot be followed further in double
# precision (the closed form's products become subnormal and v = 0 by
# underflow).  The search reports a zero there (:mod:`.search`), and the event loop puts the
# state on x*_k, an equilibrium.
UNDERFLOW = 1e-280

EPS = 2.220446049250313e-16
# ulps allowed between a computed φ and ±f_c before σ decides (rows iii/v/vii/ix)
SNAP_ULPS = 8.0
# Dense output: at most this many equally spaced slip samples in a row are stepped with the
# exact propagator e^{AΔ} before the closed form is evaluated again (see _emit).
STEP_RUN = 8
N_SERIES = 12
# 1/(2n)! and 1/(2n+1)! for n = 0 … N_SERIES (12 terms reach 1/24! ≈ 1.6e-24)
INV_EVEN_FACT = tuple(1.0 / math.factorial(2 * n) for n in range(N_SERIES + 1))
INV_ODD_FACT = tuple(1.0 / math.factorial(2 * n + 1) for n in range(N_SERIES + 1))

__all__ = [name for name in dir() if name.isupper()]  # the constants; decorators is imported by name
