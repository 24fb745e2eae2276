"""The sup-flow template, version 2: one form per sign of ``σv`` and the friction-drag split (beyond the paper).

Version 1 (:mod:`.sup_flow`) bounds ``V_∞`` on ``R̂`` by ``U = max_i U_i`` with
one form ``U_i = yᵀK_iy`` (``K₁₂ = 0``) for both signs of ``σ``.  Two facts of
the slip on ``R̂ ∩ {v > 0}`` (the model :mod:`._model.sup_flow`, the
obligations ``sup_flow_v2.*``) let it go lower:

* **Sign split.**  ``σ̇ = −k_iv < 0`` there, so ``σ`` crosses 0 at most once,
  from ``+`` to ``−``.  Each piece has ``U⁺ = yᵀK⁺y`` (used where ``σv > 0``)
  and ``U⁻ = yᵀK⁻y`` (``σv < 0`` and ``σ = 0``), each needing only its own
  sign's premises, with ``K₁₂`` kept of that sign (the rate form's ``(1, 1)``
  entry is ``2sK₁₂``) and ``U⁻ ≤ U⁺`` on ``σ = 0`` (the coupling block
  copositive), so ``U`` can only drop where ``σ`` changes sign.  ``x ↦ −x``
  keeps ``σv``, so ``v < 0`` is the mirror image.
* **Friction-drag split.**  With the friction excess ``f = f_c − φ − |dz φ|``
  and constants ``ℓ ≥ 0``: on ``R̂′ = {f > ℓᵀy}`` the friction takes at least
  ``2(Ky)₃ℓᵀy`` off ``U̇`` (:func:`._model.quadratic.drag_rate_entries`);
  on ``R̂ \\ R̂′`` ``x − f_c e₂`` lies between ``D₀y`` and ``D_ℓy``
  (:func:`._model.sup_flow.drag_exit_map`), so ``V_∞ ≤ c₂|x|²_𝒜`` there when
  ``c₂ ≥ ‖e^{At}D_ℓ‖²`` (``g`` is convex); where a solution leaves ``R̂′`` at
  ``f = ℓᵀy``, ``U ≥ |e^{At}D_ℓy|²`` (the drag exit form).  ``ℓ = 0`` needs
  none of this: ``R̂′`` is then ``R̂`` off the plane ``φ = f_c``, version 1's exit.

A certificate is proved when, decided exactly or in arb balls rounded outward
(undecided is not proved): the frame of version 1 (Assumption 1, ``f_c > 0``,
pieces covering ``[0, ∞)``, the tail's ``P``); ``ℓ ≥ 0``; ``c₂ ≥ ‖e^{At}‖²``
and, with ``ℓ ≠ 0``, ``c₂ ≥ ‖e^{At}D_ℓ(±1)‖²`` for every ``t ≥ 0``; ``K⁺ − I``
and ``K⁻ − I`` copositive on the first piece; per piece and sign ``s``:
``sK^s₁₂ ≥ 0``, the drag rate form (3×3) and drag band form (2×2)
copositive, ``K^s₃ⱼ ≥ 0``, ``γI − K^s`` copositive, the exit forms of both
planes and (``ℓ ≠ 0``) the drag exit form copositive for every ``t`` of the
piece; the coupling block copositive; ``κ² ≥ c₂``, ``κ² ≥ γ_i``.

Format (``schema`` ``symbolic-friction/sup-flow-certificate/v2``, ``template``
``sup-flow/v2``)::

    {"constants": {"c2": …, "ell1": …, "ell2": …, "ell3": …, "p": …, "tail_p11": …, …},
     "overshoot_bound": "1.38000", "parameters": {…},
     "pieces": [{"end": …, "gamma": …, "km11": …, "km12": …, …, "km33": …, "kp11": …, …, "kp33": …, "start": "0"}, …],
     "provenance": {…}, "schema": "symbolic-friction/sup-flow-certificate/v2", "template": "sup-flow/v2"}
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any, ClassVar

from .._model import quadratic as quad
from .._model import sup_flow as model
from ._template import Template, register
from .quadratic import Copositive, _scaled_identity, _sub, canonical_staleness
from .sup_flow import (
    SupFlowCertificate,
    SupFlowPiece,
    bound_premises,
    dumps_sup_flow,
    frame_premises,
    in_fmpq,
    piece_premises,
    verify_sup_flow,
)
from .sup_flow_enclosure import FlowExit, FlowNorm
from .verify import Inequality

__all__ = ["SCHEMA", "TEMPLATE_ID", "CONSTANTS", "PIECE_CONSTANTS", "OBLIGATIONS", "SupFlowPieceV2",
           "SupFlowCertificateV2", "sup_flow_v2_premises", "load_sup_flow", "SUP_FLOW_V2"]

SCHEMA = "symbolic-friction/sup-flow-certificate/v2"
TEMPLATE_ID = "sup-flow/v2"
CONSTANTS = ("c2", "p", "ell1", "ell2", "ell3")
_ENTRIES = ("11", "12", "13", "22", "23", "33")
PIECE_CONSTANTS = tuple(f"kp{e}" for e in _ENTRIES) + tuple(f"km{e}" for e in _ENTRIES) + ("gamma",)
"""``K⁺`` (used where ``σv > 0``), ``K⁻`` (``σv < 0`` and ``σ = 0``) and ``γ``."""
OBLIGATIONS = (
    "lemma2.P",
    "lemma2.dVdt",
    "sup_flow.slip_flow",
    "sup_flow.rest_minimum",
    "sup_flow.nonincreasing",
    "sup_flow.bounds",
    "sup_flow.exit",
    "sup_flow_v2.U_rate",
    "sup_flow_v2.sign_crossing",
    "sup_flow_v2.drag_region",
    "sup_flow_v2.exit",
    "sup_flow_v2.stability_bound",
)
"""The proof obligations (ids of ``symbolic-friction check``) a version-2 certificate instantiates."""


@dataclass(frozen=True)
class SupFlowPieceV2(SupFlowPiece):
    """One time piece with ``K⁺``, ``K⁻`` (``K₁₂`` kept, signed) and ``γ``."""

    names: ClassVar[tuple[str, ...]] = PIECE_CONSTANTS

    def form(self, s: int) -> tuple[tuple[Fraction, ...], ...]:
        """``K⁺`` (``s = 1``) or ``K⁻`` (``s = −1``)."""
        c, tag = self.constants, "kp" if s > 0 else "km"
        return quad.u_matrix_signed(*(c[tag + e] for e in _ENTRIES))

    def k_matrix(self) -> tuple[tuple[Fraction, ...], ...]:
        raise AttributeError("a version-2 piece has two forms: use form(+1) and form(−1)")

    def signed_forms(self) -> tuple[tuple[int, tuple[tuple[Fraction, ...], ...]], ...]:
        return ((1, self.form(1)), (-1, self.form(-1)))


@dataclass(frozen=True)
class SupFlowCertificateV2(SupFlowCertificate):
    """A version-2 sup-flow certificate: version 1's gains, ``c₂``, ``p``, tail and pieces, plus ``ℓ``."""

    schema: ClassVar[str] = SCHEMA
    template_id: ClassVar[str] = TEMPLATE_ID
    constant_names: ClassVar[tuple[str, ...]] = CONSTANTS
    piece_type: ClassVar[type[SupFlowPiece]] = SupFlowPieceV2

    @property
    def ell(self) -> tuple[Fraction, Fraction, Fraction]:
        return (self.constants["ell1"], self.constants["ell2"], self.constants["ell3"])

    def drag_maps(self) -> tuple[tuple[int, Any], ...]:
        """``(s, D_ℓ)`` for ``s = ±1``; none when ``ℓ = 0`` (then ``f = ℓᵀy`` is only the plane ``φ = f_c``)."""
        if not any(self.ell):
            return ()
        return tuple((s, model.drag_exit_map(Fraction(s), self.ell)) for s in (1, -1))

    def premises(self) -> list[Any]:
        return sup_flow_v2_premises(self)


