"""Cross-check of certificates on exact simulated trajectories.

A certificate (:mod:`symbolic_friction._certify`) is *proved* exactly; the
cross-check confirms on real solutions of eq. (xDot), simulated by the exact
event-driven method, that every inequality it instantiates holds, and
measures how conservative the bounds are:

* :mod:`._properties` — the paper's list of properties, one
  :class:`~._property.Property` each, from one module per part of the paper:
  :mod:`.lemma2`, :mod:`.lemma3`, :mod:`.prop1`, :mod:`.remark_armstrong`
  (the Remark after Lemma 2) and :mod:`.mode_table` (Claim 1); they read the
  package's one model along the trajectories through :mod:`._along`, and
  :mod:`._checker` loops over them (:mod:`._results`: tallies, counterexamples);
* :mod:`._initial` — initial states: random spheres,
  grids, special states, and optimisers that try to break the inequalities;
* :mod:`._overshoot` — the adversary of Proposition 1: the worst overshoot
  found per scale of ``|x(0)|_𝒜``, peaks located on the closed form, and how
  ``|x(t)|_𝒜 → 0`` (power law or exponential);
* :mod:`._iss_search` — Corollary 1's worst found ultimate bound over the
  admissible selections of ``SGN_ρ`` (found, never called a worst case);
* :mod:`._iss` — Corollary 1: an empirical ISS gain ``γ(ρ)``;
* :mod:`._run`, :mod:`._outcome` — :func:`crosscheck`, the driver;
* :mod:`._report` — tables and counterexample files.
"""

from __future__ import annotations

from ._claims import Claims
from ._overshoot import DecayFit, decay_fit
from ._iss import IssEstimate, iss_gain
from ._iss_search import WorstFound, worst_found
from ._overshoot import OvershootSearch
from ._property import Evaluation, Property
from ._properties import DEFAULT_RTOL, DEFAULT_THETA, PROPERTIES, Counterexample, PropertyResult
from ._report import format_report, write_counterexamples
from ._files import default_certificate_files, default_certificate_selection
from ._run import CertificateCheck, CrosscheckReport, crosscheck, default_horizon

__all__ = [
    "Claims",
    "crosscheck",
    "CrosscheckReport",
    "CertificateCheck",
    "PropertyResult",
    "Counterexample",
    "PROPERTIES",
    "DEFAULT_RTOL",
    "DEFAULT_THETA",
    "default_horizon",
    "default_certificate_files",
    "default_certificate_selection",
    "decay_fit",
    "DecayFit",
    "iss_gain",
    "IssEstimate",
    "worst_found",
    "WorstFound",
    "OvershootSearch",
    "Property",
    "Evaluation",
    "format_report",
    "write_counterexamples",
]
