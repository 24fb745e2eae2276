"""The quadratic template: a certificate of Proposition 1's bound with a free ``P`` and a general ``V̂`` (beyond the paper).

The model of the template is :mod:`symbolic_friction._model.quadratic`; this
module reads and writes its files and decides them exactly.  With ``P`` of
:func:`~symbolic_friction._model.quadratic.quadratic_p_entries` and
``U = yᵀKy`` (``K₁₂ = 0``), a certificate is proved when, in exact rationals
(semidefiniteness by every principal minor, copositivity by
:mod:`._certify.copositive`):

* Assumption 1 and ``f_c > 0``;
* ``P − I ⪰ 0`` (``|x|²_𝒜 ≤ V`` everywhere) and ``c₂I − P ⪰ 0`` (``V ≤ c₂|x|²_𝒜`` on ``R``);
* ``c > 0`` and ``−(AᵀP + PA) − c e₃e₃ᵀ ⪰ 0``: eq. (Vdecrease) with this ``c``;
* ``−(K B_s + B_sᵀ K)`` and the band form copositive for ``s = ±1``, and
  ``K₃₁, K₃₂, K₃₃ ≥ 0``: ``U`` does not increase on ``R̂``;
* ``K − I`` and ``γI − K`` copositive: ``|x|²_𝒜 ≤ U ≤ γ|x|²_𝒜`` on ``R̂``;
* the two exit forms copositive: ``U ≥ V`` where a solution leaves ``R̂``;
* ``κ > 0``, ``κ² ≥ c₂`` and ``κ² ≥ γ``: eq. (stabState) with ``max(c₂, γ)`` for ``c₂ĉ₂/(c₁ĉ₁)``.

Format (``schema`` ``symbolic-friction/quadratic-certificate/v1``, ``template``
``quadratic/v1``; keys sorted, exact rational strings, no timings)::

    {"constants": {"c": …, "c2": …, "gamma": …, "k11": …, "k13": …, "k22": …, "k23": …,
                   "k33": …, "p11": …, "p22": …, "p33": …},
     "overshoot_bound": "1.80855", "parameters": {…}, "provenance": {…},
     "schema": "symbolic-friction/quadratic-certificate/v1", "template": "quadratic/v1"}
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any, ClassVar

from .._infra.errors import CertificateFormatError
from .._infra.rational import format_rational as _f
from .._model import quadratic as model
from ._template import Template, register
from .copositive import decide_copositive
from .verify import Check, Inequality, Semidefinite, VerificationReport, decide

__all__ = [
    "SCHEMA", "TEMPLATE_ID", "CONSTANTS", "OBLIGATIONS", "QuadraticCertificate", "QuadraticReport",
    "QuadraticProvenance", "Copositive", "quadratic_premises", "verify_quadratic", "dumps_quadratic", "not_canonical", "canonical_staleness", "Gains", "GainsAndBound", "PARAMETERS", "check_provenance", "read_common", "QUADRATIC",
]

SCHEMA = "symbolic-friction/quadratic-certificate/v1"
TEMPLATE_ID = "quadratic/v1"
PARAMETERS = ("k_p", "k_i", "k_v", "f_c")
CONSTANTS = ("p11", "p22", "p33", "c", "c2", "k11", "k13", "k22", "k23", "k33", "gamma")
OBLIGATIONS = (
    "lemma2.P",
    "quadratic.P_structure",
    "quadratic.V_decrease",
    "quadratic.U_rate",
    "quadratic.U_exit",
    "quadratic.stability_bound",
)
"""The proof obligations (ids of ``symbolic-friction check``) a quadratic certificate instantiates."""
_TOP = ("schema", "template", "parameters", "constants", "overshoot_bound")
_PROVENANCE = ("package", "search", "solver", "solver_status", "margin", "label")


@dataclass(frozen=True)
class QuadraticProvenance:
    """How a certificate of a template beyond the paper was found (informative; never part of the proof).

    The quadratic and the sup-flow templates record the same fields (their searches are SDPs).
    """

    search: str = "sdp"
    solver: str = ""
    solver_status: str = ""
    margin: str = ""
    label: str = ""
    package: str = "symbolic-friction"

    def __post_init__(self) -> None:
        check_provenance(self, _PROVENANCE)

    def to_dict(self) -> dict[str, str]:
        return {name: getattr(self, name) for name in _PROVENANCE}


def check_provenance(provenance: Any, names: tuple[str, ...]) -> None:
    """Every provenance field in ``names`` is a string of at most 10,000 characters (informative, but bounded)."""
    for name in names:
        value = getattr(provenance, name)
        if not isinstance(value, str) or len(value) > 10_000:
            raise CertificateFormatError(f"provenance.{name} must be a string of at most 10000 characters; got {value!r:.60}")


class Gains:
    """A certificate's gains ``k_p, k_i, k_v, f_c`` (fields of the subclass), by name and as text."""

    @property
    def parameters(self) -> dict[str, Fraction]:
        """The gains, by name."""
        return {name: getattr(self, name) for name in PARAMETERS}

    def gains_text(self) -> str:
        """``"k_p=3, k_i=4, k_v=32/5, f_c=1"``."""
        return ", ".join(f"{name}={_f(value)}" for name, value in self.parameters.items())


