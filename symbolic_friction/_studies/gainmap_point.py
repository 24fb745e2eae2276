"""The columns of one gain-map point beyond its gains (see :mod:`.gainmap`).

* :func:`float_up`: a decimal bound κ as the smallest float not below it;
* :func:`worst_overshoot`: Proposition 1's adversary of the cross-check on a small budget (found, not proved);
* :func:`hunting_cycles`: symmetric hunting cycles found and proved in arb balls;
* :func:`tight_kappa`: what default ``certify`` proves (the cheapest template reaching κ_lin within a
  tolerance, in a time budget, the closed form as its floor) and the proven lower end of κ_lin.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np


__all__ = ["float_up", "worst_overshoot", "hunting_cycles", "tight_kappa", "TIGHT_TEMPLATES"]

TIGHT_TEMPLATES = ("none", "paper", "quadratic", "sup-flow")
"""The codes of the column ``tight_template``: the template whose certificate gave ``kappa_tight``."""


def float_up(decimal: str) -> float:
    """The smallest float ``≥`` the decimal ``decimal`` (decided exactly)."""
    f = float(decimal)
    return math.nextafter(f, math.inf) if Fraction(f) < Fraction(decimal) else f


def worst_overshoot(params: Any, *, budget: int, seed: int) -> float:
    """The largest ``sup_t |x(t)|_𝒜/|x(0)|_𝒜`` the cross-check's adversary finds with ``budget`` exact trajectories (found, not proved)."""
    from .._crosscheck._along import along
    from .._crosscheck._outcome import default_horizon, sample_times
    from .._crosscheck._overshoot import search_overshoot
    from .._model.coordinates import x_to_z
    from .._simulation.batch import simulate_batch

    t = sample_times(default_horizon(params), 101)

    def evaluate(X0: np.ndarray, label: str) -> np.ndarray:
        return along(simulate_batch(params, x_to_z(params, X0), float(t[-1]), t_eval=t)).overshoot

    found = search_overshoot(params, evaluate, budget=budget, seed=seed, t_eval=t)
    ratio = found.ratio[np.isfinite(found.ratio)]
    return float(ratio.max()) if ratio.size else math.nan


def hunting_cycles(params: Any) -> tuple[int, int]:
    """``(found, proved)``: symmetric hunting cycles found by the map and proved by the Krawczyk test."""
    from .._certify.hunting_proof import box_around, prove_cycle
    from .._hunting._map import find_cycles

    cycles = find_cycles(params, general=False)
    return len(cycles), sum(1 for c in cycles if prove_cycle(params, box_around(c.sigma, c.slip_time)).proved)


def tight_kappa(params: Any, *, budget: float) -> tuple[float, float, int]:
    """``(κ, κ_lin lower end, template code)``: default ``certify`` on ``params`` within ``budget`` seconds.

    ``κ`` is the proved bound rounded up to a float, the lower end of κ_lin
    rounded down (NaN where none was had), the code an index of
    :data:`TIGHT_TEMPLATES` (0 and NaNs: no template proved anything).  Every
    certificate was verified exactly by its template's verifier inside
    :func:`~symbolic_friction._certify.choose.certify_template`; a search's
    failure is that search's reason, never an exception here.
    """
    from .._certify.choose import certify_template
    from .._infra.errors import SymbolicFrictionError

    try:
        choice = certify_template(params, budget=budget)
    except SymbolicFrictionError:
        return math.nan, math.nan, 0
    lower = choice.kappa_lin_lower
    low = math.nan
    if lower is not None:
        low = float(lower)
        if Fraction(low) > lower:
            low = math.nextafter(low, -math.inf)
    return float_up(choice.certificate.overshoot_bound), low, TIGHT_TEMPLATES.index(choice.template.id.split("/")[0])
