"""The kernel-against-reference control of ``check``: it holds, its tolerances are pinned, and real mutants fail it.

Each mutant is a one-token change of the real source (the plain kernel's two
files, or the cross-check's ``∫ v²``), loaded as a module and put in place
of the original; ``kernel_rows`` (what ``check`` runs) must then report a
failing scenario.  Most of these changes are invisible at ``f_c = 1``, without
static friction, on a non-uniform grid, or away from the horizon.
"""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import numpy as np
import pytest

from symbolic_friction._crosscheck import _along, _kernel_check
from symbolic_friction._simulation import _jit

SIM = Path(_jit.__file__).parent


def _load(name: str, path: Path, replace: list[tuple[str, str]]) -> object:
    source = path.read_text(encoding="utf-8")
    for old, new in replace:
        assert source.count(old) == 1, (path.name, old)
        source = source.replace(old, new)
    spec = importlib.util.spec_from_loader(name, loader=None, origin=str(path))
    module = importlib.util.module_from_spec(spec)
    module.__package__ = name.rsplit(".", 1)[0]
    module.__file__ = str(path)
    sys.modules[name] = module
    exec(compile(source, str(path), "exec"), module.__dict__)
    return module


def mutate_kernel(monkeypatch, *, kernel: list[tuple[str, str]] = (), flow: list[tuple[str, str]] = ()) -> None:
    """Run the plain kernel with ``kernel`` replacements in ``_kernel.py`` and ``flow`` ones in ``_kernel_flow.py``."""
    pkg = "symbolic_friction._simulation"
    monkeypatch.setenv(_jit.ENV, "0")
    monkeypatch.delitem(sys.modules, f"{pkg}._kernel_flow_mut", raising=False)
    monkeypatch.delitem(sys.modules, f"{pkg}._kernel_mut", raising=False)
    _load(f"{pkg}._kernel_flow_mut", SIM / "_kernel_flow.py", list(flow))
    mutant = _load(f"{pkg}._kernel_mut", SIM / "_kernel.py",
                   [("    from ._kernel_flow import *  # noqa: F403", "    from ._kernel_flow_mut import *  # noqa: F403"), *kernel])
    monkeypatch.setattr(_jit, "plain", lambda: mutant)
    monkeypatch.setattr("symbolic_friction._simulation.event.plain", lambda: mutant)


def failing(rows) -> list:
    return [r for r in rows if not r.ok]


def test_every_scenario_matches_the_reference():
    rows = _kernel_check.kernel_rows()
    assert len(rows) == 26 and not failing(rows), failing(rows)
    names = " ".join(r.scenario for r in rows)
    for part in ("f_c=1,", "f_c=2,", "f_c=1e-6,", "f_c=1e6,", "f_s=6/5 f_c", "uniform", "squared", "after event"):
        assert part in names


def test_the_unmutated_copy_of_the_kernel_holds(monkeypatch):
    """The loader itself changes nothing: the copy passes (so the failures below are the mutants')."""
    mutate_kernel(monkeypatch)
    assert not failing(_kernel_check.kernel_rows())


def test_the_tolerances_are_pinned():
    assert (_kernel_check.STATE_TOL, _kernel_check.TIME_TOL, _kernel_check.INTEGRAL_TOL) == (1e-12, 1e-12, 1e-12)


def test_a_perturbation_above_the_state_tolerance_fails():
    """A reference sample moved by 4·STATE_TOL·scale fails; so a 2⁴⁰ looser tolerance would pass it and be caught here."""
    data = _kernel_check.load_reference()
    name = _kernel_check.SCENARIOS[3].name
    entry = data[name]
    z = [list(map(float, p)) for p in entry["z"]]
    z[40][1] += 4 * _kernel_check.STATE_TOL * entry["scale"]
    data = {**data, name: {**entry, "z": [[repr(c) for c in p] for p in z]}}
    bad = failing(_kernel_check.kernel_rows(data))
    assert [r.scenario for r in bad] == [name] and "the reference's" in bad[0].detail


def test_a_missing_scenario_fails():
    data = _kernel_check.load_reference()
    data.pop(_kernel_check.SCENARIOS[0].name)
    assert "no reference numbers" in failing(_kernel_check.kernel_rows(data))[0].detail


