"""Every proof obligation of the paper, in paper order.

One module per obligation id prefix, named after it (``lemma2`` holds
``lemma2.P``, ``lemma2.lower_bound`` and ``lemma2.dVdt``; ``model`` holds the
binding obligations ``model.*_runtime``); private modules (``_name``) hold
what several obligations share.  Each obligation module lists its classes in
``OBLIGATIONS``; :func:`registry` imports every module by name in an import
statement, so a missing or renamed module is an :class:`ImportError`, never a
silently shorter proof, and orders the classes as the paper proves them.
Importing this package imports nothing heavy; :func:`all_obligations`
imports sympy.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from types import ModuleType

from ._base import Erratum, Obligation, Result

__all__ = ["all_obligations", "run_obligations", "run_checked", "all_errata", "registry", "obligation_modules"]

def obligation_modules() -> tuple[ModuleType, ...]:
    """The obligation modules (imported; a missing one raises :class:`ImportError`)."""
    from . import (
        assumption1,
        certificate,
        claim1,
        closed_form,
        coordinates,
        cor1,
        distance,
        equilibria,
        lemma1,
        lemma2,
        lemma3,
        model,
        prop1,
        quadratic,
        regularization,
        remark,
        reset,
        sup_flow,
        sup_flow_v2,
        table1,
    )

    return (coordinates, regularization, assumption1, equilibria, distance, model, lemma1, lemma2, remark,
            claim1, prop1, lemma3, cor1, table1, certificate, closed_form, quadratic, sup_flow, sup_flow_v2,
            reset)


def registry() -> tuple[type[Obligation], ...]:
    """Every obligation class, in the order the paper proves them.

    The paper's model first (coordinates, regularisation, Assumption 1's Routh
    test, equilibria, distance), the binding obligations, Lemma 1, Lemma 2 and
    its Remark, Claim 1, Proposition 1's attractivity, Lemma 3, Proposition 1's
    stability bound, Corollary 1, Table I, the verifier's bindings, and last the closed-form
    certificate for all gains, the monotonicity that box certificates rest on and the closed form's
    ``k₁ = k₄`` variant, the templates beyond the paper, and last reset PID's jumps.
    """
    from .assumption1 import Assumption1Encoding, Assumption1Routh
    from .certificate import CertificateVerifier, VerifierDecision
    from .claim1 import Claim1Cases
    from .closed_form import ClosedFormAllGains, ClosedFormBalanced, ClosedFormMonotone
    from .coordinates import Coordinates
    from .cor1 import Distances, Inflation
    from .distance import Distance
    from .equilibria import Equilibria
    from .lemma1 import Lemma1Uniqueness
    from .lemma2 import Lemma2dVdt, Lemma2LowerBound, Lemma2P
    from .lemma3 import HatVBounds, HatVDerivative, LemmaR
    from .model import (
        DistanceRuntime,
        DistanceZRuntime,
        HatVRateRuntime,
        HatVRuntime,
        KindsRuntime,
        MatricesRuntime,
        ModesRuntime,
        PNormRuntime,
        RRuntime,
        VRuntime,
    )
    from .prop1 import Prop1Invariance, StabilityBound
    from .quadratic import QuadraticPStructure, QuadraticStabilityBound, QuadraticUExit, QuadraticURate, QuadraticVDecrease
    from .regularization import Regularization
    from .remark import RemarkArmstrong
    from .reset import (
        ResetAttractor,
        ResetBasicConditions,
        ResetKernelBinding,
        ResetLeavesStick,
        ResetNoSecondJump,
        ResetSameStickExits,
        ResetVJump,
    )
    from .sup_flow import Bounds, Exit, Nonincreasing, RestMinimum, SlipFlow, SupFlowStabilityBound
    from .sup_flow_v2 import DragRegion, ExitV2, SignCrossing, StabilityBoundV2, URateV2
    from .table1 import TableI

    return (
        Coordinates, Regularization, Assumption1Routh, Equilibria, Distance,
        KindsRuntime, VRuntime, HatVRuntime, HatVRateRuntime, RRuntime, DistanceRuntime, DistanceZRuntime,
        MatricesRuntime, ModesRuntime, PNormRuntime,
        Lemma1Uniqueness, Lemma2P, Lemma2LowerBound, Lemma2dVdt, RemarkArmstrong, Claim1Cases,
        Prop1Invariance, LemmaR, HatVBounds, HatVDerivative, StabilityBound, Inflation, Distances, TableI,
        Assumption1Encoding, CertificateVerifier, VerifierDecision, ClosedFormAllGains, ClosedFormMonotone, ClosedFormBalanced,
        QuadraticPStructure, QuadraticVDecrease, QuadraticURate, QuadraticUExit, QuadraticStabilityBound,
        SlipFlow, RestMinimum, Nonincreasing, Bounds, Exit, SupFlowStabilityBound,
        URateV2, SignCrossing, DragRegion, ExitV2, StabilityBoundV2,
        ResetVJump, ResetNoSecondJump, ResetAttractor, ResetBasicConditions, ResetLeavesStick, ResetSameStickExits,
        ResetKernelBinding,
    )


def all_obligations() -> list[Obligation]:
    """Instances of every obligation, in paper order."""
    return [cls() for cls in registry()]


def run_obligations() -> list[Result]:
    """Run every obligation and return its :class:`Result`."""
    return [ob.run() for ob in all_obligations()]


def run_checked(obligations: Sequence[Obligation], *, on_result: Callable[[Result], None] | None = None) -> list[Result]:
    """Run ``obligations`` in order; one that raises is a failing :class:`Result`, never a holding one.

    ``on_result(result)``, if given, is called as soon as each is decided
    (``symbolic-friction check`` prints the row then).
    """
    import time

    from ._base import FAILS

    results: list[Result] = []
    for ob in obligations:
        start = time.perf_counter()
        try:
            result = ob.run()
        except Exception as exc:  # a crashing check is reported as failing, never as holding
            result = Result(
                id=ob.id, paper=ob.paper, statement=ob.statement, method=ob.method, status=FAILS,
                seconds=time.perf_counter() - start, reason=f"error while checking: {type(exc).__name__}: {exc}",
            )
        results.append(result)
        if on_result is not None:
            on_result(result)
    return results


def all_errata() -> list[Erratum]:
    """Every erratum declared by an obligation, deduplicated, in paper order."""
    seen: list[Erratum] = []
    for ob in all_obligations():
        for e in ob.errata:
            if e not in seen:
                seen.append(e)
    return seen
