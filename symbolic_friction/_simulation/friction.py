"""Perturbed friction laws for Corollary 1 (eq. perturbed) and the Stribeck
effect (Fig. 4).

The paper's unperturbed friction is ``f_c SGN(v)`` (eq. frictionforceSetValued).
Corollary 1 perturbs it into the *inflated* law

.. math::

    \\mathrm{SGN}_\\rho(v) =
    \\begin{cases}
      [\\operatorname{sign}(v) - \\rho,\\ \\operatorname{sign}(v) + \\rho], & |v| > \\rho,\\\\
      [-1 - \\rho,\\ 1 + \\rho], & |v| \\le \\rho,
    \\end{cases}
    \\qquad \\mathrm{SGN}_\\rho(v) = \\mathrm{SGN}(v + \\rho\\mathbb B) + \\rho\\mathbb B,

and states ISS of 𝒜 from the input ρ.  A Stribeck law whose graph lies inside
``f_c SGN_ρ`` (Fig. 4) is one of the dynamics covered.

All laws here are simulated by the ``moreau`` method (implicit Euler,
:mod:`.moreau`): pass one as ``simulate(..., method="moreau", friction=law)``.
In one implicit Euler step of size ``h`` the whole inclusion reduces to a
*scalar* inclusion in the next velocity ``w = v_{n+1}`` (see :class:`Step`):

.. math::

    D\\,w + h\\,f \\ni r,\\qquad f \\in F(w),\\qquad
    D = 1 + h k_v + h^2 k_p + h^3 k_i,\\quad r = v_n + h\\phi_n + h^2\\sigma_n,

where ``F`` is the friction graph (force per unit mass).  Each law solves
this scalar inclusion in :meth:`FrictionLaw.solve_step`.
"""

from __future__ import annotations

import abc
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, ClassVar, NamedTuple

import numpy as np

from .._infra.errors import ParameterError, SimulationError
from .._infra.rational import format_rational, to_rational

__all__ = ["Step", "FrictionLaw", "Coulomb", "InflatedCoulomb", "Stribeck", "WORST_CASE"]

WORST_CASE = "worst-case"

# sqrt(2/e): the largest slope of u -> 2u exp(-u^2), reached at u = 1/sqrt(2).
_STRIBECK_SLOPE = math.sqrt(2.0 / math.e)


class Step(NamedTuple):
    """Data of one implicit Euler step, from the state at ``t`` to ``t + h``.

    (A named tuple rather than a dataclass: one is built per step, so it must
    be cheap.)

    With ``x_n = (sigma, phi, v)`` the implicit step
    ``x_{n+1} = x_n + h (A x_{n+1} - b lambda)`` gives
    ``sigma_{n+1} = sigma - h k_i w`` and
    ``phi_{n+1} = phi + h sigma - h (h k_i + k_p) w`` for ``w = v_{n+1}``,
    and ``D w + h f_c lambda = r`` (module docstring).

    Attributes
    ----------
    t, h : float
        Step start and size.
    sigma, phi, v : float
        State at ``t`` in ``x`` coordinates.
    k_p, k_i, k_v, f_c : float
        Gains and Coulomb level.
    """

    t: float
    h: float
    sigma: float
    phi: float
    v: float
    k_p: float
    k_i: float
    k_v: float
    f_c: float

    @property
    def D(self) -> float:
        """``1 + h k_v + h^2 k_p + h^3 k_i`` (> 1)."""
        h = self.h
        return 1.0 + h * (self.k_v + h * (self.k_p + h * self.k_i))

    @property
    def r(self) -> float:
        """``v + h phi + h^2 sigma``: the next velocity if friction were absent, times ``D``."""
        return self.v + self.h * (self.phi + self.h * self.sigma)

    def next_x(self, w: float) -> tuple[float, float, float]:
        """``x_{n+1} = (sigma, phi, v)`` after the step if ``v_{n+1} = w``."""
        h = self.h
        return (self.sigma - h * self.k_i * w, self.phi + h * self.sigma - h * (h * self.k_i + self.k_p) * w, w)


