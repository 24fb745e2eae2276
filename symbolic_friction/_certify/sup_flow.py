"""The sup-flow template: a certificate of Proposition 1's bound through ``V_∞`` (beyond the paper).

The model is :mod:`symbolic_friction._model.sup_flow`; the lemma that
``V_∞`` is nonincreasing along solutions is the obligations ``sup_flow.*``.  A
certificate holds ``c₂``, ``p`` and time pieces ``I_i = [start, end)``
covering ``[0, ∞)``, each with ``U_i = yᵀK_iy`` (the quadratic template's
form) and ``γ_i``.  It is proved when, decided exactly (rationals,
copositivity by :mod:`._certify.copositive`) or rigorously (python-flint arb
balls, outward rounding, :mod:`._certify.flow_bound`'s enclosure of
``e^{AJ}`` on an interval ``J``):

* Assumption 1 and ``f_c > 0``; the pieces start at 0, follow each other and
  end at ``∞``; ``p > 0``, ``P − pI ⪰ 0`` and ``−(AᵀP + PA) ⪰ 0`` for the
  tail's ``P`` (past ``T ≥ 0``, the last piece's start: any such ``P`` bounds
  the friction-free flow, so the file may give its own, ``tail_p11`` …
  ``tail_p33`` among the constants; without them, the paper's ``P`` of eq.
  (lyapLikeP));
* ``c₂ ≥ ‖e^{At}‖₂²`` for every ``t ≥ 0`` (:class:`FlowNorm`): ``V_∞ ≤ c₂|x|²_𝒜`` on ``R``;
* ``K₀ − I`` copositive: ``U ≥ |x|²_𝒜`` on ``R̂``;
* for every piece, ``U_i`` nonincreasing on ``R̂`` (the quadratic template's
  rate, band and ``K₃ⱼ ≥ 0`` premises), ``γ_iI − K_i`` copositive and
  ``U_i ≥ |e^{At}w|²`` on both exit planes for both signs of ``σ`` and every
  ``t`` of the piece (:class:`FlowExit`; past ``T`` with the tail form);
* ``κ > 0``, ``κ² ≥ c₂`` and ``κ² ≥ γ_i`` for every piece.

The premises on the flow are decided by :mod:`.sup_flow_enclosure`: an
interval is bisected until every part is decided, a premise false at a point
is refuted there, and what is not decided within :data:`MAX_PARTS` parts is
*not proved*.

Format (``schema`` ``symbolic-friction/sup-flow-certificate/v1``, ``template``
``sup-flow/v1``; keys sorted, exact rational strings, no timings)::

    {"constants": {"c2": …, "p": …, "tail_p11": …, …, "tail_p33": …}, "overshoot_bound": "1.44500", "parameters": {…},
     "pieces": [{"end": "1/8", "gamma": …, "k11": …, "k13": …, "k22": …, "k23": …, "k33": …, "start": "0"},
                …, {"end": "inf", …, "start": "12"}],
     "provenance": {…}, "schema": "symbolic-friction/sup-flow-certificate/v1", "template": "sup-flow/v1"}
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any, ClassVar

from flint import fmpq

from .._infra.errors import CertificateFormatError
from .._infra.rational import format_rational as _f
from .._model import quadratic as quad
from .._model.lyapunov import lyapunov_matrix_entries
from ._memo import Memo
from ._template import Template, register
from .quadratic import (
    PARAMETERS,
    Copositive,
    GainsAndBound,
    QuadraticProvenance,
    QuadraticReport,
    _scaled_identity,
    _sub,
    canonical_staleness,
    decide_premise,
    dumps_quadratic,
    read_common,
)
from .sup_flow_enclosure import MAX_PARTS, MAX_TOTAL_PARTS, Budget, FlowExit, FlowNorm, decide_flow
from .verify import Check, Inequality, Semidefinite

__all__ = [
    "SCHEMA", "TEMPLATE_ID", "OBLIGATIONS", "MAX_PIECES", "MAX_PARTS", "SupFlowPiece", "SupFlowCertificate",
    "SupFlowProvenance", "TAIL_CONSTANTS", "MAX_TOTAL_PARTS", "FlowNorm", "FlowExit", "sup_flow_premises", "verify_sup_flow", "load_sup_flow", "dumps_sup_flow", "SUP_FLOW",
]

SCHEMA = "symbolic-friction/sup-flow-certificate/v1"
TEMPLATE_ID = "sup-flow/v1"
CONSTANTS = ("c2", "p")
TAIL_CONSTANTS = ("tail_p11", "tail_p12", "tail_p13", "tail_p22", "tail_p23", "tail_p33")
"""The tail's own ``P`` (optional, all or none; without them the paper's ``P``)."""
PIECE_CONSTANTS = ("k11", "k13", "k22", "k23", "k33", "gamma")
INFINITY = "inf"
MAX_PIECES = 256
"""Pieces a file may hold (bounded before anything is built)."""
OBLIGATIONS = (
    "lemma2.P",
    "lemma2.dVdt",
    "sup_flow.slip_flow",
    "sup_flow.rest_minimum",
    "sup_flow.nonincreasing",
    "sup_flow.bounds",
    "quadratic.U_rate",
    "sup_flow.exit",
    "sup_flow.stability_bound",
)
"""The proof obligations (ids of ``symbolic-friction check``) a sup-flow certificate instantiates."""
_TOP = ("schema", "template", "parameters", "constants", "pieces", "overshoot_bound")


SupFlowProvenance = QuadraticProvenance
"""How a sup-flow certificate was found: the quadratic template's fields (informative; never part of the proof)."""