def sup_flow_v2_premises(cert: SupFlowCertificateV2) -> list[Any]:
    """Every premise of a version-2 sup-flow certificate, in proof order (module docstring)."""
    k_p, k_i, k_v = cert.k_p, cert.k_i, cert.k_v
    pieces, ell = cert.pieces, cert.ell
    zero = k_i - k_i
    out = frame_premises(cert)
    out += [Inequality("sup_flow_v2.drag_region", f"ell{j + 1} ≥ 0", ell[j], ">=", zero) for j in range(3)]
    drag, p_tail = bool(cert.drag_maps()), cert.tail_matrix()  # once: the same for every piece
    norm = "c2 ≥ ‖e^(At)‖² for every t ≥ 0" + (" and c2 ≥ ‖e^(At)·D_ℓ‖² (both signs)" if drag else "")
    out.append(FlowNorm("sup_flow_v2.drag_region" if drag else "sup_flow.bounds", norm, cert, p_tail))
    eye = _scaled_identity(3, zero + 1)
    for s, sign in ((1, "+"), (-1, "−")):
        out.append(Copositive("sup_flow.bounds", f"K{sign}1 − I copositive (piece 1)", _sub(pieces[0].form(s), eye)))
    for i, piece in enumerate(pieces):
        tag = f"piece {i + 1}"
        numbers = (k_p, k_i, k_v, *ell, *map(piece.constants.get, piece.names))
        out += piece_premises(TEMPLATE_ID, tag, numbers, lambda piece=piece, tag=tag: _forms_premises(cert, piece, tag))
        where = "the exits of R̂" + (" and of f > ℓᵀy" if drag else "")
        out.append(FlowExit("sup_flow_v2.exit", f"{tag}: U± ≥ |e^(At)w|² on {where} for t in {piece.interval_text()}",
                            cert, p_tail, i))
    return out + bound_premises(cert, "sup_flow_v2.stability_bound")