class FrictionLaw(abc.ABC):
    """Base class of a friction law ``F`` replacing ``f_c SGN(v)`` in eq. (xDot).

    Contract for implementers
    -------------------------
    * :meth:`graph` returns, for an array of velocities, the lower and upper
      ends of the friction set ``F(v)`` (force per unit mass; the two ends
      coincide where ``F`` is single-valued).  It describes the law (plots,
      containment in ``f_c SGN_ρ``) and is not used by the simulator.
    * :meth:`solve_step` solves the scalar inclusion ``D w + h f ∋ r`` of one
      implicit Euler step (:class:`Step`), returning ``(w, f)`` with
      ``f ∈ F(w)`` (up to rounding) and ``D w + h f = r``.  When ``F`` is
      monotone the solution is unique; otherwise the law documents which
      solution it picks, or :meth:`check_step` rejects step sizes for which
      the solution is not unique.
    * :meth:`check_step` raises :class:`SimulationError` naming ``h`` if the
      step size is unusable (default: every ``h > 0`` is fine).
    * :attr:`time_invariant` is false if the law depends on ``t`` (then a
      state left unchanged by one step is not taken as an equilibrium).
    * Laws are immutable and validated at construction; their numbers are
      kept exact (:class:`~fractions.Fraction`), floats are used only inside
      the numerical methods.
    """

    name: ClassVar[str]

    @abc.abstractmethod
    def graph(self, v: Any, f_c: float) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper ends of ``F(v)`` for an array ``v``."""

    @abc.abstractmethod
    def solve_step(self, step: Step) -> tuple[float, float]:
        """Solve ``D w + h f ∋ r``, ``f ∈ F(w)``; return ``(w, f)``."""

    def check_step(self, h: float, *, k_p: float, k_i: float, k_v: float, f_c: float) -> None:
        """Raise :class:`SimulationError` if ``h`` is not usable with this law."""

    @property
    def time_invariant(self) -> bool:
        """Whether the law is the same at all times (default true)."""
        return True

    def describe(self) -> str:
        """One-line description with the exact numbers."""
        return self.name


def _coulomb_solve(r: float, D: float, a: float) -> tuple[float, float]:
    """``D w + a SGN(w) ∋ r`` (``a = h f_c``): the resolvent of a maximal monotone law.

    Returns ``(w, lam)`` with ``lam ∈ SGN(w)``.
    """
    if r > a:
        return (r - a) / D, 1.0
    if r < -a:
        return (r + a) / D, -1.0
    return 0.0, r / a


@dataclass(frozen=True)
class Coulomb(FrictionLaw):
    """The paper's law ``f_c SGN(v)`` (eq. frictionforceSetValued).

    ``simulate(..., method="moreau")`` without ``friction`` uses the same
    closed-form step on a faster path; this class exists so that Coulomb
    friction can be passed, plotted and compared like any other law.
    """

    name: ClassVar[str] = "coulomb"

    def graph(self, v: Any, f_c: float) -> tuple[np.ndarray, np.ndarray]:
        v = np.asarray(v, dtype=float)
        s = np.sign(v) * f_c
        return np.where(v == 0, -f_c, s), np.where(v == 0, f_c, s)

    def solve_step(self, step: Step) -> tuple[float, float]:
        w, lam = _coulomb_solve(step.r, step.D, step.h * step.f_c)
        return w, step.f_c * lam


def _check_nonnegative(value: object, name: str) -> Fraction:
    q = to_rational(value, name=name)
    if q < 0:
        raise ParameterError(f"{name} must be ≥ 0; got {name} = {format_rational(q)}")
    return q


def _check_positive(value: object, name: str) -> Fraction:
    q = to_rational(value, name=name)
    if not q > 0:
        raise ParameterError(f"{name} must be > 0; got {name} = {format_rational(q)}")
    return q


Selection = Callable[[float, tuple[float, float, float]], tuple[float, float]]


@dataclass(frozen=True)
class InflatedCoulomb(FrictionLaw):
    """The inflated law ``f_c SGN_ρ(v)`` of eq. (perturbed), with a selection.

    ``SGN_ρ`` is set-valued on all of ℝ, so solutions of eq. (perturbed) are
    not unique; a simulation follows one *selection*:

    ``selection="worst-case"`` (default)
        A greedy adversary: in each implicit Euler step, among **all** next
        states the step allows (every ``w`` with ``(r - D w)/(h f_c) ∈
        SGN_ρ(w)``), take the one farthest from 𝒜.  The squared distance
        ``|x_{n+1}|²_𝒜`` is convex in ``w`` (σ, φ are affine in ``w``), so the
        maximum is at an end of one of the (at most three) feasible
        intervals, found in closed form.  As ``h → 0`` this is the pointwise
        selection maximising ``d/dt |x|²_𝒜 = … - 2 f_c v λ``: friction
        ``(1 - ρ) f_c`` against the motion for ``|v| > ρ``, and a push
        ``(1 + ρ) f_c`` *along* the motion for ``|v| ≤ ρ``, which makes
        the mass creep at ``|v| = ρ`` instead of sticking (ultimate bound
        of order ``sqrt(ρ)``).  Ties go to the larger ``|w|``, then to
        ``w > 0``.
    ``selection=(d, e)`` with ``|d|, |e| ≤ ρ``, or a callable ``(t, x) -> (d, e)``
        Uses ``SGN_ρ(v) = SGN(v + ρ𝔹) + ρ𝔹`` (paper, after eq. perturbed):
        the friction is ``f_c (SGN(v + d) + e)``, i.e. Coulomb friction
        seen through a velocity offset ``d`` plus a force error ``f_c e``.
        ``d``, ``e`` are evaluated at the start of each step (a zero-order
        hold, as for any input signal) and the Coulomb part is solved
        implicitly, exactly; ``d = e = 0`` is the paper's law.  A callable
        returning ``|d|`` or ``|e|`` above ρ raises :class:`SimulationError`.

    Parameters
    ----------
    rho : number
        Inflation ``ρ ≥ 0`` (the ISS input of Corollary 1); kept exact.
    selection : "worst-case", (d, e) or callable, keyword-only

    Raises
    ------
    ParameterError
        If ``rho < 0``, a constant ``|d|`` or ``|e|`` exceeds ``rho``, or the
        selection is of the wrong kind.

    Examples
    --------
    >>> from symbolic_friction import Parameters
    >>> from symbolic_friction._simulation import simulate
    >>> sol = simulate(Parameters.table_i("a"), (0, 0, 0), 30.0, method="moreau", h=1e-3,
    ...                friction=InflatedCoulomb("0.01"))
    >>> 0.4 < float(sol.distance.max()) < 0.5   # pushed out of 𝒜, but boundedly
    True
    """

    rho: Fraction
    selection: Any = field(default=WORST_CASE, kw_only=True)
    _rho: float = field(init=False, repr=False, compare=False)  # float copy for the step

    name: ClassVar[str] = "inflated"

    def __post_init__(self) -> None:
        object.__setattr__(self, "rho", _check_nonnegative(self.rho, "rho"))
        object.__setattr__(self, "_rho", float(self.rho))
        sel = self.selection
        if isinstance(sel, str):
            if sel != WORST_CASE:
                raise ParameterError(
                    f"selection must be {WORST_CASE!r}, a pair (d, e) or a callable (t, x) -> (d, e); got {sel!r}"
                )
        elif isinstance(sel, (tuple, list)):
            if len(sel) != 2:
                raise ParameterError(f"a constant selection is a pair (d, e); got {len(sel)} values {tuple(sel)!r}")
            d, e = (to_rational(sel[0], name="selection d"), to_rational(sel[1], name="selection e"))
            for label, q in (("d", d), ("e", e)):
                if abs(q) > self.rho:
                    raise ParameterError(
                        f"selection {label} must satisfy |{label}| ≤ rho = {format_rational(self.rho)}; "
                        f"got {label} = {format_rational(q)}"
                    )
            object.__setattr__(self, "selection", (d, e))
        elif not callable(sel):
            raise ParameterError(
                f"selection must be {WORST_CASE!r}, a pair (d, e) or a callable (t, x) -> (d, e); "
                f"got {type(sel).__name__}"
            )

    @property
    def time_invariant(self) -> bool:
        return not callable(self.selection)

    def graph(self, v: Any, f_c: float) -> tuple[np.ndarray, np.ndarray]:
        v = np.asarray(v, dtype=float)
        rho = float(self.rho)
        inside = np.abs(v) <= rho
        s = np.sign(v)
        return (
            f_c * np.where(inside, -1.0 - rho, s - rho),
            f_c * np.where(inside, 1.0 + rho, s + rho),
        )

    def solve_step(self, step: Step) -> tuple[float, float]:
        if isinstance(self.selection, str):
            return self._worst_case(step)
        if isinstance(self.selection, tuple):
            d, e = float(self.selection[0]), float(self.selection[1])
        else:
            d, e = self._call_selection(step)
        a = step.h * step.f_c
        D = step.D
        # D (u - d) + a (SGN(u) + e) ∋ r with u = w + d: a Coulomb resolvent in u.
        u, lam = _coulomb_solve(step.r - a * e + D * d, D, a)
        return u - d, step.f_c * (lam + e)

    def _call_selection(self, step: Step) -> tuple[float, float]:
        out = self.selection(step.t, (step.sigma, step.phi, step.v))
        try:
            d, e = (float(out[0]), float(out[1]))
            if len(out) != 2:
                raise TypeError
        except (TypeError, ValueError, IndexError):
            raise SimulationError(f"the selection must return a pair (d, e) of numbers; got {out!r}") from None
        rho = self._rho
        slack = 1e-12 * max(1.0, rho)
        if not (abs(d) <= rho + slack and abs(e) <= rho + slack):
            raise SimulationError(
                f"the selection returned (d, e) = ({d!r}, {e!r}) at t = {step.t:g}; both must be within rho = {rho:g}"
            )
        return d, e

    def _worst_case(self, step: Step) -> tuple[float, float]:
        rho = self._rho
        a = step.h * step.f_c
        D, r = step.D, step.r
        # Feasible w: (r - D w)/a ∈ SGN_ρ(w).  Three closed intervals (the graph is closed).
        pieces = (
            ((r - a * (1 + rho)) / D, (r - a * (1 - rho)) / D, rho, math.inf),  # w ≥ ρ, λ ∈ [1-ρ, 1+ρ]
            ((r - a * (1 + rho)) / D, (r + a * (1 + rho)) / D, -rho, rho),  # |w| ≤ ρ
            ((r + a * (1 - rho)) / D, (r + a * (1 + rho)) / D, -math.inf, -rho),  # w ≤ -ρ
        )
        best: tuple[float, float, float] | None = None  # (distance², |w|, w)
        for lo, hi, lo_dom, hi_dom in pieces:
            lo, hi = max(lo, lo_dom), min(hi, hi_dom)
            if lo > hi:
                continue
            for w in (lo, hi):
                s_, p_, _ = step.next_x(w)
                dzp = p_ - step.f_c if p_ > step.f_c else p_ + step.f_c if p_ < -step.f_c else 0.0
                key = (s_ * s_ + dzp * dzp + w * w, abs(w), w)
                if best is None or key > best:
                    best = key
        if best is None:  # cannot happen: SGN ⊂ SGN_ρ has a solution; keep Coulomb as a guard
            w, lam = _coulomb_solve(r, D, a)
            return w, step.f_c * lam
        w = best[2]
        return w, (r - D * w) / step.h

    def describe(self) -> str:
        sel = self.selection
        if isinstance(sel, str):
            text = sel
        elif isinstance(sel, tuple):
            text = f"(d, e) = ({format_rational(sel[0])}, {format_rational(sel[1])})"
        else:
            text = f"callable {getattr(sel, '__name__', type(sel).__name__)}"
        return f"inflated f_c SGN_rho, rho = {format_rational(self.rho)}, selection {text}"


@dataclass(frozen=True)
class Stribeck(FrictionLaw):
    """Stribeck friction ``f(v) = (f_c + (f_s - f_c) e^{-(v/v_s)^2}) sign(v) + viscous·v``.

    At ``v = 0`` the friction is the static set ``[-f_s, f_s]``.  With
    ``f_s > f_c`` the law has a decreasing branch (negative damping) near
    ``v = 0`` and PID control can *hunt*: a stick–slip limit cycle that the
    paper mentions and Corollary 1 bounds (Fig. 4: the graph lies inside
    ``f_c SGN_ρ`` for ``ρ ≥`` :meth:`required_rho`).  ``viscous`` is viscous
    friction *in addition* to the ``α_v`` already inside ``k_v``.

    Parameters
    ----------
    f_s : number
        Static friction level (per unit mass), ``f_s > 0``; may exceed ``f_c``.
    v_s : number
        Stribeck velocity, ``v_s > 0``.
    viscous : number, optional
        Extra viscous coefficient, ``≥ 0`` (default 0).

    Notes
    -----
    The implicit step solves ``D w + h f(w) = r``.  For ``w > 0`` the map
    ``w ↦ D w + h f(w)`` has slope at least
    ``D + h·viscous - h|f_s - f_c|·sqrt(2/e)/v_s``, so it is increasing, and
    the step unique, when ``1 + h (k_v + viscous - |f_s - f_c| sqrt(2/e)/v_s) > 0``;
    :meth:`check_step` rejects larger ``h``.  Then ``w = 0`` (stick) if
    ``|r| ≤ h f_s`` and otherwise ``w`` is the single root of a monotone
    scalar equation, found by safeguarded Newton iteration to machine
    precision.

    Examples
    --------
    >>> law = Stribeck(f_s="1.3", v_s="0.1")
    >>> law.required_rho(1)
    Fraction(3, 10)
    >>> law.graph([0.0, 0.1], 1.0)[1].round(4)
    array([1.3   , 1.1104])
    """

    f_s: Fraction
    v_s: Fraction
    viscous: Fraction = Fraction(0)
    _floats: tuple[float, float, float] = field(init=False, repr=False, compare=False)

    name: ClassVar[str] = "stribeck"

    def __post_init__(self) -> None:
        object.__setattr__(self, "f_s", _check_positive(self.f_s, "f_s"))
        object.__setattr__(self, "v_s", _check_positive(self.v_s, "v_s"))
        object.__setattr__(self, "viscous", _check_nonnegative(self.viscous, "viscous"))
        object.__setattr__(self, "_floats", (float(self.f_s), float(self.v_s), float(self.viscous)))

    def force(self, v: Any, f_c: float) -> np.ndarray:
        """The single-valued branch ``f(v)`` for ``v != 0`` (0 at ``v = 0``)."""
        v = np.asarray(v, dtype=float)
        f_s, v_s, beta = float(self.f_s), float(self.v_s), float(self.viscous)
        return (f_c + (f_s - f_c) * np.exp(-((v / v_s) ** 2))) * np.sign(v) + beta * v

    def graph(self, v: Any, f_c: float) -> tuple[np.ndarray, np.ndarray]:
        v = np.asarray(v, dtype=float)
        f = self.force(v, f_c)
        f_s = float(self.f_s)
        return np.where(v == 0, -f_s, f), np.where(v == 0, f_s, f)

    def required_rho(self, f_c: object) -> Fraction:
        """Smallest ``ρ`` with the graph inside ``f_c SGN_ρ`` (Fig. 4), for ``viscous = 0``.

        For ``f_s ≥ f_c`` it is ``(f_s - f_c)/f_c`` exactly: the static set
        needs ``f_s ≤ (1 + ρ) f_c``, and then ``|f(v) - f_c sign v| <
        f_s - f_c = ρ f_c`` for all ``v != 0``.

        Raises
        ------
        ParameterError
            If ``viscous > 0`` (the graph then leaves every band as
            ``|v| → ∞``) or ``f_s < f_c`` (not covered here).
        """
        f_c_q = _check_positive(f_c, "f_c")
        if self.viscous != 0:
            raise ParameterError(
                f"a Stribeck law with viscous = {format_rational(self.viscous)} > 0 leaves every band "
                "f_c SGN_rho as |v| grows; required_rho needs viscous = 0"
            )
        if self.f_s < f_c_q:
            raise ParameterError(
                f"required_rho covers f_s ≥ f_c; got f_s = {format_rational(self.f_s)} < f_c = {format_rational(f_c_q)}"
            )
        return (self.f_s - f_c_q) / f_c_q

    def max_step(self, *, k_v: float, f_c: float) -> float:
        """Largest ``h`` for which the implicit step is unique (``inf`` if any ``h`` is)."""
        slope = abs(float(self.f_s) - f_c) * _STRIBECK_SLOPE / float(self.v_s) - k_v - float(self.viscous)
        return math.inf if slope <= 0 else 1.0 / slope

    def check_step(self, h: float, *, k_p: float, k_i: float, k_v: float, f_c: float) -> None:
        h_max = self.max_step(k_v=k_v, f_c=f_c)
        if not h < h_max:
            raise SimulationError(
                f"h = {h:g} is too large for the Stribeck law (f_s = {float(self.f_s):g}, v_s = {float(self.v_s):g}): "
                f"the implicit step is unique only for h < {h_max:.6g}"
            )

    def solve_step(self, step: Step) -> tuple[float, float]:
        r, D, h = step.r, step.D, step.h
        f_s, v_s, beta = self._floats
        if abs(r) <= h * f_s:
            return 0.0, r / h
        sgn = 1.0 if r > 0 else -1.0
        target = abs(r)
        f_c = step.f_c
        delta = f_s - f_c
        slope0 = D + h * beta

        def g(w: float) -> tuple[float, float]:
            ex = math.exp(-((w / v_s) ** 2))
            return (
                slope0 * w + h * (f_c + delta * ex) - target,
                slope0 - h * delta * ex * 2.0 * w / (v_s * v_s),
            )

        lo = max(0.0, (target - h * max(f_s, f_c)) / slope0)
        hi = max(lo, (target - h * min(f_s, f_c)) / slope0)
        w = 0.5 * (lo + hi)
        for _ in range(200):
            val, der = g(w)
            if val > 0:
                hi = w
            else:
                lo = w
            if val == 0 or hi - lo <= 2.0 * math.ulp(hi):
                break
            w_new = w - val / der if der > 0 else 0.5 * (lo + hi)
            if not (lo < w_new < hi):
                w_new = 0.5 * (lo + hi)
            if w_new == w:
                break
            w = w_new
        w = sgn * w
        return w, (r - D * w) / h

    def describe(self) -> str:
        return (
            f"Stribeck, f_s = {format_rational(self.f_s)}, v_s = {format_rational(self.v_s)}, "
            f"viscous = {format_rational(self.viscous)}"
        )
