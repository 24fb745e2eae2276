"""The studies' parts: the cross-check's properties and estimates, hunting cycles, scenes,
figures, the speed/accuracy trade-off, the extremes matrix and gain maps (κ of exactly verified
closed-form certificates over a grid or a sample of gains: ``map_spec``, ``run_map``, ``read_map``, ``plot_map``),
and reset PID against PID (one initial state: ``compare_settling``; settling-time ratios over a grid of gains and
the stiction table: ``settling_ratio_map``, ``plot_settling_map``, ``stiction_table``).
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
    "map_spec": "._studies.gainmap",
    "MapSpec": "._studies.gainmap",
    "run_map": "._studies.gainmap_run",
    "MapRun": "._studies.gainmap_run",
    "read_map": "._studies.gainmap_run",
    "plot_map": "._studies.gainmap_plot",
    "compare_settling": "._studies.settling",
    "SettlingComparison": "._studies.settling",
    "settling_ratio_map": "._studies.settling_map",
    "SettlingMap": "._studies.settling_map",
    "stiction_table": "._studies.settling_map",
    "StictionTable": "._studies.settling_map",
    "plot_settling_map": "._studies.settling_map_plot",
}

__all__ = list(_LAZY)

__getattr__ = lazy_getattr("symbolic_friction", globals(), _LAZY)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
