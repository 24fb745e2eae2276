"""Scenes: built-in scenes load, malformed scenes are rejected with the key
named, and outputs contain exactly what was asked for."""

import csv
from fractions import Fraction

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction.errors import SceneError
from symbolic_friction._studies.scenes import OUTPUTS, Scene, builtin_scenes, load_scene
from symbolic_friction._simulation.friction import InflatedCoulomb, Stribeck

BASE = """
t_end = 2
initial_states = [[0, 1, 0], ["0.1", "-0.5", "0.25"]]
outputs = ["trajectories", "events"]

[gains]
k_p = 3
k_i = 4
k_v = "6.4"
f_c = 1

[method]
name = "moreau"
h = 1e-2
"""


def scene(text=BASE, **replace):
    for old, new in replace.items():
        assert old in text, old
        text = text.replace(old, new)
    return Scene.from_text(text, source="test.toml", default_name="test")


def test_builtin_scenes_load():
    names = builtin_scenes()
    assert {"paper-a", "paper-b", "stribeck-hunting", "triple-root", "inflated-worst-case"} <= set(names)
    a = load_scene("paper-a")
    assert a.params == Parameters.table_i("a") and a.method == "event"
    assert a.initial_states[4] == (Fraction(1, 5), Fraction(0), Fraction(-3, 2))  # "0.2" stays exact
    assert isinstance(load_scene("stribeck-hunting").friction, Stribeck)
    assert isinstance(load_scene("inflated-worst-case").friction, InflatedCoulomb)
    assert load_scene("triple-root").params == Parameters(k_p=3, k_i=1, k_v=3)


def test_scene_from_path_and_defaults(tmp_path):
    path = tmp_path / "my-scene.toml"
    path.write_text(BASE)
    s = load_scene(path)
    assert s.name == "my-scene" and s.format == "csv" and s.samples is None
    assert s.knobs == (("h", 0.01),) and s.method_options == {"h": 0.01}
    assert s.t_end == 2 and s.initial_states[1] == (Fraction(1, 10), Fraction(-1, 2), Fraction(1, 4))


def test_physical_gains():
    text = BASE.replace('[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1', "[physical]\nm = 2\nk_p_bar = 6\nk_i_bar = 8\nk_d_bar = \"12.3\"\nalpha_v = \"0.5\"\nf_c_bar = 2")
    assert scene(text).params == Parameters.table_i("a")


def test_friction_and_v_hat_tables():
    s = scene(BASE + '\n[friction]\nlaw = "stribeck"\nf_s = "1.5"\nv_s = "0.1"\n')
    assert s.friction == Stribeck(f_s="1.5", v_s="0.1")
    s = scene(BASE + '\n[friction]\nlaw = "inflated"\nrho = "0.1"\nselection = "constant"\nd = 0\ne = "-0.1"\n')
    assert s.friction.selection == (0, Fraction(-1, 10))
    s = scene(BASE + '\n[friction]\nlaw = "coulomb"\n')
    assert s.friction is None
    s = scene(BASE.replace('"events"]', '"events", "V_hat"]') + "\n[v_hat]\nk1 = 1\nk2 = 2\nk3 = 3\nk4 = \"4.5\"\n")
    assert s.v_hat == (1, 2, 3, Fraction(9, 2))


