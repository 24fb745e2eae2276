"""Gain maps (`_studies.gainmap`, `_studies.gainmap_run`, `_studies.gainmap_plot`): points, verdicts, chunks, executors."""

from __future__ import annotations

import math
from concurrent.futures import ProcessPoolExecutor
from fractions import Fraction

import numpy as np
import pytest

from symbolic_friction import Parameters
from symbolic_friction._infra.errors import ParameterError, UsageError
from symbolic_friction._studies import gainmap, gainmap_point
from symbolic_friction._studies.gainmap import MapSpec, STATUS, evaluate_point, map_spec, normalised, parse_axis
from symbolic_friction._studies.gainmap_run import read_columns, run_map

SMALL = {"k_p": "0.2:5:6:log", "k_i": "0.5:8:5", "k_v": "2"}


def _same(a: dict, b: dict) -> None:
    assert list(a) == list(b)
    for name in a:
        np.testing.assert_array_equal(a[name], b[name])


# -- axes and specs ----------------------------------------------------------------------------------


def test_axis_texts_give_exact_points():
    lin = parse_axis("k_i", "1/3:2:6")
    assert [lin.value(j) for j in range(6)] == [Fraction(1, 3) + Fraction(5, 3) * Fraction(j, 5) for j in range(6)]
    log = parse_axis("k_p", "0.1:10:5:log")
    assert (log.value(0), log.value(2), log.value(4)) == (Fraction(1, 10), Fraction(1), Fraction(10))
    assert log.value(1) == Fraction("0.3162277660")  # SAMPLE_DIGITS significant digits
    fixed = parse_axis("k_v", "6.4")
    assert (fixed.lo, fixed.hi, fixed.ranged) == (Fraction(32, 5), Fraction(32, 5), False)
    drawn = parse_axis("k_p", "1:2", sample=True).draw(np.array([0.0, 0.25, 0.999999999999]))
    assert drawn == [1, Fraction(5, 4), 2]


@pytest.mark.parametrize(
    "name, text, sample, match",
    [
        ("k_p", "1:2", False, "needs its number of points"),
        ("k_p", "1:2:5", True, "draws its own points"),
        ("k_p", "1:2:1", False, "at least 2 points"),
        ("k_p", "2:1:5", False, "lo ≤ hi"),
        ("k_p", "1:1:5", False, "lo < hi"),
        ("k_p", "0:1:5:log", False, "log range needs 0 < lo"),
        ("k_p", "1:2:x", False, "must be an integer"),
        ("k_p", "1:2:3:4:5", False, "must be a value"),
        ("k_p", "nan:2:3", False, "finite"),
        ("k_p", "1e999:1e1000:3", False, "exponent|floating point"),
        ("k_x", "1", False, "unknown map axis 'k_x'"),
    ],
)
def test_bad_axis_texts_are_refused_by_name(name, text, sample, match):
    with pytest.raises(ParameterError, match=match):
        parse_axis(name, text, sample=sample)


@pytest.mark.parametrize(
    "values, options, match",
    [
        ({"k_p": "1", "k_i": "1"}, {}, "needs k_v"),
        ({"k_p": "1", "k_i": "1", "k_v": "2", "m": "1"}, {}, "not both"),
        ({"m": "1", "k_p_bar": "1", "k_i_bar": "1", "k_d_bar": "1"}, {}, "needs f_c_bar"),
        ({"k_p": "1", "k_i": "1", "k_v": "2", "f_c": "0"}, {}, "f_c must be positive"),
        ({"m": "0:1:3", "k_p_bar": "1", "k_i_bar": "1", "k_d_bar": "1", "f_c_bar": "1"}, {}, "m must be positive"),
        ({"m": "1", "k_p_bar": "1", "k_i_bar": "1", "k_d_bar": "1", "f_c_bar": "1", "alpha_v": "-1"}, {}, "alpha_v must be ≥ 0"),
        ({"k_p": "1", "k_i": "1", "k_v": "2", "f_c": "1:2:3", "f_s": "1.5"}, {}, "f_s ≥ f_c at every point"),
        ({"k_p": "1:2:4000", "k_i": "1:2:4000", "k_v": "2"}, {}, "at most 10,000,000 points; the grid 4000 \\(k_p\\) × 4000 \\(k_i\\) has 16,000,000"),
        ({"k_p": "1:2", "k_i": "1", "k_v": "2"}, {"sample": 10**7 + 1}, "at most 10,000,000 points"),
        ({"k_p": "1", "k_i": "1", "k_v": "2"}, {"chunk": 0}, "chunk must be an integer ≥ 1"),
        ({"k_p": "1", "k_i": "1", "k_v": "2"}, {"adversary": -1}, "adversary must be an integer ≥ 0"),
        ({"k_p": "1", "k_i": "1", "k_v": "2"}, {"mu": 0}, "mu must be positive"),
    ],
)
def test_bad_specs_are_refused_before_anything_is_allocated(values, options, match):
    with pytest.raises(ParameterError, match=match):
        map_spec(values, **options)


