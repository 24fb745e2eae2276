"""Every error the package raises; all derive from :class:`SymbolicFrictionError`.

Each subclasses the built-in it refines (``ParameterError(ValueError)``, …),
and its message names the numbers that are wrong.

Examples
--------
>>> from symbolic_friction import Parameters
>>> from symbolic_friction.errors import AssumptionError
>>> try:
...     Parameters(k_p=1, k_i=4, k_v=2)
... except AssumptionError as exc:
...     print(exc)
Assumption 1 needs k_v·k_p > k_i; got 2 ≤ 4 (k_v = 2, k_p = 1, k_i = 4)
"""

from ._infra.errors import (
    AssumptionError,
    CertificateError,
    CertificateFormatError,
    ConfigError,
    InaccurateSolveError,
    InfeasibleError,
    InputFileError,
    InvalidNumberError,
    NonFiniteError,
    OutputPathError,
    ParameterError,
    SceneError,
    SimulationError,
    SolverError,
    StaleFileError,
    SymbolicFrictionError,
    UnprovedCertificateError,
    UsageError,
)

__all__ = [
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
]
