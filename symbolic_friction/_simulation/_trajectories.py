"""The one result type of a simulation: ``N`` solutions of eq. (xDot) on common
sample times, with every event (mode change of Claim 1) and its state.

Every consumer (the :class:`Solution` of a single simulation, the
cross-check, the figures and the scenes) reads a :class:`Trajectories`;
nothing rebuilds what the simulator knew.  ``V`` (eq. lyapLike) is
discontinuous exactly at the events, so their states and the modes on either
side are kept: the one-sided limits of ``V`` are read off them.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from functools import cached_property
from typing import Any

import numpy as np

from .._infra.errors import SimulationError
from .._infra.rational import shown
from .._model.parameters import Parameters
from ._frames import SolutionFrames, TrajectoriesFrames

__all__ = ["Trajectories", "Solution", "Status", "AlongStates"]

_ONE_EMPTY_LABEL = np.array([""], dtype=object)
_ONE_EMPTY_LABEL.flags.writeable = False


class Status:
    """Why the simulation of one trajectory stopped.

    ``T_END`` and ``EQUILIBRIUM`` are *complete*: every sample was computed.
    ``FALLBACK`` is complete too, but only exact up to the start of the slip whose
    end the event kernel could not decide (``UNDECIDED``); from there a stiff
    integrator (Radau with events) computed the rest, at the tolerance its
    ``options["fallback"]`` states.  The others are *incomplete*: samples after
    the stop are NaN, never made up.
    """

    T_END = "t_end reached"
    EQUILIBRIUM = "at an equilibrium"
    MAX_EVENTS = "max_events reached"
    NONFINITE = "left the range of float64"
    UNDECIDED = "end of a slip undecided"
    FALLBACK = "t_end reached by Radau after an undecided event"

    COMPLETE = (T_END, EQUILIBRIUM, FALLBACK)


class AlongStates:
    """The paper's functions along the states ``self.x`` (shape ``(…, 3)``) of ``self.params``.

    Shared by :class:`Trajectories` (shape ``(N, m)``) and its one-row view
    :class:`Solution` (shape ``(n,)``); each evaluates the package's
    one definition (:mod:`.._lyapunov`, :mod:`.._attractor`).
    """

    @cached_property
    def V(self) -> np.ndarray:
        """``V(x(t))`` of eq. (lyapLike)."""
        from .._model.lyapunov import V

        return V(self.params, self.x)

    @cached_property
    def distance(self) -> np.ndarray:
        """``|x(t)|_𝒜`` of eq. (distFromA)."""
        from .._model.attractor import distance_x

        return distance_x(self.params, self.x)

    def V_hat(self, k: tuple[Any, Any, Any, Any]) -> np.ndarray:
        """``V̂(x(t))`` of eq. (Vhat) for constants ``k = (k1, k2, k3, k4)``."""
        from .._model.lyapunov import V_hat

        return V_hat(self.params, self.x, k)


@dataclass(frozen=True, eq=False)
class Trajectories(AlongStates, TrajectoriesFrames):
    """``N`` simulated solutions on common sample times ``t``.

    State arrays are ``(N, m, 3)``: trajectory, then time, then state, so that
    ``z[i]`` is one solution as ``(m, 3)`` rows.  python-control and
    scipy.signal put the state first: :attr:`states` is the same array as
    ``(3, N, m)`` (a view, ``np.moveaxis(z, -1, 0)``).  :meth:`to_pandas`,
    :meth:`to_xarray` and :meth:`plot` hand the samples to pandas, xarray and
    matplotlib.

    Attributes
    ----------
    params : Parameters
    method : str
        The method's name (``"event"``, ``"moreau"``, …).
    t : ndarray, shape (m,)
        Nondecreasing sample times.
    z : ndarray, shape (N, m, 3)
        ``(e_i, s, v)`` at the samples; NaN after an incomplete trajectory's stop.
    x : ndarray, shape (N, m, 3)
        The same states in ``(σ, φ, v)`` (eq. CoC).
    mode : ndarray of int8, shape (N, m)
        ``+1`` slip with ``v > 0``, ``0`` stick, ``-1`` slip with ``v < 0``;
        right-continuous (a sample at an event has the mode after it).
    event_t : ndarray, shape (N, E)
        Event times in order, NaN-padded.
    event_x : ndarray, shape (N, E, 3)
        States at the events (``v = 0`` there), NaN-padded.
    event_before, event_after : ndarray of int8, shape (N, E)
        Modes before and after each event, 0-padded.
    event_residual : ndarray, shape (N, E)
        ``|v|`` that the closed form gave at each event time before ``v`` was
        set to 0 (a check of the event times; 0 where not applicable).
    n_events : ndarray of int, shape (N,)
    status : ndarray of str, shape (N,)
        One of :class:`Status` per trajectory.
    t_stop : ndarray, shape (N,)
        Where each computation stopped (``t_end`` when complete).
    z0 : ndarray, shape (N, 3)
        Initial states as given.
    x0 : ndarray, shape (N, 3)
        The initial states in ``x`` that were simulated (``T z0``).
    source : ndarray of object, shape (N,)
        A label per initial state (``"sphere r=1"``, …), ``""`` by default.
    options : dict
        The method's accuracy knobs.
    time : ndarray, shape (m,)
        ``t`` under python-control's name.
    states : ndarray, shape (3, N, m)
        ``z`` in python-control's orientation (state first).

    Examples
    --------
    >>> from symbolic_friction import Parameters, simulate_batch
    >>> batch = simulate_batch(Parameters.table_i("a"), [(0, 1, 0), (0, -1, 0)], 5, t_eval=[0, 1, 5])
    >>> batch
    Trajectories(2 × 3 samples on [0, 5], method 'event', 2 complete, Parameters(k_p=3, k_i=4, k_v=32/5, f_c=1))
    >>> batch.z.shape, batch.states.shape
    ((2, 3, 3), (3, 2, 3))
    """

    params: Parameters
    method: str
    t: np.ndarray
    z: np.ndarray
    x: np.ndarray
    mode: np.ndarray
    event_t: np.ndarray
    event_x: np.ndarray
    event_before: np.ndarray
    event_after: np.ndarray
    event_residual: np.ndarray
    n_events: np.ndarray
    status: np.ndarray
    t_stop: np.ndarray
    z0: np.ndarray
    x0: np.ndarray
    source: np.ndarray = field(default=None)  # type: ignore[assignment]
    options: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.params, Parameters):
            raise SimulationError(f"params must be a Parameters instance; got {type(self.params).__name__}")
        arrays = [f.name for f in fields(self) if f.type == "np.ndarray" and f.name != "source"]
        wrong = [name for name in arrays if not isinstance(getattr(self, name), np.ndarray)]
        if wrong or self.mode.ndim != 2:
            raise SimulationError(f"malformed trajectories: {', '.join(wrong) or 'mode'} must be numpy arrays "
                                  "(mode of shape (N, m)); got " + (type(getattr(self, wrong[0])).__name__ if wrong
                                                                  else f"shape {self.mode.shape}"))
        N, m = self.mode.shape
        E = self.event_t.shape[1] if self.event_t.ndim == 2 else -1
        problems = []
        if self.t.shape != (m,):
            problems.append(f"t has shape {self.t.shape}, expected ({m},)")
        for name in ("z", "x"):
            if getattr(self, name).shape != (N, m, 3):
                problems.append(f"{name} has shape {getattr(self, name).shape}, expected ({N}, {m}, 3)")
        if self.event_t.shape != (N, E) or self.event_x.shape != (N, E, 3):
            problems.append(f"events have shapes {self.event_t.shape} and {self.event_x.shape}, expected ({N}, E)")
        for name in ("event_before", "event_after", "event_residual"):
            if getattr(self, name).shape != (N, E):
                problems.append(f"{name} must have the shape of event_t")
        for name in ("n_events", "status", "t_stop"):
            if getattr(self, name).shape != (N,):
                problems.append(f"{name} must have shape ({N},)")
        if self.z0.shape != (N, 3) or self.x0.shape != (N, 3):
            problems.append(f"z0 and x0 must have shape ({N}, 3)")
        if m and np.any(np.diff(self.t) < 0):
            problems.append("sample times must be nondecreasing")
        if problems:
            raise SimulationError("malformed trajectories: " + "; ".join(problems))
        if self.source is None:
            object.__setattr__(self, "source", np.full(N, "", dtype=object))

    def __repr__(self) -> str:
        # a summary, as numpy and xarray print: the arrays are a click away, not 400 lines of repr
        m = self.t.size
        span = f" on [{self.t[0]:g}, {self.t[-1]:g}]" if m else ""
        complete = int(np.count_nonzero(self.complete))
        return (f"Trajectories({self.size} × {m} samples{span}, method {self.method!r}, "
                f"{complete} complete, {self.params})")

    @classmethod
    def _unchecked(cls, **fields: Any) -> "Trajectories":
        """Construct without the shape checks, for the simulator's own output (shapes known)."""
        self = object.__new__(cls)
        fields.setdefault("options", {})
        if fields.get("source") is None:
            n = fields["mode"].shape[0]
            fields["source"] = _ONE_EMPTY_LABEL if n == 1 else np.full(n, "", dtype=object)
        self.__dict__.update(fields)
        return self

    # -- size and selection --------------------------------------------------------
    @property
    def size(self) -> int:
        """Number of trajectories ``N``."""
        return int(self.mode.shape[0])

    def __len__(self) -> int:
        return self.size

    @property
    def complete(self) -> np.ndarray:
        """Per trajectory: every sample was computed (status ``T_END``, ``EQUILIBRIUM`` or ``FALLBACK``)."""
        return np.isin(self.status, Status.COMPLETE)

    @property
    def event_modes(self) -> np.ndarray:
        """``(mode_before, mode_after)`` of each event, shape (N, E, 2)."""
        return np.stack([self.event_before, self.event_after], axis=-1)

    def subset(self, index: Any) -> "Trajectories":
        """The trajectories ``index`` (a slice, a boolean mask or an index array)."""
        rows = {
            name: getattr(self, name)[index]
            for name in (
                "z", "x", "mode", "event_t", "event_x", "event_before", "event_after",
                "event_residual", "n_events", "status", "t_stop", "z0", "x0", "source",
            )
        }
        return Trajectories(params=self.params, method=self.method, t=self.t, options=self.options, **rows)

    @classmethod
    def concatenate(cls, parts: "list[Trajectories]") -> "Trajectories":
        """Join batches of the same parameters, method and sample times (events padded to the longest)."""
        if not parts:
            raise SimulationError("nothing to concatenate")
        first = parts[0]
        for p in parts[1:]:
            if p.params != first.params or p.method != first.method or not np.array_equal(p.t, first.t):
                raise SimulationError("only trajectories of the same parameters, method and sample times can be joined")
        E = max(p.event_t.shape[1] for p in parts)

        def pad(a: np.ndarray, fill: Any) -> np.ndarray:
            width = [(0, 0)] * a.ndim
            width[1] = (0, E - a.shape[1])
            return np.pad(a, width, constant_values=fill)

        return cls(
            params=first.params,
            method=first.method,
            t=first.t,
            options=first.options,
            z=np.concatenate([p.z for p in parts]),
            x=np.concatenate([p.x for p in parts]),
            mode=np.concatenate([p.mode for p in parts]),
            event_t=np.concatenate([pad(p.event_t, np.nan) for p in parts]),
            event_x=np.concatenate([pad(p.event_x, np.nan) for p in parts]),
            event_before=np.concatenate([pad(p.event_before, 0) for p in parts]),
            event_after=np.concatenate([pad(p.event_after, 0) for p in parts]),
            event_residual=np.concatenate([pad(p.event_residual, 0.0) for p in parts]),
            n_events=np.concatenate([p.n_events for p in parts]),
            status=np.concatenate([p.status for p in parts]),
            t_stop=np.concatenate([p.t_stop for p in parts]),
            z0=np.concatenate([p.z0 for p in parts]),
            x0=np.concatenate([p.x0 for p in parts]),
            source=np.concatenate([p.source for p in parts]),
        )

    # -- one trajectory ----------------------------------------------------------
    def events(self, i: int) -> tuple[tuple[float, int, int], ...]:
        """The events ``(t, mode_before, mode_after)`` of trajectory ``i``."""
        k = int(self.n_events[i])
        return tuple(
            (float(self.event_t[i, j]), int(self.event_before[i, j]), int(self.event_after[i, j])) for j in range(k)
        )

    def solution(self, i: int = 0) -> "Solution":
        """Trajectory ``i`` as a :class:`Solution` (a view; samples after an incomplete stop dropped)."""
        if not -self.size <= i < self.size:
            raise IndexError(f"trajectory {i} out of range for {self.size} trajectories")
        return Solution(self, i % self.size)

    def __iter__(self):
        return (self.solution(i) for i in range(self.size))


