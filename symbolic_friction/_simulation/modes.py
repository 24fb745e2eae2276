"""Mode selection at a state, following the table of the proof of Claim 1
(appendix, rows (i)–(xi)).

For an initial condition ``(σ̄, φ̄, v̄)`` the table names the affine system
``k ∈ {1, 0, -1}`` of eq. (subcasesAffine) whose solution is the solution of
the inclusion (eq. xDot) on some ``[0, T]``, ``T > 0``:

====== ==================================================== ====
row    initial condition                                    k
====== ==================================================== ====
(i)    ``v̄ > 0``                                            1
(ii)   ``v̄ = 0, φ̄ > f_c``                                   1
(iii)  ``v̄ = 0, φ̄ = f_c, σ̄ > 0``                            1
(iv)   ``v̄ = 0, φ̄ = f_c, σ̄ = 0``                            0
(v)    ``v̄ = 0, φ̄ = f_c, σ̄ < 0``                            0
(vi)   ``v̄ = 0, |φ̄| < f_c``                                 0
(vii)  ``v̄ = 0, φ̄ = -f_c, σ̄ > 0``                           0
(viii) ``v̄ = 0, φ̄ = -f_c, σ̄ = 0``                           0
(ix)   ``v̄ = 0, φ̄ = -f_c, σ̄ < 0``                           -1
(x)    ``v̄ = 0, φ̄ < -f_c``                                  -1
(xi)   ``v̄ < 0``                                            -1
====== ==================================================== ====

The comparisons in :func:`select_mode` are exact: with
:class:`~fractions.Fraction` input the boundaries ``φ = ±f_c`` and the edge
``σ = 0`` (rows (iv), (viii): points of the attractor 𝒜, i.e. equilibria) are
decided exactly.  Floating-point callers that reach ``v = 0`` by computation
use :func:`mode_at_rest` (and the simulation kernel's ``mode_after_slip``), which keep ``φ`` as an
exact boundary plus an offset and decide a ``φ`` within rounding of ``±f_c``
by ``σ``, as rows (iii)/(v)/(vii)/(ix) do, instead of by the sign of a
rounding error.
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "TABLE",
    "table_row",
    "select_mode",
    "mode_at_rest",
]

_EPS = 2.220446049250313e-16

TABLE: tuple[tuple[str, str, int], ...] = (
    ("i", "v > 0", 1),
    ("ii", "v = 0, phi > f_c", 1),
    ("iii", "v = 0, phi = f_c, sigma > 0", 1),
    ("iv", "v = 0, phi = f_c, sigma = 0", 0),
    ("v", "v = 0, phi = f_c, sigma < 0", 0),
    ("vi", "v = 0, |phi| < f_c", 0),
    ("vii", "v = 0, phi = -f_c, sigma > 0", 0),
    ("viii", "v = 0, phi = -f_c, sigma = 0", 0),
    ("ix", "v = 0, phi = -f_c, sigma < 0", -1),
    ("x", "v = 0, phi < -f_c", -1),
    ("xi", "v < 0", -1),
)
"""The appendix's table: ``(row, condition, k)``."""

_MODE_OF_ROW = {row: k for row, _, k in TABLE}


def table_row(sigma: Any, phi: Any, v: Any, f_c: Any, f_s: Any = None) -> str:
    """The row (``"i"`` … ``"xi"``) of the appendix's table that contains the state.

    With static friction ``f_s > f_c`` (``None``: ``f_s = f_c``, the paper's
    model) the rows at rest are read with the stick boundary ``±f_s`` in
    place of ``±f_c``: the mass at rest sticks while ``|φ| ≤ f_s`` and leaves
    ``φ = ±f_s`` when ``σ`` pushes it out (rows (iii), (ix)); a slip's
    kinetic friction stays ``f_c`` (eq. basic with ``f_s``).

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> table_row(F(0), F(1), F(0), F(1)), table_row(-1, 1, 0, 1), table_row(0, 0.5, 0, 1)
    ('iv', 'v', 'vi')
    """
    if f_s is not None:
        f_c = f_s  # the rows at rest compare φ with the stick boundary
    if v > 0:
        return "i"
    if v < 0:
        return "xi"
    if phi > f_c:
        return "ii"
    if phi < -f_c:
        return "x"
    if phi == f_c:
        return "iii" if sigma > 0 else "iv" if sigma == 0 else "v"
    if phi == -f_c:
        return "vii" if sigma > 0 else "viii" if sigma == 0 else "ix"
    return "vi"