def _exact(value: Any, what: str) -> Fraction:
    if isinstance(value, bool) or not isinstance(value, (int, Fraction)):
        raise CertificateFormatError(f"{what} must be an exact rational; got {value!r}")
    return Fraction(value)


@dataclass(frozen=True)
class SupFlowPiece:
    """One time piece ``[start, end)`` (``end`` None for ``∞``), its ``K`` and ``γ``."""

    start: Fraction
    end: Fraction | None
    constants: dict[str, Fraction]
    names: ClassVar[tuple[str, ...]] = PIECE_CONSTANTS

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _exact(self.start, "piece start"))
        if self.end is not None:
            object.__setattr__(self, "end", _exact(self.end, "piece end"))
        if sorted(self.constants) != sorted(self.names):
            raise CertificateFormatError(f"a piece's constants must be exactly {', '.join(self.names)}; "
                                         f"got {', '.join(sorted(self.constants))}")
        object.__setattr__(self, "constants", {n: _exact(self.constants[n], f"piece {n}") for n in self.names})

    def k_matrix(self) -> tuple[tuple[Fraction, ...], ...]:
        c = self.constants
        return quad.u_matrix_entries(c["k11"], c["k13"], c["k22"], c["k23"], c["k33"])

    def signed_forms(self) -> tuple[tuple[int, tuple[tuple[Fraction, ...], ...]], ...]:
        """``(s, K)`` for each sign ``s`` of ``σv``: here one ``K`` for both."""
        k = self.k_matrix()
        return ((1, k), (-1, k))

    def interval_text(self) -> str:
        return f"[{_f(self.start)}, {'∞' if self.end is None else _f(self.end)})"

    def to_dict(self) -> dict[str, str]:
        out = {name: _f(self.constants[name]) for name in self.names}
        out["start"] = _f(self.start)
        out["end"] = INFINITY if self.end is None else _f(self.end)
        return out


