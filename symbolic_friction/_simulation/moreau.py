"""The ``moreau`` method: implicit (Moreau / catching-up) Euler time-stepping
of the inclusion ``x' ∈ A x - b SGN(v)`` (eq. xDot), with the set-valued law
solved exactly in each step.

One step of size ``h`` is ``x_{n+1} = x_n + h (A x_{n+1} - b λ)``,
``λ ∈ SGN(v_{n+1})``.  Its first two rows give ``σ_{n+1} = σ_n - h k_i v_{n+1}``
and ``φ_{n+1} = φ_n + h σ_n - h (h k_i + k_p) v_{n+1}``; the third becomes a
scalar monotone inclusion in ``w = v_{n+1}``:

.. math::

    D\\,w + h f_c\\,\\mathrm{SGN}(w) \\ni r,\\qquad
    D = 1 + h k_v + h^2 k_p + h^3 k_i,\\quad r = v_n + h\\phi_n + h^2\\sigma_n,

whose unique solution is ``w = (r - h f_c sign r)/D`` if ``|r| > h f_c`` and
``w = 0`` (stick, ``λ = r/(h f_c)``) otherwise.  In ``z = (e_i, s, v)`` the
same step reads ``s_{n+1} = s_n + h w``, ``e_{i,n+1} = e_{i,n} + h s_{n+1}``.
A stick step keeps ``v = 0`` and ``s`` *exactly*, as the inclusion does.

The θ-method (Moreau–Jean's θ-scheme, as Siconos' ``MoreauJeanOSI``
writes it) weights the smooth part ``A x`` between the two ends of the step
and keeps the friction impulse implicit:
``x_{n+1} = x_n + h (θ A x_{n+1} + (1-θ) A x_n) - h b λ``,
``λ ∈ SGN(v_{n+1})``.  With ``g = θ h`` and ``c = (1-θ) h`` the rows read
``s_{n+1} = s_n + c v_n + g w`` and ``e_{n+1} = e_n + c s_n + g s_{n+1}``,
and the third is the same scalar inclusion with

.. math::

    D = 1 + g k_v + g^2 k_p + g^3 k_i,\\qquad
    r = v_n + c\\,(\\phi_n - k_v v_n) - g\\,(k_i E + k_p S),

``S = s_n + c v_n``, ``E = e_n + c s_n + g S`` (the friction impulse
``h f_c λ`` is not weighted: it is the reaction that the step solves for).
``θ = 1`` is the implicit Euler step above, computed by the same
operations as before the θ-method existed.

Accuracy: first order for ``θ ∈ (½, 1]``; ``θ = ½`` (trapezoidal smooth
part) is second order on case (a) with its stick–slip transitions, because
a transition inside a step costs an ``O(h²)`` local error in the friction
impulse (the implicit λ catches the stick exactly) and there are finitely
many.  ``θ = ½`` does not damp a fast mode (the trapezoidal rule is
A-stable, not L-stable): on stiff gains with ``h |λ_fast| ≫ 1`` the fast
part oscillates undamped where ``θ = 1`` damps it.
``tests/simulation/test_convergence.py`` and ``tradeoff`` measure the
orders against the independent reference.

Perturbed friction (Corollary 1, Fig. 4) uses the same step with another law
from :mod:`.friction`: ``simulate(..., method="moreau", friction=law)``.

Options
-------
h : float
    Step size, ``> 0`` (default ``1e-3``).  The last step is shortened to
    end exactly at ``t_end``.
theta : float
    The weight ``θ ∈ [½, 1]`` of the smooth part at the step's end
    (default ``1``: implicit Euler).  ``θ < 1`` takes Coulomb friction only
    (the friction laws solve the implicit Euler step).
friction : FrictionLaw or None
    ``None`` (default) is the paper's Coulomb law ``f_c SGN(v)``.
max_steps : int
    Refuse runs needing more steps than this (default ``10**7``).

Output
------
Without ``t_eval`` the samples are the step points.  With ``t_eval`` they
are the scheme's piecewise-linear interpolant (the catching-up trajectory)
at those times.  ``mode[n]`` is the mode of the step that starts at
``t[n]`` (``sign(v)`` after that step, ``0`` for a stick step), so it is
right-continuous like the appendix table; the last sample takes the mode
of the last step.  Events are reported at the first step point of each new
mode.  The run stops early with status ``"at an equilibrium"`` when a step
leaves the state unchanged (a stick step with ``s = 0``).
"""

