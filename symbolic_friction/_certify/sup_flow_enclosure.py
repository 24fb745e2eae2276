"""The sup-flow template's premises on the friction-free flow, decided in python-flint arb balls.

``e^{At}`` on a part ``[a, b]`` of a piece is enclosed by ``e^{Aa}·exp(A·[0, b − a])``
(ball arithmetic encloses the value at every point of the input ball).  A
premise is decided on exact rationals taken from the ends of the balls:

* :class:`FlowNorm` — ``c₂I − e^{At}ᵀe^{At} ≻ 0`` on every part of ``[0, T]``
  (Sylvester's minors of the ball matrix, positive lower ends; the
  :mod:`.flow_bound` test) and ``c₂I − (1/p)e^{AT}ᵀPe^{AT} ≻ 0`` past ``T``;
* :class:`FlowExit` — the exit forms of :func:`._model.sup_flow.exit_forms`
  copositive on every part of a piece, with each ball replaced by its lower
  end (copositivity is monotone in the entries, so the rational matrix of
  lower ends being copositive shows it for every matrix in the ball); past
  ``T`` with the tail form.

A part that is not decided is halved.  Its midpoint is looked at first: the
matrix of upper ends there not copositive (or a Rayleigh quotient above
``c₂``) refutes the premise at that point, so a false certificate costs
little.  What is not decided within :data:`MAX_PARTS` parts (or
:data:`MAX_TOTAL_PARTS` for one certificate) is *not proved*.  Ends beyond
``2^±EXPONENT_LIMIT`` are moved outward or decide nothing (:func:`_end`), so no
Fraction grows without bound.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from .._infra.rational import format_rational as _f
from .._model import sup_flow as model
from .sup_flow_forms import exit_forms
from .verify import Check

__all__ = ["MAX_PARTS", "MAX_TOTAL_PARTS", "PRECISION", "EXPONENT_LIMIT", "FlowNorm", "FlowExit", "Budget", "decide_flow"]

MAX_PARTS = 2048
"""Intervals one rigorous decision may bisect its interval into before it says *not proved*."""
MAX_TOTAL_PARTS = 12_288
"""Intervals all rigorous decisions of one certificate may use together (a few seconds at most)."""
PRECISION = 128
"""Bits of the arb balls."""


@dataclass(frozen=True)
class FlowNorm:
    """``c₂I − e^{At}ᵀe^{At} ≻ 0`` for every ``t ∈ [0, T]``, and ``c₂I − (1/p)e^{AT}ᵀPe^{AT} ≻ 0`` (the tail).

    ``certificate`` is a :class:`~.sup_flow.SupFlowCertificate`, ``p_matrix`` the paper's ``P`` for its gains.
    """

    obligation: str
    name: str
    certificate: Any
    p_matrix: tuple[tuple[Fraction, ...], ...]


@dataclass(frozen=True)
class FlowExit:
    """``U_i ≥ |e^{At}w|²`` on both exit planes, both signs of ``σ``, every ``t`` of piece ``index``."""

    obligation: str
    name: str
    certificate: Any
    p_matrix: tuple[tuple[Fraction, ...], ...]
    index: int


def _arb(q: Fraction) -> Any:
    from .flow_bound import _arb as arb

    return arb(Fraction(q))


def _arb_of_float(x: float) -> Any:
    """``_arb(Fraction(x))`` for a float: a double is an exact arb point, so without the Fraction (a NaN or an
    infinity still goes through the Fraction, which refuses it)."""
    import math

    import flint

    return flint.arb(x) if math.isfinite(x) else _arb(Fraction(x))


def _flow(cert: Any, a: Fraction, b: Fraction) -> Any:
    """An arb enclosure of ``e^{At}`` for every ``t ∈ [a, b]``: ``e^{Aa}·e^{A[0, b − a]}``.

    Ball arithmetic encloses the value at every point of the input ball, so
    the exponential of the ball ``A·[0, b − a]`` holds every ``e^{Aτ}``; the
    point factor ``e^{Aa}`` first keeps the ball small (the exponential of a
    wide ball ``A·[a, b]`` far from 0 would be needlessly wide).
    """
    key = _gains_key(cert)
    # A bisection's parts share their left ends with their parents and their widths with their cousins, so
    # both factors repeat; each is the same ball every time it is built, so keeping it changes no decision.
    # The keys are exact (numerators and denominators: hashing ints is cheap, hashing Fractions is not), and
    # A (the same object for the same gains, :func:`_system_of`) is looked up only to build a missing factor.
    start = _cached((key, "start", a.numerator, a.denominator), lambda: (_system_of(cert) * _arb(a)).exp())
    if a == b:
        return start
    width = b - a

    def spread() -> Any:
        import flint

        half = _arb(width / 2)
        return (_system_of(cert) * flint.arb(half, half)).exp()

    return start * _cached((key, "width", width.numerator, width.denominator), spread)


def _gains_key(cert: Any) -> tuple[int, ...]:
    """The gains and the working precision as exact integers (numerator, denominator): the key of the kept balls."""
    import flint

    k_p, k_i, k_v = cert.k_p, cert.k_i, cert.k_v
    return (k_p.numerator, k_p.denominator, k_i.numerator, k_i.denominator, k_v.numerator, k_v.denominator,
            flint.ctx.prec)


_FLOWS: dict[tuple[Any, ...], Any] = {}


def _cached(key: tuple[Any, ...], build: Any) -> Any:
    """``build()`` kept under ``key`` (at most 4096 entries: the cache is cleared, never grows without bound)."""
    value = _FLOWS.get(key)
    if value is None:
        if len(_FLOWS) >= 4096:
            _FLOWS.clear()
        value = _FLOWS[key] = build()
    return value


_SYSTEMS: dict[tuple[int, ...], Any] = {}


def _system_of(cert: Any) -> Any:
    """``A`` of eq. (xDot) as an arb matrix for ``cert``'s gains at the working precision (built once per gains
    and precision: the same balls every time, and the bisection's many parts do not rebuild it)."""
    from .flow_bound import _system

    key = _gains_key(cert)
    if key not in _SYSTEMS:
        if len(_SYSTEMS) >= 64:
            _SYSTEMS.clear()
        _SYSTEMS[key] = _system(cert)  # it reads the gains k_p, k_i, k_v, which a certificate has
    return _SYSTEMS[key]


