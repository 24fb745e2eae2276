"""The hunting certificate: a file that proves a symmetric hunting cycle exists.

Format (JSON, every number that the proof reads is an exact rational string)::

    {
      "schema": "symbolic-friction/hunting-certificate/v1",
      "claim": "symmetric hunting cycle",
      "parameters": {"k_p": "3", "k_i": "4", "k_v": "32/5", "f_c": "1", "f_s": "6/5"},
      "box": {"sigma": [lo, hi], "tau": [lo, hi], "monotone_from": "…"},
      "precision_bits": 128,
      "verdict": "proved",
      "cycle": {"period": [lo, hi], "stable": true, …}   # optional: what it proves about the cycle
    }

:func:`verify_hunting` re-runs :func:`._proof.prove_cycle` on the exact
gains and box, decides every number of ``cycle`` (:mod:`.hunting_cycle`:
``sigma``, ``slip_time``, ``stick_time``, ``period``, ``multiplier``, each an
interval that must hold the enclosure over the Krawczyk box, and ``stable``)
and accepts the file only if every check holds *and* the file says
``"proved"``.  A file is stale (:func:`hunting_staleness`) when it differs
from what :func:`certificate_for` writes for its gains and the zero in its
box.  Changing a gain or a corner of the box moves the
problem: the Krawczyk test, the first-zero test or the stick test then fails
(or a file that claims something it cannot show is refused).  ``symbolic-friction
verify`` dispatches on the ``schema`` field; the stability certificates of the
paper's model keep their own verifier (:mod:`.._certify.verify`).

With ``f_s = f_c`` (the paper's model) there is nothing to certify here:
Proposition 1 (𝒜 globally asymptotically stable) holds, and the package's
stability certificates (``symbolic-friction certify``) prove it for given
gains, so no hunting cycle exists.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from .._infra.bounds import bound_text
from .._infra.errors import CertificateFormatError, InputFileError, SymbolicFrictionError
from .._model.parameters import Parameters
from ._template import Template, register
from .hunting_cycle import CycleClaims, decide_claims, polish, state_claims
from ._memo import Memo
from .hunting_proof import PRECISION, Box, CycleProof, box_around, prove_cycle, Check

__all__ = ["SCHEMA", "HuntingCertificate", "HuntingReport", "verify_hunting", "verify_hunting_file", "write_hunting",
           "certificate_for", "regenerate_hunting", "hunting_staleness", "HUNTING"]

SCHEMA = "symbolic-friction/hunting-certificate/v1"
TEMPLATE_ID = "hunting-cycle/v1"
"""The template id of a hunting certificate (the optional ``template`` member)."""
CLAIM = "symmetric hunting cycle"
_TOP = ("schema", "claim", "parameters", "box", "precision_bits", "verdict")
_OPTIONAL = ("cycle", "template")
_PARAMS = ("k_p", "k_i", "k_v", "f_c", "f_s")


def _exact(value: object, where: str) -> Fraction:
    """An exact rational string of the file format, read as strictly as a stability certificate's."""
    from .certificate import _signed_rational_field

    return _signed_rational_field(value, where)


def _pair(value: object, where: str) -> tuple[Fraction, Fraction]:
    if not (isinstance(value, list) and len(value) == 2):
        raise CertificateFormatError(f"{where} must be a list [lo, hi] of two rational strings; got {value!r}")
    return _exact(value[0], f"{where}[0]"), _exact(value[1], f"{where}[1]")


