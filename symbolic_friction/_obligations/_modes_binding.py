"""The mode selection of the simulators against the proved table, exhaustively (``model.modes_runtime``).

The appendix's table of Claim 1 (as ``claim1.cases`` proves it,
:func:`.claim1.table_rows`) decides the mode at rest by comparing ``φ`` with
the stick boundary ``±f_s`` (``f_s = f_c`` in the paper; with static friction
the mass sticks while ``|φ| ≤ f_s``).  The simulators decide it in floating
point, with ``φ`` kept as ``base·f_c + offset`` (``base ∈ {-1, 0, 1}``) and a
named snapping band: :func:`.modes.mode_at_rest` puts ``φ`` on the boundary
``s·f_s`` (``s = ±1``) when the gap it computes is within

    ``band = tol + SNAP_ULPS·ε·(|base - s|·f_c + (f_s - f_c))``,  ``ε = 2⁻⁵²``,

the caller's ``tol`` plus the rounding of the boundary's terms.  This module
binds that rule, for every ``f_c`` of :data:`F_CS`, with and without static
friction, every base, both boundaries and both slip directions, at offsets on
the boundary, at the adjacent floats, just inside and just outside the band,
and in the open classes:

* outside the band the answer must be the proved table's row at the exact
  ``φ = base·f_c + offset`` (rationals);
* inside it, the row on the boundary (``φ = s·f_s``: rows (iii)–(v), (vii)–(ix));
* points whose exact gap is within the rounding of the gap's own computation of
  the band's edge are not judged (they could go either way); every other is.

A band :data:`SNAP_ULPS` times wider or narrower than stated fails, as does a
row that no judged point reaches from some base or direction (a vacuous check).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Callable

from ._base import Outcome

__all__ = ["EPS", "SNAP_ULPS", "F_CS", "EXCESS", "band", "verify_modes"]

EPS = 2.0**-52
"""The spacing of floats at 1."""

SNAP_ULPS = 4.0
"""The snapping band's width, in units of ``ε`` times the boundary's terms (module docstring)."""

F_CS = (1.0, 2.0, 1e-6, 1e6)
"""Coulomb levels the binding runs at (states scaled with them)."""

EXCESS = (0.0, 0.2)
"""``(f_s - f_c)/f_c``: the paper's model and static friction above Coulomb."""

TOLS = (0.0, 16.0)
"""The caller's ``tol`` in units of ``ε·f_c`` (0: the band is rounding only)."""


def _q(x: float | Fraction | int) -> Any:
    """``x`` as an exact python-flint rational (``fmpq``): the same value as ``Fraction(x)``, and arithmetic in C,
    for the some 10⁵ exact comparisons below (a float is a dyadic rational: its integer ratio is exact)."""
    import flint

    if isinstance(x, float):
        return flint.fmpq(*x.as_integer_ratio())
    if isinstance(x, Fraction):
        return flint.fmpq(x.numerator, x.denominator)
    return flint.fmpq(x)


def band(base: int, s: int, f_c: float, excess: float, tol: float) -> Fraction:
    """The width within which ``φ = base·f_c + offset`` is put on ``s·f_s`` (module docstring)."""
    return Fraction(tol) + Fraction(SNAP_ULPS) * Fraction(EPS) * (abs(base - s) * Fraction(f_c) + Fraction(excess))


def _row(rows: tuple[Any, ...], sigma: Any, phi: Any, f_s: Any, memo: dict) -> Any:
    """The row of the proved table at ``v = 0`` (the boundaries at ``±f_s``); exact numbers (``phi`` and ``f_s`` of one
    type: Fraction or fmpq)."""
    phi_class = (
        "φ > f_c" if phi > f_s else "φ = f_c" if phi == f_s else "φ = -f_c" if phi == -f_s
        else "φ < -f_c" if phi < -f_s else "|φ| < f_c"
    )
    sigma_class = "> 0" if sigma > 0 else "< 0" if sigma < 0 else "= 0"
    key = (phi_class, sigma_class)
    if key in memo:
        return memo[key]
    found = [r for r in rows if r.v == "= 0" and r.phi in (None, phi_class) and r.sigma in (None, sigma_class)]
    if len(found) != 1:
        raise ValueError(f"{len(found)} rows of the proved table apply at σ = {sigma}, φ = {phi}")
    memo[key] = found[0]
    return found[0]


def _offsets(base: int, f_c: float, excess: float, bands: dict[int, float]) -> list[float]:
    """Offsets on each boundary, at its adjacent floats, inside and outside its band, and in the open classes."""
    out = [0.0, 5e-324, -5e-324, 0.5 * f_c - base * f_c, -0.5 * f_c - base * f_c, 3 * f_c - base * f_c, -3 * f_c - base * f_c]
    for s in (1, -1):
        at = (s - base) * f_c + s * excess  # the boundary s·f_s, rounded
        near = [at, math.nextafter(at, math.inf), math.nextafter(at, -math.inf),
                math.nextafter(math.nextafter(at, math.inf), math.inf), math.nextafter(math.nextafter(at, -math.inf), -math.inf)]
        for k in (0.5, 0.9, 1.25, 2.0, 8.0):
            near += [at + k * bands[s], at - k * bands[s]]
        out += near
    return out


