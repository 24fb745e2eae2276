"""Search for a sup-flow certificate: floats and SDPs propose, :func:`.sup_flow.verify_sup_flow` decides.

Nothing here is called proved.  The search:

1. takes ``p`` just below ``λ_min(P)`` for the paper's ``P`` and a horizon
   ``T = 2^m`` (in units of the slowest decay time) at which the tail form
   ``(1/p)e^{AT}ᵀPe^{AT}`` is below a quarter of ``sup_t ‖e^{At}‖₂²``
   (sampled);
2. sets ``c₂`` a relative :data:`C2_MARGIN` above the sampled peak of
   ``‖e^{At}‖₂²``;
3. starts from :data:`INITIAL_PIECES` equal pieces of ``[0, T]`` plus the tail
   ``[T, ∞)`` and, for each, minimises ``γ`` by an SDP (cvxpy, Clarabel) over
   ``K`` subject to the quadratic template's rate premises and the exit
   forms at :data:`SAMPLES` times of the piece, each copositive premise as
   ``S + N`` with a margin (:func:`copositive_constraints`);
4. halves the piece with the largest ``γ`` while that lowers the largest
   ``γ`` by more than ``rel_tol`` (so the pieces are where the bound needs
   them, not where a hand put them), up to ``max_pieces``;
5. rounds ``K`` to :data:`DIGITS` significant digits (``γ`` up) and lets the
   verifier decide each piece; a piece whose exit premise is not proved
   between its sample times is solved again with twice the samples.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from .._infra.errors import CertificateError, ParameterError
from .._model import quadratic as quad
from .._model import sup_flow as model
from .._model.lyapunov import lyapunov_matrix_entries
from .._model.parameters import Parameters

if TYPE_CHECKING:
    from .sup_flow import SupFlowCertificate

__all__ = ["certify_sup_flow", "copositive_constraints", "DIGITS", "SAMPLES", "INITIAL_PIECES", "MARGIN", "C2_MARGIN"]

DIGITS = 12
"""Significant digits kept from the solver's numbers."""
SAMPLES = 5
"""Times per piece (both ends included) at which the SDP imposes the exit forms at first."""
INITIAL_PIECES = 4
"""Equal pieces of ``[0, T]`` the refinement starts from."""
MARGIN = 1e-6
"""Relative margin of every SDP constraint, so that rounding keeps them."""
C2_MARGIN = 1e-3
"""``c₂`` is this much (relative) above the sampled peak of ``‖e^{At}‖₂²``."""
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


def copositive_constraints(M, mask, margin: float) -> list:
    """cvxpy constraints making ``M`` copositive with a margin.

    ``mask[i]`` is 0 where ``M``'s diagonal entry is structurally zero.  Such
    a row is copositive only with nonnegative off-diagonal entries, so those
    are kept ``≥ margin`` by linear constraints, and the rest of ``M`` is
    written ``M − margin·I = S + N`` with ``S ⪰ 0`` and ``N ≥ 0`` (Diananda:
    exact for ``n ≤ 4``).  Writing the zero rows into ``S + N`` too would let
    an interior-point solver keep ``S_ii`` at its tolerance and a visibly
    negative ``S_ij`` beside it, which rounding then exposes.
    """
    import cvxpy as cp
    import numpy as np

    n = M.shape[0]
    zero = [i for i in range(n) if not mask[i]]
    rest = [i for i in range(n) if mask[i]]
    cons = [M[i, j] >= margin for i in zero for j in range(n) if j != i]
    if rest:
        m = len(rest)
        S = cp.Variable((m, m), symmetric=True)
        N = cp.Variable((m, m), symmetric=True)
        sub = cp.bmat([[M[i, j] for j in rest] for i in rest])
        cons += [S >> 0, N >= 0, sub - margin * np.eye(m) == S + N]
    return cons


def _flows(a_matrix: Any, times: Any) -> list[Any]:
    from scipy.linalg import expm

    return [expm(a_matrix * float(t)) for t in times]