@dataclass(frozen=True)
class SupFlowCertificate(GainsAndBound):
    """Gains, ``c₂``, ``p``, the pieces and the bound; every number an exact rational of any sign.

    The signs, the order of the pieces and every bound are premises of
    :func:`sup_flow_premises`, so a false certificate is held and refused by
    :func:`verify_sup_flow`, not by the constructor.
    """

    k_p: Fraction
    k_i: Fraction
    k_v: Fraction
    f_c: Fraction
    constants: dict[str, Fraction]
    pieces: tuple[SupFlowPiece, ...]
    overshoot_bound: str
    provenance: SupFlowProvenance = field(default_factory=SupFlowProvenance)
    schema: ClassVar[str] = SCHEMA
    template_id: ClassVar[str] = TEMPLATE_ID
    constant_names: ClassVar[tuple[str, ...]] = CONSTANTS
    piece_type: ClassVar[type[SupFlowPiece]] = SupFlowPiece

    def __post_init__(self) -> None:
        for name in PARAMETERS:
            object.__setattr__(self, name, _exact(getattr(self, name), f"parameters.{name}"))
        names, own = sorted(self.constants), self.constant_names
        if names not in (sorted(own), sorted(own + TAIL_CONSTANTS)):
            raise CertificateFormatError(f"constants must be exactly {', '.join(own)}, with or without all of "
                                         f"{', '.join(TAIL_CONSTANTS)}; got {', '.join(names)}")
        object.__setattr__(self, "constants", {n: _exact(self.constants[n], f"constants.{n}") for n in own + TAIL_CONSTANTS
                                               if n in self.constants})
        pieces = tuple(self.pieces)
        if not 1 <= len(pieces) <= MAX_PIECES or not all(type(p) is self.piece_type for p in pieces):
            raise CertificateFormatError(f"a sup-flow certificate has 1 to {MAX_PIECES} pieces; got {len(pieces)}")
        object.__setattr__(self, "pieces", pieces)

    @property
    def own_tail(self) -> bool:
        """Whether the file gives the tail's ``P`` (else the paper's ``P`` of eq. lyapLikeP)."""
        return TAIL_CONSTANTS[0] in self.constants

    def tail_matrix(self) -> tuple[tuple[Fraction, ...], ...]:
        """The tail's ``P``: the file's own (symmetric, from its six entries) or the paper's."""
        if not self.own_tail:
            if self.k_i == 0:
                # the paper's P divides by k_i; the premise k_i > 0 refuses the file, and no traceback comes first
                return tuple(tuple(Fraction(0) for _ in range(3)) for _ in range(3))
            return tuple(tuple(Fraction(x) for x in row) for row in lyapunov_matrix_entries(self.k_p, self.k_i, self.k_v))
        c = {name[len("tail_p"):]: self.constants[name] for name in TAIL_CONSTANTS}
        return tuple(tuple(c[f"{min(i, j)}{max(i, j)}"] for j in (1, 2, 3)) for i in (1, 2, 3))

    def premises(self) -> list[Any]:
        """Every premise of this version, in proof order (:func:`sup_flow_premises`)."""
        return sup_flow_premises(self)

    def drag_maps(self) -> tuple[tuple[int, Any], ...]:
        """``(s, D_ℓ)`` of the friction-drag split for each sign (none here: v1 has no ``ℓ``)."""
        return ()

    def to_dict(self) -> dict[str, Any]:
        return {**self.common_dict(self.schema, self.template_id, self.constant_names + TAIL_CONSTANTS),
                "pieces": [piece.to_dict() for piece in self.pieces]}

    @classmethod
    def from_dict(cls, data: object, *, source: str = "<string>") -> "SupFlowCertificate":
        from .certificate import _check_keys, _signed_rational_field

        params, constants, provenance, bound = read_common(data, source, what="sup-flow", schema=cls.schema,
                                                           template_id=cls.template_id, top=_TOP,
                                                           constants=cls.constant_names, optional_constants=TAIL_CONSTANTS)
        raw = data["pieces"]  # type: ignore[index]
        if not isinstance(raw, list) or not 1 <= len(raw) <= MAX_PIECES:
            shown = len(raw) if isinstance(raw, list) else type(raw).__name__
            raise CertificateFormatError(f"{source}: pieces must be a list of 1 to {MAX_PIECES} objects; got {shown}")
        pieces = []
        for i, item in enumerate(raw):
            where = f"pieces[{i}]"
            if not isinstance(item, dict):
                raise CertificateFormatError(f"{source}: {where} must be a JSON object; got {type(item).__name__}")
            names = cls.piece_type.names
            _check_keys(item, required=("start", "end", *names), optional=(), where=where)
            end = None if item["end"] == INFINITY else _signed_rational_field(item["end"], f"{where}.end")
            pieces.append(cls.piece_type(
                start=_signed_rational_field(item["start"], f"{where}.start"), end=end,
                constants={n: _signed_rational_field(item[n], f"{where}.{n}") for n in names}))
        return cls(**params, constants=constants, pieces=tuple(pieces), overshoot_bound=bound, provenance=provenance)


# -- the premises that need the flow: decided in arb balls, interval by interval ------------------