def _rows(m: Any) -> tuple[tuple[Any, ...], ...]:
    e = m.entries()  # row-major, the same balls as m[i, j], in one call
    return tuple(e[0:3]), tuple(e[3:6]), tuple(e[6:9])


def _gram(e: Any) -> tuple[tuple[Any, ...], ...]:
    return _rows(e.transpose() * e)


def _tail_gram(premise: FlowNorm | FlowExit, horizon: Fraction) -> tuple[tuple[Any, ...], ...]:
    e = _rows(_flow(premise.certificate, horizon, horizon))
    p = tuple(tuple(_arb(x) for x in row) for row in premise.p_matrix)
    return model.tail_gram(e, p, _arb(premise.certificate.constants["p"]))


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


def _exit_holds(forms: Any, gram: Any, *, end: Any = _lower) -> tuple[bool, str]:
    """Every exit form, with each entry replaced by one end of its ball, copositive (exactly).

    ``forms`` holds ``(s, K, D)`` per sign ``s``: the 2×2 forms of both exit
    planes with ``K`` and, where ``D`` (the drag exit map ``D_ℓ``) is given,
    the 3×3 form ``K − DᵀGD``.  Copositivity is monotone in the entries: the
    rational matrix of lower ends being copositive shows it for every ``G`` in
    the enclosure; the matrix of upper ends (``end=_upper``) *not* being
    copositive shows that no ``G`` in it is (at a point ``t``: the premise is
    false there).
    """
    for s, k, d in forms:
        named = list(zip(model.EXIT_PLANES, exit_forms(k, gram, s)))
        if d is not None:
            named.append(("f = ℓᵀy", model.pullback_gap(k, gram, d)))
        for plane, form in named:
            if end is _lower and _lower_ends_clearly_copositive(form):
                continue  # proved without building Fractions (the common case); anything else is decided exactly
            if end is _upper and _upper_ends_clearly_copositive(form):
                continue  # not refuted, as the exact decision would say (the common case at a point of a true premise)
            pick = min if end is _lower else max
            n = len(form)
            try:
                rows = tuple(tuple(end(form[i][i]) if i == j else pick(end(form[i][j]), end(form[j][i])) for j in range(n))
                             for i in range(n))
            except _TooWide as exc:
                return end is not _lower, f"{plane}: {exc}"  # decides nothing: neither proved nor refuted
            from .copositive import decide_copositive

            decision = decide_copositive(rows)
            if decision.holds is not True:
                return False, f"{plane}, sign σ = {'+' if s > 0 else '−'}: {decision.reason}"
    return True, ""


