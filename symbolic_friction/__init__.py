"""symbolic_friction: a machine-checked stability proof for a PID-controlled
mass with Coulomb friction.

Paper: A. Bisoffi, M. Da Lio, A. R. Teel, L. Zaccarian, *Global asymptotic
stability of a PID control system with Coulomb friction*.

What users call, by task (``__all__``):

Gains (paper §II-A, Assumption 1)
    :class:`Parameters` (``Parameters.table_i("a")``, ``Parameters.from_physical(...)``),
    :data:`TABLE_I`, :func:`to_rational`, :func:`format_rational`
The proof
    :func:`run_obligations`, :func:`all_obligations`, :func:`all_errata`
Certificates (Lemma 2, Lemma 3, Proposition 1, exactly)
    :func:`certify`, :func:`verify_certificate`, :func:`verify_file`,
    :func:`load_certificate`, :func:`write_certificate`, :class:`Certificate`,
    :class:`VerificationReport`
Simulation (eq. xPhDot, exact event-driven solutions)
    :func:`simulate`, :func:`simulate_batch`, :class:`Solution`, :class:`Trajectories`,
    the methods :class:`EventDriven`, :class:`Moreau`,
    :class:`Regularized`, :class:`IvpEvents`
Responses, as python-control shapes them
    :func:`step_response` (reference or disturbance step), :func:`initial_response`,
    :class:`Response` (``.time``, ``.outputs``, ``.states`` (3, n_t), ``to_pandas()``,
    ``to_xarray()``, ``plot()``)
Studies
    :func:`crosscheck`, :class:`CrosscheckReport`, :func:`find_cycles`,
    :func:`prove_cycle` (hunting under stiction), :func:`measure_tradeoff`, :func:`run_extremes`
Errors
    :class:`SymbolicFrictionError`; every subclass in :mod:`symbolic_friction.errors`

Public submodules, for the parts behind these calls: :mod:`~symbolic_friction.model`
(V, V̂, the attractor, coordinates, :class:`PhysicalParameters`), :mod:`~symbolic_friction.symbolic` (the sympy
model), :mod:`~symbolic_friction.errors`, :mod:`~symbolic_friction.obligations`,
:mod:`~symbolic_friction.certificates`, :mod:`~symbolic_friction.simulation`,
:mod:`~symbolic_friction.studies`.  A name that used to sit at the top level
still does, with a :class:`DeprecationWarning` naming its new home (for one
release).

Everything that needs numpy, sympy, scipy or cvxpy is imported on first use
(PEP 562 ``__getattr__``), so that importing the package and
``symbolic-friction --help`` stay fast.

Examples
--------
>>> import symbolic_friction as sf
>>> p = sf.Parameters.table_i("a")
>>> sf.step_response(p, 30)
Response(reference step 1 of Parameters(k_p=3, k_i=4, k_v=32/5, f_c=1), 1001 samples on [0, 30], 7 events)
"""

from __future__ import annotations

import importlib
import warnings
from typing import Any

from ._infra.errors import SymbolicFrictionError
from ._infra.rational import format_rational, to_rational
from ._model.parameters import TABLE_I, Parameters

__version__ = "0.3.0"

# name -> private module that defines it (imported lazily on first access)
_LAZY: dict[str, str] = {
    # the proof
    "run_obligations": "._obligations",
    "all_obligations": "._obligations",
    "all_errata": "._obligations",
    # certificates (search with cvxpy; exact verification with Fractions)
    "certify": "._certify",
    "verify_certificate": "._certify",
    "verify_file": "._certify",
    "load_certificate": "._certify",
    "write_certificate": "._certify",
    "Certificate": "._certify",
    "VerificationReport": "._certify",
    # simulation
    "simulate": "._simulation",
    "simulate_batch": "._simulation.batch",
    "Solution": "._simulation._trajectories",
    "Trajectories": "._simulation._trajectories",
    "EventDriven": "._simulation.event",
    "Moreau": "._simulation.moreau",
    "Regularized": "._simulation.regularized",
    "IvpEvents": "._simulation.ivp_events",
    # responses shaped like python-control's
    "step_response": "._simulation.response",
    "initial_response": "._simulation.response",
    "Response": "._simulation.response",
    # studies
    "crosscheck": "._crosscheck",
    "CrosscheckReport": "._crosscheck",
    "find_cycles": "._hunting",
    "prove_cycle": "._hunting",
    "measure_tradeoff": "._studies.tradeoff",
    "run_extremes": "._extremes",
}