def frame_premises(cert: SupFlowCertificate) -> list[Any]:
    """The premises every sup-flow version shares before its forms: Assumption 1, ``f_c > 0``, pieces that
    cover ``[0, ∞)``, ``T ≥ 0``, the tail's ``p > 0``, ``P − pI ⪰ 0`` and ``−(AᵀP + PA) ⪰ 0``."""
    k_p, k_i, k_v, f_c = cert.k_p, cert.k_i, cert.k_v, cert.f_c
    pieces = cert.pieces
    zero = k_i - k_i
    out: list[Any] = [
        Inequality("lemma2.P", "k_i > 0", k_i, ">", zero),
        Inequality("lemma2.P", "k_p > 0", k_p, ">", zero),
        Inequality("lemma2.P", "k_v·k_p > k_i", k_v * k_p, ">", k_i),
        Inequality("model", "f_c > 0", f_c, ">", zero),
        Inequality("sup_flow.exit", "the first piece starts at t = 0", pieces[0].start, "==", zero),
    ]
    for i in range(1, len(pieces)):
        before = pieces[i - 1].end
        out.append(Inequality("sup_flow.exit", f"piece {i + 1} starts where piece {i} ends",
                              pieces[i].start, "==", pieces[i].start + 1 if before is None else before))
    out.append(Inequality("sup_flow.exit", "the last piece ends at ∞", int(pieces[-1].end is None), "==", 1))
    out.append(Inequality("sup_flow.exit", "T ≥ 0 (the last piece starts at or after 0)", pieces[-1].start, ">=", zero))
    p_tail = cert.tail_matrix()
    whose = "the tail's P" if cert.own_tail else "the paper's P"
    p = cert.constants["p"]
    out += [
        Inequality("sup_flow.exit", "p > 0", p, ">", zero),
        Semidefinite("sup_flow.exit", f"P − p·I ⪰ 0 ({whose})", _sub(p_tail, _scaled_identity(3, p))),
        Semidefinite("sup_flow.exit" if cert.own_tail else "lemma2.dVdt", f"−(AᵀP + PA) ⪰ 0 ({whose})",
                     tuple(tuple(-x for x in row) for row in quad.lyapunov_rate_entries(k_p, k_i, k_v, p_tail))),
    ]
    return out


def bound_premises(cert: SupFlowCertificate, obligation: str) -> list[Any]:
    """``κ > 0``, ``κ² ≥ c₂`` and ``κ² ≥ γ_i`` for every piece (``obligation``: the version's stability bound)."""
    kappa, zero = cert.kappa, Fraction(0)
    out: list[Any] = [
        Inequality(obligation, "overshoot_bound > 0", kappa, ">", zero),
        Inequality(obligation, "overshoot_bound² ≥ c2", kappa * kappa, ">=", cert.constants["c2"]),
    ]
    out += [Inequality(obligation, f"overshoot_bound² ≥ gamma (piece {i + 1})", kappa * kappa, ">=",
                       piece.constants["gamma"]) for i, piece in enumerate(cert.pieces)]
    return out


def _as(kind: type, x: Any) -> Any:
    """``x`` (a number or nested tuples and lists of them) with every exact rational as ``kind`` (fmpq or Fraction)."""
    if isinstance(x, (tuple, list)):
        return type(x)(_as(kind, y) for y in x)
    if kind is fmpq:
        return fmpq(x.numerator, x.denominator) if isinstance(x, (Fraction, int)) and not isinstance(x, bool) else x
    return Fraction(int(x.p), int(x.q)) if type(x) is fmpq else x


def in_fmpq(function: Any, *args: Any) -> Any:
    """``function(*args)`` of the model's forms evaluated on python-flint's fmpq, its result as Fractions: the same
    exact values (the forms are sums of products), several times faster than Fraction arithmetic, which was most of
    a sup-flow verification's time.  Within :data:`shared_decisions` the same function on the same exact arguments
    (an edited file's unchanged pieces) is evaluated once."""
    key = _numbers_key(args)
    compute = lambda: _as(Fraction, function(*_as(fmpq, args)))  # noqa: E731
    return compute() if key is None else _DECISIONS.get((function, key), compute)


def _numbers_key(x: Any) -> Any:
    """``x`` (nested tuples and lists of exact rationals) as nested tuples of integers (numerator, denominator);
    None if it holds anything else (a bool, a float: then nothing is kept)."""
    if type(x) is Fraction or type(x) is int:  # the leaves first: most calls are leaves
        return x.numerator, x.denominator
    if isinstance(x, (tuple, list)):
        out = tuple(map(_numbers_key, x))
        return None if None in out else out
    return None


