"""``symbolic-friction figures``: the registry, the files, and what the figures show."""

from pathlib import Path

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._studies.figures import (
    FIG3_HORIZON,
    FIG3_INITIAL_STATES,
    FIGURES,
    _pieces,
    available_figures,
    make_figures,
    register,
)
from symbolic_friction._cli.main import main

PNG = b"\x89PNG\r\n\x1a\n"
EXPECTED = [
    "fig3a_solutions.png",
    "fig3a_phase.png",
    "fig3a_V.png",
    "fig3b_solutions.png",
    "fig3b_phase.png",
    "fig3b_V.png",
    "fig2_region_R.png",
    "fig4_stribeck.png",
]


@pytest.mark.slow
def test_all_figures_are_written(tmp_path, capsys):
    # the paper's figures; figures registered by other modules may add files
    assert main(["figures", "--out", str(tmp_path), "--only", "fig2", "fig3a", "fig3b", "fig4"]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted(EXPECTED)
    for name in EXPECTED:
        data = (tmp_path / name).read_bytes()
        assert data[:8] == PNG and len(data) > 20_000
    assert capsys.readouterr().out.count("wrote ") == len(EXPECTED)
    assert {"fig2", "fig3a", "fig3b", "fig4"} <= set(available_figures())


def test_files_are_deterministic(tmp_path, sequential):
    first = make_figures(tmp_path / "1", ["fig2", "fig4"])
    # the second drawing of Fig. 2 and Fig. 4: the sequential run's, compared with the parallel run's below too
    second = sorted((p for p in sequential if p.name in ("fig2_region_R.png", "fig4_stribeck.png")), key=lambda p: p.name)
    assert [p.name for p in first] == ["fig2_region_R.png", "fig4_stribeck.png"] == [p.name for p in second]
    for a, b in zip(first, second):
        assert a.read_bytes() == b.read_bytes()


def test_registry_is_extensible(tmp_path):
    @register("test-extra", "a figure added by another module")
    def extra(out: Path) -> list[Path]:
        path = out / "extra.txt"
        path.write_text("drawn")
        return [path]

    try:
        assert "test-extra" in available_figures()
        assert make_figures(tmp_path, ["test-extra"]) == [tmp_path / "extra.txt"]
        with pytest.raises(ValueError, match="a figure named 'test-extra' is already registered"):
            register("test-extra", "again")(lambda out: [])
    finally:
        FIGURES.pop("test-extra")


def test_list_and_unknown(capsys, tmp_path):
    assert main(["figures", "--list"]) == 0
    out = capsys.readouterr().out
    for name in ("fig2", "fig3a", "fig3b", "fig4"):
        assert name in out
    assert main(["figures", "--out", str(tmp_path), "--only", "fig9"]) == 2
    assert "unknown figure(s) 'fig9'; available: fig3a, fig3b, fig2, fig4" in capsys.readouterr().err


def _stick_pieces(pieces):
    return [p for p in pieces if p.mode == 0 and p.t[-1] > p.t[0]]


def test_fig3a_shows_ramps_growing_sticks_and_a_nonincreasing_discontinuous_V():
    params = Parameters.table_i("a")
    pieces = _pieces(params, FIG3_INITIAL_STATES["a"][0], FIG3_HORIZON["a"])
    sticks = _stick_pieces(pieces)
    durations = [p.t[-1] - p.t[0] for p in sticks[:-1]]  # the last one is cut by the horizon
    assert len(durations) >= 3 and durations == sorted(durations)
    for p in sticks:
        assert np.all(p.z[:, 2] == 0) and np.ptp(p.z[:, 1]) == 0  # at rest
        slope = np.diff(p.z[:, 0]) / np.diff(p.t)
        assert np.allclose(slope, p.z[0, 1], rtol=1e-9, atol=1e-12)  # e_i ramps with slope s
        assert np.ptp(p.V) <= 1e-12 * p.V[0]  # V flat during stick
    # V is nonincreasing along every solution and jumps (down) somewhere
    jumps = 0
    for z0 in FIG3_INITIAL_STATES["a"]:
        ps = _pieces(params, z0, FIG3_HORIZON["a"])
        values = np.concatenate([p.V for p in ps])
        assert np.all(np.diff(values) <= 1e-9 * values[:-1])
        jumps += sum(nxt.V[0] < p.V[-1] * (1 - 1e-6) for p, nxt in zip(ps, ps[1:]))
    assert jumps >= 1


def test_fig3b_converges_without_further_sticking():
    params = Parameters.table_i("b")
    bound = float(params.f_c / params.k_i)
    for z0 in FIG3_INITIAL_STATES["b"]:
        pieces = _pieces(params, z0, FIG3_HORIZON["b"])
        assert len(_stick_pieces(pieces)) <= 1
        last = pieces[-1]
        assert last.mode != 0 and np.all(last.z[1:, 2] != 0)  # v never returns to 0
        assert abs(abs(last.z[-1, 0]) - bound) < 1e-2 and abs(last.z[-1, 1]) < 1e-3


def test_fig3b_highlights_a_solution_that_sticks():
    # the black (first) solution of Fig. 3b has a stick phase of several seconds, which the figure shades
    params = Parameters.table_i("b")
    sticks = _stick_pieces(_pieces(params, FIG3_INITIAL_STATES["b"][0], FIG3_HORIZON["b"]))
    assert len(sticks) == 1 and sticks[0].t[-1] - sticks[0].t[0] > 5.0


def test_fig3b_V_on_a_log_time_axis_shows_the_early_jumps():
    from symbolic_friction._studies.figures import FIG3_LOG_TIME

    params = Parameters.table_i("b")
    assert FIG3_LOG_TIME["b"]
    pieces = _pieces(params, FIG3_INITIAL_STATES["b"][3], FIG3_HORIZON["b"], log_from=1e-3)
    first = pieces[0]
    assert first.t[first.t > 0].min() <= 1.1e-3  # sampled densely from 1e-3 s on
    assert pieces[1].t[0] < 1.0 and pieces[1].V[0] < first.V[-1]  # a jump within the first second


def test_other_formats_on_request(tmp_path, capsys):
    assert main(["figures", "--out", str(tmp_path), "--only", "fig2", "--format", "pdf", "svg"]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["fig2_region_R.pdf", "fig2_region_R.png", "fig2_region_R.svg"]
    assert (tmp_path / "fig2_region_R.pdf").read_bytes()[:5] == b"%PDF-"
    assert b"<svg" in (tmp_path / "fig2_region_R.svg").read_bytes()[:2000]
    assert capsys.readouterr().out.count("wrote ") == 3
    again = make_figures(tmp_path / "again", ["fig2"], formats=("svg",))
    assert (tmp_path / "again" / "fig2_region_R.svg").read_bytes() == (tmp_path / "fig2_region_R.svg").read_bytes()
    assert main(["figures", "--out", str(tmp_path), "--only", "fig2", "--format", "gif"]) == 2
    assert "unknown figure format" in capsys.readouterr().err


# -- split figures and the parallel run (module-level task functions: the pool pickles them by name)
def _square(x):
    return x * x


def _slow(x):
    import time

    time.sleep(2.6)
    return x


def _fail(x):
    from symbolic_friction._infra.errors import SimulationError

    raise SimulationError(f"task {x} failed on purpose")


def _draw_numbers(out, results):
    path = out / "numbers.txt"
    path.write_text(" ".join(map(str, results)))
    return [path]


@pytest.fixture
def split_figure():
    from symbolic_friction._studies.figures import Task, register_split

    made = []

    def add(name, function, args, cost=1.0):
        register_split(name, "a split figure for the tests",
                       tasks=lambda: [Task(f"{name} {a}", function, (a,), cost=cost) for a in args], draw=_draw_numbers)
        made.append(name)

    yield add
    for name in made:
        FIGURES.pop(name, None)


class _Notes:
    """A stand-in for the progress bar: counts updates and keeps every note."""

    def __init__(self):
        self.count, self.notes = 0, []

    def update(self, n=1):
        self.count += n

    def note(self, text):
        self.notes.append(text)


PARALLEL_NAMES = ["fig4", "test-split", "fig2"]


@pytest.fixture(scope="module")
def sequential(tmp_path_factory):
    """The files of :data:`PARALLEL_NAMES` drawn one after the other (``test-split``: the squares of 1, 2, 3), once for
    the module: the parallel run must write the same files, and a second drawing of Fig. 2 and Fig. 4 the same bytes."""
    from symbolic_friction._studies.figures import Task, register_split

    register_split("test-split", "a split figure for the tests",
                   tasks=lambda: [Task(f"test-split {a}", _square, (a,), cost=1.0) for a in (1, 2, 3)], draw=_draw_numbers)
    try:
        return make_figures(tmp_path_factory.mktemp("sequential"), PARALLEL_NAMES, jobs=1)
    finally:
        FIGURES.pop("test-split", None)


def test_parallel_run_writes_the_files_of_the_sequential_run(tmp_path, split_figure, sequential):
    split_figure("test-split", _square, (1, 2, 3))
    names = PARALLEL_NAMES
    seq = sequential
    bar = _Notes()
    par = make_figures(tmp_path / "2", names, jobs=2, progress=bar)
    assert [p.name for p in seq] == [p.name for p in par] == ["fig4_stribeck.png", "numbers.txt", "fig2_region_R.png"]
    for a, b in zip(seq, par):
        assert a.read_bytes() == b.read_bytes()
    assert (tmp_path / "2" / "numbers.txt").read_text() == "1 4 9"  # results in task order, whatever finished first
    assert bar.count == 2 + 3  # one per unit: two whole figures, three tasks


def test_a_long_task_is_seen_running(tmp_path, split_figure):
    split_figure("test-slow", _slow, (7,))
    bar = _Notes()
    make_figures(tmp_path, ["test-slow"], jobs=2, progress=bar)
    running = [n for n in bar.notes if "running test-slow 7" in n]
    assert len(running) >= 2  # redrawn about every second while it runs: no silent gap


def test_a_failing_task_fails_the_run(tmp_path, split_figure):
    from symbolic_friction._infra.errors import SimulationError

    split_figure("test-fail", _fail, (5,))
    with pytest.raises(SimulationError, match="task 5 failed on purpose"):
        make_figures(tmp_path, ["test-fail", "fig2"], jobs=2)


def test_units_start_longest_first():
    from symbolic_friction._studies.figures_run import units

    specs = available_figures()
    order = [u.label for u in units([specs[n] for n in ("fig2", "crosscheck_iss", "extremes", "fig3a")])]
    # the ISS selection searches (cost 20 each) first, then the extremes matrix's groups (7 each), fig2 last
    assert order[0].startswith("crosscheck_iss search") and order[-1] == "fig2"
    first_extremes = next(i for i, label in enumerate(order) if label.startswith("extremes ("))
    assert all(label.startswith("crosscheck_iss search") for label in order[:first_extremes])


@pytest.mark.parametrize("jobs", ["0", "65"])
def test_bad_jobs(tmp_path, capsys, jobs):
    # refused while the command line is parsed: one line, exit 2
    with pytest.raises(SystemExit) as exc:
        main(["figures", "--out", str(tmp_path), "--only", "fig2", "--jobs", jobs])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--jobs" in err and err.count("\n") == 1
