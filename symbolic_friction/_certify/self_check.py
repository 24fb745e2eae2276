"""The verifiers refuse known-false certificates: ``check`` checks its own trusted base where it runs.

The package ships, in ``false_certificates/``, certificates that must *not*
be proved, and a true one per template that must be (a verifier that refuses
everything fails too).  ``manifest.json`` lists each file with the premise it
breaks and the exact set of checks that fail:

* a stability certificate per premise of :func:`.verify.premises`, and a
  quadratic one per premise of :func:`.quadratic.quadratic_premises`, its
  numbers edited so that this premise fails (with the premises it implies,
  when the premises are not independent: ``c₁ ≤ c₂`` cannot fail while
  ``P - c₁I ⪰ 0`` and ``c₂I - P ⪰ 0`` hold).  A sign premise (``k_p > 0``,
  ``c₁ > 0``, ``κ > 0``, …) is forged as a well-formed number of the wrong
  sign: the file format reads it, and the verifier must refuse it like any
  other premise;
* sup-flow certificates, one per premise only that template has (its pieces'
  order and horizon, ``p``, the tail's own ``P`` below ``pI`` or not a Lyapunov
  matrix, ``c₂`` against the flow, the exits of ``R̂`` on a finite piece and
  past ``T``, ``K₁ − I``), on a small true certificate with room (the premises
  it shares with the quadratic template are decided by the same functions, and
  broken by the quadratic files), and two true ones: five pieces, and one
  piece ``[0, ∞)`` closed by the tail at ``T = 0``;
* sup-flow version-2 certificates (:mod:`.sup_flow_v2`), one per premise only
  that version has (:data:`SUP_FLOW_V2_PREMISES`: ``ℓ ≥ 0``, ``c₂`` against
  the flow *and* the drag maps ``e^{At}D_ℓ``, ``K⁺ − I`` and ``K⁻ − I``, per
  sign ``sK₁₂ ≥ 0``, the drag rate and band forms, ``K₃ⱼ ≥ 0`` and
  ``γI − K^±``, the coupling ``U⁻ ≤ U⁺`` on ``σ = 0``, the exits where only
  the drag exit form fails on a finite piece and past ``T``, where only the
  planes fail for one sign, and without the drag split, and the bound under
  its own obligation; with the premises that fail with it where they are not
  independent: ``K^± − I`` is implied by the exits at ``t = 0``, the band form
  of ``s = +1`` by ``K⁺₃ⱼ ≥ 0`` and the exits), on a one-piece true certificate
  with the drag split (its frame is version 1's, decided by the same function
  and broken by the sup-flow files), and three true ones: that piece
  ``[0, ∞)``, the same split at ``t = 1/2``, and one without the drag split;
* hunting certificates: a box around a later zero of ``v``, a box that
  holds no zero, boxes shifted so that the zero lies just outside each end
  in ``σ`` and in ``τ`` (the Krawczyk inclusion, both ends), ``σ_lo = 0``, a
  monotonicity start ``τ_a`` before ``v`` peaks, a ``σ`` range where ``v' > 0``
  near ``τ = 0`` cannot be shown, each number of ``cycle`` edited, and a
  ``verdict`` of ``not proved``;
* reset-contraction certificates, one per premise of
  :data:`.reset_contraction_proof.PREMISES` (those of a file that claims an
  overshoot on Table I (a), those of one that does not on gains without
  overshoot), among them ``rho`` below ``|E₁₁(τ*)|``, a box around a later zero
  of ``E₃₁`` and a radius too large for a long dwell, and three true ones
  (Table I (a) with dwell 0 and with a dwell longer than the slip, and gains
  without overshoot).

:func:`refuse_false_certificates` verifies every file through the same
route as ``symbolic-friction verify`` and holds only if each false one is
refused *by the verifier* (exit 1 of ``verify``) naming exactly its
manifest's checks, each true one is proved, and every premise of the
stability, quadratic and reset-contraction verifiers (and each sup-flow
premise of :data:`SUP_FLOW_PREMISES` and :data:`SUP_FLOW_V2_PREMISES`) has a
false certificate.  A file the reader refuses as malformed (exit 2 of
``verify``), or one the verifier raises on, counts as not refused.  A dropped premise, a broken python-flint
or sympy, or a patched install then fails ``check``.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

__all__ = ["DIRECTORY", "SUP_FLOW_PREMISES", "SUP_FLOW_V2_PREMISES", "Refusal", "SelfCheck", "refuse_false_certificates", "expected_failures", "named_failures"]

DIRECTORY = Path(__file__).with_name("false_certificates")
"""Where the known-false (and the true) certificates are shipped."""


@dataclass(frozen=True)
class Refusal:
    """One shipped file and what the verifier said about it.

    Attributes
    ----------
    file : str
    premise : str or None
        The premise it breaks (None for a true control certificate).
    expected, named : tuple of str
        The checks that must fail, and those that failed (``malformed: …`` when the reader refused the
        file, ``crashed: …`` when the verifier raised: both are failures of the self-check).
    ok : bool
    """

    file: str
    premise: str | None
    expected: tuple[str, ...]
    named: tuple[str, ...]
    ok: bool

    def describe(self) -> str:
        if self.premise is None:
            return f"{self.file}: true, {'proved' if self.ok else 'REFUSED'}"
        if self.ok:
            return f"{self.file}: refused, naming {', '.join(self.named)}"
        return f"{self.file}: breaks {self.premise}; expected {', '.join(self.expected) or 'a refusal'}, got {', '.join(self.named) or 'proved'}"


@dataclass(frozen=True)
class SelfCheck:
    """The outcome of :func:`refuse_false_certificates`."""

    refusals: tuple[Refusal, ...]
    uncovered: tuple[str, ...]
    seconds: float

    @property
    def ok(self) -> bool:
        """Every file as its manifest says, every premise covered, and at least one file checked."""
        return bool(self.refusals) and all(r.ok for r in self.refusals) and not self.uncovered


def expected_failures(data: dict) -> list[str]:
    """The premises that fail on a stability or quadratic file's parsed JSON, read and decided as ``verify`` does."""
    return named_failures(_decide(data, "<forged>"))


