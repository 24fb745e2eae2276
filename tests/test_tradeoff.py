"""The speed/accuracy trade (``_tradeoff.py``, ``symbolic-friction tradeoff``)."""

from __future__ import annotations

import json
import math

import pytest

from symbolic_friction import Parameters
from symbolic_friction._infra.errors import UsageError
from symbolic_friction._simulation import EventDriven, IvpEvents, Moreau
from symbolic_friction._studies.tradeoff import Sweep, fit_order, measure_tradeoff, tradeoff_figures
from symbolic_friction._cli.main import main

A = Parameters.table_i("a")


@pytest.fixture(scope="module")
def small():
    sweeps = [
        Sweep("event", (EventDriven(),)),
        Sweep("moreau", tuple(Moreau(h=h) for h in (1e-1, 1e-2, 1e-3))),
        Sweep("moreau theta=0.5", tuple(Moreau(h=h, theta=0.5) for h in (1e-1, 3e-2, 1e-2, 3e-3)), 2.0),
        Sweep("ivp-events", tuple(IvpEvents(rtol=r, atol=r * 1e-3) for r in (1e-4, 1e-7, 1e-10))),
    ]
    return measure_tradeoff(A, [(0.0, 1.0, 0.0)], 10.0, label="case (a)", samples=101, repeats=3, sweeps=sweeps)


def test_errors_orders_and_ratio(small):
    ev = small.event
    assert ev.error_state < 1e-12 and ev.error_stick < 1e-10  # exact against the 50-digit reference
    moreau = next(c for c in small.curves if c.label == "moreau")
    assert 0.8 < moreau.fitted_order < 1.2  # Moreau is first order in h, as declared
    errs = [p.error_state for p in moreau.points]
    assert errs == sorted(errs, reverse=True)
    half = next(c for c in small.curves if c.label == "moreau theta=0.5")
    assert 1.9 < half.fitted_order < 2.1 and half.declared_order == 2.0  # the θ-method at θ = ½ is second order
    assert half.points[2].error_state <= 5e-5 and half.points[2].config == "moreau(h=0.01, theta=0.5)"
    eq = small.equal_error()
    assert eq["levels"] and all(lvl["ratio"] > 0 for lvl in eq["levels"])
    note = small.note()
    assert "Pareto points" in note and "fitted orders: moreau" in note and "faster" in note
    assert "event" in small.table() and "declared 1" in small.table()


def test_a_wrong_method_shows_a_large_error(small, monkeypatch):
    # the error is measured, not assumed: shift the event method's output and see it
    import symbolic_friction._simulation.event as event

    solve = event.EventDriven._solve

    def shifted(self, *args, **kw):
        sol = solve(self, *args, **kw)
        sol.trajectories.z[...] += 1e-3
        return sol

    monkeypatch.setattr(event.EventDriven, "_solve", shifted)
    bad = measure_tradeoff(A, [(0.0, 1.0, 0.0)], 10.0, samples=51, repeats=1, sweeps=[Sweep("event", (EventDriven(),))])
    assert bad.event.error_state > 1e-4


def test_fit_order_ignores_the_rounding_floor():
    assert fit_order([1e-1, 1e-2, 1e-3], [1e-2, 1e-4, 1e-6])[0] == pytest.approx(2.0)
    assert fit_order([1e-1, 1e-2, 1e-3], [1e-2, 1e-13, 1e-14]) == (None, 1)


def test_refusal_is_reported_not_measured():
    res = measure_tradeoff(A, [(0.0, 1.0, 0.0)], 1.0, samples=11, repeats=1, sweeps=[Sweep("moreau", (Moreau(h=2.0),))])
    p = res.curves[0].points[0]
    assert not p.ok and "larger than the horizon" in p.refused and math.isnan(p.error_state)


def test_bad_input():
    with pytest.raises(UsageError, match="at least one initial state"):
        measure_tradeoff(A, [], 1.0)
    with pytest.raises(UsageError, match="three finite numbers"):
        measure_tradeoff(A, [(0.0, math.inf, 0.0)], 1.0)


def test_figures_in_three_formats(small, tmp_path):
    files = tradeoff_figures(small, tmp_path, "t", ("png", "pdf", "svg"))
    assert sorted(f.name for f in files) == ["t_pareto.pdf", "t_pareto.png", "t_pareto.svg"]
    assert (tmp_path / "t_pareto.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_user_gains_json(tmp_path, capsys):
    argv = ["tradeoff", "--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--t-end", "5", "--quick",
            "--no-cost", "--repeats", "1", "--samples", "51", "--json", "--out", str(tmp_path)]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["params"]["k_v"] == "32/5"  # read exactly, as certify reads it
    labels = [c["label"] for c in data["curves"]]
    assert labels == ["event", "moreau", "moreau theta=0.5", "regularized tanh", "regularized sat", "ivp-events"]
    assert (tmp_path / "tradeoff_user_pareto.png").exists()


def test_cli_errors(capsys):
    assert main(["tradeoff", "--case", "a", "--k-p", "1", "--k-i", "1", "--k-v", "2", "--f-c", "1"]) == 2
    assert "not both" in capsys.readouterr().err
    assert main(["tradeoff", "--z0", "1,2"]) == 2
    assert "three numbers" in capsys.readouterr().err
    assert main(["tradeoff", "--format", "gif"]) == 2
    assert "unknown figure format" in capsys.readouterr().err


def test_default_sweeps_one_moreau_curve_per_theta():
    from symbolic_friction._studies.tradeoff import default_sweeps

    sweeps = {s.label: s for s in default_sweeps(quick=True, thetas=(1, 0.75, 0.5, 0.5))}
    assert [k for k in sweeps if k.startswith("moreau")] == ["moreau", "moreau theta=0.75", "moreau theta=0.5"]
    assert sweeps["moreau theta=0.5"].declared_order == 2.0 and sweeps["moreau theta=0.75"].declared_order == 1.0
    assert all(m.theta == 0.75 for m in sweeps["moreau theta=0.75"].methods)


def test_bad_theta_is_refused_before_the_reference(capsys, monkeypatch):
    import symbolic_friction._studies.tradeoff as tradeoff
    from symbolic_friction._infra.errors import SimulationError

    monkeypatch.setattr(tradeoff, "_reference", lambda *a, **k: pytest.fail("the reference ran"))
    with pytest.raises(SimulationError, match=r"theta.*\[1/2, 1\].*0\.4"):
        measure_tradeoff(A, [(0.0, 1.0, 0.0)], 1.0, thetas=(0.4,))
    for bad in ("0.4", "1.0001", "nan", "x"):
        assert main(["tradeoff", "--theta", bad, "--no-figures"]) == 2
        err = capsys.readouterr().err
        assert "--theta" in err and err.count("\n") == 1


def test_repr_is_a_summary(small):
    text = repr(small)
    assert "\n" not in text and len(text) < 200 and text.startswith("Tradeoff('")
    assert f"{len(small.curves)} methods" in text
