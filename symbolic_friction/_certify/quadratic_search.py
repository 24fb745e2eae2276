"""Search for a quadratic-template certificate: an SDP, then exact rounding (the verifier decides).

The SDP (Clarabel, written into conic form by :mod:`._conic`) minimises ``max(c₂, γ)`` over ``P₁₁, P₂₂, P₃₃``,
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


def _solve(params: Parameters, margin: float) -> tuple[str, dict[str, float]]:
    from ._conic import Program

    k_p, k_i, k_v, _ = params.as_floats()
    program = Program()
    names = ("p11", "p22", "p33", "c", "c2", "k11", "k13", "k22", "k23", "k33", "gamma")
    variables = {name: program.variable() for name in names}
    p11, p22, p33, c, c2, k11, k13, k22, k23, k33, gamma = (variables[n] for n in names)
    z = program.variable()
    p_rows = model.quadratic_p_entries(k_p, k_i, k_v, p11, p22, p33)
    k_rows = model.u_matrix_entries(k11, k13, k22, k23, k33)
    q = model.lyapunov_rate_entries(k_p, k_i, k_v, p_rows)
    scale = max(1.0, k_p, k_i, k_v, k_i / k_v, k_v / k_i)
    eps = margin
    eye = lambda i, j: 1.0 if i == j else 0.0  # noqa: E731
    program.psd([[p_rows[i][j] - (1 + eps) * eye(i, j) for j in range(3)] for i in range(3)])
    program.psd([[(c2 - eps) * eye(i, j) - p_rows[i][j] for j in range(3)] for i in range(3)])
    program.nonneg(c - eps)
    # −(Q + c·e₃e₃ᵀ) ⪰ eps·scale·diag(0, 1, 1)
    program.psd([[-q[i][j] - (c if i == j == 2 else 0.0) - (eps * scale if i == j and i > 0 else 0.0) for j in range(3)]
                 for i in range(3)])
    for s in (1.0, -1.0):
        b = model.slip_rate_entries(k_p, k_i, k_v, s)
        program.copositive(model.u_rate_entries(k_rows, b), [0, 1, 1], eps * scale)
        program.copositive(model.band_rate_entries(k_i, k_v, k_rows, s), [0, 1], eps * scale)
    program.nonneg(k13 - eps, k23 - eps, k33 - eps)
    program.copositive([[k_rows[i][j] - eye(i, j) for j in range(3)] for i in range(3)], [1, 1, 1], eps * scale)
    program.copositive([[gamma * eye(i, j) - k_rows[i][j] for j in range(3)] for i in range(3)], [1, 1, 1], eps * scale)
    at_rest, at_edge = model.exit_entries(k_rows, p_rows)
    program.copositive(at_rest, [1, 1], eps * scale)
    program.copositive(at_edge, [1, 1], eps * scale)
    program.nonneg(z - c2, z - gamma)
    status, x = program.solve(z)
    if not x:
        return status, {}
    return status, {name: Program.value(v, x) for name, v in variables.items()}


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

    params.check_paper_model()
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
