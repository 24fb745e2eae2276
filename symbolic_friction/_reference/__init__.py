"""An independent high-precision reference solution of the inclusion
``x' ∈ A x - b SGN(v)`` (eq. xDot, unique by Lemma 1): what the package's
simulation methods are measured against (``symbolic-friction tradeoff`` and
``extremes``, and the simulation tests).

Nothing here comes from the package's simulation code (it never calls
``_simulation``, nor the closed-form functions of its flow): only the exact
gains are read from :class:`~symbolic_friction.Parameters`.  The solution is
computed with mpmath at a working precision of ``dps`` (default 50) plus
guard digits, by methods chosen to be *different* from the package's; a state
asked for between its grid points is read from an arb enclosure of the flow
from the grid point before it (:mod:`.sample`), or from the mpmath flow.

The solution is a chain of pieces, each one of the three affine problems of
eq. (subcasesAffine): a slip ``k = ±1`` (eqs. subcasesAffine:f1 and
subcasesAffine:f-1) or a stick (eq. subcasesAffine:f0), the next piece being
chosen by the appendix's table of Claim 1 at ``v = 0``.

The flow of a slip and the search for its end are :mod:`.slip`
(whose docstring gives the argument).

Sticks and the table
--------------------
* the stick exit time is ``(sign(σ) f_s - φ)/σ``;
* the mode at ``v = 0`` is read off the appendix's table, written again here
  from the paper with exact comparisons (:func:`reference_table_mode`); with
  static friction ``f_s > f_c`` (eq. basic with a static level: stick while
  ``|φ| ≤ f_s``, kinetic friction ``f_c``) its rows at rest compare ``φ`` with
  ``±f_s``.

The former method (the same event loop, the flow as a Taylor series on a fixed
grid of step ``h₀`` and the guard on ``v'``) is kept as ``_method="grid"`` to
check the new one against; its cost grows like ``‖A‖∞ T``.
"""

from __future__ import annotations

import bisect
import math
from fractions import Fraction
from typing import Sequence

from .._infra.errors import SimulationError, SymbolicFrictionError
from .._model.parameters import Parameters
from .sample import flow_enclosed
from .slip import SlipMethods, _Piece, _factor, flow_key

__all__ = ["Reference", "reference_table_mode"]


def reference_table_mode(sigma, phi, v, f_c, f_s=None) -> int:
    """The appendix's table of Claim 1, rows (i)–(xi), written from the paper.

    With ``f_s`` the mass at rest sticks while ``|φ| ≤ f_s``.
    """
    if f_s is not None:
        f_c = f_s
    if v > 0:  # (i)
        return 1
    if v < 0:  # (xi)
        return -1
    if phi > f_c:  # (ii)
        return 1
    if phi < -f_c:  # (x)
        return -1
    if phi == f_c:  # (iii) σ > 0 → 1; (iv) σ = 0 → 0; (v) σ < 0 → 0
        return 1 if sigma > 0 else 0
    if phi == -f_c:  # (vii) σ > 0 → 0; (viii) σ = 0 → 0; (ix) σ < 0 → -1
        return -1 if sigma < 0 else 0
    return 0  # (vi) |φ| < f_c


MAX_DPS = 1000
"""The most digits a reference may be asked for (its cost grows faster than the square of ``dps``)."""
MAX_T_END = Fraction(10**12)
"""The longest horizon: the guard digits grow with ``log10(t_end)`` (``t_end = 1e200`` took half a minute)."""
MAX_EVENTS = 100_000
"""The largest ``max_events``."""
MAX_WORK = Fraction(10**20)
"""The largest ``‖A‖∞·max(t_end, 1)``, the stiffness over the horizon."""
MAX_STATE = Fraction(10**300)
"""The largest ``|z0|`` component."""


