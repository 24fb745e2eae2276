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
  paper's ``P`` (the tail past ``T``, the last piece's start);
* ``c₂ ≥ ‖e^{At}‖₂²`` for every ``t ≥ 0`` (:class:`FlowNorm`): ``V_∞ ≤ c₂|x|²_𝒜`` on ``R``;
* ``K₀ − I`` copositive: ``U ≥ |x|²_𝒜`` on ``R̂``;
* for every piece, ``U_i`` nonincreasing on ``R̂`` (the quadratic template's
  rate, band and ``K₃ⱼ ≥ 0`` premises), ``γ_iI − K_i`` copositive and
  ``U_i ≥ |e^{At}w|²`` on both exit planes for both signs of ``σ`` and every
  ``t`` of the piece (:class:`FlowExit`; past ``T`` with the tail form);
* ``κ > 0``, ``κ² ≥ c₂`` and ``κ² ≥ γ_i`` for every piece.

A rigorous decision on an interval bisects it until every part is decided or
:data:`MAX_PARTS` parts were tried; what is not decided is *not proved*.

Format (``schema`` ``symbolic-friction/sup-flow-certificate/v1``, ``template``
``sup-flow/v1``; keys sorted, exact rational strings, no timings)::

    {"constants": {"c2": …, "p": …}, "overshoot_bound": "1.44500", "parameters": {…},
     "pieces": [{"end": "1/8", "gamma": …, "k11": …, "k13": …, "k22": …, "k23": …, "k33": …, "start": "0"},
                …, {"end": "inf", …, "start": "12"}],
     "provenance": {…}, "schema": "symbolic-friction/sup-flow-certificate/v1", "template": "sup-flow/v1"}
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from .._infra.errors import CertificateFormatError
from .._infra.rational import format_rational as _f
from .._model import quadratic as quad
from .._model import sup_flow as model
from .._model.lyapunov import lyapunov_matrix_entries
from ._template import Template, register
from .quadratic import Copositive, _scaled_identity, _sub, decide_premise
from .verify import Check, Inequality, Semidefinite, VerificationReport

__all__ = [
    "SCHEMA", "TEMPLATE_ID", "OBLIGATIONS", "MAX_PIECES", "MAX_PARTS", "SupFlowPiece", "SupFlowCertificate",
    "SupFlowProvenance", "MAX_TOTAL_PARTS", "FlowNorm", "FlowExit", "sup_flow_premises", "verify_sup_flow", "load_sup_flow", "dumps_sup_flow", "SUP_FLOW",
]

SCHEMA = "symbolic-friction/sup-flow-certificate/v1"
TEMPLATE_ID = "sup-flow/v1"
PARAMETERS = ("k_p", "k_i", "k_v", "f_c")
CONSTANTS = ("c2", "p")
PIECE_CONSTANTS = ("k11", "k13", "k22", "k23", "k33", "gamma")
INFINITY = "inf"
MAX_PIECES = 256
"""Pieces a file may hold (bounded before anything is built)."""
MAX_PARTS = 2048
"""Intervals one rigorous decision may bisect its interval into before it says *not proved*."""
MAX_TOTAL_PARTS = 12_288
"""Intervals all rigorous decisions of one certificate may use together (a few seconds at most)."""
PRECISION = 128
"""Bits of the arb balls."""
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
_PROVENANCE = ("package", "search", "solver", "solver_status", "margin", "label")


@dataclass(frozen=True)
class SupFlowProvenance:
    """How a sup-flow certificate was found (informative; never part of the proof)."""

    search: str = "sdp"
    solver: str = ""
    solver_status: str = ""
    margin: str = ""
    label: str = ""
    package: str = "symbolic-friction"

    def __post_init__(self) -> None:
        for name in _PROVENANCE:
            value = getattr(self, name)
            if not isinstance(value, str) or len(value) > 10_000:
                raise CertificateFormatError(f"provenance.{name} must be a string of at most 10000 characters; got {value!r:.60}")

    def to_dict(self) -> dict[str, str]:
        return {name: getattr(self, name) for name in _PROVENANCE}


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

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _exact(self.start, "piece start"))
        if self.end is not None:
            object.__setattr__(self, "end", _exact(self.end, "piece end"))
        if sorted(self.constants) != sorted(PIECE_CONSTANTS):
            raise CertificateFormatError(f"a piece's constants must be exactly {', '.join(PIECE_CONSTANTS)}; "
                                         f"got {', '.join(sorted(self.constants))}")
        object.__setattr__(self, "constants", {n: _exact(self.constants[n], f"piece {n}") for n in PIECE_CONSTANTS})

    def k_matrix(self) -> tuple[tuple[Fraction, ...], ...]:
        c = self.constants
        return quad.u_matrix_entries(c["k11"], c["k13"], c["k22"], c["k23"], c["k33"])

    def interval_text(self) -> str:
        return f"[{_f(self.start)}, {'∞' if self.end is None else _f(self.end)})"

    def to_dict(self) -> dict[str, str]:
        out = {name: _f(self.constants[name]) for name in PIECE_CONSTANTS}
        out["start"] = _f(self.start)
        out["end"] = INFINITY if self.end is None else _f(self.end)
        return out