class GainsAndBound(Gains):
    """What a certificate of the templates beyond the paper says of its gains and bound (no fields of its own).

    A subclass has the gains ``k_p, k_i, k_v, f_c`` and ``overshoot_bound`` (decimal text).
    """

    @property
    def kappa(self) -> Fraction:
        """The overshoot bound as an exact number."""
        from ._json import decimal_value

        return decimal_value(self.overshoot_bound)  # type: ignore[attr-defined]  # any length (not Fraction(text))

    def common_dict(self, schema: str, template_id: str, constants: tuple[str, ...]) -> dict[str, Any]:
        """The members :func:`read_common` reads, as the file writes them (``constants``: those the certificate has)."""
        return {
            "schema": schema,
            "template": template_id,
            "parameters": {name: _f(getattr(self, name)) for name in PARAMETERS},
            "constants": {name: _f(self.constants[name]) for name in constants if name in self.constants},  # type: ignore[attr-defined]
            "overshoot_bound": self.overshoot_bound,  # type: ignore[attr-defined]
            "provenance": self.provenance.to_dict(),  # type: ignore[attr-defined]
        }


@dataclass(frozen=True)
class QuadraticCertificate(GainsAndBound):
    """Gains, the constants of ``P``, ``U`` and the bound, and how they were found (informative only).

    Every number is an exact rational of any sign (``overshoot_bound`` a plain
    decimal string): the signs the proof needs are premises of
    :func:`quadratic_premises`, so a false certificate is held and refused by
    :func:`verify_quadratic`, not by the constructor.
    """

    k_p: Fraction
    k_i: Fraction
    k_v: Fraction
    f_c: Fraction
    constants: dict[str, Fraction]
    overshoot_bound: str
    provenance: QuadraticProvenance = field(default_factory=QuadraticProvenance)

    def __post_init__(self) -> None:
        # any sign: k_p > 0, k_i > 0, f_c > 0 are premises, refused by the verifier naming them
        for name in PARAMETERS:
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, Fraction)):
                raise CertificateFormatError(f"parameters.{name} must be an exact rational; got {value!r}")
            object.__setattr__(self, name, Fraction(value))
        if sorted(self.constants) != sorted(CONSTANTS):
            raise CertificateFormatError(f"constants must be exactly {', '.join(CONSTANTS)}; got {', '.join(sorted(self.constants))}")
        for name, value in self.constants.items():
            if isinstance(value, bool) or not isinstance(value, (int, Fraction)):
                raise CertificateFormatError(f"constants.{name} must be an exact rational; got {value!r}")

    def p_matrix(self) -> tuple[tuple[Fraction, ...], ...]:
        c = self.constants
        return model.quadratic_p_entries(self.k_p, self.k_i, self.k_v, c["p11"], c["p22"], c["p33"])

    def k_matrix(self) -> tuple[tuple[Fraction, ...], ...]:
        c = self.constants
        return model.u_matrix_entries(c["k11"], c["k13"], c["k22"], c["k23"], c["k33"])

    def to_dict(self) -> dict[str, Any]:
        return self.common_dict(SCHEMA, TEMPLATE_ID, CONSTANTS)

    @classmethod
    def from_dict(cls, data: object, *, source: str = "<string>") -> "QuadraticCertificate":
        params, constants, provenance, bound = read_common(data, source, what="quadratic", schema=SCHEMA,
                                                           template_id=TEMPLATE_ID, top=_TOP, constants=CONSTANTS)
        return cls(**params, constants=constants, overshoot_bound=bound, provenance=provenance)


