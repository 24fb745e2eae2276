"""The sup-flow template (``sup-flow/v1``, ``sup-flow/v2``): Proposition 1's bound through ``V_∞`` (beyond the paper).

``V_∞(x) = min_{f ∈ f_c SGN(v)} g(x − f e₂)``, ``g(w) = sup_{t≥0} |e^{At}w|²``, never increases along solutions and is
at most ``c₂|x|²_𝒜`` on ``R``; on ``R̂`` it is below ``U = max_i U_i``, forms ``yᵀK_iy`` in ``y = (|σ|, |dz φ|, |v|)``,
one per time piece ``I_i``, each nonincreasing on ``R̂`` (the quadratic template's rate and band forms) and above
``|e^{At}w|²`` where a solution leaves ``R̂`` at a ``t ∈ I_i``.  Version 2 (docs/design/sup_flow_v2.md) has a form per
sign of ``σv`` (§ c) and lets the friction excess ``f > ℓᵀy`` pay in the rate (§ d).  The main verifier:
``_certify/sup_flow.py``, ``sup_flow_v2.py``, ``sup_flow_enclosure.py``, ``flow_bound.py``; the forms (written anew,
the model's names in brackets): ``_model/quadratic.py``, ``_model/sup_flow.py``.

Premises on the flow are decided in arb balls: ``e^{At}`` for ``t ∈ [a, b]`` lies in ``e^{Aa}·exp(A·[0, b − a])`` (arb
encloses the value at every point of an input ball), undecided parts are halved within budgets, and past ``T`` (the
last piece's start) the tail Gram ``(1/p)e^{AT}ᵀPe^{AT}`` bounds ``e^{At}ᵀe^{At}`` (``P ⪰ pI``, ``AᵀP + PA ⪯ 0``).
Undecided is not proved.  Premise names are the main verifier's; its format rules (key sets, provenance) are not checked.
"""

from __future__ import annotations

from fractions import Fraction

import flint

from ._core import Malformed, Verdict, _ints, _kept, ball, copositive, psd, q, shown

PRECISION = 128  # bits of the arb balls
MAX_PARTS = 2048  # parts one flow premise may be cut into (the main verifier's limits, as the next)
MAX_TOTAL_PARTS = 12_288  # parts all flow premises of one file may test together
MAX_PIECES = 256  # pieces a file may hold
MAX_DEPTH = 64  # times a part may be halved
EXPONENT_LIMIT = 4096  # a ball end beyond 2^±EXPONENT_LIMIT is not turned into a Fraction (it decides nothing)
TAIL = ("tail_p11", "tail_p12", "tail_p13", "tail_p22", "tail_p23", "tail_p33")
ENTRIES = ("11", "12", "13", "22", "23", "33")
ZERO, ONE = Fraction(0), Fraction(1)
NOT_EVALUATED = "not evaluated (an earlier premise fails)"
Matrix = list[list[Fraction]]


def _numbers(obj: object, names: tuple[str, ...], where: str) -> dict[str, Fraction]:
    if not isinstance(obj, dict) or any(n not in obj for n in names):
        raise Malformed(f"{where} must be an object with the members {', '.join(names)}")
    return {n: q(obj[n]) for n in names}


def _sym(e: dict[str, Fraction]) -> Matrix:
    """The symmetric 3×3 matrix of the entries ``"11" … "33"`` (a missing one is 0)."""
    return [[e.get(f"{min(i, j)}{max(i, j)}", ZERO) for j in (1, 2, 3)] for i in (1, 2, 3)]


def _mul(x: Matrix, y: Matrix) -> Matrix:
    """``xy``; the zero products (``B_s`` and ``A`` are mostly zeros) are left out of the sums."""
    return [[sum((x[i][k] * y[k][j] for k in range(len(y)) if x[i][k] and y[k][j]), 0) for j in range(len(y[0]))]
            for i in range(len(x))]


def _minus(x: Matrix, y: Matrix) -> Matrix:
    return [[a - b for a, b in zip(rx, ry)] for rx, ry in zip(x, y)]


def _eye(c: Fraction) -> Matrix:
    return [[c if i == j else ZERO for j in range(3)] for i in range(3)]


def _q(x):
    """A rational (``Fraction`` or ``fmpq``), or a matrix (a list of rows) of them, as ``fmpq``."""
    if isinstance(x, list):
        return [[flint.fmpq(v.numerator, v.denominator) for v in row] for row in x]
    return flint.fmpq(x.numerator, x.denominator)