def verify_modes(
    rows: tuple[Any, ...],
    mode_at_rest: Callable[..., Any],
    mode_after_slip: Callable[..., Any],
) -> Outcome:
    """``mode_at_rest`` from every base and ``mode_after_slip`` in both directions against the table (module docstring)."""
    judged = 0
    table = _Table(rows)
    for f_c in F_CS:
        for ratio in EXCESS:
            excess = ratio * f_c
            for tol_ulps in TOLS:
                tol = tol_ulps * EPS * f_c
                place = _Placement(f_c, excess, tol)
                reached: dict[str, set[str]] = {}
                for base in (-1, 0, 1):
                    bands = {s: float(place.band_widths[base, s]) for s in (1, -1)}
                    for offset in _offsets(base, f_c, excess, bands):
                        where_phi = f"f_c = {f_c!r}, f_s = f_c + {excess!r}, tol = {tol!r}: φ = {base}·f_c + {offset!r}"
                        at = place(base, offset)
                        # a slip in direction d ends with d·offset ≤ 0; the other side is rounding: φ = d·f_c
                        after = place(base, offset if base * offset <= 0 else 0.0) if base else None
                        for sigma in (0.5 * f_c, 0.0, -0.5 * f_c):
                            where = f"{where_phi}, σ = {sigma!r}"
                            if at is not None:
                                judged += 1
                                want = table.expect(sigma, at, place.f_s)
                                fail = _compare("mode_at_rest", mode_at_rest(sigma, base, offset, f_c, tol, excess), want, where)
                                if fail:
                                    return Outcome.fail(fail)
                                reached.setdefault(f"base {base}", set()).add(want[3])
                            if after is not None:
                                judged += 1
                                want = table.expect(sigma, after, place.f_s)
                                got = mode_after_slip(sigma, offset, base, f_c, tol, excess)
                                fail = _compare("mode_after_slip", got, want, where + f", after a slip d = {base}")
                                if fail:
                                    return Outcome.fail(fail)
                                reached.setdefault(f"a slip d = {base}", set()).add(want[3])
                for key, need in _reachable(excess).items():
                    missing = sorted(need - reached.get(key, set()))
                    if missing:
                        return Outcome.fail(
                            f"f_c = {f_c!r}, f_s = f_c + {excess!r}, tol = {tol!r}: rows {missing} were never reached "
                            f"from {key}: the check would be vacuous for them"
                        )
    return Outcome(True, f"mode_at_rest and mode_after_slip equal the proved table at {judged} judged points "
                         f"(f_c ∈ {list(F_CS)}, f_s/f_c ∈ {[1 + r for r in EXCESS]}, snapping band {SNAP_ULPS:g} ulps)")


def _reachable(excess: float) -> dict[str, set[str]]:
    """Rows each base must reach, and each slip direction (where a slip can end: ``d·(φ - d f_c) ≤ 0``)."""
    at_rest = {"ii", "iii", "iv", "v", "vi", "vii", "viii", "ix", "x"}
    plus = {"vi", "vii", "viii", "ix", "x"} | ({"iii", "iv", "v"} if excess == 0 else set())
    minus = {"ii", "iii", "iv", "v", "vi"} | ({"vii", "viii", "ix"} if excess == 0 else set())
    return {"base -1": at_rest, "base 0": at_rest, "base 1": at_rest, "a slip d = 1": plus, "a slip d = -1": minus}


class _Placement:
    """Where the exact ``φ = base·f_c + offset`` lies against the band of each boundary ``s·f_s``."""

    def __init__(self, f_c: float, excess: float, tol: float) -> None:
        # exact rationals (fmpq, :func:`_q`); the widths also as Fractions, for their floats
        self.f_c, self.excess = _q(f_c), _q(excess)
        self.f_s = self.f_c + self.excess
        self.on = {s: s * self.f_s for s in (1, -1)}
        self.eps = _q(EPS)
        self.band_widths = {(b, s): band(b, s, f_c, excess, tol) for b in (-1, 0, 1) for s in (1, -1)}
        self.widths = {key: _q(w) for key, w in self.band_widths.items()}
        # the code's gap is (base - s)·f_c - s·excess (exact when excess = 0), then + offset: each sum
        # rounds to within ε/2 of its result; the band itself rounds within a few ε of its width
        self.terms = {
            (b, s): (abs(b - s) * self.f_c + self.excess if excess else _q(0)) + self.widths[b, s] * 8
            for b in (-1, 0, 1) for s in (1, -1)
        }

    def __call__(self, base: int, offset: float) -> tuple[int, Any, float] | None:
        """``(s, φ on s·f_s, s·excess)`` inside a band, ``(base, φ, offset)`` outside both; ``None`` where rounding decides."""
        phi = base * self.f_c + _q(offset)
        for s in (1, -1):
            gap = abs(phi - self.on[s])
            width = self.widths[base, s]
            slack = self.eps * (self.terms[base, s] + gap)
            if gap > width + slack:
                continue
            if gap > width - slack:
                return None
            return s, self.on[s], s * float(self.excess)
        return base, phi, offset


class _Table:
    """The proved table at ``v = 0``, memoised per class."""

    def __init__(self, rows: tuple[Any, ...]) -> None:
        self.rows = rows
        self.memo: dict[tuple[str, str], Any] = {}

    def expect(self, sigma: float, placed: tuple[int, Any, float], f_s: Any) -> tuple[int, float, int, str]:
        base, phi, offset = placed
        row = _row(self.rows, sigma, phi, f_s, self.memo)  # σ's class: a float compares with 0 exactly
        return base, offset, row.k, row.label


def _compare(name: str, got: Any, want: tuple[int, float, int, str], where: str) -> str | None:
    b, o, k = int(got[0]), float(got[1]), int(got[2])
    if k != want[2]:
        return f"{where}: {name} gives k = {k}, row ({want[3]}) of the proved table has k = {want[2]}"
    if b != want[0] or o != want[1]:
        return f"{where}: {name} keeps φ as {b}·f_c + {o!r}; expected {want[0]}·f_c + {want[1]!r} (row ({want[3]}))"
    return None