class _PieceProblem:
    """The SDP of one piece, compiled once (cvxpy parameters for the Grams and the margins), solved per piece.

    It minimises ``γ`` over ``K`` (``K₁₂ = 0``): ``K`` nonincreasing on ``R̂``
    (the quadratic template's rate premises), ``γI − K`` copositive, on the
    first piece ``K − I`` copositive, and ``U ≥ wᵀG_jw`` on both exits for
    :data:`SAMPLES` − 1 Grams ``G_j``.
    """

    def __init__(self, k: tuple[float, float, float], *, first: bool, room: bool = False) -> None:
        import cvxpy as cp
        import numpy as np

        k_p, k_i, k_v = k
        self.names = ("k11", "k13", "k22", "k23", "k33", "gamma")
        self.variables = [cp.Variable() for _ in self.names]
        k11, k13, k22, k23, k33, gamma = self.variables
        K = cp.bmat([list(r) for r in quad.u_matrix_entries(k11, k13, k22, k23, k33)])
        rows = tuple(tuple(K[i, j] for j in range(3)) for i in range(3))
        scale = max(1.0, k_p, k_i, k_v, k_i / k_v, k_v / k_i)
        self.margin = cp.Parameter(nonneg=True)
        eps = self.margin * scale
        cons = [k13 >= eps, k23 >= eps, k33 >= eps]
        for s in (1.0, -1.0):
            b = quad.slip_rate_entries(k_p, k_i, k_v, s)
            cons += copositive_constraints(cp.bmat([list(r) for r in quad.u_rate_entries(rows, b)]), [0, 1, 1], eps)
            cons += copositive_constraints(cp.bmat([list(r) for r in quad.band_rate_entries(k_i, k_v, rows, s)]), [0, 1], eps)
        eye = np.eye(3)
        cons += copositive_constraints(gamma * eye - K, [1, 1, 1], eps)
        if first:
            cons += copositive_constraints(K - eye, [1, 1, 1], eps)
        self.grams = [cp.Parameter((3, 3), symmetric=True) for _ in range(SAMPLES - 1)]
        self.gram_margins = [cp.Parameter(nonneg=True) for _ in self.grams]
        # room: with γ capped, the largest common room of the exit forms (the verifier then needs few parts)
        self.room = cp.Variable() if room else None
        self.cap = cp.Parameter(nonneg=True) if room else None
        for gram, scale_g in zip(self.grams, self.gram_margins):
            g = tuple(tuple(gram[i, j] for j in range(3)) for i in range(3))
            for s in (1.0, -1.0):
                for form in model.exit_forms(rows, g, s):
                    margin_g = scale_g if self.room is None else scale_g * self.room
                    cons += copositive_constraints(cp.bmat([list(r) for r in form]), [1, 1], margin_g)
        if self.room is None:
            self.problem = cp.Problem(cp.Minimize(gamma), cons)
        else:
            self.problem = cp.Problem(cp.Maximize(self.room), cons + [gamma <= self.cap, self.room >= self.margin, self.room <= 1])

    def solve(self, grams: list[Any], margin: float, cap: float | None = None) -> tuple[str, dict[str, float]]:
        import cvxpy as cp
        import numpy as np

        grams = list(grams) + [grams[-1]] * (len(self.grams) - len(grams))  # the tail has one Gram
        for parameter, room, gram in zip(self.grams, self.gram_margins, grams):
            parameter.value = (gram + gram.T) / 2
            room.value = max(1.0, float(np.max(np.abs(gram)))) * (margin if self.room is None else 1.0)
        self.margin.value = margin
        if self.cap is not None:
            self.cap.value = cap
        try:
            self.problem.solve(solver=getattr(cp, SOLVER))
        except cp.error.SolverError as exc:
            return f"solver error ({exc})", {}
        if any(v.value is None for v in self.variables):
            return str(self.problem.status), {}
        return str(self.problem.status), {n: float(v.value) for n, v in zip(self.names, self.variables)}