@dataclass(frozen=True)
class SupFlowCertificate:
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

    def __post_init__(self) -> None:
        for name in PARAMETERS:
            object.__setattr__(self, name, _exact(getattr(self, name), f"parameters.{name}"))
        if sorted(self.constants) != sorted(CONSTANTS):
            raise CertificateFormatError(f"constants must be exactly {', '.join(CONSTANTS)}; got {', '.join(sorted(self.constants))}")
        object.__setattr__(self, "constants", {n: _exact(self.constants[n], f"constants.{n}") for n in CONSTANTS})
        pieces = tuple(self.pieces)
        if not 1 <= len(pieces) <= MAX_PIECES or not all(isinstance(p, SupFlowPiece) for p in pieces):
            raise CertificateFormatError(f"a sup-flow certificate has 1 to {MAX_PIECES} pieces; got {len(pieces)}")
        object.__setattr__(self, "pieces", pieces)

    @property
    def parameters(self) -> dict[str, Fraction]:
        return {name: getattr(self, name) for name in PARAMETERS}

    def gains_text(self) -> str:
        """``"k_p=3, k_i=4, k_v=32/5, f_c=1"``."""
        return ", ".join(f"{name}={_f(value)}" for name, value in self.parameters.items())

    @property
    def kappa(self) -> Fraction:
        return Fraction(self.overshoot_bound)

    def to_dict(self) -> dict[str, Any]:
        return {
            "schema": SCHEMA,
            "template": TEMPLATE_ID,
            "parameters": {name: _f(getattr(self, name)) for name in PARAMETERS},
            "constants": {name: _f(self.constants[name]) for name in CONSTANTS},
            "pieces": [piece.to_dict() for piece in self.pieces],
            "overshoot_bound": self.overshoot_bound,
            "provenance": self.provenance.to_dict(),
        }

    @classmethod
    def from_dict(cls, data: object, *, source: str = "<string>") -> "SupFlowCertificate":
        from .certificate import _check_keys, _decimal_field, _signed_rational_field

        if not isinstance(data, dict):
            raise CertificateFormatError(f"{source}: a sup-flow certificate is a JSON object; got {type(data).__name__}")
        _check_keys(data, required=_TOP, optional=("provenance",), where="certificate")
        if data["schema"] != SCHEMA or data["template"] != TEMPLATE_ID:
            raise CertificateFormatError(f"{source}: schema {data['schema']!r} / template {data['template']!r} is not {SCHEMA} / {TEMPLATE_ID}")
        for key, names in (("parameters", PARAMETERS), ("constants", CONSTANTS)):
            if not isinstance(data[key], dict):
                raise CertificateFormatError(f"{source}: {key} must be a JSON object; got {type(data[key]).__name__}")
            _check_keys(data[key], required=names, optional=(), where=key)
        raw = data["pieces"]
        if not isinstance(raw, list) or not 1 <= len(raw) <= MAX_PIECES:
            shown = len(raw) if isinstance(raw, list) else type(raw).__name__
            raise CertificateFormatError(f"{source}: pieces must be a list of 1 to {MAX_PIECES} objects; got {shown}")
        pieces = []
        for i, item in enumerate(raw):
            where = f"pieces[{i}]"
            if not isinstance(item, dict):
                raise CertificateFormatError(f"{source}: {where} must be a JSON object; got {type(item).__name__}")
            _check_keys(item, required=("start", "end", *PIECE_CONSTANTS), optional=(), where=where)
            end = None if item["end"] == INFINITY else _signed_rational_field(item["end"], f"{where}.end")
            pieces.append(SupFlowPiece(
                start=_signed_rational_field(item["start"], f"{where}.start"), end=end,
                constants={n: _signed_rational_field(item[n], f"{where}.{n}") for n in PIECE_CONSTANTS}))
        provenance = data.get("provenance", {})
        if not isinstance(provenance, dict):
            raise CertificateFormatError(f"{source}: provenance must be a JSON object")
        _check_keys(provenance, required=(), optional=_PROVENANCE, where="provenance")
        return cls(
            **{n: _signed_rational_field(data["parameters"][n], f"parameters.{n}") for n in PARAMETERS},
            constants={n: _signed_rational_field(data["constants"][n], f"constants.{n}") for n in CONSTANTS},
            pieces=tuple(pieces), overshoot_bound=_decimal_field(data["overshoot_bound"], "overshoot_bound"),
            provenance=SupFlowProvenance(**provenance),
        )


