"""What one piece of a sup-flow search holds: version 1 or version 2 of the format (floats; never a proof).

:class:`Layout` writes a piece's premises into an SDP (:mod:`._conic`) from the template's model functions
(:mod:`._model.quadratic`, :mod:`._model.sup_flow`), the same ones the exact verifiers of :mod:`.sup_flow`
and :mod:`.sup_flow_v2` decide, and takes a float look at its exit forms.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from .._model import quadratic as quad
from .._model import sup_flow as model

__all__ = ["ELL", "LAYOUTS", "Layout", "piece_constraints"]


ELL = (Fraction(1, 1000), Fraction(0), Fraction(1, 1000))
"""The friction-drag split's ``ℓ`` of a version-2 search (float floors: ``docs/design/sup_flow_v2.md``)."""


@dataclass(frozen=True)
class Layout:
    """What one piece of a search holds: version 1 (one ``K``, ``K₁₂ = 0``) or version 2 (``K⁺``, ``K⁻``, ``ℓ``).

    Version 2's premises are those of :mod:`.sup_flow_v2`; ``ℓ = 0`` drops the friction-drag split.
    """

    version: int = 2
    ell: tuple[Fraction, Fraction, Fraction] = ELL

    @property
    def title(self) -> str:
        if self.version == 1:
            return "version 1"
        return "version 2, " + ("ℓ = (" + ", ".join(str(x) for x in self.ell) + ")" if self.drag else "no drag split")

    @property
    def names(self) -> tuple[str, ...]:
        if self.version == 1:
            return ("k11", "k13", "k22", "k23", "k33", "gamma")
        from .sup_flow_v2 import PIECE_CONSTANTS

        return PIECE_CONSTANTS

    @property
    def drag(self) -> bool:
        return self.version == 2 and any(self.ell)

    def forms(self, values: Any) -> list[tuple[float, Any]]:
        """``(s, K)`` per sign from the piece's unknowns or numbers (in :attr:`names` order, or a dict)."""
        v = values if isinstance(values, dict) else dict(zip(self.names, values))
        if self.version == 1:
            k = quad.u_matrix_entries(v["k11"], v["k13"], v["k22"], v["k23"], v["k33"])
            return [(1.0, k), (-1.0, k)]
        return [(float(s), quad.u_matrix_signed(*(v[tag + e] for e in ("11", "12", "13", "22", "23", "33"))))
                for s, tag in ((1, "kp"), (-1, "km"))]

    def drag_maps(self) -> dict[float, Any]:
        """``{s: D_ℓ}`` in floats (empty without the drag split)."""
        if not self.drag:
            return {}
        ell = tuple(float(x) for x in self.ell)
        return {float(s): model.drag_exit_map(float(s), ell) for s in (1, -1)}

    def constraints(self, program: Any, k: tuple[float, float, float], variables: list[Any], *, first: bool,
                    margin: float) -> tuple[list[tuple[float, Any]], Any]:
        """The piece's premises on its forms and ``γ`` (:func:`piece_constraints` for version 1)."""
        if self.version == 1:
            rows, gamma = piece_constraints(program, k, variables, first=first, margin=margin)
            return [(1.0, rows), (-1.0, rows)], gamma
        k_p, k_i, k_v = k
        gamma = variables[-1]
        forms = self.forms(variables)
        ell = tuple(float(x) for x in self.ell)
        eps = margin * max(1.0, k_p, k_i, k_v, k_i / k_v, k_v / k_i)
        eye = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
        for s, rows in forms:
            b = quad.slip_rate_entries(k_p, k_i, k_v, s)
            program.nonneg(rows[0][1] * s, rows[0][2] - eps, rows[1][2] - eps, rows[2][2] - eps)
            program.copositive(quad.drag_rate_entries(rows, b, ell), [1, 1, 1], eps)
            program.copositive(quad.drag_band_entries(k_i, k_v, rows, s, ell), [1 if ell[0] else 0, 1], eps)
            program.copositive(tuple(tuple(gamma * eye[i][j] - rows[i][j] for j in range(3)) for i in range(3)), [1, 1, 1], eps)
            if first:
                program.copositive(tuple(tuple(rows[i][j] - eye[i][j] for j in range(3)) for i in range(3)), [1, 1, 1], eps)
        program.copositive(model.coupling_block(forms[0][1], forms[1][1]), [1, 1], eps)
        return forms, gamma

    def exits(self, program: Any, forms: list[tuple[float, Any]], gram: Any, margin: Any) -> None:
        """``U^s ≥ wᵀGw`` on both exit planes and (with the drag split) on ``f = ℓᵀy``, each form its own sign."""
        maps = self.drag_maps()
        for s, rows in forms:
            for form in model.exit_forms(rows, gram, s):
                program.copositive(form, [1, 1], margin)
            if s in maps:
                program.copositive(model.pullback_gap(rows, gram, maps[s]), [1, 1, 1], margin)

    def exit_ok(self, values: dict[str, float], gram: Any) -> bool:
        """Every exit form of the piece's float forms copositive with a little room at ``gram`` (a float look)."""
        maps = self.drag_maps()
        for s, k in self.forms(values):
            forms = list(model.exit_forms(k, gram, s)) + ([model.pullback_gap(k, gram, maps[s])] if s in maps else [])
            for form in forms:
                if not _float_copositive(form):
                    return False
        return True