def certify_sup_flow(params: Parameters, *, label: str = "", rel_tol: float = 3e-3, max_pieces: int = 32) -> "SupFlowCertificate":
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

    Raises
    ------
    ParameterError
        If ``params`` has static friction above Coulomb, or an option is out of range.
    CertificateError
        If an SDP fails or the rounded constants do not verify.
    """
    import numpy as np

    from .rounding import round_significant, sqrt_decimal_up
    from .sup_flow import SupFlowCertificate, SupFlowPiece, SupFlowProvenance, verify_sup_flow

    if params.stiction:
        raise ParameterError(f"a stability certificate is for the paper's model f_s = f_c; got f_s = {params.f_s} > f_c = {params.f_c}")
    if not 0 < rel_tol < 1 or not 1 <= max_pieces <= 200:
        raise ParameterError(f"rel_tol must be in (0, 1) and max_pieces in 1..200; got {rel_tol}, {max_pieces}")
    k_p, k_i, k_v, _ = params.as_floats()
    a_matrix = np.array([[0.0, 0.0, -k_i], [1.0, 0.0, -k_p], [0.0, 1.0, -k_v]])
    p_exact = tuple(tuple(Fraction(x) for x in row) for row in lyapunov_matrix_entries(params.k_p, params.k_i, params.k_v))
    p_float = np.array(p_exact, dtype=float)
    p = _p_below(p_exact, float(np.linalg.eigvalsh(p_float)[0]))
    decay = float(min(abs(np.linalg.eigvals(a_matrix).real)))
    # the horizon: a power of two past which the tail form is small next to the peak
    horizon = Fraction(2) ** int(np.ceil(np.log2(4.0 / decay)))
    for _ in range(80):
        times = np.linspace(0.0, float(horizon), 2001)
        peak = max(float(np.linalg.norm(e, 2)) ** 2 for e in _flows(a_matrix, times))
        tail = _tail(a_matrix, p_float, float(p), float(horizon))
        if np.linalg.norm(tail, 2) <= peak / 4:
            break
        horizon *= 2
    else:
        raise CertificateError(f"no horizon makes the tail small for {params}")
    c2 = round_significant(peak * (1 + C2_MARGIN), 6, direction="up")
    k = (k_p, k_i, k_v)
    width = horizon / INITIAL_PIECES
    pieces = [_Piece(width * j, width * (j + 1)) for j in range(INITIAL_PIECES)] + [_Piece(horizon, None)]
    problems = {first: _PieceProblem(k, first=first) for first in (True, False)}
    solve = lambda piece: _solve(a_matrix, p_float, float(p), problems, piece)  # noqa: E731
    for piece in pieces:
        solve(piece)
        if piece.values is None:
            raise CertificateError(f"no sup-flow certificate for {params} verifies exactly: the SDP of the piece starting at "
                                   f"t = {float(piece.start):.6g} is {piece.status} at every margin tried")
    # halve the pieces whose K fails between its sample times (a dense float look, not a proof)
    while True:
        bad = [q for q in pieces if q.end is not None and q.values is not None and not _dense_ok(a_matrix, q)]
        if not bad or _finite(pieces) + len(bad) > max_pieces:
            break
        for q in bad:
            pieces = _halve(pieces, q, solve)
    # halve the piece with the largest γ until halving stops lowering it: a coarse piece's γ carries the
    # spread of the Gram over its parts, so a half may be worse before its own halves are better, and a
    # piece is given up only after STALLS generations without a drop of rel_tol
    while _finite(pieces) < max_pieces:
        open_ = [q for q in pieces if not q.final and q.end is not None]
        if not open_:
            break
        worst = max(open_, key=lambda q: q.gamma)
        if worst.gamma < max((q.gamma for q in pieces if q.end is None or q.final), default=0.0):
            break  # the largest γ is the tail's or a piece's that halving does not lower
        before = list(pieces)
        pieces = _halve(pieces, worst, solve)
        halves = [q for q in pieces if q not in before]
        if not all(_dense_ok(a_matrix, h) for h in halves):
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
    roomy = {first: _PieceProblem(k, first=first, room=True) for first in (True, False)}
    for q in pieces:
        grams = _piece_grams(a_matrix, p_float, float(p), q)
        status, values = roomy[q.start == 0].solve(grams, MARGIN, cap)
        if status == "optimal" and values and values["gamma"] <= cap:
            q.values = values
    failures: list[str] = []
    for attempt in range(4):
        rounded = []
        for piece in pieces:
            if piece.values is None:
                raise CertificateError(f"no SDP solution for the piece starting at t = {float(piece.start):.6g} of {params}")
            constants = {}
            for name, value in piece.values.items():
                direction = "up" if name == "gamma" else "nearest"
                constants[name] = (round_significant(abs(value), DIGITS, direction=direction) * (1 if value > 0 else -1)
                                   if value != 0 else Fraction(0))
            rounded.append(SupFlowPiece(start=piece.start, end=piece.end, constants=constants))
        kappa_sq = max([c2] + [q.constants["gamma"] for q in rounded])
        # c₂ costs nothing up to κ², and the room above the peak makes the verifier's cover of [0, T] coarse
        certificate = SupFlowCertificate(
            k_p=params.k_p, k_i=params.k_i, k_v=params.k_v, f_c=params.f_c, constants={"c2": kappa_sq, "p": p},
            pieces=tuple(rounded), overshoot_bound=sqrt_decimal_up(kappa_sq),
            provenance=SupFlowProvenance(search="sdp", solver=SOLVER, solver_status="optimal",
                                         margin=str(Fraction(MARGIN).limit_denominator(10**12)), label=label),
        )
        report = verify_sup_flow(certificate)
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


def _dense_ok(a_matrix: Any, piece: _Piece) -> bool:
    """Every exit form of the piece's float ``K`` copositive, with room, at :data:`DENSE` times of the piece."""
    import numpy as np

    v = piece.values
    if v is None:
        return False
    k = quad.u_matrix_entries(v["k11"], v["k13"], v["k22"], v["k23"], v["k33"])
    for e in _flows(a_matrix, np.linspace(float(piece.start), float(piece.end), DENSE)):
        g = tuple(map(tuple, e.T @ e))
        for s in (1.0, -1.0):
            for (a, b), (_, c) in model.exit_forms(k, g, s):
                room = 1e-9 * max(1.0, abs(a), abs(c))
                if a < room or c < room or (b < 0 and b * b > a * c * (1 - 1e-7)):
                    return False
    return True


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
        flows = _flows(a_matrix, np.linspace(a, b, SUBSAMPLES))
        grams = [e.T @ e for e in flows]
        (middle,) = _flows(a_matrix, [(a + b) / 2])
        centre = middle.T @ middle
        spread = max(float(np.linalg.norm(g - centre, 2)) for g in grams)
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
    import numpy as np

    grams = _piece_grams(a_matrix, p_float, p, piece)
    for margin in (MARGIN, MARGIN * 10, MARGIN * 100):
        status, values = problems[piece.start == 0].solve(grams, margin)
        if status == "optimal" and values:
            piece.values, piece.gamma, piece.status = values, values["gamma"], status
            return
    piece.values, piece.gamma, piece.status = None, float("inf"), status
