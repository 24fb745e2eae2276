"""symbolic_friction: a machine-checked stability proof for a PID-controlled
mass with Coulomb friction.

Paper: A. Bisoffi, M. Da Lio, A. R. Teel, L. Zaccarian, *Global asymptotic
stability of a PID control system with Coulomb friction*.

The public API is listed in ``__all__``.  Light objects (parameters, errors)
are imported eagerly; everything that needs numpy, sympy, scipy or cvxpy is
imported on first use (PEP 562 ``__getattr__``), so that importing the
package and ``symbolic-friction --help`` stay fast.
"""

from __future__ import annotations

import importlib
from typing import Any

from ._infra.errors import (
    AssumptionError,
    CertificateError,
    CertificateFormatError,
    InaccurateSolveError,
    InfeasibleError,
    InvalidNumberError,
    NonFiniteError,
    ParameterError,
    SceneError,
    SimulationError,
    SolverError,
    StaleFileError,
    UnprovedCertificateError,
    UsageError,
    ConfigError,
    InputFileError,
    OutputPathError,
    SymbolicFrictionError,
)
from ._model.parameters import TABLE_I, Parameters
from ._infra.rational import format_rational, to_rational

__version__ = "0.1.0"

# name -> private module that defines it (imported lazily on first access)
_LAZY: dict[str, str] = {
    # model (eq. CoC, xDot, A, distFromA, lyapLike, Vhat)
    "z_to_x": "._model.coordinates",
    "x_to_z": "._model.coordinates",
    "system_matrix": "._model.coordinates",
    "input_vector": "._model.coordinates",
    "dz": "._model.attractor",
    "distance_x": "._model.attractor",
    "squared_distance_x": "._model.attractor",
    "distance_z": "._model.attractor",
    "in_attractor_x": "._model.attractor",
    "attractor_bound_x": "._model.attractor",
    "attractor_bound_z": "._model.attractor",
    "lyapunov_matrix": "._model.lyapunov",
    "V": "._model.lyapunov",
    "V_k": "._model.lyapunov",
    "V_hat": "._model.lyapunov",
    "in_R": "._model.lyapunov",
    # proof obligations
    "Obligation": "._obligations._base",
    "Outcome": "._obligations._base",
    "Result": "._obligations._base",
    "all_obligations": "._obligations",
    "run_obligations": "._obligations",
    "all_errata": "._obligations",
    "Erratum": "._obligations._base",
    # conditions on k1..k4 (Lemma 3)
    "k_conditions": "._model.kconditions",
    "check_k_conditions": "._model.kconditions",
    "Condition": "._model.kconditions",
    # certificates (search with cvxpy; exact verification with Fractions)
    "certify": "._certify",
    "certify_many": "._certify",
    "SweepItem": "._certify",
    "verify_certificate": "._certify",
    "verify_file": "._certify",
    "VerificationReport": "._certify",
    "Certificate": "._certify",
    "Provenance": "._certify",
    "Candidate": "._certify",
    "find_candidate": "._certify",
    "load_certificate": "._certify",
    "loads_certificate": "._certify",
    "dumps_certificate": "._certify",
    "write_certificate": "._certify",
    "certify_table_i": "._certify",
    "check_committed_certificates": "._certify",
    "CommittedCertificate": "._certify",
    "TABLE_I_FILES": "._certify",
    # cross-check of certificates on simulated trajectories
    "crosscheck": "._crosscheck",
    "CrosscheckReport": "._crosscheck",
    "CertificateCheck": "._crosscheck",
    "PropertyResult": "._crosscheck",
    "Counterexample": "._crosscheck",
    "Claims": "._crosscheck",
    "PROPERTIES": "._crosscheck",
    "decay_fit": "._crosscheck",
    "DecayFit": "._crosscheck",
    "iss_gain": "._crosscheck",
    "IssEstimate": "._crosscheck",
    "format_report": "._crosscheck",
    "write_counterexamples": "._crosscheck",
    # simulation
    "Solution": "._simulation._trajectories",
    "FrictionLaw": "._simulation.friction",
    "Coulomb": "._simulation.friction",
    "InflatedCoulomb": "._simulation.friction",
    "Stribeck": "._simulation.friction",
    "Scene": "._studies.scenes",
    "load_scene": "._studies.scenes",
    "builtin_scenes": "._studies.scenes",
    "make_figures": "._studies.figures",
    "available_figures": "._studies.figures",
    "simulate": "._simulation",
    "simulate_batch": "._simulation.batch",
    "iter_batches": "._simulation.batch",
    "Trajectories": "._simulation._trajectories",
    "Status": "._simulation._trajectories",
    "MatrixExponential": "._simulation.affine",
    "select_mode": "._simulation.modes",
    "table_row": "._simulation.modes",
    "SimulationMethod": "._simulation._base",
    "EventDriven": "._simulation.event",
    "Moreau": "._simulation.moreau",
    "Regularized": "._simulation.regularized",
    "IvpEvents": "._simulation.ivp_events",
    # hunting: static friction above Coulomb (beyond the paper)
    "HuntingMap": "._hunting",
    "HuntingCycle": "._hunting",
    "find_cycles": "._hunting",
    "prove_cycle": "._hunting",
    "HuntingCertificate": "._hunting",
    "verify_hunting": "._hunting",
    # measured against the independent 50-digit reference: speed/accuracy and the extremes
    "Reference": "._reference",
    "measure_tradeoff": "._studies.tradeoff",
    "measure_cost": "._studies.tradeoff",
    "Tradeoff": "._studies.tradeoff",
    "run_extremes": "._extremes",
    "Extremes": "._extremes",
    # gain maps: κ of exactly verified closed-form certificates over a grid or a sample of gains
    "map_spec": "._studies.gainmap",
    "MapSpec": "._studies.gainmap",
    "run_map": "._studies.gainmap_run",
    "MapRun": "._studies.gainmap_run",
    "read_map": "._studies.gainmap_run",
    "plot_map": "._studies.gainmap_plot",
}

# public submodules (imported lazily): name -> private module
_MODULES: dict[str, str] = {
    # the paper's model in sympy, for symbolic gains: gains(), A, A_z, b, P, T, T_inv, K_hat, dz, sat
    "symbolic": "._model.symbolic",
}

__all__ = [
    "__version__",
    "Parameters",
    "TABLE_I",
    "to_rational",
    "format_rational",
    "SymbolicFrictionError",
    "ParameterError",
    "InvalidNumberError",
    "NonFiniteError",
    "AssumptionError",
    "SceneError",
    "CertificateError",
    "CertificateFormatError",
    "SolverError",
    "InfeasibleError",
    "InaccurateSolveError",
    "SimulationError",
    "StaleFileError",
    "UnprovedCertificateError",
    "UsageError",
    "ConfigError",
    "InputFileError",
    "OutputPathError",
    *_LAZY,
    *_MODULES,
]


def __getattr__(name: str) -> Any:
    if name in _MODULES:
        value = importlib.import_module(_MODULES[name], __name__)
        globals()[name] = value
        return value
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'symbolic_friction' has no attribute {name!r}")
    value = getattr(importlib.import_module(module, __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
