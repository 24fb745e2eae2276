"""The sup-flow exit forms in arb, as :func:`._model.sup_flow.exit_forms` computes them, without its products of zeros.

The verifier (:mod:`.sup_flow_enclosure`) evaluates the exit forms on every part of every bisection, and the
model's function builds each of their entries as a sum of nine products, of which eight have an exact zero
factor.  :func:`exit_forms` computes the one product that is not zero, as the model does, read off the model's
own functions (:func:`_exit_plan`), so the model stays the one definition and every ball is the model's, bit
for bit.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from .._model import sup_flow as model

__all__ = ["exit_forms"]


def _arb(q: Fraction) -> Any:
    from .flow_bound import _arb as arb

    return arb(Fraction(q))


def exit_forms(k: Any, gram: Any, s: int) -> Any:
    """:func:`._model.sup_flow.exit_forms` of ``(k, gram, s)`` in arb, without its products of exact zeros.

    Each entry of the model's forms is one entry ``K_ij`` minus one product ``d·G_mn·d'`` of exit-map
    entries ``d, d' = ±1`` (the exit maps select coordinates and flip signs) plus products with exact
    zeros: :func:`_exit_plan` reads which ones off the model's functions themselves, on exact unit
    matrices, so the model stays the one definition.  ``K_ij − (d·G_mn)·d'`` is computed here as the model
    computes it, and the exact zeros the model adds change no ball, so every entry is the model's ball,
    bit for bit.  A gram with a non-finite entry (where ``0·x`` is not 0), or a model whose forms are not
    of that shape, is evaluated by the model's function itself.
    """
    plan = _exit_plan(s)
    if plan is None or not _finite(gram):
        return model.exit_forms(k, gram, _sign(s))
    unit = {1: _sign(1), -1: _sign(-1)}
    return [[[k[i][j] - unit[da] * gram[m][n] * unit[db] for i, j, m, n, da, db in row] for row in form] for form in plan]


def _finite(gram: Any) -> bool:
    try:
        return all(x.is_finite() for row in gram for x in row)
    except AttributeError:  # not arb balls: the model's function decides
        return False


_PLANS: dict[tuple[Any, ...], Any] = {}
_SIGNS: dict[tuple[int, int], Any] = {}


def _sign(s: int) -> Any:
    """``s`` as an arb ball at the working precision (kept: the forms take it on every call)."""
    import flint

    key = (s, flint.ctx.prec)
    if key not in _SIGNS:
        _SIGNS[key] = _arb(Fraction(s))
    return _SIGNS[key]


def _exit_plan(s: int) -> Any:
    """Per exit form and entry, ``(i, j, m, n, d, d')`` with entry ``= K_ij − d·G_mn·d'`` (:func:`exit_forms`),
    or ``None`` if the model's forms are not of that shape (its function is then evaluated on every call).

    Kept per sign and per the model's functions themselves: a model function replaced in this process (a test's
    patch) is read again, never answered for by the plan of the one it replaced.
    """
    key = (s, model.exit_forms, model.exit_map, model.EXIT_PLANES)
    if key not in _PLANS:
        if len(_PLANS) >= 64:
            _PLANS.clear()
        try:
            _PLANS[key] = _trace_exit_forms(s)
        except Exception:  # a model that cannot be read on exact rationals: its function is evaluated every time
            _PLANS[key] = None
    return _PLANS[key]


def _trace_exit_forms(s: int) -> Any:
    """The plan of :func:`_exit_plan`, from :func:`._model.sup_flow.exit_forms` and ``exit_map`` on exact rationals.

    ``exit_forms`` is affine in ``(K, G)``: its value at ``0`` and at each unit matrix gives each entry's
    coefficients; an entry must have exactly one ``K_ij`` (coefficient 1) and one ``G_mn`` whose
    coefficient is the product of the exit map's entries ``d_ma·d_nb`` (each ``±1``).  A generic point
    checks the affine reading.
    """
    zero = Fraction(0)
    nothing = ((zero,) * 3,) * 3
    cells = [(i, j) for i in range(3) for j in range(3)]

    def unit(i: int, j: int) -> Any:
        return tuple(tuple(Fraction(int((r, c) == (i, j))) for c in range(3)) for r in range(3))

    sign = Fraction(s)
    of_k = {ij: model.exit_forms(unit(*ij), nothing, sign) for ij in cells}
    of_g = {mn: model.exit_forms(nothing, unit(*mn), sign) for mn in cells}
    constant = model.exit_forms(nothing, nothing, sign)
    if len(constant) != len(model.EXIT_PLANES):
        return None
    plan = []
    for f, form in enumerate(constant):
        d = model.exit_map(model.EXIT_PLANES[f], sign)
        rows = []
        for a, row in enumerate(form):
            entries = []
            for b, value in enumerate(row):
                ks = [ij for ij, out in of_k.items() if out[f][a][b] != 0]
                gs = [mn for mn, out in of_g.items() if out[f][a][b] != 0]
                if value != 0 or len(ks) != 1 or of_k[ks[0]][f][a][b] != 1 or len(gs) != 1:
                    return None
                (i, j), (m, n) = ks[0], gs[0]
                da, db = d[m][a], d[n][b]
                if da not in (1, -1) or db not in (1, -1) or of_g[m, n][f][a][b] != -da * db:
                    return None
                entries.append((i, j, m, n, int(da), int(db)))
            rows.append(tuple(entries))
        plan.append(tuple(rows))
    k = tuple(tuple(Fraction(2 * r + 3, 7 + c) for c in range(3)) for r in range(3))
    g = tuple(tuple(Fraction(5 + r * c, 3 + r + 2 * c) for c in range(3)) for r in range(3))
    expected = tuple(tuple(tuple(k[i][j] - da * g[m][n] * db for i, j, m, n, da, db in row) for row in form) for form in plan)
    if tuple(tuple(tuple(row) for row in form) for form in model.exit_forms(k, g, sign)) != expected:
        return None
    return tuple(plan)
