"""The slips of the high-precision reference (:class:`~symbolic_friction._reference.Reference`): their flow and their end.

Like the rest of the reference, nothing here comes from the package's
simulation code; everything is mpmath at the reference's working precision.

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
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from mpmath.libmp import fone, from_int, fzero, mpf_add, mpf_div, mpf_mul, mpf_neg, mpf_sub

from .._infra.errors import SimulationError

__all__ = ["SlipMethods"]

_EXPM_CACHE_SIZE = 16384
"""The most ``e^{Aτ}`` remembered (then they are all forgotten and the count starts again)."""
_EXPM_CACHE: dict = {}
"""``e^{Aτ}`` (raw) by ``(flow_key, τ, precision, rounding)``, shared by a process's references: the key holds all
the value is formed from, so a value found is the one that would be formed, bit for bit.  The event search asks
again for its brackets' ends; a reference made again (another horizon or event budget) for the same ``τ``."""


def flow_key(k_p, k_i, k_v, norm, theta0, ring_terms) -> tuple:
    """What ``e^{Aτ}`` is formed from besides ``τ``: gains, ``‖A‖∞``, scaling threshold (mpf), Taylor terms."""
    return (k_p._mpf_, k_i._mpf_, k_v._mpf_, norm._mpf_, theta0._mpf_, ring_terms)


@dataclass
class _Piece:
    t0: object  # mpf
    t1: object
    mode: int
    x0: list  # [σ, φ, v] at t0
    grid: list | None = None  # slip: offsets y = x - x*_k at t0 + j h
    h: object = None  # slip: the grid's step
    taylor: bool = True  # slip: grid values continued by their Taylor polynomial (the "grid" method)


