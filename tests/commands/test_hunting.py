"""``symbolic-friction hunting``: prints the cycle, proves it, writes a certificate `verify` accepts."""

from __future__ import annotations

import json

from symbolic_friction._cli.main import main

A = ["--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"]


def test_case_a_prints_proves_and_writes_a_certificate(tmp_path, capsys):
    png = tmp_path / "a.png"
    rc = main(["hunting", *A, "--f-s", "1.2", "--out", str(tmp_path), "--name", "a", "--figure", str(png), "--sweep", "1.1,1.2"])
    out = capsys.readouterr().out
    assert rc == 0
    assert "σ* = 0.10504486800" in out and "period T = 46.86041856" in out
    assert "PROVED: exactly one symmetric cycle" in out and "stable (proved |multiplier| < 1)" in out
    assert "agrees to 1e-9" in out
    assert "Corollary 1 at ρ = (f_s - f_c)/f_c = 0.2" in out and "within the worst found γ̂(ρ)" in out
    assert png.stat().st_size > 10_000
    cert = tmp_path / "a.json"
    data = json.loads(cert.read_text(encoding="utf-8"))
    assert data["parameters"]["f_s"] == "6/5" and data["cycle"]["stable"] is True
    assert "iss" not in data["cycle"]  # an empirical comparison is printed, not certified
    assert main(["verify", str(cert)]) == 0
    assert capsys.readouterr().out.startswith("PROVED ")
    assert not list(tmp_path.glob("*.tmp*"))


def test_the_paper_model_says_the_existing_certificates_apply(tmp_path, capsys):
    assert main(["hunting", *A, "--f-s", "1", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "f_s = f_c, the paper's model" in out and "no hunting cycle exists" in out
    assert not list(tmp_path.iterdir())


def test_static_below_coulomb_is_a_usage_error(tmp_path, capsys):
    assert main(["hunting", *A, "--f-s", "0.9", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "f_s ≥ f_c" in err[0] and "9/10" in err[0]


def test_bad_sweep_is_a_usage_error(tmp_path, capsys):
    assert main(["hunting", *A, "--f-s", "1.2", "--out", str(tmp_path), "--sweep", "0.5", "--no-iss", "--no-simulation"]) == 2
    assert "--sweep ratios f_s/f_c must lie in (1, 100] (f_s > f_c); got 0.5" in capsys.readouterr().err
