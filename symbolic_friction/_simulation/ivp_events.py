"""The ``ivp-events`` method: mode switching with :func:`scipy.integrate.solve_ivp`
terminal events, the usual do-it-yourself way to simulate eq. (xPhDot).

Each mode of Lemma 1 / Claim 1 is an ODE in ``z = (e_i, s, v)``:

* slip ``v > 0`` (``k = 1``): ``z' = A_δ z - (0, 0, f_c)``, ended by the
  terminal event ``v = 0`` (direction ``-``);
* slip ``v < 0`` (``k = -1``): ``z' = A_δ z + (0, 0, f_c)``, ended by ``v = 0``
  (direction ``+``);
* stick (``k = 0``): ``z' = (s, 0, 0)``, integrated by ``solve_ivp`` too and
  ended by the terminal events ``φ = -k_i e_i - k_p s = ±f_c``.

At the start and after every terminal event ``v`` is set to 0 exactly (after
a slip) and the next mode is chosen from the state by the appendix's table
(Claim 1, the package's :func:`.modes.select_mode`, applied to floats): ``v = 0`` and ``φ > f_c``, or ``φ = f_c`` with ``σ > 0`` → ``+1``;
``φ < -f_c``, or ``φ = -f_c`` with ``σ < 0`` → ``-1``; otherwise stick.  A
stick with ``σ = 0`` (``s = 0``) inside ``|φ| ≤ f_c`` is an equilibrium of
𝒜 and ends the run (status ``"at an equilibrium"``).  Because the table is
applied to floating-point states, rounding near ``|φ| = f_c`` can produce
zero-length segments; ``max_events`` bounds the loop (status
``"max_events reached"``).  The exact method (``event``) does not have this
weakness; this one is here to compare against.

Options
-------
rtol, atol : float
    Tolerances of ``solve_ivp`` (defaults ``1e-8``, ``1e-10``).
integrator : {"DOP853", "RK45", "Radau", "BDF", "LSODA"}
    The integrator of each segment (default ``"DOP853"``, scipy's
    recommendation for tight tolerances).  The explicit ones (DOP853, RK45)
    are refused on stiff gains, when the spectral radius of ``A_δ`` times
    ``t_end`` exceeds 10⁷ (their steps are bounded by stability to about
    ``3/ρ``): use Radau or BDF there.
max_events : int
    Maximum number of mode switches (default ``10_000``).

Output
------
Without ``t_eval`` the samples are the integrator's steps of each segment
(a switching time appears twice: as the end of one segment, with the old
mode, and the start of the next).  With ``t_eval`` the samples are the dense
output of the segment containing each time; a time equal to a switching time
takes the new mode (right-continuous, as the table).  scipy is imported only
when a simulation runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .._infra.errors import SimulationError
from .._infra.guards import check_count
from .._infra.rational import shown
from .._model.parameters import Parameters
from .._model.coordinates import coc_entries, input_vector_entries, z_system_matrix_entries
from ._base import MAX_EVENTS, SimulationMethod, as_float, Solution, Status, check_rtol, finite_or_raise
from .modes import select_mode

__all__ = ["IvpEvents", "INTEGRATORS"]

INTEGRATORS = ("DOP853", "RK45", "Radau", "BDF", "LSODA")
EXPLICIT = ("DOP853", "RK45")
# ρ·t_end above which an explicit integrator is refused (about 3·10⁶ stability-limited steps)
EXPLICIT_WORK = 1e7


def _check_positive(options: dict[str, Any], name: str) -> None:
    value = options[name]
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise SimulationError(f"option {name} must be a number > 0; got {value!r}")
    if not (math.isfinite(as_float(value)) and float(value) > 0):
        raise SimulationError(f"option {name} must be finite and > 0; got {name} = {shown(value)}")



@dataclass(frozen=True, kw_only=True)
class IvpEvents(SimulationMethod):
    """Mode switching with ``solve_ivp`` terminal events (see the module docstring).

    Examples
    --------
    >>> from symbolic_friction import IvpEvents, Parameters, simulate
    >>> p = Parameters.table_i("a")
    >>> exact = simulate(p, (0, 1, 0), 5, t_eval=[5])
    >>> ivp = simulate(p, (0, 1, 0), 5, method=IvpEvents(rtol=1e-10), t_eval=[5])
    >>> bool(abs(ivp.z - exact.z).max() < 1e-6)
    True
    """

    rtol: float = 1e-8
    atol: float = 1e-10
    integrator: str = "DOP853"
    max_events: int = 10_000

    name: ClassVar[str] = "ivp-events"
    order: ClassVar[float] = 1.0
    knob: ClassVar[str | None] = "rtol"

    def _validate(self, options: dict[str, Any]) -> None:
        _check_positive(options, "rtol")
        _check_positive(options, "atol")
        check_rtol(options["rtol"])
        if options["integrator"] not in INTEGRATORS:
            raise SimulationError(
                f"option integrator must be one of {', '.join(map(repr, INTEGRATORS))}; got {options['integrator']!r}"
            )
        check_count(options["max_events"], name="option max_events", high=MAX_EVENTS, error=SimulationError)

    def _solve(
        self, params: Parameters, z0: np.ndarray, t_end: float, t_eval: np.ndarray | None, options: dict[str, Any]
    ) -> Solution:
        from scipy.integrate import solve_ivp

        from ._radau import integrator as solver

        k_p, k_i, k_v, f_c = params.as_floats()
        rtol, atol = float(options["rtol"]), float(options["atol"])
        integrator = options["integrator"]
        max_events = int(options["max_events"])
        if integrator in EXPLICIT:
            # an explicit integrator's steps are bounded by stability to about 3/ρ (ρ the spectral
            # radius of A_δ): say so rather than run for hours
            rho = float(np.max(np.abs(np.roots([1.0, k_v, k_p, k_i]))))
            if rho * t_end > EXPLICIT_WORK:
                raise SimulationError(
                    f"stiff gains for the explicit integrator {integrator}: spectral radius {rho:.3g} over t_end = "
                    f"{t_end:g} needs about {rho * t_end / 3:.2g} steps (more than {EXPLICIT_WORK / 3:.0e}); "
                    "use integrator='Radau' or 'BDF', or the event method"
                )

        # The package's one model: A_δ and b of eq. (xPhDot), the rows of T (eq. CoC) that give
        # σ = t_σ·z and φ = t_φ·z, and the appendix's table (modes.select_mode).
        a_z = np.array(z_system_matrix_entries(k_p, k_i, k_v), dtype=float)
        b = np.array(input_vector_entries(f_c), dtype=float)
        t_sigma, t_phi, _ = (tuple(float(c) for c in row) for row in coc_entries(k_p, k_i))

        def phi_of(z: np.ndarray) -> float:
            return t_phi[0] * z[0] + t_phi[1] * z[1] + t_phi[2] * z[2]

        def mode_of(z: np.ndarray) -> int:
            sigma = t_sigma[0] * z[0] + t_sigma[1] * z[1] + t_sigma[2] * z[2]
            return select_mode(sigma, phi_of(z), z[2], f_c)

        def slip_rhs(sign: float):
            # A_δ z - sign b as ndarray.dot (the same product as @, with less dispatch) minus the vector made once:
            # the integrator's every stage calls this
            dot, signed_b = a_z.dot, sign * b

            def rhs(_t: float, z: np.ndarray) -> np.ndarray:
                return dot(z) - signed_b

            return rhs

        def stick_rhs(_t: float, z: np.ndarray) -> np.ndarray:
            return np.array([z[1], 0.0, 0.0])

        def v_zero(_t: float, z: np.ndarray) -> float:
            return z[2]

        def phi_up(_t: float, z: np.ndarray) -> float:
            return phi_of(z) - f_c

        def phi_down(_t: float, z: np.ndarray) -> float:
            return phi_of(z) + f_c

        for fn in (v_zero, phi_up, phi_down):
            fn.terminal = True  # type: ignore[attr-defined]

        t_parts: list[np.ndarray] = []
        z_parts: list[np.ndarray] = []
        m_parts: list[np.ndarray] = []
        events: list[tuple[float, int, int]] = []
        t0 = 0.0
        z = np.asarray(z0, dtype=float).copy()
        mode = mode_of(z)
        status = Status.T_END
        k_eval = 0  # next t_eval index
        segments = 0
        # DOP853 with increasing t_eval: solve_ivp samples each step's dense output itself, at the steps that hold a
        # sample, instead of building one for every step (about a fifth of a run: three more stages a step).  It is
        # the interpolant the solution object would pick for each sample (the step ending at or after it), and
        # DOP853's is evaluated elementwise, so every sample is the same number; other integrators keep the solution
        # object (theirs is a matrix product, and BDF and LSODA pick the other step at a step's end).
        sampled = t_eval is not None and integrator == "DOP853" and bool(np.all(np.diff(t_eval) > 0))

        while True:
            if mode == 0 and z[1] == 0.0:
                status = Status.EQUILIBRIUM
                if t_eval is not None:
                    rest = t_eval[k_eval:]
                    t_parts.append(rest)
                    z_parts.append(np.tile(z, (rest.size, 1)))
                    m_parts.append(np.zeros(rest.size, dtype=int))
                else:
                    t_parts.append(np.array([t0, t_end]))
                    z_parts.append(np.tile(z, (2, 1)))
                    m_parts.append(np.zeros(2, dtype=int))
                break
            if mode == 0:
                # Both edges as terminal events, each in its outward direction.
                phi_up.direction, phi_down.direction = 1.0, -1.0  # type: ignore[attr-defined]
                rhs, evs = stick_rhs, (phi_up, phi_down)
            else:
                v_zero.direction = -float(mode)  # type: ignore[attr-defined]
                rhs, evs = slip_rhs(float(mode)), (v_zero,)
            sampling = {"t_eval": t_eval[k_eval:]} if sampled else {"dense_output": t_eval is not None}
            seg = solve_ivp(rhs, (t0, t_end), z, method=solver(integrator), rtol=rtol, atol=atol, events=evs,
                            **sampling)
            if seg.status == -1 and sampled:  # run again as below, for the time it failed at (samples hide it)
                seg = solve_ivp(rhs, (t0, t_end), z, method=solver(integrator), rtol=rtol, atol=atol, events=evs,
                                dense_output=True)
            if seg.status == -1:
                raise SimulationError(f"the {integrator} integrator failed at t = {seg.t[-1]:g}: {seg.message}")
            if sampled:
                # every event is terminal: the one that ended the segment is the only one recorded
                ended = [k for k, times in enumerate(seg.t_events) if times.size]
                t1 = float(seg.t_events[ended[0]][-1]) if seg.status == 1 else float(t_end)
                n = len(seg.t)
                if seg.status == 1:  # a sample at the event's time belongs to the next segment, as below
                    n = int(np.searchsorted(seg.t, t1, side="left")) if n else 0
                if n:
                    t_parts.append(t_eval[k_eval:k_eval + n])
                    z_parts.append(seg.y[:, :n].T)
                    m_parts.append(np.full(n, mode, dtype=int))
                    k_eval += n
            else:
                t1 = float(seg.t[-1])
            if t_eval is None:
                t_parts.append(seg.t)
                z_parts.append(seg.y.T)
                m_parts.append(np.full(seg.t.size, mode, dtype=int))
            elif not sampled:
                stop = np.searchsorted(t_eval, t1, side="right" if seg.status == 0 else "left")
                if stop > k_eval:
                    ts = t_eval[k_eval:stop]
                    t_parts.append(ts)
                    z_parts.append(seg.sol(ts).T)
                    m_parts.append(np.full(ts.size, mode, dtype=int))
                    k_eval = stop
            if seg.status == 0:
                break  # t_end reached
            z = seg.y_events[ended[0]][-1].copy() if sampled else seg.y[:, -1].copy()
            if mode != 0:
                z[2] = 0.0  # the event found v = 0; make it exact
            new_mode = mode_of(z)
            if mode == 0 and new_mode == 0:
                # The event fired on |φ| = f_c but rounding left |φ| a hair inside:
                # leave stick in the direction the edge was crossed (rows iii / ix).
                new_mode = 1 if seg.t_events[0].size else -1
            if new_mode != mode:
                events.append((t1, mode, new_mode))
            mode = new_mode
            t0 = t1
            segments += 1
            # A segment that keeps its mode (v touched 0 tangentially) is not an event but still counts,
            # so that rounding can never make the loop spin.
            if len(events) >= max_events or segments >= 2 * max_events:
                status = Status.MAX_EVENTS
                break

        t = np.concatenate(t_parts) if t_parts else np.zeros(0)
        zz = np.concatenate(z_parts) if z_parts else np.zeros((0, 3))
        finite_or_raise(self.name, t, zz)
        mm = np.concatenate(m_parts) if m_parts else np.zeros(0, dtype=int)
        return Solution.from_samples(
            params=params,
            method=self.name,
            t=t,
            z=zz,
            mode=mm,
            events=tuple(events),
            status=status,
            options=dict(options),
        )