class SlipMethods:
    """The flow and the event search of :class:`._reference.Reference` (its attributes ``ctx``, ``A``, ``h``, …)."""

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
    # These loops hold most of the reference's time, so they run on mpmath's raw values
    # (the ``_mpf_`` tuples) with the very calls ``ctx.mpf`` arithmetic makes (``mpf_mul``,
    # ``mpf_add``, ``mpf_sub``, ``mpf_div`` at the context's precision and rounding), in the
    # same order: the results are the same bits, without an mpf object per operation.
    def _raw_constants(self, prec, rnd):
        """``(-k_i, k_p, k_v, [n for n < ring_terms])`` raw for the loops at ``prec`` (``-k_i`` as mpf rounds it)."""
        key = (prec, rnd)
        consts = self._raw_cache.get(key)
        if consts is None:
            consts = (mpf_neg(self.k_i._mpf_, prec, rnd), self.k_p._mpf_, self.k_v._mpf_,
                      [from_int(n) for n in range(self._ring_terms)])
            self._raw_cache[key] = consts
        return consts

    def _ring_square(self, a, prec, rnd):
        """``a²`` for a raw triple in ``R[A]``, reduced by ``A³ = -k_v A² - k_p A - k_i I`` (a squaring
        step): each cross product ``a_i a_j = a_j a_i`` (one rounded product, ``mpf_mul`` being symmetric)
        is formed once and added twice."""
        a0, a1, a2 = a
        p01 = mpf_mul(a0, a1, prec, rnd)
        p02 = mpf_mul(a0, a2, prec, rnd)
        p12 = mpf_mul(a1, a2, prec, rnd)
        d0 = mpf_mul(a0, a0, prec, rnd)
        d1 = mpf_add(p01, p01, prec, rnd)
        d2 = mpf_add(mpf_add(p02, mpf_mul(a1, a1, prec, rnd), prec, rnd), p02, prec, rnd)
        d3 = mpf_add(p12, p12, prec, rnd)
        d4 = mpf_mul(a2, a2, prec, rnd)
        # d₀ + d₁A + … + d₄A⁴ back to a triple
        k_p, k_i, k_v = self.k_p._mpf_, self.k_i._mpf_, self.k_v._mpf_
        d3 = mpf_sub(d3, mpf_mul(k_v, d4, prec, rnd), prec, rnd)
        d2 = mpf_sub(d2, mpf_mul(k_p, d4, prec, rnd), prec, rnd)
        d1 = mpf_sub(d1, mpf_mul(k_i, d4, prec, rnd), prec, rnd)
        d2 = mpf_sub(d2, mpf_mul(k_v, d3, prec, rnd), prec, rnd)
        d1 = mpf_sub(d1, mpf_mul(k_p, d3, prec, rnd), prec, rnd)
        d0 = mpf_sub(d0, mpf_mul(k_i, d3, prec, rnd), prec, rnd)
        return (d0, d1, d2)

    def _expm_ring(self, tau):
        """``(c₀, c₁, c₂)`` (mpf) with ``e^{Aτ} = c₀ I + c₁ A + c₂ A²`` (``τ < 0`` only for a
        time asked for before a piece's start)."""
        make = self.ctx.make_mpf
        return tuple(make(c) for c in self._expm_raw(tau))

    def _expm_raw(self, tau):
        """:meth:`_expm_ring` as raw values, remembered (:data:`_EXPM_CACHE`)."""
        ctx = self.ctx
        # keyed by the working precision too: a value formed at another precision has other bits
        key = None if getattr(tau, "_mpf_", None) is None else (self._flow_key, tau._mpf_, *ctx._prec_rounding)
        cache = _EXPM_CACHE
        if key in cache:
            return cache[key]
        if tau == 0:
            c = (fone, fzero, fzero)
        else:
            theta = self.norm * abs(tau)
            m = 0
            if theta > self._theta0:
                m = max(0, int(math.ceil(math.log2(float(theta / self._theta0)))))
                while ctx.ldexp(theta, -m) > self._theta0:
                    m += 1
            s = ctx.ldexp(tau, -m)._mpf_
            prec, rnd = ctx._prec_rounding
            neg_k_i, k_p, k_v, ints = self._raw_constants(prec, rnd)
            mul, add, sub, div = mpf_mul, mpf_add, mpf_sub, mpf_div
            t0, t1, t2 = fone, fzero, fzero
            c0, c1, c2 = t0, t1, t2
            for n in range(1, self._ring_terms):
                f = div(s, ints[n], prec, rnd)
                t0, t1, t2 = (
                    mul(mul(neg_k_i, t2, prec, rnd), f, prec, rnd),
                    mul(sub(t0, mul(k_p, t2, prec, rnd), prec, rnd), f, prec, rnd),
                    mul(sub(t1, mul(k_v, t2, prec, rnd), prec, rnd), f, prec, rnd),
                )
                c0 = add(c0, t0, prec, rnd)
                c1 = add(c1, t1, prec, rnd)
                c2 = add(c2, t2, prec, rnd)
            c = (c0, c1, c2)
            for _ in range(m):
                c = self._ring_square(c, prec, rnd)
        if key is not None:
            if len(cache) >= _EXPM_CACHE_SIZE:
                cache.clear()
            cache[key] = c
        return c

    def _apply(self, c, y):
        """``(c₀ I + c₁ A + c₂ A²) y`` for mpf ``c`` and ``y``."""
        return self._apply_raw(tuple(x._mpf_ for x in c), y)

    def _apply_raw(self, c, y):
        """:meth:`_apply` with ``c`` raw: ``c₀ y + c₁ Ay + c₂ A(Ay)`` as :meth:`_Ay` forms them."""
        prec, rnd = self.ctx._prec_rounding
        neg_k_i, k_p, k_v, _ = self._raw_constants(prec, rnd)

        def a_times(z):
            return (mpf_mul(neg_k_i, z[2], prec, rnd), mpf_sub(z[0], mpf_mul(k_p, z[2], prec, rnd), prec, rnd),
                    mpf_sub(z[1], mpf_mul(k_v, z[2], prec, rnd), prec, rnd))

        y = tuple(x._mpf_ for x in y)
        Ay = a_times(y)
        AAy = a_times(Ay)
        c0, c1, c2 = c
        make = self.ctx.make_mpf
        return [make(mpf_add(mpf_add(mpf_mul(c0, y[i], prec, rnd), mpf_mul(c1, Ay[i], prec, rnd), prec, rnd),
                             mpf_mul(c2, AAy[i], prec, rnd), prec, rnd)) for i in range(3)]

    def _flow(self, y, tau):
        """``e^{Aτ} y``."""
        return self._apply_raw(self._expm_raw(tau), y)

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
