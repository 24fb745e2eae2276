"""Simulation results in the scientific Python stack: pandas, xarray and matplotlib.

The states of eq. (xPhDot), ``z = (e_i, s, v)``, and of eq. (xDot),
``x = (σ, φ, v)`` (eq. CoC), become named columns (pandas) or data variables
on a ``time`` dimension (xarray).  pandas and xarray are optional extras
(``pip install 'symbolic-friction[pandas]'``, ``[xarray]``), imported only
when a conversion is asked for; matplotlib, a dependency, only when a plot is.
"""

from __future__ import annotations

import importlib
from typing import Any

import numpy as np

__all__ = ["optional", "STATE_NAMES", "X_NAMES", "solution_columns", "state_axes", "SolutionFrames", "TrajectoriesFrames"]

STATE_NAMES = ("e_i", "s", "v")
"""The state ``z`` of eq. (xPhDot): integral error, position error, velocity."""

X_NAMES = ("sigma", "phi")
"""The first two coordinates of ``x = (σ, φ, v)`` (eq. CoC); the third is ``v``."""

_LONG = {"e_i": "integral error e_i", "s": "position s", "v": "velocity v"}


def optional(module: str, extra: str) -> Any:
    """Import ``module`` of the optional extra ``extra``, or say how to install it.

    Raises
    ------
    ImportError
        If ``module`` is not installed; the message names the extra.
    """
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise ImportError(
            f"this needs {module}, an optional extra: pip install 'symbolic-friction[{extra}]' ({exc})"
        ) from None


def solution_columns(z: np.ndarray, x: np.ndarray, mode: np.ndarray) -> dict[str, np.ndarray]:
    """``e_i, s, v, sigma, phi, mode`` from states of shape ``(…, 3)`` and modes of shape ``(…)``."""
    cols = {name: z[..., j] for j, name in enumerate(STATE_NAMES)}
    cols.update({name: x[..., j] for j, name in enumerate(X_NAMES)})
    cols["mode"] = mode
    return cols


def state_axes(t: np.ndarray, z: np.ndarray, *, ax: Any = None, states: Any = ("s",), **kwargs: Any) -> Any:
    """Plot ``states`` (names among ``e_i, s, v``) of ``z`` (shape ``(…, n_t, 3)``) against ``t``; return the Axes."""
    from .._infra.errors import UsageError

    names = (states,) if isinstance(states, str) else tuple(states)
    unknown = [n for n in names if n not in STATE_NAMES]
    if not names or unknown:
        raise UsageError(f"states must name some of {', '.join(STATE_NAMES)}; got {names!r}")
    if ax is None:
        import matplotlib.pyplot as plt

        ax = plt.figure().add_subplot()
    rows = z.reshape(-1, z.shape[-2], 3)
    for name in names:
        j = STATE_NAMES.index(name)
        for i, row in enumerate(rows):
            # one legend entry per state, however many trajectories
            ax.plot(t, row[:, j], label=_LONG[name] if i == 0 else None, **kwargs)
    ax.set_xlabel("time t")
    if len(names) == 1:
        ax.set_ylabel(_LONG[names[0]])
    ax.legend(loc="best")
    return ax


def frame_on_time(columns: dict[str, np.ndarray], time: np.ndarray, attrs: dict[str, str]) -> Any:
    """A ``pandas.DataFrame`` of ``columns`` indexed by ``time`` (one trace), with ``attrs``."""
    pd = optional("pandas", "pandas")
    frame = pd.DataFrame(columns, index=pd.Index(time, name="time"))
    frame.attrs.update(attrs)
    return frame


def dataset_on_time(columns: dict[str, np.ndarray], time: np.ndarray, attrs: dict[str, str]) -> Any:
    """An ``xarray.Dataset`` of ``columns`` on a ``time`` dimension (one trace), with ``attrs``."""
    xr = optional("xarray", "xarray")
    return xr.Dataset({k: ("time", v) for k, v in columns.items()}, coords={"time": time}, attrs=attrs)


