"""The tail's own Lyapunov matrix for the sup-flow template: found in floats, made exact (search side, never a proof).

Any ``P ≻ 0`` with ``AᵀP + PA ⪯ 0`` bounds the friction-free flow:
``|e^{At}w|² ≤ (1/p)|w|²_P`` for ``P ⪰ pI`` and every ``t ≥ 0`` (the
obligation ``sup_flow.exit``).  :func:`best_conditioned_lyapunov` finds the
``P`` of nearly least condition number (an SDP); :func:`exact_lyapunov` turns a
float ``P`` into an exact rational one for which ``−(AᵀP + PA) ⪰ 0`` holds
exactly, so no solver tolerance reaches the verifier's premise.
"""

from __future__ import annotations

import functools
from fractions import Fraction
from typing import Any

from .._infra.errors import CertificateError

__all__ = ["lyapunov_constraints", "best_conditioned_lyapunov", "exact_lyapunov"]


def lyapunov_constraints(program: Any, k: tuple[float, float, float]) -> tuple[Any, Any]:
    """Add ``I ⪯ P ⪯ tI`` and ``AᵀP + PA ⪯ 0`` to ``program`` (:mod:`._conic`); returns ``(P's rows, t)``."""
    from .._model.quadratic import lyapunov_rate_entries

    entries = {(i, j): program.variable() for i in range(3) for j in range(i, 3)}
    p = tuple(tuple(entries[min(i, j), max(i, j)] for j in range(3)) for i in range(3))
    t = program.variable()
    program.psd([[p[i][j] - (1.0 if i == j else 0.0) for j in range(3)] for i in range(3)])
    program.psd([[(t if i == j else 0.0) - p[i][j] for j in range(3)] for i in range(3)])
    rate = lyapunov_rate_entries(k[0], k[1], k[2], p)
    program.psd([[-rate[i][j] for j in range(3)] for i in range(3)])
    return p, t


def best_conditioned_lyapunov(k: tuple[float, float, float]) -> Any:
    """A float ``P`` with ``I ⪯ P ⪯ tI`` and ``AᵀP + PA ⪯ 0`` of nearly least ``t`` (an SDP; a candidate only).

    Raises
    ------
    CertificateError
        If the SDP gives no solution.
    """
    import numpy as np

    from ._conic import Program

    program = Program()
    p, t = lyapunov_constraints(program, k)
    status, x = program.solve(t)
    if not x:
        raise CertificateError(f"the SDP for the tail's P is {status}")
    return np.array([[Program.value(p[i][j], x) for j in range(3)] for i in range(3)])


def exact_lyapunov(k: tuple[Fraction, Fraction, Fraction], p_float: Any) -> tuple[tuple[Fraction, ...], ...]:
    """An exact rational ``P`` near ``p_float`` with ``−(AᵀP + PA)`` positive semidefinite, exactly.

    ``P₀`` is ``p_float`` in rationals; ``Q₀ = −(AᵀP₀ + P₀A)`` misses
    semidefiniteness by the solver's tolerance at most.  With ``X`` the exact
    solution of ``AᵀX + XA = −I`` (unique: ``A`` is Hurwitz under Assumption
    1), ``P = P₀ + δX`` has ``−(AᵀP + PA) = Q₀ + δI``, and ``δ`` is raised
    from ``−λ_min(Q₀)`` until that is positive semidefinite by its principal
    minors.  (Rebuilding ``P`` from a corrected ``Q`` instead would divide the
    tolerance by the slowest decay rate: on a slow flow, a large change.)
    """
    import numpy as np

    from .verify import Semidefinite

    p0 = tuple(tuple(Fraction(float(p_float[min(i, j), max(i, j)])) for j in range(3)) for i in range(3))
    q0 = tuple(tuple(-x for x in row) for row in _rate(k, p0))
    x = _unit_solution(tuple(k)) if all(type(q) is Fraction for q in k) else _solve_lyapunov(k, _EYE)
    low = float(np.linalg.eigvalsh(np.array(q0, dtype=float))[0])
    delta = Fraction(max(-low, 0.0)) * Fraction(11, 10)
    step = max(delta, Fraction(abs(float(q0[2][2])) or 1.0) * Fraction(1, 10**15))
    for _ in range(200):
        rows = tuple(tuple(q0[i][j] + (delta if i == j else 0) for j in range(3)) for i in range(3))
        if all(d >= 0 for _, d in Semidefinite("", "", rows).minors()):
            return tuple(tuple(p0[i][j] + delta * x[i][j] for j in range(3)) for i in range(3))
        delta, step = delta + step, step * 2
    raise CertificateError("cannot make −(AᵀP + PA) positive semidefinite exactly")


@functools.lru_cache(maxsize=16)
def _unit_solution(k: tuple[Fraction, Fraction, Fraction]) -> tuple[tuple[Fraction, ...], ...]:
    """``X`` with ``AᵀX + XA = −I`` (:func:`_solve_lyapunov`) for exact gains, kept for the last gains asked: a
    one-piece search makes six candidate ``P`` exact for the same gains, each with this ``X`` (a value of the gains
    alone, immutable)."""
    return _solve_lyapunov(k, _EYE)


_EYE = tuple(tuple(Fraction(int(i == j)) for j in range(3)) for i in range(3))


def _rate(k: tuple[Fraction, Fraction, Fraction], p: Any) -> Any:
    from .._model.quadratic import lyapunov_rate_entries

    return lyapunov_rate_entries(k[0], k[1], k[2], p)


def _solve_lyapunov(k: tuple[Fraction, Fraction, Fraction], q: Any) -> tuple[tuple[Fraction, ...], ...]:
    """The symmetric ``P`` with ``AᵀP + PA = −Q``, in exact rationals (six linear equations, python-flint)."""
    import flint

    index = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
    columns = []
    for i, j in index:
        basis = tuple(tuple(Fraction(int((r, c) in ((i, j), (j, i)))) for c in range(3)) for r in range(3))
        rate = _rate(k, basis)
        columns.append([rate[r][c] for r, c in index])
    system = flint.fmpq_mat(6, 6, [_fmpq(columns[c][r]) for r in range(6) for c in range(6)])
    rhs = flint.fmpq_mat(6, 1, [_fmpq(-q[r][c]) for r, c in index])
    try:
        solution = system.solve(rhs)
    except ZeroDivisionError:
        raise CertificateError("AᵀP + PA = −Q has no unique solution (A is not Hurwitz)") from None
    entries = {ij: Fraction(int(solution[n, 0].p), int(solution[n, 0].q)) for n, ij in enumerate(index)}
    return tuple(tuple(entries[(min(i, j), max(i, j))] for j in range(3)) for i in range(3))


def _fmpq(q: Fraction) -> Any:
    import flint

    return flint.fmpq(q.numerator, q.denominator)
