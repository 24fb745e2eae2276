"""What a hunting certificate states about its cycle, enclosed in arb balls and decided.

The proof (:mod:`.hunting_proof`) shows that ``F(σ, τ) = (v, σ₁ + σ)`` has
exactly one zero ``(σ*, τ*)`` in the box and that it lies in the Krawczyk
box ``K(X)`` (:attr:`.hunting_proof.CycleProof.zero`).  From it follow the
cycle's numbers (module docstring of :mod:`.hunting_proof`, with
``y(τ; σ) = e^{Aτ}(σ, f_s - f_c, 0) = (σ₁, p₁, v)``):

* ``slip_time = τ*``, the duration of each slip;
* ``stick_time = (f_s + φ₁)/σ*`` with ``φ₁ = f_c + p₁(τ*; σ*)``: the stick
  keeps ``σ = -σ*`` and lasts until ``φ`` reaches ``-f_s``;
* ``period = 2 (slip_time + stick_time)`` (two mirror-image halves);
* ``multiplier = -P'(σ*) = -(∂σ₁/∂σ - ∂σ₁/∂τ · (∂v/∂σ)/(∂v/∂τ))`` and
  ``stable``: ``|multiplier| < 1`` (``true``), ``> 1`` (``false``), or
  ``null`` (not decided).

The file's ``cycle`` member states each as a closed interval ``[lo, hi]`` of
exact rationals; :func:`decide_claims` encloses the quantity in arb balls over
``K(X)`` and holds the claim only if the ball lies in ``[lo, hi]`` (certain
comparisons), so every number the file states is proved, and an edited one
fails, naming its field.  :func:`state_claims` writes the intervals the
verifier proves: the balls rounded outward to :data:`DIGITS` significant
digits, deterministic, so regenerating a file gives the same bytes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from .._infra.errors import CertificateFormatError
from .._model.parameters import Parameters
from .hunting_proof import PRECISION, Check, CycleProof, _Arb

__all__ = ["CycleClaims", "FIELDS", "DIGITS", "enclose", "decide_claims", "state_claims", "polish"]

FIELDS = ("sigma", "slip_time", "stick_time", "period", "multiplier")
"""The enclosed numbers of the ``cycle`` member, each ``[lo, hi]``; with ``stable`` they are all it holds."""
DIGITS = 12
"""Significant digits of a written enclosure (its ends rounded outward)."""


@dataclass(frozen=True)
class CycleClaims:
    """The ``cycle`` member of a hunting certificate: closed intervals of exact rationals and ``stable``."""

    sigma: tuple[Fraction, Fraction]
    slip_time: tuple[Fraction, Fraction]
    stick_time: tuple[Fraction, Fraction]
    period: tuple[Fraction, Fraction]
    multiplier: tuple[Fraction, Fraction]
    stable: bool | None

    def __post_init__(self) -> None:
        for name in FIELDS:
            lo, hi = getattr(self, name)
            if not lo <= hi:
                raise CertificateFormatError(f"cycle.{name} must be an interval [lo, hi] with lo ≤ hi; got [{lo}, {hi}]")
        if self.stable not in (True, False, None):
            raise CertificateFormatError(f"cycle.stable must be true, false or null; got {self.stable!r}")

    def to_dict(self) -> dict[str, Any]:
        from .._infra.rational import format_rational as s

        out: dict[str, Any] = {name: [s(getattr(self, name)[0]), s(getattr(self, name)[1])] for name in FIELDS}
        out["stable"] = self.stable
        return out

    @classmethod
    def from_dict(cls, data: object) -> "CycleClaims":
        """Parse strictly: exactly the keys of :data:`FIELDS` and ``stable``; :class:`CertificateFormatError` names the key."""
        from .certificate import _signed_rational_field

        keys = FIELDS + ("stable",)
        if not isinstance(data, dict) or sorted(data) != sorted(keys):
            shown = sorted(data) if isinstance(data, dict) else type(data).__name__
            raise CertificateFormatError(f"cycle must have exactly the keys {list(keys)}; got {shown}")
        values: dict[str, Any] = {}
        for name in FIELDS:
            pair = data[name]
            if not (isinstance(pair, list) and len(pair) == 2):
                raise CertificateFormatError(f"cycle.{name} must be a list [lo, hi] of two rational strings; got {pair!r}")
            values[name] = (_signed_rational_field(pair[0], f"cycle.{name}[0]"), _signed_rational_field(pair[1], f"cycle.{name}[1]"))
        return cls(**values, stable=data["stable"])


def enclose(params: Parameters, zero: tuple[tuple[Fraction, Fraction], tuple[Fraction, Fraction]]) -> dict[str, Any]:
    """Arb balls of :data:`FIELDS` for every ``(σ, τ)`` of the box ``zero`` (call at the proof's precision)."""
    M = _Arb(params)
    (s_lo, s_hi), (t_lo, t_hi) = zero
    S, T = M.ball(s_lo, s_hi), M.ball(t_lo, t_hi)
    E, y, dy = M.state(S, T)
    stick = (M.f_s + M.f_c + y[1]) / S
    return {
        "sigma": S,
        "slip_time": T,
        "stick_time": stick,
        "period": 2 * (T + stick),
        "multiplier": -(E[0, 0] - dy[0] * E[2, 0] / dy[2]),
    }


def _stability(ball) -> bool | None:
    if bool(abs(ball) < 1):
        return True
    if bool(abs(ball) > 1):
        return False
    return None


def decide_claims(params: Parameters, proof: CycleProof, claims: CycleClaims, *, precision: int = PRECISION) -> tuple[Check, ...]:
    """One :class:`Check` per field of ``claims`` (``cycle.period`` …): the enclosure over ``K(X)`` lies in the stated interval.

    Nothing is decided without a proved zero: every claim then fails (the
    numbers of a cycle that is not shown to exist are not shown either).
    """
    if proof.zero is None:
        return tuple(Check(f"cycle.{name}", False, "not decided: the Krawczyk test proved no zero")
                     for name in FIELDS + ("stable",))
    from flint import ctx

    saved = ctx.prec
    ctx.prec = int(precision)
    try:
        balls = enclose(params, proof.zero)
        M = _Arb(params)
        out = []
        for name in FIELDS:
            lo, hi = getattr(claims, name)
            ball = balls[name]
            holds = bool(ball >= M.q(lo)) and bool(ball <= M.q(hi))
            out.append(Check(f"cycle.{name}", holds,
                             f"{ball.str(12)} {'⊆' if holds else 'NOT ⊆'} [{float(lo):.15g}, {float(hi):.15g}]"))
        shown = _stability(balls["multiplier"])
        stated = claims.stable
        holds = stated is None or stated == shown
        words = {True: "stable (|multiplier| < 1)", False: "unstable (|multiplier| > 1)", None: "undecided"}
        out.append(Check("cycle.stable", holds, f"the file says {words[stated]}; the enclosure shows {words[shown]}"))
        return tuple(out)
    finally:
        ctx.prec = saved


def _round(x: Fraction, *, up: bool) -> Fraction:
    """``x`` rounded to :data:`DIGITS` significant decimal digits, up or down (outward for an interval's end)."""
    if x == 0:
        return x
    exponent = math.floor(math.log10(abs(float(x)))) - DIGITS + 1
    scale = Fraction(10) ** exponent
    n = x / scale
    q = -((-n.numerator) // n.denominator) if up else n.numerator // n.denominator
    return q * scale


def state_claims(params: Parameters, proof: CycleProof, *, precision: int = PRECISION) -> CycleClaims | None:
    """The claims :func:`decide_claims` proves for ``proof``: each ball rounded outward (None if no zero is proved)."""
    if proof.zero is None:
        return None
    from flint import ctx

    from .hunting_proof import _exact_mid

    saved = ctx.prec
    ctx.prec = int(precision)
    try:
        balls = enclose(params, proof.zero)
        values = {name: (_round(_exact_mid(balls[name].lower()), up=False), _round(_exact_mid(balls[name].upper()), up=True))
                  for name in FIELDS}
        return CycleClaims(**values, stable=_stability(balls["multiplier"]))
    finally:
        ctx.prec = saved


def polish(params: Parameters, sigma: float | Fraction, tau: float | Fraction, *, steps: int = 8) -> tuple[float, float]:
    """``(σ*, τ*)`` to double precision: Newton's method on ``F`` in 128-bit arb midpoints from ``(σ, τ)``.

    A search (not a proof): it makes the box a function of the zero alone,
    not of the last bits of the float search that found it, so a certificate
    regenerated from its own box is byte-identical to the one first written.
    """
    from flint import ctx

    saved = ctx.prec
    ctx.prec = PRECISION
    try:
        M = _Arb(params)
        s, t = M.q(Fraction(sigma)), M.q(Fraction(tau))
        for _ in range(steps):
            E, y, dy = M.state(s, t)
            f0, f1 = y[2], y[0] + s
            a, b, c, d = E[2, 0], dy[2], E[0, 0] + 1, dy[0]
            det = a * d - b * c
            s, t = (s - (d * f0 - b * f1) / det).mid(), (t - (a * f1 - c * f0) / det).mid()
        return float(s), float(t)
    finally:
        ctx.prec = saved