def _checked(params, z0, t_end, dps, max_events) -> tuple[list[Fraction], Fraction]:
    """The arguments of :class:`Reference`, checked before any work: ``z0`` and ``t_end`` exactly (floats binary)."""
    from .._infra.guards import check_count, check_real
    from .._infra.rational import shown, to_rational

    if not isinstance(params, Parameters):
        raise SimulationError(f"params must be a Parameters instance; got {type(params).__name__}")
    if isinstance(dps, int) and not isinstance(dps, bool) and dps < 40:
        raise SimulationError(f"the reference needs at least 40 digits; got dps = {dps}")
    check_count(dps, name="dps", low=40, high=MAX_DPS, error=SimulationError)
    check_count(max_events, name="max_events", high=MAX_EVENTS, error=SimulationError)
    if isinstance(z0, (str, bytes, dict, set)) or not hasattr(z0, "__len__") or len(z0) != 3:
        raise SimulationError(f"the initial state z0 must be three numbers (e_i, s, v); got {shown(z0)}")
    zq = []
    for i, c in enumerate(z0):
        try:
            q = to_rational(c, name=f"z0[{i}]", binary=True)
        except SymbolicFrictionError as exc:
            raise SimulationError(str(exc)) from None
        if abs(q) > MAX_STATE:
            raise SimulationError(f"z0[{i}] must lie in [-1e300, 1e300]; got {shown(c)}")
        zq.append(q)
    check_real(t_end, name="t_end", low=0, high=MAX_T_END, error=SimulationError,
               why="the reference's guard digits grow with log10(t_end)")
    t_end_q = to_rational(t_end, name="t_end", binary=True)
    norm = max(params.k_i, 1 + params.k_p, 1 + params.k_v)  # ‖A‖∞
    if norm * max(t_end_q, 1) > MAX_WORK:
        raise SimulationError(
            f"t_end·‖A‖∞ must be at most 1e20 for the reference (its guard digits and steps grow with it); got "
            f"t_end = {shown(t_end)} with ‖A‖∞ = {shown(float(norm)) if norm < 10**300 else 'beyond 1e300'}"
        )
    return zq, t_end_q