class Solution(AlongStates, SolutionFrames):
    """One simulated solution: a view of one row of a :class:`.Trajectories`.

    State arrays are ``(n, 3)``, one row per sample (as ``scipy.integrate.odeint``);
    :attr:`states` is ``z`` in python-control's and ``solve_ivp``'s orientation,
    ``(3, n)``.

    Attributes
    ----------
    params : Parameters
    method : str
    t : ndarray, shape (n,)
        Sample times (those after an incomplete trajectory's stop dropped).
    z : ndarray, shape (n, 3)
        ``(e_i, s, v)``.
    x : ndarray, shape (n, 3)
        ``(σ, φ, v)``.
    mode : ndarray of int, shape (n,)
        ``+1`` slip with ``v > 0``, ``0`` stick, ``-1`` slip with ``v < 0``.
    events : tuple of (float, int, int)
        ``(t, mode_before, mode_after)`` for every mode change.
    event_x : ndarray, shape (n_events, 3)
        The state at each event (NaN where the method does not compute it).
    status : str
        One of :class:`Status`.
    complete : bool
    options : dict
        The accuracy knobs used.
    trajectories, index
        The batch this is a view of, and the row.
    time : ndarray, shape (n,)
        ``t`` under python-control's name.
    states : ndarray, shape (3, n)
        ``z`` in python-control's orientation (``solution.states[1]`` is ``s(t)``).

    Examples
    --------
    >>> from symbolic_friction import Parameters, simulate
    >>> sol = simulate(Parameters.table_i("a"), (0, 1, 0), 10, t_eval=[0, 5, 10])
    >>> sol
    Solution(method='event', samples=3, events=3, status='t_end reached')
    >>> sol.z.shape, sol.states.shape
    ((3, 3), (3, 3))
    >>> sol.to_pandas().columns.tolist()  # doctest: +SKIP
    ['e_i', 's', 'v', 'sigma', 'phi', 'mode']
    """

    def __init__(self, trajectories: "Trajectories", index: int) -> None:
        if not isinstance(trajectories, Trajectories):
            raise SimulationError(f"trajectories must be a Trajectories; got {type(trajectories).__name__}")
        if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < trajectories.size:
            raise SimulationError(f"index must be an integer in [0, {trajectories.size}); got {shown(index)}")
        self.trajectories = trajectories
        self.index = index
        complete = trajectories.status[index] in Status.COMPLETE
        self._keep = slice(None) if complete else trajectories.t <= trajectories.t_stop[index]

    @classmethod
    def from_samples(
        cls,
        *,
        params: Parameters,
        method: str,
        t: np.ndarray,
        z: np.ndarray,
        mode: np.ndarray,
        events: tuple[tuple[float, int, int], ...],
        status: str,
        options: dict[str, Any],
    ) -> "Solution":
        """A solution from samples of one trajectory (the time-stepping methods), states at events unknown (NaN)."""
        from .._model.coordinates import z_to_x

        t = np.asarray(t, dtype=float)
        z = np.asarray(z, dtype=float).reshape(-1, 3)
        n = len(events)
        ev = np.array(events, dtype=float).reshape(n, 3)
        batch = Trajectories(
            params=params,
            method=method,
            t=t,
            z=z[None],
            x=z_to_x(params, z)[None],
            mode=np.asarray(mode, dtype=np.int8)[None],
            event_t=ev[None, :, 0],
            event_x=np.full((1, n, 3), np.nan),
            event_before=ev[None, :, 1].astype(np.int8),
            event_after=ev[None, :, 2].astype(np.int8),
            event_residual=np.zeros((1, n)),
            n_events=np.array([n]),
            status=np.array([status], dtype=object),
            t_stop=np.array([t[-1] if t.size else 0.0]),
            z0=z[:1].copy() if z.size else np.zeros((1, 3)),
            x0=z_to_x(params, z[:1]) if z.size else np.zeros((1, 3)),
            options=dict(options),
        )
        return cls(batch, 0)

    # -- what the row holds ----------------------------------------------------------
    @property
    def params(self) -> Parameters:
        return self.trajectories.params

    @property
    def method(self) -> str:
        return self.trajectories.method

    @property
    def options(self) -> dict[str, Any]:
        return self.trajectories.options

    @property
    def status(self) -> str:
        return str(self.trajectories.status[self.index])

    @property
    def complete(self) -> bool:
        return self.status in Status.COMPLETE

    @cached_property
    def t(self) -> np.ndarray:
        return self.trajectories.t[self._keep]

    @cached_property
    def z(self) -> np.ndarray:
        return self.trajectories.z[self.index][self._keep]

    @cached_property
    def x(self) -> np.ndarray:
        """States in ``(σ, φ, v)``, shape (n, 3)."""
        return self.trajectories.x[self.index][self._keep]

    @cached_property
    def mode(self) -> np.ndarray:
        return self.trajectories.mode[self.index][self._keep]

    @cached_property
    def events(self) -> tuple[tuple[float, int, int], ...]:
        return self.trajectories.events(self.index)

    @property
    def event_x(self) -> np.ndarray:
        return self.trajectories.event_x[self.index, : int(self.trajectories.n_events[self.index])]

    @property
    def t_stop(self) -> float:
        return float(self.trajectories.t_stop[self.index])

    def __repr__(self) -> str:
        return f"Solution(method={self.method!r}, samples={self.t.size}, events={len(self.events)}, status={self.status!r})"
