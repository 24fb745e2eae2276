"""The certificate of Lemma 2, Lemma 3 and Proposition 1 for one gain set, and
its JSON file format ``symbolic-friction/certificate/v1``.

A certificate holds, as exact rationals, the gains ``(k_p, k_i, k_v, f_c)``
and the constants that instantiate

* Lemma 2: ``c₁|x|²_𝒜 ≤ V(x)`` and ``V̇ ≤ -c v²`` with ``c = 2(k_v k_p - k_i)``;
* Lemma 3: ``c₁|x|²_𝒜 ≤ V ≤ c₂|x|²_𝒜`` on ``R`` (eq. VandR),
  ``ĉ₁|x|²_𝒜 ≤ V̂ ≤ ĉ₂|x|²_𝒜`` on ``R̂`` (eq. hatVandHatR) and
  ``V̂° ≤ 0`` on ``R̂`` (eq. hatVdot) through ``k₁ … k₄``;
* Proposition 1, eq. (stabState): ``|x(t)|_𝒜 ≤ κ|x(0)|_𝒜`` with
  ``κ = √(c₂ĉ₂/(c₁ĉ₁))``, written as the decimal ``overshoot_bound ≥ κ``.

This module only reads and writes the data: it checks the *form* of a file
(JSON, schema, keys, exact rational strings, plain decimals, sizes) and raises
:class:`~symbolic_friction.CertificateFormatError` naming the offending key.
Whether the numbers *prove* anything, signs included (``k_p > 0``, ``κ > 0``:
premises, so a number of the wrong sign makes a *false* certificate, not a
malformed file), is decided by :mod:`._certify.verify`.

File format (keys sorted, two-space indentation, trailing newline; no
timestamps, timings or third-party version numbers, so that regenerating a
certificate gives a byte-identical file on any machine)::

    {
      "constants": {"c": "152/5", "c1": "1", "c1_hat": "1", ...},
      "overshoot_bound": "3.69516",
      "parameters": {"f_c": "1", "k_i": "4", "k_p": "3", "k_v": "32/5"},
      "provenance": {...},
      "schema": "symbolic-friction/certificate/v1"
    }
"""

from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from .._infra.errors import CertificateError, CertificateFormatError
from .._infra.io import atomic_write_text
from .._infra.rational import format_rational, parse_integer
from ._json import MAX_FILE_BYTES, decimal_value, parse_json, read_json
from ._schema import json_schema, validate_schema

__all__ = [
    "SCHEMA",
    "PARAMETER_NAMES",
    "PHYSICAL_NAMES",
    "json_schema",
    "validate_schema",
    "CONSTANT_NAMES",
    "OBLIGATIONS",
    "Provenance",
    "Certificate",
    "dumps",
    "loads",
    "load",
    "atomic_write_text",
    "load_certificate",
    "loads_certificate",
    "dumps_certificate",
]

SCHEMA = "symbolic-friction/certificate/v1"
TEMPLATE_ID = "lyapunov-pair/v1"
"""The template id of a stability certificate (the optional ``template`` member; omitted when written)."""
PARAMETER_NAMES: tuple[str, ...] = ("k_p", "k_i", "k_v", "f_c")
CONSTANT_NAMES: tuple[str, ...] = ("k1", "k2", "k3", "k4", "c1", "c2", "c1_hat", "c2_hat", "c")
OBLIGATIONS: tuple[str, ...] = (
    "lemma2.P",
    "lemma2.lower_bound",
    "lemma2.dVdt",
    "lemma3.R",
    "lemma3.hatV_bounds",
    "lemma3.hatV_derivative",
    "prop1.stability_bound",
)
"""The proof obligations (ids of ``symbolic-friction check``) a certificate instantiates."""

