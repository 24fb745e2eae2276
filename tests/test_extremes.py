"""The extremes matrix (``_extremes.py``, ``symbolic-friction extremes``).

Every cell is classified against the 50-digit reference, and here each
classification is checked again, independently: every ``ok`` cell's
trajectory (kept by the forked child that made it) is compared with the
reference samples here, and each method's run is repeated on one cell and
must give that trajectory bit for bit; a ``refused`` cell's method is run
again and must raise or stop early; no cell is ``wrong``.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

import numpy as np
import pytest

import symbolic_friction._extremes as extremes_module
import symbolic_friction._simulation as simulation_module
from symbolic_friction._infra.errors import SimulationError
from symbolic_friction._extremes import (
    HUNG,
    OK,
    PROVED,
    REFUSED,
    WRONG,
    cells,
    claimed_error,
    classify_run,
    default_methods,
    run_extremes,
)
from symbolic_friction._simulation import Moreau, Status, simulate
from tests.computed_once import computed_once


@pytest.fixture(scope="module", autouse=True)
def references():
    """Each cell's 50-digit reference computed once for the module (a pure function of the cell; about 0.3 s each):
    the matrix computes them all, and the later runs of a few cells (``only=``) reuse them."""
    with computed_once(extremes_module, "_reference") as known:
        yield known


def _kept(runs: Path, cell: str, method: str) -> Path:
    """The file of the kept trajectory of ``method`` on the cell labelled ``cell`` (labels hold ``/`` and ``|``)."""
    key = hashlib.sha256("\0".join((cell, method)).encode()).hexdigest()[:24]
    return runs / f"{key}.npy"


@pytest.fixture(scope="module")
def runs(tmp_path_factory) -> Path:
    """Where the matrix's forked children leave each ``ok`` run's sampled trajectory (``result``)."""
    return tmp_path_factory.mktemp("extremes_runs")


@pytest.fixture(scope="module")
def result(runs):
    """The whole matrix, once for the module: about a minute alone (each cell's runs in a forked child), so the tests that
    use it are marked slow, which also hands this module out first (tests/conftest.py): started last, it was the
    suite's tail.

    Each child also saves its ``ok`` run's trajectory (the very array it classified) in ``runs``, so that
    test_each_classification_agrees_with_the_reference checks every ``ok`` run against the reference without
    making it a second time (the runs were a fifth of this module's CPU)."""
    real = extremes_module.classify_run

    def keeping(method, cell, ref):
        made = []

        def recording(*args, **kw):
            made.append(simulate(*args, **kw))
            return made[-1]

        with pytest.MonkeyPatch.context() as patch:  # in the forked child: its own copy of the module
            patch.setattr(simulation_module, "simulate", recording)
            outcome = real(method, cell, ref)
        if outcome.outcome == OK:
            np.save(_kept(runs, cell.label, outcome.method), made[-1].z)
        return outcome

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(extremes_module, "classify_run", keeping)
        return run_extremes()


def test_matrix_covers_the_hard_cases():
    labels = [c.label for c in cells()]
    assert "k_v k_p/k_i = 1+1e-12" in labels
    assert {c.group for c in cells()} == {
        "Routh boundary", "repeated roots", "stiff", "random admissible", "f_c", "|z0|", "long horizon",
    }
    # gains over 1e-4..1e4, Routh margins to 1 + 1e-9 and fast/slow ratios to 1e8
    random = [c for c in cells() if c.group == "random admissible"]
    assert len(random) >= 6 and all(c.params.k_v * c.params.k_p > c.params.k_i for c in random)
    assert min(c.params.k_v * c.params.k_p / c.params.k_i for c in random) < 1 + 1e-8
    assert "fast/slow 1e8, slow pair zeta 0.1" in labels
    fcs = [float(c.params.f_c) for c in cells()]
    assert min(fcs) == 1e-9 and max(fcs) == 1e9
    sizes = [max(abs(x) for x in c.z0) for c in cells()]
    assert min(sizes) == 1e-9 and max(sizes) == 1e9


@pytest.mark.slow
def test_every_cell_classified_and_none_silently_wrong(result):
    cols = len(default_methods()) + 1
    assert len(result.outcomes) == len(cells()) * cols
    assert result.silently_wrong == []
    assert {o.outcome for o in result.outcomes} <= {OK, PROVED, REFUSED, HUNG}
    assert all(o.reason for o in result.outcomes if o.outcome in (REFUSED, HUNG))
    assert result.seconds < 120  # the command's stated budget, on a shared 2-core machine
    assert "| stiff |" in result.report()


@pytest.mark.slow
def test_each_classification_agrees_with_the_reference(result, runs):
    methods = {m: m for m in default_methods()}
    names = {o.method: m for m in methods for o in result.outcomes if o.method.startswith(type(m).name)}
    # the runs are repeatable: each method again, here, on a cell every method simulates, bit for bit the
    # trajectory its forked child kept (so checking the kept ones below is checking the method's runs)
    again = next(c for c in cells() if c.label == "case (a), f_c = 1e3")
    for name, method in names.items():
        assert result.get(again.label, name).outcome == OK, name
        sol = simulate(again.params, again.z0, again.t_end, method=method, t_eval=result.references[again.label].times)
        assert np.array_equal(sol.z, np.load(_kept(runs, again.label, name))), name
    for cell in cells():
        ref = result.references[cell.label]
        for name, method in names.items():
            o = result.get(cell.label, name)
            if o.outcome == OK:
                # every ok run, the stiff cells' slow ones too (a repeat skipped them)
                z = np.load(_kept(runs, cell.label, name))
                assert z.shape == ref.z.shape, (cell.label, name)
                err = np.max(np.abs(z - ref.z)) / ref.scale
                assert err <= claimed_error(method), (cell.label, name, err)
                assert err == pytest.approx(o.error, rel=1e-6, abs=1e-300)
            elif o.outcome == REFUSED:
                try:
                    sol = simulate(cell.params, cell.z0, cell.t_end, method=method, t_eval=ref.times)
                except SimulationError:
                    continue
                assert sol.status not in Status.COMPLETE, (cell.label, name)


@pytest.mark.slow
def test_certify_bound_is_checked_along_the_reference(result):
    for cell in cells():
        o = result.get(cell.label, "certify")
        assert o.outcome == PROVED and 0 <= o.error <= 1, (cell.label, o)


@pytest.mark.slow
def test_a_silently_wrong_method_is_classified_wrong(result):
    # a Moreau run whose output is shifted by 1 % of the solution must be caught
    cell = cells()[0]
    ref = result.references[cell.label]

    class Shifted(Moreau):
        def _solve(self, *args, **kw):
            sol = super()._solve(*args, **kw)
            sol.trajectories.z[...] += 0.2 * ref.scale
            return sol

    o = classify_run(Shifted(), cell, ref)
    assert o.outcome == WRONG and "above its claim" in o.reason and o.error > 0.1


def test_a_run_without_an_answer_is_stopped_and_the_runs_after_it_are_still_made(monkeypatch):
    """A cell's runs share one forked child: a run that hangs past ``limit``, or ends its child, is ``no answer``
    with its reason, and a new child makes the runs after it."""
    import os
    import time

    from symbolic_friction._simulation import Regularized

    real = extremes_module.classify_run

    def flaky(method, cell, ref):
        if isinstance(method, Moreau):
            time.sleep(60)
        if isinstance(method, Regularized):
            os._exit(3)
        return real(method, cell, ref)

    monkeypatch.setattr(extremes_module, "classify_run", flaky)  # the forked children inherit it
    cell = next(c for c in cells() if c.label == "case (a), f_c = 1e3")
    out = extremes_module.classify_runs_limited(default_methods(), cell, extremes_module._reference(cell), limit=0.5)
    assert [o.outcome for o in out] == [OK, HUNG, HUNG, OK]
    assert "no answer within 0.5 s" in out[1].reason and "ended without an answer" in out[2].reason
    assert [o.method for o in out] == [extremes_module._name(m) for m in default_methods()]


def test_only_and_bad_group():
    # one method (the event kernel, the cheapest): the filter and certify=False are what is tested here, and the
    # fixture above has already run every method on these cells
    res = run_extremes(default_methods()[:1], only=["Routh boundary"], certify=False)
    assert len(res.cells) == 5 and len(res.outcomes) == 5 and all(o.method != "certify" for o in res.outcomes)
    with pytest.raises(SimulationError, match="no extreme cell matches"):
        run_extremes(only=["nothing"])


def test_claims():
    assert claimed_error(Moreau(h=1e-3)) == pytest.approx(0.1)
    assert claimed_error(Moreau(h=1e-6)) == pytest.approx(1e-3)
    assert math.isclose(claimed_error(default_methods()[0]), 1e-9)


def test_cli_writes_report_and_heat_map(tmp_path, capsys):
    from symbolic_friction._cli.main import main

    # the one cell of the f_c group that has a refusal (a whole group through the CLI: tests/test_hostile_options.py)
    assert main(["extremes", "--only", "case (a), f_c = 1e9", "--out", str(tmp_path), "--format", "svg"]) == 0
    out = capsys.readouterr().out
    assert "| f_c | case (a), f_c = 1e9 |" in out and "refused: option epsilon" in out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["extremes.md", "extremes_heatmap.png", "extremes_heatmap.svg"]


def test_cli_fails_on_a_silently_wrong_cell(tmp_path, monkeypatch, capsys):
    import symbolic_friction._extremes as ex
    from symbolic_friction._cli.main import main

    real = ex.classify_run

    def broken(method, cell, ref):
        o = real(method, cell, ref)
        return ex.Outcome(o.cell, o.method, WRONG, 0.5, o.claim, "made wrong on purpose") if o.method == "event" else o

    monkeypatch.setattr(ex, "classify_run", broken)
    assert main(["extremes", "--only", "case (a), f_c = 1e3", "--out", str(tmp_path)]) == 1
    assert "**WRONG** made wrong on purpose" in capsys.readouterr().out


def test_theta_knob():
    from symbolic_friction._extremes import _name

    half = Moreau(h=1e-3, theta=0.5)
    assert claimed_error(half) == pytest.approx(1e3 * 1e-6)  # θ = ½ claims its second order
    assert _name(half) == "moreau(h=0.001, theta=0.5)" and _name(Moreau(h=1e-3)) == "moreau(h=0.001)"
    assert default_methods(theta=0.5)[1].theta == 0.5
    res = run_extremes(only=["case (a), f_c = 1e3"], certify=False, theta=0.5)
    o = res.get("case (a), f_c = 1e3", "moreau(h=0.001, theta=0.5)")
    assert o.outcome == "ok" and o.error <= 1e-3


def test_cli_bad_theta(tmp_path, capsys):
    from symbolic_friction._cli.main import main

    assert main(["extremes", "--theta", "1.5", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "--theta must be in [1/2, 1]" in err and "1.5" in err and err.count("\n") == 1


def test_reasons_are_never_cut():
    from symbolic_friction._extremes import Extremes, Outcome

    cell = cells()[0]
    reason = "stiff gains for the explicit integrator DOP853: " + "spectral radius 1e+08 over t_end = 5 needs " * 5 + "END"
    report = Extremes(
        cells=(cell,), methods=("moreau",),
        outcomes=(Outcome(cell.label, "moreau", REFUSED, math.nan, 1.0, reason + "\nsecond line"),
                  Outcome(cell.label, "certify", PROVED, 0.5, 1.0, "kappa = 3.467")),
        seconds=0.0, reference_seconds=0.0,
    ).report()
    row = next(line for line in report.splitlines() if line.startswith("| ") and cell.label in line)
    assert f"refused: {reason} second line" in row  # whole, and the row stays one line


def test_repr_is_the_counts():
    from symbolic_friction._extremes import Extremes, Outcome

    cell = cells()[0]
    result = Extremes(cells=(cell,), methods=("moreau",),
                      outcomes=(Outcome(cell.label, "moreau", OK, 1e-9, 1.0),
                                Outcome(cell.label, "certify", PROVED, 0.5, 1.0, "kappa = 3.467")),
                      seconds=2.0, reference_seconds=1.0)
    assert repr(result) == "Extremes(1 cells × 2 columns: 1 ok, 1 proved; 2.0 s)"


def test_the_figure_s_groups_combine_into_the_whole_matrix():
    """The ``extremes`` figure runs one task per group; combined, the groups give the matrix's cells in order."""
    from symbolic_friction._extremes import Extremes, cells, combine_extremes

    order = cells()
    groups = list(dict.fromkeys(c.group for c in order))
    parts = [Extremes(tuple(c for c in order if c.group == g), ("m",), (), 1.0, 0.5) for g in reversed(groups)]
    whole = combine_extremes(parts)
    assert [c.label for c in whole.cells] == [c.label for c in order]
    assert whole.seconds == len(groups) and whole.reference_seconds == len(groups) / 2
    with pytest.raises(Exception, match="different methods"):
        combine_extremes([parts[0], Extremes(parts[1].cells, ("other",), (), 1.0, 0.5)])
