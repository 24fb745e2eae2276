"""Stribeck friction (Fig. 4): static level ``f_s``, Coulomb level ``f_c``, Stribeck velocity ``v_s``; its graph lies inside ``f_c SGN_ρ`` for ``ρ ≥ f_s/f_c − 1``, for the ``moreau`` method."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, ClassVar

import numpy as np

from ..._infra.errors import ParameterError, SimulationError
from ._law import _check_nonnegative, _check_positive, _STRIBECK_SLOPE, FrictionLaw, Step
from ..._infra.rational import format_rational

__all__ = ["Stribeck"]


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
