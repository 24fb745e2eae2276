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