def _arb(x: Matrix):
    return flint.arb_mat([[ball(v) for v in row] for row in x])


def system(kp: Fraction, ki: Fraction, kv: Fraction) -> Matrix:
    """``A`` of eq. (xDot): ``σ̇ = −k_i v``, ``φ̇ = σ − k_p v``, ``v̇ = φ − k_v v`` (the friction shifts ``φ``)."""
    return [[ZERO, ZERO, -ki], [ONE, ZERO, -kp], [ZERO, ONE, -kv]]


def slip(kp: Fraction, ki: Fraction, kv: Fraction, s: int) -> Matrix:
    """``B_s``: ``ẏ = B_s y − (0, 0, f)`` on ``R̂ ∩ {v > 0}`` outside the band, ``s = sign σ`` [slip_rate_entries]."""
    return [[ZERO, ZERO, -ki * s], [Fraction(-s), ZERO, kp], [ZERO, -ONE, -kv]]


def rate(k: Matrix, b: Matrix, ell: tuple[Fraction, ...]) -> Matrix:
    """``−(KB + BᵀK) + Ke₃ℓᵀ + ℓe₃ᵀK``: ``U̇ = −yᵀ(−KB − BᵀK)y − 2(Ky)₃f ≤ −yᵀ(this)y`` where ``f > ℓᵀy``,
    ``(Ky)₃ ≥ 0`` (design § d) [drag_rate_entries; ``ℓ = 0``: u_rate_entries, the quadratic template's]."""
    kb = _mul(k, b)
    return [[-kb[i][j] - kb[j][i] + k[i][2] * ell[j] + ell[i] * k[j][2] for j in range(3)] for i in range(3)]


def band(ki: Fraction, kv: Fraction, k: Matrix, s: int, ell: tuple[Fraction, ...]) -> Matrix:
    """The rate form in ``(|σ|, v)`` inside the band ``|φ| ≤ f_c`` (``y₂ = 0``, ``ẏ₁ = −k_i s v``,
    ``v̇ = −k_v v − f``) plus the drag block ``[[2K₁₃ℓ₁, K₁₃ℓ₃ + K₃₃ℓ₁], [·, 2K₃₃ℓ₃]]`` [drag_band_entries]."""
    off = ki * s * k[0][0] + kv * k[0][2] + k[0][2] * ell[2] + k[2][2] * ell[0]
    return [[2 * k[0][2] * ell[0], off], [off, 2 * ki * s * k[0][2] + 2 * kv * k[2][2] + 2 * k[2][2] * ell[2]]]


def drag_map(s: int, ell: tuple[Fraction, ...]) -> Matrix:
    """``D_ℓ``: ``x − f_c e₂ = (sy₁, −(y₂ + f), y₃) = D_ℓy`` where the friction excess ``f = ℓᵀy`` (design § d)."""
    return [[Fraction(s), ZERO, ZERO], [-ell[0], -ONE - ell[1], -ell[2]], [ZERO, ZERO, ONE]]


def exit_forms(k: Matrix, s: int, ell: tuple[Fraction, ...] | None) -> list[tuple[Matrix, Matrix]]:
    """``(K_e, D)`` per exit of ``R̂ ∩ {v > 0}``: there ``U − |e^{At}w|² = zᵀ(K_e − DᵀGD)z``, ``G = e^{At}ᵀe^{At}``
    [exit_forms, pullback_gap]: at ``v = 0`` ``w = (sy₁, −y₂, 0)``, at ``φ = f_c`` ``w = (sy₁, 0, y₃)`` and, with
    ``ℓ``, at ``f = ℓᵀy`` ``w = D_ℓy``.  ``v < 0`` is the mirror image (``g`` is even)."""
    s_ = Fraction(s)
    out = [([[k[0][0], k[0][1]], [k[1][0], k[1][1]]], [[s_, ZERO], [ZERO, -ONE], [ZERO, ZERO]]),
           ([[k[0][0], k[0][2]], [k[2][0], k[2][2]]], [[s_, ZERO], [ZERO, ZERO], [ZERO, ONE]])]
    return out + ([(k, drag_map(s, ell))] if ell is not None else [])


# -- decisions on ball matrices (``m`` symmetric in truth; its upper triangle is read) -----------------------------