PHYSICAL_NAMES: tuple[str, ...] = ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar")
"""Optional physical parameters (paper §II-A) a certificate may record beside its normalised gains."""
_TOP_KEYS = ("schema", "parameters", "constants", "overshoot_bound")
_OPTIONAL_TOP_KEYS = ("provenance", "physical", "template")
_PROVENANCE_KEYS = ("package", "package_version", "mode", "margin", "solver", "solver_status", "obligations", "label")
SEARCHES: tuple[str, ...] = ("closed-form", "sdp")  # the closed form of .closed_form, or the SDP of .search
_RATIONAL_RE = re.compile(r"^[+-]?[0-9]+(/[0-9]+)?$")
_DECIMAL_RE = re.compile(r"^-?[0-9]+(\.[0-9]+)?$")
MAX_NUMBER_CHARS = 20_000
"""Longest exact number accepted in a certificate (a 1,500-digit denominator is fine; 10⁵ digits is not)."""
MAX_TEXT_CHARS = 10_000
"""Longest free-text field (label, solver, …)."""


def _signed_rational_field(value: object, key: str, *, positive: bool = False, nonnegative: bool = False) -> Fraction:
    """Parse one exact rational string of the file format (any sign unless ``positive`` or ``nonnegative``)."""
    if isinstance(value, bool) or not isinstance(value, str):
        kind = "float" if isinstance(value, float) else type(value).__name__
        raise CertificateFormatError(
            f"{key} must be a string holding an exact rational such as '32/5' or '4'; got the {kind} {value!r}"
        )
    if len(value) > MAX_NUMBER_CHARS:
        raise CertificateFormatError(f"{key} has {len(value)} characters; at most {MAX_NUMBER_CHARS} are accepted")
    if not _RATIONAL_RE.match(value):
        shown = value if len(value) <= 40 else value[:40] + "…"
        raise CertificateFormatError(
            f"{key} must be an exact rational string such as '32/5' or '4' (ASCII digits, no decimals, no spaces); got {shown!r}"
        )
    num, _, den = value.partition("/")
    denominator = parse_integer(den) if den else 1
    if denominator == 0:
        raise CertificateFormatError(f"{key} has a zero denominator: {value[:40]!r}")
    q = Fraction(parse_integer(num), denominator)
    if positive and not q > 0:
        raise CertificateFormatError(f"{key} must be positive; got {value!r}")
    if nonnegative and q < 0:
        raise CertificateFormatError(f"{key} must be ≥ 0; got {value!r}")
    return q


def _as_fraction(value: object, key: str, *, positive: bool = False) -> Fraction:
    """Constructor-side conversion: Fraction/int (or a file-format string) → Fraction (positive if ``positive``)."""
    if isinstance(value, bool):
        raise CertificateFormatError(f"{key} must be an exact rational; got the boolean {value!r}")
    if isinstance(value, int):
        value = Fraction(value)
    if isinstance(value, Fraction):
        if positive and not value > 0:
            raise CertificateFormatError(f"{key} must be positive; got {format_rational(value)}")
        return value
    return _signed_rational_field(value, key, positive=positive)


def _decimal_field(value: object, key: str) -> str:
    """A plain decimal string (``'3.69516'``, ``'-2.5'``); its sign is the premise ``overshoot_bound > 0``, not the format's."""
    if isinstance(value, bool) or not isinstance(value, str):
        kind = "float" if isinstance(value, float) else type(value).__name__
        raise CertificateFormatError(f"{key} must be a decimal string such as '3.69516'; got the {kind} {value!r}")
    if len(value) > MAX_NUMBER_CHARS:
        raise CertificateFormatError(f"{key} has {len(value)} characters; at most {MAX_NUMBER_CHARS} are accepted")
    if not _DECIMAL_RE.match(value):
        shown = value if len(value) <= 40 else value[:40] + "…"
        raise CertificateFormatError(f"{key} must be a plain decimal string such as '3.69516'; got {shown!r}")
    return value