def sup_flow_premises(cert: SupFlowCertificate) -> list[Any]:
    """Every premise of a sup-flow certificate, in proof order."""
    k_p, k_i, k_v = cert.k_p, cert.k_i, cert.k_v
    pieces = cert.pieces
    zero = k_i - k_i
    out = frame_premises(cert)
    p_tail = cert.tail_matrix()
    out += [
        FlowNorm("sup_flow.bounds", "c2 ≥ ‖e^(At)‖² for every t ≥ 0", cert, p_tail),
        Copositive("sup_flow.bounds", "K1 − I copositive (piece 1)", _sub(pieces[0].k_matrix(), _scaled_identity(3, zero + 1))),
    ]
    for i, piece in enumerate(pieces):
        tag = f"piece {i + 1}"
        numbers = (k_p, k_i, k_v, *map(piece.constants.get, piece.names))
        out += piece_premises(TEMPLATE_ID, tag, numbers, lambda piece=piece, tag=tag: _forms_premises(cert, piece, tag))
        out.append(FlowExit("sup_flow.exit", f"{tag}: U ≥ |e^(At)w|² on the exits of R̂ for t in {piece.interval_text()}", cert,
                            p_tail, i))
    return out + bound_premises(cert, "sup_flow.stability_bound")


def _forms_premises(cert: SupFlowCertificate, piece: SupFlowPiece, tag: str) -> list[Any]:
    """A piece's premises on its form ``K`` and ``γ`` (exact; :func:`sup_flow_premises`'s, before its exit)."""
    k_p, k_i, k_v, k = cert.k_p, cert.k_i, cert.k_v, piece.k_matrix()
    zero, out = k_i - k_i, []
    for s, sign in ((1, "+"), (-1, "−")):
        b = quad.slip_rate_entries(k_p, k_i, k_v, zero + s)
        out.append(Copositive("quadratic.U_rate", f"{tag}: −(K·B{sign} + B{sign}ᵀ·K) copositive",
                              in_fmpq(quad.u_rate_entries, k, b)))
        out.append(Copositive("quadratic.U_rate", f"{tag}: band form (s = {sign}1) copositive",
                              in_fmpq(quad.band_rate_entries, k_i, k_v, k, zero + s)))
    for j in range(3):
        out.append(Inequality("quadratic.U_rate", f"{tag}: K3{j + 1} ≥ 0", k[2][j], ">=", zero))
    out.append(Copositive("sup_flow.stability_bound", f"{tag}: gamma·I − K copositive",
                          _sub(_scaled_identity(3, piece.constants["gamma"]), k)))
    return out


def piece_premises(template: str, tag: str, numbers: tuple[Any, ...], build: Any) -> tuple[Any, ...]:
    """``build()``, a piece's exact premises on its forms (frozen, built from ``numbers`` alone: the gains, ``ℓ``
    and the piece's constants), kept within :data:`shared_decisions` under the template's id, ``tag`` and the exact
    ``numbers`` (an edited file's unchanged pieces: most of them)."""
    if not all(type(x) is Fraction for x in numbers):
        return tuple(build())
    return _DECISIONS.get(("piece premises", template, tag, _exact_key(*numbers)), lambda: tuple(build()))


def _decide(premise: Any, budget: Budget | None = None) -> Check:
    if isinstance(premise, (FlowNorm, FlowExit)):
        return _decide_flow(premise, budget or Budget())
    if isinstance(premise, Copositive) and all(type(x) in (Fraction, int) for row in premise.matrix for x in row):
        # a pure function of the name and the exact matrix (anything else, a bool, a float, is decided, and refused)
        key = (premise.obligation, premise.name, tuple(_exact_key(*row) for row in premise.matrix))
        return _DECISIONS.get(key, lambda: decide_premise(premise))
    if (type(premise) is Inequality and premise.rhs_text is None and type(premise.lhs) is Fraction
            and type(premise.rhs) is Fraction):  # likewise a pure function of its name, relation and two numbers
        key = (premise.obligation, premise.name, premise.op, _exact_key(premise.lhs, premise.rhs))
        return _DECISIONS.get(key, lambda: decide_premise(premise))
    return decide_premise(premise)


_DECISIONS = Memo()
shared_decisions = _DECISIONS.sharing
"""Within the block, a premise on the flow, a copositivity premise or an inequality of two rationals with the same
numbers as one decided before is not decided again (the self-check's false files and an edited certificate's copies
share most of their pieces with a true file)."""


def _exact_key(*numbers: Fraction) -> tuple[int, ...]:
    return tuple(n for x in numbers for n in (x.numerator, x.denominator))