def _ends(m, end: str) -> list:
    """The lower or upper ends (exact points) of the entries of ``m``."""
    n, e = m.nrows(), m.entries()
    return [[getattr(e[n * min(i, j) + max(i, j)], end)() for j in range(n)] for i in range(n)]


def _fails(e: list) -> bool:
    """The matrix of points ``e`` is certainly not copositive: a diagonal entry ``< 0`` or a principal 2×2
    ``[[a, b], [b, c]]`` with ``b < 0``, ``b² > ac`` (Hadeler).  Of upper ends: no matrix in the ball is."""
    n = len(e)
    return any(e[i][i] < 0 for i in range(n)) or any(
        e[i][j] < 0 and e[i][j] * e[i][j] > e[i][i] * e[j][j] for i in range(n) for j in range(i + 1, n))


def _fraction(point) -> Fraction | None:
    """The exact value of an arb point; None if it is not finite or beyond ``2^±EXPONENT_LIMIT``."""
    man, exp = (int(v) for v in point.man_exp()) if point.is_finite() else (1, 2 * EXPONENT_LIMIT)
    return None if man and abs(exp + man.bit_length()) > EXPONENT_LIMIT else Fraction(man) * Fraction(2) ** exp


def copositive_lower(m) -> bool:
    """Every matrix in the ball matrix ``m`` is copositive, shown on the matrix ``L`` of its lower ends.

    Copositivity is monotone in the entries (``M ≥ L`` and ``y ≥ 0`` give ``yᵀMy ≥ yᵀLy``).  Fast path in arb on
    ``L``'s exact points: Hadeler's 2×2 test, every entry ``≥ 0``, or Sylvester's minors ``> 0``; ``L`` certainly
    not copositive is False; what arb leaves open is decided by :func:`._core.copositive` on ``L``'s Fractions.
    """
    low = _ends(m, "lower")
    if len(low) == 2:
        a, b, c = low[0][0], low[0][1], low[1][1]
        if a >= 0 and c >= 0 and (b >= 0 or b * b <= a * c):
            return True
    elif all(x >= 0 for row in low for x in row) or (
            low[0][0] > 0 and low[0][0] * low[1][1] - low[0][1] ** 2 > 0 and flint.arb_mat(low).det() > 0):
        return True
    if _fails(low):
        return False
    exact = [[_fraction(x) for x in row] for row in low]
    return all(x is not None for row in exact for x in row) and copositive(exact) is True


def positive_definite(m) -> bool:
    """Every matrix in the 3×3 ball matrix ``m`` is positive definite (Sylvester: its leading minors ``> 0``)."""
    return bool(m[0, 0] > 0 and m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0] > 0 and m.det() > 0)