class Reference(SlipMethods):
    """High-precision solution from ``z0 = (e_i, s, v)`` on ``[0, t_end]``.

    Parameters
    ----------
    params : Parameters
    z0 : sequence of 3 floats (taken exactly) or Fractions
    t_end : float
    dps : int
        Decimal digits asked of the result (≥ 40); the arithmetic carries guard
        digits on top (see the module docstring).
    max_events : int
    _method : {"adaptive", "grid"}
        ``"grid"`` is the former fixed-grid flow, kept to check against.
    _max_step : number or None
        Overrides the step of the adaptive method (tests use it to break the
        step rule); ``None`` keeps ``min(π/(2β), t_end)``.

    Attributes
    ----------
    status : str
        ``"t_end"``, ``"equilibrium"`` or ``"max_events"``.
    events : list of (mpf, int, int)
        ``(t, mode_before, mode_after)``.
    pieces : list
        The slips and sticks in order.
    step : mpf
        The adaptive method's step ``h`` (``π/(2β)`` capped at ``t_end``).
    lambda_r, nu, beta : mpf
        The real root ``λ_r`` of ``s³ + k_v s² + k_p s + k_i`` that is divided
        out, ``ν = k_v + λ_r`` and the cofactor's ``β`` (``None`` when real).
    guard_v_hits : int
        Zeros of ``v`` found by the guard on ``v'`` but not by the one on ``g``.
    """

    def __init__(
        self,
        params: Parameters,
        z0: Sequence,
        t_end: float,
        *,
        dps: int = 50,
        max_events: int = 200,
        _method: str = "adaptive",
        _max_step=None,
    ):
        zq, t_end_q = _checked(params, z0, t_end, dps, max_events)
        if _method not in ("adaptive", "grid"):
            raise SimulationError(f"unknown reference method {_method!r}")
        from mpmath.ctx_mp import MPContext  # imported lazily

        self.dps = dps
        self.method = _method
        fr = {name: Fraction(getattr(params, name)) for name in ("k_p", "k_i", "k_v", "f_c", "f_s")}
        norm_q = max(fr["k_i"], 1 + fr["k_p"], 1 + fr["k_v"])  # ‖A‖∞, exactly

        # The step of the adaptive method and the guard digits follow from the
        # eigen-structure, found at a precision well above any working one.
        lam_r, nu, q0, beta = _factor(fr["k_p"], fr["k_i"], fr["k_v"], bits=3 * int((dps + 60) * 3.33) + 64)
        if _max_step is not None:
            step_f = float(_max_step)
        elif beta is None:
            step_f = float(t_end_q)
        else:
            step_f = min(math.pi / (2 * beta), float(t_end_q))
        h0_f = 1 / (4 * float(norm_q))
        step_f = max(step_f, h0_f)
        guard = 10 + 2 * max(0, math.ceil(math.log10(16 * float(norm_q) * max(step_f, float(t_end_q), h0_f))))
        wp = dps + guard if _method == "adaptive" else dps

        ctx = MPContext()
        ctx.dps = wp
        self.ctx = ctx
        q = lambda value: ctx.mpf(Fraction(value).numerator) / Fraction(value).denominator  # noqa: E731
        self.k_p, self.k_i, self.k_v, self.f_c = q(fr["k_p"]), q(fr["k_i"]), q(fr["k_v"]), q(fr["f_c"])
        self.f_s = q(fr["f_s"])
        self._fs_minus_fc = q(fr["f_s"] - fr["f_c"])  # exact difference, then rounded once
        self._fr = fr
        self._gains_q = tuple((fr[k].numerator, fr[k].denominator) for k in ("k_p", "k_i", "k_v"))  # for .sample
        # reset PID (Parameters.reset_dwell): the law written again from its definition, not from the kernel
        self.dwell = None if params.reset_dwell is None else q(params.reset_dwell)
        self._last_reset = None
        self.A = [
            [ctx.mpf(0), ctx.mpf(0), -self.k_i],
            [ctx.mpf(1), ctx.mpf(0), -self.k_p],
            [ctx.mpf(0), ctx.mpf(1), -self.k_v],
        ]
        self.norm = q(norm_q)
        self.h = 1 / (4 * self.norm)
        self.tol = ctx.mpf(10) ** (-(dps - 8))
        self.tol_t = self.tol * self.h
        # Taylor terms needed so that (1/4)^n / n! < 10^{-wp-5} (the grid method)
        n, term = 0, ctx.mpf(1)
        while term > ctx.mpf(10) ** (-(wp + 5)):
            n += 1
            term = term / 4 / n
        self.n_terms = n + 1
        self._E_h = None
        self._raw_cache = {}  # the raw loops' constants by precision (slip.SlipMethods._raw_constants)
        # the adaptive method's Taylor sums run at ‖A‖∞ θ ≤ 1/16
        self._theta0 = ctx.mpf(1) / 16
        n, term = 0, ctx.mpf(1)
        while term > ctx.mpf(10) ** (-(wp + 3)):
            n += 1
            term = term / 16 / n
        self._ring_terms = n + 1
        self._flow_key = flow_key(self.k_p, self.k_i, self.k_v, self.norm, self._theta0, self._ring_terms)
        self.lambda_r = ctx.mpf(lam_r)
        self.nu = ctx.mpf(nu)
        self.beta = None if beta is None else ctx.mpf(beta)
        self.step = ctx.mpf(step_f)
        self.E_step = self._expm_ring(self.step) if _method == "adaptive" else None

        e_i, s, v = (q(c) for c in zq)
        self.z0 = (e_i, s, v)
        # x0 exactly: σ = -k_i s, φ = -k_i e_i - k_p s (eq. CoC)
        self._x0q = [-fr["k_i"] * zq[1], -fr["k_i"] * zq[0] - fr["k_p"] * zq[1], zq[2]]
        self.x0 = [q(c) for c in self._x0q]
        self.t_end = q(t_end_q)
        self.max_events = max_events
        self.pieces: list[_Piece] = []
        self.events: list[tuple] = []
        self.status = "t_end"
        self._starts = None  # piece start times, for x_at
        self.guard_v_hits = 0  # zeros found by the guard on v' and missed by the one on g
        self._run()

    @property
    def E_h(self):
        """``e^{A h₀}`` as the Taylor sum of the grid method (formed when first asked for)."""
        if self._E_h is None:
            self._E_h = self._taylor_matrix(self.h)
        return self._E_h

    def _rest_mode(self, sigma, ref, off):
        """The table's mode at ``v = 0`` for ``φ = ref·f_c + off``.

        Near the threshold ``ref·f_s`` the comparisons are taken on the exact-ish
        offset ``φ - ref·f_s = off - ref (f_s - f_c)``; the table is then asked
        with a stand-in ``φ`` on the same side of every threshold.
        """
        if ref == 0:
            return reference_table_mode(sigma, off, 0, self.f_c, self.f_s)
        e = off - ref * self._fs_minus_fc
        if abs(e) < self.f_s / 2:
            phi = ref * self.f_s if e == 0 else ref * self.f_s + (self.f_s / 2 if e > 0 else -self.f_s / 2)
        else:
            phi = ref * self.f_c + off
        return reference_table_mode(sigma, phi, 0, self.f_c, self.f_s)

    def _run(self):
        ctx = self.ctx
        xq = self._x0q
        fr = self._fr
        t = ctx.mpf(0)
        mode = reference_table_mode(xq[0], xq[1], xq[2], fr["f_c"], fr["f_s"])
        # the state as (σ, ref, off, v) with φ = ref·f_c + off; at t = 0 the offsets are exact
        if mode == 0:
            sigma, ref, off = self.x0[0], 0, self.x0[1]
            exact = xq
        else:
            off_q = xq[1] - mode * fr["f_c"]
            y = [self.x0[0], ctx.mpf(off_q.numerator) / off_q.denominator, self.x0[2]]
            exact = None
        while True:
            if mode == 0:
                if sigma == 0:
                    self.pieces.append(_Piece(t, self.t_end, 0, [sigma, ref * self.f_c + off, ctx.mpf(0)]))
                    self.status = "equilibrium"
                    return
                e = 1 if sigma > 0 else -1
                if exact is not None:  # the initial stick: its exit time from the exact state
                    num = Fraction(e) * fr["f_s"] - exact[1]
                    gap = ctx.mpf(num.numerator) / num.denominator
                elif e == ref:
                    gap = e * self._fs_minus_fc - off
                else:
                    gap = e * self.f_s - ref * self.f_c - off
                exact = None
                if self.dwell is not None and self._reset(t, sigma, e, ref, off):
                    t = self._last_reset
                    ref, off = e, ctx.mpf(0)  # φ⁺ = e·f_c
                    if len(self.events) >= self.max_events:
                        self.status = "max_events"
                        return
                    continue
                t1 = t + gap / sigma
                x_start = [sigma, ref * self.f_c + off, ctx.mpf(0)]
                if t1 >= self.t_end:
                    self.pieces.append(_Piece(t, self.t_end, 0, x_start))
                    return
                self.pieces.append(_Piece(t, t1, 0, x_start))
                t = t1
                new = reference_table_mode(sigma, e * self.f_s, 0, self.f_c, self.f_s)
                if new != 0:
                    # φ = e f_s: the new slip's offset e f_s - new f_c, formed exactly
                    dq = Fraction(e) * fr["f_s"] - new * fr["f_c"]
                    y = [sigma, ctx.mpf(dq.numerator) / dq.denominator, ctx.mpf(0)]
                else:
                    ref, off = e, e * self._fs_minus_fc
            else:
                piece, y_end = self._slip(t, y, mode)
                self.pieces.append(piece)
                if y_end is None:
                    return
                t = piece.t1
                sigma, ref, off = y_end[0], mode, y_end[1]
                new = self._rest_mode(sigma, ref, off)
                if new != 0:
                    y = [sigma, off + (mode - new) * self.f_c, ctx.mpf(0)]
            if new != mode:
                self.events.append((t, mode, new))
                mode = new
            if len(self.events) >= self.max_events:
                self.status = "max_events"
                return

    def _reset(self, t, sigma, e, ref, off) -> bool:
        """Reset PID at a stick from ``t``: jump ``e_i`` so that ``φ⁺ = sign(σ)·f_c``, if the law says so.

        The jump set is ``v = 0``, ``σφ < f_c|σ|`` (``φ`` short of ``sign(σ) f_c``, which it
        reaches at the rate ``σ``) and a dwell of at least ``reset_dwell`` since the last
        jump.  Records the stick up to the jump and the event ``(t, 0, 0)``.
        """
        phi = ref * self.f_c + off
        if not e * phi < self.f_c:
            return False
        t_allow = t if self._last_reset is None else max(t, self._last_reset + self.dwell)
        if not (t_allow < t + (e * self.f_c - phi) / sigma and t_allow < self.t_end):
            return False
        if t_allow > t:
            self.pieces.append(_Piece(t, t_allow, 0, [sigma, phi, self.ctx.mpf(0)]))
        self.events.append((t_allow, 0, 0))
        self._last_reset = t_allow
        return True

    def reset_times(self):
        """Times (floats) of the resets of reset PID, in order."""
        return [float(t) for t, a, b in self.events if a == 0 and b == 0]

    # -- output ---------------------------------------------------------------
    def x_at(self, t):
        """``(σ, φ, v)`` (mpf) and the mode at time ``t`` (float or mpf)."""
        y, piece = self._offset_at(t)
        if piece.mode == 0:
            return y, 0
        return [y[0], y[1] + piece.mode * self.f_c, y[2]], piece.mode

    def _offset_at(self, t):
        """The state at ``t``: the offset ``y`` from ``x*_k`` in a slip, ``x`` in a stick."""
        t = self.ctx.mpf(t)
        if self._starts is None or len(self._starts) != len(self.pieces):
            self._starts = [p.t0 for p in self.pieces]
        # the last piece starting at or before t (the first one before t0)
        piece = self.pieces[max(0, bisect.bisect_right(self._starts, t) - 1)]
        tau = t - piece.t0
        if piece.mode == 0:
            return [piece.x0[0], piece.x0[1] + piece.x0[0] * tau, self.ctx.mpf(0)], piece
        j = max(0, min(int(tau / piece.h), len(piece.grid) - 1))
        r = tau - j * piece.h
        if piece.taylor:
            return self._poly_state(self._coefficients(piece.grid[j]), r), piece
        # between grid points from an arb enclosure (.sample), the mpmath flow when it is not tight enough
        y = None if r == 0 else flow_enclosed(self.ctx, self._gains_q, piece.grid[j], r)
        return (self._flow(piece.grid[j], r) if y is None else y), piece

    def z_mpf_at(self, t):
        """``(e_i, s, v)`` as mpf and the mode at time ``t`` (eq. CoC inverted).

        At ``t = 0`` the given state, also when reset PID jumps at once (a hybrid solution's first point).
        """
        (sigma, phi, v), mode = self.x_at(t)
        if t == 0:
            return self.z0, mode
        s = -sigma / self.k_i
        e_i = (-phi - self.k_p * s) / self.k_i
        return (e_i, s, v), mode

    def z_at(self, t):
        """``(e_i, s, v)`` as floats and the mode at time ``t``."""
        z, mode = self.z_mpf_at(t)
        return tuple(float(c) for c in z), mode

    def sample(self, times):
        """Arrays-as-lists of ``z`` and modes at ``times``."""
        zs, modes = [], []
        for t in times:
            z, m = self.z_at(t)
            zs.append(z)
            modes.append(m)
        return zs, modes

    def event_list(self):
        """Events ``(t, mode_before, mode_after)`` with float times."""
        return [(float(t), a, b) for t, a, b in self.events]

    def stick_starts(self):
        """Times (floats) at which a stick phase starts after a slip, in order."""
        return [float(t) for t, a, b in self.events if b == 0 and a != 0]

    def scale(self, times) -> float:
        """``max |z(t)|∞`` over ``times`` and ``t = 0`` (the size errors are measured relative to)."""
        zs, _ = self.sample(times)
        return self.scale_of(zs)

    def scale_of(self, zs) -> float:
        """:meth:`scale` from samples already taken (``zs`` of :meth:`sample`)."""
        return max([max(abs(c) for c in z) for z in zs] + [float(max(abs(c) for c in self.z0))])