KERNEL_MUTANTS = {
    "slip dense output without f_c": [("x0, x1, x2 = ys, yp + mode * f_c, mode", "x0, x1, x2 = ys, yp + mode, mode")],
    "stick dense output without f_c": [("x0, x1, x2 = sigma, base * f_c + (offset", "x0, x1, x2 = sigma, base + (offset")],
    "event state φ without f_c": [("ev_x[n_ev, 1] = base * f_c + offset", "ev_x[n_ev, 1] = base + offset")],
    "stick duration without f_c": [("gap = -offset if base == d else (d - base) * f_c - offset",
                                     "gap = -offset if base == d else (d - base) - offset")],
    "stiction exit with the wrong sign": [("gap += d * excess", "gap -= d * excess")],
    "slip offset after a stick with the wrong sign": [("(d * excess if excess != 0.0 else 0.0), d",
                                                       "(-d * excess if excess != 0.0 else 0.0), d")],
    "slip start offset from the wrong boundary": [("(offset if base == d else (base - d) * f_c + offset)",
                                                   "(offset if base == d else (d - base) * f_c + offset)")],
    "stepped propagator index slip": [("e10 = w1 * K[b1 + 3] + w0 * K[b2 + 3]", "e10 = w1 * K[b1 + 4] + w0 * K[b2 + 3]")],
    "stepped propagator reads e12 for e21": [("e20 * ys + e21 * yp + e22 * yv", "e20 * ys + e12 * yp + e22 * yv")],
}


@pytest.mark.parametrize("name", sorted(KERNEL_MUTANTS))
def test_a_kernel_mutant_fails(monkeypatch, name):
    mutate_kernel(monkeypatch, kernel=KERNEL_MUTANTS[name])
    assert failing(_kernel_check.kernel_rows()), name


def test_a_scan_that_skips_the_last_partial_cell_fails(monkeypatch):
    """The horizon ends 1e-9 relative after a slip's end: a floor instead of a ceil misses the event."""
    mutate_kernel(monkeypatch, flow=[("    last = min(n_cells, int(math.ceil((horizon - a_w) / dt)))\n    extra = grow * min(",
                                      "    last = min(n_cells, int((horizon - a_w) / dt))\n    extra = grow * min(")])
    bad = failing(_kernel_check.kernel_rows())
    assert bad and all("after event" in r.scenario for r in bad), bad


def test_the_integral_without_f_c_fails(monkeypatch):
    """``∫ v²`` with the slip's offset x*_k taken at f_c = 1: invisible at f_c = 1, caught at f_c = 2."""
    mutant = _load("symbolic_friction._crosscheck._along_mut", Path(_along.__file__),
                   [("y[..., 1] -= kk * self.f_c", "y[..., 1] -= kk")])
    monkeypatch.setattr(_along, "along", mutant.along)
    bad = failing(_kernel_check.kernel_rows())
    assert bad and all("∫v²" in r.detail for r in bad) and not any(r.scenario.startswith("f_c=1,") for r in bad)


@pytest.mark.slow
def test_the_shipped_numbers_are_the_references():
    """kernel_reference.json is what the 50-digit reference computes now (regenerate with reference_data).

    Its states, modes, horizons, events and scales, and ``integral_v2`` of the uniform grids (the number the
    cross-check's ∫v² is held to in ``kernel_rows``: an mpmath quadrature, half this test's time)."""
    shipped = _kernel_check.load_reference()
    fresh = json.loads(json.dumps(_kernel_check.reference_data()))
    assert fresh.keys() == shipped.keys()
    assert any("integral_v2" in entry for entry in fresh.values())
    for name in fresh:
        a, b = fresh[name], shipped[name]
        assert ("integral_v2" in a) == ("integral_v2" in b), name
        if "integral_v2" in a:
            assert np.isclose(a["integral_v2"], b["integral_v2"], rtol=1e-15, atol=0), name
        assert a["mode"] == b["mode"] and a["t_end"] == b["t_end"], name
        assert np.isclose(a["scale"], b["scale"], rtol=1e-15, atol=0), name
        assert np.allclose(np.array(a["z"], float), np.array(b["z"], float), rtol=0, atol=1e-15 * a["scale"]), name
        assert [e[1:3] for e in a["events"]] == [e[1:3] for e in b["events"]], name