def _flow_key(premise: FlowNorm | FlowExit) -> tuple[Any, ...]:
    """Everything :func:`decide_flow` reads of ``premise``, as exact integers (its name and obligation too).

    The tail (``P``, ``p`` and ``T``) is read only by :class:`FlowNorm` and the exit of the last piece (which
    ends at ``∞``): an exit on a finite piece is keyed without it, so an edit of the tail decides only those again."""
    cert = premise.certificate
    piece = None if isinstance(premise, FlowNorm) else cert.pieces[premise.index]
    tail = () if piece is not None and piece.end is not None else _exact_key(
        *(x for row in premise.p_matrix for x in row), cert.constants["p"], cert.pieces[-1].start)
    common = (type(premise).__name__, premise.obligation, premise.name, _exact_key(cert.k_p, cert.k_i, cert.k_v),
              tuple((s, _exact_key(*(x for row in d for x in row))) for s, d in cert.drag_maps()), tail)
    if piece is None:
        return common + (_exact_key(cert.constants["c2"]),)
    return common + (_exact_key(piece.start), piece.end is None or _exact_key(piece.end),
                     tuple((s, _exact_key(*(x for row in k for x in row))) for s, k in piece.signed_forms()))


def _decide_flow(premise: FlowNorm | FlowExit, budget: Budget) -> Check:
    """:func:`decide_flow`, or its verdict on the same numbers earlier in a :func:`shared_decisions` block.

    A kept verdict is reused only where the budget cannot have changed it: the decision that made it never came
    near the end of its budget (every test of a part then saw at least 2 parts left), and this budget has room for
    the same parts again; the parts are then taken from this budget as the bisection would take them.
    """
    kept = _DECISIONS.get(_flow_key(premise), list)  # outside a block: a new empty list, so nothing is kept
    if kept and budget.left - kept[1] >= 2:
        budget.left -= kept[1]
        return kept[0]
    before = budget.left
    check = decide_flow(premise, budget)
    if budget.left >= 2:
        kept[:] = [check, before - budget.left]
    return check


@dataclass(frozen=True)
class SupFlowReport(QuadraticReport):
    """Per-premise verdicts of a sup-flow certificate (the quadratic report's rule: proved iff there is a check
    and every one holds)."""

    template_name: ClassVar[str] = "sup-flow"


def verify_sup_flow(certificate: SupFlowCertificate, *, source: str = "<certificate>",
                    max_parts: int | None = None) -> SupFlowReport:
    """Decide every premise of :func:`sup_flow_premises` (a structural failure stops before the flow is enclosed).

    ``max_parts`` lowers the parts all enclosures together may use (default and upper limit
    :data:`MAX_TOTAL_PARTS`): a search short of time fails sooner; a lower budget can only refuse more.
    """
    if not isinstance(certificate, SupFlowCertificate):
        raise TypeError(f"verify_sup_flow needs a SupFlowCertificate; got {type(certificate).__name__}")
    checks, structural, budget = [], True, Budget(max_parts)
    for premise in certificate.premises():
        if isinstance(premise, Inequality) and premise.obligation in ("lemma2.P", "sup_flow.exit"):
            check = _decide(premise)
            structural = structural and check.holds
            checks.append(check)
            continue
        if isinstance(premise, (FlowNorm, FlowExit)) and not structural:
            # the enclosures need Assumption 1, contiguous pieces and p > 0: without them they mean nothing
            checks.append(Check(premise.obligation, premise.name, "not evaluated (an earlier premise fails)", False, evaluated=False))
            continue
        checks.append(_decide(premise, budget))
    return SupFlowReport(certificate, tuple(checks), source)


def load_sup_flow(path: str | Path) -> SupFlowCertificate:
    """Read a version-1 sup-flow certificate file strictly (bounded read; not verified).

    :func:`.sup_flow_v2.load_sup_flow` reads either version.

    Raises
    ------
    InputFileError, CertificateFormatError
        If the file cannot be read, is not strict JSON or is not a sup-flow certificate.
    """
    from ._json import read_json

    return SupFlowCertificate.from_dict(read_json(path), source=str(path))


def dumps_sup_flow(certificate: SupFlowCertificate) -> str:
    """The file's bytes: the quadratic template's canonical JSON (sorted keys, two-space indentation, trailing newline)."""
    return dumps_quadratic(certificate)


SUP_FLOW = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: SupFlowCertificate.from_dict(data, source=source),
    verify=lambda certificate, source: verify_sup_flow(certificate, source=source),
    dumps=dumps_sup_flow,
    stale=canonical_staleness(dumps_sup_flow),
    claim=lambda certificate: f"κ ≤ {certificate.overshoot_bound} (sup-flow template)",
    default=True,
))
"""The sup-flow template (beyond the paper): ``V_∞`` on ``R``, ``U = max_i U_i`` on ``R̂``."""
