"""``symbolic-friction simulate``: outputs, errors, and imports only what the scene needs."""

import csv
import json
import subprocess
import sys

import numpy as np
import pytest

from symbolic_friction._cli.main import main

HEAVY = ("sympy", "cvxpy", "scipy.integrate", "matplotlib")


def imported_after(argv):
    """Run the CLI in a fresh interpreter; return (exit code, heavy modules imported)."""
    code = (
        "import sys, json, contextlib, io\n"
        "from symbolic_friction._cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    rc = main({argv!r})\n"
        f"print(json.dumps([rc, sorted(m for m in {HEAVY!r} if m in sys.modules)]))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def test_event_scene_imports_nothing_heavy(tmp_path):
    assert imported_after(["simulate", "paper-a", "--out", str(tmp_path)]) == [0, []]
    assert (tmp_path / "paper-a.csv").is_file()


def test_the_import_check_can_fail(tmp_path):
    # the same probe sees matplotlib when a PNG is asked for, and scipy.integrate for a scipy method
    assert imported_after(["simulate", "paper-a", "--out", str(tmp_path), "--png"]) == [0, ["matplotlib"]]
    scene = tmp_path / "reg.toml"
    scene.write_text(
        't_end = 1\ninitial_states = [[0, 1, 0]]\n[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1\n'
        '[method]\nname = "regularized"\nepsilon = 1e-2\n'
    )
    assert imported_after(["simulate", str(scene), "--out", str(tmp_path)]) == [0, ["scipy.integrate"]]


def test_writes_csv_npz_and_png(tmp_path, capsys):
    assert main(["simulate", "triple-root", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "scene triple-root" in out and "trajectory 2:" in out and "wrote" in out
    with open(tmp_path / "triple-root.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert list(rows[0]) == ["trajectory", "t", "mode", "e_i", "s", "v", "sigma", "phi", "V", "distance"]
    assert len(rows) == 3 * 3001
    assert (tmp_path / "triple-root_events.csv").read_text().startswith("trajectory,t,mode_before,mode_after\n")
    assert "as csv" in out and "triple-root.csv (CSV)" in out
    assert main(["simulate", "triple-root", "--out", str(tmp_path), "--format", "npz", "--png"]) == 0
    out = capsys.readouterr().out
    # the summary and the closing lines name the format written, not the scene's default
    assert "as npz" in out and "as csv" not in out and "triple-root.npz (NPZ)" in out and "triple-root.png (PNG)" in out
    data = np.load(tmp_path / "triple-root.npz")
    assert data["z_0"].shape == (3001, 3) and data["t_0"][-1] == 30.0
    assert (tmp_path / "triple-root.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_list(capsys):
    assert main(["simulate", "--list"]) == 0
    out = capsys.readouterr().out
    assert "paper-a" in out and "stribeck-hunting" in out


@pytest.mark.parametrize(
    "text, message",
    [
        ("t_end = 1\n", "simulate: error: initial_states: missing key (required)"),
        ('t_end = 1\ninitial_states = [[0, 1, 0]]\nspeed = 2\n[gains]\nk_p = 1\nk_i = 1\nk_v = 2\nf_c = 1\n', "speed: unknown key"),
        ('t_end = 1\ninitial_states = [[0, 1, 0]]\n[gains]\nk_p = 1\nk_i = 1\nk_v = 2\nf_c = 1\n[method]\nname = "moreau"\nh = -1\n', "got h = -1.0"),
    ],
)
def test_malformed_scene_is_a_one_line_error(tmp_path, capsys, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["simulate", str(path), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_missing_and_unknown_scene(capsys):
    assert main(["simulate"]) == 2
    assert "no scene given; pass a .toml path or one of: " in capsys.readouterr().err
    assert main(["simulate", "paper-z"]) == 2
    assert "scene 'paper-z': no such file and no built-in scene of that name" in capsys.readouterr().err


def test_theta_option(tmp_path, capsys):
    scene = tmp_path / "m.toml"
    scene.write_text(
        't_end = 3\ninitial_states = [[0, 1, 0]]\n[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1\n'
        '[method]\nname = "moreau"\nh = 0.01\n'
    )
    assert main(["simulate", str(scene), "--out", str(tmp_path / "one")]) == 0
    assert main(["simulate", str(scene), "--out", str(tmp_path / "half"), "--theta", "1/2"]) == 0
    capsys.readouterr()
    from symbolic_friction import Parameters
    from symbolic_friction._simulation import simulate

    half = np.loadtxt(tmp_path / "half" / "m.csv", delimiter=",", skiprows=1, usecols=(3, 4, 5))
    one = np.loadtxt(tmp_path / "one" / "m.csv", delimiter=",", skiprows=1, usecols=(3, 4, 5))
    direct = simulate(Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1), (0, 1, 0), 3.0, method="moreau", h=0.01, theta=0.5)
    assert np.allclose(half, direct.z, rtol=1e-12, atol=1e-14) and not np.allclose(one, half, rtol=1e-6)


@pytest.mark.parametrize("scene, theta, message", [
    ("paper-a", "0.5", "--theta is a knob of method moreau; scene 'paper-a' uses method 'event'"),
    ("paper-a", "0.2", "--theta must be in [1/2, 1]"),
    ("paper-a", "x", "--theta"),
    ("stribeck-hunting", "0.5", "takes Coulomb friction only"),
])
def test_bad_theta_is_one_line_exit_2(tmp_path, capsys, scene, theta, message):
    assert main(["simulate", scene, "--out", str(tmp_path), "--theta", theta]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err