def _lower_ends_clearly_copositive(form: Any) -> bool:
    """A sufficient test, in arb, that the matrix of the lower ends of ``form``'s balls is copositive.

    A 3×3 form (the drag exit) is proved here when the symmetric matrix of the
    lower ends (the smaller of each off-diagonal pair) has every entry ``≥ 0``,
    or is positive definite for certain (its leading principal minors' balls
    are positive); either makes it copositive.  Anything else is decided
    exactly by the caller.

    With ``a``, ``c`` the diagonal's and ``b`` the smaller off-diagonal lower
    end (exact points), it asks arb whether ``a ≥ 0``, ``c ≥ 0`` and
    ``b ≥ 0`` or ``b² ≤ ac`` hold *for certain* (a comparison of balls is True
    only when it holds for every point in them) — Hadeler's 2×2 criterion,
    which :func:`.copositive.decide_copositive` decides on the same numbers as
    Fractions.  True proves the form; False decides nothing (the caller then
    decides exactly), so a weaker test here costs time, never soundness.
    """
    if len(form) == 3:
        low = [[form[i][j].lower() for j in range(3)] for i in range(3)]
        if not all(x.is_finite() for row in low for x in row):
            return False
        off = [[low[i][j] if i == j else min(low[i][j], low[j][i]) for j in range(3)] for i in range(3)]
        if all(off[i][j] >= 0 for i in range(3) for j in range(3)):
            return True  # every entry ≥ 0
        # positive definite (leading principal minors > 0, in arb) implies copositive
        m2 = off[0][0] * off[1][1] - off[0][1] * off[0][1]
        m3 = (off[0][0] * (off[1][1] * off[2][2] - off[1][2] * off[1][2]) - off[0][1] * (off[0][1] * off[2][2] - off[1][2] * off[0][2])
              + off[0][2] * (off[0][1] * off[1][2] - off[1][1] * off[0][2]))
        return bool(off[0][0] > 0 and m2 > 0 and m3 > 0)
    a, c = form[0][0].lower(), form[1][1].lower()
    b = min(form[0][1].lower(), form[1][0].lower())
    if not (a.is_finite() and b.is_finite() and c.is_finite()):
        return False
    return bool(a >= 0 and c >= 0 and (b >= 0 or b * b <= a * c))


def _upper_ends_clearly_copositive(form: Any) -> bool:
    """A sufficient test, in arb, that the matrix of the upper ends of a 2×2 ``form``'s balls is copositive.

    The refutation at a point (``end=_upper``) looks for a form whose upper ends are *not* copositive; at a
    point of a premise that holds, every form passes, and this spares building its Fractions.  It asks, as
    :func:`_lower_ends_clearly_copositive` does on the lower ends, Hadeler's 2×2 criterion for certain on the
    exact points ``a``, ``c`` (diagonal) and ``b`` (the larger off-diagonal upper end, as the exact path
    takes).  True only where :func:`.copositive.decide_copositive` says True on what :func:`_upper` makes of
    the same ends: every end is below ``2^EXPONENT_LIMIT`` in magnitude (beyond it the exact path raises
    :class:`_TooWide` and stops, which this must not skip), and the tiny ends :func:`_end` moves move up,
    which keeps a copositive matrix copositive.  A 3×3 form (the drag exit) is left to the exact decision.
    """
    if len(form) != 2:
        return False
    a, c = form[0][0].upper(), form[1][1].upper()
    b01, b10 = form[0][1].upper(), form[1][0].upper()
    if not (a.is_finite() and c.is_finite() and b01.is_finite() and b10.is_finite()):
        return False
    big = _two_to_limit()
    if not (a < big and c < big and -big < b01 < big and -big < b10 < big):
        return False
    b = max(b01, b10)
    return bool(a >= 0 and c >= 0 and (b >= 0 or b * b <= a * c))


_LIMITS: list[Any] = []


def _two_to_limit() -> Any:
    """``2^EXPONENT_LIMIT`` as an exact arb point (a power of two is exact at every precision)."""
    import flint

    if not _LIMITS:
        _LIMITS.append(flint.arb(2) ** EXPONENT_LIMIT)
    return _LIMITS[0]


def _not(verdict: tuple[bool, str]) -> tuple[bool, str]:
    return not verdict[0], verdict[1]


