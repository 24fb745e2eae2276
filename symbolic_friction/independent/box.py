"""The box certificate (``lyapunov-box/v1``): Proposition 1's bound for every gain set of a box.

A file holds a ``box`` of gains (``k_p, k_i, k_v, f_c``, each ``[lo, hi]``), optionally the ``physical``
box it normalises from (paper §II-A), a global ``overshoot_bound`` κ, and ``pieces``: sub-boxes in
``k_p, k_i, k_v``, each with constants ``k1 … k4, c1, c2, c1_hat, c2_hat`` of the paper's point certificate.

Why four corners decide a piece.  With the constants fixed, every premise of :func:`.paper.premises`
depends on the gains only through ``a = k_v/k_i``, ``k_p`` and ``f_c``, and monotonically:

* ``P(a, k_p) − c1·I = P(a₀, k_p₀) − c1·I + diag(a − a₀, 0, k_p − k_p₀)``: positive semidefinite for every
  ``a ≥ a₀, k_p ≥ k_p₀`` once it is at ``(a₀, k_p₀)``; ``c2·I − P`` likewise at ``(a₁, k_p₁)``;
* ``k_v k_p > k_i ⟺ a·k_p > 1`` (``k_i > 0``); ``k3 > k1/a`` and ``k4 > k3/a`` (``k1, k3 > 0``) are
  least at the least ``a``; ``k4 > k_p·k2`` (``k2 > 0``) at the largest ``k_p``; ``f_c`` enters ``f_c > 0`` only;
* the rate ``c = 2(k_v k_p − k_i)`` is taken at each corner, so Lemma 2's premises on ``c`` are Assumption 1;
* the rest are the constants' own.

So the premises hold on the piece when they hold at ``f_c = f_c,lo`` and the four corners
``{k_p,lo, k_p,hi} × {(k_i,hi, k_v,lo), (k_i,lo, k_v,hi)}``: these hold ``k_i,lo > 0`` and, through
``k_v,lo·k_p,lo > k_i,hi > 0``, ``k_v,lo > 0``, so ``a`` ranges over ``[k_v,lo/k_i,hi, k_v,hi/k_i,lo]``, whose
ends they realise with both ends of ``k_p``.
"""

from __future__ import annotations

from fractions import Fraction

from ._core import Malformed, Verdict, q, shown
from .paper import CONSTANTS, GAINS, PHYSICAL, numbers, premises

AXES = ("k_p", "k_i", "k_v")
MAX_PIECES = 4096
"""Most pieces a file may have (the format's limit; the cover check compares every pair)."""
Interval = tuple[Fraction, Fraction]


def intervals(obj: object, names: tuple[str, ...], where: str) -> dict[str, Interval]:
    """The members ``names`` of ``obj``, each ``[lo, hi]`` with ``lo ≤ hi`` (``Malformed`` otherwise)."""
    if not isinstance(obj, dict) or any(n not in obj for n in names):
        raise Malformed(f"{where} must be an object with the members {', '.join(names)}")
    out = {}
    for n in names:
        pair = obj[n]
        if not (isinstance(pair, list) and len(pair) == 2) or not q(pair[0]) <= q(pair[1]):
            raise Malformed(f"{where}.{n} must be [lo, hi] with lo ≤ hi")
        out[n] = (q(pair[0]), q(pair[1]))
    return out


def corners(piece: dict[str, Interval], f_c: Fraction) -> list[dict[str, Fraction]]:
    """The four corners that decide a piece (module docstring), at ``f_c = f_c,lo``."""
    (kp_lo, kp_hi), (ki_lo, ki_hi), (kv_lo, kv_hi) = (piece[n] for n in AXES)
    return [{"k_p": kp, "k_i": ki, "k_v": kv, "f_c": f_c} for kp in (kp_lo, kp_hi) for ki, kv in ((ki_hi, kv_lo), (ki_lo, kv_hi))]


def _volume(b: dict[str, Interval], axes: list[str]) -> Fraction:
    out = Fraction(1)
    for n in axes:
        out *= b[n][1] - b[n][0]
    return out