MALFORMED = [
    # unknown keys, at every level, named with their dotted path
    ({"t_end = 2": "t_end = 2\ncolour = 1"}, r"colour: unknown key; expected one of name, description, t_end"),
    ({"k_p = 3": "k_p = 3\nk_d = 1"}, r"gains\.k_d: unknown key; expected one of k_p, k_i, k_v, f_c"),
    ({"h = 1e-2": "hh = 1e-2"}, r"method\.hh: unknown option for method 'moreau'; expected one of h, max_steps"),
    # missing keys
    ({"t_end = 2\n": ""}, r"t_end: missing key \(required\)"),
    ({"k_i = 4\n": ""}, r"gains\.k_i: missing key \(required\)"),
    ({'[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1': ""}, r"gains: missing table; give \[gains\]"),
    # wrong types
    ({"t_end = 2": 't_end = "soon"'}, r"t_end must be a decimal such as '6\.4' or a fraction such as '32/5'; got 'soon'"),
    ({"t_end = 2": "t_end = true"}, r"t_end: expected a number .*; got bool True"),
    ({'k_v = "6.4"': "k_v = [6.4]"}, r"gains\.k_v: expected a number .*; got list \[6\.4\]"),
    ({'outputs = ["trajectories", "events"]': 'outputs = "V"'}, r"outputs: expected a list of strings; got str 'V'"),
    ({"h = 1e-2": 'h = "tiny"'}, r"method\.h must be a decimal .*; got 'tiny'"),
    ({'name = "moreau"': "name = 3"}, r"method\.name: expected a string; got int 3"),
    ({"[method]": "method = 1\n[xmethod]"}, r"xmethod: unknown key"),
    ({"initial_states = [[0, 1, 0], [\"0.1\", \"-0.5\", \"0.25\"]]": "initial_states = [[0, 1]]"}, r"initial_states\[0\]: expected \[e_i, s, v\] \(3 numbers\); got 2 values"),
    ({"initial_states = [[0, 1, 0], [\"0.1\", \"-0.5\", \"0.25\"]]": "initial_states = []"}, r"initial_states: expected a non-empty list of \[e_i, s, v\]"),
    ({"initial_states = [[0, 1, 0], [\"0.1\", \"-0.5\", \"0.25\"]]": 'initial_states = [[0, "x", 0]]'}, r"initial_states\[0\]\[1\] must be a decimal"),
    ({"initial_states = [[0, 1, 0], [\"0.1\", \"-0.5\", \"0.25\"]]": 'initial_states = [[0, "inf", 0]]'}, r"initial_states\[0\]\[1\] must be finite; got 'inf'"),
    # bad values
    ({"t_end = 2": "t_end = -1"}, r"t_end: expected a number > 0; got -1"),
    ({"t_end = 2": "t_end = 2\nsamples = 1"}, r"samples: expected an integer ≥ 2; got int 1"),
    ({"h = 1e-2": "h = -1e-3"}, r"method: option h \(the step size\) must be finite and > 0; got h = -0\.001"),
    ({'name = "moreau"': 'name = "rk4"'}, r"method\.name: expected one of 'event', 'moreau', 'regularized', 'ivp-events'; got 'rk4'"),
    ({"k_i = 4": "k_i = 40"}, r"gains: Assumption 1 needs k_v·k_p > k_i; got 96/5 ≤ 40"),
    ({'outputs = ["trajectories", "events"]': 'outputs = ["movie"]'}, r"outputs\[0\]: expected one of 'trajectories', 'events', 'V', 'V_hat', 'distance', 'figure'; got 'movie'"),
    ({'outputs = ["trajectories", "events"]': 'outputs = ["V", "V"]'}, r"outputs: an output is listed twice"),
    ({'outputs = ["trajectories", "events"]': 'outputs = []'}, r"outputs: expected at least one of"),
    ({'outputs = ["trajectories", "events"]': 'outputs = ["V_hat"]'}, r"v_hat: missing table; the output \"V_hat\" needs \[v_hat\]"),
    ({"t_end = 2": 't_end = 2\nformat = "xlsx"'}, r"format: expected one of 'csv', 'npz'; got 'xlsx'"),
    ({"t_end = 2": 't_end = 2\nname = "a b"'}, r"name: expected letters, digits, '_', '\.' or '-' \(used in file names\); got 'a b'"),
    ({"[method]": '[physical]\nm = 1\n[method]'}, r"gains, physical: give the gains in one table only"),
]


@pytest.mark.parametrize("replace, match", MALFORMED, ids=[m for _, m in MALFORMED])
def test_malformed_scene_names_the_key(replace, match):
    with pytest.raises(SceneError, match=match):
        scene(**{old: new for old, new in replace.items()})