def _forms_premises(cert: SupFlowCertificateV2, piece: SupFlowPieceV2, tag: str) -> list[Any]:
    """A piece's premises on its forms ``K⁺``, ``K⁻`` and ``γ`` (exact; :func:`sup_flow_v2_premises`'s, before its exit)."""
    k_p, k_i, k_v, ell = cert.k_p, cert.k_i, cert.k_v, cert.ell
    zero, out = k_i - k_i, []
    for s, sign in ((1, "+"), (-1, "−")):
        k = piece.form(s)
        b = quad.slip_rate_entries(k_p, k_i, k_v, zero + s)
        out.append(Inequality("sup_flow_v2.U_rate", f"{tag}: {'' if s > 0 else '−'}K{sign}12 ≥ 0", s * k[0][1], ">=", zero))
        out.append(Copositive("sup_flow_v2.U_rate", f"{tag}: drag rate form of K{sign} (s = {sign}1) copositive",
                              in_fmpq(quad.drag_rate_entries, k, b, ell)))
        out.append(Copositive("sup_flow_v2.U_rate", f"{tag}: drag band form of K{sign} (s = {sign}1) copositive",
                              in_fmpq(quad.drag_band_entries, k_i, k_v, k, zero + s, ell)))
        for j in range(3):
            out.append(Inequality("sup_flow_v2.U_rate", f"{tag}: K{sign}3{j + 1} ≥ 0", k[2][j], ">=", zero))
        out.append(Copositive("sup_flow_v2.stability_bound", f"{tag}: gamma·I − K{sign} copositive",
                              _sub(_scaled_identity(3, piece.constants["gamma"]), k)))
    out.append(Copositive("sup_flow_v2.sign_crossing", f"{tag}: coupling (K+ − K−) on (|dz φ|, |v|) copositive",
                          model.coupling_block(piece.form(1), piece.form(-1))))
    return out


def load_sup_flow(path: str | Path) -> SupFlowCertificate:
    """Read a sup-flow certificate file of either version strictly (bounded read; not verified).

    The file's ``template`` member (``sup-flow/v1`` or ``sup-flow/v2``) selects the reader.

    Raises
    ------
    InputFileError, CertificateFormatError
        If the file cannot be read, is not strict JSON or is not a sup-flow certificate.

    Examples
    --------
    >>> cert = load_sup_flow("proofs/sup_flow/case_a.json")  # doctest: +SKIP
    >>> cert.template_id, cert.overshoot_bound  # doctest: +SKIP
    ('sup-flow/v2', '1.37852')
    """
    from ._json import read_json

    data = read_json(path)
    v2 = isinstance(data, dict) and data.get("template") == TEMPLATE_ID
    return (SupFlowCertificateV2 if v2 else SupFlowCertificate).from_dict(data, source=str(path))


SUP_FLOW_V2 = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: SupFlowCertificateV2.from_dict(data, source=source),
    verify=lambda certificate, source: verify_sup_flow(certificate, source=source),
    dumps=dumps_sup_flow,
    stale=canonical_staleness(dumps_sup_flow),
    claim=lambda certificate: f"κ ≤ {certificate.overshoot_bound} (sup-flow template, version 2)",
    default=True,
))
"""The sup-flow template, version 2 (beyond the paper): forms per sign of ``σv`` and the friction-drag split."""
