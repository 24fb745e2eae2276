"""An independent high-precision reference solution of the inclusion
``x' ∈ A x - b SGN(v)`` (eq. xDot, unique by Lemma 1): what the package's
simulation methods are measured against (``symbolic-friction tradeoff`` and
``extremes``, and the simulation tests).

Nothing here comes from the package's simulation code (it never calls
``_simulation``, nor the closed-form functions of its flow): only the exact
gains are read from :class:`~symbolic_friction.Parameters`.  Everything is
computed with mpmath at a working precision of ``dps`` (default 50) plus
guard digits, by methods chosen to be *different* from the package's.

The solution is a chain of pieces, each one of the three affine problems of
eq. (subcasesAffine): a slip ``k = ±1`` (eqs. subcasesAffine:f1 and
subcasesAffine:f-1) or a stick (eq. subcasesAffine:f0), the next piece being
chosen by the appendix's table of Claim 1 at ``v = 0``.

Slips: the flow
---------------
Within slip ``k`` the state is ``x = x*_k + y`` with ``x*_k = (0, k f_c, 0)``
and ``y' = A y`` (``A`` of eq. xDot), and the reference carries the *offset* ``y``, never
``x``: a solution that creeps (``v`` tiny, ``|φ|`` just past ``f_c``) has a
small ``y`` known to full relative precision, where ``φ`` itself would hold
it only to ``10^{-dps} f_c``.  At rest the state is likewise
``φ = k f_c + (offset)``; the stick exit time ``(±f_s - φ)/σ`` and the table's
comparisons of ``φ`` with ``±f_s`` are taken on the offset, with
``f_s - f_c`` formed exactly from the rational gains.

``e^{Aτ}`` is kept as the three numbers ``(c₀, c₁, c₂)`` of
``e^{Aτ} = c₀ I + c₁ A + c₂ A²`` (Cayley–Hamilton, ``A³ = -k_v A² - k_p A -
k_i I``): a Taylor series ``Σ (θA)ⁿ/n!`` for ``θ = τ/2^m`` with
``‖A‖∞ θ ≤ 1/16``, then ``m`` squarings in that algebra (scaling and
squaring).  No root of the characteristic polynomial and no closed form enter
the flow.  The cost of ``e^{Aτ}`` grows like ``log(‖A‖τ)``, not ``‖A‖τ``:
this is what makes stiff gains (``k_v`` up to ``10^9``, fast mode ``≈ -k_v``
dying within ``1/k_v`` while the slow pair lives on a scale ``≫ 1/k_v``)
cost as much as mild ones.  The squarings amplify rounding by up to about
``(‖A‖τ)²``; the working precision carries
``10 + 2 log₁₀(16 ‖A‖∞ max(h, T))`` guard digits for it (18 digits for
Table I with ``T = 10``, 32 for ``k_v = 10^8``, ``T = 20``).  The grid values ``y(jh)`` are
``e^{Ah}`` applied repeatedly; a state between them is ``e^{Ar}`` applied to
the grid value before it.

Slips: the step and the event search
------------------------------------
A slip ``k`` ends at the first zero of ``v``.  The flow is sampled on a grid of
step ``h``, and inside a step a zero of ``v`` can hide only between two
crossings.  The step rule comes from a factorization of the characteristic
polynomial ``p(s) = s³ + k_v s² + k_p s + k_i`` (every component of ``y``
solves ``p(D) u = 0``): take a real root ``λ_r`` (one lies in ``(-k_v, 0)``
since ``p(-k_v) = k_i - k_v k_p < 0 < p(0)`` by Assumption 1; it is found by
Newton's method inside a bisection bracket at three times the working
precision), so that
``p(s) = (s - λ_r) q(s)`` with ``q(s) = s² + ν s + q₀``, ``ν = k_v + λ_r``,
``q₀ = -k_i/λ_r``.  Then

* ``g(τ) = e^{-λ_r τ} v(τ)`` has the zeros of ``v`` and
  ``g' = e^{-λ_r τ} w`` with ``w = v' - λ_r v = y_φ - ν y_v``;
* ``w`` solves ``q(D) w = 0``: it is ``c₁e^{μ₁τ} + c₂e^{μ₂τ}``,
  ``(c₁ + c₂τ) e^{μτ}`` or ``r e^{ατ} cos(βτ + θ)``; the first two have at most
  one zero on the whole line, the third at most one on any interval shorter
  than ``π/β``.

So with ``h ≤ π/(2β)`` (no limit when ``q`` has real roots; ``h ≤ T``
anyway) ``g`` has *at most one extremum in a step*, whatever the size of the
decaying mode ``λ_r`` (the fast one in a stiff gain set): the double-crossing
guard, a sign change of ``k·v'`` from − to + with ``k·v ≤ 0`` at the minimum,
is applied to ``g``, whose derivative has the sign of ``w``; for ``λ_r = 0``
it would be the guard on ``v'`` itself.  ``v`` may have two extrema in a step
(the fast transient and a slow turn), ``g`` not.  With ``u = k v`` on a step
``[a, b]``:

* ``u(b) ≤ 0 < u(a)``: exactly one zero in ``(a, b]``;
* ``u(a), u(b) > 0``: a zero lies inside only if ``g`` has a minimum there,
  i.e. ``k w`` changes sign from − to +; its zero ``m`` is found and the
  slip ends in ``(a, m]`` iff ``u(m) ≤ 0``;
* at the start of a slip ``u(a) = 0`` and ``k w(a) = k v'(a) ≥ 0`` (the table
  picks ``k`` so); if ``u(b) ≤ 0`` the zero follows the maximum of ``g``, the
  zero of ``w`` in ``(a, b)``.

The argument is exact for the exact ``λ_r``; the computed one is off by
``10^{-3·wp}`` relative, which moves ``w`` by far less than its rounding.
This is also why the step does not have to shrink with the fast mode: that
mode is divided out of ``g``, and the step is set by the slow pair alone, so
the cost of a trajectory is set by its number of events and by ``βT``, not by
``‖A‖∞ T``.  The former guard on ``v'`` is still run after the one on ``g``;
a zero that only it finds is counted in ``guard_v_hits`` (none has been seen).
The crossings are located by Newton's method on the flow, safeguarded by
bisection, down to ``10^{-(dps-8)} h₀`` with ``h₀ = 1/(4‖A‖∞)``.

A slip that leaves a stick and creeps is one slip like any other: it starts
from ``y = (σ, k(f_s - f_c), 0)`` exactly, and ``v`` stays of one sign until
its next zero, which the guard finds whatever the length of the creep.

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
from dataclasses import dataclass
from fractions import Fraction
from typing import Sequence

from ._errors import SimulationError
from ._parameters import Parameters

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


@dataclass
class _Piece:
    t0: object  # mpf
    t1: object
    mode: int
    x0: list  # [σ, φ, v] at t0
    grid: list | None = None  # slip: offsets y = x - x*_k at t0 + j h
    h: object = None  # slip: the grid's step
    taylor: bool = True  # slip: grid values continued by their Taylor polynomial (the "grid" method)


class Reference:
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
        if dps < 40:
            raise SimulationError(f"the reference needs at least 40 digits; got dps = {dps}")
        if _method not in ("adaptive", "grid"):
            raise SimulationError(f"unknown reference method {_method!r}")
        from mpmath.ctx_mp import MPContext  # imported lazily

        self.dps = dps
        self.method = _method
        fr = {name: Fraction(getattr(params, name)) for name in ("k_p", "k_i", "k_v", "f_c", "f_s")}
        norm_q = max(fr["k_i"], 1 + fr["k_p"], 1 + fr["k_v"])  # ‖A‖∞, exactly
        t_end_q = Fraction(t_end)

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
        # the adaptive method's Taylor sums run at ‖A‖∞ θ ≤ 1/16
        self._theta0 = ctx.mpf(1) / 16
        n, term = 0, ctx.mpf(1)
        while term > ctx.mpf(10) ** (-(wp + 3)):
            n += 1
            term = term / 16 / n
        self._ring_terms = n + 1
        self.lambda_r = ctx.mpf(lam_r)
        self.nu = ctx.mpf(nu)
        self.beta = None if beta is None else ctx.mpf(beta)
        self.step = ctx.mpf(step_f)
        self.E_step = self._expm_ring(self.step) if _method == "adaptive" else None

        zq = [Fraction(c) for c in z0]
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

    # -- linear algebra on lists of mpf -------------------------------------
    def _mv(self, M, y):
        return [M[i][0] * y[0] + M[i][1] * y[1] + M[i][2] * y[2] for i in range(3)]

    def _Ay(self, y):
        return [-self.k_i * y[2], y[0] - self.k_p * y[2], y[1] - self.k_v * y[2]]

    def _taylor_matrix(self, tau):
        ctx = self.ctx
        E = [[ctx.mpf(int(i == j)) for j in range(3)] for i in range(3)]
        term = [row[:] for row in E]
        for n in range(1, self.n_terms):
            term = [[sum(term[i][k] * self.A[k][j] for k in range(3)) * tau / n for j in range(3)] for i in range(3)]
            E = [[E[i][j] + term[i][j] for j in range(3)] for i in range(3)]
        return E

    # -- e^{Aτ} = c₀ I + c₁ A + c₂ A² by scaling and squaring ----------------------
    def _ring_mul(self, a, b):
        """Product in ``R[A]``, reduced by ``A³ = -k_v A² - k_p A - k_i I``."""
        a0, a1, a2 = a
        b0, b1, b2 = b
        d0 = a0 * b0
        d1 = a0 * b1 + a1 * b0
        d2 = a0 * b2 + a1 * b1 + a2 * b0
        d3 = a1 * b2 + a2 * b1
        d4 = a2 * b2
        d3 -= self.k_v * d4
        d2 -= self.k_p * d4
        d1 -= self.k_i * d4
        d2 -= self.k_v * d3
        d1 -= self.k_p * d3
        d0 -= self.k_i * d3
        return (d0, d1, d2)

    def _expm_ring(self, tau):
        """``(c₀, c₁, c₂)`` with ``e^{Aτ} = c₀ I + c₁ A + c₂ A²`` (``τ < 0`` only for a
        time asked for before a piece's start)."""
        ctx = self.ctx
        if tau == 0:
            return (ctx.mpf(1), ctx.mpf(0), ctx.mpf(0))
        theta = self.norm * abs(tau)
        m = 0
        if theta > self._theta0:
            m = max(0, int(math.ceil(math.log2(float(theta / self._theta0)))))
            while ctx.ldexp(theta, -m) > self._theta0:
                m += 1
        s = ctx.ldexp(tau, -m)
        k_p, k_i, k_v = self.k_p, self.k_i, self.k_v
        t0, t1, t2 = ctx.mpf(1), ctx.mpf(0), ctx.mpf(0)
        c0, c1, c2 = t0, t1, t2
        for n in range(1, self._ring_terms):
            f = s / n
            t0, t1, t2 = -k_i * t2 * f, (t0 - k_p * t2) * f, (t1 - k_v * t2) * f
            c0 += t0
            c1 += t1
            c2 += t2
        c = (c0, c1, c2)
        for _ in range(m):
            c = self._ring_mul(c, c)
        return c

    def _apply(self, c, y):
        Ay = self._Ay(y)
        AAy = self._Ay(Ay)
        return [c[0] * y[i] + c[1] * Ay[i] + c[2] * AAy[i] for i in range(3)]

    def _flow(self, y, tau):
        """``e^{Aτ} y``."""
        return self._apply(self._expm_ring(tau), y)

    def _w(self, y):
        """``w = v' - λ_r v`` for ``y' = A y``: the derivative of ``g = e^{-λ_r τ} v`` up to ``e^{-λ_r τ} > 0``."""
        return y[1] - self.nu * y[2]

    # -- the grid method's Taylor polynomials -------------------------------------
    def _coefficients(self, y):
        """``A^n y / n!`` for n < n_terms: the Taylor coefficients of the flow at a grid point."""
        coeffs = [list(y)]
        for n in range(1, self.n_terms):
            coeffs.append([c / n for c in self._mv(self.A, coeffs[-1])])
        return coeffs

    @staticmethod
    def _poly(coeffs, tau, comp):
        acc = coeffs[-1][comp]
        for c in reversed(coeffs[:-1]):
            acc = acc * tau + c[comp]
        return acc

    def _poly_state(self, coeffs, tau):
        return [self._poly(coeffs, tau, i) for i in range(3)]

    def _dpoly(self, coeffs, tau, comp):
        acc = (len(coeffs) - 1) * coeffs[-1][comp]
        for n in range(len(coeffs) - 2, 0, -1):
            acc = acc * tau + n * coeffs[n][comp]
        return acc

    def _bisect(self, f, lo, hi):
        """Zero of ``f`` with ``f(lo) > 0 ≥ f(hi)``."""
        while hi - lo > self.tol * self.h:
            mid = (lo + hi) / 2
            if f(mid) > 0:
                lo = mid
            else:
                hi = mid
        return hi

    # -- root finding on the flow (adaptive method) ---------------------------------
    def _zero(self, F, lo, hi):
        """A zero of ``f`` with ``f(lo) > 0 ≥ f(hi)``, ``F(τ) = (f, f')``: the returned
        ``hi`` has ``f(hi) ≤ 0`` and lies within ``tol_t`` of a ``lo`` with ``f(lo) > 0``.

        Newton's method from the bracket end with the smaller ``|f|``, falling back
        to bisection whenever it leaves the bracket or the bracket fails to halve;
        once a Newton correction is below ``tol_t/4`` the bracket is closed by two
        probes ``tol_t/2`` either side.
        """
        tol = self.tol_t
        f_lo, d_lo = F(lo)
        f_hi, d_hi = F(hi)
        stall = 0
        for _ in range(4000):
            width = hi - lo
            if width <= tol:
                return hi
            c = None
            if stall < 2:
                x0, f0, d0 = (lo, f_lo, d_lo) if abs(f_lo) <= abs(f_hi) else (hi, f_hi, d_hi)
                if d0 != 0:
                    c = x0 - f0 / d0
                    if not lo < c < hi:
                        c = None
                    elif abs(c - x0) < tol / 4:
                        for p in (c - tol / 2, c + tol / 2):
                            if lo < p < hi:
                                fp, dp = F(p)
                                if fp > 0:
                                    lo, f_lo, d_lo = p, fp, dp
                                else:
                                    hi, f_hi, d_hi = p, fp, dp
                        stall = stall + 1 if hi - lo > width / 2 else 0
                        continue
            if c is None:
                c = (lo + hi) / 2
                stall = 0
            fc, dc = F(c)
            if fc > 0:
                lo, f_lo, d_lo = c, fc, dc
            else:
                hi, f_hi, d_hi = c, fc, dc
            if hi - lo > width / 2:
                stall += 1
            else:
                stall = 0
        raise SimulationError("the reference's root search did not converge")

    # -- the event loop -------------------------------------------------------
    def _slip(self, t0, y0, d):
        """Follow slip ``d`` from the offset ``y0 = x - x*_d`` at ``t0``; return the
        piece and the offset at its end (``None`` when it reaches ``t_end``)."""
        if self.method == "grid":
            return self._slip_grid(t0, y0, d)
        h, E = self.step, self.E_step
        horizon = self.t_end - t0
        y = y0
        grid = [y]
        u_a, w_a = d * y[2], d * self._w(y)
        j = 0
        x0 = [y0[0], y0[1] + d * self.f_c, y0[2]]
        while True:
            a = j * h
            if a >= horizon:
                return _Piece(t0, self.t_end, d, x0, grid, h, False), None
            y_b = self._apply(E, y)
            u_b, w_b = d * y_b[2], d * self._w(y_b)
            hit = self._crossing(y, y_b, d, h, u_a, w_a, u_b, w_b)
            if hit is not None and a + hit <= horizon:
                y_end = self._flow(y, hit)
                return _Piece(t0, t0 + a + hit, d, x0, grid, h, False), [y_end[0], y_end[1], self.ctx.mpf(0)]
            y, u_a, w_a = y_b, u_b, w_b
            grid.append(y)
            j += 1

    def _crossing(self, y, y_b, d, h, u_a, w_a, u_b, w_b):
        """The first zero of ``u = d v`` in ``(0, h]`` of the flow from ``y`` (reaching
        ``y_b`` at ``h``), or ``None`` (the case analysis of the module docstring)."""

        def u(tau):
            z = self._flow(y, tau)
            return d * z[2], d * (z[1] - self.k_v * z[2])

        def w(sign):
            def f(tau):
                z = self._flow(y, tau)
                Az = self._Ay(z)
                return sign * d * self._w(z), sign * d * self._w(Az)

            return f

        def minus_du(tau):
            z = self._flow(y, tau)
            Az = self._Ay(z)
            return -d * Az[2], -d * self._Ay(Az)[2]

        ctx = self.ctx
        if u_b <= 0:
            if u_a > 0:
                return self._zero(u, ctx.mpf(0), h)
            # slip start: the zero follows the maximum of g
            if w_a > 0 and w_b < 0:
                m = self._zero(w(1), ctx.mpf(0), h)
                if u(m)[0] > 0:
                    return self._zero(u, m, h)
                return self._zero(u, h * self.tol, m)
            return self._zero(u, h * self.tol, h)
        if w_a < 0 < w_b:
            # one minimum of g inside: the slip ends before it iff v reaches 0 there
            m = self._zero(w(-1), ctx.mpf(0), h)
            if u(m)[0] <= 0:
                lo = ctx.mpf(0) if u_a > 0 else h * self.tol
                return self._zero(u, lo, m)
        # The former guard on v' itself, kept as a second line: a minimum of v with
        # v ≤ 0 there that the guard on g did not see could only come from rounding.
        du_a, du_b = d * (y[1] - self.k_v * y[2]), d * (y_b[1] - self.k_v * y_b[2])
        if u_a > 0 and du_a < 0 < du_b:
            m = self._zero(minus_du, ctx.mpf(0), h)
            if u(m)[0] <= 0:
                self.guard_v_hits += 1
                return self._zero(u, ctx.mpf(0), m)
        return None

    def _slip_grid(self, t0, y0, d):
        """The former method: Taylor grid of step ``h₀`` and the guard on ``v'``."""
        y = y0
        grid = [y]
        horizon = self.t_end - t0
        x0 = [y0[0], y0[1] + d * self.f_c, y0[2]]
        j = 0
        while True:
            a = j * self.h
            if a >= horizon:
                return _Piece(t0, self.t_end, d, x0, grid, self.h, True), None
            y_next = self._mv(self.E_h, y)
            u_a, u_b = d * y[2], d * y_next[2]
            coeffs = None
            hit = None
            if u_b <= 0:
                coeffs = self._coefficients(y)
                lo = a if u_a > 0 else a + self.h * self.tol
                hit = self._bisect(lambda s: d * self._poly(coeffs, s - a, 2), lo, a + self.h) - a
            else:
                du_a = d * (y[1] - self.k_v * y[2])
                du_b = d * (y_next[1] - self.k_v * y_next[2])
                if du_a < 0 < du_b:
                    coeffs = self._coefficients(y)
                    m = self._bisect(lambda s: -d * self._dpoly(coeffs, s - a, 2), a, a + self.h) - a
                    if d * self._poly(coeffs, m, 2) <= 0:
                        hit = self._bisect(lambda s: d * self._poly(coeffs, s - a, 2), a, a + m) - a
            if hit is not None and a + hit <= horizon:
                y_end = self._poly_state(coeffs, hit)
                return _Piece(t0, t0 + a + hit, d, x0, grid, self.h, True), [y_end[0], y_end[1], self.ctx.mpf(0)]
            y = y_next
            grid.append(y)
            j += 1

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
        return self._flow(piece.grid[j], r), piece

    def z_mpf_at(self, t):
        """``(e_i, s, v)`` as mpf and the mode at time ``t`` (eq. CoC inverted)."""
        (sigma, phi, v), mode = self.x_at(t)
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
        return max([max(abs(c) for c in z) for z in zs] + [float(max(abs(c) for c in self.z0))])


def _factor(k_p: Fraction, k_i: Fraction, k_v: Fraction, *, bits: int):
    """A real root ``λ_r`` of ``p(s) = s³ + k_v s² + k_p s + k_i`` and its cofactor.

    Returns ``(λ_r, ν, q₀, β)`` as mpf at ``bits`` of precision, with
    ``p(s) = (s - λ_r)(s² + ν s + q₀)`` and ``β`` the imaginary part of the
    cofactor's roots (a float; ``None`` when they are real).  ``λ_r`` is
    found in ``(-k_v, 0)``, where ``p`` changes sign by Assumption 1
    (``p(-k_v) = k_i - k_v k_p < 0 < k_i = p(0)``), by Newton's method kept
    inside a bisection bracket, so no root solver is trusted with a
    clustered or multiple root.
    """
    from mpmath.ctx_mp import MPContext

    ctx = MPContext()
    ctx.prec = bits
    kp, ki, kv = (ctx.mpf(x.numerator) / x.denominator for x in (k_p, k_i, k_v))

    def p(s):
        return ((s + kv) * s + kp) * s + ki

    # Newton's method inside the bracket, bisection whenever it leaves the bracket
    # or stops converging quadratically (a multiple root)
    lo, hi = -kv, ctx.mpf(0)  # p(lo) < 0 < p(hi)
    eps = ctx.ldexp(ctx.mpf(1), 8 - bits)
    root_eps = ctx.ldexp(ctx.mpf(1), 4 - bits // 2)
    lam, last = (lo + hi) / 2, None
    for _ in range(8 * bits):
        value = p(lam)
        if value == 0:
            break
        if value < 0:
            lo = lam
        else:
            hi = lam
        slope = (3 * lam + 2 * kv) * lam + kp
        new = lam - value / slope if slope != 0 else None
        newton = new is not None and lo <= new <= hi and (last is None or abs(new - lam) <= abs(last) / 2)
        if not newton:
            new = (lo + hi) / 2
        step, lam = new - lam, new
        if abs(step) <= eps * abs(lam) or hi - lo <= eps * abs(lam):
            break
        if newton and abs(step) <= root_eps * abs(lam):
            # converging quadratically: the next correction is at the rounding level
            slope = (3 * lam + 2 * kv) * lam + kp
            if slope != 0:
                lam = lam - p(lam) / slope
            break
        last = step
    nu = kv + lam
    q0 = -ki / lam
    disc = nu * nu - 4 * q0
    beta = None if disc >= 0 else float(ctx.sqrt(-disc) / 2)
    return lam, nu, q0, beta
