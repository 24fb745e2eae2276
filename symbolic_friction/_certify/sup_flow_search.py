"""Search for a sup-flow certificate: floats and SDPs propose, :func:`.sup_flow.verify_sup_flow` decides.

Nothing here is called proved.  The search:

1. takes ``p`` just below ``λ_min(P)`` for the paper's ``P`` (exactly: ``P − pI ⪰ 0`` by principal minors)
   and a horizon ``T = 2^m`` at which the tail form ``(1/p)e^{AT}ᵀPe^{AT}`` is below a quarter of the sampled
   ``sup_t ‖e^{At}‖₂²``;
2. starts from :data:`INITIAL_PIECES` equal pieces of ``[0, T]`` plus the tail ``[T, ∞)`` and, for each,
   minimises ``γ`` by an SDP (Clarabel, written into conic form by :mod:`._conic`, :class:`_PieceProblem`) over ``K`` subject to the
   quadratic template's rate premises and the exit forms on :data:`SAMPLES` − 1 parts of the piece, each with
   the Gram at the part's middle plus its measured spread (:func:`_covering_grams`), every copositive premise
   as ``S + N`` with a margin (:func:`copositive_constraints`);
3. halves a piece whose ``K`` fails between its parts on a dense float grid (:func:`_dense_ok`);
4. halves the piece with the largest ``γ`` until halving stops lowering it (:data:`STALLS` generations
   without a drop of ``rel_tol``), up to ``max_pieces``, so the pieces are where the bound is decided, not
   where a hand put them;
5. gives every piece below the largest ``γ`` room: ``γ`` capped there, the exit forms' common margin
   maximised (the verifier then needs few parts);
6. sets ``c₂ = κ²`` (``c₂`` costs nothing up to ``κ²``, and the room makes the verifier's cover of ``[0, T]``
   coarse), rounds ``K`` to :data:`DIGITS` significant digits (``γ`` up) and lets the verifier decide; a piece
   it does not prove is halved and solved again (at most three rounds).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from .._infra.errors import CertificateError, ParameterError
from .._model import sup_flow as model
from .._model.lyapunov import lyapunov_matrix_entries
from .._model.parameters import Parameters
from .sup_flow_layout import ELL, LAYOUTS, Layout

if TYPE_CHECKING:
    from .sup_flow import SupFlowCertificate

__all__ = ["certify_sup_flow", "rounded_constants", "Layout", "ELL", "DIGITS", "SAMPLES", "INITIAL_PIECES", "MARGIN"]

DIGITS = 12
"""Significant digits kept from the solver's numbers."""
SAMPLES = 5
"""Times per piece (both ends included) at which the SDP imposes the exit forms at first."""
INITIAL_PIECES = 4
"""Equal pieces of ``[0, T]`` the refinement starts from."""
MARGIN = 1e-6
"""Relative margin of every SDP constraint, so that rounding keeps them."""
STALLS = 3
"""Generations of halving without a drop of ``rel_tol`` in ``γ`` after which a piece is left as it is."""
SOLVER = "CLARABEL"


@dataclass
class _Piece:
    start: Fraction
    end: Fraction | None
    samples: int = SAMPLES
    gamma: float = float("inf")
    values: dict[str, float] | None = None
    final: bool = False
    status: str = ""
    stalls: int = 0
    best: float = float("inf")


def _flows(a_matrix: Any, times: Any) -> list[Any]:
    """``e^{At}`` at each time, in floats (for where the search looks; the verifier encloses the flow itself).

    With a well-conditioned eigenbasis ``A = VΛV⁻¹`` (the usual case) all times cost one vectorised
    ``V e^{Λt} V⁻¹``; near a repeated root (``V`` ill-conditioned) each is a Padé ``expm``.
    """
    import numpy as np
    from scipy.linalg import expm

    times = np.asarray([float(t) for t in times])
    lam, v = np.linalg.eig(a_matrix)
    if np.linalg.cond(v) < 1e6:
        v_inv = np.linalg.inv(v)
        e = np.einsum("ij,tj,jk->tik", v, np.exp(np.outer(times, lam)), v_inv).real
        return list(e)
    return [expm(a_matrix * t) for t in times]