@dataclass(frozen=True)
class HuntingCertificate:
    """The content of a hunting certificate (exact)."""

    params: Parameters
    box: Box
    precision_bits: int = PRECISION
    verdict: str = "proved"
    cycle: CycleClaims | None = None

    def __post_init__(self) -> None:
        if self.cycle is not None and not isinstance(self.cycle, CycleClaims):
            raise CertificateFormatError(f"cycle must be CycleClaims or None; got {type(self.cycle).__name__}")

    def gains_text(self) -> str:
        """The exact gains, as ``check`` and ``verify`` print them."""
        return ", ".join(f"{name} = {value}" for name, value in self.params.as_strings().items())

    def to_dict(self) -> dict[str, Any]:
        from .._infra.rational import format_rational as s

        p = self.params
        out: dict[str, Any] = {
            "schema": SCHEMA,
            "claim": CLAIM,
            "parameters": {name: s(getattr(p, name)) for name in _PARAMS},
            "box": {
                "sigma": [s(self.box.sigma[0]), s(self.box.sigma[1])],
                "tau": [s(self.box.tau[0]), s(self.box.tau[1])],
                "monotone_from": s(self.box.monotone_from),
            },
            "precision_bits": int(self.precision_bits),
            "verdict": self.verdict,
        }
        if self.cycle is not None:
            out["cycle"] = self.cycle.to_dict()
        return out

    @classmethod
    def from_dict(cls, data: object) -> "HuntingCertificate":
        """Parse strictly; :class:`CertificateFormatError` names what is wrong."""
        if not isinstance(data, dict):
            raise CertificateFormatError(f"a hunting certificate is a JSON object; got {type(data).__name__}")
        if data.get("schema") != SCHEMA:
            raise CertificateFormatError(f"unknown schema {data.get('schema')!r}; expected {SCHEMA!r}")
        missing = [k for k in _TOP if k not in data]
        unknown = [k for k in data if k not in _TOP + _OPTIONAL]
        if missing or unknown:
            raise CertificateFormatError(f"hunting certificate: missing keys {missing}, unknown keys {unknown}")
        if "template" in data and data["template"] != TEMPLATE_ID:
            raise CertificateFormatError(f"template {data['template']!r} is not a hunting certificate's ({TEMPLATE_ID!r})")
        if data["claim"] != CLAIM:
            raise CertificateFormatError(f"unknown claim {data['claim']!r}; expected {CLAIM!r}")
        params = data["parameters"]
        if not isinstance(params, dict) or sorted(params) != sorted(_PARAMS):
            raise CertificateFormatError(f"parameters must have exactly the keys {list(_PARAMS)}; got {params!r}")
        gains = {k: _exact(params[k], f"parameters.{k}") for k in _PARAMS}
        try:
            p = Parameters(**gains)
        except SymbolicFrictionError as exc:
            raise CertificateFormatError(f"parameters: {exc}") from None
        box = data["box"]
        if not isinstance(box, dict) or sorted(box) != ["monotone_from", "sigma", "tau"]:
            raise CertificateFormatError(f"box must have the keys sigma, tau, monotone_from; got {box!r}")
        prec = data["precision_bits"]
        if isinstance(prec, bool) or not isinstance(prec, int) or not 53 <= prec <= 4096:
            raise CertificateFormatError(f"precision_bits must be an integer in [53, 4096]; got {prec!r}")
        if data["verdict"] not in ("proved", "not proved"):
            raise CertificateFormatError(f"verdict must be 'proved' or 'not proved'; got {data['verdict']!r}")
        return cls(
            params=p,
            box=Box(
                sigma=_pair(box["sigma"], "box.sigma"),
                tau=_pair(box["tau"], "box.tau"),
                monotone_from=_exact(box["monotone_from"], "box.monotone_from"),
            ),
            precision_bits=prec,
            verdict=data["verdict"],
            cycle=CycleClaims.from_dict(data["cycle"]) if "cycle" in data else None,
        )


@dataclass(frozen=True)
class HuntingReport:
    """The outcome of :func:`verify_hunting` (the shape ``symbolic-friction verify`` prints)."""

    source: str
    certificate: HuntingCertificate
    proof: CycleProof
    claims: tuple[Check, ...] = ()

    @property
    def checks(self) -> tuple[Check, ...]:
        """The proof's checks, then one per number the file's ``cycle`` states."""
        return self.proof.checks + self.claims

    @property
    def proved(self) -> bool:
        return self.proof.proved and all(c.holds for c in self.claims) and self.certificate.verdict == "proved"

    def summary(self) -> str:
        p = self.certificate.params
        lo, hi = self.certificate.box.sigma
        if self.proved:
            m_lo, m_hi = self.proof.multiplier
            stab = {True: "stable", False: "unstable", None: "stability undecided"}[self.proof.stable]
            return (
                f"PROVED {self.source}: a symmetric hunting cycle exists for {p} through σ* ∈ "
                f"[{bound_text(lo, 12, direction='down')}, {bound_text(hi, 12, direction='up')}] (unique there); multiplier ∈ "
                f"[{bound_text(Fraction(m_lo), 6, direction='down')}, {bound_text(Fraction(m_hi), 6, direction='up')}], {stab}"
            )
        failing = [c.name for c in self.checks if not c.holds]
        if not failing:
            return f"NOT PROVED {self.source}: the file's verdict is {self.certificate.verdict!r}"
        return f"NOT PROVED {self.source}: {', '.join(failing)} fail(s) for {p}"


def verify_hunting(certificate: HuntingCertificate, *, source: str = "<certificate>") -> HuntingReport:
    """Re-run the proof (:func:`._proof.prove_cycle`) on the certificate's exact gains and box, and decide its ``cycle``."""
    key = (certificate.params, certificate.box, certificate.precision_bits)
    proof = _PROOFS.get(key, lambda: prove_cycle(*key[:2], precision=key[2]))
    _LAST_PROOF[:] = [(certificate, proof)]
    claims = () if certificate.cycle is None else decide_claims(
        certificate.params, proof, certificate.cycle, precision=certificate.precision_bits)
    return HuntingReport(source=source, certificate=certificate, proof=proof, claims=claims)


_PROOFS = Memo()
shared_proofs = _PROOFS.sharing
"""Within the block, files with the same gains, box and precision share one proof (they differ only in ``cycle`` or ``verdict``)."""


