"""Simulation beyond :func:`symbolic_friction.simulate`: friction laws, the method base class,
batches, the mode table of Claim 1 and the independent 50-digit reference.
"""

from __future__ import annotations

from ._namespace import lazy_getattr

# name -> private module that defines it (imported on first use)
_LAZY: dict[str, str] = {
    "Status": "._simulation._trajectories",
    "FrictionLaw": "._simulation.friction",
    "Coulomb": "._simulation.friction",
    "InflatedCoulomb": "._simulation.friction",
    "Stribeck": "._simulation.friction",
    "iter_batches": "._simulation.batch",
    "MatrixExponential": "._simulation.affine",
    "select_mode": "._simulation.modes",
    "table_row": "._simulation.modes",
    "SimulationMethod": "._simulation._base",
    "Reference": "._reference",
}

__all__ = list(_LAZY)

__getattr__ = lazy_getattr("symbolic_friction", globals(), _LAZY)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