def test_the_digest_separates_specs_and_ignores_nothing_that_changes_a_point():
    base = map_spec(SMALL)
    assert base.digest() == map_spec(dict(SMALL)).digest()
    for other in (map_spec(SMALL, chunk=7), map_spec(SMALL, seed=1), map_spec({**SMALL, "k_v": "2.5"}),
                  map_spec(SMALL, mu=Fraction(1, 1000))):
        assert other.digest() != base.digest()


def test_normalisation_is_the_models():
    rng = np.random.default_rng(3)
    for _ in range(20):
        phys = {k: Fraction(int(v), 7) for k, v in zip(("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar"),
                                                       rng.integers(1, 200, 6))}
        g = normalised(phys)
        try:
            p = Parameters.from_physical(**phys)
        except ParameterError:
            assert not g["k_v"] * g["k_p"] > g["k_i"]
            continue
        assert (g["k_p"], g["k_i"], g["k_v"], g["f_c"]) == (p.k_p, p.k_i, p.k_v, p.f_c)


# -- one point -------------------------------------------------------------------------------------


def test_a_point_carries_the_verifiers_verdict_and_an_upper_bound_on_kappa():
    spec = map_spec({"k_p": "3", "k_i": "4", "k_v": "6.4"})
    row = evaluate_point(spec, {"k_p": Fraction(3), "k_i": Fraction(4), "k_v": Fraction(32, 5), "f_c": Fraction(1)})
    assert STATUS[row["status"]] == "proved"
    assert Fraction(row["kappa"]) >= Fraction("3.46703") and row["kappa"] == pytest.approx(3.46703, abs=1e-12)


def test_a_point_outside_assumption_1_is_marked_not_an_error():
    spec = map_spec({"k_p": "1", "k_i": "2", "k_v": "2"})
    row = evaluate_point(spec, {"k_p": Fraction(1), "k_i": Fraction(2), "k_v": Fraction(2), "f_c": Fraction(1)})
    assert STATUS[row["status"]] == "outside_assumption_1" and math.isnan(row["kappa"])


def test_a_wrong_closed_form_is_refused_by_the_verifier(monkeypatch):
    """The status is the exact verifier's: constants with k₃ a factor too small do not verify."""
    from dataclasses import replace

    from symbolic_friction._certify import closed_form

    real = closed_form.closed_form_constants
    monkeypatch.setattr(closed_form, "closed_form_constants", lambda *a, **k: replace(real(*a, **k), k3=real(*a, **k).k3 / 4))
    spec = map_spec({"k_p": "3", "k_i": "4", "k_v": "6.4"})
    row = evaluate_point(spec, {"k_p": Fraction(3), "k_i": Fraction(4), "k_v": Fraction(32, 5), "f_c": Fraction(1)})
    assert STATUS[row["status"]] == "not_proved" and math.isnan(row["kappa"])


def test_float_up_never_rounds_below_the_decimal():
    for text in ("3.46703", "0.1", "114.553", "1e-7", "123456789.123457"):
        f = gainmap_point.float_up(text)
        assert Fraction(f) >= Fraction(text) and math.nextafter(f, -math.inf) < Fraction(text)