def select_mode(sigma: Any, phi: Any, v: Any, f_c: Any, f_s: Any = None) -> int:
    """The mode ``k ∈ {1, 0, -1}`` that the table assigns to ``(σ, φ, v)``.

    ``1`` is slip with ``v > 0`` (``x' = Ax - b``), ``0`` is stick
    (``σ' = 0, φ' = σ, v' = 0``), ``-1`` is slip with ``v < 0``
    (``x' = Ax + b``).  Exact for exact (``Fraction``/``int``) input.

    Examples
    --------
    >>> select_mode(1, 1, 0, 1), select_mode(-1, 1, 0, 1), select_mode(-1, -1, 0, 1)
    (1, 0, -1)
    """
    return _MODE_OF_ROW[table_row(sigma, phi, v, f_c, f_s)]


def mode_at_rest(
    sigma: float, base: int, offset: float, f_c: float, tol: float, excess: float = 0.0
) -> tuple[int, float, int]:
    """The table's mode at ``v = 0`` for ``φ = base·f_c + offset``, with rounding decided by ``σ``.

    The state is kept as an exact boundary ``base ∈ {-1, 0, 1}`` plus an
    ``offset``, so that ``φ ∓ f_c`` is *exactly* ``offset`` when
    ``base = ±1``: after a slip ``φ - k f_c`` is what the closed form
    computes, and adding ``f_c`` first would lose it (a stick that follows a
    tiny slip would get its duration wrong by ``ε f_c/σ``).  ``φ`` within
    ``tol`` (the uncertainty of ``offset``, plus the rounding of adding
    ``±f_c``) of ``±f_c`` is put on the boundary, where ``σ`` decides as rows
    (iii)–(v) and (vii)–(ix) do.  With ``tol = 0`` and exact numbers this is
    exactly :func:`select_mode`.

    With static friction (``excess = f_s - f_c > 0``) the table is the same
    with the stick boundaries moved to ``φ = ±f_s`` (:func:`table_row` with
    ``f_s``): the mass sticks while ``|φ| ≤ f_s``; the boundary ``±f_s`` is
    kept as ``base = ±1`` plus ``offset = ±excess``.  ``excess = 0`` is the
    paper's model, computed with the very same operations.

    Returns
    -------
    base, offset : int, float
        ``(±1, 0)`` (``(±1, ±excess)``) if ``φ`` was put on ``±f_s``, else unchanged.
    mode : int
    """
    # Written without calls to other Python functions: the simulation kernel
    # compiles this very function (see ._kernel).
    gap_plus = offset - excess if base == 1 else (base - 1) * f_c - excess + offset  # φ - f_s
    gap_minus = offset + excess if base == -1 else (base + 1) * f_c + excess + offset  # φ + f_s
    # the uncertainty of k·f_c + offset when offset is known within tol, plus the rounding of ±f_c (and f_s - f_c)
    if abs(gap_plus) <= tol + 4.0 * _EPS * (abs(base - 1) * f_c + excess):
        return 1, 0.0 * offset + excess, 1 if sigma > 0 else 0  # rows (iii), (iv), (v)
    if abs(gap_minus) <= tol + 4.0 * _EPS * (abs(base + 1) * f_c + excess):
        return -1, 0.0 * offset - excess, -1 if sigma < 0 else 0  # rows (vii), (viii), (ix)
    if gap_plus > 0:
        return base, offset, 1  # row (ii)
    if gap_minus < 0:
        return base, offset, -1  # row (x)
    return base, offset, 0  # row (vi)
