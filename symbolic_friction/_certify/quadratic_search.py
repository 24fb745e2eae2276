"""Search for a quadratic-template certificate: an SDP, then exact rounding (the verifier decides).

The SDP (cvxpy, Clarabel) minimises ``max(c₂, γ)`` over ``P₁₁, P₂₂, P₃₃``,
``c``, ``K`` (``K₁₂ = 0``) and ``γ`` subject to the premises of
:func:`._certify.quadratic.quadratic_premises`, each copositive premise written
as ``M = S + N`` with ``S ⪰ 0`` and ``N ≥ 0`` entrywise (exact for ``n ≤ 3``,
Diananda's theorem), with a relative margin so that the rounded constants
keep every strict inequality.  Its numbers are rounded to decimals of
:data:`DIGITS` significant digits; nothing here is called proved.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING

from .._infra.errors import CertificateError, ParameterError
from .._model import quadratic as model
from .._model.parameters import Parameters

if TYPE_CHECKING:
    from .quadratic import QuadraticCertificate

__all__ = ["certify_quadratic", "MARGINS", "DIGITS"]

DIGITS = 12
"""Significant digits kept from the solver's numbers."""
MARGINS: tuple[float, ...] = (1e-7, 1e-6, 1e-5, 1e-4)
"""Relative margins tried in turn until the rounded constants verify."""
SOLVER = "CLARABEL"


def _solve(params: Parameters, margin: float):
    import cvxpy as cp
    import numpy as np

    k_p, k_i, k_v, _ = params.as_floats()
    p11, p22, p33, c, c2, gamma, z = (cp.Variable() for _ in range(7))
    k11, k13, k22, k23, k33 = (cp.Variable() for _ in range(5))
    P = cp.bmat([list(row) for row in model.quadratic_p_entries(k_p, k_i, k_v, p11, p22, p33)])
    K = cp.bmat([list(row) for row in model.u_matrix_entries(k11, k13, k22, k23, k33)])
    Q = cp.bmat([list(row) for row in model.lyapunov_rate_entries(k_p, k_i, k_v, tuple(tuple(P[i, j] for j in range(3)) for i in range(3)))])
    eye, e3 = np.eye(3), np.diag([0.0, 0.0, 1.0])
    scale = max(1.0, k_p, k_i, k_v, k_i / k_v, k_v / k_i)
    eps = margin
    cons = [P - (1 + eps) * eye >> 0, c2 * eye - P - eps * eye >> 0, c >= eps, -(Q + c * e3) - eps * scale * np.diag([0.0, 1.0, 1.0]) >> 0]

    def copositive(M, mask):
        n = M.shape[0]
        S = cp.Variable((n, n), symmetric=True)
        N = cp.Variable((n, n), symmetric=True)
        # a structurally zero diagonal entry forces its row of M to be ≥ 0: keep those entries ≥ the margin instead
        free = 1 - np.array(mask, dtype=float)
        margin_matrix = np.diag(np.array(mask, dtype=float)) + (1 - np.eye(n)) * np.minimum(1, np.add.outer(free, free))
        return [S >> 0, N >= 0, M - eps * scale * margin_matrix == S + N]

    k_rows = tuple(tuple(K[i, j] for j in range(3)) for i in range(3))
    for s in (1.0, -1.0):
        b = model.slip_rate_entries(k_p, k_i, k_v, s)
        cons += copositive(cp.bmat([list(r) for r in model.u_rate_entries(k_rows, b)]), [0, 1, 1])
        cons += copositive(cp.bmat([list(r) for r in model.band_rate_entries(k_i, k_v, k_rows, s)]), [0, 1])
    cons += [k13 >= eps, k23 >= eps, k33 >= eps]
    cons += copositive(K - eye, [1, 1, 1]) + copositive(gamma * eye - K, [1, 1, 1])
    p_rows = tuple(tuple(P[i, j] for j in range(3)) for i in range(3))
    at_rest, at_edge = model.exit_entries(k_rows, p_rows)
    cons += copositive(cp.bmat([list(r) for r in at_rest]), [1, 1]) + copositive(cp.bmat([list(r) for r in at_edge]), [1, 1])
    problem = cp.Problem(cp.Minimize(z), cons + [z >= c2, z >= gamma])
    try:
        problem.solve(solver=getattr(cp, SOLVER))
    except cp.error.SolverError as exc:
        return f"solver error ({exc})", {}
    values = {name: var.value for name, var in (("p11", p11), ("p22", p22), ("p33", p33), ("c", c), ("c2", c2),
                                               ("k11", k11), ("k13", k13), ("k22", k22), ("k23", k23), ("k33", k33),
                                               ("gamma", gamma))}
    return problem.status, values


def certify_quadratic(params: Parameters, *, label: str = "") -> "QuadraticCertificate":
    """Search, round and exactly verify a quadratic-template certificate for ``params``.

    Raises
    ------
    ParameterError
        If ``params`` has static friction above Coulomb.
    CertificateError
        If no margin of :data:`MARGINS` gives constants that verify exactly.
    """
    from .quadratic import QuadraticCertificate, QuadraticProvenance, verify_quadratic
    from .rounding import round_significant, sqrt_decimal_up

    if params.stiction:
        raise ParameterError(f"a stability certificate is for the paper's model f_s = f_c; got f_s = {params.f_s} > f_c = {params.f_c}")
    failures = []
    for margin in MARGINS:
        status, values = _solve(params, margin)
        if status != "optimal" or not values or any(v is None for v in values.values()):
            failures.append(f"margin {margin:g}: solver status {status}")
            continue
        constants = {}
        for name, value in values.items():
            value = float(value)
            direction = {"c": "down", "c2": "up", "gamma": "up"}.get(name, "nearest")
            constants[name] = round_significant(abs(value), DIGITS, direction=direction) * (1 if value > 0 else -1) if value != 0 else Fraction(0)
        kappa = sqrt_decimal_up(max(constants["c2"], constants["gamma"]))
        certificate = QuadraticCertificate(
            k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_c=params.f_c, constants=constants, overshoot_bound=kappa,
            provenance=QuadraticProvenance(search="sdp", solver=SOLVER, solver_status=status,
                                           margin=str(Fraction(margin).limit_denominator(10**12)), label=label),
        )
        report = verify_quadratic(certificate)
        if report.proved:
            return certificate
        failures.append(f"margin {margin:g}: " + "; ".join(check.name for check in report.failures))
    raise CertificateError(f"no quadratic certificate for {params} verifies exactly: " + " | ".join(failures))