def read_common(data: object, source: str, *, what: str, schema: str, template_id: str, top: tuple[str, ...],
                constants: tuple[str, ...], optional_constants: tuple[str, ...] = ()
                ) -> tuple[dict[str, Fraction], dict[str, Fraction], QuadraticProvenance, str]:
    """The members a quadratic or sup-flow file share, read strictly: ``(gains, constants, provenance, bound)``.

    Raises
    ------
    CertificateFormatError
        Naming the member that is missing, unknown, of the wrong type or not an exact rational.
    """
    from .certificate import _check_keys, _decimal_field, _signed_rational_field

    if not isinstance(data, dict):
        raise CertificateFormatError(f"{source}: a {what} certificate is a JSON object; got {type(data).__name__}")
    _check_keys(data, required=top, optional=("provenance",), where="certificate")
    if data["schema"] != schema or data["template"] != template_id:
        raise CertificateFormatError(f"{source}: schema {data['schema']!r} / template {data['template']!r} is not {schema} / {template_id}")
    for key, names, optional in (("parameters", PARAMETERS, ()), ("constants", constants, optional_constants)):
        if not isinstance(data[key], dict):
            raise CertificateFormatError(f"{source}: {key} must be a JSON object; got {type(data[key]).__name__}")
        _check_keys(data[key], required=names, optional=optional, where=key)
    params = {n: _signed_rational_field(data["parameters"][n], f"parameters.{n}") for n in PARAMETERS}
    values = {n: _signed_rational_field(data["constants"][n], f"constants.{n}") for n in (*constants, *optional_constants)
              if n in data["constants"]}
    provenance = data.get("provenance", {})
    if not isinstance(provenance, dict):
        raise CertificateFormatError(f"{source}: provenance must be a JSON object")
    _check_keys(provenance, required=(), optional=_PROVENANCE, where="provenance")
    return params, values, QuadraticProvenance(**provenance), _decimal_field(data["overshoot_bound"], "overshoot_bound")


@dataclass(frozen=True)
class Copositive:
    """The premise ``yᵀMy ≥ 0`` for every ``y ≥ 0``."""

    obligation: str
    name: str
    matrix: tuple[tuple[Any, ...], ...]


def _sub(a, b):
    return tuple(tuple(x - y for x, y in zip(ra, rb)) for ra, rb in zip(a, b))


def _scaled_identity(n: int, scale: Any) -> tuple[tuple[Any, ...], ...]:
    return tuple(tuple(scale if i == j else scale - scale for j in range(n)) for i in range(n))


def quadratic_premises(cert: Any) -> list[Inequality | Semidefinite | Copositive]:
    """Every premise of a quadratic certificate, in proof order (plain arithmetic: Fractions or sympy)."""
    k_p, k_i, k_v, f_c = cert.k_p, cert.k_i, cert.k_v, cert.f_c
    const = cert.constants
    zero = k_i - k_i
    p = model.quadratic_p_entries(k_p, k_i, k_v, const["p11"], const["p22"], const["p33"])
    k = model.u_matrix_entries(const["k11"], const["k13"], const["k22"], const["k23"], const["k33"])
    q = model.lyapunov_rate_entries(k_p, k_i, k_v, p)
    c = const["c"]
    decrease = tuple(tuple(-q[i][j] - (c if i == j == 2 else zero) for j in range(3)) for i in range(3))
    out: list[Inequality | Semidefinite | Copositive] = [
        Inequality("lemma2.P", "k_i > 0", k_i, ">", zero),
        Inequality("lemma2.P", "k_p > 0", k_p, ">", zero),
        Inequality("lemma2.P", "k_v·k_p > k_i", k_v * k_p, ">", k_i),
        Inequality("model", "f_c > 0", f_c, ">", zero),
        Semidefinite("quadratic.P_structure", "P − I ⪰ 0", _sub(p, _scaled_identity(3, zero + 1))),
        Semidefinite("quadratic.P_structure", "c2·I − P ⪰ 0", _sub(_scaled_identity(3, const["c2"]), p)),
        Inequality("quadratic.V_decrease", "c > 0", c, ">", zero),
        Semidefinite("quadratic.V_decrease", "−(AᵀP + PA) − c·e3e3ᵀ ⪰ 0", decrease),
    ]
    for s, sign in ((1, "+"), (-1, "−")):
        b = model.slip_rate_entries(k_p, k_i, k_v, zero + s)
        out.append(Copositive("quadratic.U_rate", f"−(K·B{sign} + B{sign}ᵀ·K) copositive", model.u_rate_entries(k, b)))
        out.append(Copositive("quadratic.U_rate", f"band form (s = {sign}1) copositive", model.band_rate_entries(k_i, k_v, k, zero + s)))
    for j in range(3):
        out.append(Inequality("quadratic.U_rate", f"K3{j + 1} ≥ 0", k[2][j], ">=", zero))
    out.append(Copositive("quadratic.U_exit", "K − I copositive", _sub(k, _scaled_identity(3, zero + 1))))
    out.append(Copositive("quadratic.U_exit", "gamma·I − K copositive", _sub(_scaled_identity(3, const["gamma"]), k)))
    at_rest, at_edge = model.exit_entries(k, p)
    out.append(Copositive("quadratic.U_exit", "U − V copositive at v = 0", at_rest))
    out.append(Copositive("quadratic.U_exit", "U − V copositive at φ = ±f_c", at_edge))
    kappa = cert.kappa
    out += [
        Inequality("quadratic.stability_bound", "overshoot_bound > 0", kappa, ">", zero),
        Inequality("quadratic.stability_bound", "overshoot_bound² ≥ c2", kappa * kappa, ">=", const["c2"]),
        Inequality("quadratic.stability_bound", "overshoot_bound² ≥ gamma", kappa * kappa, ">=", const["gamma"]),
    ]
    return out


