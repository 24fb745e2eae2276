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
5. also finds ``P`` and ``U`` together (:func:`joint_tail`: better where ``U``, not ``P``, decides κ);
6. lets :func:`.sup_flow.verify_sup_flow` decide each, and keeps the smaller proved κ.
"""

from __future__ import annotations

import functools
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from .._infra.errors import CertificateError, ParameterError
from .._model.parameters import Parameters
from .lyapunov_tail import best_conditioned_lyapunov, exact_lyapunov

if TYPE_CHECKING:
    from .sup_flow import SupFlowCertificate

__all__ = ["certify_sup_flow_tail", "joint_tail"]

SOLVER = "CLARABEL"
"""The solver of both SDPs (recorded in the provenance)."""


def joint_tail(k: tuple[float, float, float], *, margin: float, layout: Any = None) -> tuple[Any, dict[str, float]]:
    """``P`` and ``U`` found together: minimise ``t`` with ``I ⪯ P ⪯ tI``, ``AᵀP + PA ⪯ 0``, ``γ ≤ t`` and the
    piece's premises on ``U`` with the exit forms' Gram ``P`` itself (affine in both; ``p = 1``).

    Where ``U`` decides κ (``γ`` above ``λ_max(P)``), this trades some of ``P``'s conditioning for a smaller
    ``γ``; a candidate only.  Returns ``(P, K's values)``; raises :class:`CertificateError` without a solution.
    """
    import numpy as np

    from ._conic import Program
    from .lyapunov_tail import lyapunov_constraints
    from .sup_flow_search import Layout

    layout = layout or Layout(version=1)
    program = Program()
    p, t = lyapunov_constraints(program, k)
    variables = [program.variable() for _ in layout.names]
    forms, gamma = layout.constraints(program, k, variables, first=True, margin=margin)
    layout.exits(program, forms, p, t * margin)
    program.nonneg(t - gamma)
    status, x = program.solve(t)
    if not x:
        raise CertificateError(f"the joint SDP for the tail's P and U is {status}")
    return (np.array([[Program.value(p[i][j], x) for j in range(3)] for i in range(3)]),
            {n: Program.value(v, x) for n, v in zip(layout.names, variables)})


def _c2_above(p_matrix: tuple[tuple[Fraction, ...], ...], p: Fraction, estimate: float, layout: Any = None) -> Fraction:
    """A decimal ``c₂`` with ``c₂I − DᵀPD/p ≻ 0`` exactly (leading principal minors positive) for ``D = I`` and
    the drag maps of ``layout`` (version 2 with ``ℓ ≠ 0``)."""
    import numpy as np

    from .._model import sup_flow as model
    from .rounding import round_significant
    from .verify import Semidefinite

    maps = [] if layout is None or not layout.drag else [model.drag_exit_map(Fraction(s), layout.ell) for s in (1, -1)]
    grams = [p_matrix] + [model.pullback_gap(tuple(tuple(Fraction(0) for _ in range(3)) for _ in range(3)),
                                             p_matrix, d) for d in maps]
    grams = [g if i == 0 else tuple(tuple(-x for x in row) for row in g) for i, g in enumerate(grams)]
    estimate = max([estimate] + [float(np.linalg.eigvalsh(np.array(g, dtype=float))[-1]) / float(p) for g in grams[1:]])
    c2 = round_significant(estimate * (1 + 1e-9), 12, direction="up")
    for _ in range(200):
        if all(all(d > 0 for _, d in Semidefinite("", "", tuple(tuple((c2 if i == j else 0) - g[i][j] / p for j in range(3))
                                                               for i in range(3))).minors()) for g in grams):
            return c2
        c2 *= Fraction(1001, 1000)
    raise CertificateError("cannot bound λ_max(P)/p above")


def certify_sup_flow_tail(params: Parameters, *, label: str = "", layout: Any = None) -> "SupFlowCertificate":
    """Search, round and exactly verify a one-piece sup-flow certificate (the tail's own ``P`` at ``T = 0``).

    Parameters
    ----------
    params : Parameters
        Gains satisfying Assumption 1, ``f_s = f_c``.
    label : str, keyword-only
        Written into the provenance.
    layout : sup_flow_search.Layout, keyword-only
        Version 1 or version 2 of the format (:mod:`.sup_flow_v2`) and its ``ℓ``; default: each of
        :data:`.sup_flow_search.LAYOUTS` (version 2 with and without the friction-drag split), keeping the
        smallest proved κ.

    Raises
    ------
    ParameterError
        If ``params`` has static friction above Coulomb.
    CertificateError
        If an SDP fails or the rounded constants do not verify.

    Examples
    --------
    >>> cert = certify_sup_flow_tail(Parameters(k_p=1000, k_i="1/1000", k_v=1000, f_c=1))
    >>> len(cert.pieces), cert.own_tail, float(cert.overshoot_bound) < 2.6 * 1.4142  # κ_lin ≈ 1.4142
    (1, True, True)
    """
    import numpy as np

    from .sup_flow import verify_sup_flow
    from .sup_flow_search import MARGIN

    params.check_paper_model()
    k_p, k_i, k_v, _ = params.as_floats()
    if not all(np.isfinite(x) and 0 < x < 1e150 for x in (k_p, k_i, k_v)):
        raise CertificateError(f"the gains of {params} are beyond the range of the floats the SDPs work in")
    k = (params.k_p, params.k_i, params.k_v)
    proved, failures = [], []
    from .sup_flow_search import LAYOUTS

    layouts = LAYOUTS if layout is None else (layout,)
    best_p = best_conditioned_lyapunov((k_p, k_i, k_v))
    # the best-conditioned P made exact once for all layouts (the same P: the same exact one)
    best_exact = functools.cache(lambda: exact_lyapunov(k, best_p))

    def joint(lay: Any) -> tuple[Any, dict[str, float]]:
        p_float, values = joint_tail((k_p, k_i, k_v), margin=MARGIN, layout=lay)
        return exact_lyapunov(k, p_float), values

    candidates = [(f"the best-conditioned P, {lay.title}", lambda: (best_exact(), None), lay) for lay in layouts]
    candidates += [(f"P and U together, {lay.title}", lambda lay=lay: joint(lay), lay) for lay in layouts]
    for what, find, lay in candidates:
        try:
            p_exact, values = find()
            certificate = _one_piece(params, p_exact, values, label=label, layout=lay)
        except CertificateError as exc:
            failures.append(f"{what}: {exc}")
            continue
        report = verify_sup_flow(certificate)
        if report.proved:
            proved.append(certificate)
        else:
            failures.append(f"{what}: " + "; ".join(check.message for check in report.failures[:4]))
    if not proved:
        raise CertificateError(f"no one-piece sup-flow certificate for {params} verifies exactly: " + " | ".join(failures))
    return min(proved, key=lambda c: c.kappa)


def _one_piece(params: Parameters, p_exact: Any, values: dict[str, float] | None, *, label: str,
               layout: Any) -> "SupFlowCertificate":
    """The certificate with the tail's exact ``P`` and ``U`` (``values``, or solved here for the Gram ``P/p``)."""
    import numpy as np

    from .rounding import sqrt_decimal_up
    from .sup_flow import TAIL_CONSTANTS, SupFlowProvenance
    from .sup_flow_search import MARGIN, _p_below, _PieceProblem, layout_types, rounded_constants

    certificate_type, piece_type = layout_types(layout)
    p_float = np.array(p_exact, dtype=float)
    eig = np.linalg.eigvalsh(p_float)
    p = _p_below(p_exact, float(eig[0]))
    c2_floor = _c2_above(p_exact, p, float(eig[-1]) / float(p), layout)
    if values is None:
        problem = _PieceProblem(params.as_floats()[:3], first=True, grams=1, layout=layout)
        status = ""
        for margin in (MARGIN, MARGIN * 10, MARGIN * 100):
            status, values = problem.solve([p_float / float(p)], margin)
            if status == "optimal" and values:
                break
        else:
            raise CertificateError(f"the SDP for U is {status} at every margin tried")
    piece = piece_type(start=Fraction(0), end=None, constants=rounded_constants(values))
    kappa_sq = max(c2_floor, piece.constants["gamma"])
    tail = {name: p_exact[int(name[-2]) - 1][int(name[-1]) - 1] for name in TAIL_CONSTANTS}
    if layout.version == 2:
        tail.update({f"ell{j + 1}": layout.ell[j] for j in range(3)})
    return certificate_type(
        k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_c=params.f_c, constants={"c2": kappa_sq, "p": p, **tail},
        pieces=(piece,), overshoot_bound=sqrt_decimal_up(kappa_sq),
        provenance=SupFlowProvenance(search="sdp", solver=SOLVER, solver_status="optimal",
                                     margin=str(Fraction(MARGIN).limit_denominator(10**12)), label=label),
    )