@pytest.mark.slow
def test_sdp_adversary_and_hunting_columns():
    spec = map_spec({"k_p": "3", "k_i": "4", "k_v": "6.4", "f_s": "1.2"}, sdp=True, adversary=24)
    cols = gainmap.evaluate_chunk(spec, 0)
    assert STATUS[cols["status"][0]] == "proved"
    assert cols["kappa_sdp"][0] == pytest.approx(3.46703, abs=1e-5)
    assert 1.0 < cols["worst_overshoot"][0] < cols["kappa"][0]
    assert cols["tightness"][0] == pytest.approx(cols["worst_overshoot"][0] / cols["kappa"][0])
    assert cols["hunting_found"][0] >= 1 and cols["hunting_proved"][0] == cols["hunting_found"][0]


# -- runs: datasets, chunks, resumption, executors ---------------------------------------------------


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """An uninterrupted in-process run of a small grid (chunks of 7 points)."""
    spec = map_spec(SMALL, chunk=7)
    directory = tmp_path_factory.mktemp("ref") / "map"
    run = run_map(spec, directory, progress=False)
    return spec, directory, run, read_columns(directory, spec)


def test_a_run_counts_and_writes_both_datasets(reference):
    spec, directory, run, cols = reference
    assert run.computed == spec.chunks == 5 and run.skipped == 0
    assert sum(run.counts.values()) == spec.points == 30 and run.counts["not_proved"] == 0
    assert run.counts["outside_assumption_1"] == int(np.count_nonzero(2 * cols["k_p"] <= cols["k_i"]))
    assert sorted(p.name for p in directory.iterdir()) == ["chunks", "manifest.json", "map.csv", "map.nc"]


def test_the_csv_loads_in_one_line_with_pandas(reference):
    pd = pytest.importorskip("pandas")
    spec, directory, _, cols = reference
    df = pd.read_csv(directory / "map.csv")
    assert list(df.columns) == [name for name, _ in spec.columns()] and len(df) == spec.points
    np.testing.assert_array_equal(df["kappa"].to_numpy(), cols["kappa"])
    assert set(df["status"]) <= set(STATUS)


def test_the_netcdf_loads_in_one_line_with_xarray(reference):
    xr = pytest.importorskip("xarray")
    spec, directory, _, cols = reference
    ds = xr.open_dataset(directory / "map.nc")
    assert dict(ds.sizes) == {"k_p": 6, "k_i": 5}
    np.testing.assert_array_equal(ds["kappa"].values, cols["kappa"].reshape(6, 5))
    np.testing.assert_array_equal(ds["k_i"].values, cols["k_i"][:5])
    assert ds["status"].attrs["flag_meanings"] == " ".join(STATUS)
    ds.close()


def test_a_killed_run_loses_at_most_the_chunk_in_flight_and_resumes(reference, tmp_path, monkeypatch):
    spec, _, _, expected = reference
    real = gainmap.evaluate_chunk
    calls: list[int] = []

    def crash_on_the_third(spec, c):
        calls.append(c)
        if len(calls) == 3:
            raise KeyboardInterrupt  # the process dies between chunks 1 and 2
        return real(spec, c)

    monkeypatch.setattr(gainmap, "evaluate_chunk", crash_on_the_third)
    with pytest.raises(KeyboardInterrupt):
        run_map(spec, tmp_path / "m", progress=False)
    names = sorted(p.name for p in (tmp_path / "m" / "chunks").iterdir())
    assert names == ["chunk-000000.npz", "chunk-000001.npz"]  # no partial file
    assert not (tmp_path / "m" / "map.csv").exists()
    with pytest.raises(UsageError, match="chunk 2 of 5 is missing"):
        read_columns(tmp_path / "m", spec)
    calls.clear()
    monkeypatch.setattr(gainmap, "evaluate_chunk", lambda spec, c: calls.append(c) or real(spec, c))
    run = run_map(spec, tmp_path / "m", progress=False)
    assert calls == [2, 3, 4] and (run.computed, run.skipped) == (3, 2)
    _same(read_columns(tmp_path / "m", spec), expected)
    calls.clear()
    assert run_map(spec, tmp_path / "m", progress=False).computed == 0 and calls == []