# -- the premises that need the flow: decided in arb balls, interval by interval ------------------


@dataclass(frozen=True)
class FlowNorm:
    """``c₂I − e^{At}ᵀe^{At} ≻ 0`` for every ``t ∈ [0, T]``, and ``c₂I − (1/p)e^{AT}ᵀPe^{AT} ≻ 0`` (the tail)."""

    obligation: str
    name: str
    certificate: SupFlowCertificate


@dataclass(frozen=True)
class FlowExit:
    """``U_i ≥ |e^{At}w|²`` on both exit planes, both signs of ``σ``, every ``t`` of piece ``index``."""

    obligation: str
    name: str
    certificate: SupFlowCertificate
    index: int


def _arb(q: Fraction) -> Any:
    from .flow_bound import _arb as arb

    return arb(Fraction(q))


def _flow(cert: SupFlowCertificate, a: Fraction, b: Fraction) -> Any:
    """An arb enclosure of ``e^{At}`` for every ``t ∈ [a, b]``: ``e^{Aa}·e^{A[0, b − a]}``.

    Ball arithmetic encloses the value at every point of the input ball, so
    the exponential of the ball ``A·[0, b − a]`` holds every ``e^{Aτ}``; the
    point factor ``e^{Aa}`` first keeps the ball small (the exponential of a
    wide ball ``A·[a, b]`` far from 0 would be needlessly wide).
    """
    import flint

    from .flow_bound import _system

    a_matrix = _system(_Gains(cert))
    start = (a_matrix * _arb(a)).exp()
    if a == b:
        return start
    half = _arb((b - a) / 2)
    return start * (a_matrix * flint.arb(half, half)).exp()


class _Gains:
    """The gains of ``cert`` in the shape :func:`.flow_bound._system` reads."""

    def __init__(self, cert: SupFlowCertificate) -> None:
        self.k_p, self.k_i, self.k_v = cert.k_p, cert.k_i, cert.k_v


def _rows(m: Any) -> tuple[tuple[Any, ...], ...]:
    return tuple(tuple(m[i, j] for j in range(3)) for i in range(3))


def _gram(e: Any) -> tuple[tuple[Any, ...], ...]:
    return _rows(e.transpose() * e)


def _paper_p(cert: SupFlowCertificate) -> tuple[tuple[Fraction, ...], ...]:
    return tuple(tuple(Fraction(x) for x in row) for row in lyapunov_matrix_entries(cert.k_p, cert.k_i, cert.k_v))


def _tail_gram(cert: SupFlowCertificate, horizon: Fraction) -> tuple[tuple[Any, ...], ...]:
    e = _rows(_flow(cert, horizon, horizon))
    p = tuple(tuple(_arb(x) for x in row) for row in _paper_p(cert))
    return model.tail_gram(e, p, _arb(cert.constants["p"]))


EXPONENT_LIMIT = 4096
"""Binary exponent beyond which an end of a ball is not turned into a Fraction (see :func:`_end`)."""


class _TooWide(Exception):
    """An end of a ball is beyond ``2^EXPONENT_LIMIT``: nothing is decided from it."""