@pytest.mark.parametrize(
    "extra, match",
    [
        ('[friction]\nlaw = "sand"\n', r"friction\.law: expected one of 'coulomb', 'stribeck', 'inflated'; got 'sand'"),
        ('[friction]\nlaw = "stribeck"\nf_s = 2\n', r"friction\.v_s: missing key \(required\)"),
        ('[friction]\nlaw = "stribeck"\nf_s = 2\nv_s = 0\n', r"friction: v_s must be > 0; got v_s = 0"),
        ('[friction]\nlaw = "stribeck"\nf_s = 2\nv_s = 1\nmu = 1\n', r"friction\.mu: unknown key; expected one of law, f_s, v_s, viscous"),
        ('[friction]\nlaw = "inflated"\nrho = "-0.1"\n', r"friction: rho must be ≥ 0; got rho = -1/10"),
        ('[friction]\nlaw = "inflated"\nrho = "0.1"\nd = 0\n', r"friction\.d: only used with selection = \"constant\""),
        ('[friction]\nlaw = "inflated"\nrho = "0.1"\nselection = "constant"\nd = 0\n', r"friction\.e: missing key \(required by selection = \"constant\"\)"),
        ('[friction]\nlaw = "coulomb"\nrho = 1\n', r"friction\.rho: unknown key; expected one of law"),
        ("[v_hat]\nk1 = 1\nk2 = 1\nk3 = 1\n", r"v_hat\.k4: missing key \(required\)"),
        ("[v_hat]\nk1 = 1\nk2 = 1\nk3 = 1\nk4 = 0\n", r"v_hat\.k4: expected a number > 0; got 0"),
    ],
)
def test_malformed_tables(extra, match):
    with pytest.raises(SceneError, match=match):
        scene(BASE + "\n" + extra)


def test_friction_needs_moreau():
    text = BASE.replace('name = "moreau"\nh = 1e-2', 'name = "ivp-events"') + '\n[friction]\nlaw = "stribeck"\nf_s = 2\nv_s = 1\n'
    with pytest.raises(SceneError, match=r"friction\.law: the 'stribeck' law is simulated by method \"moreau\"; got method 'ivp-events'"):
        scene(text)
    with pytest.raises(SceneError, match=r"method\.friction: declare the friction law in the \[friction\] table"):
        scene(BASE.replace("h = 1e-2", "h = 1e-2\nfriction = 1"))


def test_knob_types():
    with pytest.raises(SceneError, match=r"method\.max_steps: expected an integer; got float 10\.5"):
        scene(BASE.replace("h = 1e-2", "h = 1e-2\nmax_steps = 10.5"))
    s = scene(BASE.replace('name = "moreau"\nh = 1e-2', 'name = "regularized"\nepsilon = "1e-3"\nlaw = "sat"'))
    assert dict(s.knobs) == {"epsilon": 1e-3, "law": "sat"}
    with pytest.raises(SceneError, match=r"method: option law must be one of 'tanh', 'sat'; got 'cubic'"):
        scene(BASE.replace('name = "moreau"\nh = 1e-2', 'name = "regularized"\nlaw = "cubic"'))


def test_direct_construction_is_validated():
    p = Parameters.table_i("a")
    with pytest.raises(SceneError, match=r"initial_states\[0\]: expected \(e_i, s, v\) \(3 numbers\); got \(1, 2\)"):
        Scene(name="x", params=p, initial_states=((1, 2),), t_end=1)
    with pytest.raises(SceneError, match=r"params: expected a Parameters instance; got dict"):
        Scene(name="x", params={}, initial_states=((0, 0, 0),), t_end=1)
    with pytest.raises(SceneError, match=r"friction: expected a FrictionLaw or None; got str"):
        Scene(name="x", params=p, initial_states=((0, 0, 0),), t_end=1, method="moreau", friction="stribeck")
    with pytest.raises(SceneError, match=r"v_hat: expected \(k1, k2, k3, k4\); got \(1, 2\)"):
        Scene(name="x", params=p, initial_states=((0, 0, 0),), t_end=1, v_hat=(1, 2))
    with pytest.raises(SceneError, match=r"method\.zz: unknown option for method 'moreau'"):
        Scene(name="x", params=p, initial_states=((0, 0, 0),), t_end=1, method="moreau", knobs=(("zz", 1),))
    with pytest.raises(SceneError, match=r"method: a knob is given twice"):
        Scene(name="x", params=p, initial_states=((0, 0, 0),), t_end=1, method="moreau", knobs=(("h", 0.1), ("h", 0.2)))
    s = Scene(name="x", params=p, initial_states=(("0.5", 0, 0),), t_end="1.5", method="moreau")
    assert s.initial_states == ((Fraction(1, 2), 0, 0),) and s.t_end == Fraction(3, 2)


