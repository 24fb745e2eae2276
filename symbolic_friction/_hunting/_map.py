"""The hunting map ``P`` of the stiction model and its cycles (search, in floats).

Beyond the paper (its conclusion names static friction above Coulomb as
future work): with ``f_s > f_c`` the mass at rest sticks while
``|φ| ≤ f_s``, ``φ = -k_i e_i - k_p s`` (eq. CoC), and slips with kinetic
friction ``f_c``.  A stick ends at ``φ = ±f_s`` with ``σ = -k_i s`` of the
same sign (``φ' = σ`` in stick), so the state at a stick exit is the one
number ``σ`` (equivalently ``s = -σ/k_i``).  The *hunting map*

    ``P(σ)`` = ``σ`` at the next stick exit,

is computed with the one event-driven model: the slip from
``y0 = (σ, ±(f_s - f_c), 0)`` (offset from the slip equilibrium
``(0, ±f_c, 0)``) ends at the first zero of ``v`` (the kernel's certified
search, :func:`.._simulation.slip.first_zero`), the kernel's end-of-slip
rule (:func:`.._simulation.slip.mode_after_slip`, the mode table with
``f_s``) decides stick or reversal, and a stick keeps ``σ`` and ends at
``sign(σ) f_s``.

The model is odd (``x ↦ -x`` maps solutions to solutions), so ``P(-σ) =
-P(σ)``; a *symmetric* hunting cycle is a fixed point of ``σ ↦ -P(σ)``, a
general one a fixed point of ``P∘P``.  When the slip from a stick exit ends
in a stick (no reversal) ``P`` is positively homogeneous in the excess:
``P(σ) = (f_s - f_c) h(σ/(f_s - f_c))`` with ``h`` depending on the gains
only, so the cycle's amplitude grows linearly from 0 with ``f_s - f_c``.

Fixed points are *found* here (a scan for sign changes and Brent's method on
the closed form); they are *proved* by :mod:`.._certify.hunting_proof`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._model.coordinates import system_matrix, x_to_z
from .._infra.errors import ParameterError
from .._model.parameters import Parameters

__all__ = ["HuntingMap", "MapStep", "HuntingCycle", "find_cycles", "cycle_orbit", "RealRootEscape", "real_root_escape"]

# A slip still going after this many time constants of the slowest root has decayed by e^-240
# (1e-104 relative): it is reported as not ending (the solution converges to a point of 𝒜).
_TIME_CONSTANTS = 240.0
# A slip whose offset has decayed to this fraction of its start is on its equilibrium to working precision.
_DECAYED = 64 * 2.220446049250313e-16
_MAX_SLIPS = 16


@dataclass(frozen=True)
class MapStep:
    """One application of ``P`` from a stick exit with ``σ`` (floats).

    Attributes
    ----------
    sigma : float
        ``σ`` at the stick exit (``φ = sign(σ) f_s``, ``v = 0``).
    slips : tuple of (direction, duration, σ_end, φ_end)
        The slips until the mass sticks again (more than one: reversals).
    stick : float
        Duration of the stick that follows (``nan`` if none).
    next_sigma : float
        ``P(σ)``; ``nan`` if there is no next stick exit.
    reason : str
        ``"exit"``, ``"slips forever"`` (a slip that never ends: the solution
        converges to a point of 𝒜 during it), ``"equilibrium"`` (sticks with
        ``σ = 0``) or ``"too many reversals"``.
    """

    sigma: float
    slips: tuple[tuple[int, float, float, float], ...]
    stick: float
    next_sigma: float
    reason: str

    @property
    def slip_time(self) -> float:
        return float(sum(s[1] for s in self.slips))


class HuntingMap:
    """``P`` for one gain set with ``f_s > f_c`` (see the module docstring).

    Parameters
    ----------
    params : Parameters
        With ``f_s > f_c``.

    Raises
    ------
    ParameterError
        If ``f_s = f_c`` (the paper's model: no stick exit has a successor
        that is not in the paper's GAS set, Proposition 1).
    """

    def __init__(self, params: Parameters) -> None:
        if not isinstance(params, Parameters):
            raise ParameterError(f"params must be a Parameters instance with f_s > f_c; got {type(params).__name__}")
        if not params.stiction:
            raise ParameterError(
                f"the hunting map needs static friction above Coulomb; got f_s = f_c = {params.f_c} "
                "(the paper's model: 𝒜 is globally asymptotically stable, Proposition 1, no hunting)"
            )
        from .._simulation.slip import slip_model

        self.params = params
        try:
            self.model = slip_model(params)
        except (OverflowError, ZeroDivisionError) as exc:  # gains beyond float64's range
            raise ParameterError(f"params: the hunting map of {params} leaves the range of float64 ({exc})") from None
        self.f_c = float(params.f_c)
        self.f_s = float(params.f_s)
        self.excess = float(params.f_s - params.f_c)
        self.horizon = _TIME_CONSTANTS / self.model.expm.slowest_rate

    def step(self, sigma: float) -> MapStep:
        """Follow the solution from the stick exit with ``σ`` to the next one (or to its end)."""
        from .._simulation.slip import EPS, SNAP_ULPS, UNDERFLOW, first_zero, mode_after_slip

        sigma = float(sigma)
        if sigma == 0.0:
            return MapStep(sigma, (), math.nan, math.nan, "equilibrium")
        d = 1 if sigma > 0 else -1
        p = d * self.excess  # φ - d f_c at φ = d f_s
        s, slips = sigma, []
        for _ in range(_MAX_SLIPS):
            tau, (ys, yp, yv) = first_zero(self.model, (s, p, 0.0), d, self.horizon)
            # decayed onto x*_d ∈ 𝒜: below underflow, as in the kernel, or below the rounding of the
            # slip's own start (a zero there is the rounding's, e.g. on a real-root escape bound)
            if tau is None or max(abs(ys), abs(yp), abs(yv)) <= max(UNDERFLOW, _DECAYED * max(abs(s), abs(p))):
                slips.append((d, math.inf, 0.0, d * self.f_c))
                return MapStep(sigma, tuple(slips), math.nan, math.nan, "slips forever")
            tol = SNAP_ULPS * EPS * max(abs(s), abs(p))
            base, offset, mode = mode_after_slip(ys, yp, d, self.f_c, tol, self.excess)
            phi = base * self.f_c + offset
            slips.append((d, tau, ys, phi))
            if mode == 0:
                if ys == 0.0:
                    return MapStep(sigma, tuple(slips), math.inf, math.nan, "equilibrium")
                e = 1 if ys > 0 else -1
                return MapStep(sigma, tuple(slips), (e * self.f_s - phi) / ys, ys, "exit")
            # a reversal (|φ| > f_s): the slip in the other direction starts from rest
            s, p, d = ys, phi - mode * self.f_c, mode
        return MapStep(sigma, tuple(slips), math.nan, math.nan, "too many reversals")

    def __call__(self, sigma: float) -> float:
        """``P(σ)`` (``nan`` if there is no next stick exit)."""
        return self.step(sigma).next_sigma

    def flow_matrix(self, tau: float) -> np.ndarray:
        """``e^{Aτ}`` (closed form of :class:`.._simulation.affine.MatrixExponential`)."""
        return np.asarray(self.model.expm(float(tau)), dtype=float)

    def derivative(self, sigma: float, st: MapStep | None = None) -> float:
        """``P'(σ)`` by implicit differentiation of ``v(τ; σ) = 0`` (one slip, no reversal).

        ``st``: :meth:`step` at ``σ`` when the caller has it already.
        """
        st = self.step(sigma) if st is None else st
        if st.reason != "exit" or len(st.slips) != 1:
            return math.nan
        tau = st.slips[0][1]
        d = 1 if sigma > 0 else -1
        E = self.flow_matrix(tau)
        A = system_matrix(self.params)
        y = E @ np.array([sigma, d * self.excess, 0.0])
        dy_dsigma = E[:, 0]
        dy_dtau = A @ y
        dtau = -dy_dsigma[2] / dy_dtau[2]
        return float(dy_dsigma[0] + dy_dtau[0] * dtau)


@dataclass(frozen=True)
class HuntingCycle:
    """A hunting cycle found by the map (floats; :mod:`._proof` proves it).

    Attributes
    ----------
    params : Parameters
    sigma : float
        ``σ* > 0`` at the stick exit ``φ = f_s`` (the cycle passes through
        ``±σ*``); ``s = ∓σ*/k_i`` there.
    symmetric : bool
        A fixed point of ``σ ↦ -P(σ)`` (else of ``P∘P`` only).
    slip_time, stick_time : float
        Duration of each slip and of each stick (half a period each).
    period : float
        ``2 (slip_time + stick_time)`` for a symmetric cycle.
    phi_end : float
        ``φ`` where the slip from ``φ = f_s`` ends (in ``[-f_s, f_c]``).
    multiplier : float
        ``d(-P)/dσ`` at ``σ*``: the cycle attracts nearby stick exits if
        ``|multiplier| < 1``; ``multiplier²`` is the derivative of ``P∘P``.
    amplitude_s, amplitude_e_i : float
        ``max |s|`` and ``max |e_i|`` over a period.
    amplitude_distance, amplitude_distance_x : float
        ``max |z|_𝒜`` (the distance of the proof of Corollary 1) and
        ``max |x|_𝒜`` over a period, to the paper's 𝒜 (eq. Aph, with ``f_c``).
        Amplitudes are maxima over 4001 samples of one exactly simulated
        period plus its events (``max |s|`` is exact: it is reached in the sticks).
    slips : int
        Slips per half period (1: no reversal).
    """

    params: Parameters
    sigma: float
    symmetric: bool
    slip_time: float
    stick_time: float
    period: float
    phi_end: float
    multiplier: float
    amplitude_s: float = math.nan
    amplitude_e_i: float = math.nan
    amplitude_distance: float = math.nan
    amplitude_distance_x: float = math.nan
    slips: int = 1

    @property
    def stable(self) -> bool:
        return abs(self.multiplier) < 1.0

    @property
    def exit_state(self) -> tuple[float, float, float]:
        """``z = (e_i, s, v)`` at the stick exit ``x = (σ*, f_s, 0)`` (eq. CoC inverted)."""
        z = x_to_z(self.params, np.array([self.sigma, float(self.params.f_s), 0.0]))
        return (float(z[0]), float(z[1]), float(z[2]))


MAX_POINTS = 100_000
"""The most grid points :func:`find_cycles` scans (each costs a step of the map, a few milliseconds)."""


def find_cycles(params: Parameters, *, points: int = 240, span: float = 1e4, general: bool = True) -> list[HuntingCycle]:
    """Hunting cycles of ``params`` (``f_s > f_c``): fixed points of ``σ ↦ -P(σ)`` (and of ``P∘P``).

    ``σ > 0`` is scanned on a geometric grid of ``points`` values over
    ``[(f_s - f_c)/span, (f_s - f_c)·span]`` (``P`` scales with the excess),
    every sign change of ``P(σ) + σ`` is refined with Brent's method, and
    likewise ``P(P(σ)) - σ`` for cycles that are not symmetric.  A search:
    nothing here is a proof (:func:`._proof.prove_cycle` is).

    Returns
    -------
    list of HuntingCycle
        Sorted by ``σ*``; empty if there is none in the scanned range.

    Examples
    --------
    >>> from symbolic_friction import Parameters, find_cycles
    >>> p = Parameters(k_p=3, k_i=4, k_v="6.4", f_s="1.2")  # static friction 20 % above Coulomb
    >>> [round(c.sigma, 6) for c in find_cycles(p, points=40, general=False)]
    [0.105045]
    """
    from scipy.optimize import brentq

    from .._infra.guards import check_count, check_real

    P = HuntingMap(params)
    points = check_count(points, name="points", low=2, high=MAX_POINTS, why="each point is a step of the map, ms each")
    span = check_real(span, name="span", low=1, high=1e300, why="the grid spans [excess/span, excess·span]")
    if not isinstance(general, (bool, np.bool_)):
        raise ParameterError(f"general must be True or False; got {type(general).__name__}")
    grid = P.excess * np.geomspace(1.0 / span, span, points)
    vals = np.array([P(s) for s in grid])
    roots: list[tuple[float, bool]] = []

    def refine(g, a, b, symmetric):
        r = brentq(g, a, b, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=200)
        if not any(abs(r - q) <= 1e-9 * r for q, _ in roots):
            roots.append((float(r), symmetric))

    g_sym = vals + grid
    for j in range(points - 1):
        a, b = g_sym[j], g_sym[j + 1]
        if np.isfinite(a) and np.isfinite(b) and a * b < 0:
            refine(lambda s: P(s) + s, grid[j], grid[j + 1], True)
    if general:
        twice = np.array([P(v) if np.isfinite(v) else math.nan for v in vals])
        g2 = np.abs(twice) - grid  # P∘P(σ) = ±σ; the sign of P∘P(σ) is the sign of σ for a cycle
        for j in range(points - 1):
            a, b = g2[j], g2[j + 1]
            if np.isfinite(a) and np.isfinite(b) and a * b < 0 and twice[j] > 0 and twice[j + 1] > 0:
                refine(lambda s: P(P(s)) - s, grid[j], grid[j + 1], False)
    cycles = [_describe(P, r, sym) for r, sym in sorted(roots)]
    return [c for c in cycles if c is not None]


def _describe(P: HuntingMap, sigma: float, symmetric: bool) -> HuntingCycle | None:
    st = P.step(sigma)
    if st.reason != "exit":
        return None
    if symmetric:
        period = 2.0 * (st.slip_time + st.stick)
        multiplier = -P.derivative(sigma, st)
    else:
        st2 = P.step(st.next_sigma)
        period = st.slip_time + st.stick + st2.slip_time + st2.stick
        multiplier = P.derivative(sigma, st) * P.derivative(st.next_sigma, st2)
    cycle = HuntingCycle(
        params=P.params,
        sigma=sigma,
        symmetric=symmetric,
        slip_time=st.slip_time,
        stick_time=st.stick,
        period=period,
        phi_end=st.slips[-1][3],
        multiplier=multiplier,
        slips=len(st.slips),
    )
    orbit = cycle_orbit(cycle, samples=4001)
    return cycle if orbit is None else _with_amplitudes(cycle, orbit)


def _with_amplitudes(cycle: HuntingCycle, orbit) -> HuntingCycle:
    from .._model.attractor import distance_z

    z = orbit.z
    values = dict(cycle.__dict__)
    values.update(
        amplitude_s=float(np.abs(z[:, 1]).max()),
        amplitude_e_i=float(np.abs(z[:, 0]).max()),
        amplitude_distance=float(np.asarray(distance_z(cycle.params, z)).max()),
        amplitude_distance_x=float(np.asarray(orbit.distance).max()),
    )
    return HuntingCycle(**values)


def cycle_orbit(cycle: HuntingCycle, *, samples: int = 2001, periods: float = 1.0):
    """One period of the cycle, simulated exactly from its stick exit (a :class:`Solution`)."""
    from .._simulation import simulate

    if not math.isfinite(cycle.period) or cycle.period <= 0:
        return None
    t_end = cycle.period * periods
    # the distance |z|_𝒜 is largest where |s| is (the sticks) or within a slip; the samples and events cover both
    sol = simulate(cycle.params, cycle.exit_state, t_end, grid_points=samples, max_events=10_000)
    return sol


@dataclass(frozen=True)
class RealRootEscape:
    """Three distinct real roots: a slip from a stick exit with ``|σ| ≥ |λ₁|(f_s - f_c)`` never ends.

    Proof.  Let ``λ₃ < λ₂ < λ₁ < 0`` be the roots of ``χ(s) = s³ + k_v s² + k_p s + k_i``
    (the discriminant is positive, decided exactly).  ``ℓ_j = (1, λ_j, λ_j²)`` is a left
    eigenvector of ``A`` (``ℓ_jᵀ A = λ_j ℓ_jᵀ``), so ``L_j(y) = σ + λ_j p + λ_j² v`` obeys
    ``L_j(y(t)) = e^{λ_j t} L_j(y0)`` along the slip, and
    ``v(t) = Σ_j L_j(y0) e^{λ_j t} / χ'(λ_j)`` (the right eigenvector ``(-k_i/λ, λ + k_v, 1)``
    has ``ℓ_jᵀ r_j = χ'(λ_j)``).  A sum of three real exponentials has at most two real zeros
    counted with multiplicity (Pólya–Szegő, Part V, Problem 75).  A slip from the stick exit
    ``σ > 0``, ``φ = f_s`` starts from ``y0 = (σ, Δ, 0)``, ``Δ = f_s - f_c``: ``v(0) = 0`` is one
    zero and ``v'(0) = Δ > 0``.  As ``t → ∞`` the sign of ``v`` is that of
    ``L₁(y0)/χ'(λ₁) = (σ + λ₁Δ)/χ'(λ₁)`` with ``χ'(λ₁) > 0``.  If ``σ > |λ₁|Δ`` that is positive:
    ``v`` is positive near ``0⁺`` and near ``∞``, so it has an even number of zeros in
    ``(0, ∞)``, at most one: none.  If ``σ = |λ₁|Δ``, ``v`` is a sum of two exponentials with
    its one zero at 0: none either.  So the slip never ends and the solution converges to
    ``(0, f_c, 0) ∈ 𝒜`` with ``v > 0``: no further stick.  (Below the bound ``v`` changes sign
    once, and at the end ``L₁ = σ_end + λ₁ p_end < 0`` with ``p_end ≤ 0`` gives
    ``σ_end < 0``: the slip always overshoots.)  The case ``σ < 0`` is the mirror image.

    Attributes
    ----------
    root_bracket : tuple of Fraction
        ``a ≤ λ₁ ≤ b < 0`` (exact; ``χ(a) ≤ 0 ≤ χ(b)``).
    bound : Fraction
        ``|a| (f_s - f_c) ≥ |λ₁| (f_s - f_c)``: stick exits with ``|σ|`` at or above it slip forever.
    """

    root_bracket: tuple
    bound: object


def real_root_escape(params: Parameters) -> RealRootEscape | None:
    """:class:`RealRootEscape` if ``χ`` has three distinct real roots (decided exactly), else ``None``."""
    from fractions import Fraction

    a, b, c = params.k_v, params.k_p, params.k_i
    disc = 18 * a * b * c - 4 * a**3 * c + a**2 * b**2 - 4 * b**3 - 27 * c**2
    if not disc > 0:
        return None

    def chi(x: Fraction) -> Fraction:
        return ((x + a) * x + b) * x + c

    lam = max(np.roots([1.0, float(a), float(b), float(c)]).real)
    r = Fraction(float(lam)).limit_denominator(10**9)  # an exact rational root when there is a simple one
    if chi(r) == 0:
        lo = hi = r
    else:
        eps = Fraction(abs(float(lam)) * 1e-12 + 1e-300)
        lo, hi = r - eps, r + eps
        while not (chi(lo) < 0 < chi(hi)):
            eps *= 4
            lo, hi = r - eps, r + eps
    if not hi < 0:
        return None
    return RealRootEscape(root_bracket=(lo, hi), bound=-lo * (params.f_s - params.f_c))