def test_a_damaged_chunk_is_recomputed(reference, tmp_path):
    spec, _, _, expected = reference
    run_map(spec, tmp_path / "m", progress=False, formats=["csv"])
    (tmp_path / "m" / "chunks" / "chunk-000003.npz").write_bytes(b"not a chunk")
    run = run_map(spec, tmp_path / "m", progress=False, formats=["csv"])
    assert (run.computed, run.skipped) == (1, 4)
    _same(read_columns(tmp_path / "m", spec), expected)


def test_chunks_of_another_spec_are_never_mixed(reference, tmp_path):
    spec, directory, _, _ = reference
    with pytest.raises(UsageError, match="holds chunks of a different map"):
        run_map(map_spec(SMALL, chunk=8), directory, progress=False)
    (tmp_path / "notes.txt").write_text("mine")
    with pytest.raises(UsageError, match="not empty and holds no gain map"):
        run_map(spec, tmp_path, progress=False)
    (tmp_path / "x").mkdir()
    (tmp_path / "x" / "manifest.json").write_text("{")
    with pytest.raises(UsageError, match="is not a gain-map manifest"):
        run_map(spec, tmp_path / "x", progress=False)
    with pytest.raises(ParameterError, match="dataset formats are csv, netcdf; got 'parquet'"):
        run_map(spec, tmp_path / "y", progress=False, formats=["parquet"])


def test_a_process_pool_gives_the_same_map(reference, tmp_path):
    spec, _, _, expected = reference
    with ProcessPoolExecutor(2) as pool:
        run = run_map(spec, tmp_path / "m", executor=pool, progress=False)
    assert run.computed == spec.chunks
    _same(read_columns(tmp_path / "m", spec), expected)


def test_a_dask_local_cluster_gives_the_same_map(reference, tmp_path):
    distributed = pytest.importorskip("distributed", reason="dask.distributed is an optional extra ([dask])")
    spec, _, _, expected = reference
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            run = run_map(spec, tmp_path / "m", executor=client.get_executor(), progress=False)
    assert run.computed == spec.chunks
    _same(read_columns(tmp_path / "m", spec), expected)


def test_a_sample_is_reproducible_chunk_by_chunk(tmp_path):
    spec = map_spec({"k_p": "0.1:10:log", "k_i": "0.1:10:log", "k_v": "1:3"}, sample=25, chunk=10, seed=4)
    first = [gainmap.chunk_gains(spec, c) for c in range(spec.chunks)]
    assert [len(c) for c in first] == [10, 10, 5]
    assert gainmap.chunk_gains(spec, 1) == first[1]  # any chunk recomputed alone gives the same points
    for point in (p for chunk in first for p in chunk):
        for name in ("k_p", "k_i", "k_v"):
            a = spec.axis(name)
            assert a.lo <= point[name] <= a.hi
    assert gainmap.chunk_gains(map_spec({"k_p": "0.1:10:log", "k_i": "0.1:10:log", "k_v": "1:3"}, sample=25, chunk=10, seed=5), 0) != first[0]
    run = run_map(spec, tmp_path / "s", progress=False)
    assert sum(run.counts.values()) == 25
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(tmp_path / "s" / "map.nc") as ds:
        assert dict(ds.sizes) == {"point": 25}


def test_a_physical_grid_is_normalised_per_point(tmp_path):
    spec = map_spec({"m": "2", "k_p_bar": "2:20:4", "k_i_bar": "1:30:3", "k_d_bar": "12.3", "alpha_v": "0.5", "f_c_bar": "2"})
    run = run_map(spec, tmp_path / "p", progress=False, formats=["csv"])
    cols = read_columns(tmp_path / "p", spec)
    np.testing.assert_allclose(cols["k_v"], 6.4)
    np.testing.assert_allclose(cols["k_p"], cols["k_p_bar"] / 2)
    assert sum(run.counts.values()) == 12 and run.counts["not_proved"] == 0