_LAST_PROOF: list = []
"""The last certificate :func:`verify_hunting` decided (the object itself) and its proof: its staleness reuses it."""


def certificate_for(params: Parameters, sigma: float | Fraction, tau: float | Fraction, *,
                    known: tuple[Box, int, CycleProof] | None = None) -> tuple[HuntingCertificate, CycleProof]:
    """The certificate ``symbolic-friction hunting`` writes for the cycle near ``(σ, τ)``, and its proof.

    The zero is polished (:func:`.hunting_cycle.polish`) before the box is
    drawn around it, so the file depends on the zero, not on the search
    that found it; ``cycle`` states what the verifier proves about it (None
    if the proof fails).
    """
    box = box_around(*polish(params, sigma, tau))
    # `known`: a proof of (box, precision) for these gains just decided, which `check` need not repeat
    proof = known[2] if known is not None and known[:2] == (box, PRECISION) else prove_cycle(params, box)
    return HuntingCertificate(params=params, box=box, cycle=state_claims(params, proof)), proof


def regenerate_hunting(certificate: HuntingCertificate) -> HuntingCertificate:
    """What ``symbolic-friction hunting`` writes for the gains of ``certificate`` and the zero in its box.

    Raises
    ------
    CertificateError
        If the box drawn around the polished zero is not proved (nothing unproved is written).
    """
    from .._infra.errors import CertificateError

    (s_lo, s_hi), (t_lo, t_hi) = certificate.box.sigma, certificate.box.tau
    last = _LAST_PROOF[0] if _LAST_PROOF else None
    # `check` verifies a file, then asks whether it is stale: the proof of that very certificate is reused
    known = (certificate.box, certificate.precision_bits, last[1]) if last is not None and last[0] is certificate else None
    fresh, proof = certificate_for(certificate.params, (s_lo + s_hi) / 2, (t_lo + t_hi) / 2, known=known)
    if not proof.proved:
        failing = ", ".join(c.name for c in proof.checks if not c.holds)
        raise CertificateError(f"the box around the polished zero for {certificate.params} is not proved ({failing})")
    return fresh


def hunting_staleness(certificate: HuntingCertificate, path: Path) -> str:
    """Why the committed ``path`` differs from what :func:`regenerate_hunting` writes now ("" if not)."""
    from .._infra.errors import CertificateError
    from .._infra.io import read_limited
    from ._json import MAX_FILE_BYTES

    try:
        fresh = regenerate_hunting(certificate)
    except CertificateError as exc:
        return f"cannot be regenerated: {exc}"
    if read_limited(path, limit=MAX_FILE_BYTES, what="certificate") != dumps(fresh).encode("utf-8"):
        return f"{path.name} differs from what `symbolic-friction hunting` writes now for its gains"
    return ""


def is_hunting(data: object) -> bool:
    """Whether a parsed certificate file is a hunting certificate (its ``schema``)."""
    return isinstance(data, dict) and data.get("schema") == SCHEMA


def hunting_from_data(data: object, *, source: str = "<string>") -> HuntingCertificate:
    """The hunting certificate in a parsed JSON value; :class:`CertificateFormatError` names ``source``."""
    try:
        return HuntingCertificate.from_dict(data)
    except CertificateFormatError as exc:
        raise CertificateFormatError(f"{source}: {exc}") from None


def load_hunting(path: str | os.PathLike[str]) -> HuntingCertificate:
    """Read (strictly, within the package's bounds) and parse a hunting certificate file."""
    from .certificate import read_json

    return hunting_from_data(read_json(path), source=str(path))


def verify_hunting_file(path: str | os.PathLike[str]) -> HuntingReport:
    """Load and verify one hunting certificate file."""
    return verify_hunting(load_hunting(path), source=str(path))


def dumps(certificate: HuntingCertificate) -> str:
    return json.dumps(certificate.to_dict(), indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def write_hunting(certificate: HuntingCertificate, path: str | os.PathLike[str]) -> Path:
    """Write the certificate atomically (:func:`.._io.atomic_write_text`)."""
    from .._infra.io import atomic_write_text

    return atomic_write_text(path, dumps(certificate))


def is_hunting_file(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` is a hunting certificate (``crosscheck`` leaves those out of its default list)."""
    from .certificate import read_json

    try:
        return is_hunting(read_json(path))
    except (CertificateFormatError, InputFileError):
        return False  # the certificate loader says what is wrong with it


HUNTING = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: hunting_from_data(data, source=source),
    verify=lambda certificate, source: verify_hunting(certificate, source=source),
    dumps=dumps,
    # the statement is the file itself (verify decides it); regeneration only finds other digits
    stale=lambda certificate, path: "",
    drift=hunting_staleness,
    failure=lambda report: report.summary(),
    claim=lambda certificate: "a hunting cycle",
    default=True,
))
"""The hunting certificate: a Krawczyk box around a symmetric stick–slip cycle (beyond the paper)."""