def _end(point: Any, *, down: bool) -> Fraction:
    """The exact value of an arb point as a Fraction, moved outward where it is tiny (so sizes stay bounded).

    A magnitude below ``2^-EXPONENT_LIMIT`` becomes 0 or ``±2^-EXPONENT_LIMIT``,
    whichever is below (``down``) or above the value, so a lower end stays a
    lower end and an upper end an upper end; a magnitude above
    ``2^EXPONENT_LIMIT`` raises :class:`_TooWide` (the premise is then not
    decided on that part), never a Fraction of thousands of digits.
    """
    mantissa, exponent = (int(x) for x in point.man_exp())
    if mantissa == 0:
        return Fraction(0)
    if exponent + mantissa.bit_length() > EXPONENT_LIMIT:
        raise _TooWide(f"a ball end beyond 2^{EXPONENT_LIMIT}")
    if exponent + mantissa.bit_length() < -EXPONENT_LIMIT:
        tiny = Fraction(1, 2**EXPONENT_LIMIT)
        if down:
            return Fraction(0) if mantissa > 0 else -tiny
        return tiny if mantissa > 0 else Fraction(0)
    return Fraction(mantissa * 2**exponent) if exponent >= 0 else Fraction(mantissa, 2**-exponent)


def _lower(ball: Any) -> Fraction:
    return _end(ball.lower(), down=True)


def _upper(ball: Any) -> Fraction:
    return _end(ball.upper(), down=False)


def _exit_holds(k: Any, gram: Any, *, end: Any = _lower) -> tuple[bool, str]:
    """Every exit form, with each entry replaced by one end of its ball, copositive (exactly).

    Copositivity is monotone in the entries: the rational matrix of lower ends
    being copositive shows it for every ``G`` in the enclosure; the matrix of
    upper ends (``end=_upper``) *not* being copositive shows that no ``G`` in
    it is (at a point ``t``: the premise is false there).
    """
    from .copositive import decide_copositive

    for s in (1, -1):
        for plane, form in zip(model.EXIT_PLANES, model.exit_forms(k, gram, _arb(Fraction(s)))):
            pick = min if end is _lower else max
            try:
                off = pick(end(form[0][1]), end(form[1][0]))
                rows = ((end(form[0][0]), off), (off, end(form[1][1])))
            except _TooWide as exc:
                return end is not _lower, f"{plane}: {exc}"  # decides nothing: neither proved nor refuted
            decision = decide_copositive(rows)
            if decision.holds is not True:
                return False, f"{plane}, sign σ = {'+' if s > 0 else '−'}: {decision.reason}"
    return True, ""


def _not(verdict: tuple[bool, str]) -> tuple[bool, str]:
    return not verdict[0], verdict[1]


class _Budget:
    """The parts one verification may still bisect into (all its premises together)."""

    def __init__(self, parts: int) -> None:
        self.left = parts


def _bisect(a: Fraction, b: Fraction, test: Any, refute: Any, budget: _Budget) -> tuple[int, str]:
    """Cover ``[a, b]`` by dyadic parts on each of which ``test(lo, hi)`` holds: ``(parts, "")``, or ``(parts, why not)``.

    Where a part is not decided, ``refute(t)`` looks at its midpoint: a premise
    false there ends the search at once (a false certificate costs little);
    otherwise the part is halved, up to :data:`MAX_PARTS` parts for this
    premise and the budget of the whole verification.
    """
    stack, done, why = [(a, b)], 0, ""
    while stack:
        lo, hi = stack.pop()
        holds, why = test(lo, hi)
        budget.left -= 1
        if holds:
            done += 1
            continue
        mid = (lo + hi) / 2
        false_at, reason = refute(mid)
        if false_at:
            return done, f"refuted at t = {_f(mid)} ({reason})"
        if done + len(stack) + 2 > MAX_PARTS or budget.left < 2:
            limit = f"{MAX_PARTS} parts" if budget.left >= 2 else f"the {MAX_TOTAL_PARTS} parts of one verification"
            return done, f"not decided on [{float(lo):.6g}, {float(hi):.6g}] within {limit} ({why})"
        stack += [(mid, hi), (lo, mid)]
    return done, ""