LAYOUTS = tuple(Layout(ell=(q, Fraction(0), q)) for q in (Fraction(0), Fraction(1, 1000), Fraction(1, 10)))
"""What the one-piece search tries: version 2 without the friction-drag split, then with ``ℓ = (q, 0, q)`` for a
small and a larger ``q`` (a larger ``ℓ`` helps the rate forms more and costs more in ``c₂`` and the drag exit;
which wins depends on the gains: ``tests/benchmarks/bench_tightness.py``)."""


def _float_copositive(form: Any) -> bool:
    """A float look at copositivity with a little room: Hadeler's criterion (2×2 and 3×3; never a proof)."""
    import math

    n = len(form)
    m = [[float(form[i][j]) for j in range(n)] for i in range(n)]
    room = 1e-9 * max(1.0, *(abs(m[i][i]) for i in range(n)))
    if any(m[i][i] < room for i in range(n)):
        return False
    bar = {}
    for i in range(n):
        for j in range(i + 1, n):
            root = math.sqrt(m[i][i] * m[j][j])
            if m[i][j] < -root * (1 - 1e-7):
                return False
            bar[i, j] = m[i][j] + root
    if n == 2 or all(m[i][j] >= 0 for i in range(3) for j in range(i + 1, 3)):
        return True
    r = [math.sqrt(m[i][i]) for i in range(3)]
    total = (r[0] * r[1] * r[2] + m[0][1] * r[2] + m[0][2] * r[1] + m[1][2] * r[0]
             + math.sqrt(max(0.0, 2 * bar[0, 1] * bar[0, 2] * bar[1, 2])))
    return total >= room * r[0] * r[1] * r[2] / max(r)


def piece_constraints(program: Any, k: tuple[float, float, float], variables: list[Any], *, first: bool,
                      margin: float) -> tuple[Any, Any]:
    """Add a piece's premises on ``K`` and ``γ`` to ``program`` (:mod:`._conic`): ``U`` nonincreasing on ``R̂``
    (the quadratic template's rate, band and ``K₃ⱼ ≥ 0`` premises), ``γI − K`` and, on the first piece, ``K − I``
    copositive, each with ``margin`` scaled by the gains.  ``variables`` are ``k11, k13, k22, k23, k33, γ``;
    returns ``(K's rows, γ)``."""
    k_p, k_i, k_v = k
    k11, k13, k22, k23, k33, gamma = variables
    rows = quad.u_matrix_entries(k11, k13, k22, k23, k33)
    eps = margin * max(1.0, k_p, k_i, k_v, k_i / k_v, k_v / k_i)
    program.nonneg(k13 - eps, k23 - eps, k33 - eps)
    for s in (1.0, -1.0):
        b = quad.slip_rate_entries(k_p, k_i, k_v, s)
        program.copositive(quad.u_rate_entries(rows, b), [0, 1, 1], eps)
        program.copositive(quad.band_rate_entries(k_i, k_v, rows, s), [0, 1], eps)
    eye = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    program.copositive(tuple(tuple(gamma * eye[i][j] - rows[i][j] for j in range(3)) for i in range(3)), [1, 1, 1], eps)
    if first:
        program.copositive(tuple(tuple(rows[i][j] - eye[i][j] for j in range(3)) for i in range(3)), [1, 1, 1], eps)
    return rows, gamma
