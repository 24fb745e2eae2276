"""Hunting: static friction above Coulomb (``f_s > f_c``), beyond the paper.

The paper's conclusion names a static friction force larger than the Coulomb
one as future work.  With ``f_s > f_c`` a PID loop *hunts*: it settles into a
stick–slip limit cycle around the setpoint.  Here the cycle is

* a fixed point of the hunting map ``P`` (stick exit to stick exit),
  computed with the exact event-driven model and *found* in floats
  (:mod:`._map`);
* *proved* to exist with interval arithmetic (a Krawczyk test on the slip's
  closed form in arb balls, the slip's end time enclosed rigorously and its
  being the first zero of ``v`` checked; :mod:`._proof`), in a certificate
  file that ``symbolic-friction verify`` re-checks (:mod:`._certificate`);
* compared with Corollary 1: the stiction law lies in ``f_c SGN_ρ`` with
  ``ρ = (f_s - f_c)/f_c`` (eq. perturbed), so the cycle is an ISS "graceful
  degradation" whose size the empirical gain ``γ̂(ρ)`` must cover
  (:mod:`._iss`).
"""

from __future__ import annotations

from .._certify.hunting import HuntingCertificate, verify_hunting, verify_hunting_file, write_hunting
from ._map import HuntingCycle, HuntingMap, MapStep, cycle_orbit, find_cycles
from .._certify.hunting_proof import Box, CycleProof, box_around, prove_cycle

__all__ = [
    "Box",
    "CycleProof",
    "HuntingCertificate",
    "HuntingCycle",
    "HuntingMap",
    "MapStep",
    "box_around",
    "cycle_orbit",
    "find_cycles",
    "prove_cycle",
    "verify_hunting",
    "verify_hunting_file",
    "write_hunting",
]