def _norm_refuted(cert: SupFlowCertificate, mu: Any, t: Fraction) -> tuple[bool, str]:
    """``‖e^{At}‖₂² > c₂`` shown at the point ``t`` (the Rayleigh quotient of ``e^{At}ᵀe^{At}`` at a float guess of
    its top eigenvector, in arb; a lower end above ``c₂``)."""
    import numpy as np

    e = _flow(cert, t, t)
    g = e.transpose() * e
    guess = np.linalg.eigh(np.array([[float(g[i, j].mid()) for j in range(3)] for i in range(3)]))[1][:, -1]
    v = [_arb(Fraction(float(x))) for x in guess]
    q = sum(v[i] * g[i, j] * v[j] for i in range(3) for j in range(3)) / sum(x * x for x in v)
    return bool(q > mu), "‖e^(At)‖² > c2 there"


def _decide_flow(premise: FlowNorm | FlowExit, budget: _Budget) -> Check:
    import flint

    from .flow_bound import _below

    cert = premise.certificate
    old = flint.ctx.prec
    flint.ctx.prec = PRECISION
    try:
        horizon = cert.pieces[-1].start
        if isinstance(premise, FlowNorm):
            mu = _arb(cert.constants["c2"])
            if not _below(mu, flint.arb_mat([list(r) for r in _tail_gram(cert, horizon)])):
                return Check(premise.obligation, premise.name, f"the tail form at T = {_f(horizon)} is not below c2", False)

            def below(lo: Fraction, hi: Fraction) -> tuple[bool, str]:
                e = _flow(cert, lo, hi)
                return _below(mu, e.transpose() * e), "‖e^(At)‖² ≥ c2 or too close to it"

            parts, why = _bisect(Fraction(0), horizon, below, lambda t: _norm_refuted(cert, mu, t), budget)
            text = f"c2 = {_f(cert.constants['c2'])} on [0, {_f(horizon)}] in {parts} parts and past it by P"
            return Check(premise.obligation, premise.name, why or text, not why)
        piece = cert.pieces[premise.index]
        k = tuple(tuple(_arb(x) for x in row) for row in piece.k_matrix())
        if piece.end is None:
            holds, why = _exit_holds(k, _tail_gram(cert, piece.start))
            return Check(premise.obligation, premise.name, why or f"past T = {_f(piece.start)} by P", holds)
        if not piece.start < piece.end:
            return Check(premise.obligation, premise.name, f"empty piece {piece.interval_text()}", False)
        parts, why = _bisect(piece.start, piece.end, lambda lo, hi: _exit_holds(k, _gram(_flow(cert, lo, hi))),
                             lambda t: _not(_exit_holds(k, _gram(_flow(cert, t, t)), end=_upper)), budget)
        return Check(premise.obligation, premise.name, why or f"on {piece.interval_text()} in {parts} parts", not why)
    finally:
        flint.ctx.prec = old


def sup_flow_premises(cert: SupFlowCertificate) -> list[Any]:
    """Every premise of a sup-flow certificate, in proof order."""
    k_p, k_i, k_v, f_c = cert.k_p, cert.k_i, cert.k_v, cert.f_c
    const, pieces = cert.constants, cert.pieces
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
    out.append(Inequality("sup_flow.exit", "T > 0 (the last piece starts after 0)", pieces[-1].start, ">", zero))
    p_paper = _paper_p(cert)
    p = const["p"]
    out += [
        Inequality("sup_flow.exit", "p > 0", p, ">", zero),
        Semidefinite("sup_flow.exit", "P − p·I ⪰ 0 (the paper's P)", _sub(p_paper, _scaled_identity(3, p))),
        Semidefinite("lemma2.dVdt", "−(AᵀP + PA) ⪰ 0 (the paper's P)",
                     tuple(tuple(-x for x in row) for row in quad.lyapunov_rate_entries(k_p, k_i, k_v, p_paper))),
        FlowNorm("sup_flow.bounds", "c2 ≥ ‖e^(At)‖² for every t ≥ 0", cert),
        Copositive("sup_flow.bounds", "K1 − I copositive (piece 1)", _sub(pieces[0].k_matrix(), _scaled_identity(3, zero + 1))),
    ]
    for i, piece in enumerate(pieces):
        k, tag = piece.k_matrix(), f"piece {i + 1}"
        for s, sign in ((1, "+"), (-1, "−")):
            b = quad.slip_rate_entries(k_p, k_i, k_v, zero + s)
            out.append(Copositive("quadratic.U_rate", f"{tag}: −(K·B{sign} + B{sign}ᵀ·K) copositive", quad.u_rate_entries(k, b)))
            out.append(Copositive("quadratic.U_rate", f"{tag}: band form (s = {sign}1) copositive",
                                  quad.band_rate_entries(k_i, k_v, k, zero + s)))
        for j in range(3):
            out.append(Inequality("quadratic.U_rate", f"{tag}: K3{j + 1} ≥ 0", k[2][j], ">=", zero))
        out.append(Copositive("sup_flow.stability_bound", f"{tag}: gamma·I − K copositive",
                              _sub(_scaled_identity(3, piece.constants["gamma"]), k)))
        out.append(FlowExit("sup_flow.exit", f"{tag}: U ≥ |e^(At)w|² on the exits of R̂ for t in {piece.interval_text()}", cert, i))
    kappa = cert.kappa
    out += [
        Inequality("sup_flow.stability_bound", "overshoot_bound > 0", kappa, ">", zero),
        Inequality("sup_flow.stability_bound", "overshoot_bound² ≥ c2", kappa * kappa, ">=", const["c2"]),
    ]
    out += [Inequality("sup_flow.stability_bound", f"overshoot_bound² ≥ gamma (piece {i + 1})", kappa * kappa, ">=",
                       piece.constants["gamma"]) for i, piece in enumerate(pieces)]
    return out