class Flow:
    """Enclosures of ``e^{At}`` (cached) and ``G = e^{At}ᵀe^{At}``, and the part budget of one file."""

    def __init__(self, a: Matrix) -> None:
        self.a, self.left, self.exact = _arb(a), MAX_TOTAL_PARTS, _ints(*(x for row in a for x in row))
        # t ↦ e^{At}; h ↦ e^{Ah}; h ↦ exp(A·[0, h]), which holds e^{Aτ} for every τ ∈ [0, h]
        self.starts, self.steps, self.widths = {}, {}, {}

    def at(self, t: Fraction, before: Fraction | None = None):
        """``e^{At}``, directly or (``before`` given, its own already known) as ``e^{A·before}·e^{A(t − before)}``."""
        key = (t.numerator, t.denominator)  # exact, and hashed far faster than a Fraction
        if key not in self.starts:
            h = t if before is None else t - before
            if (hk := (h.numerator, h.denominator)) not in self.steps:
                self.steps[hk] = (self.a * ball(h)).exp()
            self.starts[key] = self.steps[hk] if before is None else self.at(before) * self.steps[hk]
        return self.starts[key]

    def gram(self, lo: Fraction, hi: Fraction):
        """``G`` for every ``t ∈ [lo, hi]``: ``E = e^{A·lo}·exp(A·[0, hi − lo])``, then ``EᵀE``."""
        h = hi - lo
        if (hk := (h.numerator, h.denominator)) not in self.widths:
            self.widths[hk] = (self.a * flint.arb(0).union(ball(h))).exp()
        e = self.at(lo) * self.widths[hk]
        return e.transpose() * e

    def cover(self, parts: list[tuple[Fraction, Fraction]], test, refute, key: tuple) -> tuple[bool | None, str]:
        """``test(G)`` on parts covering ``parts``, halving where undecided (at most :data:`MAX_DEPTH` times);
        ``refute(G(t))`` at the midpoint of the 1st, 2nd, 4th, 8th … undecided part ends it with False; out of parts
        (this premise's or the file's) or of depth it is undecided.  Within :func:`shared`, the verdict on the same
        ``A``, parts and ``key`` (every number ``test`` and ``refute`` read) is kept where the file's budget did not
        decide it: it never came within 2 parts of its end, and this file has room for as many parts again."""
        kept = _kept((PRECISION, self.exact, _ints(*(x for part in parts for x in part)), key), list)
        if kept and self.left - kept[2] >= 2:
            self.left -= kept[2]
            return kept[0], kept[1]
        before, verdict = self.left, self._cover(parts, test, refute)
        if self.left >= 2:
            kept[:] = [*verdict, before - self.left]
        return verdict

    def _cover(self, parts: list[tuple[Fraction, Fraction]], test, refute) -> tuple[bool | None, str]:
        stack, done, undecided = [(lo, hi, 0) for lo, hi in reversed(parts)], 0, 0
        while stack:
            lo, hi, depth = stack.pop()
            self.left -= 1
            if test(self.gram(lo, hi)):
                done += 1
                continue
            mid, undecided = (lo + hi) / 2, undecided + 1
            e = self.at(mid, lo)
            if undecided & (undecided - 1) == 0 and refute(e.transpose() * e):
                return False, f"false at t = {shown(mid)}"
            if done + len(stack) + 2 > MAX_PARTS or self.left < 2 or depth == MAX_DEPTH:
                return None, f"not decided on [{ball(lo).str(6, radius=False)}, {ball(hi).str(6, radius=False)}]"
            stack += [(mid, hi, depth + 1), (lo, mid, depth + 1)]
        return True, f"{done} parts"


def _pieces(raw: object, v2: bool) -> list[tuple[Fraction, Fraction | None, Fraction, list[tuple[int, Matrix]]]]:
    """``(start, end or None for ∞, γ, [(s, K^s)])``: v1 one ``K`` (``K₁₂ = 0``) for both signs ``s``; v2 ``K⁺``
    (used where ``σv > 0``) and ``K⁻`` (``σv < 0`` and ``σ = 0``)."""
    if not isinstance(raw, list) or not 1 <= len(raw) <= MAX_PIECES:
        raise Malformed(f"pieces must be a list of 1 to {MAX_PIECES} objects")
    out = []
    keys = tuple(f"k{s}{e}" for s in "pm" for e in ENTRIES) if v2 else tuple(f"k{e}" for e in ENTRIES if e != "12")
    for i, item in enumerate(raw):
        c = _numbers(item, ("start", "gamma") + keys, f"pieces[{i}]")
        k = {s: _sym({e: c[f"k{'pm'[s < 0] if v2 else ''}{e}"] for e in ENTRIES if v2 or e != "12"}) for s in (1, -1)}
        end = None if item.get("end") == "inf" else q(item.get("end"))  # no end: Malformed
        out.append((c["start"], end, c["gamma"], [(1, k[1]), (-1, k[-1])]))
    return out


