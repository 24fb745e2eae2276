"""An independent high-precision reference solution of the inclusion
``x' ∈ A x - b SGN(v)`` (eq. xDot, unique by Lemma 1): what the package's
simulation methods are measured against (``symbolic-friction tradeoff`` and
``extremes``, and the simulation tests).

Nothing here comes from the package's simulation code (it never calls
``_simulation``): only the exact gains
are read from :class:`~symbolic_friction.Parameters`.  Everything is computed
with mpmath at ``dps`` (default 50) significant digits, by methods chosen to
be *different* from the package's:

* the flow of ``y' = A y`` is a Taylor series ``Σ (τA)ⁿ y / n!`` taken on a
  fixed fine grid of step ``h = 1/(4‖A‖∞)`` (no roots of the characteristic
  polynomial, no closed form), with the grid values obtained by repeated
  multiplication with the Taylor sum of ``e^{hA}``;
* a slip ends at the first grid interval where ``k·v`` changes sign, or where
  ``k·v'`` changes sign from − to + with ``k·v ≤ 0`` at the local minimum
  (a double crossing inside one step); the crossing is then bisected on the
  interval's Taylor polynomial down to ``10^{-(dps-8)}`` relative;
* the stick exit time is ``(sign(σ) f_s - φ)/σ``;
* the mode at ``v = 0`` is read off the appendix's table, written again here
  from the paper with exact comparisons; with static friction ``f_s > f_c``
  (eq. basic with a static level: stick while ``|φ| ≤ f_s``, kinetic
  friction ``f_c``) its rows at rest compare ``φ`` with ``±f_s``.

The reference is slow (mpmath), so tests use it on a few hundred sample times.

Limitation: ``φ`` is carried as an absolute number, so when a solution
*creeps* (stick–slip cycles in which ``σ`` shrinks geometrically, each stick
lasting ``-(φ ∓ f_c)/σ``) the event times lose accuracy once ``|φ ∓ f_c|``
falls below about ``10^{12-dps} f_c``.  Raise ``dps`` for such solutions.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Sequence

from ._infra.errors import SimulationError
from ._model.parameters import Parameters

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
    grid: list | None = None  # slip: offsets y at t0 + j h


class Reference:
    """High-precision solution from ``z0 = (e_i, s, v)`` on ``[0, t_end]``.

    Parameters
    ----------
    params : Parameters
    z0 : sequence of 3 floats (taken exactly) or Fractions
    t_end : float
    dps : int
        Decimal digits of the mpmath context (≥ 40).
    max_events : int
    """

    def __init__(self, params: Parameters, z0: Sequence, t_end: float, *, dps: int = 50, max_events: int = 200):
        if dps < 40:
            raise SimulationError(f"the reference needs at least 40 digits; got dps = {dps}")
        from mpmath.ctx_mp import MPContext  # imported lazily

        ctx = MPContext()
        ctx.dps = dps
        self.ctx = ctx
        q = lambda value: ctx.mpf(Fraction(value).numerator) / Fraction(value).denominator  # noqa: E731
        self.k_p, self.k_i, self.k_v, self.f_c = q(params.k_p), q(params.k_i), q(params.k_v), q(params.f_c)
        self.f_s = q(params.f_s)
        self.A = [
            [ctx.mpf(0), ctx.mpf(0), -self.k_i],
            [ctx.mpf(1), ctx.mpf(0), -self.k_p],
            [ctx.mpf(0), ctx.mpf(1), -self.k_v],
        ]
        norm = max(sum(abs(a) for a in row) for row in self.A)
        self.h = 1 / (4 * norm)
        self.tol = ctx.mpf(10) ** (-(dps - 8))
        # Taylor terms needed so that (1/4)^n / n! < 10^{-dps-5}
        n, term = 0, ctx.mpf(1)
        while term > ctx.mpf(10) ** (-(dps + 5)):
            n += 1
            term = term / 4 / n
        self.n_terms = n + 1
        self.E_h = self._taylor_matrix(self.h)
        e_i, s, v = (q(c) for c in z0)
        self.z0 = (e_i, s, v)
        self.x0 = [-self.k_i * s, -self.k_i * e_i - self.k_p * s, v]
        self.t_end = q(t_end)
        self.max_events = max_events
        self.pieces: list[_Piece] = []
        self.events: list[tuple] = []
        self.status = "t_end"
        self._run()

    # -- linear algebra on lists of mpf -------------------------------------
    def _mv(self, M, y):
        return [M[i][0] * y[0] + M[i][1] * y[1] + M[i][2] * y[2] for i in range(3)]

    def _taylor_matrix(self, tau):
        ctx = self.ctx
        E = [[ctx.mpf(int(i == j)) for j in range(3)] for i in range(3)]
        term = [row[:] for row in E]
        for n in range(1, self.n_terms):
            term = [[sum(term[i][k] * self.A[k][j] for k in range(3)) * tau / n for j in range(3)] for i in range(3)]
            E = [[E[i][j] + term[i][j] for j in range(3)] for i in range(3)]
        return E

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

    # -- the event loop -------------------------------------------------------
    def _slip(self, t0, x0, d):
        """Follow slip ``d`` from ``x0`` at ``t0``; return the piece and the end state."""
        star = [0, d * self.f_c, 0]
        y = [x0[0], x0[1] - star[1], x0[2]]
        grid = [y]
        horizon = self.t_end - t0
        j = 0
        while True:
            a = j * self.h
            if a >= horizon:
                return _Piece(t0, self.t_end, d, x0, grid), None
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
                t1 = t0 + a + hit
                return _Piece(t0, t1, d, x0, grid), [y_end[0], y_end[1] + star[1], self.ctx.mpf(0)]
            y = y_next
            grid.append(y)
            j += 1

    def _run(self):
        ctx = self.ctx
        x = list(self.x0)
        t = ctx.mpf(0)
        mode = reference_table_mode(x[0], x[1], x[2], self.f_c, self.f_s)
        while True:
            if mode == 0:
                sigma, phi = x[0], x[1]
                if sigma == 0:
                    self.pieces.append(_Piece(t, self.t_end, 0, x))
                    self.status = "equilibrium"
                    return
                d = 1 if sigma > 0 else -1
                t1 = t + (d * self.f_s - phi) / sigma
                if t1 >= self.t_end:
                    self.pieces.append(_Piece(t, self.t_end, 0, x))
                    return
                self.pieces.append(_Piece(t, t1, 0, x))
                x = [sigma, d * self.f_s, ctx.mpf(0)]
                t = t1
                new = reference_table_mode(x[0], x[1], x[2], self.f_c, self.f_s)
            else:
                piece, x_end = self._slip(t, x, mode)
                self.pieces.append(piece)
                if x_end is None:
                    return
                t, x = piece.t1, x_end
                new = reference_table_mode(x[0], x[1], x[2], self.f_c, self.f_s)
            if new != mode:
                self.events.append((t, mode, new))
                mode = new
            if len(self.events) >= self.max_events:
                self.status = "max_events"
                return

    # -- output ---------------------------------------------------------------
    def x_at(self, t):
        """``(σ, φ, v)`` (mpf) and the mode at time ``t`` (float or mpf)."""
        t = self.ctx.mpf(t)
        piece = self.pieces[0]
        for p in self.pieces:
            if p.t0 <= t:
                piece = p
        tau = t - piece.t0
        if piece.mode == 0:
            return [piece.x0[0], piece.x0[1] + piece.x0[0] * tau, self.ctx.mpf(0)], 0
        j = min(int(tau / self.h), len(piece.grid) - 1)
        y = self._poly_state(self._coefficients(piece.grid[j]), tau - j * self.h)
        return [y[0], y[1] + piece.mode * self.f_c, y[2]], piece.mode

    def z_at(self, t):
        """``(e_i, s, v)`` as floats and the mode at time ``t``."""
        (sigma, phi, v), mode = self.x_at(t)
        s = -sigma / self.k_i
        e_i = (-phi - self.k_p * s) / self.k_i
        return (float(e_i), float(s), float(v)), mode

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