# public submodules (imported lazily)
_MODULES = ("model", "symbolic", "errors", "obligations", "certificates", "simulation", "studies")
_MODULE_PATHS: dict[str, str] = {}  # every public submodule is a module of its own name

# Names that left the top level: still importable here for one release, with a warning naming their home.
_MOVED: dict[str, str] = {
    **{name: "errors" for name in (
        "ParameterError", "InvalidNumberError", "NonFiniteError", "AssumptionError", "SceneError",
        "CertificateError", "CertificateFormatError", "SolverError", "InfeasibleError", "InaccurateSolveError",
        "SimulationError", "StaleFileError", "UnprovedCertificateError", "UsageError", "ConfigError",
        "InputFileError", "OutputPathError",
    )},
    **{name: "model" for name in (
        "z_to_x", "x_to_z", "system_matrix", "input_vector", "dz", "distance_x", "squared_distance_x",
        "distance_z", "in_attractor_x", "attractor_bound_x", "attractor_bound_z", "lyapunov_matrix", "V", "V_k",
        "V_hat", "in_R", "k_conditions", "check_k_conditions", "Condition",
    )},
    **{name: "obligations" for name in ("Obligation", "Outcome", "Result", "Erratum")},
    **{name: "certificates" for name in (
        "certify_many", "SweepItem", "Provenance", "Candidate", "find_candidate", "loads_certificate",
        "dumps_certificate", "certify_table_i", "check_committed_certificates", "CommittedCertificate", "TABLE_I_FILES",
    )},
    **{name: "simulation" for name in (
        "FrictionLaw", "Coulomb", "InflatedCoulomb", "Stribeck", "iter_batches", "MatrixExponential", "select_mode",
        "table_row", "SimulationMethod", "Reference", "Status",
    )},
    **{name: "studies" for name in (
        "CertificateCheck", "PropertyResult", "Counterexample", "Claims", "PROPERTIES", "decay_fit", "DecayFit",
        "iss_gain", "IssEstimate", "format_report", "write_counterexamples", "HuntingCycle", "HuntingCertificate",
        "verify_hunting", "HuntingMap", "Scene", "load_scene", "builtin_scenes", "make_figures", "available_figures", "measure_cost", "Tradeoff", "Extremes",
    )},
}

__all__ = [
    "__version__",
    "Parameters",
    "TABLE_I",
    "to_rational",
    "format_rational",
    "SymbolicFrictionError",
    *_LAZY,
    *_MODULES,
]


def __getattr__(name: str) -> Any:
    if name in _MODULES:
        value = importlib.import_module(_MODULE_PATHS.get(name, f".{name}"), __name__)
        globals()[name] = value
        return value
    module = _LAZY.get(name)
    if module is not None:
        value = getattr(importlib.import_module(module, __name__), name)
        globals()[name] = value
        return value
    home = _MOVED.get(name)
    if home is not None:
        # not cached in globals(): every use warns, so a caller cannot miss it
        warnings.warn(
            f"symbolic_friction.{name} has moved to symbolic_friction.{home}.{name}; "
            "the top-level name will be removed in the next release",
            DeprecationWarning,
            stacklevel=2,
        )
        return getattr(importlib.import_module(f".{home}", __name__), name)
    raise AttributeError(f"module 'symbolic_friction' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