def test_unknown_scene_and_bad_toml(tmp_path):
    with pytest.raises(SceneError, match=r"scene 'no-such-scene': no such file and no built-in scene of that name; built-in scenes: .*paper-a"):
        load_scene("no-such-scene")
    bad = tmp_path / "bad.toml"
    bad.write_text("t_end = = 3\n")
    with pytest.raises(SceneError, match=r"bad\.toml: not valid TOML: "):
        load_scene(bad)
    binary = tmp_path / "bin.toml"
    binary.write_bytes(b"\xff\xfe\x00t_end")
    with pytest.raises(SceneError, match=r"bin\.toml: not a UTF-8 text file"):
        load_scene(binary)


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def test_outputs_contain_what_was_asked(tmp_path):
    s = scene(BASE.replace('"events"]', '"events", "V", "distance"]').replace("t_end = 2", "t_end = 2\nsamples = 21"))
    result = s.run()
    files = result.write(tmp_path)
    assert [f.name for f in files] == ["test.csv", "test_events.csv"]
    rows = read_csv(tmp_path / "test.csv")
    assert list(rows[0]) == ["trajectory", "t", "mode", "e_i", "s", "v", "sigma", "phi", "V", "distance"]
    assert len(rows) == 2 * 21
    sol = result.solutions[1]
    mine = [r for r in rows if r["trajectory"] == "1"]
    assert np.array_equal([float(r["s"]) for r in mine], sol.z[:, 1])  # repr: lossless
    assert np.array_equal([float(r["V"]) for r in mine], sol.V)
    events = read_csv(tmp_path / "test_events.csv")
    assert [(float(e["t"]), int(e["mode_before"]), int(e["mode_after"])) for e in events if e["trajectory"] == "1"] == list(sol.events)
    # only events: no sample file
    only = scene(BASE.replace('outputs = ["trajectories", "events"]', 'outputs = ["events"]'))
    files = only.run().write(tmp_path / "only")
    assert [f.name for f in files] == ["test_events.csv"]


def test_npz_output(tmp_path):
    s = scene(BASE.replace('"events"]', '"events", "distance"]'))
    result = s.run()
    (path,) = result.write(tmp_path, fmt="npz")
    data = np.load(path)
    assert {"t_0", "z_0", "x_0", "mode_0", "distance_0", "events_0", "t_1", "initial_states", "status"} <= set(data.files)
    assert "V_0" not in data.files
    assert np.array_equal(data["z_1"], result.solutions[1].z)
    assert data["events_0"].shape == (len(result.solutions[0].events), 3)
    assert list(data["status"]) == [sol.status for sol in result.solutions]
    with pytest.raises(SceneError, match=r"format: expected one of 'csv', 'npz'; got 'xls'"):
        result.write(tmp_path, fmt="xls")


def test_every_output_name_is_documented():
    import symbolic_friction._studies.scenes as module

    for name in OUTPUTS:
        assert f'"{name}"' in module.__doc__


