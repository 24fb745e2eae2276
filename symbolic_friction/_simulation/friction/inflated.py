"""The inflated Coulomb law ``f_c SGN_ρ(v)`` of Corollary 1 (eq. perturbed), with a selection (greedy, or any admissible ``(d, e)``), for the ``moreau`` method."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, ClassVar

import numpy as np

from ..._infra.errors import ParameterError, SimulationError
from ._law import _check_nonnegative, _coulomb_solve, Coulomb, FrictionLaw, Step, WORST_CASE
from ..._infra.rational import format_rational, to_rational

__all__ = ["InflatedCoulomb"]


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

    def stepper(self, *, k_p: float, k_i: float, k_v: float, f_c: float) -> Any:
        """For a callable selection, the step of :meth:`solve_step` without building a :class:`Step` (the
        searches over selections run millions of steps); the same operations, so the same ``w``."""
        if not callable(self.selection):
            return super().stepper(k_p=k_p, k_i=k_i, k_v=k_v, f_c=f_c)
        selection, checked = self.selection, self._checked
        limit = self._rho + 1e-12 * max(1.0, self._rho)  # as _checked allows

        def step(t: float, h: float, sigma: float, phi: float, v: float, D: float, r: float) -> float:
            out = selection(t, (sigma, phi, v))
            try:  # the common case inline; anything unusual goes through _checked, which refuses it
                d, e = out
                d, e = float(d), float(e)
                if not (abs(d) <= limit and abs(e) <= limit):
                    raise ValueError
            except (TypeError, ValueError):
                d, e = checked(out, t)
            a = h * f_c
            u, _ = _coulomb_solve(r - a * e + D * d, D, a)
            return u - d

        return step

    def _call_selection(self, step: Step) -> tuple[float, float]:
        return self._checked(self.selection(step.t, (step.sigma, step.phi, step.v)), step.t)

    def _checked(self, out: Any, t: float) -> tuple[float, float]:
        """The selection's value ``(d, e)`` as floats, refused unless both are within ρ."""
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
                f"the selection returned (d, e) = ({d!r}, {e!r}) at t = {t:g}; both must be within rho = {rho:g}"
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