from __future__ import annotations

import math
from array import array
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .._infra.errors import SimulationError
from .._infra.guards import check_count, check_memory
from .._infra.rational import shown
from .._model.parameters import Parameters
from ._base import SimulationMethod, Solution, Status, as_float, finite_or_raise
from .friction import FrictionLaw

__all__ = ["Moreau", "step_grid"]


def step_grid(t_end: float, h: float) -> int:
    """Number of steps ``N`` for step ``h`` on ``[0, t_end]``.

    The grid is ``t_n = n h`` for ``n < N`` and ``t_N = t_end``; when
    ``t_end/h`` is an integer up to rounding no sliver step is added.
    """
    ratio = t_end / h
    nearest = round(ratio)
    if nearest >= 1 and abs(ratio - nearest) <= 1e-9 * ratio:
        return int(nearest)
    return int(math.ceil(ratio))


def _weights(theta: float, h: float) -> tuple[float, float]:
    """``(θ h, (1-θ) h)``: how much of a step of size ``h`` the smooth part is taken at its end and at its start."""
    g = theta * h
    return g, h - g


MAX_STEPS = 1_000_000_000
"""The largest ``max_steps`` accepted (the default is 10⁷, about 40 s of steps)."""
_STEP_BYTES = 90  # a recorded step (t, e_i, s, v, mode) and then its rows of the result's z, x, t and mode


class _Recorder:
    """Collects samples on the step grid or, with ``t_eval``, interpolates."""

    def __init__(self, t_eval: np.ndarray | None) -> None:
        self.t_eval = t_eval
        self.k = 0  # next t_eval index
        self.t = array("d")
        self.e = array("d")
        self.s = array("d")
        self.v = array("d")
        self.mode = array("b")

    def add(self, t: float, e: float, s: float, v: float, mode: int) -> None:
        self.t.append(t)
        self.e.append(e)
        self.s.append(s)
        self.v.append(v)
        self.mode.append(mode)

    def step(self, t0: float, t1: float, z0: tuple[float, float, float], z1: tuple[float, float, float], mode: int, last: bool) -> None:
        """Record the step ``[t0, t1]`` (its left end, or the t_eval points in it)."""
        if self.t_eval is None:
            self.add(t0, *z0, mode)
            if last:
                self.add(t1, *z1, mode)
            return
        te = self.t_eval
        n = te.size
        dt = t1 - t0
        while self.k < n and (te[self.k] < t1 or (last and te[self.k] <= t1)):
            tau = te[self.k]
            if last and tau >= t1:
                self.add(tau, *z1, mode)
            else:
                th = (tau - t0) / dt
                self.add(tau, *(a + th * (b - a) for a, b in zip(z0, z1)), mode)
            self.k += 1

    def upcoming(self) -> float:
        """The next ``t_eval`` time not yet recorded (``inf`` when none is left, or without ``t_eval``)."""
        te = self.t_eval
        return float(te[self.k]) if te is not None and self.k < te.size else math.inf

    def hold(self, t: float, z: tuple[float, float, float], t_end: float) -> None:
        """The state stays at ``z`` from ``t`` to ``t_end`` (equilibrium)."""
        if self.t_eval is None:
            self.add(t, *z, 0)
            if t_end > t:
                self.add(t_end, *z, 0)
            return
        te = self.t_eval
        while self.k < te.size:
            self.add(te[self.k], *z, 0)
            self.k += 1

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        t = np.frombuffer(self.t, dtype=float).copy()
        z = np.column_stack(
            [np.frombuffer(self.e, dtype=float), np.frombuffer(self.s, dtype=float), np.frombuffer(self.v, dtype=float)]
        ) if len(self.t) else np.zeros((0, 3))
        mode = np.frombuffer(self.mode, dtype=np.int8).astype(int)
        return t, z, mode