def kappa_squared(c1: Any, c2: Any, c1_hat: Any, c2_hat: Any) -> Any:
    """``κ² = c₂ĉ₂/(c₁ĉ₁)`` of eq. (stabState), with plain arithmetic (exact or symbolic)."""
    return (c2 * c2_hat) / (c1 * c1_hat)


@dataclass(frozen=True)
class Provenance:
    """How a certificate was found (informative; never part of the proof).

    Attributes
    ----------
    mode : str
        ``"feasible"``, ``"tightest"`` or any other label of the producer.
    margin : Fraction
        Relative margin imposed on the strict inequalities during the search.
    solver, solver_status : str
        Numerical solver and the status it reported for the candidate.
    package_version : str
        Version of :mod:`symbolic_friction` that wrote the file.
    obligations : tuple of str
        Ids of the proof obligations the certificate instantiates.
    label : str
        Free text, e.g. ``"Table I, case (a)"``.
    package : str
        Always ``"symbolic-friction"``.
    search : str
        ``"closed-form"`` or ``"sdp"`` (written only for the closed form: older SDP files stay current).
    """

    mode: str
    margin: Fraction
    solver: str
    solver_status: str
    package_version: str
    obligations: tuple[str, ...] = OBLIGATIONS
    label: str = ""
    package: str = "symbolic-friction"
    search: str = "sdp"

    def __post_init__(self) -> None:
        if self.search not in SEARCHES:
            raise CertificateFormatError(f"provenance.search must be one of {', '.join(SEARCHES)}; got {self.search!r}")
        for name in ("mode", "solver", "solver_status", "package_version", "label", "package"):
            if not isinstance(getattr(self, name), str):
                raise CertificateFormatError(
                    f"provenance.{name} must be a string; got {type(getattr(self, name)).__name__}"
                )
            if len(getattr(self, name)) > MAX_TEXT_CHARS:
                raise CertificateFormatError(f"provenance.{name} is longer than {MAX_TEXT_CHARS} characters")
        object.__setattr__(self, "margin", _as_fraction(self.margin, "provenance.margin", positive=True))
        obligations = self.obligations
        if isinstance(obligations, str) or not all(isinstance(o, str) for o in obligations):
            raise CertificateFormatError(f"provenance.obligations must be a list of strings; got {obligations!r}")
        object.__setattr__(self, "obligations", tuple(obligations))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready mapping (exact margin as a rational string)."""
        out = {
            "package": self.package, "package_version": self.package_version, "mode": self.mode,
            "margin": format_rational(self.margin), "solver": self.solver, "solver_status": self.solver_status,
            "obligations": list(self.obligations), "label": self.label,
        }
        return out if self.search == "sdp" else {**out, "search": self.search}

    @classmethod
    def from_dict(cls, data: object) -> "Provenance":
        """Parse the ``provenance`` object of a file, strictly."""
        if not isinstance(data, dict):
            raise CertificateFormatError(f"provenance must be a JSON object; got {type(data).__name__}")
        _check_keys(data, required=_PROVENANCE_KEYS, optional=("search",), where="provenance")
        if not isinstance(data["obligations"], list):
            raise CertificateFormatError(
                f"provenance.obligations must be a list of strings; got {type(data['obligations']).__name__}"
            )
        return cls(
            mode=data["mode"],
            margin=_signed_rational_field(data["margin"], "provenance.margin", positive=True),
            solver=data["solver"],
            solver_status=data["solver_status"],
            package_version=data["package_version"],
            obligations=tuple(data["obligations"]),
            label=data["label"],
            package=data["package"],
            search=data.get("search", "sdp"),
        )


@dataclass(frozen=True)
class Certificate:
    """Exact constants claimed to prove Lemma 2, Lemma 3 and Proposition 1 for one gain set.

    All numeric fields are :class:`~fractions.Fraction` values (ints and
    exact rational strings such as ``"32/5"`` are accepted).  The constructor
    checks the *form* only: a certificate holds claims, and a false one must
    be representable to be refused.  :func:`~symbolic_friction.verify_certificate`
    decides whether the inequalities hold, the signs (``k_p > 0``, ``c₁ > 0``,
    ``κ > 0``, …) included.

    Attributes
    ----------
    k_p, k_i, k_v, f_c : Fraction
        Normalised gains and Coulomb level.
    k1, k2, k3, k4 : Fraction
        Coefficients of ``V̂`` (eq. Vhat).
    c1, c2 : Fraction
        Bounds of ``V`` (Lemma 2, eq. VandR).
    c1_hat, c2_hat : Fraction
        Bounds of ``V̂`` on ``R̂`` (eq. hatVandHatR).
    c : Fraction
        Decrease rate of Lemma 2, item 2; must equal ``2(k_v k_p - k_i)``.
    overshoot_bound : str
        Decimal string claimed to be positive and ``≥ √(c₂ĉ₂/(c₁ĉ₁))`` (eq. stabState),
        as written in the file; :attr:`kappa` is the same number as a ``Fraction``.
    provenance : Provenance or None
        How the certificate was found.
    physical : dict or None
        The physical parameters the gains were given as (``m``, ``k_p_bar``,
        ``k_i_bar``, ``k_d_bar``, ``alpha_v``, ``f_c_bar``; paper §II-A), if
        any; the verifier checks that they normalise to the gains.

    Raises
    ------
    CertificateFormatError
        If a field is not an exact rational (or, for ``overshoot_bound``, a
        plain decimal string).
    """

    k_p: Fraction
    k_i: Fraction
    k_v: Fraction
    f_c: Fraction
    k1: Fraction
    k2: Fraction
    k3: Fraction
    k4: Fraction
    c1: Fraction
    c2: Fraction
    c1_hat: Fraction
    c2_hat: Fraction
    c: Fraction
    overshoot_bound: str
    provenance: Provenance | None = field(default=None)
    physical: dict[str, Fraction] | None = field(default=None, compare=True)

    def __post_init__(self) -> None:
        if self.physical is not None:
            object.__setattr__(self, "physical", _physical(self.physical))
        for name in PARAMETER_NAMES:
            object.__setattr__(self, name, _as_fraction(getattr(self, name), f"parameters.{name}"))
        for name in CONSTANT_NAMES:
            object.__setattr__(self, name, _as_fraction(getattr(self, name), f"constants.{name}"))
        _decimal_field(self.overshoot_bound, "overshoot_bound")
        if self.provenance is not None and not isinstance(self.provenance, Provenance):
            raise CertificateFormatError(
                f"provenance must be a Provenance or None; got {type(self.provenance).__name__}"
            )

    # -- derived quantities -------------------------------------------------
    @property
    def parameters(self) -> dict[str, Fraction]:
        """``{"k_p": …, "k_i": …, "k_v": …, "f_c": …}`` (exact)."""
        return {name: getattr(self, name) for name in PARAMETER_NAMES}

    def as_parameters(self) -> Any:
        """The gains as :class:`~symbolic_friction.Parameters` (for simulation or re-certification).

        Raises
        ------
        AssumptionError
            If the certificate's gains are not positive or violate
            Assumption 1 (such a certificate also fails verification).
        """
        from .._model.parameters import Parameters

        return Parameters(k_p=self.k_p, k_i=self.k_i, k_v=self.k_v, f_c=self.f_c)

    @property
    def constants(self) -> dict[str, Fraction]:
        """``{"k1": …, …, "c": …}`` in the order of :data:`CONSTANT_NAMES` (exact)."""
        return {name: getattr(self, name) for name in CONSTANT_NAMES}

    @property
    def kappa_squared(self) -> Fraction:
        """``c₂ĉ₂/(c₁ĉ₁)``, the exact square of Proposition 1's constant (:class:`CertificateError` if ``c₁ĉ₁ = 0``)."""
        if self.c1 * self.c1_hat == 0:  # such a certificate fails "c1 > 0" or "c1_hat > 0"
            raise CertificateError(f"κ² = c2·c2_hat/(c1·c1_hat) is undefined: c1·c1_hat = {self.c1}·{self.c1_hat} = 0")
        return kappa_squared(self.c1, self.c2, self.c1_hat, self.c2_hat)

    @property
    def kappa(self) -> Fraction:
        """The claimed overshoot bound κ as an exact number (``overshoot_bound`` is its decimal text).

        ``float(cert.kappa)`` for plots; ``cert.kappa ** 2 >= cert.kappa_squared`` is the claim, exactly.
        """
        return decimal_value(self.overshoot_bound)

    # -- (de)serialisation --------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """JSON-ready mapping of the file format."""
        out: dict[str, Any] = {
            "schema": SCHEMA,
            "parameters": {k: format_rational(v) for k, v in self.parameters.items()},
            "constants": {k: format_rational(v) for k, v in self.constants.items()},
            "overshoot_bound": self.overshoot_bound,
        }
        if self.provenance is not None:
            out["provenance"] = self.provenance.to_dict()
        if self.physical is not None:
            out["physical"] = {k: format_rational(v) for k, v in self.physical.items()}
        return out

    def gains_text(self) -> str:
        """``"k_p=3, k_i=4, k_v=32/5, f_c=1"`` (and the physical parameters when recorded)."""
        text = ", ".join(f"{k}={format_rational(v)}" for k, v in self.parameters.items())
        if self.physical is not None:
            text += " (" + ", ".join(f"{k}={format_rational(v)}" for k, v in self.physical.items()) + ")"
        return text

    @classmethod
    def from_dict(cls, data: object) -> "Certificate":
        """Build a certificate from a parsed JSON object, strictly.

        Raises
        ------
        CertificateFormatError
            Naming the key: unknown schema, missing or unknown keys, a number
            that is not an exact rational string (a number of the wrong sign
            is read: the verifier refuses it, naming the premise).
        """
        if not isinstance(data, dict):
            raise CertificateFormatError(f"a certificate must be a JSON object; got a JSON {_json_kind(data)}")
        if "schema" not in data:
            raise CertificateFormatError(f"missing key 'schema' (expected {SCHEMA!r})")
        if data["schema"] != SCHEMA:
            raise CertificateFormatError(f"unknown schema {data['schema']!r}; expected {SCHEMA!r}")
        _check_keys(data, required=_TOP_KEYS, optional=_OPTIONAL_TOP_KEYS, where="certificate")
        if "template" in data and data["template"] != TEMPLATE_ID:
            raise CertificateFormatError(f"template {data['template']!r} is not a stability certificate's ({TEMPLATE_ID!r})")
        parameters = data["parameters"]
        constants = data["constants"]
        for where, obj, names in (("parameters", parameters, PARAMETER_NAMES), ("constants", constants, CONSTANT_NAMES)):
            if not isinstance(obj, dict):
                raise CertificateFormatError(f"{where} must be a JSON object; got a JSON {_json_kind(obj)}")
            _check_keys(obj, required=names, optional=(), where=where)
        values = {name: _signed_rational_field(parameters[name], f"parameters.{name}") for name in PARAMETER_NAMES}
        values.update({name: _signed_rational_field(constants[name], f"constants.{name}") for name in CONSTANT_NAMES})
        provenance = Provenance.from_dict(data["provenance"]) if "provenance" in data else None
        physical = None
        if "physical" in data:
            if not isinstance(data["physical"], dict):
                raise CertificateFormatError(f"physical must be a JSON object; got a JSON {_json_kind(data['physical'])}")
            _check_keys(data["physical"], required=PHYSICAL_NAMES, optional=(), where="physical")
            physical = {n: _signed_rational_field(data["physical"][n], f"physical.{n}") for n in PHYSICAL_NAMES}
        return cls(
            **values,
            overshoot_bound=_decimal_field(data["overshoot_bound"], "overshoot_bound"),
            provenance=provenance,
            physical=physical,
        )