class _PieceProblem:
    """The SDP of one piece, written into Clarabel's conic form (:mod:`._conic`) per solve.

    It minimises ``γ`` over ``K`` (``K₁₂ = 0``): ``K`` nonincreasing on ``R̂``
    (the quadratic template's rate premises), ``γI − K`` copositive, on the
    first piece ``K − I`` copositive, and ``U ≥ wᵀG_jw`` on both exits for
    ``grams`` Grams ``G_j``.  With ``room``, ``γ`` is capped and the exit
    forms' common margin maximised instead.
    """

    names = ("k11", "k13", "k22", "k23", "k33", "gamma")

    def __init__(self, k: tuple[float, float, float], *, first: bool, room: bool = False, grams: int = SAMPLES - 1,
                 layout: Layout = Layout(version=1)) -> None:
        self.k, self.first, self.room, self.grams, self.layout = k, first, room, grams, layout
        self.names = layout.names

    def solve(self, grams: list[Any], margin: float, cap: float | None = None) -> tuple[str, dict[str, float]]:
        import numpy as np

        from ._conic import Program

        program = Program()
        variables = [program.variable() for _ in self.names]
        forms, gamma = self.layout.constraints(program, self.k, variables, first=self.first, margin=margin)
        room = program.variable() if self.room else None
        grams = list(grams) + [grams[-1]] * (self.grams - len(grams))  # the tail has one Gram
        for gram in grams[: self.grams]:
            sym = (np.asarray(gram) + np.asarray(gram).T) / 2
            scale = max(1.0, float(np.max(np.abs(sym))))
            g = tuple(tuple(float(sym[i, j]) for j in range(3)) for i in range(3))
            self.layout.exits(program, forms, g, scale * margin if room is None else room * scale)
        if room is None:
            status, x = program.solve(gamma)
        else:
            program.nonneg(cap - gamma, room - margin, 1.0 - room)
            status, x = program.solve(room, maximize=True)
        if not x:
            return status, {}
        return status, {n: Program.value(v, x) for n, v in zip(self.names, variables)}