def named_failures(report: Any) -> list[str]:
    """The names of the failing checks of a report of either template (``verdict`` when only the file's verdict fails)."""
    failing = [c.name for c in report.checks if not c.holds]
    if not failing and not report.proved:
        return ["verdict"]
    return failing


SUP_FLOW_PREMISES: tuple[str, ...] = (
    "the first piece starts at t = 0", "piece 3 starts where piece 2 ends", "the last piece ends at ∞",
    "T ≥ 0 (the last piece starts at or after 0)", "p > 0", "P − p·I ⪰ 0 (the paper's P)", "P − p·I ⪰ 0 (the tail's P)",
    "−(AᵀP + PA) ⪰ 0 (the tail's P)", "c2 ≥ ‖e^(At)‖² for every t ≥ 0",
    "K1 − I copositive (piece 1)", "piece 2: U ≥ |e^(At)w|² on the exits of R̂ for t in [2, 4)",
    "piece 5: U ≥ |e^(At)w|² on the exits of R̂ for t in [8, ∞)",
)
"""The sup-flow premises a shipped false certificate must break (those only the sup-flow template has, on the
five-piece true certificate the false ones are edited from)."""

SUP_FLOW_V2_PREMISES: tuple[str, ...] = (
    "ell1 ≥ 0", "ell2 ≥ 0", "ell3 ≥ 0",
    "c2 ≥ ‖e^(At)‖² for every t ≥ 0 and c2 ≥ ‖e^(At)·D_ℓ‖² (both signs)",
    "K+1 − I copositive (piece 1)", "K−1 − I copositive (piece 1)",
    "piece 1: K+12 ≥ 0", "piece 1: drag rate form of K+ (s = +1) copositive", "piece 1: drag band form of K+ (s = +1) copositive",
    "piece 1: K+31 ≥ 0", "piece 1: K+32 ≥ 0", "piece 1: K+33 ≥ 0", "piece 1: gamma·I − K+ copositive",
    "piece 1: −K−12 ≥ 0", "piece 1: drag rate form of K− (s = −1) copositive", "piece 1: drag band form of K− (s = −1) copositive",
    "piece 1: K−31 ≥ 0", "piece 1: K−32 ≥ 0", "piece 1: K−33 ≥ 0", "piece 1: gamma·I − K− copositive",
    "piece 1: coupling (K+ − K−) on (|dz φ|, |v|) copositive",
    "piece 1: U± ≥ |e^(At)w|² on the exits of R̂ and of f > ℓᵀy for t in [0, 1/2)",
    "piece 2: U± ≥ |e^(At)w|² on the exits of R̂ and of f > ℓᵀy for t in [1/2, ∞)",
    "piece 1: U± ≥ |e^(At)w|² on the exits of R̂ and of f > ℓᵀy for t in [0, ∞)",
    "piece 1: U± ≥ |e^(At)w|² on the exits of R̂ for t in [0, ∞)",
    "overshoot_bound > 0", "overshoot_bound² ≥ c2", "overshoot_bound² ≥ gamma (piece 1)",
)
"""The sup-flow version-2 premises a shipped false certificate must break (those only version 2 has, named on its
true certificates: one piece ``[0, ∞)`` with the drag split, split at ``t = 1/2``, and one piece without the split,
whose exits are the planes alone; the bound's premises are listed here as they are version 2's obligation)."""