def _piece_forms(tag: str, piece: tuple, gains: tuple, ell: tuple, v2: bool) -> list[tuple[str, bool | None, str]]:
    """The exact premises of one piece's forms, in the main verifier's order and names (in python-flint's fmpq:
    the same exact values, several times faster than Fraction arithmetic, where the checker spent most of its time)."""
    out = Verdict("")
    (kp, ki, kv, gamma, *ell), forms = (_q(x) for x in (*gains, piece[2], *ell)), [(s, _q(k)) for s, k in piece[3]]
    for s, k in forms[:1 + v2]:
        sign = "+−"[s < 0] if v2 else ""
        if v2:  # design § c: the rate form's (1, 1) entry is 2sK₁₂
            out.add(f"{tag}: {'−' * (s < 0)}K{sign}12 ≥ 0", s * k[0][1] >= 0)
        # quadratic.U_rate, sup_flow_v2.U_rate: U̇ ≤ 0 on R̂ outside and inside the band for its sign (v1: both)
        for t in (s,) if v2 else (1, -1):
            b = "+−"[t < 0]
            out.add(f"{tag}: drag rate form of K{sign} (s = {sign}1) copositive" if v2 else
                    f"{tag}: −(K·B{b} + B{b}ᵀ·K) copositive", copositive(rate(k, _q(slip(kp, ki, kv, t)), ell)))
            out.add(f"{tag}: drag band form of K{sign} (s = {sign}1) copositive" if v2 else
                    f"{tag}: band form (s = {b}1) copositive", copositive(band(ki, kv, k, t, ell)))
        for j in range(3):  # the friction's term −2(Ky)₃f ≤ 0
            out.add(f"{tag}: K{sign}3{j + 1} ≥ 0", k[2][j] >= 0)
        out.add(f"{tag}: gamma·I − K{sign} copositive", copositive(_minus(_q(_eye(gamma)), k)))  # U_i ≤ γ_i|y|²
    if v2:  # design § c: U⁻ ≤ U⁺ on σ = 0, where σ may change sign (from + to −)
        out.add(f"{tag}: coupling (K+ − K−) on (|dz φ|, |v|) copositive",
                copositive([[forms[0][1][r][j] - forms[1][1][r][j] for j in (1, 2)] for r in (1, 2)]))
    return out.premises


