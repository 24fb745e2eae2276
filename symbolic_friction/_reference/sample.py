"""A state of the reference between its grid points, ``e^{Ar} y(jh)``, from a rigorous enclosure.

The reference's grid values ``y(jh)`` and its events come from the mpmath flow of :mod:`.slip`; a state asked
for between two grid points (:meth:`~symbolic_friction._reference.Reference.x_at`) is ``e^{Ar}`` applied to the
grid value before it, and most of a reference's cost is in these, one ``e^{Ar}`` per time asked for.  Here
``e^{Ar} y`` is enclosed in arb balls (python-flint): ``A`` of eq. xDot from the exact gains, ``r`` and ``y``
taken exactly from their mpf values, so the ball holds the exact ``e^{Ar} y``.  Its midpoint, rounded once to
the working precision, is the state when the ball's radius is below ``2^{8-prec}`` times the state's size (the
working precision's rounding level, guard digits above the digits asked for); otherwise, or when flint cannot
be used, ``None`` and the caller uses the mpmath flow.
"""

from __future__ import annotations

import functools

__all__ = ["flow_enclosed"]

_EXTRA_BITS = 32
"""Bits carried by the arb evaluation above the working precision (the squarings of its ``exp`` lose some)."""
_SLACK_BITS = 8
"""The radius accepted: ``2^{slack - prec}`` times the state's size."""


def flow_enclosed(ctx, gains: tuple, y, tau):
    """``e^{Aτ} y`` (three mpf of ``ctx``) from an arb enclosure, or ``None`` when its radius is too large.

    Parameters
    ----------
    ctx : mpmath context of the reference (its precision is the working precision)
    gains : tuple
        The exact gains ``k_p``, ``k_i``, ``k_v`` of ``A`` in eq. xDot, each as ``(numerator, denominator)``.
    y : sequence of 3 mpf
        The offset at the start (a grid value).
    tau : mpf
        The time from it.
    """
    import flint
    from mpmath.libmp import from_man_exp

    if not all(ctx.isfinite(c) for c in (*y, tau)):  # an infinity's or NaN's raw mantissa is 0: never read it as 0
        return None
    prec = ctx.prec
    old = flint.ctx.prec
    flint.ctx.prec = prec + _EXTRA_BITS
    try:
        A = _matrix(gains, prec + _EXTRA_BITS)
        z = (A * _arb(tau)).exp() * flint.arb_mat([[_arb(c)] for c in y])
        balls = [z[i, 0] for i in range(3)]
        mids = [b.mid() for b in balls]
        size = max(abs(m) for m in mids)
        bound = flint.arb(size) * flint.arb(2) ** (_SLACK_BITS - prec)
        if not all(b.rad() <= bound for b in balls) or not all(b.is_finite() for b in balls):
            return None
        out = []
        for m in mids:
            man, exp = m.man_exp()
            out.append(ctx.make_mpf(from_man_exp(int(man), int(exp), prec, ctx._prec_rounding[1])))
        return out
    finally:
        flint.ctx.prec = old


@functools.lru_cache(maxsize=64)
def _matrix(gains: tuple, bits: int):
    """``A`` of eq. xDot in arb balls at ``bits`` (the caller's flint precision), each holding the exact gain."""
    import flint

    from .._model.coordinates import system_matrix_entries

    k_p, k_i, k_v = (flint.arb(flint.fmpq(*q)) for q in gains)
    return flint.arb_mat([list(row) for row in system_matrix_entries(k_p, k_i, k_v)])  # the model's A, not a copy


def _arb(x):
    """An mpf as the arb point holding exactly its value."""
    import flint

    sign, man, exp, _ = x._mpf_
    return flint.arb(flint.arf((-man if sign else man, exp)))
