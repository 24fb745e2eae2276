"""``symbolic-friction map``."""

from __future__ import annotations

import json

import pytest

from symbolic_friction._cli.main import main

GRID = ["--k-p", "0.2:5:6:log", "--k-i", "0.5:8:5", "--k-v", "2", "--chunk", "7"]


def test_a_grid_writes_the_datasets_and_the_heat_map(tmp_path, capsys):
    out = tmp_path / "m"
    assert main(["map", *GRID, "--out", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("30 points (5 chunks computed, 0 already done)") and "0 not proved" in lines[0]
    assert lines[1].startswith("κ from ")
    assert (out / "kappa.png").read_bytes()[:4] == b"\x89PNG"
    # the same command again: every chunk is found finished
    assert main(["map", *GRID, "--out", str(out), "--json", "--no-plot"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert (summary["computed"], summary["skipped"], summary["points"]) == (0, 5, 30)
    assert summary["files"] == [str(out / "map.csv"), str(out / "map.nc")]


def test_workers_and_a_sample(tmp_path, capsys):
    argv = ["map", "--k-p", "0.1:10:log", "--k-i", "0.1:10:log", "--k-v", "3", "--sample", "40", "--chunk", "10",
            "--workers", "2", "--out", str(tmp_path / "s"), "--format", "csv", "--json", "--plot", "k_i,k_p"]
    assert main(argv) == 0
    summary = json.loads(capsys.readouterr().out)
    assert sum(summary["counts"].values()) == 40 and summary["files"][-1].endswith("kappa.png")


def test_a_physical_grid(tmp_path, capsys):
    argv = ["map", "--m", "2", "--k-p-bar", "2:20:4", "--k-i-bar", "1:30:3", "--k-d-bar", "12.3", "--f-c-bar", "2",
            "--out", str(tmp_path / "p"), "--json"]
    assert main(argv) == 0
    counts = json.loads(capsys.readouterr().out)["counts"]
    assert counts == {"proved": 10, "not_proved": 0, "outside_assumption_1": 2}  # k_v·k_p ≤ k_i at k̄_p = 2, k̄_i ≥ 15.5


@pytest.mark.parametrize(
    "argv, message",
    [
        ([], "give the axes"),
        (["--k-p", "1:2:3"], "a normalised map needs k_i, k_v"),
        (["--k-p", "x", "--k-i", "1", "--k-v", "1"], "--k-p must be a decimal"),
        (["--k-p", "1:2:4000", "--k-i", "1:2:4000", "--k-v", "1"], "at most 10,000,000 points"),
        (["--k-p", "1:2:3", "--k-i", "1:2:3", "--k-v", "1", "--plot", "k_p,k_v"], "--plot needs two different ranged axes"),
        (["--k-p", "1:2:3", "--k-i", "1", "--k-v", "1"], "a heat map needs two ranged axes"),
        (["--k-p", "1:2:3", "--k-i", "1:2:3", "--k-v", "1", "--sample", "-1"], "--sample must be an integer from 0 to 10000000"),
        (["--k-p", "1:2:3", "--k-i", "1:2:3", "--k-v", "1", "--workers", "0"], "--workers must be an integer from 1 to 256"),
        (["--k-p", "1:2", "--k-i", "1:2", "--k-v", "1", "--sample", "5", "--chunk", "0"], "--chunk must be an integer from 1 to 1000000"),
        (["--k-p", "1:2", "--k-i", "1:2", "--k-v", "1", "--sample", "٣"], "ASCII digits"),
    ],
)
def test_bad_input_exits_2_with_one_line(argv, message, tmp_path, capsys):
    try:
        code = main(["map", *argv, "--out", str(tmp_path / "m")])
    except SystemExit as exc:  # refused by the argument parser itself
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("symbolic-friction map: error:") and message in err
    assert not (tmp_path / "m").exists()


def test_another_spec_on_the_same_directory_exits_2(tmp_path, capsys):
    out = str(tmp_path / "m")
    assert main(["map", *GRID, "--out", out, "--no-plot"]) == 0
    capsys.readouterr()
    assert main(["map", *GRID[:-1], "8", "--out", out, "--no-plot"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "holds chunks of a different map" in err


def test_scheduler_without_dask_exits_2_naming_the_extra(tmp_path, capsys, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "dask.distributed", None)  # as if the [dask] extra were not installed
    assert main(["map", *GRID, "--out", str(tmp_path / "m"), "--scheduler", "tcp://127.0.0.1:1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and 'pip install "symbolic-friction[dask]"' in err


def test_workers_and_scheduler_exclude_each_other(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["map", *GRID, "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"])
    assert exc.value.code == 2 and "not allowed with argument" in capsys.readouterr().err
