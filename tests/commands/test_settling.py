"""``symbolic-friction settling``: PID against reset PID on exact trajectories, the issue's Table I cases."""

from __future__ import annotations

import json

import pytest

from symbolic_friction._cli.main import main

A = ["--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"]
B = ["--k-p", "0.66", "--k-i", "0.08", "--k-v", "1.5", "--f-c", "1"]


def _json(capsys, argv):
    assert main(["settling", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_case_a_pid_does_not_settle_and_reset_does(tmp_path, capsys):
    out = _json(capsys, [*A, "--z0", "0,3,0", "--out", str(tmp_path)])
    assert set(out["pid"]) >= {"settling_time", "events", "resets", "overshoot", "hunting"}
    assert out["pid"]["settling_time"] is None and out["pid"]["resets"] == 0
    assert out["reset"]["settling_time"] is not None and out["reset"]["settling_time"] < 100
    assert out["reset"]["resets"] >= 20
    assert (tmp_path / out["figure"].rsplit("/", 1)[-1]).stat().st_size > 10_000
    assert not list(tmp_path.glob("*.tmp*"))


def test_case_b_without_events_reset_is_not_slower(capsys):
    out = _json(capsys, [*B, "--z0", "0,3,0", "--no-figure"])
    assert out["pid"]["events"] == 0 and out["reset"]["resets"] == 0
    assert out["reset"]["settling_time"] == out["pid"]["settling_time"]


def test_case_b_after_a_long_stick_reset_is_faster(capsys):
    out = _json(capsys, [*B, "--z0", "-5,0.3,1.2", "--no-figure"])
    assert 90 < out["pid"]["settling_time"] < 100
    assert out["reset"]["settling_time"] < out["pid"]["settling_time"] - 10
    assert out["reset"]["resets"] == 1


def test_with_stiction_both_hunt_on_the_proved_cycle(capsys):
    out = _json(capsys, [*A, "--f-s", "1.2", "--z0", "0,1,0", "--t-end", "100", "--no-figure"])
    assert out["pid"]["hunting"].startswith("cycle proven (σ* = 0.105045")
    assert out["reset"]["hunting"].startswith("cycle proven (σ* = 0.105045") and "stick-exit map" in out["reset"]["hunting"]


def test_text_output_names_both_controllers(capsys, tmp_path):
    assert main(["settling", *A, "--z0", "0,3,0", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "pid    settles not within t_end" in out and "reset  settles at t = " in out
    assert "reset settles where PID does not" in out


@pytest.mark.parametrize(
    "argv, says",
    [
        ([*A, "--tol", "2"], "--tol must lie in (0, 1)"),
        ([*A, "--z0", "1,2"], "takes three numbers"),
        ([*A, "--reset-dwell", "0"], "--reset-dwell must lie in (0,"),
        ([*A, "--t-end", "-1"], "--t-end must lie in"),
        ([*A, "--samples", "1"], "--samples must be an integer"),
        (["--k-p", "1", "--k-i", "4", "--k-v", "1", "--f-c", "1"], "Assumption 1"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(argv, says, capsys):
    try:
        rc = main(["settling", *argv, "--no-figure"])
    except SystemExit as exc:  # a usage error, from argparse
        rc = exc.code
    assert rc == 2
    err = capsys.readouterr().err
    assert says in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_contraction_writes_a_certificate_verify_proves(tmp_path, capsys):
    out = _json(capsys, [*A, "--no-figure", "--contraction", "--out", str(tmp_path)])
    c = out["contraction"]
    assert c["proved"] is True and c["rho"] == "458633/1000000"
    assert main(["verify", c["path"]]) == 0
    assert capsys.readouterr().out.startswith("PROVED ")


def test_contraction_says_why_there_is_none_with_real_roots(tmp_path, capsys):
    out = _json(capsys, [*B, "--no-figure", "--contraction", "--out", str(tmp_path)])
    assert out["contraction"]["path"] is None and "only real roots" in out["contraction"]["reason"]
    assert not list(tmp_path.iterdir())