def certify_sup_flow(params: Parameters, *, label: str = "", rel_tol: float = 3e-3, max_pieces: int = 32,
                     tail: str = "paper", deadline: float | None = None,
                     layout: Layout = LAYOUTS[0]) -> "SupFlowCertificate":
    """Search, round and exactly verify a sup-flow certificate for ``params``.

    Parameters
    ----------
    params : Parameters
        Gains satisfying Assumption 1, ``f_s = f_c``.
    label : str, keyword-only
        Written into the provenance.
    rel_tol : float, keyword-only
        A piece is halved while that lowers the largest ``γ`` by more than this (relative).
    max_pieces : int, keyword-only
        At most this many finite pieces (the tail is one more).
    tail : {"paper", "own"}, keyword-only
        The tail's ``P``: the paper's (eq. lyapLikeP), or the best-conditioned exact Lyapunov matrix of
        :mod:`.sup_flow_tail`, written into the file (a shorter horizon on stiff, slow and spread gains).
    deadline : float, keyword-only
        A ``time.monotonic()`` past which no more pieces are halved (the pieces so far are rounded and verified).
    layout : Layout, keyword-only
        Version 1 (one ``K`` per piece) or version 2 (:mod:`.sup_flow_v2`: forms per sign of ``σv`` and the
        friction-drag split with ``layout.ell``); default: version 2 without the drag split.

    Raises
    ------
    ParameterError
        If ``params`` has static friction above Coulomb, or an option is out of range.
    CertificateError
        If an SDP fails or the rounded constants do not verify.
    """
    import numpy as np

    from .rounding import round_significant, sqrt_decimal_up
    from .sup_flow import TAIL_CONSTANTS, SupFlowProvenance, verify_sup_flow

    params.check_paper_model()
    if not 0 < rel_tol < 1 or not 1 <= max_pieces <= 200 or tail not in ("paper", "own"):
        raise ParameterError(f"rel_tol must be in (0, 1), max_pieces in 1..200 and tail 'paper' or 'own'; "
                             f"got {rel_tol}, {max_pieces}, {tail!r}")
    k_p, k_i, k_v, _ = params.as_floats()
    if not all(np.isfinite(x) and 1e-150 < x < 1e150 for x in (k_p, k_i, k_v)):
        raise CertificateError(f"the gains of {params} are beyond the range of the floats the SDPs work in")
    a_matrix = np.array([[0.0, 0.0, -k_i], [1.0, 0.0, -k_p], [0.0, 1.0, -k_v]])
    own_tail = tail == "own"
    if not own_tail:
        p_exact = tuple(tuple(Fraction(x) for x in row) for row in lyapunov_matrix_entries(params.k_p, params.k_i, params.k_v))
    else:
        from .lyapunov_tail import best_conditioned_lyapunov, exact_lyapunov

        p_exact = exact_lyapunov((params.k_p, params.k_i, params.k_v), best_conditioned_lyapunov((k_p, k_i, k_v)))
    p_float = np.array(p_exact, dtype=float)
    p = _p_below(p_exact, float(np.linalg.eigvalsh(p_float)[0]))
    from .flow_bound import flow_rates

    rates = flow_rates(params)
    # the horizon: a power of two past which the tail form is small next to the peak (the paper's P: from the
    # slowest time constant; a well-conditioned P: from the fastest, doubled as needed)
    horizon = Fraction(2) ** int(np.ceil(np.log2(4.0 / float(max(rates) if own_tail else min(rates)))))
    for _ in range(80):
        times = np.unique(np.concatenate([np.linspace(0.0, float(horizon), 2001), float(horizon) * np.logspace(-9, 0, 500)]))
        peak = max(_peak_norms(_flows(a_matrix, times), layout))
        if np.linalg.norm(_tail(a_matrix, p_float, float(p), float(horizon)), 2) <= peak / 4:
            break
        horizon *= 2
    else:
        raise CertificateError(f"no horizon makes the tail small for {params}")
    c2_floor = round_significant(peak * (1 + 1e-3), 6, direction="up")  # above the sampled peak of ‖e^{At}‖²
    k = (k_p, k_i, k_v)
    width = horizon / INITIAL_PIECES
    pieces = [_Piece(width * j, width * (j + 1)) for j in range(INITIAL_PIECES)] + [_Piece(horizon, None)]
    problems = {first: _PieceProblem(k, first=first, layout=layout) for first in (True, False)}
    solve = lambda piece: _solve(a_matrix, p_float, float(p), problems, piece)  # noqa: E731
    for piece in pieces:
        solve(piece)
        if piece.values is None:
            raise CertificateError(f"no sup-flow certificate for {params} verifies exactly: the SDP of the piece starting at "
                                   f"t = {float(piece.start):.6g} is {piece.status} at every margin tried")
    # halve the pieces whose K fails between its sample times (a dense float look, not a proof)
    while True:
        bad = [q for q in pieces if q.end is not None and q.values is not None and not _dense_ok(a_matrix, q, layout)]
        if not bad or _finite(pieces) + len(bad) > max_pieces or _past(deadline):
            break
        for q in bad:
            pieces = _halve(pieces, q, solve)
    # halve the piece with the largest γ until halving stops lowering it: a coarse piece's γ carries the
    # spread of the Gram over its parts, so a half may be worse before its own halves are better, and a
    # piece is given up only after STALLS generations without a drop of rel_tol
    while _finite(pieces) < max_pieces and not _past(deadline):
        open_ = [q for q in pieces if not q.final and q.end is not None]
        if not open_:
            break
        worst = max(open_, key=lambda q: q.gamma)
        if worst.gamma < max((q.gamma for q in pieces if q.end is None or q.final), default=0.0):
            break  # the largest γ is the tail's or a piece's that halving does not lower
        before = list(pieces)
        pieces = _halve(pieces, worst, solve)
        halves = [q for q in pieces if q not in before]
        if not all(_dense_ok(a_matrix, h, layout) for h in halves):
            pieces = before
            worst.final = True
            continue
        lowered = max(h.gamma for h in halves) < worst.best / (1 + rel_tol)
        for h in halves:
            h.best = min(h.gamma, worst.best)
            h.stalls = 0 if lowered else worst.stalls + 1
            h.final = h.stalls >= STALLS
    # every piece below the largest γ gets room: γ up to that largest, the exit forms as far from the
    # boundary as that allows
    cap = max(q.gamma for q in pieces) * (1 - 1e-6)
    roomy = {first: _PieceProblem(k, first=first, room=True, layout=layout) for first in (True, False)}
    for q in pieces:
        grams = _piece_grams(a_matrix, p_float, float(p), q)
        status, values = roomy[q.start == 0].solve(grams, MARGIN, cap)
        if status == "optimal" and values and values["gamma"] <= cap:
            q.values = values
    own = {} if not own_tail else {name: p_exact[int(name[-2]) - 1][int(name[-1]) - 1] for name in TAIL_CONSTANTS}
    certificate_type, piece_type = layout_types(layout)
    if layout.version == 2:
        own.update({f"ell{j + 1}": layout.ell[j] for j in range(3)})
    failures: list[str] = []
    for attempt in range(4):
        rounded = []
        for piece in pieces:
            if piece.values is None:
                raise CertificateError(f"no SDP solution for the piece starting at t = {float(piece.start):.6g} of {params}")
            rounded.append(piece_type(start=piece.start, end=piece.end, constants=rounded_constants(piece.values)))
        kappa_sq = max([c2_floor] + [q.constants["gamma"] for q in rounded])
        # c₂ costs nothing up to κ², and the room above the peak makes the verifier's cover of [0, T] coarse
        certificate = certificate_type(
            k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_c=params.f_c, constants={"c2": kappa_sq, "p": p, **own},
            pieces=tuple(rounded), overshoot_bound=sqrt_decimal_up(kappa_sq),
            provenance=SupFlowProvenance(search="sdp", solver=SOLVER, solver_status="optimal",
                                         margin=str(Fraction(MARGIN).limit_denominator(10**12)), label=label),
        )
        if _past(deadline):
            raise CertificateError(f"no sup-flow certificate for {params} within the time budget (past it before "
                                   f"verification round {attempt + 1})")
        report = verify_sup_flow(certificate, max_parts=_parts_left(deadline))
        if report.proved:
            return certificate
        failures = [check.message for check in report.failures]
        redo = {int(c.name.split(":")[0].split()[1]) - 1 for c in report.failures if c.name.startswith("piece ")}
        if not redo or _finite(pieces) + len(redo) > max_pieces:
            break
        for q in [pieces[i] for i in sorted(redo)]:
            if q.end is None:
                break  # the tail has one Gram and nothing to split
            else:
                pieces = _halve(pieces, q, solve)
    raise CertificateError(f"no sup-flow certificate for {params} verifies exactly: " + "; ".join(failures[:4]))


