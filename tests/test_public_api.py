"""The public API (``symbolic_friction/__init__.py`` and the task modules): curated, lazy, deprecations tested."""

from __future__ import annotations

import importlib
import pydoc
import subprocess
import sys
import warnings

import pytest

import symbolic_friction as sf

# every name the previous release listed in __all__: each must still import (from __all__ or with a warning)
PREVIOUS_ALL = (
    "AssumptionError Candidate Certificate CertificateCheck CertificateError CertificateFormatError Claims "
    "CommittedCertificate Condition ConfigError Coulomb Counterexample CrosscheckReport DecayFit Erratum EventDriven "
    "Extremes FrictionLaw HuntingCertificate HuntingCycle HuntingMap InaccurateSolveError InfeasibleError "
    "InflatedCoulomb InputFileError InvalidNumberError IssEstimate IvpEvents MatrixExponential Moreau NonFiniteError "
    "Obligation Outcome OutputPathError PROPERTIES ParameterError Parameters PropertyResult Provenance Reference "
    "Regularized Result Scene SceneError SimulationError SimulationMethod Solution SolverError StaleFileError Status "
    "Stribeck SweepItem SymbolicFrictionError TABLE_I TABLE_I_FILES Tradeoff Trajectories UnprovedCertificateError "
    "UsageError V V_hat V_k VerificationReport __version__ all_errata all_obligations attractor_bound_x "
    "attractor_bound_z available_figures builtin_scenes certify certify_many certify_table_i "
    "check_committed_certificates check_k_conditions crosscheck decay_fit distance_x distance_z dumps_certificate dz "
    "find_candidate find_cycles format_rational format_report in_R in_attractor_x input_vector iss_gain iter_batches "
    "k_conditions load_certificate load_scene loads_certificate lyapunov_matrix make_figures measure_cost "
    "measure_tradeoff prove_cycle run_extremes run_obligations select_mode simulate simulate_batch "
    "squared_distance_x symbolic system_matrix table_row to_rational verify_certificate verify_file verify_hunting "
    "write_certificate write_counterexamples x_to_z z_to_x"
).split()


def _callables() -> list[str]:
    return [n for n in sf.__all__ if n != "__version__" and n not in sf._MODULES]


def test_all_is_curated():
    names = _callables()
    assert len(PREVIOUS_ALL) == 116 and 25 <= len(names) <= 35, len(names)
    assert len(set(sf.__all__)) == len(sf.__all__)
    for name in sf.__all__:  # each resolves without a warning
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert getattr(sf, name) is not None


def test_every_previous_name_still_imports_and_the_moved_ones_warn():
    for name in PREVIOUS_ALL:
        if name in sf.__all__:
            continue
        home = sf._MOVED[name]
        with pytest.warns(DeprecationWarning, match=rf"symbolic_friction\.{name} has moved to symbolic_friction\.{home}\.{name}"):
            value = getattr(sf, name)
        assert value is getattr(importlib.import_module(f"symbolic_friction.{home}"), name)


def test_from_import_of_a_moved_name_warns_at_the_callers_line():
    with pytest.warns(DeprecationWarning) as record:
        from symbolic_friction import ParameterError  # noqa: F401
    assert record[0].filename == __file__


def test_every_task_module_resolves_its_names():
    for module in sf._MODULES:
        namespace = getattr(sf, module)
        for name in getattr(namespace, "__all__", []):
            assert getattr(namespace, name) is not None, (module, name)
    with pytest.raises(AttributeError, match="module 'symbolic_friction.model' has no attribute 'nope'"):
        sf.model.nope  # noqa: B018
    with pytest.raises(AttributeError, match="module 'symbolic_friction' has no attribute 'nope'"):
        sf.nope  # noqa: B018


def test_help_lists_the_curated_api_by_task():
    text = pydoc.render_doc(sf, renderer=pydoc.plaintext)
    for heading in ("Gains", "The proof", "Certificates", "Simulation", "Responses", "Studies", "Errors"):
        assert f"\n    {heading}" in text or f"\n{heading}" in text, heading
    doc = sf.__doc__
    missing = [n for n in _callables() if f"`{n}`" not in doc]
    assert missing == [], f"the module docstring does not list {missing}"


def test_importing_the_package_stays_light():
    code = "import sys, symbolic_friction; print(sorted(m for m in ('numpy', 'sympy', 'scipy', 'cvxpy', 'pandas', 'xarray', 'matplotlib') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
