"""Figures of the cross-check: the tightness plot and the ISS-gain plot are drawn from real results."""

from __future__ import annotations

from pathlib import Path

from symbolic_friction import Parameters
from symbolic_friction._crosscheck import crosscheck, iss_gain
from symbolic_friction._studies.crosscheck_figures import plot_iss, plot_tightness, table_i_certificates

PROOFS = Path(__file__).resolve().parents[1] / "proofs"


def _is_png(path: Path) -> bool:
    return path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_tightness_figure(tmp_path):
    files = [PROOFS / f"case_a_{m}.json" for m in ("feasible", "tightest")]
    report = crosscheck(files, trajectories=40, adversarial=False, samples=51)
    path = plot_tightness(report.checks, tmp_path / "t.png")
    assert path.exists() and _is_png(path) and path.stat().st_size > 10_000


def test_iss_figure(tmp_path):
    est = iss_gain(Parameters.table_i("a"), ("0", "0.01", "0.1"), horizon=10.0, h=1e-2)
    path = plot_iss([est], tmp_path / "g.png", labels=["case (a)"])
    assert path.exists() and _is_png(path)


def test_table_i_certificates_prefers_committed_files():
    found = table_i_certificates(PROOFS)
    assert [Path(p).name for p in found] == [
        "case_a_feasible.json", "case_a_tightest.json", "case_b_feasible.json", "case_b_tightest.json",
    ]


def test_figures_are_registered_for_the_figures_command():
    import symbolic_friction._studies.crosscheck_figures  # noqa: F401  (registers on import)
    from symbolic_friction._studies.figures import FIGURES

    assert {"crosscheck_tightness", "crosscheck_iss"} <= set(FIGURES)


def test_table_i_certificates_are_certified_when_no_file_exists(tmp_path):
    from symbolic_friction._certify import verify_certificate

    found = table_i_certificates(tmp_path)
    assert len(found) == 4
    assert all(verify_certificate(c).proved for c in found)


def test_tightness_split_by_gain_set_is_the_joint_cross_check(monkeypatch):
    # the figure runs one cross-check per case (in parallel); each must be what the joint run does for it
    import symbolic_friction._crosscheck as cc
    import symbolic_friction._studies.crosscheck_figures as cf

    real = cc.crosscheck

    def small(certs, **kw):  # fewer and cheaper trajectories, the seeds as the figure passes them
        return real(certs, **{**kw, "trajectories": 12, "adversarial": False, "samples": 31})

    monkeypatch.chdir(PROOFS.parent)  # the figure reads proofs/ from the working directory
    monkeypatch.setattr(cc, "crosscheck", small)
    split = cf._tightness_checks("a") + cf._tightness_checks("b")
    joint = small(table_i_certificates(), seed=0, progress=False).checks
    assert [c.source for c in split] == [c.source for c in joint]
    for a, b in zip(split, joint):
        assert a.max_overshoot == b.max_overshoot and a.worst_state == b.worst_state


def test_iss_search_tasks_call_the_search_as_iss_gain_does(monkeypatch):
    import numpy as np

    import symbolic_friction._crosscheck as cc
    import symbolic_friction._crosscheck._iss_search as search
    import symbolic_friction._studies.crosscheck_figures as cf

    calls = []

    def record(params, rho, **kw):
        calls.append((params, rho, kw))
        return search.WorstFound(rho=float(rho), bound=1.0, law="recorded", initial_state=(0.0, 0.0, 0.0))

    monkeypatch.setattr(cc, "worst_found", record)
    monkeypatch.setattr(search, "worst_found", record)
    cf._iss_search("b", "0.1")
    iss_gain(Parameters.table_i("b"), ("0",), laws=(), search_rhos=("0.1",))
    (p1, r1, kw1), (p2, r2, kw2) = calls
    assert (p1, r1) == (p2, r2) and sorted(kw1) == sorted(kw2)
    for key in kw1:
        assert np.array_equal(kw1[key], kw2[key]), key
    assert len(cf._iss_tasks()) == 2 + 2 * len(cf.ISS_SEARCH_RHOS)
