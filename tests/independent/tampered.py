"""Tampered corpora: deterministic single edits of every committed certificate, decided by both verifiers (issue 33).

From each certificate of every kind the independent checker reads (``proofs/`` and the version-1 sup-flow test
data; a file of a template the checker does not know is left out) :func:`edits` makes single edits: every number
nudged by a relative ``1e-12``, ``1e-6``, ``1e-2`` up and down, doubled, halved, negated, set to 0; numbers written
as JSON floats or integers, decimals, unreduced, signed, padded, in other digits; keys removed and added; schema,
template, label and provenance strings changed; intervals swapped, widened, narrowed and moved; pieces dropped,
duplicated, swapped, reversed, split and merged; κ set just below and just above what the file's own constants
prove.  :func:`corpus` samples them, seeded, per kind.

Truth is decided without either verifier (:func:`claim_class`): every edit is compared with the committed file,
which both verifiers prove, by what it *claims* (the gains, κ, a box, a cycle's numbers, ρ, …), not by its witness
numbers (constants, forms, pieces, enclosure boxes):

* ``same``: the claim is unchanged (only the witness or the spelling moved), so it is still true;
* ``weaker``: the committed claim implies it (κ raised, a smaller box, a wider interval, a claim dropped);
* ``false``: it claims more than the committed file proves, by more than the committed numbers' rounding, or
  breaks the model's assumptions (κ below the committed value by more than its 5-decimal rounding or below what
  the file's constants give, a gain box enlarged, a Krawczyk box or a cycle interval moved off the committed
  enclosure, ``stable`` turned false, ``overshoot`` flipped, ρ lowered, the radius raised, a time shortened, gains
  that leave Assumption 1): **both verifiers must refuse it**;
* ``other``: a different claim neither implied nor known false (other gains, a stronger κ within its rounding, a
  label): either verdict may be right, but the verifiers must agree.

Where they do not, the main verifier must refuse by a format rule (:func:`format_rule`: a malformed file, the
equation for ``c``, a label, the provenance's obligations) and ``verify`` must say so (checked by running it).

``python -m tests.independent.tampered --all`` runs the full corpus and prints the counts per kind.
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import functools
import io
import json
import math
import random
import re
import sys
import tempfile
import time
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any, Iterator

ROOT = Path(__file__).resolve().parents[2]
KIND_OF_TEMPLATE = {
    "lyapunov-pair/v1": "paper", "lyapunov-box/v1": "box", "quadratic/v1": "quadratic", "sup-flow/v1": "sup-flow/v1",
    "sup-flow/v2": "sup-flow/v2", "hunting-cycle/v1": "hunting", "reset-contraction/v1": "reset-contraction",
}
SCHEMA_TEMPLATE = {
    "symbolic-friction/certificate/v1": "lyapunov-pair/v1",
    "symbolic-friction/box-certificate/v1": "lyapunov-box/v1",
    "symbolic-friction/hunting-certificate/v1": "hunting-cycle/v1",
}
SCHEMAS = (
    "symbolic-friction/certificate/v1", "symbolic-friction/box-certificate/v1", "symbolic-friction/hunting-certificate/v1",
    "symbolic-friction/quadratic-certificate/v1", "symbolic-friction/sup-flow-certificate/v1",
    "symbolic-friction/sup-flow-certificate/v2", "symbolic-friction/reset-contraction-certificate/v1",
)
KINDS = tuple(dict.fromkeys(KIND_OF_TEMPLATE.values()))
DEFAULT_PER_KIND = 100
"""Edits per kind the default test suite decides (seeded)."""
FULL_PER_KIND = 600
"""Edits per kind of the full sweep (``--all``)."""
DEFAULT_CAPS = {"proofs/sup_flow/case_a.json": 6, "proofs/box_case_a_10pct.json": 30}
"""In the default run, at most so many edits of the files whose main verification is slow (about 2 s and 0.2 s
a file; the rest of the kind's quota goes to its other files); ``--all`` has no caps."""
KAPPA_ROUNDING = Fraction(1, 10**5)
"""κ is written rounded up to 5 decimals: an edit lower by less may still be what the constants prove."""
ROUNDING = Fraction(1, 10**5)
"""Relative slack of the reset-contraction numbers (ρ, radius, times: 6 significant digits rounded outward)."""
RELATIVE = (Fraction(1, 10**12), Fraction(1, 10**6), Fraction(1, 100))


def template_of(data: object) -> str | None:
    if not isinstance(data, dict):
        return None
    template = data.get("template")
    return template if isinstance(template, str) else SCHEMA_TEMPLATE.get(data.get("schema"))


def sources() -> list[tuple[str, Path]]:
    """``(kind, path)`` of every committed certificate of a kind the independent checker reads."""
    files = sorted((ROOT / "proofs").rglob("*.json")) + sorted((ROOT / "tests/certify/data/sup_flow_v1").glob("*.json"))
    out = []
    for path in files:
        kind = KIND_OF_TEMPLATE.get(template_of(json.loads(path.read_text(encoding="utf-8"))))
        if kind is not None:
            out.append((kind, path))
    return out


@dataclass
class Edit:
    """One edited copy of a committed certificate and what it claims compared with the original."""

    kind: str
    source: str
    what: str
    family: str
    data: Any
    claim: str = ""
    note: str = ""
    text: str | None = None  # the file's text when it is not the canonical dump of ``data``
    original: Any = field(default=None, repr=False)  # the committed file's data

    def file_text(self) -> str:
        return self.text if self.text is not None else json.dumps(self.data, indent=2, sort_keys=True, ensure_ascii=False) + "\n"


# -- numbers ---------------------------------------------------------------------------------------------------------

_RATIONAL = re.compile(r"^[+-]?[0-9]+(/[0-9]+)?$")
_DECIMAL = re.compile(r"^-?[0-9]+(\.[0-9]+)?$")


def value(x: object) -> Fraction | None:
    """What a number of a file means, read leniently (None: not a number)."""
    if isinstance(x, bool) or x is None:
        return None
    if isinstance(x, (int, float)):
        return Fraction(x) if math.isfinite(x) else None
    if isinstance(x, str):
        exponent = re.search(r"[eE]([+-]?[0-9]+)", x)
        if exponent and abs(int(exponent.group(1))) > 20_000:
            return None  # beyond what either reader takes (and 10^999999 is slow to build)
        try:
            with any_digits():  # a number of 4400 digits means what it says
                return Fraction(x)
        except (ValueError, ZeroDivisionError):
            return None
    return None


@contextlib.contextmanager
def any_digits() -> Iterator[None]:
    """Python's limit on int ↔ str conversions lifted while the corpus writes or reads a number (never while a
    verifier runs: a verifier must cope with 4400-digit numbers under the default limit)."""
    limit = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)
    try:
        yield
    finally:
        sys.set_int_max_str_digits(limit)


