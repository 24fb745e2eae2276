"""The one-piece sup-flow search: the whole flow bounded by one Lyapunov matrix, found in well under a second.

Beyond the paper.  For any ``P ≻ 0`` with ``AᵀP + PA ⪯ 0`` and ``P ⪰ pI``, the
friction-free flow satisfies ``|e^{At}w|² ≤ (1/p)|w|²_P`` for every ``t ≥ 0``
(the obligation ``sup_flow.exit``, tail at ``T = 0``), so ``g(w) ≤ wᵀ(P/p)w``
and ``sup_t ‖e^{At}‖₂² ≤ λ_max(P)/p``.  The ``P`` of smallest condition number
makes that ``c₂`` as small as one quadratic bound can be (about ``κ_lin²`` to
``4κ_lin²`` on stiff, slow and spread gains, where time pieces need thousands
of intervals); the sup-flow certificate is then one piece ``[0, ∞)``.

Nothing here is called proved.  The search:

1. minimises ``t`` subject to ``I ⪯ P ⪯ tI``, ``AᵀP + PA ⪯ 0`` (an SDP, Clarabel through :mod:`._conic`);
2. makes that ``P`` exactly a Lyapunov matrix (:func:`exact_lyapunov`: the rational ``P`` plus ``δX``, ``X`` the
   exact solution of ``AᵀX + XA = −I``), so the verifier's premise ``−(AᵀP + PA) ⪰ 0`` holds by construction
   and no solver tolerance reaches it;
3. takes ``p`` just below ``λ_min(P)`` and ``c₂`` just above ``λ_max(P)/p``, both checked exactly;
4. minimises ``γ`` over ``U`` with the exit forms' Gram ``P/p`` (the piece SDP of :mod:`.sup_flow_search`);
5. lets :func:`.sup_flow.verify_sup_flow` decide.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING, Any

from .._infra.errors import CertificateError, ParameterError
from .._model.parameters import Parameters

if TYPE_CHECKING:
    from .sup_flow import SupFlowCertificate

__all__ = ["certify_sup_flow_tail", "best_conditioned_lyapunov", "exact_lyapunov"]

SOLVER = "CLARABEL"
"""The solver of both SDPs (recorded in the provenance)."""


def best_conditioned_lyapunov(k: tuple[float, float, float]) -> Any:
    """A float ``P`` with ``I ⪯ P ⪯ tI`` and ``AᵀP + PA ⪯ 0`` of nearly least ``t`` (an SDP; a candidate only).

    Raises
    ------
    CertificateError
        If the SDP gives no solution.
    """
    import numpy as np

    from .._model.quadratic import lyapunov_rate_entries
    from ._conic import Program

    program = Program()
    entries = {(i, j): program.variable() for i in range(3) for j in range(i, 3)}
    p = tuple(tuple(entries[min(i, j), max(i, j)] for j in range(3)) for i in range(3))
    t = program.variable()
    program.psd([[p[i][j] - (1.0 if i == j else 0.0) for j in range(3)] for i in range(3)])
    program.psd([[(t if i == j else 0.0) - p[i][j] for j in range(3)] for i in range(3)])
    rate = lyapunov_rate_entries(k[0], k[1], k[2], p)
    program.psd([[-rate[i][j] for j in range(3)] for i in range(3)])
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
    eye = tuple(tuple(Fraction(int(i == j)) for j in range(3)) for i in range(3))
    x = _solve_lyapunov(k, eye)
    low = float(np.linalg.eigvalsh(np.array(q0, dtype=float))[0])
    delta = Fraction(max(-low, 0.0)) * Fraction(11, 10)
    step = max(delta, Fraction(abs(float(q0[2][2])) or 1.0) * Fraction(1, 10**15))
    for _ in range(200):
        rows = tuple(tuple(q0[i][j] + (delta if i == j else 0) for j in range(3)) for i in range(3))
        if all(d >= 0 for _, d in Semidefinite("", "", rows).minors()):
            return tuple(tuple(p0[i][j] + delta * x[i][j] for j in range(3)) for i in range(3))
        delta, step = delta + step, step * 2
    raise CertificateError("cannot make −(AᵀP + PA) positive semidefinite exactly")


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


def _c2_above(p_matrix: tuple[tuple[Fraction, ...], ...], p: Fraction, estimate: float) -> Fraction:
    """A decimal ``c₂`` with ``c₂I − P/p ≻ 0`` exactly (leading principal minors positive)."""
    from .rounding import round_significant
    from .verify import Semidefinite

    c2 = round_significant(estimate * (1 + 1e-9), 12, direction="up")
    for _ in range(200):
        rows = tuple(tuple((c2 if i == j else 0) - p_matrix[i][j] / p for j in range(3)) for i in range(3))
        if all(d > 0 for _, d in Semidefinite("", "", rows).minors()):
            return c2
        c2 *= Fraction(1001, 1000)
    raise CertificateError("cannot bound λ_max(P)/p above")


def certify_sup_flow_tail(params: Parameters, *, label: str = "") -> "SupFlowCertificate":
    """Search, round and exactly verify a one-piece sup-flow certificate (the tail's own ``P`` at ``T = 0``).

    Parameters
    ----------
    params : Parameters
        Gains satisfying Assumption 1, ``f_s = f_c``.
    label : str, keyword-only
        Written into the provenance.

    Raises
    ------
    ParameterError
        If ``params`` has static friction above Coulomb.
    CertificateError
        If an SDP fails or the rounded constants do not verify.

    Examples
    --------
    >>> cert = certify_sup_flow_tail(Parameters(k_p=1000, k_i="1/1000", k_v=1000, f_c=1))
    >>> len(cert.pieces), cert.own_tail, float(cert.overshoot_bound) < 2 * 1.4143
    (1, True, True)
    """
    import numpy as np

    from .rounding import sqrt_decimal_up
    from .sup_flow import TAIL_CONSTANTS, SupFlowCertificate, SupFlowPiece, SupFlowProvenance, verify_sup_flow
    from .sup_flow_search import MARGIN, _p_below, _PieceProblem, rounded_constants

    if params.stiction:
        raise ParameterError(f"a stability certificate is for the paper's model f_s = f_c; got f_s = {params.f_s} > f_c = {params.f_c}")
    k_p, k_i, k_v, _ = params.as_floats()
    if not all(np.isfinite(x) and 0 < x < 1e150 for x in (k_p, k_i, k_v)):
        raise CertificateError(f"the gains of {params} are beyond the range of the floats the SDPs work in")
    p_exact = exact_lyapunov((params.k_p, params.k_i, params.k_v), best_conditioned_lyapunov((k_p, k_i, k_v)))
    p_float = np.array(p_exact, dtype=float)
    eig = np.linalg.eigvalsh(p_float)
    p = _p_below(p_exact, float(eig[0]))
    c2_floor = _c2_above(p_exact, p, float(eig[-1]) / float(p))
    gram = p_float / float(p)
    problem = _PieceProblem((k_p, k_i, k_v), first=True, grams=1)
    values, status = None, ""
    for margin in (MARGIN, MARGIN * 10, MARGIN * 100):
        status, values = problem.solve([gram], margin)
        if status == "optimal" and values:
            break
    else:
        raise CertificateError(f"no one-piece sup-flow certificate for {params}: the SDP for U is {status} at every margin tried")
    piece = SupFlowPiece(start=Fraction(0), end=None, constants=rounded_constants(values))
    kappa_sq = max(c2_floor, piece.constants["gamma"])
    tail = {name: p_exact[int(name[-2]) - 1][int(name[-1]) - 1] for name in TAIL_CONSTANTS}
    certificate = SupFlowCertificate(
        k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_c=params.f_c, constants={"c2": kappa_sq, "p": p, **tail},
        pieces=(piece,), overshoot_bound=sqrt_decimal_up(kappa_sq),
        provenance=SupFlowProvenance(search="sdp", solver=SOLVER, solver_status="optimal",
                                     margin=str(Fraction(MARGIN).limit_denominator(10**12)), label=label),
    )
    report = verify_sup_flow(certificate)
    if not report.proved:
        raise CertificateError(f"no one-piece sup-flow certificate for {params} verifies exactly: "
                               + "; ".join(check.message for check in report.failures[:4]))
    return certificate