def cover(box: dict[str, Interval], parts: list[dict[str, Interval]]) -> list[tuple[str, bool]]:
    """The pieces cover the box: inside it, interiors disjoint, volumes summing to the box's (exact).

    Why that suffices: the part of the box no (closed) piece holds is open in the box; were it not empty it
    would hold a small box of positive volume, and the pieces, disjoint but for their faces, would then
    fill less than the box's volume.  Volumes are taken along the axes where the box is not flat (a piece
    inside the box is flat there too).
    """
    axes = [n for n in AXES if box[n][0] < box[n][1]]
    inside = all(box[n][0] <= p[n][0] and p[n][1] <= box[n][1] for p in parts for n in AXES)
    disjoint = all(any(max(a[n][0], b[n][0]) >= min(a[n][1], b[n][1]) for n in axes)
                   for i, a in enumerate(parts) for b in parts[:i])
    total = sum((_volume(p, axes) for p in parts), Fraction(0))
    return [("every piece lies in the box", inside), ("the pieces' interiors are disjoint", disjoint),
            ("the pieces' volumes sum to the box's", total == _volume(box, axes))]


def physical_image(ph: dict[str, Interval]) -> dict[str, Interval] | None:
    """The normalised box enclosing a physical box (§II-A), or None where a numerator or ``m`` can be ``≤ 0``.

    ``k_p = k̄_p/m`` with ``k̄_p, m > 0`` grows with ``k̄_p`` and falls with ``m``, so it ranges over
    ``[k̄_p,lo/m_hi, k̄_p,hi/m_lo]``; likewise ``k_i``, ``f_c`` and ``k_v = (k̄_d + α_v)/m``.
    """
    (m_lo, m_hi), (a_lo, a_hi), (d_lo, d_hi) = ph["m"], ph["alpha_v"], ph["k_d_bar"]
    numerators = {"k_p": ph["k_p_bar"], "k_i": ph["k_i_bar"], "k_v": (d_lo + a_lo, d_hi + a_hi), "f_c": ph["f_c_bar"]}
    if not (m_lo > 0 and a_lo >= 0 and all(lo > 0 for lo, _ in numerators.values())):
        return None
    return {n: (lo / m_hi, hi / m_lo) for n, (lo, hi) in numerators.items()}


def check(data: dict) -> Verdict:
    """Decide a ``lyapunov-box/v1`` file: the physical box, the cover, and every piece at its four corners."""
    box = intervals(data.get("box"), GAINS, "box")
    kappa = q(data.get("overshoot_bound"))
    pieces = data.get("pieces")
    if not isinstance(pieces, list) or len(pieces) > MAX_PIECES or not all(isinstance(p, dict) for p in pieces):
        raise Malformed(f"pieces must be a list of at most {MAX_PIECES} objects")
    parts = [intervals(p, AXES, f"pieces[{i}]") for i, p in enumerate(pieces)]
    constants = [numbers(p.get("constants"), CONSTANTS, f"pieces[{i}].constants") for i, p in enumerate(pieces)]
    verdict = Verdict("lyapunov-box/v1")
    if "physical" in data:  # paper §II-A: the physical box's image lies in the box, so the claim covers it
        image = physical_image(intervals(data["physical"], PHYSICAL, "physical"))
        verdict.add("the physical box normalises (m > 0, alpha_v ≥ 0, numerators > 0)", image is not None)
        for n in GAINS:
            verdict.add(f"{n} of the physical box lies in the box",
                        image is not None and box[n][0] <= image[n][0] and image[n][1] <= box[n][1])
    for name, holds in cover(box, parts):
        verdict.add(name, holds)
    for i, (part, k) in enumerate(zip(parts, constants)):
        # Lemmas 2–3 and Proposition 1 (paper.premises) at the four corners, which decide the piece
        failed = []
        for g in corners(part, box["f_c"][0]):
            c = 2 * (g["k_v"] * g["k_p"] - g["k_i"])  # Lemma 2's rate at this corner
            failed += [f"({shown(g['k_p'])}, {shown(g['k_i'])}, {shown(g['k_v'])}): {name}"  # shown: any length
                       for name, holds in premises(g, k, c, kappa) if not holds]
        verdict.add(f"piece {i + 1}: every premise at its 4 corners", not failed, "; ".join(failed[:5]))
    return verdict