def rational_text(q: Fraction) -> str:
    with any_digits():
        return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def decimal_text(q: Fraction) -> str | None:
    """``q`` as a plain decimal (exact), or None if it has no finite one."""
    d, twos, fives = q.denominator, 0, 0
    while d % 2 == 0:
        d, twos = d // 2, twos + 1
    while d % 5 == 0:
        d, fives = d // 5, fives + 1
    if d != 1:
        return None
    places = max(twos, fives)
    n = abs(q.numerator) * 10**places // q.denominator
    with any_digits():
        digits = str(n).rjust(places + 1, "0")
    body = digits if places == 0 else f"{digits[:-places]}.{digits[-places:]}"
    return ("-" if q < 0 else "") + body


def written_like(original: object, q: Fraction) -> object:
    """``q`` written as the original number was (a decimal stays a decimal, an integer an integer)."""
    if isinstance(original, int) and not isinstance(original, bool):
        return int(q)
    if isinstance(original, str) and "." in original:
        return decimal_text(q) or rational_text(q)
    return rational_text(q)


def leaves(obj: object, path: tuple = ()) -> Iterator[tuple[tuple, object]]:
    if isinstance(obj, dict):
        for key in sorted(obj):
            yield from leaves(obj[key], (*path, key))
    elif isinstance(obj, list):
        for i, item in enumerate(obj):
            yield from leaves(item, (*path, i))
    else:
        yield path, obj


def get(obj: object, path: tuple) -> object:
    for key in path:
        obj = obj[key]  # type: ignore[index]
    return obj


class Lazy:
    """An edit of ``data`` at ``path`` made only when asked (a sup-flow file has thousands of numbers).

    ``written``: ``(original, q)``, the new value is ``written_like(original, q)``, spelt only then (a 4400-digit
    nudge of each of those numbers took most of the time to list a file's edits, of which a sample is made).
    """

    def __init__(self, data: object, path: tuple, new: object = None, *, remove: bool = False,
                 written: tuple[object, Fraction] | None = None) -> None:
        self.data, self.path, self.new, self.remove, self.written = data, path, new, remove, written

    def __call__(self) -> object:
        out = copy.copy(self.data)
        holder, parent = out, None
        for key in self.path[:-1]:  # copy only the containers on the path
            parent, holder = holder, copy.copy(holder[key])  # type: ignore[index]
            parent[key] = holder  # type: ignore[index]
        if self.remove:
            del holder[self.path[-1]]  # type: ignore[attr-defined]
        else:
            holder[self.path[-1]] = self.new if self.written is None else written_like(*self.written)  # type: ignore[index]
        return out


def replaced(data: object, path: tuple, new: object) -> Lazy:
    return Lazy(data, path, new)


def removed(data: object, path: tuple) -> Lazy:
    return Lazy(data, path, remove=True)


def built(edited: object) -> object:
    return edited() if isinstance(edited, Lazy) else edited


def where(path: tuple) -> str:
    return "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in path).lstrip(".") or "(top)"


def is_number_leaf(path: tuple, x: object) -> bool:
    if isinstance(x, bool) or x is None:
        return False
    if isinstance(x, int):
        return True
    return isinstance(x, str) and bool(_RATIONAL.match(x) or _DECIMAL.match(x)) and path[-1] != "package_version"


# -- the edits -------------------------------------------------------------------------------------------------------


def numeric_edits(data: dict) -> Iterator[tuple[str, str, object]]:
    """``(what, family, edited data)``: every number nudged, doubled, halved, negated, zeroed (integers by ±1 too)."""
    for path, x in leaves(data):
        if not is_number_leaf(path, x):
            continue
        q = value(x)
        assert q is not None
        name = where(path)
        if isinstance(x, int):
            for label, y in (("+1", x + 1), ("−1", x - 1), ("×2", 2 * x), ("÷2", x // 2), ("negated", -x), ("0", 0)):
                if y != x:
                    yield f"{name} {label}", f"int {label}", replaced(data, path, y)
            continue
        changes = [(f"×(1{s}1e-{e})", f"nudge {s}1e-{e}", q * (1 + sign * Fraction(1, 10**e)))
                   for e in (12, 9, 6, 4, 2) for sign, s in ((1, "+"), (-1, "−"))]
        # a number that no longer fits in 60 (or 4300) digits, almost the same value
        changes += [(f"×(1{s}1e-{e})", f"long nudge {s}1e-{e}", q * (1 + sign * Fraction(1, 10**e)))
                    for e in (70, 4400) for sign, s in ((1, "+"), (-1, "−"))]
        changes += [("×2", "×2", 2 * q), ("÷2", "÷2", q / 2), ("negated", "negated", -q), ("set to 0", "zero", Fraction(0))]
        if q == 0:
            changes += [(f"set to {t}", "from zero", Fraction(t)) for t in ("1/1000000000000", "1/100", "-1/100", "1")]
        for label, family, y in changes:
            if y != q:
                yield f"{name} {label}", family, Lazy(data, path, written=(x, y))


FULLWIDTH = str.maketrans("0123456789", "０１２３４５６７８９")


def spelling_edits(data: dict, rng: random.Random) -> Iterator[tuple[str, str, object]]:
    """The same (or a float-rounded) number in another spelling: float, integer, decimal, unreduced, signed, …"""
    for path, x in leaves(data):
        if not is_number_leaf(path, x) or isinstance(x, int):
            continue
        q = value(x)
        assert q is not None
        name = where(path)
        forms = [("JSON float", float(q)), ("float repr", repr(float(q))), ("unreduced", f"{2 * q.numerator}/{2 * q.denominator}"),
                 ("leading +", "+" + x if not x.startswith("-") else None), ("leading 0", re.sub(r"^(-?)", r"\g<1>0", x, count=1)),
                 ("padded", f" {x} "), ("exponent", f"{x}e0" if "/" not in x else None),
                 ("fullwidth digits", x.translate(FULLWIDTH)), ("rational", rational_text(q) if "." in x else None),
                 ("decimal", decimal_text(q) if "." not in x else None), ("underscore", x[:1] + "_" + x[1:] if len(x) > 1 and x[1].isdigit() else None)]
        if q.denominator == 1:
            forms.append(("JSON integer", int(q)))
        if "/" in x:
            forms.append(("4400 digits", x.replace("/", "0" * 4400 + "/") + "0" * 4400))
        forms = [(label, y) for label, y in forms if y is not None and y != x]
        for label, y in rng.sample(forms, min(3, len(forms))):
            yield f"{name} as {label} {y!r:.40}", f"spelling: {label}", replaced(data, path, y)


def key_edits(data: dict) -> Iterator[tuple[str, str, object]]:
    """Every key of every object removed (pieces: of the first and last only), and an unknown one added to each."""
    def objects(obj: object, path: tuple = ()) -> Iterator[tuple[tuple, dict]]:
        if isinstance(obj, dict):
            yield path, obj
            for key in sorted(obj):
                yield from objects(obj[key], (*path, key))
        elif isinstance(obj, list):
            for i, item in enumerate(obj):
                if i in (0, len(obj) - 1):
                    yield from objects(item, (*path, i))

    for path, obj in objects(data):
        for key in sorted(obj):
            yield f"{where((*path, key))} removed", "key removed", removed(data, (*path, key))
        yield f"{where(path)}: unknown key added", "key added", replaced(data, (*path, "extra"), "1") if path else {**data, "extra": "1"}
    for key in ("provenance", "physical", "cycle", "template"):
        if key not in data:
            added = {"provenance": {"label": "x"}, "physical": None, "cycle": None,
                     "template": next((t for t, k in SCHEMA_TEMPLATE.items() if k == data.get("schema")), None)}[key]
            if added is not None:
                yield f"{key} added", "key added", {**data, key: added}


def string_edits(data: dict) -> Iterator[tuple[str, str, object]]:
    """Schema, template, label, claim, verdict and provenance strings changed."""
    schema = data.get("schema")
    for other in SCHEMAS:
        if other != schema:
            yield f"schema → {other}", "schema", {**data, "schema": other}
    yield "schema + 'x'", "schema", {**data, "schema": f"{schema}x"}
    for other in KIND_OF_TEMPLATE:
        if other != data.get("template"):
            yield f"template → {other}", "template", {**data, "template": other}
    yield "template → 'nope/v1'", "template", {**data, "template": "nope/v1"}
    prov = data.get("provenance")
    if isinstance(prov, dict):
        for label in ("Table I, case (a)", "Table I, case (b)", "Table I, case (c)", "table I, case (a)",
                      "Table I, case (a) ", "compared with Table I, case (b)", ""):
            if prov.get("label") != label:
                yield f"provenance.label → {label!r}", "label", {**data, "provenance": {**prov, "label": label}}
        if isinstance(prov.get("obligations"), list):
            obl = prov["obligations"]
            for what, new in (("first dropped", obl[1:]), ("unknown added", [*obl, "lemma9.nowhere"]), ("emptied", []),
                              ("duplicated", [*obl, obl[0]])):
                yield f"provenance.obligations {what}", "obligations", {**data, "provenance": {**prov, "obligations": new}}
        for key in sorted(prov):
            if isinstance(prov[key], str) and key != "label":
                yield f"provenance.{key} → 'tampered'", "provenance string", {**data, "provenance": {**prov, key: "tampered"}}
    for key, options in (("claim", ("symmetric hunting cycles", "asymmetric hunting cycle")),
                         ("verdict", ("not proved", "Proved", "proved ")),):
        if key in data:
            for new in options:
                yield f"{key} → {new!r}", key, {**data, key: new}


def interval_edits(data: dict) -> Iterator[tuple[str, str, object]]:
    """Every ``[lo, hi]``: swapped, collapsed to either end, widened and narrowed (relative 1e-6), moved by its width."""
    for path, x in leaves(data):
        if not (path and path[-1] == 0):
            continue
        pair = get(data, path[:-1])
        if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(v, str) for v in pair)):
            continue
        lo, hi = value(pair[0]), value(pair[1])
        if lo is None or hi is None:
            continue
        name, at = where(path[:-1]), path[:-1]
        width, big = hi - lo, max(abs(lo), abs(hi))
        eps = big / 10**6
        for label, new in (("swapped", (hi, lo)), ("collapsed to lo", (lo, lo)), ("collapsed to hi", (hi, hi)),
                           ("widened", (lo - eps, hi + eps)), ("narrowed", (lo + width / 4, hi - width / 4)),
                           ("moved up by its width", (hi, hi + width)), ("moved down by its width", (lo - width, lo)),
                           ("moved up 1e-2", (lo + big / 100, hi + big / 100))):
            if new != (lo, hi):
                yield f"{name} {label}", f"interval {label}", replaced(data, at, [rational_text(new[0]), rational_text(new[1])])


