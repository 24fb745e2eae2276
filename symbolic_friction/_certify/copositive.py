"""Exact copositivity of small symmetric rational matrices: ``yᵀMy ≥ 0`` for every ``y ≥ 0``.

The quadratic template's premises are quadratic forms in the nonnegative
vector ``y = (|σ|, |dz(φ)|, |v|)``, so they need copositivity, not
semidefiniteness.  For ``n ≤ 3`` it is decided by Hadeler's criterion
(K. P. Hadeler, *On copositive matrices*, Linear Algebra Appl. 49, 1983):

* ``n = 1``: ``a ≥ 0``;
* ``n = 2``: ``a₁₁ ≥ 0``, ``a₂₂ ≥ 0`` and ``a₁₂ ≥ −√(a₁₁a₂₂)``, i.e.
  ``a₁₂ ≥ 0`` or ``a₁₂² ≤ a₁₁a₂₂`` (exact in rationals);
* ``n = 3``: every 2×2 principal submatrix copositive and
  ``√(a₁₁a₂₂a₃₃) + a₁₂√a₃₃ + a₁₃√a₂₂ + a₂₃√a₁₁ + √(2ā₁₂ā₁₃ā₂₃) ≥ 0`` with
  ``āᵢⱼ = aᵢⱼ + √(aᵢᵢaⱼⱼ)``.

The last inequality has square roots of rationals.  It is decided first by the
exact sufficient tests (every off-diagonal entry ``≥ 0``; every principal minor
``≥ 0``, i.e. positive semidefinite), then in arb balls (python-flint) with
outward rounding at increasing precision: a ball strictly above 0 proves it, a
ball strictly below 0 refutes it, and a ball that still contains 0 at the
highest precision is *undecided*, which the verifier reports as not proved.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from fractions import Fraction
from typing import Sequence

from .verify import _det  # the verifier's cofactor determinant, in the entries' own arithmetic

__all__ = ["CopositivityDecision", "decide_copositive", "PRECISIONS"]

PRECISIONS: tuple[int, ...] = (128, 512, 2048)
"""Working precisions (bits) of the arb evaluation of Hadeler's 3×3 inequality."""


@dataclass(frozen=True)
class CopositivityDecision:
    """The verdict on one matrix and the reason, e.g. ``"a₁₂ = −3 < −√(a₁₁a₂₂)"``.

    ``holds`` is True (copositive), False (a witness of the contrary) or None (undecided).
    """

    holds: bool | None
    reason: str


def _pair(a: Fraction, b: Fraction, c: Fraction) -> bool:
    """``[[a, b], [b, c]]`` copositive (``a, c ≥ 0`` checked by the caller)."""
    return b >= 0 or b * b <= a * c


def decide_copositive(matrix: Sequence[Sequence[Fraction]]) -> CopositivityDecision:
    """Decide whether the symmetric rational ``matrix`` (``n ≤ 3``) is copositive.

    Raises
    ------
    ValueError
        If the matrix is not square, not symmetric, larger than 3×3, or not exact.
    """
    m = [list(row) for row in matrix]
    n = len(m)
    if not 1 <= n <= 3 or any(len(row) != n for row in m):
        raise ValueError(f"copositivity is decided for square matrices up to 3×3; got {n} rows")
    for row in m:
        for x in row:
            if isinstance(x, bool) or not isinstance(x, (int, Fraction)):
                raise ValueError(f"copositivity is decided for exact rationals only; got {type(x).__name__} {x!r}")
    m = [[x if type(x) is Fraction else Fraction(x) for x in row] for row in m]  # a Fraction is kept (immutable)
    if any(m[i][j] != m[j][i] for i in range(n) for j in range(n)):
        raise ValueError("copositivity is decided for symmetric matrices only")
    for i in range(n):
        if m[i][i] < 0:
            return CopositivityDecision(False, f"diagonal entry {i + 1} is {m[i][i]} < 0 (y = e{i + 1})")
    for i, j in itertools.combinations(range(n), 2):
        if not _pair(m[i][i], m[i][j], m[j][j]):
            return CopositivityDecision(
                False, f"entry ({i + 1},{j + 1}) = {m[i][j]} < −√({m[i][i]}·{m[j][j]}) (a nonnegative y on that face)"
            )
    if n < 3:
        return CopositivityDecision(True, "Hadeler's conditions hold exactly")
    if all(m[i][j] >= 0 for i in range(n) for j in range(n)):
        return CopositivityDecision(True, "every entry ≥ 0")
    minors = [_det([[m[i][j] for j in idx] for i in idx]) for k in (1, 2, 3) for idx in itertools.combinations(range(3), k)]
    if all(d >= 0 for d in minors):
        return CopositivityDecision(True, "positive semidefinite (every principal minor ≥ 0)")
    return _hadeler_3(m)


def _hadeler_3(m: list[list[Fraction]]) -> CopositivityDecision:
    import flint

    for bits in PRECISIONS:
        old = flint.ctx.prec
        flint.ctx.prec = bits
        try:
            a = [[flint.arb(x.numerator) / x.denominator for x in row] for row in m]
            root = [a[i][i].sqrt() for i in range(3)]
            bar = {(i, j): a[i][j] + root[i] * root[j] for i, j in ((0, 1), (0, 2), (1, 2))}
            product = 2 * bar[0, 1] * bar[0, 2] * bar[1, 2]
            # each ā ≥ 0 exactly (checked above), so the product is ≥ 0; a ball that straddles 0 is
            # rounding only, and √ of it is enclosed in [0, √upper]
            if product > 0:
                tail = product.sqrt()
            else:
                high = flint.arb(product.upper()).sqrt().upper()
                tail = flint.arb(high / 2, high / 2)
            total = root[0] * root[1] * root[2] + a[0][1] * root[2] + a[0][2] * root[1] + a[1][2] * root[0] + tail
            if total > 0:
                return CopositivityDecision(True, f"Hadeler's 3×3 inequality holds: {total.str(5, radius=False)} > 0 (arb, {bits} bits)")
            if total < 0:
                return CopositivityDecision(False, f"Hadeler's 3×3 inequality fails: {total.str(5, radius=False)} < 0 (arb, {bits} bits)")
        finally:
            flint.ctx.prec = old
    return CopositivityDecision(None, f"Hadeler's 3×3 inequality is undecided at {PRECISIONS[-1]} bits (the ball contains 0)")
