"""The ``regularized`` method: replace ``SGN(v)`` in eq. (xPhDot) by a smooth or
Lipschitz approximation and integrate the resulting stiff ODE with scipy.

.. math::

    \\dot e_i = s,\\quad \\dot s = v,\\quad
    \\dot v = -k_i e_i - k_p s - k_v v - f_c\\,\\psi(v/\\varepsilon),
    \\qquad \\psi = \\tanh \\text{ or } \\psi = \\mathrm{sat}.

This is what many users would write first.  It has no stick phase: while the
exact solution sticks, the regularized velocity is of order ``ε`` and the
position creeps, so the error is of order ``ε`` (first order;
``tests/simulation/test_convergence.py`` measures it).  For small ``ε`` the
ODE is stiff (the Jacobian has the entry ``-f_c ψ'(v/ε)/ε``), so only
scipy's implicit integrators are offered, with the analytic Jacobian.

Options
-------
epsilon : float
    Regularization width ``ε > 0`` (default ``1e-4``).
law : {"tanh", "sat"}
    ``ψ`` (default ``"tanh"``).
rtol, atol : float
    Tolerances of :func:`scipy.integrate.solve_ivp` (defaults ``1e-8``, ``1e-10``).
integrator : {"Radau", "BDF", "LSODA"}
    The stiff solver (default ``"Radau"``).

Valid range
-----------
Besides an ``ε`` float64 cannot resolve, the method refuses a horizon
longer than two *creep times* ``sqrt(f_c/(k_i ε))`` (:func:`creep_time`)
when the set 𝒜 is not negligible against the state: the regularized system
has the origin as its only equilibrium, so where the inclusion sticks its
solution drifts across 𝒜 and, over long horizons, ends far from the exact
one without any integrator noticing.  After the run, the longest stay in
the boundary layer gives an estimate of that drift (:func:`drift_estimate`);
a result whose drift may exceed 10 % of the solution's size is refused.

Output
------
Without ``t_eval`` the samples are the integrator's steps; with ``t_eval``
its dense output at those times.  ``mode`` is ``0`` inside the boundary
layer ``|v| ≤ w`` (``w = ε`` for ``sat``, where the law is linear, and
``w = 3ε`` for ``tanh``, where ``|tanh| ≤ 0.995``) and ``sign(v)`` outside;
events are the crossings of ``v = ±w``, located by the integrator's event
finder.  scipy is imported only when a simulation runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .._infra.errors import SimulationError
from .._infra.rational import shown
from .._model.coordinates import input_vector_entries, z_system_matrix_entries
from .._model.parameters import Parameters
from ._base import SimulationMethod, Solution, Status, as_float, check_rtol, finite_or_raise

__all__ = ["Regularized", "LAWS", "INTEGRATORS", "vector_field", "creep_time", "drift_estimate"]

LAWS = ("tanh", "sat")
INTEGRATORS = ("Radau", "BDF", "LSODA")
_LAYER = {"tanh": 3.0, "sat": 1.0}
# ε below this multiple of the state's scale is not resolved by float64 (module doc of _solve)
_RESOLVABLE = 1e3 * 2.220446049250313e-16
# the creep inside 𝒜 (creep_time) is refused beyond this many creep times, when 𝒜 is at least this
# fraction of the state's size
CREEP_FACTOR = 2.0
CREEP_SIZE = 1e-2
# a result whose estimated drift across 𝒜 (drift_estimate) exceeds this fraction of its size is refused
DRIFT_TOLERANCE = 0.1


def _positive_number(options: dict[str, Any], name: str, meaning: str) -> None:
    value = options[name]
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise SimulationError(f"option {name} ({meaning}) must be a number > 0; got {value!r}")
    if not (math.isfinite(as_float(value)) and float(value) > 0):
        raise SimulationError(f"option {name} ({meaning}) must be finite and > 0; got {name} = {shown(value)}")


def creep_time(params: Parameters, epsilon: float) -> float:
    """``sqrt(f_c / (k_i ε))``: the time scale on which the regularized solution creeps inside 𝒜.

    Inside the boundary layer the law is ``f_c v/ε`` (both laws), so the
    regularized system there is linear with characteristic polynomial
    ``s³ + (k_v + f_c/ε) s² + k_p s + k_i``, whose slow roots are about
    ``± i sqrt(k_i ε / f_c)``: where the inclusion sticks (``v = 0``, ``s``
    constant), the regularized solution drifts on this time scale towards
    its only equilibrium, the origin, across the set 𝒜 of eq. (Aph).
    """
    k_p, k_i, k_v, f_c = params.as_floats()
    return math.sqrt(f_c / (k_i * float(epsilon)))


def _check_creep(params: Parameters, z0: np.ndarray, t_end: float, eps: float) -> None:
    """Refuse a horizon over which the creep inside 𝒜 is no longer small.

    The drift is bounded by the size of 𝒜, ``f_c/k_i`` in ``e_i``; it matters
    when that is more than ``CREEP_SIZE`` of the state's size, and then only a
    horizon within ``CREEP_FACTOR`` creep times keeps it a small fraction of
    ``f_c/k_i`` (measured by ``symbolic-friction extremes``: 30 s of Table I
    case (a) at ε = 1e-4, 0.6 creep times, 0.3 % error; 300 s, 6 creep times,
    34 %; case (b) over 1000 s, 2.8 creep times, 197 %).
    """
    k_p, k_i, k_v, f_c = params.as_floats()
    size = f_c / k_i
    if size <= CREEP_SIZE * float(np.max(np.abs(z0))):
        return
    limit = CREEP_FACTOR * creep_time(params, eps)
    if t_end > limit:
        raise SimulationError(
            f"t_end = {t_end:g} exceeds {CREEP_FACTOR:g} creep times sqrt(f_c/(k_i epsilon)) = {limit:.3g} at "
            f"epsilon = {eps:g}: where the inclusion sticks, the regularized solution drifts across the set of "
            f"equilibria (|e_i| <= f_c/k_i = {size:.3g}) towards the origin; use t_end <= {limit:.3g} or "
            f"epsilon <= {eps * (t_end / limit) ** -2:.3g}"
        )


def drift_estimate(params: Parameters, epsilon: float, longest: float, size: float) -> float:
    """Relative drift across 𝒜 after ``longest`` seconds in the boundary layer, for a solution of ``size``.

    Inside the layer the regularized solution turns towards the origin on
    the creep time scale ``τ = creep_time``, so ``e_i`` moves by about
    ``A (1 - cos(t/τ)) ≤ A min(2, (t/τ)²/2)`` where the inclusion keeps it
    still, ``A = min(f_c/k_i, size)`` (the drift goes no further than 𝒜, nor
    than the state itself).  Relative to ``size``.
    """
    k_p, k_i, k_v, f_c = params.as_floats()
    ratio = longest / creep_time(params, epsilon)
    return min(f_c / k_i, size) / size * min(2.0, ratio * ratio / 2.0)


def _check_drift(
    params: Parameters, z0: np.ndarray, z: np.ndarray, t_end: float, eps: float, initial: int, events: list
) -> None:
    """Refuse a result that spent so long in the boundary layer that its drift (:func:`drift_estimate`) is large.

    ``initial`` is the mode at ``t = 0`` (0: inside the layer), ``events`` the layer crossings.
    """
    start, longest = (0.0 if initial == 0 else None), 0.0
    for te, before, after in events:
        if after == 0:
            start = te
        elif before == 0 and start is not None:
            longest, start = max(longest, te - start), None
    if start is not None:
        longest = max(longest, t_end - start)
    size = float(max(np.max(np.abs(z)), np.max(np.abs(z0)))) or 1.0
    drift = drift_estimate(params, eps, longest, size)
    if drift > DRIFT_TOLERANCE:
        raise SimulationError(
            f"the regularized solution spent {longest:.3g} s in its boundary layer |v| <= epsilon-scale, "
            f"{longest / creep_time(params, eps):.2g} creep times sqrt(f_c/(k_i epsilon)) = {creep_time(params, eps):.3g}: "
            f"where the inclusion sticks it drifts across the set of equilibria by up to {drift:.2g} of the "
            f"solution's size (more than {DRIFT_TOLERANCE:g}); use a smaller epsilon or a shorter horizon"
        )


def vector_field(params: Parameters, epsilon: float, law: str) -> tuple[Any, Any]:
    """The regularized right-hand side ``f(t, z)`` and its analytic Jacobian ``J(t, z)``."""
    k_p, k_i, k_v, f_c = params.as_floats()
    eps = float(epsilon)
    if law == "tanh":

        def psi(v: float) -> float:
            return math.tanh(v / eps)

        def dpsi(v: float) -> float:
            th = math.tanh(v / eps)
            return (1.0 - th * th) / eps

    else:

        def psi(v: float) -> float:
            return max(-1.0, min(1.0, v / eps))

        def dpsi(v: float) -> float:
            return 1.0 / eps if abs(v) < eps else 0.0

    # the package's A_δ and b (eq. xPhDot), with SGN(v) replaced by ψ(v)
    a_z = np.array(z_system_matrix_entries(k_p, k_i, k_v), dtype=float)
    b = np.array(input_vector_entries(f_c), dtype=float)

    dot = a_z.dot  # the same product as a_z @ z, with less dispatch: the integrator calls rhs at every stage

    def rhs(_t: float, z: np.ndarray) -> np.ndarray:
        return dot(z) - b * psi(z[2])

    def jac(_t: float, z: np.ndarray) -> np.ndarray:
        out = a_z.copy()
        out[:, 2] -= b * dpsi(z[2])
        return out

    return rhs, jac


@dataclass(frozen=True, kw_only=True)
class Regularized(SimulationMethod):
    """``SGN(v) ≈ tanh(v/ε)`` (or ``sat(v/ε)``) integrated by a stiff scipy solver.

    Examples
    --------
    >>> from symbolic_friction import Parameters, Regularized, simulate
    >>> p = Parameters.table_i("a")
    >>> exact = simulate(p, (0, 1, 0), 5, t_eval=[5])
    >>> smooth = simulate(p, (0, 1, 0), 5, method=Regularized(epsilon=1e-3), t_eval=[5])
    >>> bool(abs(smooth.z - exact.z).max() < 1e-2)
    True


    See the module docstring for the options and the output conventions.
    """

    epsilon: float = 1e-4
    law: str = "tanh"
    rtol: float = 1e-8
    atol: float = 1e-10
    integrator: str = "Radau"

    name: ClassVar[str] = "regularized"
    order: ClassVar[float] = 1.0
    knob: ClassVar[str | None] = "epsilon"

    def _validate(self, options: dict[str, Any]) -> None:
        _positive_number(options, "epsilon", "the regularization width")
        _positive_number(options, "rtol", "relative tolerance")
        _positive_number(options, "atol", "absolute tolerance")
        check_rtol(options["rtol"])
        if options["law"] not in LAWS:
            raise SimulationError(f"option law must be one of {', '.join(map(repr, LAWS))}; got {options['law']!r}")
        if options["integrator"] not in INTEGRATORS:
            raise SimulationError(
                f"option integrator must be one of {', '.join(map(repr, INTEGRATORS))} (stiff solvers); "
                f"got {options['integrator']!r}"
            )

    def _solve(
        self, params: Parameters, z0: np.ndarray, t_end: float, t_eval: np.ndarray | None, options: dict[str, Any]
    ) -> Solution:
        from scipy.integrate import solve_ivp

        from ._radau import integrator

        eps = float(options["epsilon"])
        law = options["law"]
        # The boundary layer |v| ≤ 3ε must be wider than the rounding of v: below that the
        # vector field is a discontinuous sign with a zero Jacobian, and the integrator
        # returns a wrong answer without failing.
        scale = max(float(np.max(np.abs(z0))), float(params.f_c))
        if eps < _RESOLVABLE * scale:
            raise SimulationError(
                f"option epsilon = {eps:.3g} is below what float64 can resolve for this state "
                f"(|z0|, f_c up to {scale:.3g}); use epsilon ≥ {_RESOLVABLE * scale:.3g}"
            )
        _check_creep(params, z0, t_end, eps)
        layer = _LAYER[law] * eps
        rhs, jac = vector_field(params, eps, law)

        def upper(_t: float, z: np.ndarray) -> float:
            return z[2] - layer

        def lower(_t: float, z: np.ndarray) -> float:
            return z[2] + layer

        try:
            with np.errstate(over="raise", invalid="raise"):
                result = solve_ivp(
                    rhs,
                    (0.0, t_end),
                    np.asarray(z0, dtype=float),
                    method=integrator(options["integrator"]),
                    t_eval=t_eval,
                    rtol=float(options["rtol"]),
                    atol=float(options["atol"]),
                    jac=jac,
                    events=(upper, lower),
                )
        except (FloatingPointError, OverflowError, ValueError):
            # inf or NaN reached the integrator (scipy raises ValueError on them in its linear algebra)
            raise SimulationError(
                "the regularized solution leaves the range of float64 (about ±1.8e308) from z0 = "
                f"({', '.join(f'{c:g}' for c in z0)}): scale the initial state down"
            ) from None
        if not result.success:
            raise SimulationError(
                f"the {options['integrator']} integrator failed at t = {result.t[-1]:g} "
                f"(epsilon = {eps:g}, rtol = {options['rtol']:g}): {result.message}"
            )
        t = np.asarray(result.t, dtype=float)
        z = np.asarray(result.y, dtype=float).T
        finite_or_raise(self.name, t, z)

        def mode_of(v: np.ndarray) -> np.ndarray:
            return np.where(v > layer, 1, np.where(v < -layer, -1, 0))

        mode = mode_of(z[:, 2])
        crossings = [(float(te), +1) for te in result.t_events[0]] + [(float(te), -1) for te in result.t_events[1]]
        crossings.sort()
        events: list[tuple[float, int, int]] = []
        current = initial = int(mode_of(np.array([z0[2]]))[0])
        for te, side in crossings:
            # Crossing v = +w switches between 0 and +1; v = -w between 0 and -1.
            after = 0 if current == side else side
            if after != current:
                events.append((te, current, after))
                current = after
        _check_drift(params, z0, z, t_end, eps, initial, events)
        return Solution.from_samples(
            params=params,
            method=self.name,
            t=t,
            z=z,
            mode=mode,
            events=tuple(events),
            status=Status.T_END,
            options=dict(options),
        )