def _decide(premise: Any, budget: _Budget | None = None) -> Check:
    if isinstance(premise, (FlowNorm, FlowExit)):
        return _decide_flow(premise, budget or _Budget(MAX_TOTAL_PARTS))
    return decide_premise(premise)


@dataclass(frozen=True)
class SupFlowReport(VerificationReport):
    """Per-premise verdicts of a sup-flow certificate (proved iff there is a check and every one holds)."""

    certificate: SupFlowCertificate  # type: ignore[assignment]
    checks: tuple[Check, ...]
    source: str = "<certificate>"

    def summary(self) -> str:
        if self.proved:
            return (f"PROVED {self.source}: all {len(self.checks)} premises of the sup-flow template hold; "
                    f"|x(t)|_A <= {self.certificate.overshoot_bound}·|x(0)|_A")
        return super().summary()


def verify_sup_flow(certificate: SupFlowCertificate, *, source: str = "<certificate>") -> SupFlowReport:
    """Decide every premise of :func:`sup_flow_premises` (a structural failure stops before the flow is enclosed)."""
    if not isinstance(certificate, SupFlowCertificate):
        raise TypeError(f"verify_sup_flow needs a SupFlowCertificate; got {type(certificate).__name__}")
    checks, structural, budget = [], True, _Budget(MAX_TOTAL_PARTS)
    for premise in sup_flow_premises(certificate):
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
    """Read a sup-flow certificate file strictly (bounded read; not verified).

    Raises
    ------
    InputFileError, CertificateFormatError
        If the file cannot be read, is not strict JSON or is not a sup-flow certificate.
    """
    from ._json import read_json

    return SupFlowCertificate.from_dict(read_json(path), source=str(path))


def dumps_sup_flow(certificate: SupFlowCertificate) -> str:
    """The file's bytes: sorted keys, two-space indentation, trailing newline."""
    return json.dumps(certificate.to_dict(), indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def _stale(certificate: SupFlowCertificate, path: Path) -> str:
    """Why the committed ``path`` is not the canonical file of its own numbers (empty if it is); no search is re-run."""
    from .._infra.io import read_limited
    from ._json import MAX_FILE_BYTES

    if read_limited(Path(path), limit=MAX_FILE_BYTES, what="certificate") != dumps_sup_flow(certificate).encode("utf-8"):
        return f"{Path(path).name} is not in canonical form (keys sorted, two-space indentation, exact rationals)"
    return ""


SUP_FLOW = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: SupFlowCertificate.from_dict(data, source=source),
    verify=lambda certificate, source: verify_sup_flow(certificate, source=source),
    dumps=dumps_sup_flow,
    stale=_stale,
    failure=lambda report: "; ".join(check.message for check in report.failures),
    claim=lambda certificate: f"κ ≤ {certificate.overshoot_bound} (sup-flow template)",
    default=True,
))
"""The sup-flow template (beyond the paper): ``V_∞`` on ``R``, ``U = max_i U_i`` on ``R̂``."""