def decide_premise(premise: Inequality | Semidefinite | Copositive) -> Check:
    """Decide one premise exactly (copositivity by :func:`._certify.copositive.decide_copositive`)."""
    if isinstance(premise, Copositive):
        try:
            decision = decide_copositive(premise.matrix)
        except ValueError as exc:
            return Check(premise.obligation, premise.name, str(exc), False)
        text = "[" + "; ".join(", ".join(_f(Fraction(x)) for x in row) for row in premise.matrix) + "]"
        verdict = {True: "", False: " — refuted", None: " — undecided, so not proved"}[decision.holds]
        return Check(premise.obligation, premise.name, f"{text}: {decision.reason}{verdict}", decision.holds is True)
    return decide(premise)


@dataclass(frozen=True)
class QuadraticReport(VerificationReport):
    """Per-premise verdicts of a quadratic certificate.

    ``proved``, ``failures``, ``raise_if_failed`` and the FAILED line are the
    stability verifier's (:class:`~.verify.VerificationReport`): one rule for
    every template (proved iff there is a check and every one holds).
    """

    certificate: QuadraticCertificate  # type: ignore[assignment]
    checks: tuple[Check, ...]
    source: str = "<certificate>"
    template_name: ClassVar[str] = "quadratic"

    def summary(self) -> str:
        if self.proved:
            return (f"PROVED {self.source}: all {len(self.checks)} premises of the {self.template_name} template hold; "
                    f"|x(t)|_A <= {self.certificate.overshoot_bound}·|x(0)|_A")
        return super().summary()


def verify_quadratic(certificate: QuadraticCertificate, *, source: str = "<certificate>") -> QuadraticReport:
    """Decide every premise of :func:`quadratic_premises` exactly."""
    if not isinstance(certificate, QuadraticCertificate):
        raise TypeError(f"verify_quadratic needs a QuadraticCertificate; got {type(certificate).__name__}")
    return QuadraticReport(certificate, tuple(decide_premise(p) for p in quadratic_premises(certificate)), source)


def dumps_quadratic(certificate: QuadraticCertificate) -> str:
    """The file's bytes: sorted keys, two-space indentation, trailing newline."""
    return json.dumps(certificate.to_dict(), indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def not_canonical(text: str, path: Path) -> str:
    """Why the committed ``path`` is not ``text``, the canonical file of its own numbers (empty if it is).

    For the templates whose search is an SDP (quadratic, sup-flow): its
    rounding may differ between solver versions; that is drift, not a
    different statement, so staleness does not re-run the search: the file
    must be exactly what the template writes for the numbers it holds.
    """
    from .._infra.io import read_limited
    from ._json import MAX_FILE_BYTES

    if read_limited(Path(path), limit=MAX_FILE_BYTES, what="certificate") != text.encode("utf-8"):
        return f"{Path(path).name} is not in canonical form (keys sorted, two-space indentation, exact rationals)"
    return ""


def canonical_staleness(dumps: Callable[[Any], str]) -> Callable[[Any, Path], str]:
    """A template's ``stale``: the committed file must be ``dumps`` of its own numbers (:func:`not_canonical`)."""
    return lambda certificate, path: not_canonical(dumps(certificate), path)


QUADRATIC = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: QuadraticCertificate.from_dict(data, source=source),
    verify=lambda certificate, source: verify_quadratic(certificate, source=source),
    dumps=dumps_quadratic,
    stale=canonical_staleness(dumps_quadratic),
    claim=lambda certificate: f"κ ≤ {certificate.overshoot_bound} (quadratic template)",
    default=True,
))
"""The quadratic template (beyond the paper): free ``P`` with ``P₁₂ = 0`` and ``U = yᵀKy``."""