def _physical(values: object) -> dict[str, Fraction]:
    """Constructor-side check of the physical parameters: all six names, exact, ``m, f_c_bar > 0``, ``alpha_v ≥ 0``."""
    if not isinstance(values, dict):
        raise CertificateFormatError(f"physical must be a mapping of {', '.join(PHYSICAL_NAMES)}; got {type(values).__name__}")
    _check_keys(values, required=PHYSICAL_NAMES, optional=(), where="physical")
    out: dict[str, Fraction] = {}
    for name in PHYSICAL_NAMES:
        value = values[name]
        if isinstance(value, bool):
            raise CertificateFormatError(f"physical.{name} must be an exact rational; got the boolean {value!r}")
        q = Fraction(value) if isinstance(value, (int, Fraction)) else _signed_rational_field(value, f"physical.{name}")
        if name in ("m", "f_c_bar") and not q > 0:
            raise CertificateFormatError(f"physical.{name} must be positive; got {format_rational(q)}")
        if name == "alpha_v" and q < 0:
            raise CertificateFormatError(f"physical.alpha_v must be ≥ 0; got {format_rational(q)}")
        out[name] = q
    return out


def _json_kind(value: object) -> str:
    return {dict: "object", list: "array", str: "string", bool: "boolean", type(None): "null"}.get(
        type(value), "number"
    )