def rounded_constants(values: dict[str, float]) -> dict[str, Fraction]:
    """A piece's SDP values to :data:`DIGITS` significant digits (``γ`` up, the entries of ``K`` to nearest)."""
    from .rounding import round_significant

    constants = {}
    for name, value in values.items():
        direction = "up" if name == "gamma" else "nearest"
        constants[name] = (round_significant(abs(value), DIGITS, direction=direction) * (1 if value > 0 else -1)
                           if value != 0 else Fraction(0))
    # version 2's K⁺₁₂ ≥ 0 ≥ K⁻₁₂: a solver's value a hair on the wrong side of 0 becomes 0
    if "kp12" in constants:
        constants["kp12"] = max(constants["kp12"], Fraction(0))
        constants["km12"] = min(constants["km12"], Fraction(0))
    return constants


def layout_types(layout: Layout) -> tuple[type, type]:
    """The certificate and piece classes of ``layout``'s version."""
    if layout.version == 1:
        from .sup_flow import SupFlowCertificate, SupFlowPiece

        return SupFlowCertificate, SupFlowPiece
    from .sup_flow_v2 import SupFlowCertificateV2, SupFlowPieceV2

    return SupFlowCertificateV2, SupFlowPieceV2


def _peak_norms(flows: list[Any], layout: Layout) -> list[float]:
    """``max(‖e‖₂², ‖e·D_ℓ‖₂²)`` over the drag maps (floats) for each ``e`` of ``flows``: what ``c₂`` must bound at
    that time.

    The norms of all times are taken in one call (:func:`_largest_singular_values`; the search asks at 2,500 times
    per horizon tried).  Each product ``e·D_ℓ`` is still formed on its own (``e`` may be a strided view, which numpy
    multiplies without BLAS)."""
    import numpy as np

    norms = [_largest_singular_values(flows)]
    for d in layout.drag_maps().values():
        d_matrix = np.array(d, dtype=float)
        norms.append(_largest_singular_values([e @ d_matrix for e in flows]))
    return [max([n ** 2 for n in at_time]) for at_time in zip(*norms)]


def _largest_singular_values(matrices: list[Any]) -> list[float]:
    """``float(np.linalg.norm(m, 2))`` for each 3×3 ``m`` of ``matrices``: one ``svd`` of their stack (the same
    LAPACK call on each matrix, so the same floats)."""
    import numpy as np

    return np.linalg.svd(np.array(matrices, dtype=float).reshape(-1, 3, 3), compute_uv=False).max(axis=1).tolist()


def _past(deadline: float | None) -> bool:
    import time

    return deadline is not None and time.monotonic() > deadline


PARTS_PER_SECOND = 2000
"""About how many intervals the verifier's enclosures decide per second (sets the parts a deadline leaves)."""


def _parts_left(deadline: float | None) -> int | None:
    """The verifier's budget of parts that the time left allows (None: its own limit)."""
    import time

    if deadline is None:
        return None
    return max(256, int(PARTS_PER_SECOND * (deadline - time.monotonic())))


def _finite(pieces: list[_Piece]) -> int:
    return sum(1 for q in pieces if q.end is not None)