def test_the_progress_bar_shows_points_per_second(tmp_path, monkeypatch):
    import io

    class Tty(io.StringIO):
        encoding = "utf-8"

        def isatty(self):
            return True

    stream = Tty()
    monkeypatch.setattr("sys.stderr", stream)
    run_map(map_spec(SMALL, chunk=10), tmp_path / "m", progress=True, formats=[])
    assert "pt/s" in stream.getvalue() and "30/30" in stream.getvalue()


# -- the heat map --------------------------------------------------------------------------------------


def test_the_heat_map_draws_kappa_and_the_assumption_1_boundary(reference, tmp_path, monkeypatch):
    from symbolic_friction._studies import gainmap_plot

    spec, directory, _, cols = reference
    drawn: list[bool] = []
    real = gainmap_plot._boundary
    monkeypatch.setattr(gainmap_plot, "_boundary", lambda *a: drawn.append(real(*a)) or drawn[-1])
    path = gainmap_plot.plot_map(spec, cols, tmp_path / "k.png", x="k_p", y="k_i")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and drawn == [True]
    with pytest.raises(ParameterError, match="'k_v' is not a ranged axis"):
        gainmap_plot.plot_map(spec, cols, tmp_path / "k.png", x="k_p", y="k_v")
    with pytest.raises(ParameterError, match="two different axes"):
        gainmap_plot.plot_map(spec, cols, tmp_path / "k.png", x="k_p", y="k_p")
    with pytest.raises(ParameterError, match="needs two ranged axes"):
        gainmap_plot.default_axes(map_spec({"k_p": "1:2:3", "k_i": "1", "k_v": "2"}))


def test_a_finished_map_reads_back_with_its_spec(reference, tmp_path):
    from symbolic_friction._studies.gainmap_run import read_map

    spec, directory, _, cols = reference
    again, columns = read_map(directory)
    assert again == spec and again.digest() == spec.digest()
    _same(columns, cols)
    with pytest.raises(UsageError, match="holds no gain map"):
        read_map(tmp_path)
    (tmp_path / "manifest.json").write_text('{"format": "symbolic-friction/gain-map/v1", "spec": {}}')
    with pytest.raises(UsageError, match="is not a gain-map manifest"):
        read_map(tmp_path)
    with pytest.raises(ParameterError, match="not a gain-map spec"):
        MapSpec.from_dict({"axes": []})


def test_the_tight_columns_are_default_certify_against_kappa_lin():
    """``tight``: κ of default certify per point, below the closed form's and above κ_lin's proven lower end."""
    from symbolic_friction._studies.gainmap import evaluate_point, map_spec
    from symbolic_friction._studies.gainmap_point import TIGHT_TEMPLATES

    spec = map_spec({"k_p": "1000", "k_i": "0.001", "k_v": "1000"}, tight=5.0)
    assert [c for c, _ in spec.columns()][-4:] == ["kappa_tight", "kappa_lin", "tight_ratio", "tight_template"]
    row = evaluate_point(spec, {a.name: a.lo for a in spec.axes})
    assert row["kappa_lin"] <= row["kappa_tight"] <= row["kappa"]
    assert row["kappa_tight"] < row["kappa"] / 1000  # the closed form is 31622.9 there, the sup-flow one piece 3.67
    assert TIGHT_TEMPLATES[row["tight_template"]] == "sup-flow"
    assert row["tight_ratio"] == row["kappa_tight"] / row["kappa_lin"]


def test_a_map_without_tight_keeps_its_digest():
    from symbolic_friction._studies.gainmap import MapSpec, map_spec

    spec = map_spec({"k_p": "1:3:2", "k_i": "1", "k_v": "2"})
    assert "tight" not in spec.to_dict()
    tight = map_spec({"k_p": "1:3:2", "k_i": "1", "k_v": "2"}, tight=1.5)
    assert tight.digest() != spec.digest() and MapSpec.from_dict(tight.to_dict()) == tight
    for bad in (-1.0, 601.0, True, "2"):
        with pytest.raises(Exception, match="tight must be seconds"):
            map_spec({"k_p": "1", "k_i": "1", "k_v": "2"}, tight=bad)