class Budget:
    """The parts one verification may still bisect into (all its premises together)."""

    def __init__(self, parts: int | None = None) -> None:
        self.total = MAX_TOTAL_PARTS if parts is None else max(0, min(int(parts), MAX_TOTAL_PARTS))
        self.left = self.total


def _bisect(a: Fraction, b: Fraction, test: Any, refute: Any, budget: Budget) -> tuple[int, str]:
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
            limit = f"{MAX_PARTS} parts" if budget.left >= 2 else f"the {budget.total} parts of one verification"
            return done, f"not decided on [{float(lo):.6g}, {float(hi):.6g}] within {limit} ({why})"
        stack += [(mid, hi), (lo, mid)]
    return done, ""


def _pullbacks(gram: Any, maps: Any) -> list[Any]:
    """``G`` and ``DᵀGD`` for each drag map ``D`` (arb matrices): the Grams ``c₂`` must bound."""
    import flint

    out = [gram]
    for d in maps:
        m = flint.arb_mat([[x for x in row] for row in d])
        out.append(m.transpose() * gram * m)
    return out


def _norm_refuted(cert: Any, mu: Any, t: Fraction, maps: Any = ()) -> tuple[bool, str]:
    """``‖e^{At}D‖₂² > c₂`` shown at the point ``t`` for ``D = I`` or a drag map (the Rayleigh quotient of
    ``DᵀGD`` at a float guess of its top eigenvector, in arb; a lower end above ``c₂``)."""
    import numpy as np

    e = _flow(cert, t, t)
    for i, g in enumerate(_pullbacks(e.transpose() * e, maps)):
        g = _rows(g)
        guess = np.linalg.eigh(np.array([[float(g[i][j].mid()) for j in range(3)] for i in range(3)]))[1][:, -1]
        v = [_arb_of_float(float(x)) for x in guess]
        q = sum(v[i] * g[i][j] * v[j] for i in range(3) for j in range(3)) / sum(x * x for x in v)
        if q > mu:
            return True, "‖e^(At)‖² > c2 there" if i == 0 else "‖e^(At)·D_ℓ‖² > c2 there"
    return False, "‖e^(At)‖² > c2 there"


def decide_flow(premise: FlowNorm | FlowExit, budget: Budget) -> Check:
    import flint

    from .flow_bound import _below

    cert = premise.certificate
    old = flint.ctx.prec
    flint.ctx.prec = PRECISION
    try:
        horizon = cert.pieces[-1].start
        maps = [tuple(tuple(_arb(x) for x in row) for row in d) for _, d in cert.drag_maps()]
        if isinstance(premise, FlowNorm):
            mu = _arb(cert.constants["c2"])
            tail = flint.arb_mat([list(r) for r in _tail_gram(premise, horizon)])
            if not all(_below(mu, g) for g in _pullbacks(tail, maps)):
                return Check(premise.obligation, premise.name, f"the tail form at T = {_f(horizon)} is not below c2", False)

            def below(lo: Fraction, hi: Fraction) -> tuple[bool, str]:
                e = _flow(cert, lo, hi)
                return all(_below(mu, g) for g in _pullbacks(e.transpose() * e, maps)), "‖e^(At)‖² ≥ c2 or too close to it"

            parts, why = _bisect(Fraction(0), horizon, below, lambda t: _norm_refuted(cert, mu, t, maps), budget)
            text = f"c2 = {_f(cert.constants['c2'])} on [0, {_f(horizon)}] in {parts} parts and past it by P"
            return Check(premise.obligation, premise.name, why or text, not why)
        piece = cert.pieces[premise.index]
        drag = dict(zip([s for s, _ in cert.drag_maps()], maps))
        forms = [(s, tuple(tuple(_arb(x) for x in row) for row in k), drag.get(s)) for s, k in piece.signed_forms()]
        if piece.end is None:
            holds, why = _exit_holds(forms, _tail_gram(premise, piece.start))
            return Check(premise.obligation, premise.name, why or f"past T = {_f(piece.start)} by P", holds)
        if not piece.start < piece.end:
            return Check(premise.obligation, premise.name, f"empty piece {piece.interval_text()}", False)
        parts, why = _bisect(piece.start, piece.end, lambda lo, hi: _exit_holds(forms, _gram(_flow(cert, lo, hi))),
                             lambda t: _not(_exit_holds(forms, _gram(_flow(cert, t, t)), end=_upper)), budget)
        return Check(premise.obligation, premise.name, why or f"on {piece.interval_text()} in {parts} parts", not why)
    finally:
        flint.ctx.prec = old
