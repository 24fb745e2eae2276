"""One hunting cycle studied end to end: found, proved, compared and certified.

For a cycle found by :func:`._map.find_cycles`, :func:`study_cycle` proves it
in arb balls (:func:`symbolic_friction._certify.hunting_proof.prove_cycle` on
the box around it), optionally compares it with a long exact simulation
(:func:`._report.simulation_agreement`) and with Corollary 1's empirical gain
(:func:`._iss.iss_comparison`), and, when proved, builds the hunting
certificate that ``symbolic-friction verify`` re-checks.  ``symbolic-friction
hunting`` prints what this returns.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from .._certify.hunting import HuntingCertificate, certificate_for
from .._certify.hunting_proof import Box, CycleProof
from .._model.parameters import Parameters
from ._map import HuntingCycle

__all__ = ["CycleStudy", "study_cycle", "parse_sweep"]


@dataclass(frozen=True)
class CycleStudy:
    """What is known about one symmetric hunting cycle.

    Attributes
    ----------
    cycle : HuntingCycle
        The cycle as found (floats).
    box : Box
        The exact box the proof is run on.
    proof : CycleProof
        The Krawczyk proof and its checks.
    agreement : Agreement or None
        The long exact simulation's agreement (None if not asked for).
    inside_box : bool or None
        Whether the simulated stick exits lie in the proved box.
    iss : IssComparison or None
        Corollary 1's empirical gain at ``ρ`` (None if not asked for).
    certificate : HuntingCertificate or None
        The certificate to write (None if not proved).
    """

    cycle: HuntingCycle
    box: Box
    proof: CycleProof
    agreement: Any = None
    inside_box: bool | None = None
    iss: Any = None
    certificate: HuntingCertificate | None = None


def study_cycle(params: Parameters, cycle: HuntingCycle, *, simulate: bool = True, iss: bool = True) -> CycleStudy:
    """Prove ``cycle`` exactly and, if proved, compare it and build its certificate.

    The certificate states only what its verifier proves (:mod:`.._certify.hunting_cycle`);
    the amplitudes, the simulation's agreement and Corollary 1's comparison are reported here, not certified.
    """
    certificate, proof = certificate_for(params, cycle.sigma, cycle.slip_time)
    box = certificate.box
    if not proof.proved:
        return CycleStudy(cycle, box, proof)
    agreement = inside = None
    if simulate:
        from ._report import simulation_agreement

        agreement = simulation_agreement(cycle)
        lo, hi = box.sigma
        inside = bool(agreement.last_sigmas) and all(lo <= Fraction(x) <= hi for x in agreement.last_sigmas)
    comparison = None
    if iss:
        from ._iss import iss_comparison

        comparison = iss_comparison(cycle)
    return CycleStudy(cycle, box, proof, agreement, inside, comparison, certificate)


def parse_sweep(text: str) -> list[Fraction]:
    """Ratios ``f_s/f_c`` from ``"1.1,1.2"``, each exact and above 1.

    Raises
    ------
    ParameterError
        If a ratio is not a number or is not above 1.
    """
    from .._infra.errors import ParameterError
    from .._infra.rational import to_rational

    parts = [r.strip() for r in text.split(",") if r.strip()]
    if not parts or len(parts) > MAX_SWEEP:
        raise ParameterError(f"--sweep takes 1 to {MAX_SWEEP} comma-separated ratios f_s/f_c like 1.1,1.2; got {len(parts)}")
    ratios = [to_rational(r, name="a --sweep ratio") for r in parts]
    bad = [r for r in ratios if not 1 < r <= MAX_RATIO]
    if bad:
        raise ParameterError(f"--sweep ratios f_s/f_c must lie in (1, {MAX_RATIO}] (f_s > f_c); got {float(bad[0]):g}")
    return ratios


# Bounds on --sweep: at most this many ratios, each at most this large (static friction this far above Coulomb).
MAX_SWEEP, MAX_RATIO = 50, 100
