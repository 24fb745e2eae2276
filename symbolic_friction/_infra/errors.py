"""Exception hierarchy of :mod:`symbolic_friction`.

Every error a user can provoke with bad input derives from
:class:`SymbolicFrictionError` *and* from the matching built-in exception, so
``except ValueError`` keeps working for callers that do not know this package.
The command-line interface turns any :class:`SymbolicFrictionError` into a
one-line message and exit code 2, without a traceback.
"""

from __future__ import annotations

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
    "UsageError",
    "UnprovedCertificateError",
    "ConfigError",
    "InputFileError",
    "OutputPathError",
]


class SymbolicFrictionError(Exception):
    """Base class of every error raised on purpose by this package.

    Every subclass (:mod:`symbolic_friction.errors`) also derives from the
    built-in it refines, and its message names the numbers that are wrong.

    Examples
    --------
    >>> from symbolic_friction import Parameters, SymbolicFrictionError
    >>> try:
    ...     Parameters(k_p=3, k_i=4, k_v=1)
    ... except SymbolicFrictionError as exc:
    ...     print(type(exc).__name__, isinstance(exc, ValueError))
    AssumptionError True
    """


class ParameterError(SymbolicFrictionError, ValueError):
    """A gain, a physical quantity or a state is not acceptable."""


class InvalidNumberError(ParameterError, TypeError):
    """A value could not be read as an exact rational number."""


class NonFiniteError(ParameterError):
    """A value is NaN or infinite where a finite number is required."""


class AssumptionError(ParameterError):
    """Parameters violate Assumption 1 of the paper (or f_c > 0, m > 0)."""


class SceneError(SymbolicFrictionError, ValueError):
    """A scene file or scene mapping is malformed."""


class CertificateError(SymbolicFrictionError, ValueError):
    """A certificate does not prove what it claims."""


class UnprovedCertificateError(CertificateError):
    """A certificate was given where a proved one is required, and exact verification rejects it."""


class CertificateFormatError(CertificateError):
    """A certificate file is not well formed (JSON, schema, keys, types)."""


class SolverError(SymbolicFrictionError, RuntimeError):
    """The numerical search did not return a usable candidate."""


class InfeasibleError(SolverError):
    """The solver reports the search problem as infeasible or unbounded."""


class InaccurateSolveError(SolverError):
    """The solver returned an inaccurate or non-optimal status."""


class SimulationError(SymbolicFrictionError, ValueError):
    """A simulation request is invalid (method, option, horizon, state)."""


class StaleFileError(SymbolicFrictionError, RuntimeError):
    """A committed generated file differs from what would be generated now."""


class UsageError(SymbolicFrictionError, ValueError):
    """A command was asked for something it cannot do as given (a missing directory, a bad combination)."""


class ConfigError(UsageError):
    """The project configuration (``[tool.symbolic-friction]``) is missing, unreadable or malformed."""


class InputFileError(SymbolicFrictionError, OSError):
    """An input path cannot be read as asked: missing, not a regular file, too large, a symlink loop, …"""


class OutputPathError(SymbolicFrictionError, OSError):
    """An output path cannot be written: it is a file, lies below a file, has a name too long, …"""
