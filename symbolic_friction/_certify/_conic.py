"""Small semidefinite programs written straight into Clarabel's conic form (the searches' solver; never a proof).

The sup-flow searches solve many SDPs with a handful of scalar unknowns whose
constraints come from the template's model functions (:mod:`._model.quadratic`,
:mod:`._model.sup_flow`), which use plain arithmetic.  :class:`Affine` is an
affine expression those functions compute with unchanged; :class:`Program`
collects ``M(x) ⪰ 0``, ``e(x) ≥ 0`` and copositivity (``M − εI = S + N``,
``S ⪰ 0``, ``N ≥ 0``: Diananda, exact for ``n ≤ 4``) and hands Clarabel the
matrices ``s = b − Ax ∈ K`` directly.  Building one costs about a millisecond,
where compiling the same problem through a modelling layer costs seconds.

What a solve returns is a candidate: every certificate it leads to is decided
by its template's exact verifier.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["Affine", "Program", "STATUS"]

STATUS = {"Solved": "optimal", "AlmostSolved": "optimal_inaccurate", "PrimalInfeasible": "infeasible",
          "AlmostPrimalInfeasible": "infeasible_inaccurate", "DualInfeasible": "unbounded",
          "AlmostDualInfeasible": "unbounded_inaccurate"}
"""Clarabel's statuses in the words the searches report (anything else: its own name, lower case)."""


class Affine:
    """``c + Σ a_k x_k``: a constant and a sparse map from variable index to coefficient."""

    __slots__ = ("const", "terms")

    def __init__(self, const: float = 0.0, terms: dict[int, float] | None = None) -> None:
        self.const = float(const)
        self.terms = terms or {}

    @staticmethod
    def _lift(other: Any) -> "Affine":
        return other if isinstance(other, Affine) else Affine(float(other))

    def __add__(self, other: Any) -> "Affine":
        other = self._lift(other)
        terms = dict(self.terms)
        for k, a in other.terms.items():
            terms[k] = terms.get(k, 0.0) + a
        return Affine(self.const + other.const, terms)

    __radd__ = __add__

    def __neg__(self) -> "Affine":
        return Affine(-self.const, {k: -a for k, a in self.terms.items()})

    def __sub__(self, other: Any) -> "Affine":
        return self + (-self._lift(other))

    def __rsub__(self, other: Any) -> "Affine":
        return self._lift(other) - self

    def __mul__(self, other: Any) -> "Affine":
        if isinstance(other, Affine):
            if other.terms and self.terms:
                raise TypeError("a product of two unknowns is not affine")
            scalar, expr = (other.const, self) if not other.terms else (self.const, other)
            return expr * scalar
        c = float(other)
        return Affine(self.const * c, {k: a * c for k, a in self.terms.items()})

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> "Affine":
        return self * (1.0 / float(other))


class Program:
    """Unknowns, cone constraints and a linear objective, solved by Clarabel."""

    def __init__(self) -> None:
        self.count = 0
        self._rows: list[tuple[str, int, list[Affine]]] = []  # (cone, size, entries of s = b − Ax)

    def variable(self) -> Affine:
        self.count += 1
        return Affine(0.0, {self.count - 1: 1.0})

    def nonneg(self, *exprs: Any) -> None:
        """Each ``e ≥ 0``."""
        self._rows.append(("nonneg", len(exprs), [Affine._lift(e) for e in exprs]))

    def psd(self, matrix: Any) -> None:
        """``M ⪰ 0`` for a symmetric ``M`` (its upper triangle, column by column, off-diagonals times √2)."""
        n = len(matrix)
        entries = [Affine._lift(matrix[i][j]) * (1.0 if i == j else math.sqrt(2.0)) for j in range(n) for i in range(j + 1)]
        self._rows.append(("psd", n, entries))

    def copositive(self, matrix: Any, mask: Any, margin: Any) -> None:
        """``M`` copositive with a margin.

        A row whose diagonal entry is structurally zero (``mask[i]`` false) is
        copositive only with non-negative off-diagonal entries, kept
        ``≥ margin``; the rest is ``M − margin·I = S + N``, ``S ⪰ 0``, ``N ≥ 0``.  (Writing the zero rows
        into ``S + N`` too would let an interior-point solver keep ``S_ii`` at
        its tolerance and a visibly negative ``S_ij`` beside it, which rounding
        then exposes.)
        """
        n = len(matrix)
        zero = [i for i in range(n) if not mask[i]]
        rest = [i for i in range(n) if mask[i]]
        for i in zero:
            self.nonneg(*(matrix[i][j] - margin for j in range(n) if j != i))
        if not rest:
            return
        off = {}
        for a in range(len(rest)):
            for b in range(a + 1, len(rest)):
                off[a, b] = off[b, a] = self.variable()
        self.nonneg(*(off[a, b] for a in range(len(rest)) for b in range(a + 1, len(rest))))
        self.psd([[matrix[i][j] - (margin if a == b else 0.0) - (off[a, b] if a != b else 0.0)
                   for b, j in enumerate(rest)] for a, i in enumerate(rest)])

    def solve(self, objective: Affine, *, maximize: bool = False) -> tuple[str, list[float]]:
        """``(status, x)``: minimise (or maximise) ``objective``; ``x`` is empty without a solution."""
        import clarabel
        import numpy as np
        import scipy.sparse as sparse

        order = {"nonneg": 0, "psd": 1}  # Clarabel takes the cones in the order given; group them
        rows = sorted(self._rows, key=lambda r: order[r[0]])
        data, row_index, col_index, b, cones = [], [], [], [], []
        r = 0
        for cone, size, entries in rows:
            for e in entries:
                for k, a in e.terms.items():
                    data.append(-a)
                    row_index.append(r)
                    col_index.append(k)
                b.append(e.const)
                r += 1
            cones.append(clarabel.NonnegativeConeT(size) if cone == "nonneg" else clarabel.PSDTriangleConeT(size))
        a_matrix = sparse.csc_matrix((data, (row_index, col_index)), shape=(r, self.count))
        q = np.zeros(self.count)
        for k, a in objective.terms.items():
            q[k] = -a if maximize else a
        settings = clarabel.DefaultSettings()
        settings.verbose = False
        try:
            solution = clarabel.DefaultSolver(sparse.csc_matrix((self.count, self.count)), q, a_matrix, np.array(b),
                                              cones, settings).solve()
        except BaseException as exc:  # a panic of the solver's Rust core (pyo3's PanicException) is not an Exception
            if isinstance(exc, (KeyboardInterrupt, SystemExit, GeneratorExit)):
                raise
            return f"solver error ({type(exc).__name__}: {' '.join(str(exc).split())})", []
        status = STATUS.get(str(solution.status), str(solution.status).lower())
        x = list(solution.x)
        if status not in ("optimal", "optimal_inaccurate") or not all(map(math.isfinite, x)):
            return status, []
        return status, x

    @staticmethod
    def value(expr: Affine, x: list[float]) -> float:
        """``expr`` at the solution ``x``."""
        return expr.const + sum(a * x[k] for k, a in expr.terms.items())
