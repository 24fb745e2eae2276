"""The studies' parts: the cross-check's properties and estimates, hunting cycles, scenes,
figures, the speed/accuracy trade-off and the extremes matrix.
"""

from __future__ import annotations

from ._namespace import lazy_getattr

# name -> private module that defines it (imported on first use)
_LAZY: dict[str, str] = {
    "HuntingMap": "._hunting",
    "load_scene": "._studies.scenes",
    "make_figures": "._studies.figures",
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
    "HuntingCycle": "._hunting",
    "HuntingCertificate": "._hunting",
    "verify_hunting": "._hunting",
    "Scene": "._studies.scenes",
    "builtin_scenes": "._studies.scenes",
    "available_figures": "._studies.figures",
    "measure_cost": "._studies.tradeoff",
    "Tradeoff": "._studies.tradeoff",
    "Extremes": "._extremes",
    "box_around": "._hunting",
}

__all__ = list(_LAZY)

__getattr__ = lazy_getattr("symbolic_friction", globals(), _LAZY)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