class SolutionFrames:
    """``states``, ``to_pandas``, ``to_xarray`` and ``plot`` of one solution (``t``, ``z``, ``x``, ``mode``)."""

    @property
    def time(self) -> np.ndarray:
        """The sample times ``t`` (python-control's name)."""
        return self.t

    @property
    def states(self) -> np.ndarray:
        """``z = (e_i, s, v)`` in python-control's orientation: shape ``(3, n_t)`` (``z`` is ``(n_t, 3)``)."""
        return self.z.T

    def to_pandas(self) -> Any:
        """A ``pandas.DataFrame`` indexed by ``time``: columns ``e_i, s, v, sigma, phi, mode``.

        Raises
        ------
        ImportError
            Without pandas (``pip install 'symbolic-friction[pandas]'``).
        """
        return frame_on_time(solution_columns(self.z, self.x, self.mode), self.t, self._frame_attrs())

    def to_xarray(self) -> Any:
        """An ``xarray.Dataset`` on a ``time`` dimension: ``e_i, s, v, sigma, phi, mode``.

        Raises
        ------
        ImportError
            Without xarray (``pip install 'symbolic-friction[xarray]'``).
        """
        return dataset_on_time(solution_columns(self.z, self.x, self.mode), self.t, self._frame_attrs())

    def plot(self, states: Any = ("e_i", "s", "v"), *, ax: Any = None, **kwargs: Any) -> Any:
        """Plot ``states`` (names among ``e_i, s, v``) against time; return the matplotlib Axes.

        ``ax`` draws into given Axes; other keywords go to ``Axes.plot``.
        """
        return state_axes(self.t, self.z, ax=ax, states=states, **kwargs)

    def _frame_attrs(self) -> dict[str, str]:
        return {"params": str(self.params), "method": self.method, "status": str(self.status)}


class TrajectoriesFrames:
    """``states``, ``to_pandas``, ``to_xarray`` and ``plot`` of ``N`` solutions on common times."""

    @property
    def time(self) -> np.ndarray:
        """The sample times ``t`` (python-control's name)."""
        return self.t

    @property
    def states(self) -> np.ndarray:
        """``z`` in python-control's orientation for several traces: shape ``(3, N, m)`` (``z`` is ``(N, m, 3)``)."""
        return np.moveaxis(self.z, -1, 0)

    def to_pandas(self) -> Any:
        """A long ``pandas.DataFrame`` indexed by ``(trajectory, time)``: ``e_i, s, v, sigma, phi, mode``.

        Samples after an incomplete trajectory's stop are NaN (mode 0), as in ``z``.

        Raises
        ------
        ImportError
            Without pandas (``pip install 'symbolic-friction[pandas]'``).
        """
        pd = optional("pandas", "pandas")
        N, m = self.mode.shape
        cols = {k: v.reshape(N * m) for k, v in solution_columns(self.z, self.x, self.mode).items()}
        index = pd.MultiIndex.from_product([np.arange(N), self.t], names=["trajectory", "time"])
        frame = pd.DataFrame(cols, index=index)
        frame.attrs.update({"params": str(self.params), "method": self.method})
        return frame

    def to_xarray(self) -> Any:
        """An ``xarray.Dataset`` on ``(trajectory, time)``, with ``status``, ``n_events``, ``source`` per trajectory.

        Raises
        ------
        ImportError
            Without xarray (``pip install 'symbolic-friction[xarray]'``).
        """
        xr = optional("xarray", "xarray")
        cols = solution_columns(self.z, self.x, self.mode)
        data = {k: (("trajectory", "time"), v) for k, v in cols.items()}
        data.update(status=("trajectory", self.status.astype(str)), n_events=("trajectory", self.n_events),
                    source=("trajectory", self.source.astype(str)), t_stop=("trajectory", self.t_stop))
        return xr.Dataset(data, coords={"trajectory": np.arange(self.size), "time": self.t},
                          attrs={"params": str(self.params), "method": self.method})

    def plot(self, states: Any = ("s",), *, ax: Any = None, **kwargs: Any) -> Any:
        """Plot ``states`` of every trajectory against time; return the matplotlib Axes."""
        return state_axes(self.t, self.z, ax=ax, states=states, **kwargs)