def test_more_malformed_values():
    with pytest.raises(SceneError, match=r"gains: expected a table; got int 3"):
        scene(BASE.replace('[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1', "").replace("t_end = 2", "t_end = 2\ngains = 3"))
    physical = "[physical]\nm = 0\nk_p_bar = 6\nk_i_bar = 8\nk_d_bar = 1\nf_c_bar = 2"
    with pytest.raises(SceneError, match=r"physical: the mass needs m > 0; got m = 0"):
        scene(BASE.replace('[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1', physical))
    with pytest.raises(SceneError, match=r"method\.law: expected a string; got int 3"):
        scene(BASE.replace('name = "moreau"\nh = 1e-2', 'name = "regularized"\nlaw = 3'))


def test_direct_construction_checks_every_field():
    p = Parameters.table_i("a")
    ok = {"name": "x", "params": p, "initial_states": ((0, 0, 0),), "t_end": 1}
    cases = [
        ({"initial_states": ()}, r"initial_states: expected a non-empty sequence of \(e_i, s, v\); got \(\)"),
        ({"samples": 1}, r"samples: expected an integer ≥ 2; got 1"),
        ({"t_end": 0}, r"t_end: expected a number > 0; got 0"),
        ({"method": "rk4"}, r"method\.name: expected one of 'event', 'moreau', 'regularized', 'ivp-events'; got 'rk4'"),
        ({"outputs": ("trajectories", "movie")}, r"outputs\[1\]: expected one of .*; got 'movie'"),
        ({"format": "xlsx"}, r"format: expected one of 'csv', 'npz'; got 'xlsx'"),
        ({"v_hat": (1, 1, 1, -1)}, r"v_hat\.k4: expected a number > 0; got -1"),
    ]
    for change, match in cases:
        with pytest.raises(SceneError, match=match):
            Scene(**{**ok, **change})



def test_a_scene_may_give_a_static_level_above_coulomb():
    text = BASE.replace('[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1', '[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1\nf_s = "1.2"')
    params = scene(text).params
    assert params.f_s == Fraction(6, 5) and params.stiction
    with pytest.raises(SceneError, match="f_s ≥ f_c"):
        scene(text.replace('f_s = "1.2"', 'f_s = "0.5"'))


def test_readme_documents_the_scene_format_of_the_module_docstring():
    """The scene file format is published in the user guide (docs/guide/simulation.md, formerly the README), word for
    word as in the module docstring."""
    from pathlib import Path

    import symbolic_friction._studies.scenes as scenes

    block = scenes.__doc__.split("unknown keys are errors)::\n\n", 1)[1].split("\nBuilt-in scenes", 1)[0]
    expected = "\n".join(line[4:] if line.startswith("    ") else line for line in block.rstrip("\n").splitlines())
    guide = (Path(__file__).resolve().parents[1] / "docs" / "guide" / "simulation.md").read_text(encoding="utf-8")
    assert "### Scene files" in guide and expected in guide


def test_a_scene_can_ask_for_reset_pid_and_only_the_event_method_takes_it():
    from symbolic_friction._infra.errors import SceneError
    from symbolic_friction._studies.scenes import Scene, load_scene

    scene = load_scene("reset-a")
    assert scene.params.reset_dwell == Fraction(1, 100)
    result = scene.run()
    events = result.solutions[0].events if hasattr(result, "solutions") else result.trajectories.events(0)
    assert any(e[1:] == (0, 0) for e in events)
    text = 't_end = 1\ninitial_states = [[0, 1, 0]]\n[gains]\nk_p = 3\nk_i = 4\nk_v = "6.4"\nf_c = 1\nreset_dwell = "1/100"\n'
    assert Scene.from_text(text).params.reset
    with pytest.raises(SceneError, match="reset PID is simulated by method"):
        Scene.from_text(text + '[method]\nname = "moreau"\n')
    with pytest.raises(SceneError, match="reset_dwell > 0"):
        Scene.from_text(text.replace('"1/100"', "0"))
    physical = ('t_end = 1\ninitial_states = [[0, 1, 0]]\n[physical]\nm = 2\nk_p_bar = 6\nk_i_bar = 8\nk_d_bar = "12.8"\n'
                'f_c_bar = 2\nreset_dwell = "1/50"\n')
    assert Scene.from_text(physical).params.reset_dwell == Fraction(1, 50)