def _check_keys(obj: dict[str, Any], *, required: tuple[str, ...], optional: tuple[str, ...], where: str) -> None:
    missing = [k for k in required if k not in obj]
    if missing:
        prefix = "" if where == "certificate" else f"{where}."
        raise CertificateFormatError(
            f"missing key{'s' if len(missing) > 1 else ''} {', '.join(repr(prefix + k) for k in missing)} "
            f"in {where} (required: {', '.join(required)})"
        )
    unknown = sorted(k for k in obj if k not in required and k not in optional)
    if unknown:
        raise CertificateFormatError(
            f"unknown key{'s' if len(unknown) > 1 else ''} {', '.join(repr(k) for k in unknown)} in {where} "
            f"(allowed: {', '.join(required + optional)})"
        )


def dumps(certificate: Certificate) -> str:
    """The file text: sorted keys, two-space indentation, ASCII, trailing newline."""
    return json.dumps(certificate.to_dict(), indent=2, sort_keys=True, ensure_ascii=True) + "\n"


def from_data(data: object, *, source: str = "<string>") -> Certificate:
    """The certificate in a parsed JSON value, validated against the format and the shipped schema."""
    try:
        certificate = Certificate.from_dict(data)
        validate_schema(data)
    except CertificateFormatError as exc:
        raise CertificateFormatError(f"{source}: {exc}") from None
    return certificate


def loads(text: str | bytes, *, source: str = "<string>") -> Certificate:
    """Parse a certificate from its file text, strictly.

    Raises
    ------
    CertificateFormatError
        If ``text`` is not JSON (the message gives ``source``, line and
        column) or violates the format (see :meth:`Certificate.from_dict`).
    """
    return from_data(parse_json(text, source=source), source=source)


def load(path: str | os.PathLike[str]) -> Certificate:
    """Read and parse a certificate file (see :func:`read_json` and :func:`from_data`).

    Raises
    ------
    InputFileError
        If ``path`` is not a readable regular file of at most
        :data:`MAX_FILE_BYTES` bytes (a FIFO, a device, a directory, …).
    CertificateFormatError
        If the content is not a well-formed certificate.
    """
    return from_data(read_json(path), source=str(path))


# Unambiguous names for the package's top-level API.
load_certificate = load
loads_certificate = loads
dumps_certificate = dumps
