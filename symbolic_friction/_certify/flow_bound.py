"""The friction-free limit ``κ_lin = sup_{t≥0} ‖e^{At}‖₂``, enclosed rigorously (python-flint arb).

``A`` is the matrix of eq. (xDot) (:func:`~symbolic_friction._model.coordinates.system_matrix`).  For
states much larger than ``f_c`` friction is negligible (the inclusion is positively homogeneous in
``(x, f_c)``), so a trajectory from such a state follows ``e^{At}`` up to ``O(f_c/|x|)`` and no overshoot
bound ``κ`` of Proposition 1 (eq. stabState), of any template, can be below ``κ_lin``.
:func:`kappa_lin_bound` returns an exact interval ``[lower, upper]`` that contains ``κ_lin``:

* **lower**: at a time ``t*`` found by sampling, ``‖e^{At*}‖₂² ≥ vᵀMᵀMv/vᵀv`` for any vector ``v``
  (``M = e^{At*}`` enclosed in arb balls); the lower end of that ball.
* **upper** ``= √μ``: ``[0, T]`` is covered by intervals ``J``, bisected where needed; on each,
  ``e^{AJ}`` is enclosed by arb's matrix exponential of the ball ``A·J`` (ball arithmetic encloses the
  value at every point of the input ball), and ``μI − MᵀM ≻ 0`` is shown for every ``M`` in that
  enclosure by its three leading principal minors (Sylvester), each a ball with a positive lower end.
  Past ``T``: Lemma 2's ``AᵀP + PA = −c e₃e₃ᵀ ⪯ 0`` (the paper's ``P``, eq. lyapLikeP; the obligation
  ``lemma2.dVdt``) gives ``|e^{At}x|_P ≤ |e^{AT}x|_P`` for ``t ≥ T``, hence
  ``‖e^{At}‖₂ ≤ √(p̄/p) ‖e^{AT}‖_F`` with exact rationals ``p ≤ λ_min(P)``, ``p̄ ≥ λ_max(P)`` (decided by
  principal minors); ``T`` is doubled until that is at most ``lower``.

Nothing here is a float decision: the sampling only chooses ``t*`` and the target ``μ``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from .._infra.errors import ParameterError
from .._model.lyapunov import lyapunov_matrix_entries
from .._model.parameters import Parameters

__all__ = ["FlowBound", "kappa_lin_bound", "kappa_lin_lower", "flow_rates"]

PRECISION = 128
"""Bits of the arb balls."""


@dataclass(frozen=True)
class FlowBound:
    """An exact enclosure ``lower ≤ κ_lin ≤ upper`` of ``sup_{t≥0} ‖e^{At}‖₂``.

    Attributes
    ----------
    lower, upper : Fraction
        The enclosure (``upper`` is ``√upper_squared`` rounded up to a decimal).
    upper_squared : Fraction
        ``μ``: ``‖e^{At}‖₂² < μ`` was shown for every ``t ≥ 0``.
    t_peak : float
        Where the lower bound was taken.
    horizon : Fraction
        ``T``: intervals cover ``[0, T]``, Lemma 2's ``P`` the rest.
    pieces : int
        Intervals in the cover.
    """

    lower: Fraction
    upper: Fraction
    upper_squared: Fraction
    t_peak: float
    horizon: Fraction
    pieces: int

    def __post_init__(self) -> None:
        if not (0 < self.lower <= self.upper and self.upper * self.upper >= self.upper_squared > 0):
            raise ValueError(f"not an enclosure: lower {self.lower}, upper {self.upper}, upper² ≥ μ = {self.upper_squared}")


def _arb(q: Fraction) -> Any:
    import flint

    q = Fraction(q)
    return flint.arb(flint.fmpq(q.numerator, q.denominator))


def _fraction(point: Any) -> Fraction:
    """The exact value of an arb point (zero radius), e.g. ``ball.lower()``."""
    mantissa, exponent = point.man_exp()
    mantissa, exponent = int(mantissa), int(exponent)
    return Fraction(mantissa * 2**exponent) if exponent >= 0 else Fraction(mantissa, 2**-exponent)


def _system(params: Parameters) -> Any:
    import flint

    k_p, k_i, k_v = (Fraction(q) for q in (params.k_p, params.k_i, params.k_v))
    rows = ((0, 0, -k_i), (1, 0, -k_p), (0, 1, -k_v))
    return flint.arb_mat([[_arb(Fraction(x)) for x in row] for row in rows])


def _gram(M: Any) -> Any:
    return M.transpose() * M


def _below(mu: Any, S: Any) -> bool:
    """``μI − S ≻ 0`` for every ``S`` in the ball matrix: its leading principal minors have positive lower ends."""
    d = [[(mu if i == j else 0) - S[i, j] for j in range(3)] for i in range(3)]
    m1 = d[0][0]
    m2 = d[0][0] * d[1][1] - d[0][1] * d[1][0]
    m3 = (d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) - d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0])
          + d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]))
    return bool(m1 > 0 and m2 > 0 and m3 > 0)


def _flow_entries(A: Any, t: float) -> list[float]:
    """The nine entries of ``e^{At}`` (arb's enclosure at :data:`PRECISION`, its midpoints) in floats, row by row.

    A finite double ``t`` is taken into arb directly (exactly, as its Fraction is; a NaN or an infinity still goes
    through the Fraction, which refuses it), and the entries are read in one call."""
    import flint

    M = (A * (flint.arb(t) if math.isfinite(t) else _arb(Fraction(t)))).exp()
    return [float(x.mid()) for x in M.entries()]


def _norms_at(A: Any, ts: list[float]) -> list[float]:
    """``‖e^{At}‖₂`` in floats at each time of ``ts`` (only to choose where to look).

    The largest singular value is what ``np.linalg.norm(·, 2)`` returns, without its generic axis handling: numpy's
    ``svd`` of the stack of matrices runs the same LAPACK call on each matrix as on that matrix alone (the same
    floats), in one call instead of one per time."""
    import numpy as np

    if not ts:
        return []
    stack = np.array([_flow_entries(A, t) for t in ts]).reshape(-1, 3, 3)
    return np.linalg.svd(stack, compute_uv=False).max(axis=1).tolist()


def _peak(A: Any, horizon: float, near: float | None = None) -> float:
    """A time of nearly largest ``‖e^{At}‖₂``: a logarithmic and a linear grid (or around ``near``), then
    golden-section search around the best point.

    The search asks about a thousand times per κ_lin; a time asked again (the section's new inner point is now and
    then, to the last bit, the one it kept) is answered from the value found before."""
    if near is None:
        ts = sorted({0.0, *(horizon * 10.0 ** (-12 + 12 * k / 600) for k in range(601)),
                     *(horizon * k / 400 for k in range(401))})
    else:
        ts = [near * 2.0 ** ((k - 50) / 50) for k in range(101)]  # [near/2, 2·near]
    values = _norms_at(A, ts)
    k = max(range(len(ts)), key=values.__getitem__)
    a, b = ts[max(k - 1, 0)], ts[min(k + 1, len(ts) - 1)]
    g = (math.sqrt(5) - 1) / 2
    known: dict[float, float] = {}
    for _ in range(60):
        c, d = b - g * (b - a), a + g * (b - a)
        new = [t for t in dict.fromkeys((c, d)) if t not in known]
        known.update(zip(new, _norms_at(A, new)))
        if known[c] >= known[d]:
            b = d
        else:
            a = c
    return (a + b) / 2


def _lower(A: Any, t: float) -> Fraction:
    """A rigorous lower bound of ``‖e^{At}‖₂`` (Rayleigh quotient of ``MᵀM`` at the top singular vector, in arb)."""
    import numpy as np

    t_exact = Fraction(t)
    M = (A * _arb(t_exact)).exp()
    S = _gram(M)
    Sf = np.array([[float(S[i, j].mid()) for j in range(3)] for i in range(3)])
    v = [Fraction(float(x)) for x in np.linalg.eigh(Sf)[1][:, -1]]
    num = sum(_arb(v[i]) * S[i, j] * _arb(v[j]) for i in range(3) for j in range(3))
    den = sum(x * x for x in v)
    return _fraction((num / _arb(den)).sqrt().lower())


def flow_rates(params: Parameters) -> Any:
    """``|Re λ|`` of the eigenvalues of ``A`` (eq. xDot), in floats: where the searches look, never a decision."""
    import numpy as np

    k_p, k_i, k_v, _ = params.as_floats()
    return np.abs(np.linalg.eigvals(np.array([[0.0, 0.0, -k_i], [1.0, 0.0, -k_p], [0.0, 1.0, -k_v]])).real)


def kappa_lin_lower(params: Parameters) -> Fraction:
    """A proven lower end of ``κ_lin = sup_t ‖e^{At}‖₂``, cheaply: the lower end of :func:`kappa_lin_bound` alone.

    The time ``t*`` is searched in floats; ``‖e^{At*}‖₂ ≥ √(vᵀMᵀMv/vᵀv)`` is
    then enclosed in arb at ``M = e^{At*}`` (a Rayleigh quotient), and its
    lower end returned.  No overshoot bound of any template can be below it,
    so ``certify`` measures its κ against it.  About 0.1–0.3 s; no cover, so it
    also serves gains whose cover :func:`kappa_lin_bound` cannot finish.

    Raises
    ------
    ParameterError
        If Assumption 1 fails, or the gains are beyond float range (the search for ``t*``).

    Examples
    --------
    >>> lower = kappa_lin_lower(Parameters.table_i("a"))
    >>> 1.3732 < float(lower) <= 1.3732678
    True
    """
    import flint

    if not params.k_v * params.k_p > params.k_i > 0:
        raise ParameterError(f"Assumption 1 needs k_v·k_p > k_i > 0; got k_v·k_p = {params.k_v * params.k_p}, k_i = {params.k_i}")
    k_p, k_i, k_v, _ = params.as_floats()
    if not all(math.isfinite(x) and 1e-150 < x < 1e150 for x in (k_p, k_i, k_v)):
        raise ParameterError(f"the gains of {params} are beyond the float range the search for the peak time works in")
    old = flint.ctx.prec
    flint.ctx.prec = PRECISION
    try:
        A = _system(params)
        decay = float(min(flow_rates(params)))
        return _lower(A, _peak(A, 40.0 / decay))
    finally:
        flint.ctx.prec = old


def _p_condition(params: Parameters) -> Fraction:
    """An exact ``q ≥ λ_max(P)/λ_min(P)`` for the paper's ``P`` (eq. lyapLikeP), decided by principal minors.

    Floats only give the first guesses ``0 < p ≤ λ_min`` and ``p̄ ≥ λ_max``; each is halved or doubled
    until ``P − pI ⪰ 0`` and ``p̄I − P ⪰ 0`` hold exactly.
    """
    import numpy as np

    from .verify import Semidefinite

    P = [[Fraction(x) for x in row] for row in lyapunov_matrix_entries(params.k_p, params.k_i, params.k_v)]

    def psd(sign: int, shift: Fraction) -> bool:  # sign·(P − shift·I) ⪰ 0, exactly
        rows = tuple(tuple(sign * (P[i][j] - shift * (i == j)) for j in range(3)) for i in range(3))
        return all(d >= 0 for _, d in Semidefinite("", "", rows).minors())

    eig = np.linalg.eigvalsh(np.array(P, dtype=float))
    low, high = Fraction(float(eig[0])) / 2, Fraction(float(eig[-1])) * 2
    for _ in range(200):
        if low > 0 and psd(1, low):
            break
        low = low / 2 if low > 0 else Fraction(1, 2**60)
    else:
        raise ParameterError(f"cannot bound λ_min(P) > 0 below for {params}: is Assumption 1 satisfied?")
    for _ in range(200):
        if psd(-1, high):
            break
        high *= 2
    else:
        raise ParameterError(f"cannot bound λ_max(P) above for {params}")
    return high / low


def kappa_lin_bound(params: Parameters, *, rel_tol: Fraction = Fraction(1, 1000), max_pieces: int = 200_000,
                    restarts: int = 20) -> FlowBound:
    """Enclose ``κ_lin = sup_{t≥0} ‖e^{At}‖₂`` for the gains of ``params`` (module docstring).

    Parameters
    ----------
    params : Parameters
        Gains satisfying Assumption 1 (``f_c`` plays no part).
    rel_tol : Fraction, keyword-only
        ``upper ≤ lower·(1 + rel_tol)`` is aimed for first (``μ = (lower·(1 + rel_tol))²``); where the
        cover cannot show that within ``max_pieces`` intervals, the aim is doubled (up to 1) and the
        enclosure says how wide it came out.
    max_pieces : int, keyword-only
        Bound on the intervals of the cover.
    restarts : int, keyword-only
        Times the target may be raised or widened before giving up.

    Raises
    ------
    ParameterError
        If ``rel_tol`` is not in ``(0, 1]``, or the cover needs more than ``max_pieces`` intervals.

    Examples
    --------
    >>> b = kappa_lin_bound(Parameters.table_i("a"))
    >>> float(b.lower) <= 1.373268 <= float(b.upper), float(b.upper / b.lower) <= 1.0011
    (True, True)
    """
    import flint

    rel_tol = Fraction(rel_tol)
    if not 0 < rel_tol <= 1:
        raise ParameterError(f"rel_tol must be in (0, 1]; got {rel_tol}")
    if not params.k_v * params.k_p > params.k_i > 0:
        raise ParameterError(f"Assumption 1 needs k_v·k_p > k_i > 0; got k_v·k_p = {params.k_v * params.k_p}, k_i = {params.k_i}")
    old = flint.ctx.prec
    flint.ctx.prec = PRECISION
    try:
        A = _system(params)
        decay = float(min(flow_rates(params)))
        t_peak = _peak(A, 40.0 / decay)
        lower = _lower(A, t_peak)
        # the tail: T with √(p̄/p)·‖e^{AT}‖_F ≤ lower
        q = _p_condition(params)
        horizon = Fraction(2) ** math.ceil(math.log2(max(40.0 / decay, 1e-300)))
        for _ in range(200):
            M = (A * _arb(horizon)).exp()
            frob2 = sum(M[i, j] * M[i, j] for i in range(3) for j in range(3))
            if _arb(q) * frob2 < _arb(lower * lower):
                break
            horizon *= 2
        else:
            raise ParameterError(f"no horizon closes the tail for {params}")
        for _ in range(restarts):
            target = lower * (1 + rel_tol)
            mu = target * target
            pieces, above = _cover(A, _arb(mu), horizon, max_pieces)
            if above is None:
                break
            # the norm exceeds the target near `above`: the sampled peak was not the highest
            t_peak = _peak(A, 40.0 / decay, near=above)
            better = _lower(A, t_peak)
            if better > lower:
                lower = better
            elif rel_tol < 1:
                # no larger norm there: the target is too close to the supremum for intervals of this cover
                # (a slowly decaying oscillation stays near its peak for many periods); aim wider
                rel_tol = min(2 * rel_tol, Fraction(1))
            else:
                raise ParameterError(f"cannot show ‖e^(At)‖₂ < {float(target):.8g} near t = {above:.6g} for {params}, "
                                     "nor find a larger norm there")
        else:
            raise ParameterError(f"the enclosure of sup ‖e^(At)‖₂ did not settle after {restarts} restarts for {params}")
        from .rounding import sqrt_decimal_up

        return FlowBound(lower=lower, upper=Fraction(sqrt_decimal_up(mu, 8)), upper_squared=mu, t_peak=t_peak, horizon=horizon,
                         pieces=pieces)
    finally:
        flint.ctx.prec = old


def _cover(A: Any, mu: Any, horizon: Fraction, max_pieces: int) -> tuple[int, float | None]:
    """Cover ``[0, horizon]`` by dyadic intervals on each of which ``‖e^{At}‖₂² < μ``.

    Returns ``(intervals, None)``, or ``(intervals so far, t)`` where an interval around ``t`` could not be
    shown below ``μ`` even when split to a width of ``horizon·2⁻⁶⁰`` (or the cover reached
    ``max_pieces``): the norm there is at or above ``√μ``, or too close to it.
    """
    import flint

    stack = [(Fraction(0), horizon)]
    done = 0
    while stack:
        a, b = stack.pop()
        ball = flint.arb(_arb((a + b) / 2), _arb((b - a) / 2))
        if _below(mu, _gram((A * ball).exp())):
            done += 1
            continue
        if done + len(stack) + 2 > max_pieces or b - a < horizon / 2**60:
            return done, float((a + b) / 2)
        mid = (a + b) / 2
        stack += [(mid, b), (a, mid)]
    return done, None
