"""Step and initial-condition responses of the closed loop, shaped like python-control's.

The loop of paper §II-A (eqs. uPID, basic, xPhDot) has two inputs besides
its initial state: the position **reference** ``r`` and a constant
**disturbance** force ``d`` on the mass (normalised by ``m``, like ``f_c``).
The paper tracks ``r = 0`` and notes that a piecewise constant setpoint is a
change of coordinates away; a constant force is one too, because the integral
action absorbs it:

* a **reference step** ``r`` with the mass at rest at position 0 and the
  integrator empty (``e_i(0) = 0``, as in eq. uPID) is eq. (xPhDot) from
  ``z(0) = (0, -r, 0)``, where ``s`` is the position error; the output is the
  position ``y = s + r``;
* a **disturbance step** ``d`` (``v' = u + d - f_c SGN(v)``) with the mass at
  rest at the setpoint is eq. (xPhDot) in ``ẽ_i = e_i - d/k_i`` from
  ``z̃(0) = (-d/k_i, 0, 0)``; the output is the position ``y = s``.  The mass
  moves only if ``|d| > f_c``: below, the initial state lies in the
  attractor 𝒜 (eq. Aph) and nothing happens, as Coulomb friction holds it.

Both are simulated by the exact event-driven method.  The result,
:class:`Response`, follows ``control.TimeResponseData``: ``time`` ``(n_t,)``,
``outputs`` ``(n_t,)``, ``inputs`` ``(n_t,)``, ``states`` ``(3, n_t)`` and
``t, y = response`` unpacking.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Iterator

import numpy as np

from .._infra.errors import SimulationError
from .._infra.guards import check_real
from .._infra.rational import format_rational, shown, to_rational
from .._model.parameters import Parameters
from ._base import MAX_TIME_CONSTANTS, _check_float_model
from ._frames import STATE_NAMES, dataset_on_time, frame_on_time

__all__ = ["Response", "step_response", "initial_response", "default_time"]

INPUTS = ("reference", "disturbance")
DEFAULT_SAMPLES = 1001
MAX_SAMPLES = 10_000_000
"""The most sample times one response may ask for (a bound on memory)."""


@dataclass(frozen=True, eq=False, repr=False)
class Response:
    """A time response of the closed loop, in python-control's layout.

    Attributes
    ----------
    time : ndarray, shape (n_t,)
        Sample times.
    outputs : ndarray, shape (n_t,)
        The position of the mass (``s + r`` for a reference step).
    states : ndarray, shape (3, n_t)
        ``(e_i, s, v)`` of eq. (xPhDot), state first as in python-control and
        scipy.signal (``solution.z`` holds the simulated states as ``(n_t, 3)``).
    inputs : ndarray, shape (n_t,)
        The input: the reference ``r`` or the disturbance ``d`` (0 for an
        initial-condition response).
    input : {"reference", "disturbance", None}
        Which input stepped (None: an initial-condition response).
    amplitude : Fraction
        The step's size, exact.
    params : Parameters
    solution : Solution
        The event-driven solution behind the response (events, modes, ``x``).

    Examples
    --------
    >>> from symbolic_friction import Parameters, step_response
    >>> response = step_response(Parameters.table_i("a"), 30)
    >>> response
    Response(reference step 1 of Parameters(k_p=3, k_i=4, k_v=32/5, f_c=1), 1001 samples on [0, 30], 7 events)
    >>> t, y = response
    >>> t.shape, y.shape, response.states.shape
    ((1001,), (1001,), (3, 1001))
    >>> round(float(y.max()), 3)  # case (a) overshoots by half the step
    1.5
    """

    time: np.ndarray
    outputs: np.ndarray
    states: np.ndarray
    inputs: np.ndarray
    input: str | None
    amplitude: Fraction
    params: Parameters
    solution: Any

    def __post_init__(self) -> None:
        from ._trajectories import Solution

        if not isinstance(self.params, Parameters):
            raise SimulationError(f"params must be a Parameters instance; got {type(self.params).__name__}")
        if self.input is not None and self.input not in INPUTS:
            raise SimulationError(f"input must be one of {', '.join(INPUTS)} or None; got {shown(self.input)}")
        object.__setattr__(self, "amplitude", to_rational(self.amplitude, name="amplitude"))
        if not isinstance(self.solution, Solution):
            raise SimulationError(f"solution must be a Solution (from simulate); got {type(self.solution).__name__}")
        arrays = {name: getattr(self, name) for name in ("time", "outputs", "inputs", "states")}
        wrong = [name for name, a in arrays.items() if not isinstance(a, np.ndarray)]
        if wrong:
            raise SimulationError(f"{wrong[0]} must be a numpy array; got {type(arrays[wrong[0]]).__name__}")
        n = self.time.shape
        if len(n) != 1 or self.outputs.shape != n or self.inputs.shape != n or self.states.shape != (3, *n):
            raise SimulationError(
                f"time, outputs and inputs must have one shape (n,) and states (3, n); got {self.time.shape}, "
                f"{self.outputs.shape}, {self.inputs.shape} and {self.states.shape}"
            )

    def __iter__(self) -> Iterator[np.ndarray]:
        # `t, y = step_response(...)`, as python-control allows
        return iter((self.time, self.outputs))

    def __repr__(self) -> str:
        what = "initial response" if self.input is None else f"{self.input} step {format_rational(self.amplitude)}"
        span = f" on [{self.time[0]:g}, {self.time[-1]:g}]" if self.time.size else ""
        return (f"Response({what} of {self.params}, {self.time.size} samples{span}, "
                f"{len(self.solution.events)} events)")

    @property
    def state_labels(self) -> tuple[str, ...]:
        """``("e_i", "s", "v")``: the rows of :attr:`states`."""
        return STATE_NAMES

    def _columns(self) -> dict[str, np.ndarray]:
        cols = {"input": self.inputs, "output": self.outputs}
        cols.update({name: self.states[j] for j, name in enumerate(STATE_NAMES)})
        cols["mode"] = self.solution.mode
        return cols

    def _attrs(self) -> dict[str, str]:
        return {"params": str(self.params), "input": str(self.input), "amplitude": format_rational(self.amplitude)}

    def to_pandas(self) -> Any:
        """A ``pandas.DataFrame`` indexed by ``time``: ``input, output, e_i, s, v, mode``.

        Raises
        ------
        ImportError
            Without pandas (``pip install 'symbolic-friction[pandas]'``).
        """
        return frame_on_time(self._columns(), self.time, self._attrs())

    def to_xarray(self) -> Any:
        """An ``xarray.Dataset`` on a ``time`` dimension: ``input, output, e_i, s, v, mode``.

        Raises
        ------
        ImportError
            Without xarray (``pip install 'symbolic-friction[xarray]'``).
        """
        return dataset_on_time(self._columns(), self.time, self._attrs())

    def plot(self, *, ax: Any = None, **kwargs: Any) -> Any:
        """The position against time, with the reference dashed; returns the matplotlib Axes.

        ``ax`` draws into given Axes; other keywords go to ``Axes.plot``.
        """
        if ax is None:
            import matplotlib.pyplot as plt

            ax = plt.figure().add_subplot()
        ax.plot(self.time, self.outputs, label="position", **kwargs)
        reference = self.inputs if self.input == "reference" else np.zeros_like(self.time)
        ax.plot(self.time, reference, "k--", lw=0.8, label="reference")
        ax.set_xlabel("time t")
        ax.set_ylabel("position")
        what = "initial response" if self.input is None else f"{self.input} step {format_rational(self.amplitude)}"
        ax.set_title(f"{what}: {self.params}", fontsize="small")
        ax.legend(loc="best")
        return ax


def default_time(params: Parameters) -> float:
    """``10/|Re λ|`` for the slowest root ``λ`` of ``s³ + k_v s² + k_p s + k_i`` (the loop without friction), rounded up."""
    roots = np.roots([1.0, *(float(q) for q in (params.k_v, params.k_p, params.k_i))])
    return float(math.ceil(10.0 / abs(float(np.max(roots.real)))))


def _times(params: Parameters, T: Any) -> np.ndarray:
    """``T`` as python-control reads it: None (a default horizon), a final time, or the sample times."""
    if T is None:
        T = default_time(params)
    if isinstance(T, (str, bytes, dict, set)):
        raise SimulationError(f"T must be a final time or an array of sample times; got {shown(T)}")
    if np.ndim(T) == 0:
        try:
            t_end = float(T)
        except OverflowError:  # 10**400
            t_end = math.inf
        except (TypeError, ValueError):
            raise SimulationError(f"T must be a final time or an array of sample times; got {shown(T)}") from None
        if not (math.isfinite(t_end) and t_end > 0):
            raise SimulationError(f"the final time T must be finite and > 0; got {shown(T)}")
        longest = _check_float_model(params)
        if t_end > longest:
            raise SimulationError(f"the final time T must be at most {longest:.3g} for these gains (t_end·‖A‖∞ ≤ "
                                  f"{MAX_TIME_CONSTANTS:g}, within float64's range); got {shown(T)}")
        return np.linspace(0.0, t_end, DEFAULT_SAMPLES)
    if np.size(T) > MAX_SAMPLES:
        raise SimulationError(f"at most {MAX_SAMPLES} sample times are supported (a bound on memory); got {np.size(T)}")
    if np.size(T) == 0:
        raise SimulationError("T must hold at least one sample time; got an empty array")
    try:
        t = np.asarray(T, dtype=float).reshape(-1)
    except (TypeError, ValueError, OverflowError):
        raise SimulationError(f"T must be a final time or an array of sample times; got {T!r}"[:300]) from None
    if not (np.all(np.isfinite(t)) and t[0] >= 0 and t[-1] > 0 and np.all(np.diff(t) >= 0)):
        raise SimulationError(
            f"the sample times T must be finite, nondecreasing, from t ≥ 0 to a final time > 0; "
            f"got {t.size} times from {t[0]:g} to {t[-1]:g}"
        )
    return t


def initial_response(params: Parameters, T: Any = None, z0: Any = (0, 1, 0)) -> Response:
    """The response from the initial state ``z0 = (e_i, s, v)`` with no input (eq. xPhDot).

    Parameters
    ----------
    params : Parameters
    T : float or array_like, optional
        Final time, or the sample times (from 0); default ``10/|Re λ|`` of
        the slowest root of the loop without friction, 1001 samples.
    z0 : array_like, shape (3,)
        Initial state ``(e_i, s, v)``.

    Returns
    -------
    Response
        ``outputs`` is the position ``s``; ``inputs`` is 0.

    Examples
    --------
    >>> from symbolic_friction import Parameters, initial_response
    >>> response = initial_response(Parameters.table_i("b"), 60, z0=(0, 3, 0))
    >>> response.states.shape, round(float(response.outputs[-1]), 5)
    ((3, 1001), 1e-05)
    """
    from . import simulate

    if not isinstance(params, Parameters):
        raise SimulationError(f"params must be a Parameters instance; got {type(params).__name__}")
    t = _times(params, T)
    sol = simulate(params, z0, float(t[-1]), t_eval=t)
    return _response(params, sol, input=None, amplitude=Fraction(0), shift=0.0, offset=0.0)


def step_response(params: Parameters, T: Any = None, *, input: str = "reference", amplitude: Any = 1) -> Response:
    """The response to a step of the reference or of a constant disturbance, from rest (module docstring).

    Parameters
    ----------
    params : Parameters
    T : float or array_like, optional
        Final time, or the sample times (from 0); default ``10/|Re λ|`` of
        the slowest root of the loop without friction, 1001 samples.
    input : {"reference", "disturbance"}, keyword-only
        A step of the position setpoint ``r``, or a constant force ``d`` on
        the mass (normalised like ``f_c``).
    amplitude : number, keyword-only
        The step's size (exact: ``"0.5"`` is 1/2); may be negative.

    Returns
    -------
    Response
        ``outputs`` is the position of the mass; ``inputs`` the stepped input.

    Raises
    ------
    SimulationError
        For an unknown input or a bad ``T``.

    Examples
    --------
    >>> from symbolic_friction import Parameters, step_response
    >>> p = Parameters.table_i("a")
    >>> ax = step_response(p).plot()  # doctest: +SKIP
    >>> r = step_response(p, 30, input="disturbance", amplitude="0.5")  # held by friction: |d| < f_c
    >>> float(abs(r.outputs).max())
    0.0
    """
    if input not in INPUTS:
        raise SimulationError(f"input must be one of {', '.join(INPUTS)}; got {input!r}")
    if not isinstance(params, Parameters):
        raise SimulationError(f"params must be a Parameters instance; got {type(params).__name__}")
    a = to_rational(amplitude, name="amplitude")
    check_real(a if input == "reference" else a / params.k_i, name="amplitude" if input == "reference" else "amplitude/k_i",
               low=None, error=SimulationError)  # within float64, which the simulation computes in
    from . import simulate

    t = _times(params, T)
    if input == "reference":
        # s is the position error: the mass at 0 sees s = -r; the position is s + r
        sol = simulate(params, (0.0, -float(a), 0.0), float(t[-1]), t_eval=t)
        return _response(params, sol, input=input, amplitude=a, shift=0.0, offset=float(a))
    # the integral absorbs d: ẽ_i = e_i - d/k_i obeys eq. (xPhDot); e_i is shifted back
    shift = a / params.k_i
    sol = simulate(params, (-float(shift), 0.0, 0.0), float(t[-1]), t_eval=t)
    return _response(params, sol, input=input, amplitude=a, shift=float(shift), offset=0.0)


def _response(params: Parameters, sol: Any, *, input: str | None, amplitude: Fraction, shift: float,
              offset: float) -> Response:
    if not sol.complete:
        raise SimulationError(f"the simulation stopped early ({sol.status}) at t = {sol.t_stop:g}")
    states = sol.z.T.copy()
    states[0] += shift
    states.flags.writeable = False
    return Response(
        time=sol.t, outputs=states[1] + offset, states=states, inputs=np.full(sol.t.shape, float(amplitude)),
        input=input, amplitude=amplitude, params=params, solution=sol,
    )