def _premise_names() -> dict[str, list[str]]:
    """Every premise name a false certificate must break, per manifest ``template``: those of the stability and the
    quadratic verifier (on a stand-in whose numbers are all 1), and the listed sup-flow and reset-contraction ones."""
    from .quadratic import CONSTANTS, quadratic_premises
    from .verify import premises

    class One:
        constants = {name: Fraction(1) for name in CONSTANTS}

        def __getattr__(self, name: str) -> Fraction:
            return Fraction(1)

    from .reset_contraction_proof import PREMISES as RESET_PREMISES

    return {"stability": [p.name for p in premises(One())], "quadratic": [p.name for p in quadratic_premises(One())],
            "sup-flow": list(SUP_FLOW_PREMISES), "sup-flow/v2": list(SUP_FLOW_V2_PREMISES),
            "reset-contraction": list(RESET_PREMISES)}


def _decide(data: object, source: str) -> Any:
    """Read a parsed file and decide it as ``verify`` does, without the stability format's second reader (the JSON Schema: 10 ms a file)."""
    from ._template import template_for
    from .certificate import Certificate
    from .templates import builtin_templates

    stability = builtin_templates()[0]
    template = template_for(data, fallback=stability)
    certificate = Certificate.from_dict(data) if template is stability else template.read(data, source)
    return template.verify(certificate, source)


def _one(path: Path, entry: dict) -> Refusal:
    from .._infra.errors import CertificateFormatError
    from ._json import read_json

    premise, expected = entry["premise"], tuple(entry["fails"])
    try:
        report = _decide(read_json(path), str(path))
    except CertificateFormatError as exc:  # refused as malformed (exit 2), not by the verifier: not a refusal
        return Refusal(path.name, premise, expected, (f"malformed: {exc}",), False)
    except Exception as exc:  # a verifier that raises has refused nothing (`verify` would not exit 1)
        return Refusal(path.name, premise, expected, (f"crashed: {type(exc).__name__}: {exc}",), False)
    named = tuple(named_failures(report))
    if premise is None:
        return Refusal(path.name, None, (), named, report.proved)
    return Refusal(path.name, premise, expected, named, not report.proved and named == expected)


def refuse_false_certificates(directory: str | Path = DIRECTORY) -> SelfCheck:
    """Verify every file of ``directory``'s manifest and compare with what it must give (module docstring)."""
    start = time.perf_counter()
    directory = Path(directory)
    manifest = json.loads((directory / "manifest.json").read_text(encoding="utf-8"))["false_certificates"]
    from .hunting import shared_proofs
    from .reset_contraction_proof import shared_enclosures
    from .box import shared_corners
    from .sup_flow import shared_decisions

    with shared_proofs(), shared_enclosures(), shared_decisions(), shared_corners():
        refusals = tuple(_one(directory / entry["file"], entry) for entry in manifest)
    uncovered = tuple(
        f"{template}: {name}"
        for template, names in _premise_names().items()
        for name in names
        if name not in {entry["premise"] for entry in manifest if entry["template"] == template}
    )
    return SelfCheck(refusals, uncovered, time.perf_counter() - start)