def check(data: dict) -> Verdict:
    """Decide every premise of a ``sup-flow/v1`` or ``sup-flow/v2`` certificate, in the main verifier's order."""
    template = data.get("template")
    if template not in ("sup-flow/v1", "sup-flow/v2"):
        raise Malformed(f"not a sup-flow certificate: template {template!r}")
    v2 = template == "sup-flow/v2"
    kp, ki, kv, fc = _numbers(data.get("parameters"), ("k_p", "k_i", "k_v", "f_c"), "parameters").values()
    c = _numbers(data.get("constants"), ("c2", "p") + (("ell1", "ell2", "ell3") if v2 else ()), "constants")
    if 0 < sum(n in data["constants"] for n in TAIL) < len(TAIL):
        raise Malformed(f"constants must hold all of {', '.join(TAIL)} or none")
    tail = _numbers(data["constants"], TAIL, "constants") if TAIL[0] in data["constants"] else None
    kappa, pieces = q(data.get("overshoot_bound")), _pieces(data.get("pieces"), v2)
    ell = (c["ell1"], c["ell2"], c["ell3"]) if v2 else (ZERO,) * 3
    drag = ell if any(ell) else None  # ℓ = 0: no drag premises (then f = ℓᵀy is the plane φ = f_c)
    out, horizon, p = Verdict(template), pieces[-1][0], c["p"]
    # Assumption 1 (Routh–Hurwitz: A is Hurwitz, the paper's P ≻ 0); f_c > 0
    frame = [out.add("k_i > 0", ki > 0), out.add("k_p > 0", kp > 0), out.add("k_v·k_p > k_i", kv * kp > ki)]
    out.add("f_c > 0", fc > 0)
    # sup_flow.exit: the pieces I_i = [start, end) cover [0, ∞) in order; T ≥ 0
    frame.append(out.add("the first piece starts at t = 0", pieces[0][0] == 0))
    frame += [out.add(f"piece {i + 1} starts where piece {i} ends", pieces[i - 1][1] == pieces[i][0])
              for i in range(1, len(pieces))]
    frame.append(out.add("the last piece ends at ∞", pieces[-1][1] is None))
    frame.append(out.add("T ≥ 0 (the last piece starts at or after 0)", horizon >= 0))
    # the tail (sup_flow.exit; the paper's P: Lemma 2): |e^{At}w|² ≤ (1/p)|e^{At}w|²_P ≤ (1/p)|e^{AT}w|²_P for t ≥ T
    frame.append(out.add("p > 0", p > 0))
    whose, a = "the tail's P" if tail else "the paper's P", system(kp, ki, kv)
    pm = _sym({e: tail[f"tail_p{e}"] for e in ENTRIES}) if tail else _sym(
        {"11": kv / ki, "13": -ONE, "22": ONE, "33": kp}) if ki else None  # eq. (lyapLikeP)
    out.add(f"P − p·I ⪰ 0 ({whose})", pm is not None and psd(_minus(pm, _eye(p))))
    out.add(f"−(AᵀP + PA) ⪰ 0 ({whose})", pm is not None and psd(_minus(_eye(ZERO), [
        [x + y for x, y in zip(r, s)] for r, s in zip(_mul([list(col) for col in zip(*a)], pm), _mul(pm, a))])))
    for j in range(3 if v2 else 0):  # design § d: the drag split needs ℓ ≥ 0
        out.add(f"ell{j + 1} ≥ 0", ell[j] >= 0)
    old, flint.ctx.prec = flint.ctx.prec, PRECISION
    try:
        flow = Flow(a) if all(frame) else None  # the enclosures mean nothing without the frame
        tail_gram = flow and flow.at(horizon).transpose() * _arb(pm) * flow.at(horizon) / ball(p)
        # sup_flow.bounds, design § d: V_∞ ≤ c₂|x|²_𝒜 on R (and on R̂ \ R̂′): c₂I − DᵀG(t)D ≻ 0 for D = I, D_ℓ(±1);
        # a diagonal entry of DᵀG(t)D above c₂ refutes it
        maps = [_arb(_eye(ONE))] + ([_arb(drag_map(s, drag)) for s in (1, -1)] if drag else [])
        mu = ball(c["c2"])
        below = lambda g: all(positive_definite(mu * maps[0] - d.transpose() * g * d) for d in maps)  # noqa: E731
        name = "c2 ≥ ‖e^(At)‖² for every t ≥ 0" + (" and c2 ≥ ‖e^(At)·D_ℓ‖² (both signs)" if drag else "")
        if flow is None:
            out.add(name, None, NOT_EVALUATED)
        elif not below(tail_gram):
            out.add(name, False, f"the tail form at T = {shown(horizon)} is not below c2")
        else:
            out.add(name, *flow.cover([(s, e) for s, e, _, _ in pieces[:-1]], below, lambda g: any(
                (d.transpose() * g * d)[i, i] > mu for d in maps for i in range(3)), ("c2", _ints(c["c2"], *drag or ()))))
        for s, k in pieces[0][3][:1 + v2]:  # sup_flow.bounds: U ≥ |y|² = |x|²_𝒜 on R̂ at t = 0
            out.add(f"K{'+−'[s < 0] if v2 else ''}1 − I copositive (piece 1)", copositive(_minus(k, _eye(ONE))))
        for i, (start, end, gamma, forms) in enumerate(pieces):
            tag, numbers = f"piece {i + 1}", _ints(*(x for _, k in forms for row in k for x in row), *drag or ())
            out.premises += _kept(("forms", tag, numbers, _ints(kp, ki, kv, gamma, *ell), v2),
                                  lambda tag=tag, i=i: _piece_forms(tag, pieces[i], (kp, ki, kv), ell, v2))
            # sup_flow.exit, sup_flow_v2.exit: U^s ≥ |e^(At)w|² where a solution leaves, for every t of the piece
            name = (f"piece {i + 1}: U{'±' * v2} ≥ |e^(At)w|² on the exits of R̂{' and of f > ℓᵀy' * bool(drag)}"
                    f" for t in [{shown(start)}, {'∞' if end is None else shown(end)})")  # shown: str() raises past 4300 digits
            ex = _kept(("exit forms", PRECISION, numbers), lambda forms=forms: [
                (_arb(ke), _arb(d), _arb(d).transpose()) for s, k in forms for ke, d in exit_forms(k, s, drag)])
            above = lambda g, ex=ex: all(copositive_lower(ke - dt * g * d) for ke, d, dt in ex)  # noqa: E731
            if flow is None:
                out.add(name, None, NOT_EVALUATED)
            elif end is None:
                out.add(name, above(tail_gram), f"past T = {shown(horizon)} by P")
            elif not start < end:
                out.add(name, False, "empty piece")
            else:
                out.add(name, *flow.cover([(start, end)], above, lambda g, ex=ex: any(
                    _fails(_ends(ke - dt * g * d, "upper")) for ke, d, dt in ex), ("exits", numbers)))
    finally:
        flint.ctx.prec = old
    # sup_flow.stability_bound: |x(t)|²_𝒜 ≤ max(c₂, γ_i)|x(0)|²_𝒜 ≤ κ²|x(0)|²_𝒜 (eq. stabState)
    out.add("overshoot_bound > 0", kappa > 0)
    out.add("overshoot_bound² ≥ c2", kappa * kappa >= c["c2"])
    for i, piece in enumerate(pieces):
        out.add(f"overshoot_bound² ≥ gamma (piece {i + 1})", kappa * kappa >= piece[2])
    return out
