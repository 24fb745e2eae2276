"""The settling-ratio map and the stiction table (`_studies.settling_map`, `_studies.settling_map_plot`): reset PID
against the paper's PID over gains, never slower, and hunting that resets cannot remove."""

from __future__ import annotations

import json
import math
from fractions import Fraction as F

import pytest

from symbolic_friction._infra.errors import ParameterError
from symbolic_friction._studies.settling_map import (
    SettlingCell,
    log_gains,
    settling_ratio_map,
    stiction_table,
)
from symbolic_friction._studies.settling_map_plot import (
    plot_settling_map,
    write_settling_map_figure,
)

# k_p, k_i where both controllers settle with Coulomb friction by t_end = 200; one cell with f_s/f_c = 1.2 is a
# PID run that looks settled on [0, 200] inside a long stick, and reset PID's run shows its next slip leaving
K_P = (F(1221, 200), F(10))
K_I = (F(1389, 1000), F(569, 250))


@pytest.fixture(scope="module")
def grid():
    return settling_ratio_map(k_p=K_P, k_i=K_I, samples=2001)


def test_log_gains_are_exact_and_span_the_range():
    axis = log_gains()
    assert len(axis) == 8 and all(isinstance(q, F) for q in axis)
    assert axis[0] == F("0.3162") and axis[-1] == 10
    assert list(axis) == sorted(axis)
    assert log_gains(1, lo=0) == (F(1),)


def test_the_grid_has_every_cell_with_the_routh_margin(grid):
    assert len(grid.cells) == 2 * len(K_P) * len(K_I)
    assert grid.f_s_ratios == (1, F(6, 5)) and grid.margin == 2
    for c in grid.cells:
        assert c.k_v * c.k_p / c.k_i == 2
        assert c.same_exits, c  # the stick exits of PID are the first of reset PID's (the key fact)
        assert c.reset_exits >= c.pid_exits
    assert grid.grid(1).shape == (len(K_I), len(K_P))
    assert grid.resolution == pytest.approx(0.1)


def test_reset_is_never_slower_on_the_grid(grid):
    """The ratio PID / reset is ≥ 1 everywhere, up to the settling-time resolution."""
    assert grid.slower == ()
    for c in grid.cells:
        assert c.reset_time is not None, c  # reset PID reaches the level in every cell of this grid
        if c.pid_time is not None:
            assert c.pid_time >= c.reset_time - grid.resolution, c
            assert c.ratio >= 1 - grid.resolution / c.reset_time
        else:
            assert c.ratio == math.inf


def test_coulomb_both_settle_and_reset_is_strictly_faster(grid):
    cells = grid.cells_at(1)
    assert all(c.criterion == "tol" and c.level == pytest.approx(3e-6) for c in cells)
    assert all(c.pid_time is not None and c.ratio > 1 for c in cells)
    assert all(c.resets > 0 and c.hunting.startswith("no (f_s = f_c") for c in cells)
    summary = grid.summary(1)
    assert summary["both"] == 4 and summary["neither"] == 0 and summary["min"] > 1


def test_stiction_measures_the_approach_to_the_hunting_cycle(grid):
    cells = grid.cells_at(F(6, 5))
    assert all(c.criterion == "band" and c.hunting.startswith("cycle found, not proven") for c in cells)
    # neither settles to the tolerance: both end on the cycle, |s(t_end)| near a* = level/1.1
    assert all(c.reset_final > 3e-6 and c.pid_final > 3e-6 for c in cells)
    refuted = [c for c in cells if c.pid_refuted]
    assert [(c.k_p, c.k_i) for c in refuted] == [(F(10), F(569, 250))]
    assert refuted[0].pid_time is None and refuted[0].ratio == math.inf


def test_the_refutation_is_needed_there():
    """Without it PID would look faster: inside a stick at t_end with |s| below the band, which its next slip leaves."""
    m = settling_ratio_map(k_p=[10], k_i=[F(569, 250)], f_s_ratios=[F(6, 5)], samples=2001)
    c = m.cells[0]
    assert c.pid_refuted and c.pid_final < c.level and m.slower == ()


def test_as_dict_is_json(grid):
    data = json.loads(json.dumps(grid.as_dict()))
    assert data["k_p"] == ["1221/200", "10"] and data["margin"] == "2" and data["slower"] == []
    assert len(data["cells"]) == 8 and {s["f_s_ratio"] for s in data["summary"]} == {"1", "6/5"}
    inf = [c for c in data["cells"] if c["ratio"] == "inf"]
    assert len(inf) == 1 and inf[0]["pid_refuted"] is True


def test_a_cell_without_reset_settling_has_no_ratio():
    cell = SettlingCell(k_p=F(1), k_i=F(1), k_v=F(2), f_s_ratio=F(1), criterion="tol", level=1e-6, pid_time=None,
                        reset_time=None, pid_final=1.0, reset_final=1.0, resets=0, hunting="")
    assert cell.ratio is None and cell.as_dict()["ratio"] is None


def test_table_i_a_reset_settles_pid_does_not():
    m = settling_ratio_map(k_p=[3], k_i=[4], margin="4.8", f_s_ratios=[1], samples=2001)
    c = m.cells[0]
    assert c.k_v == F(32, 5)
    assert c.pid_time is None and 2e-3 < c.pid_final < 4e-3
    assert 70 < c.reset_time < 72 and c.ratio == math.inf


@pytest.mark.parametrize("kwargs, match", [
    ({"margin": 1}, "Routh margin"),
    ({"band": "0.9"}, "band must be"),
    ({"f_s_ratios": ["0.5"]}, "f_s/f_c must be ≥ 1"),
    ({"f_s_ratios": []}, "f_s/f_c must be ≥ 1"),
    ({"z0": (1, 2)}, "three numbers"),
    ({"k_p": []}, "at least one value"),
    ({"points": 0}, "positive integer"),
])
def test_bad_options_are_refused(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        settling_ratio_map(**kwargs)


def test_the_heat_map_is_written_atomically(grid, tmp_path):
    fig = plot_settling_map(grid)
    assert len(fig.axes) == 3  # two panels and the colour bar
    texts = [t.get_text() for t in fig.axes[1].texts]
    assert len(texts) == 4 and sum(t.startswith(">") for t in texts) == 1
    out = tmp_path / "map" / "settling_map.png"
    write_settling_map_figure(grid, out)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert [p.name for p in out.parent.iterdir()] == ["settling_map.png"]  # no temporary left behind


def test_the_stiction_table_keeps_the_cycle_for_reset_pid():
    table = stiction_table([F(6, 5)], ["a"])
    (entry,) = table.entries
    assert entry.pid_proved and entry.reset_proved
    assert "σ* = 0.105045" in entry.pid and "stick-exit map" in entry.reset
    assert "| (a) | 1.2 | cycle proven" in table.markdown()
    assert json.loads(json.dumps(table.as_dict()))["entries"][0]["reset_proved"] is True
    found = stiction_table([2], ["b"], prove=False).entries[0]
    assert found.pid.startswith("cycle found, not proven") and not found.pid_proved


def test_the_stiction_table_refuses_coulomb():
    with pytest.raises(ParameterError, match="must be > 1"):
        stiction_table([1])