def _piece_split(piece: dict, kind: str) -> tuple[dict, dict] | None:
    if kind == "box":
        axis = max(("k_p", "k_i", "k_v"), key=lambda n: value(piece[n][1]) - value(piece[n][0]))
        lo, hi = value(piece[axis][0]), value(piece[axis][1])
        mid = rational_text((lo + hi) / 2)
        return {**piece, axis: [piece[axis][0], mid]}, {**piece, axis: [mid, piece[axis][1]]}
    start, end = value(piece["start"]), value(piece["end"]) if piece["end"] != "inf" else None
    mid = rational_text(start + 1 if end is None else (start + end) / 2)
    return {**piece, "end": mid}, {**piece, "start": mid}


def piece_edits(data: dict, kind: str) -> Iterator[tuple[str, str, object]]:
    """Pieces dropped, duplicated, swapped with the next, reversed, split in two (same constants) and merged."""
    pieces = data.get("pieces")
    if not isinstance(pieces, list):
        return
    n = len(pieces)
    for i in sorted({0, 1, n // 2, n - 2, n - 1} & set(range(n))):
        rest = pieces[:i] + pieces[i + 1:]
        yield f"pieces[{i}] dropped", "piece dropped", {**data, "pieces": rest}
        yield f"pieces[{i}] duplicated", "piece duplicated", {**data, "pieces": pieces[:i + 1] + pieces[i:]}
        if i + 1 < n:
            yield f"pieces[{i}] swapped with the next", "pieces swapped", {**data, "pieces": pieces[:i] + [pieces[i + 1], pieces[i]] + pieces[i + 2:]}
        halves = _piece_split(pieces[i], kind)
        if halves is not None:
            yield f"pieces[{i}] split in two", "piece split", {**data, "pieces": pieces[:i] + list(halves) + pieces[i + 1:]}
        if kind != "box" and i + 1 < n:  # one piece over both intervals, with the first's forms
            merged = {**pieces[i], "end": pieces[i + 1]["end"]}
            yield f"pieces[{i}] merged with the next", "pieces merged", {**data, "pieces": pieces[:i] + [merged] + pieces[i + 2:]}
    yield "pieces reversed", "pieces reversed", {**data, "pieces": pieces[::-1]}
    yield "pieces emptied", "pieces emptied", {**data, "pieces": []}
    if kind == "box":  # a face shared by two pieces moved into one of them: an overlap, or a gap
        for i in range(min(n, 4)):
            for axis in ("k_p", "k_i", "k_v"):
                lo, hi = value(pieces[i][axis][0]), value(pieces[i][axis][1])
                box_hi = value(data["box"][axis][1])
                if hi < box_hi:
                    for label, new in (("overlapping its neighbour", hi + (hi - lo) / 8), ("leaving a gap", hi - (hi - lo) / 8)):
                        moved = [*pieces[:i], {**pieces[i], axis: [pieces[i][axis][0], rational_text(new)]}, *pieces[i + 1:]]
                        yield f"pieces[{i}].{axis} hi moved, {label}", f"piece {label}", {**data, "pieces": moved}
                    break
    else:
        for i in sorted({0, n // 2, n - 2} & set(range(n - 1))):
            yield f"pieces[{i}] ends at inf", "piece ends at inf", replaced(data, ("pieces", i, "end"), "inf")
        last = value(pieces[-1]["start"])
        yield "the last piece ends at a number", "last piece finite", replaced(data, ("pieces", n - 1, "end"), rational_text(last + 1))


def kappa_bound(data: dict, kind: str) -> Fraction | None:
    """κ² that the file's own constants give (Proposition 1's bound, as the template states it)."""
    try:
        if kind == "paper":
            c = {k: value(v) for k, v in data["constants"].items()}
            return c["c2"] * c["c2_hat"] / (c["c1"] * c["c1_hat"])
        if kind == "box":
            return max(value(p["constants"]["c2"]) * value(p["constants"]["c2_hat"])
                       / (value(p["constants"]["c1"]) * value(p["constants"]["c1_hat"])) for p in data["pieces"])
        if kind == "quadratic":
            return max(value(data["constants"]["c2"]), value(data["constants"]["gamma"]))
        if kind.startswith("sup-flow"):
            return max([value(data["constants"]["c2"])] + [value(p["gamma"]) for p in data["pieces"]])
    except (KeyError, TypeError, ZeroDivisionError):
        return None
    return None


def sqrt_decimal(square: Fraction, places: int, *, up: bool) -> Fraction:
    """``√square`` rounded down or up to ``places`` decimals (exact)."""
    scale = 10**places
    n = math.isqrt(square.numerator * scale * scale // square.denominator)
    while Fraction(n + 1, scale) ** 2 <= square:
        n += 1
    while Fraction(n, scale) ** 2 > square:
        n -= 1
    if up and Fraction(n, scale) ** 2 < square:
        n += 1
    return Fraction(n, scale)


def special_edits(data: dict, kind: str) -> Iterator[tuple[str, str, object, str, str]]:
    """``(what, family, data, claim, note)`` whose truth is known by construction."""
    square = kappa_bound(data, kind)
    if square is not None:
        below = sqrt_decimal(square, 5, up=False)
        if below * below < square:
            yield (f"overshoot_bound → {decimal_text(below)}, just below √{float(square):.9g}", "κ just below the constants' bound",
                   {**data, "overshoot_bound": decimal_text(below)}, "false",
                   "κ below what the file's own constants prove (κ² < their bound)")
        above = sqrt_decimal(square, 6, up=True)
        yield (f"overshoot_bound → {decimal_text(above)}, just above √{float(square):.9g}", "κ just above the constants' bound",
               {**data, "overshoot_bound": decimal_text(above)}, "other",
               "a stronger κ that the file's own constants still prove (κ² ≥ their bound)")
        yield "overshoot_bound → 100", "κ raised", {**data, "overshoot_bound": "100"}, "weaker", "a larger κ"
    if kind == "hunting":
        cycle = data.get("cycle") or {}
        for axis, claim in (("sigma", "sigma"), ("tau", "slip_time")):
            c_lo, c_hi = (value(v) for v in cycle[claim])
            b_lo, b_hi = (value(v) for v in data["box"][axis])
            for label, new in (("shrunk below the zero", (b_lo, c_lo - (c_lo - b_lo) / 2)),
                               ("shrunk above the zero", (c_hi + (b_hi - c_hi) / 2, b_hi))):
                yield (f"box.{axis} {label}", "Krawczyk box shrunk off the zero",
                       replaced(data, ("box", axis), [rational_text(new[0]), rational_text(new[1])]), "false",
                       f"the zero lies in cycle.{claim}, outside the box")
            yield (f"box.{axis} shrunk onto cycle.{claim}", "Krawczyk box shrunk onto the enclosure",
                   replaced(data, ("box", axis), [rational_text(c_lo), rational_text(c_hi)]), "other",
                   "the zero is still in the box, which is smaller")
        if cycle.get("stable") is not None:
            yield ("cycle.stable negated", "stable negated", replaced(data, ("cycle", "stable"), not cycle["stable"]), "false",
                   "the committed file proves the opposite")
            yield "cycle.stable → null", "stable → null", replaced(data, ("cycle", "stable"), None), "weaker", "claims nothing"
        for key in ("precision_bits",):
            for bits in (53, 64, 256, 4096, 52, 4097, 128.0, "128", True):
                if bits != data[key] or type(bits) is not type(data[key]):
                    yield f"precision_bits → {bits!r}", "precision", {**data, key: bits}, "", ""
    if kind == "reset-contraction":
        yield ("overshoot flipped", "overshoot flipped", {**data, "overshoot": not data["overshoot"]}, "false",
               "the committed file proves the opposite sign of E11")
        for new in ("true", 1, None):
            yield f"overshoot → {new!r}", "overshoot spelling", {**data, "overshoot": new}, "", ""
        for cycles in (9.0, "9", True, 10_001, -1):
            yield f"settling.cycles → {cycles!r}", "cycles spelling", replaced(data, ("settling", "cycles"), cycles), "", ""


def text_edits(data: dict, text: str) -> Iterator[tuple[str, str, object, str]]:
    """``(what, family, data, file text)``: edits of the file's text that no JSON value spells."""
    first = next(p for p, x in leaves(data) if is_number_leaf(p, x) and isinstance(x, str) and isinstance(p[-1], str))
    key = json.dumps(first[-1])
    at = text.index(key + ":")
    start = text.rindex("\n", 0, at) + 1
    duplicate = text[:start] + text[start:at] + f'{key}: "1",\n' + text[start:]  # the same key, earlier, another value
    yield f"{where(first)} twice (duplicate key)", "duplicate key", data, duplicate
    yield "a byte-order mark", "byte-order mark", data, "\ufeff" + text
    yield "trailing garbage", "trailing garbage", data, text + "x"
    x = get(data, first)
    yield f"{where(first)} → NaN", "NaN", data, text.replace(f"{key}: {json.dumps(x)}", f"{key}: NaN", 1)
    for path in dict.fromkeys([first] + [("overshoot_bound",)] * ("overshoot_bound" in data)):
        x = get(data, path)
        # the same number in 4400 digits (past Python's 4300-digit default) and in 20000 or more (past both readers' limit)
        for n, family in ((4400, "huge digits"), (10000, "too many digits")):
            num, _, den = x.partition("/")
            y = (x + "0" * 2 * n) if "." in x else f"{num}{'0' * n}/{den or '1'}{'0' * n}"
            yield f"{where(path)} in {len(y)} characters", family, replaced(data, path, y)(), None
        yield f"{where(path)} → 1e999999", "huge exponent", replaced(data, path, "1e999999")(), None

def borderline_edits(data: dict, kind: str) -> Iterator[tuple[str, str, object]]:
    """Boxes and intervals narrowed towards what they enclose, and τ_a moved: where arb enclosures decide at the edge."""
    if kind == "hunting":
        cycle = data["cycle"]
        for axis, claim in (("sigma", "sigma"), ("tau", "slip_time")):
            c_lo, c_hi = (value(v) for v in cycle[claim])
            mid = (c_lo + c_hi) / 2
            b_lo, b_hi = (value(v) for v in data["box"][axis])
            for k in (1, 2, 3, 4, 6):
                half = (b_hi - b_lo) / 2 / 10**k
                yield (f"box.{axis} narrowed 10^{k}× around the enclosure", "Krawczyk box narrowed",
                       replaced(data, ("box", axis), [rational_text(mid - half), rational_text(mid + half)]))
            for k in (1, 2, 4):
                half = (b_hi - b_lo) / 2 * 10**k
                yield (f"box.{axis} widened 10^{k}×", "Krawczyk box widened",
                       replaced(data, ("box", axis), [rational_text(mid - half), rational_text(mid + half)]))
        t_lo = value(data["box"]["tau"][0])
        for f in ("1/100", "1/2", "9/10", "99/100", "9999/10000", "1"):
            yield f"box.monotone_from → {f}·τ_lo", "τ_a moved", replaced(data, ("box", "monotone_from"), rational_text(t_lo * Fraction(f)))
    if kind == "reset-contraction":
        lo, hi = (value(v) for v in data["slip"]["tau"])
        mid = (lo + hi) / 2
        for k in (1, 2, 4, 8):
            half = (hi - lo) / 2 / 10**k
            yield (f"slip.tau narrowed 10^{k}×", "slip interval narrowed",
                   replaced(data, ("slip", "tau"), [rational_text(mid - half), rational_text(mid + half)]))
        for k in (1, 3, 6):
            half = (hi - lo) / 2 * 10**k
            yield (f"slip.tau widened 10^{k}×", "slip interval widened",
                   replaced(data, ("slip", "tau"), [rational_text(mid - half), rational_text(mid + half)]))
        for f in ("1/100", "1/2", "9/10", "99/100", "9999/10000", "1"):
            yield f"slip.monotone_from → {f}·τ_lo", "τ_a moved", replaced(data, ("slip", "monotone_from"), rational_text(lo * Fraction(f)))


def all_edits(kind: str, path: Path, seed: int = 0) -> list[Edit]:
    """Every edit of one committed file, not yet made (:func:`made` makes it and decides its claim class).

    Each edit's ``family`` names the kind of edit and the member it touches (``nudge +1e-6 @ constants``):
    :func:`corpus` draws across families, so a sample of a few hundred holds every kind of edit.
    """
    return [copy.copy(edit) for edit in _listed_edits(kind, path, seed)]  # made() fills in the copy, not the list


@functools.cache
def _listed_edits(kind: str, path: Path, seed: int) -> tuple[Edit, ...]:
    """:func:`all_edits`, listed once per process: a sup-flow file's tens of thousands of edits take about half a
    second, and the tests list each file for the sample (:func:`corpus`) and again for its types (:func:`edit_types`)."""
    data = json.loads(path.read_text(encoding="utf-8"))
    rng = random.Random(f"{seed}:{path.name}:{kind}")
    source = path.relative_to(ROOT).as_posix()
    raw: list[tuple[str, str, object, str, str]] = []
    for generator in (numeric_edits(data), spelling_edits(data, rng), key_edits(data), string_edits(data),
                      interval_edits(data), piece_edits(data, kind)):
        raw += [(w, f, d, "", "") for w, f, d in generator]
    raw += [(w, f, d, "", "") for w, f, d in borderline_edits(data, kind)]
    raw += list(special_edits(data, kind))
    out = []
    for what, family, edited, claim, note in raw:
        member = edited.path[0] if isinstance(edited, Lazy) else ""
        out.append(Edit(kind, source, what, f"{family} @ {member}" if member else family, edited, claim, note, original=data))
    for what, family, edited, text in text_edits(data, path.read_text(encoding="utf-8")):
        out.append(Edit(kind, source, what, family, edited, "", "", text, original=data))
    return tuple(out)


def made(edit: Edit) -> Edit:
    """The edit made, with its claim class (:func:`claim_class`) unless it was known by construction."""
    edit.data = built(edit.data)
    if not edit.claim:
        edit.claim, edit.note = claim_class(edit.kind, edit.original, edit.data)
    return edit


# -- the truth of an edit, from what it claims -----------------------------------------------------------------------


def _combine(parts: list[tuple[str, str]]) -> tuple[str, str]:
    classes = {c for c, _ in parts}
    for c in ("false", "other"):
        if c in classes:
            return c, "; ".join(n for k, n in parts if k == c)
    if classes <= {"same"}:
        return "same", "the claim is unchanged: the committed file proves it"
    return "weaker", "; ".join(n for k, n in parts if k == "weaker")


def _assumption(g: dict[str, Fraction | None], hunting: bool = False) -> bool:
    """Assumption 1 and ``f_c > 0`` (``f_s > f_c`` for a hunting cycle): without them the claim is false."""
    kp, ki, kv, fc = (g.get(n) for n in ("k_p", "k_i", "k_v", "f_c"))
    if None in (kp, ki, kv, fc):
        return True  # not a number: the file claims nothing (it is malformed)
    ok = ki > 0 and kp > 0 and kv * kp > ki and fc > 0
    if hunting:
        fs = g.get("f_s")
        ok = ok and fs is not None and fs > fc
    return ok


def _numbers_of(obj: object) -> dict[str, Fraction | None]:
    return {k: value(v) for k, v in obj.items()} if isinstance(obj, dict) else {}


def _gains(old: dict, new: dict, kind: str) -> tuple[str, str]:
    hunting = kind == "hunting"
    a, b = _numbers_of(old.get("parameters")), _numbers_of(new.get("parameters"))
    if a == b:
        return "same", ""
    if None in b.values():
        return "weaker", "a gain that is not a number: nothing claimed"
    if not _assumption(b, hunting):
        return "false", "the gains leave Assumption 1, f_c > 0" + (" or f_s > f_c" if hunting else "")
    if set(a) == set(b) and all(a[n] == b[n] for n in a if n != "f_c"):
        if kind == "reset-contraction":  # x ↦ x/f_c: the radius is in units of f_c
            if b["f_c"] > a["f_c"]:
                return "weaker", "a larger f_c: the radius, in units of f_c, is smaller"
            if b["f_c"] >= a["f_c"] * (1 - ROUNDING):
                return "other", "f_c lowered within the radius' rounding"
            return "false", "f_c lowered: the radius, in units of f_c, grows beyond its rounding"
        if not hunting:  # κ does not depend on f_c > 0 (the model scales with f_c: x ↦ x/f_c)
            return "weaker", "f_c only, still > 0: the same claim (x ↦ x/f_c scales it away)"
    return "other", "other gains: a claim about another system"


def _kappa(old: dict, new: dict) -> tuple[str, str]:
    a, b = value(old.get("overshoot_bound")), value(new.get("overshoot_bound"))
    if b == a:
        return "same", ""
    if b is None:
        return "weaker", "no κ: nothing claimed"
    if b > a:
        return "weaker", "a larger κ"
    if b >= a - KAPPA_ROUNDING:
        return "other", "κ lowered within its 5-decimal rounding (the constants may still give it)"
    return "false", "κ below the committed value by more than its rounding"


def _interval(x: object) -> tuple[Fraction, Fraction] | None:
    if isinstance(x, list) and len(x) == 2:
        lo, hi = value(x[0]), value(x[1])
        if lo is not None and hi is not None:
            return lo, hi
    return None


def _box_claim(old: dict, new: dict) -> list[tuple[str, str]]:
    out = []
    for axis in ("k_p", "k_i", "k_v", "f_c"):
        a = _interval((old.get("box") or {}).get(axis))
        b = _interval((new.get("box") or {}).get(axis)) if isinstance(new.get("box"), dict) else None
        if b == a:
            continue
        if b is None or b[0] > b[1]:
            out.append(("weaker", f"box.{axis} empty or unreadable: nothing claimed"))
        elif axis == "f_c":
            out.append(("false", "f_c ≤ 0 in the box") if b[0] <= 0 else
                       ("weaker", "f_c enters only through f_c > 0 (the model scales with f_c: x ↦ x/f_c): κ holds for every f_c > 0"))
        elif a[0] <= b[0] and b[1] <= a[1]:
            out.append(("weaker", f"a smaller box in {axis}"))
        else:
            out.append(("false", f"box.{axis} enlarged beyond the pieces' cover"))
    if "physical" in old:
        if "physical" not in new:
            out.append(("weaker", "no physical box claimed"))
        elif new["physical"] != old["physical"]:
            for name in sorted(old["physical"]):
                a = _interval(old["physical"][name])
                b = _interval(new["physical"].get(name)) if isinstance(new["physical"], dict) else None
                if b == a:
                    continue
                if b is None or b[0] > b[1]:
                    out.append(("weaker", f"physical.{name} empty or unreadable"))
                elif (name in ("m", "k_p_bar", "k_i_bar", "f_c_bar") and b[0] <= 0) or (name == "alpha_v" and b[0] < 0):
                    out.append(("false", f"physical.{name} reaches where the model has no meaning"))
                elif a[0] <= b[0] and b[1] <= a[1]:
                    out.append(("weaker", f"a smaller physical box in {name}"))
                else:
                    out.append(("other", f"physical.{name} enlarged (true iff its image stays in the box)"))
    return out


def _physical_point(new: dict) -> tuple[str, str]:
    ph, g = _numbers_of(new.get("physical")), _numbers_of(new.get("parameters"))
    if None in ph.values() or None in g.values() or len(ph) != 6:
        return "weaker", "physical unreadable: nothing claimed of it"
    m = ph["m"]
    if not m or m <= 0 or ph["alpha_v"] < 0:
        return "false", "physical parameters with m ≤ 0 or alpha_v < 0"
    image = {"k_p": ph["k_p_bar"] / m, "k_i": ph["k_i_bar"] / m, "k_v": (ph["k_d_bar"] + ph["alpha_v"]) / m, "f_c": ph["f_c_bar"] / m}
    if any(g.get(n) != image[n] for n in image):
        return "false", "the physical parameters do not normalise to the gains"
    return "other", "physical parameters that normalise to the gains"


def _cycle(old: dict, new: dict) -> list[tuple[str, str]]:
    out = []
    a, b = old.get("cycle"), new.get("cycle")
    if a == b:
        return out
    if not isinstance(b, dict):
        return [("weaker", "no cycle claimed")]
    for name in ("sigma", "slip_time", "stick_time", "period", "multiplier"):
        ca, cb = _interval(a.get(name)), _interval(b.get(name))
        if ca == cb:
            continue
        if cb is None:
            out.append(("weaker", f"cycle.{name} unreadable"))
        elif cb[0] > cb[1] or cb[1] < ca[0] or cb[0] > ca[1]:
            out.append(("false", f"cycle.{name} misses the committed enclosure of the number"))
        elif cb[0] <= ca[0] and ca[1] <= cb[1]:
            out.append(("weaker", f"a wider cycle.{name}"))
        else:
            out.append(("other", f"a narrower cycle.{name}, still meeting the committed enclosure"))
    if a.get("stable") != b.get("stable"):
        sb = b.get("stable")
        out.append(("weaker", "stable: null claims nothing") if sb is None else
                   ("false", "stable contradicts the committed file") if isinstance(sb, bool) else ("weaker", "stable unreadable"))
    return out


def _hunting_box(old: dict, new: dict) -> list[tuple[str, str]]:
    out = []
    cycle = old.get("cycle") or {}
    for axis, claim in (("sigma", "sigma"), ("tau", "slip_time")):
        a = _interval(old["box"][axis])
        b = _interval(new["box"].get(axis)) if isinstance(new.get("box"), dict) else None
        if a == b:
            continue
        c = _interval(cycle.get(claim))
        if b is None:
            out.append(("weaker", f"box.{axis} unreadable: nothing claimed"))
        elif b[0] > b[1] or (c is not None and (b[1] < c[0] or b[0] > c[1])):
            out.append(("false", f"box.{axis} holds no zero: it misses cycle.{claim}, which holds it"))
        else:
            out.append(("other", f"another box.{axis} (a zero in it, unique there: the Krawczyk test decides)"))
    return out


def _reset(old: dict, new: dict) -> list[tuple[str, str]]:
    out = []

    def num(d: object, *path: str) -> Fraction | None:
        for key in path:
            if not isinstance(d, dict):
                return None
            d = d.get(key)
        return value(d)

    # (path, stronger when …): ρ, the times and tol are upper bounds (lower is stronger), the radius a lower one
    for path, lower_is_stronger in ((("rho",), True), (("cycle_time",), True), (("settling", "time"), True),
                                    (("radius",), False)):
        a, b = num(old, *path), num(new, *path)
        if a == b:
            continue
        name = ".".join(path)
        if b is None:
            out.append(("weaker", f"{name} unreadable"))
        elif (b > a) == lower_is_stronger:
            out.append(("weaker", f"a weaker {name}"))
        elif abs(b - a) <= ROUNDING * abs(a):
            out.append(("other", f"{name} moved within its rounding"))
        else:
            out.append(("false", f"{name} beyond the committed value by more than its rounding"))
    a, b = num(old, "settling", "tol"), num(new, "settling", "tol")
    if a != b:
        floor = num(old, "rho") ** old["settling"]["cycles"]  # the committed ρ^cycles ≥ |E11(τ*)|^cycles
        out.append(("weaker", "unreadable tol") if b is None else ("weaker", "a larger tol") if b > a else
                   ("false", "tol below the committed ρ^cycles (beyond its rounding): |σ| is that large after the settling time")
                   if b < floor * (1 - Fraction(1, 10**4)) else ("other", "a smaller tol, above ρ^cycles"))
    # the claim holds for every dwell ≤ max(dwell, τ_lo)
    a, b = num(old, "dwell"), num(new, "dwell")
    tau_lo = _interval(old["slip"]["tau"])[0]
    if a != b:
        out.append(("weaker", "a shorter dwell") if b is None or b < a else
                   ("same", "") if max(b, tau_lo) == max(a, tau_lo) else ("other", "a longer dwell"))
    if old.get("overshoot") != new.get("overshoot"):
        b = new.get("overshoot")
        out.append(("false", "overshoot contradicts the committed file") if isinstance(b, bool) else ("weaker", "overshoot unreadable"))
    tau = _interval(new["slip"].get("tau")) if isinstance(new.get("slip"), dict) else None
    if tau != _interval(old["slip"]["tau"]):
        out.append(("weaker", "slip.tau unreadable") if tau is None else
                   ("other", "another slip interval (its τ_lo bounds the dwells the claim covers)"))
    return out


def claim_class(kind: str, old: dict, new: object) -> tuple[str, str]:
    """``(class, why)`` of an edited file against the committed one, from what each claims (module docstring)."""
    if not isinstance(new, dict):
        return "weaker", "not a certificate: nothing claimed"
    parts: list[tuple[str, str]] = []
    hunting = kind == "hunting"
    parts.append(_gains(old, new, kind))
    if kind in ("paper", "box", "quadratic", "sup-flow/v1", "sup-flow/v2"):
        parts.append(_kappa(old, new))
    if kind == "paper" and "physical" in old:
        parts.append(("weaker", "no physical parameters claimed") if "physical" not in new else
                     ("same", "") if new["physical"] == old["physical"] and new.get("parameters") == old.get("parameters") else
                     _physical_point(new))
    if kind == "paper" and "physical" not in old and "physical" in new:
        parts.append(_physical_point(new))
    if kind == "box":
        parts += _box_claim(old, new)
    if hunting:
        parts += _hunting_box(old, new) + _cycle(old, new)
        if new.get("verdict") != old.get("verdict") or new.get("claim") != old.get("claim"):
            parts.append(("weaker", "not the claim 'proved symmetric hunting cycle': nothing claimed"))
    if kind == "reset-contraction":
        parts += _reset(old, new)
    label = lambda d: (d.get("provenance") or {}).get("label") if isinstance(d.get("provenance"), dict) else None  # noqa: E731
    # the label is free text but for the paper's template, where a Table I label claims Table I's gains
    if kind == "paper" and label(old) != label(new) and re.fullmatch(r"Table I, case \(([ab])\)", label(new) or ""):
        parts.append(("other", "a label naming Table I's gains (the main verifier's label rule)"))
    return _combine(parts)


# -- deciding an edit with both verifiers ----------------------------------------------------------------------------


@dataclass
class Outcome:
    edit: Edit
    main: bool
    independent: bool
    main_why: str = ""
    independent_why: str = ""
    rule: str | None = None  # the main verifier's format rule that refuses it (None: a premise, or it proves it)
    crash: str = ""
    verify_status: int | None = None  # ``symbolic-friction verify`` on the file (run where the verifiers disagree)
    verify_text: str = ""

    @property
    def agree(self) -> bool:
        return self.main == self.independent


def decide(edit: Edit, directory: Path, index: int) -> Outcome:
    """Both verifiers on the edited file, in this process (as ``verify`` runs them)."""
    from symbolic_friction._certify.templates import verify_template_file
    from symbolic_friction._certify.verify import format_rules
    from symbolic_friction._infra.errors import CertificateFormatError, InputFileError
    from symbolic_friction.independent import Malformed, check_file

    path = directory / f"edit{index}.json"
    path.write_text(edit.file_text(), encoding="utf-8")
    out = Outcome(edit, False, False)
    try:
        _, report = verify_template_file(path)
        out.main = bool(report.proved)
        if not out.main:
            failing = [c.name for c in report.checks if not c.holds]
            out.main_why = "; ".join(failing) or "the file's verdict"
            rules = format_rules(report)
            out.rule = ", ".join(rules) if rules else None
    except (CertificateFormatError, InputFileError) as exc:
        out.main_why = f"malformed: {exc}"
        out.rule = str(exc).replace(str(path), "FILE")
    except Exception as exc:  # noqa: BLE001 - a crash is a finding
        out.crash += f"main: {type(exc).__name__}: {exc}; "
    try:
        verdict = check_file(str(path))
        out.independent = verdict.proved
        out.independent_why = "; ".join(verdict.failing)
    except Malformed as exc:
        out.independent_why = f"malformed: {exc}"
    except Exception as exc:  # noqa: BLE001
        out.crash += f"independent: {type(exc).__name__}: {exc}"
    return out


def verify_output(edit: Edit, directory: Path) -> tuple[int, str]:
    """``symbolic-friction verify`` on the edited file, in this process: ``(exit status, stdout + stderr)``."""
    from symbolic_friction._cli.main import main

    path = directory / "shown.json"
    path.write_text(edit.file_text(), encoding="utf-8")
    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = main(["verify", str(path)])
    except Exception as exc:  # noqa: BLE001 - a traceback from verify is a finding, not the end of the sweep
        return -1, f"verify crashed: {type(exc).__name__}: {exc}"
    return status, out.getvalue() + err.getvalue()


def corpus(per_kind: int | None, seed: int = 0, kinds: tuple[str, ...] = KINDS,
           caps: dict[str, int] | None = None) -> dict[str, list[Edit]]:
    """The edits of every committed file of ``kinds``, made, ``per_kind`` per kind (None: all of them).

    ``caps``: at most so many edits of the files named (their sources: see :data:`DEFAULT_CAPS`).

    A seeded draw that takes one edit of each type in turn (``nudge +1e-6``, ``key removed``, …; over every file of
    the kind), and within a type the members it touches in turn (``constants``, ``overshoot_bound``, ``pieces``, …),
    so that the thousands of nudges of a sup-flow file's forms do not crowd out its κ, gains or keys, and a
    sample of a hundred holds every type; an edit that gives a file already drawn (or the committed one) is skipped.
    """
    by_kind: dict[str, list[Edit]] = defaultdict(list)
    for kind, path in sources():
        if kind in kinds:
            by_kind[kind] += _listed_edits(kind, path, seed)  # not copied: a drawn edit is copied before made()
    out = {}
    for kind, edits in by_kind.items():
        rng = random.Random(f"{seed}:{kind}")
        # edit type → member → edits: each round takes one edit of every type, its members in turn
        types: dict[str, dict[str, list[Edit]]] = defaultdict(lambda: defaultdict(list))
        for edit in edits:
            kind_of_edit, _, member = edit.family.partition(" @ ")
            types[kind_of_edit][member].append(edit)
        pools: dict[str, list[list[Edit]]] = {}
        for name, members in types.items():
            pools[name] = [members[m] for m in sorted(members)]
            rng.shuffle(pools[name])
            for group in pools[name]:
                rng.shuffle(group)
        order = sorted(pools)
        rng.shuffle(order)
        seen = {json.dumps(o, sort_keys=True) for o in {id(e.original): e.original for e in edits}.values()}
        chosen: list[Edit] = []
        taken: Counter = Counter()
        while order and (per_kind is None or len(chosen) < per_kind):
            for name in list(order):
                if per_kind is not None and len(chosen) >= per_kind:
                    break
                groups = pools[name]
                while True:  # this type's next edit that is neither capped nor a file already drawn
                    groups[:] = [g for g in groups if g]
                    if not groups:
                        order.remove(name)
                        break
                    groups.append(groups.pop(0))  # the next member's turn comes next
                    edit = groups[-1].pop()
                    if caps is not None and taken[edit.source] >= caps.get(edit.source, per_kind or len(edits)):
                        continue
                    edit = made(copy.copy(edit))
                    key = edit.text if edit.text is not None else json.dumps(edit.data, sort_keys=True)
                    if key not in seen:
                        seen.add(key)
                        taken[edit.source] += 1
                        chosen.append(edit)
                        break
        out[kind] = chosen
    return out


@dataclass
class Tally:
    edits: int = 0
    both_refuse: int = 0
    both_accept: int = 0
    disagree: int = 0
    false: int = 0  # edits whose claim is stronger than the committed file proves (every one must be refused by both)
    accepted: Counter = field(default_factory=Counter)  # claim class of the edits both accept
    rules: Counter = field(default_factory=Counter)  # format rules behind the disagreements


FORMAT_MESSAGE = re.compile(
    r"unknown key|missing key|must be a string|must be an exact rational|plain decimal|does not match the box certificate"
    r"|schema|template|JSON|must be a list|must have exactly the keys|must be an integer|must be true|must be 'proved'"
    r"|must be a decimal|characters|zero denominator|unknown claim|provenance|box must have the keys")
"""Malformed-file messages of the main verifier that are rules of the format, not premises in disguise."""


def problems(outcomes: list[Outcome]) -> list[str]:
    """What the corpus shows wrong (empty: nothing): crashes, accepted false claims, unexplained disagreements."""
    out = []
    for o in outcomes:
        e = o.edit
        tag = f"[{e.kind}] {e.source}: {e.what} ({e.claim}: {e.note})"
        if o.crash or o.verify_status == -1:
            out.append(f"{tag}: crashed: {o.crash or o.verify_text}")
        if e.claim == "false" and (o.main or o.independent):
            out.append(f"{tag}: a false claim accepted (main {o.main}, independent {o.independent})")
        if not o.agree:
            if o.main:
                out.append(f"{tag}: the main verifier proves it; the independent checker refuses: {o.independent_why}")
            elif o.rule is None or (o.main_why.startswith("malformed") and not FORMAT_MESSAGE.search(o.rule)):
                out.append(f"{tag}: the independent checker proves it; the main verifier refuses for a premise: {o.main_why}")
            if o.verify_status is not None:
                said = [line for line in o.verify_text.splitlines() if line.startswith("DISAGREE")]
                if o.verify_status == 0 or len(said) != 1 or (not o.main and "format rule" not in said[0]):
                    out.append(f"{tag}: verify (exit {o.verify_status}) does not say which format rule: {o.verify_text[:300]!r}")
    return out


def run(per_kind: int | None, seed: int = 0, kinds: tuple[str, ...] = KINDS, *, show: bool = True,
        verbose: bool = False, caps: dict[str, int] | None = None, why: bool = False) -> tuple[dict[str, Tally], list[Outcome], list[str]]:
    """Decide the corpus; print the counts per kind (``show``); return them, the outcomes and the problems."""
    tallies: dict[str, Tally] = {}
    outcomes: list[Outcome] = []
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="tampered-") as tmp:
        directory = Path(tmp)
        for kind, edits in corpus(per_kind, seed, kinds, caps).items():
            t0, tally = time.perf_counter(), Tally()
            for i, edit in enumerate(edits):
                o = decide(edit, directory, i)
                outcomes.append(o)
                tally.edits += 1
                tally.false += edit.claim == "false"
                if o.agree and o.main:
                    tally.both_accept += 1
                    tally.accepted[edit.claim] += 1
                elif o.agree:
                    tally.both_refuse += 1
                else:
                    tally.disagree += 1
                    tally.rules[_rule_name(o.rule)] += 1
                if verbose:
                    print(f"  {'ok ' if o.agree else 'DIS'} M{int(o.main)} I{int(o.independent)} {edit.claim:6} {edit.source}: {edit.what}")
            tallies[kind] = tally
            if show:
                print(f"{kind:18} {tally.edits:4} edits ({tally.false} false): {tally.both_refuse:4} refused by both, "
                      f"{tally.both_accept:4} accepted by both "
                      f"({', '.join(f'{n} {c}' for c, n in sorted(tally.accepted.items()))}), {tally.disagree:3} disagreements"
                      f"{' (' + '; '.join(f'{n}× {r}' for r, n in tally.rules.most_common()) + ')' if tally.rules else ''}"
                      f"  [{time.perf_counter() - t0:.1f} s]", flush=True)
                if why:  # why each edit both accept is still true: its claim class and the reason, counted
                    reasons = Counter(f"{o.edit.claim}: {o.edit.note}" for o in outcomes[-len(edits):] if o.agree and o.main)
                    for reason, n in sorted(reasons.items()):
                        print(f"    accepted by both, {n:3}× {reason}")
    with tempfile.TemporaryDirectory(prefix="tampered-verify-") as tmp:
        for o in outcomes:
            if not o.agree or o.crash:
                o.verify_status, o.verify_text = verify_output(o.edit, Path(tmp))
    found = problems(outcomes)
    if show:
        print(f"{len(outcomes)} edits in {time.perf_counter() - start:.1f} s; {len(found)} problem(s)")
        for line in found:
            print("PROBLEM", line)
    return tallies, outcomes, found


RULE_NAMES = (
    (r"c = 2\(", "c's defining equation"), (r"^label ", "a Table I label"),
    (r"provenance\.obligations", "provenance.obligations"),
    (r"Additional properties|required property|unknown key|missing key|must have (exactly )?the keys", "key sets"),
    (r"plain decimal|^overshoot_bound", "κ a plain decimal"),
    (r"exact rational|must be a string holding|does not match '\^\[|is not of type 'string'", "exact rational strings"),
    (r"was expected|schema|template", "schema and template ids"), (r"provenance", "provenance fields"),
)
"""Short names of the main verifier's format rules (the counts of the disagreements group by them)."""


@functools.lru_cache(maxsize=None)
def default_run(kind: str) -> tuple[Tally, list[Outcome], list[str]]:
    """The default sample of one kind decided (once per process): ``(tally, outcomes, problems)``."""
    tallies, outcomes, found = run(DEFAULT_PER_KIND, 0, (kind,), show=False, caps=DEFAULT_CAPS)
    return tallies[kind], outcomes, found


def edit_types(kind: str) -> set[str]:
    """Every type of edit (``nudge +1e-6``, ``key removed``, …) the generator makes of the kind's files."""
    return {e.family.partition(" @ ")[0] for k, path in sources() if k == kind for e in _listed_edits(k, path, 0)}


def _rule_name(rule: str | None) -> str:
    """The short name of a disagreement's format rule (:data:`RULE_NAMES`; else the message's start)."""
    if rule is None:
        return "no format rule"
    text = re.sub(r"^FILE: |does not match the box certificate schema at ", "", rule)
    return next((name for pattern, name in RULE_NAMES if re.search(pattern, text)), text[:60])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m tests.independent.tampered", description=__doc__.split("\n\n")[0])
    parser.add_argument("--all", action="store_true", help=f"the full sweep: {FULL_PER_KIND} edits per kind")
    parser.add_argument("--every", action="store_true", help="every generated edit (slow for sup-flow)")
    parser.add_argument("--per-kind", type=int, default=None, help=f"edits per kind (default {DEFAULT_PER_KIND})")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--kind", action="append", choices=KINDS, help="only these kinds")
    parser.add_argument("--verbose", action="store_true", help="one line per edit")
    parser.add_argument("--why", action="store_true", help="why each edit both verifiers accept is still true, counted")
    args = parser.parse_args(argv)
    per_kind = None if args.every else args.per_kind or (FULL_PER_KIND if args.all else DEFAULT_PER_KIND)
    caps = None if args.all or args.every else DEFAULT_CAPS
    _, _, found = run(per_kind, args.seed, tuple(args.kind or KINDS), verbose=args.verbose, caps=caps, why=args.why)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
