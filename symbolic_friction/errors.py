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

from ._infra.errors import *  # noqa: F401,F403  (every error, defined once in _infra.errors)

from ._infra.errors import __all__  # noqa: F401