def _halve(pieces: list[_Piece], piece: _Piece, solve: Any) -> list[_Piece]:
    """``pieces`` with ``piece`` replaced by its two halves, each solved."""
    mid = (piece.start + piece.end) / 2
    halves = [_Piece(piece.start, mid), _Piece(mid, piece.end)]
    for half in halves:
        solve(half)
    i = pieces.index(piece)
    return pieces[:i] + halves + pieces[i + 1:]


DENSE = 64
"""Times per piece at which the search looks (in floats) whether ``K`` also holds between its sample times."""


def _dense_ok(a_matrix: Any, piece: _Piece, layout: Layout) -> bool:
    """Every exit form of the piece's float forms copositive, with room, at :data:`DENSE` times of the piece."""
    if piece.values is None:
        return False
    return all(layout.exit_ok(piece.values, tuple(map(tuple, e.T @ e)))
               for e in _uniform_flows(a_matrix, float(piece.start), float(piece.end), DENSE))


def _uniform_flows(a_matrix: Any, start: float, end: float, n: int) -> list[Any]:
    """``e^{At}`` at ``n`` equally spaced times of ``[start, end]`` (:func:`_flows`)."""
    import numpy as np

    return _flows(a_matrix, np.linspace(start, end, n))


def _p_below(p_exact: tuple[tuple[Fraction, ...], ...], estimate: float) -> Fraction:
    """A rational ``p > 0`` with ``P − pI ⪰ 0`` exactly (principal minors), from just below the float ``λ_min``."""
    from .verify import Semidefinite

    p = Fraction(estimate * (1 - 1e-6)).limit_denominator(10**12)
    for _ in range(200):
        rows = tuple(tuple(p_exact[i][j] - p * (i == j) for j in range(3)) for i in range(3))
        if p > 0 and all(d >= 0 for _, d in Semidefinite("", "", rows).minors()):
            return p
        p = p / 2 if p > 0 else Fraction(1, 10**12)
    raise CertificateError("cannot bound λ_min(P) below")


def _tail(a_matrix: Any, p_float: Any, p: float, horizon: float) -> Any:
    import numpy as np

    (e,) = _flows(a_matrix, [horizon])
    return np.array(model.tail_gram(tuple(map(tuple, e)), tuple(map(tuple, p_float)), p))


def _covering_grams(a_matrix: Any, start: float, end: float, samples: int) -> list[Any]:
    """Grams ``G_j + δ_jI`` that bound ``e^{At}ᵀe^{At}`` on ``samples − 1`` equal parts of ``[start, end]`` (in floats).

    ``G_j`` is the Gram at the part's middle and ``δ_j`` :data:`SPREAD` times the
    largest ``‖G(t) − G_j‖₂`` seen at :data:`SUBSAMPLES` times of the part.  The
    exit maps have orthonormal columns (``DᵀD = I``), so a ``K`` above
    ``DᵀG_jD + δ_jI`` is above ``DᵀG(t)D`` on the whole part when ``δ_j`` covers
    the spread, with room that the verifier's bisection can find.
    """
    import numpy as np

    edges = np.linspace(start, end, max(samples, 2))
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        flows = _uniform_flows(a_matrix, float(a), float(b), SUBSAMPLES)
        grams = [e.T @ e for e in flows]
        (middle,) = _flows(a_matrix, [(a + b) / 2])
        centre = middle.T @ middle
        spread = max(_largest_singular_values([g - centre for g in grams]))
        out.append(centre + (SPREAD * spread + 1e-12 * float(np.linalg.norm(centre, 2))) * np.eye(3))
    return out


SUBSAMPLES = 9
"""Times per part at which :func:`_covering_grams` measures the spread of the Gram."""
SPREAD = 1.5
"""Factor on the measured spread (the Gram is smooth in ``t``; the factor covers what the samples miss)."""


def _piece_grams(a_matrix: Any, p_float: Any, p: float, piece: _Piece) -> list[Any]:
    if piece.end is None:
        return [_tail(a_matrix, p_float, p, float(piece.start))]
    return _covering_grams(a_matrix, float(piece.start), float(piece.end), piece.samples)


def _solve(a_matrix: Any, p_float: Any, p: float, problems: dict[bool, _PieceProblem], piece: _Piece) -> None:
    """Solve ``piece``'s SDP at growing margins; keep the first optimal solution (or none, with the last status)."""
    grams = _piece_grams(a_matrix, p_float, p, piece)
    for margin in (MARGIN, MARGIN * 10, MARGIN * 100):
        status, values = problems[piece.start == 0].solve(grams, margin)
        if status == "optimal" and values:
            piece.values, piece.gamma, piece.status = values, values["gamma"], status
            return
    piece.values, piece.gamma, piece.status = None, float("inf"), status
