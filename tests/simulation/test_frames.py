"""Results in the scientific Python stack (``_simulation/_frames.py``): orientation, pandas, xarray, plots, reprs."""

from __future__ import annotations

import numpy as np
import pytest

from symbolic_friction import Parameters, simulate, simulate_batch
from symbolic_friction.errors import UsageError

CASE_A = Parameters.table_i("a")


@pytest.fixture(scope="module")
def batch():
    return simulate_batch(CASE_A, [(0, 1, 0), (0, -1.5, 0), (1, 1, 1)], 20)


def test_repr_is_a_summary(batch):
    # the dataclass repr printed every array (about 460 lines for one trajectory)
    text = repr(batch)
    assert "\n" not in text and len(text) < 200
    assert text.startswith("Trajectories(3 × ") and "method 'event'" in text and "3 complete" in text
    assert "\n" not in repr(batch.solution(0))


def test_states_in_python_controls_orientation(batch):
    assert batch.states.shape == (3, 3, batch.t.size)  # (n_states, n_traces, n_times)
    np.testing.assert_array_equal(batch.states[1, 2], batch.z[2, :, 1])
    assert np.shares_memory(batch.states, batch.z)  # a view: nothing copied, the (N, m, 3) arrays unchanged
    sol = batch.solution(1)
    assert sol.states.shape == (3, sol.t.size) and sol.time is sol.t
    np.testing.assert_array_equal(sol.states[2], sol.z[:, 2])


def test_solution_to_pandas_and_xarray(batch):
    sol = batch.solution(0)
    frame = sol.to_pandas()
    assert frame.index.name == "time" and list(frame.columns) == ["e_i", "s", "v", "sigma", "phi", "mode"]
    np.testing.assert_array_equal(frame["phi"].to_numpy(), sol.x[:, 1])
    assert frame.attrs["method"] == "event" and frame.attrs["status"] == "t_end reached"
    pytest.importorskip("xarray")
    data = sol.to_xarray()
    np.testing.assert_array_equal(data["v"].to_numpy(), sol.z[:, 2])
    assert data.attrs["params"] == str(CASE_A)


def test_trajectories_to_pandas_and_xarray(batch):
    frame = batch.to_pandas()
    assert frame.index.names == ["trajectory", "time"] and len(frame) == batch.size * batch.t.size
    np.testing.assert_array_equal(frame.loc[2]["s"].to_numpy(), batch.z[2, :, 1])
    pytest.importorskip("xarray")
    data = batch.to_xarray()
    assert data["s"].dims == ("trajectory", "time") and list(data["status"].values) == ["t_end reached"] * 3
    np.testing.assert_array_equal(data["e_i"].sel(trajectory=1).to_numpy(), batch.z[1, :, 0])


def test_plots_return_axes(batch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.axes import Axes

    ax = batch.plot()
    assert isinstance(ax, Axes) and len(ax.get_lines()) == 3 and ax.get_ylabel() == "position s"
    ax = simulate(CASE_A, (0, 1, 0), 5).plot(ax=ax)  # into given Axes
    assert len(ax.get_lines()) == 6
    with pytest.raises(UsageError, match=r"states must name some of e_i, s, v; got \('x',\)"):
        batch.plot("x")
    plt.close("all")
