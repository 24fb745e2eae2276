"""Box certificates: one proof of Proposition 1 for every gain set in a box (beyond the paper).

A box ``k_p ∈ [lo, hi]``, ``k_i ∈ [lo, hi]``, ``k_v ∈ [lo, hi]``, ``f_c ∈ [lo, hi]`` (or the
box of physical parameters it normalises from, paper §II-A) is covered by pieces, each a
sub-box with one set of constants ``k₁ … k₄, c₁, c₂, ĉ₁, ĉ₂`` (the closed form of
:mod:`.closed_form` built at the piece's worst corners); the file claims
``|x(t)|_𝒜 ≤ κ·|x(0)|_𝒜`` on the whole box with κ the largest over the pieces.

Why four corners decide a piece: every premise of the exact verifier, with the constants
fixed, depends on the gains through ``a = k_v/k_i``, ``k_p`` and ``f_c`` only (up to a
positive power of ``k_i``) and monotonically in each (obligation ``closed_form.monotone``
of ``symbolic-friction check``), so its least margin is at a corner of
``[a_lo, a_hi] × [kp_lo, kp_hi]`` at ``f_c = f_c,lo``; and ``a_lo = k_v,lo/k_i,hi``,
``a_hi = k_v,hi/k_i,lo``.  :func:`verify_box` therefore runs the real verifier
(:func:`.verify.verify_certificate`) at the four corners
``{k_p lo, hi} × {(k_i hi, k_v lo), (k_i lo, k_v hi)}`` of every piece, checks that the pieces
tile the box exactly, and that a recorded physical box normalises into the normalised one.

File format ``symbolic-friction/box-certificate/v1`` (keys sorted, exact rational strings,
no timings)::

    {"schema": "...", "template": "lyapunov-box/v1",
     "box": {"k_p": ["27/10", "33/10"], "k_i": [...], "k_v": [...], "f_c": ["1", "1"]},
     "physical": {...} (optional), "pieces": [{"k_p": [..], "k_i": [..], "k_v": [..], "constants": {...}}, ...],
     "overshoot_bound": "4.23...", "provenance": {...}}
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import os
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from .._infra.errors import AssumptionError, CertificateError, CertificateFormatError, ParameterError
from .._infra.rational import format_rational as _f
from ._memo import Memo
from ._template import Template, register
from .certificate import Certificate, _signed_rational_field
from .verify import Check, verify_certificate

__all__ = [
    "SCHEMA", "TEMPLATE_ID", "GAINS", "PHYSICAL", "BoxPiece", "BoxCertificate", "BoxReport", "normalised_box",
    "certify_box", "verify_box", "dumps_box", "box_from_data", "BOX", "MAX_PIECES", "corners", "is_box_file",
    "write_box", "regenerate_box", "check_box",
]

SCHEMA = "symbolic-friction/box-certificate/v1"
TEMPLATE_ID = "lyapunov-box/v1"
GAINS = ("k_p", "k_i", "k_v", "f_c")
PHYSICAL = ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar")
CONSTANTS = ("k1", "k2", "k3", "k4", "c1", "c2", "c1_hat", "c2_hat")
MAX_PIECES = 4096
"""Most pieces a cover may have (``--pieces``, or what ``--kappa-tol`` needs)."""
MONOTONE = "closed_form.monotone"
"""The obligation (``symbolic-friction check``) that makes four corners decide a piece."""

Interval = tuple[Fraction, Fraction]


def _interval(value: object, where: str) -> Interval:
    if not (isinstance(value, list) and len(value) == 2):
        raise CertificateFormatError(f"{where} must be a list [lo, hi] of two rational strings; got {value!r}")
    lo, hi = (_signed_rational_field(v, f"{where}[{i}]") for i, v in enumerate(value))
    if not lo <= hi:
        raise CertificateFormatError(f"{where} must have lo ≤ hi; got [{_f(lo)}, {_f(hi)}]")
    return lo, hi


def _text(interval: Interval) -> list[str]:
    return [_f(interval[0]), _f(interval[1])]


def normalised_box(physical: dict[str, Interval]) -> dict[str, Interval]:
    """The normalised box enclosing the image of a physical box (paper §II-A), exactly.

    ``k_p = k̄_p/m`` is increasing in ``k̄_p`` and decreasing in ``m`` (``k̄_p > 0``), and so on, so
    the image of the physical box lies in ``k_p ∈ [k̄_p,lo/m_hi, k̄_p,hi/m_lo]``,
    ``k_v ∈ [(k̄_d + α_v)_lo/m_hi, (k̄_d + α_v)_hi/m_lo]``, … (a box that may be larger than the image).

    Raises
    ------
    AssumptionError
        If the mass or a numerator can be ``≤ 0`` or ``α_v < 0`` somewhere in the box.
    """
    m = physical["m"]
    if not m[0] > 0:
        raise AssumptionError(f"the mass needs m > 0 on the whole box; got m ∈ [{_f(m[0])}, {_f(m[1])}]")
    if physical["alpha_v"][0] < 0:
        raise AssumptionError(f"the viscous coefficient needs alpha_v ≥ 0; got alpha_v,lo = {_f(physical['alpha_v'][0])}")
    numerators = {
        "k_p": physical["k_p_bar"], "k_i": physical["k_i_bar"], "f_c": physical["f_c_bar"],
        "k_v": (physical["k_d_bar"][0] + physical["alpha_v"][0], physical["k_d_bar"][1] + physical["alpha_v"][1]),
    }
    for name, (lo, _) in numerators.items():
        if not lo > 0:
            raise AssumptionError(f"{name} = ({'k_d_bar + alpha_v' if name == 'k_v' else name + '_bar'})/m needs a positive "
                                  f"numerator on the whole box; its lowest value is {_f(lo)}")
    return {name: (numerators[name][0] / m[1], numerators[name][1] / m[0]) for name in GAINS}


def corners(box: dict[str, Interval]) -> list[dict[str, Fraction]]:
    """The four corners that decide a box: ``{k_p lo, hi} × {(k_i hi, k_v lo), (k_i lo, k_v hi)}``, ``f_c`` lowest."""
    (kp_lo, kp_hi), (ki_lo, ki_hi), (kv_lo, kv_hi) = box["k_p"], box["k_i"], box["k_v"]
    return [{"k_p": kp, "k_i": ki, "k_v": kv, "f_c": box["f_c"][0]}
            for kp in (kp_lo, kp_hi) for ki, kv in ((ki_hi, kv_lo), (ki_lo, kv_hi))]


def check_box(box: dict[str, Interval]) -> None:
    """Refuse a box that is empty, not positive, or leaves Assumption 1 anywhere (naming the corner)."""
    for name in GAINS:
        lo, hi = box[name]
        if not 0 < lo <= hi:
            raise ParameterError(f"the box needs 0 < {name},lo ≤ {name},hi; got {name} ∈ [{_f(lo)}, {_f(hi)}]")
    # k_v·k_p − k_i is least at (k_p lo, k_i hi, k_v lo)
    kp, ki, kv = box["k_p"][0], box["k_i"][1], box["k_v"][0]
    if not kv * kp > ki:
        raise AssumptionError(
            f"the box leaves Assumption 1 at its corner k_p = {_f(kp)}, k_i = {_f(ki)}, k_v = {_f(kv)}: "
            f"k_v·k_p = {_f(kv * kp)} ≤ k_i = {_f(ki)}"
        )


@dataclass(frozen=True)
class BoxPiece:
    """One piece of the cover: its sub-box (``k_p``, ``k_i``, ``k_v``) and its constants."""

    k_p: Interval
    k_i: Interval
    k_v: Interval
    constants: dict[str, Fraction]

    def box(self, f_c: Interval) -> dict[str, Interval]:
        return {"k_p": self.k_p, "k_i": self.k_i, "k_v": self.k_v, "f_c": f_c}


@dataclass(frozen=True)
class BoxCertificate:
    """A box of gains, its cover by pieces with constants, the claimed κ and how it was found."""

    box: dict[str, Interval]
    pieces: tuple[BoxPiece, ...]
    overshoot_bound: str
    provenance: dict[str, Any]
    physical: dict[str, Interval] | None = None

    def gains_text(self) -> str:
        """``"k_p ∈ [27/10, 33/10], …"`` (and the physical box when recorded)."""
        text = ", ".join(f"{n} ∈ [{_f(lo)}, {_f(hi)}]" for n, (lo, hi) in self.box.items())
        if self.physical is not None:
            text += " (" + ", ".join(f"{n} ∈ [{_f(lo)}, {_f(hi)}]" for n, (lo, hi) in self.physical.items()) + ")"
        return text

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "schema": SCHEMA, "template": TEMPLATE_ID,
            "box": {n: _text(v) for n, v in self.box.items()},
            "pieces": [{"k_p": _text(p.k_p), "k_i": _text(p.k_i), "k_v": _text(p.k_v),
                        "constants": {n: _f(p.constants[n]) for n in CONSTANTS}} for p in self.pieces],
            "overshoot_bound": self.overshoot_bound,
            "provenance": self.provenance,
        }
        if self.physical is not None:
            out["physical"] = {n: _text(v) for n, v in self.physical.items()}
        return out


def dumps_box(certificate: BoxCertificate) -> str:
    """The file text: sorted keys, two-space indentation, ASCII, trailing newline."""
    return json.dumps(certificate.to_dict(), indent=2, sort_keys=True, ensure_ascii=True) + "\n"


@functools.lru_cache(maxsize=1)
def _validator() -> Any:
    import jsonschema
    from importlib.resources import files

    from ._schema import inline_local_refs

    schema = json.loads(files("symbolic_friction").joinpath("schemas", "box-certificate-v1.schema.json").read_text(encoding="utf-8"))
    return jsonschema.Draft202012Validator(inline_local_refs(schema))


def box_from_data(data: object, *, source: str = "<string>") -> BoxCertificate:
    """Parse a box certificate strictly (the shipped JSON schema, then exact rationals); name what is wrong."""
    import jsonschema

    error = jsonschema.exceptions.best_match(_validator().iter_errors(data))
    if error is not None:
        where = "".join(f"[{p!r}]" if isinstance(p, int) else f".{p}" for p in error.absolute_path).lstrip(".") or "certificate"
        raise CertificateFormatError(f"{source}: does not match the box certificate schema at {where}: {error.message[:200]}")
    assert isinstance(data, dict)
    try:
        box = {n: _interval(data["box"][n], f"box.{n}") for n in GAINS}
        physical = None
        if "physical" in data:
            physical = {n: _interval(data["physical"][n], f"physical.{n}") for n in PHYSICAL}
        pieces = tuple(
            BoxPiece(*(_interval(p[n], f"pieces[{i}].{n}") for n in ("k_p", "k_i", "k_v")),
                     {c: _signed_rational_field(p["constants"][c], f"pieces[{i}].constants.{c}", positive=True) for c in CONSTANTS})
            for i, p in enumerate(data["pieces"])
        )
    except CertificateFormatError as exc:
        raise CertificateFormatError(f"{source}: {exc}") from None
    return BoxCertificate(box, pieces, data["overshoot_bound"], dict(data["provenance"]), physical)


# -- the exact decision ---------------------------------------------------------------------

@dataclass(frozen=True)
class BoxReport:
    """What :func:`verify_box` checked, and the verdict."""

    certificate: BoxCertificate
    checks: tuple[Check, ...]
    source: str = "<certificate>"

    @property
    def proved(self) -> bool:
        return bool(self.checks) and all(c.holds for c in self.checks)

    @property
    def failures(self) -> tuple[Check, ...]:
        return tuple(c for c in self.checks if not c.holds)

    def summary(self) -> str:
        if self.proved:
            return (f"PROVED {self.source}: {len(self.certificate.pieces)} piece(s) × 4 corners verified exactly; "
                    f"|x(t)|_A <= {self.certificate.overshoot_bound}·|x(0)|_A for every gain set in the box")
        return f"FAILED {self.source}: " + "; ".join(c.message for c in self.failures[:5])


def _volume(box: dict[str, Interval], axes: tuple[str, ...]) -> Fraction:
    out = Fraction(1)
    for n in axes:
        out *= box[n][1] - box[n][0]
    return out


def _cover_checks(cert: BoxCertificate) -> list[Check]:
    """The pieces tile the box: inside it, flat where it is flat, interiors disjoint, volumes summing to its volume."""
    axes = tuple(n for n in ("k_p", "k_i", "k_v") if cert.box[n][0] < cert.box[n][1])
    boxes = [p.box(cert.box["f_c"]) for p in cert.pieces]
    outside = [i for i, b in enumerate(boxes) if any(
        not (cert.box[n][0] <= b[n][0] <= b[n][1] <= cert.box[n][1]) or (n not in axes and b[n] != cert.box[n])
        for n in ("k_p", "k_i", "k_v"))]
    overlap = next(((i, j) for i in range(len(boxes)) for j in range(i) if all(
        max(boxes[i][n][0], boxes[j][n][0]) < min(boxes[i][n][1], boxes[j][n][1]) for n in axes)), None)
    total, whole = sum((_volume(b, axes) for b in boxes), Fraction(0)), _volume(cert.box, axes)
    return [
        Check("cover", "every piece lies in the box", "all inside" if not outside else f"pieces {outside[:5]} are not", not outside and bool(boxes)),
        Check("cover", "the pieces' interiors are disjoint", "disjoint" if overlap is None else f"pieces {overlap} overlap", overlap is None),
        Check("cover", "the pieces' volumes sum to the box's", f"{_f(total)} = {_f(whole)}", total == whole),
    ]


_CORNERS = Memo()
shared_corners = _CORNERS.sharing
"""Within the block, a corner with the same numbers as one verified before keeps its report (the self-check's and an
edited file's copies of a box share most pieces, and neighbouring pieces share corners)."""


def verify_box(cert: BoxCertificate, *, source: str = "<certificate>") -> BoxReport:
    """Decide a box certificate exactly: the cover, the physical box, and the real verifier at every piece's 4 corners."""
    checks: list[Check] = []
    try:
        check_box(cert.box)
        checks.append(Check("lemma2.P", "Assumption 1 on the whole box", "k_v,lo·k_p,lo > k_i,hi", True))
    except ParameterError as exc:
        checks.append(Check("lemma2.P", "Assumption 1 on the whole box", str(exc), False))
    if cert.physical is not None:
        try:
            image = normalised_box(cert.physical)
            for n in GAINS:
                inside = cert.box[n][0] <= image[n][0] and image[n][1] <= cert.box[n][1]
                checks.append(Check("provenance", f"{n} of the physical box lies in the box",
                                    f"[{_f(image[n][0])}, {_f(image[n][1])}] ⊆ [{_f(cert.box[n][0])}, {_f(cert.box[n][1])}]", inside))
        except ParameterError as exc:
            checks.append(Check("provenance", "the physical box normalises", str(exc), False))
    checks += _cover_checks(cert)
    checks.append(Check(MONOTONE, "four corners decide a piece",
                        "every premise is monotone in a = k_v/k_i, k_p and f_c (obligation closed_form.monotone of "
                        "symbolic-friction check)", True))
    for i, piece in enumerate(cert.pieces):
        failed: list[Check] = []
        count = 0
        for corner in corners(piece.box(cert.box["f_c"])):
            where = f"piece {i + 1}, corner k_p = {_f(corner['k_p'])}, k_i = {_f(corner['k_i'])}, k_v = {_f(corner['k_v'])}"
            try:
                point = Certificate(**corner, **piece.constants, c=2 * (corner["k_v"] * corner["k_p"] - corner["k_i"]),
                                    overshoot_bound=cert.overshoot_bound)
            except CertificateFormatError as exc:
                failed.append(Check("lemma2.P", where, str(exc), False))
                continue
            key = (tuple((n, x.numerator, x.denominator) for n, x in sorted({**corner, **piece.constants}.items())),
                   point.c.numerator, point.c.denominator, point.overshoot_bound)
            report = _CORNERS.get(key, lambda: verify_certificate(point))
            count = len(report.checks)
            failed += [dataclasses.replace(c, name=f"{where}: {c.name}") for c in report.failures]
        checks += failed or [Check(MONOTONE, f"piece {i + 1}: its 4 corners", f"all {count} inequalities hold at each", True)]
    return BoxReport(cert, tuple(checks), source)


# -- the search: the closed form per piece, pieces by bisection --------------------------------

def _piece_kappa_squared(box: dict[str, Interval], mu: Fraction) -> tuple[Fraction, Any]:
    from .closed_form import closed_form_constants

    c = closed_form_constants(box["k_v"][0] / box["k_i"][1], box["k_v"][1] / box["k_i"][0], *box["k_p"], mu=mu)
    return c.kappa_squared, c


def _split(box: dict[str, Interval]) -> tuple[dict[str, Interval], dict[str, Interval]]:
    """Halve the piece along its widest axis (largest hi/lo), exactly."""
    axis = max((n for n in ("k_p", "k_i", "k_v") if box[n][0] < box[n][1]), key=lambda n: box[n][1] / box[n][0])
    lo, hi = box[axis]
    mid = (lo + hi) / 2
    return {**box, axis: (lo, mid)}, {**box, axis: (mid, hi)}


def _pointwise_kappa_squared(box: dict[str, Interval], mu: Fraction) -> Fraction:
    return max(_piece_kappa_squared({n: (v, v) for n, v in c.items()}, mu)[0] for c in corners(box))


def certify_box(
    box: dict[str, Interval] | None = None, *, physical: dict[str, Interval] | None = None, pieces: int = 1,
    kappa_tol: Fraction | None = None, margin: object = None, label: str = "",
) -> BoxCertificate:
    """A box certificate proved by :func:`verify_box` (never returned unproved).

    Parameters
    ----------
    box : dict of (lo, hi), optional
        ``k_p``, ``k_i``, ``k_v``, ``f_c`` intervals (exact).
    physical : dict of (lo, hi), keyword-only
        Instead of ``box``: ``m``, ``k_p_bar``, ``k_i_bar``, ``k_d_bar``, ``alpha_v``, ``f_c_bar``
        intervals; the box is :func:`normalised_box` of it, and both are recorded.
    pieces : int, keyword-only
        Number of pieces of the cover (the piece with the largest κ is halved until there are so many).
    kappa_tol : Fraction, keyword-only
        Instead: halve until the cover's κ is within this relative tolerance of the largest pointwise
        κ at the pieces' corners (at most :data:`MAX_PIECES` pieces).
    margin : number, keyword-only
        ``μ`` of the strict k-conditions (default 1/10⁶).

    Raises
    ------
    ParameterError, AssumptionError
        A box that is empty, not positive, or leaves Assumption 1 (the message names the corner);
        a bad number of pieces or tolerance.
    CertificateError
        If the result does not verify exactly.
    """
    from .. import __version__
    from .certificate import OBLIGATIONS
    from .rounding import KAPPA_DIGITS, sqrt_decimal_up
    from .search import check_margin

    if (box is None) == (physical is None):
        raise ParameterError("give either a box of normalised gains or a box of physical parameters")
    gains = normalised_box(physical) if physical is not None else dict(box)  # type: ignore[arg-type]
    check_box(gains)
    if isinstance(pieces, bool) or not isinstance(pieces, int) or not 1 <= pieces <= MAX_PIECES:
        raise ParameterError(f"--pieces must be an integer in [1, {MAX_PIECES}]; got {pieces!r}")
    if kappa_tol is not None and not 0 < kappa_tol <= 1:
        raise ParameterError(f"--kappa-tol must be in (0, 1]; got {_f(Fraction(kappa_tol))}")
    mu = check_margin(margin, "tightest")
    cover = [(gains, *_piece_kappa_squared(gains, mu))]
    while True:
        worst = max(range(len(cover)), key=lambda i: cover[i][1])
        if kappa_tol is None:
            if len(cover) >= pieces:
                break
        else:
            floor = max(_pointwise_kappa_squared(b, mu) for b, _, _ in cover)
            if cover[worst][1] <= (1 + kappa_tol) ** 2 * floor:
                break
            if len(cover) >= MAX_PIECES:
                raise ParameterError(f"--kappa-tol {_f(Fraction(kappa_tol))} needs more than {MAX_PIECES} pieces")
        if all(cover[worst][0][n][0] == cover[worst][0][n][1] for n in ("k_p", "k_i", "k_v")):
            break  # a point cannot be split
        halves = [(b, *_piece_kappa_squared(b, mu)) for b in _split(cover[worst][0])]
        cover[worst:worst + 1] = halves
    kappa = sqrt_decimal_up(max(k for _, k, _ in cover), KAPPA_DIGITS)
    provenance = {
        "package": "symbolic-friction", "package_version": __version__, "search": "closed-form", "margin": _f(mu),
        "pieces": None if kappa_tol is not None else pieces, "kappa_tol": None if kappa_tol is None else _f(Fraction(kappa_tol)),
        "obligations": [*OBLIGATIONS, MONOTONE], "label": label,
    }
    cert = BoxCertificate(
        gains,
        tuple(BoxPiece(b["k_p"], b["k_i"], b["k_v"], {n: getattr(c, n) for n in CONSTANTS}) for b, _, c in cover),
        kappa, provenance, physical,
    )
    report = verify_box(cert)
    if not report.proved:
        raise CertificateError(f"the closed-form box certificate does not verify exactly: {report.summary()}")
    return cert


def regenerate_box(cert: BoxCertificate) -> BoxCertificate:
    """What :func:`certify_box` writes now for the box, cover settings, margin and label of ``cert``."""
    prov = cert.provenance
    tol = prov.get("kappa_tol")
    return certify_box(
        None if cert.physical is not None else cert.box, physical=cert.physical,
        pieces=prov.get("pieces") or 1, kappa_tol=None if tol is None else Fraction(tol), margin=prov.get("margin"),
        label=prov.get("label", ""),
    )


def box_staleness(cert: BoxCertificate, path: Path) -> str:
    """Why the committed box file differs from what ``certify`` writes now (empty if it does not)."""
    from .._infra.errors import SymbolicFrictionError
    from .._infra.io import read_limited
    from ._json import MAX_FILE_BYTES

    try:
        fresh = dumps_box(regenerate_box(cert))
    except SymbolicFrictionError as exc:
        return f"cannot be regenerated: {exc}"
    if read_limited(path, limit=MAX_FILE_BYTES, what="certificate") != fresh.encode("utf-8"):
        return f"{path.name} differs from what `symbolic-friction certify` writes now"
    return ""


def default_box_stem(cert: BoxCertificate) -> str:
    """``box_<hash of the exact box>``."""
    key = json.dumps(cert.to_dict()["box"], sort_keys=True) + json.dumps(cert.to_dict().get("physical"), sort_keys=True)
    return f"box_{hashlib.sha256(key.encode()).hexdigest()[:12]}"


def is_box_file(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` is a box certificate (``crosscheck`` simulates one gain set per file and leaves these out)."""
    from .._infra.errors import InputFileError
    from ._json import read_json

    try:
        data = read_json(path)
    except (CertificateFormatError, InputFileError):
        return False  # the certificate loader says what is wrong with it
    return isinstance(data, dict) and data.get("schema") == SCHEMA


def write_box(cert: BoxCertificate, path: str | os.PathLike[str]) -> Path:
    """Verify ``cert`` and write it atomically (nothing unproved is written)."""
    from .._infra.io import atomic_write_text

    path = Path(path)
    if path.suffix != ".json":
        raise ParameterError(f"a certificate file name must end in '.json'; got {str(path)!r}")
    report = verify_box(cert, source=path.name)
    if not report.proved:
        raise CertificateError(report.summary())
    return atomic_write_text(path, dumps_box(cert))


BOX = register(Template(
    id=TEMPLATE_ID,
    schema=SCHEMA,
    read=lambda data, source: box_from_data(data, source=source),
    verify=lambda cert, source: verify_box(cert, source=source),
    dumps=dumps_box,
    # the statement is the file itself (verify decides it); regeneration only finds other digits
    stale=lambda certificate, path: "",
    drift=box_staleness,
    failure=lambda report: "; ".join(c.message for c in report.failures[:5]),
    claim=lambda cert: f"κ ≤ {cert.overshoot_bound} on a box, {len(cert.pieces)} piece(s)",
    default=True,
    regenerate=regenerate_box,
))
"""The box certificate: one κ for every gain set in a box, four corners per piece decided by the verifier."""