@dataclass(frozen=True, kw_only=True)
class Moreau(SimulationMethod):
    """Implicit (Moreau / catching-up) Euler with the exact set-valued step.

    See the module docstring for the step, the options and the output
    conventions.

    Examples
    --------
    >>> from symbolic_friction import Parameters
    >>> from symbolic_friction._simulation import simulate
    >>> sol = simulate(Parameters.table_i("a"), (0, 1, 0), 5.0, method="moreau", h=1e-3)
    >>> float(sol.t[-1]), sol.z.shape, [(round(t, 3), a, b) for t, a, b in sol.events]  # exact: 3.6144, 4.4472
    (5.0, (5001, 3), [(3.615, -1, 0), (4.449, 0, 1)])
    """

    h: float = 1e-3
    theta: float = 1.0
    friction: FrictionLaw | None = None
    max_steps: int = 10_000_000

    name: ClassVar[str] = "moreau"
    # the order every θ in [½, 1] guarantees; θ = ½ is second order (accuracy_order)
    order: ClassVar[float] = 1.0
    knob: ClassVar[str | None] = "h"

    @property
    def accuracy_order(self) -> float:
        """The order in ``h`` of this configuration: 2 for ``θ = ½`` (trapezoidal), else 1."""
        return 2.0 if float(self.theta) == 0.5 else 1.0

    def _validate(self, options: dict[str, Any]) -> None:
        h = options["h"]
        if isinstance(h, bool) or not isinstance(h, (int, float, np.integer, np.floating)):
            raise SimulationError(f"option h must be a number > 0; got {h!r}")
        if not (math.isfinite(as_float(h)) and float(h) > 0):
            raise SimulationError(f"option h (the step size) must be finite and > 0; got h = {shown(h)}")
        theta = options["theta"]
        if isinstance(theta, bool) or not isinstance(theta, (int, float, np.integer, np.floating)):
            raise SimulationError(f"option theta must be a number in [1/2, 1]; got {theta!r}")
        # written so that NaN fails: below 1/2 the θ-scheme amplifies the oscillating modes, above 1 it is not one
        if not 0.5 <= as_float(theta) <= 1.0:
            raise SimulationError(
                f"option theta (the weight of the step's end) must be in [1/2, 1]; got theta = {shown(theta)}"
            )
        friction = options["friction"]
        if friction is not None and not isinstance(friction, FrictionLaw):
            raise SimulationError(
                f"option friction must be None (Coulomb) or a FrictionLaw such as Stribeck(...); got {type(friction).__name__}"
            )
        if friction is not None and float(theta) != 1.0:
            raise SimulationError(
                f"option theta = {theta!r} takes Coulomb friction only (friction=None): the friction law "
                f"{friction.name!r} solves the implicit Euler step, theta = 1"
            )
        check_count(options["max_steps"], name="option max_steps", high=MAX_STEPS, error=SimulationError)

    def _solve(
        self, params: Parameters, z0: np.ndarray, t_end: float, t_eval: np.ndarray | None, options: dict[str, Any]
    ) -> Solution:
        h = float(options["h"])
        if h > t_end:
            raise SimulationError(
                f"option h = {h:g} is larger than the horizon t_end = {t_end:g}: one step would cover it; use h ≤ t_end"
            )
        if t_end / h > options["max_steps"]:
            steps = t_end / h  # a count up to 1e12 in full, beyond that in exponent form
            count = str(step_grid(t_end, h)) if steps < 1e12 else f"{steps:.3g}"
            raise SimulationError(
                f"h = {h:g} needs {count} steps to reach t_end = {t_end:g}, more than max_steps = {options['max_steps']}"
            )
        n_steps = step_grid(t_end, h)
        if t_eval is None:  # every step is a sample: refused before the loop if they exceed the memory cap
            check_memory(name="h", value=h, count=n_steps + 1, item_bytes=_STEP_BYTES,
                         what=f"{n_steps} steps to t_end = {t_end:g}, each a sample", error=SimulationError,
                         hint="pass t_eval (only those times are kept), or a larger h")
        k_p, k_i, k_v, f_c = params.as_floats()
        law: FrictionLaw | None = options["friction"]
        if law is not None:
            law.check_step(h, k_p=k_p, k_i=k_i, k_v=k_v, f_c=f_c)
        rec = _Recorder(t_eval)
        events: list[tuple[float, int, int]] = []
        e, s, v = (float(c) for c in z0)
        prev_mode: int | None = None
        status = Status.T_END
        theta = float(options["theta"])
        euler = theta == 1.0  # the implicit Euler step, by the operations it always used (bit for bit)
        g_full, c_full = _weights(theta, h)
        D_full = 1.0 + g_full * (k_v + g_full * (k_p + g_full * k_i))
        g = c = 0.0
        solve = None if law is None else law.stepper(k_p=k_p, k_i=k_i, k_v=k_v, f_c=f_c)
        # Without t_eval the samples are the step points: appended here, not through the recorder's
        # calls (a third of the time of a run with a friction law went into those calls).
        grid = t_eval is None
        t_add, e_add, s_add, v_add, m_add = rec.t.append, rec.e.append, rec.s.append, rec.v.append, rec.mode.append
        # With t_eval, most steps contain no sample: the recorder is called only for a step that ends after the next
        # sample time (or the last step), the test its loop starts with, so the samples are the same.
        upcoming = rec.upcoming()
        for n in range(n_steps):
            t0 = n * h
            last = n == n_steps - 1
            t1 = t_end if last else (n + 1) * h
            hn = t1 - t0
            phi = -k_i * e - k_p * s
            if euler:
                D = D_full if hn == h else 1.0 + hn * (k_v + hn * (k_p + hn * k_i))
                sigma = -k_i * s
                r = v + hn * (phi + hn * sigma)
            else:
                g, c = (g_full, c_full) if hn == h else _weights(theta, hn)
                D = D_full if hn == h else 1.0 + g * (k_v + g * (k_p + g * k_i))
                s_free = s + c * v
                e_free = e + c * s + g * s_free
                r = v + c * (phi - k_v * v) - g * (k_i * e_free + k_p * s_free)
                sigma = -k_i * s
            if solve is None:
                a = hn * f_c
                w = (r - a) / D if r > a else (r + a) / D if r < -a else 0.0
            else:
                w = solve(t0, hn, sigma, phi, v, D, r)
            if euler:
                s1 = s + hn * w
                e1 = e + hn * s1
            else:
                s1 = s + c * v + g * w
                e1 = e + c * s + g * s1
            mode = 1 if w > 0 else -1 if w < 0 else 0
            if prev_mode is not None and mode != prev_mode:
                events.append((t0, prev_mode, mode))
            if w == 0.0 and v == 0.0 and s1 == s and e1 == e and (law is None or law.time_invariant):
                # A fixed point of a time-invariant step stays forever (Coulomb: a point of 𝒜).
                status = Status.EQUILIBRIUM
                rec.hold(t0, (e, s, v), t_end)
                break
            if grid:
                t_add(t0)
                e_add(e)
                s_add(s)
                v_add(v)
                m_add(mode)
                if last:
                    rec.add(t1, e1, s1, w, mode)
            elif upcoming < t1 or last:
                rec.step(t0, t1, (e, s, v), (e1, s1, w), mode, last)
                upcoming = rec.upcoming()
            prev_mode = mode
            e, s, v = e1, s1, w
        t, z, modes = rec.arrays()
        finite_or_raise(self.name, t, z)
        return Solution.from_samples(
            params=params,
            method=self.name,
            t=t,
            z=z,
            mode=modes,
            events=tuple(events),
            status=status,
            options=dict(options),
        )
