"""Numerical search for the constants of Lemma 2, Lemma 3 and Proposition 1
(cvxpy + Clarabel).  This is the ONLY module of the package that imports
cvxpy, and it does so lazily.

What is searched
----------------
Proposition 1's overshoot bound is ``κ² = (c₂/c₁)·(ĉ₂/ĉ₁)``.

* ``c₁ ≤ λ_min(P)`` and ``c₂ ≥ λ_max(P)`` (Lemma 2, eq. VandR) with ``P`` of
  eq. (lyapLikeP).  ``P`` is fixed by the gains, so the best constants are its
  extreme eigenvalues; they are computed here in closed form (no solver):
  the middle entry ``1`` of ``P`` decouples, and the 2×2 block
  ``B = [[k_v/k_i, -1], [-1, k_p]]`` has
  ``λ₊ = (tr B + √((k_v/k_i - k_p)² + 4))/2`` (a sum of positive terms, no
  cancellation) and ``λ₋ = det B / λ₊`` with ``det B = (k_v k_p - k_i)/k_i``
  formed exactly.  This keeps full relative accuracy even at the Routh
  boundary ``k_v k_p/k_i → 1``, where ``λ₋ → 0`` and ``numpy.linalg.eigvalsh``
  would lose most digits.
* ``V̂ = ½ wᵀKw`` (eq. Vhat) with ``K = [[k₁,0,k₃],[0,k₂,0],[k₃,0,k₄]]`` and
  ``w = (|σ|, |dz(φ)|, |v|) ≥ 0``, ``|w|² = |x|²_𝒜``.  The tightest constants
  over *nonnegative* ``w`` are ``ĉ₁ = min(k₁,k₂,k₄)/2`` and
  ``ĉ₂ = λ_max(K)/2`` (see :mod:`._certify.rounding` for why).  ``V̂`` is
  homogeneous of degree one in ``(k₁,…,k₄)``, so we normalise
  ``k₁, k₂, k₄ ≥ 2`` (hence ``ĉ₁ ≥ 1``) and

  - ``tightest``: minimise ``t`` subject to ``t·I - K/2 ⪰ 0`` (an SDP; at the
    optimum ``t = λ_max(K)/2 = ĉ₂``);
  - ``feasible``: minimise ``trace(K)/2`` (its linear surrogate; no SDP),

  both subject to the k-conditions of Lemma 3 with a relative margin ``μ``
  (strict ``a > b`` becomes ``a ≥ (1+μ)·b``):
  ``k₃ ≥ (1+μ)(k_i/k_v)k₁``, ``k₃ ≥ (1+μ)k₂``, ``k₄ ≥ (1+μ)(k_i/k_v)k₃``,
  ``k₄ ≥ (1+μ)k_p k₂`` and ``k₁k₄ ≥ (1+μ)k₃²`` written as the 2×2 linear
  matrix inequality ``[[k₁, k₃], [k₃, k₄/(1+μ)]] ⪰ 0``.

Scaling
-------
The data enter only through ``r = k_i/k_v`` and ``k_p``, which can span
twelve decades, and so do the optimal ``k``'s (e.g. ``k₄ ≈ r·k₃ ≈ r²k₁``).
Each solve therefore substitutes ``k_j = s_j·y_j`` where ``s`` is an explicit
feasible point (the greedy choice ``k₁ = k₂ = 2`` with ``k₃``, ``k₄`` at their
lower bounds) and divides the objective by ``λ_max`` at ``s``; the scaled
coefficients are the cvxpy ``Parameter`` values, so the problem is compiled
once (DPP) and re-solved for every gain set, with ``y = O(1)``.

The result is a :class:`Candidate`: floats plus the solver's status.  It is
*not* a certificate; :mod:`._certify.rounding` turns it into exact rationals
and :mod:`._certify.verify` (which shares no code with this module) decides
whether it proves anything.
"""

from __future__ import annotations

import math
import sys
import threading
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from .._infra.errors import InaccurateSolveError, InfeasibleError, ParameterError, SolverError
from .._model.parameters import Parameters
from .._infra.rational import short_rational, to_rational

__all__ = ["MODES", "DEFAULT_MARGIN", "Candidate", "Search", "find_candidate", "eigen_bounds_P", "check_mode", "check_margin"]

MODES: tuple[str, ...] = ("feasible", "tightest")
"""The two search modes."""

DEFAULT_MARGIN: dict[str, Fraction] = {"feasible": Fraction(1, 100), "tightest": Fraction(1, 10**6)}
"""Relative margin ``μ`` on every strict inequality, per mode."""

SOLVER = "CLARABEL"

_STATUS_OPTIMAL = "optimal"
_STATUS_INFEASIBLE = ("infeasible", "infeasible_inaccurate", "unbounded", "unbounded_inaccurate")


def check_mode(mode: object) -> str:
    """Return ``mode`` if it is one of :data:`MODES`, else raise ParameterError."""
    if mode not in MODES:
        raise ParameterError(f"mode must be one of {', '.join(repr(m) for m in MODES)}; got {mode!r}")
    return str(mode)


def check_margin(margin: object, mode: str) -> Fraction:
    """The relative margin as an exact Fraction in ``(0, 1]`` (default per mode)."""
    if margin is None:
        return DEFAULT_MARGIN[mode]
    q = to_rational(margin, name="margin")
    if not 0 < q <= 1:
        raise ParameterError(f"margin must be in (0, 1] (a relative margin); got margin = {short_rational(q)}")
    return q


@dataclass(frozen=True)
class Candidate:
    """A floating-point candidate returned by the search (not a proof).

    Attributes
    ----------
    params : Parameters
        The gains searched for.
    mode : str
        ``"feasible"`` or ``"tightest"``.
    margin : Fraction
        Relative margin ``μ`` imposed on the strict k-conditions.
    solver, status : str
        Solver name and the status it reported (always ``"optimal"`` for a
        returned candidate; other statuses raise).
    k : tuple of 4 floats
        The solver's ``(k₁, k₂, k₃, k₄)``, unscaled.
    objective : float
        ``λ_max(K)/2`` (tightest) or ``trace(K)/2`` (feasible) at the solver's
        ``k``, from the solver.
    lambda_min_P, lambda_max_P : float
        Extreme eigenvalues of ``P``, computed in closed form.
    """

    params: Parameters
    mode: str
    margin: Fraction
    solver: str
    status: str
    k: tuple[float, float, float, float]
    objective: float
    lambda_min_P: float
    lambda_max_P: float


def _float(q: Fraction) -> float:
    """``float(q)``, but ``±inf`` instead of OverflowError for huge rationals."""
    try:
        return float(q)
    except OverflowError:
        return math.inf if q > 0 else -math.inf


def eigen_bounds_P(params: Parameters) -> tuple[float, float]:
    """``(λ_min(P), λ_max(P))`` of eq. (lyapLikeP), accurate to a few ulps.

    ``λ_min(P) = min(1, λ₋)``, ``λ_max(P) = max(1, λ₊)`` where ``λ±`` are the
    eigenvalues of ``B = [[k_v/k_i, -1], [-1, k_p]]``; ``λ₊`` is a sum of
    positive terms and ``λ₋ = det B/λ₊`` with ``det B`` formed exactly, so both
    keep full relative precision (also when ``det B`` is 1e-9 or smaller).
    """
    a = params.k_v / params.k_i
    det = (params.k_v * params.k_p - params.k_i) / params.k_i  # exact, > 0 under Assumption 1
    lam_plus = (_float(a + params.k_p) + math.hypot(_float(a - params.k_p), 2.0)) / 2.0
    lam_minus = _float(det) / lam_plus
    return min(1.0, lam_minus), max(1.0, lam_plus)


def _lambda_max_K(k1: float, k2: float, k3: float, k4: float) -> float:
    return max(k2, (k1 + k4 + math.hypot(k1 - k4, 2.0 * k3)) / 2.0)


def _greedy_point(r: float, k_p: float, m: float) -> tuple[float, float, float, float]:
    """An explicit feasible ``k`` used as the scaling point (lower bounds taken in order)."""
    s1 = s2 = 2.0
    s3 = m * max(r * s1, s2)
    s4 = m * max(r * s3, k_p * s2, s3 * s3 / s1, 2.0)
    return s1, s2, s3, s4


def _interpret_status(status: str | None, params: Parameters, mode: str) -> None:
    """Raise unless ``status`` is exactly optimal (a solver status is never taken as a proof)."""
    if status == _STATUS_OPTIMAL:
        return
    gains = ", ".join(f"{k}={v}" for k, v in params.as_strings().items())
    if status in _STATUS_INFEASIBLE:
        raise InfeasibleError(f"{SOLVER} reports the {mode} search as {status} for gains {gains}; no certificate")
    raise InaccurateSolveError(
        f"{SOLVER} returned status {status!r} (not 'optimal') in the {mode} search for gains {gains}; no certificate"
    )


class Search:
    """The compiled search problem for one mode and margin; call it per gain set.

    The cvxpy problem is built once (DPP-compliant: the gains enter only
    through ``Parameter`` values multiplying variables) and each call only
    updates the parameter values and re-solves with Clarabel.

    Parameters
    ----------
    mode : {"tightest", "feasible"}, keyword-only
    margin : number or None, keyword-only
        Relative margin ``μ`` in ``(0, 1]``; default :data:`DEFAULT_MARGIN`.

    Examples
    --------
    >>> cand = Search(mode="tightest")(Parameters.table_i("a"))
    >>> cand.status, round(cand.objective, 3)
    ('optimal', 3.414)
    """

    def __init__(self, *, mode: str = "tightest", margin: object = None) -> None:
        import cvxpy as cp  # lazy: cvxpy takes about a second to import

        self.mode = check_mode(mode)
        self.margin = check_margin(margin, self.mode)
        m = float(1 + self.margin)
        self._m = m
        y = cp.Variable(4, name="y")  # scaled k1..k4
        t = cp.Variable(name="t")  # scaled λ_max(K)/2
        floor = cp.Parameter(3, name="floor")  # 2/s1, 2/s2, 2/s4
        alpha = cp.Parameter(4, name="alpha")  # scaled linear k-conditions
        beta = cp.Parameter(name="beta")  # s3/√(s1 s4)
        gamma = cp.Parameter(4, nonneg=True, name="gamma")  # s_j/(2 λ_max(K(s)))
        constraints = [
            y[0] >= floor[0],
            y[1] >= floor[1],
            y[3] >= floor[2],
            y[2] >= alpha[0] * y[0],  # k3 ≥ (1+μ)(k_i/k_v) k1
            y[2] >= alpha[1] * y[1],  # k3 ≥ (1+μ) k2
            y[3] >= alpha[2] * y[2],  # k4 ≥ (1+μ)(k_i/k_v) k3
            y[3] >= alpha[3] * y[1],  # k4 ≥ (1+μ) k_p k2
            # k1 k4 ≥ (1+μ) k3², congruent (by diag(1/√s1, 1/√s4)) to this 2×2 LMI
            cp.bmat([[y[0], beta * y[2]], [beta * y[2], y[3] / m]]) >> 0,
        ]
        if self.mode == "tightest":
            constraints.append(
                cp.bmat(
                    [
                        [t - gamma[0] * y[0], 0, -gamma[2] * y[2]],
                        [0, t - gamma[1] * y[1], 0],
                        [-gamma[2] * y[2], 0, t - gamma[3] * y[3]],
                    ]
                )
                >> 0
            )
            objective = cp.Minimize(t)
        else:
            objective = cp.Minimize(gamma[0] * y[0] + gamma[1] * y[1] + gamma[3] * y[3])
        self._problem = cp.Problem(objective, constraints)
        if not self._problem.is_dpp():  # guards future edits of the formulation
            raise SolverError("the certificate search problem is not DPP-compliant")
        self._y, self._t = y, t
        self._floor, self._alpha, self._beta, self._gamma = floor, alpha, beta, gamma
        self._cp = cp
        # one compiled problem holds the parameter values and the solution: serialise its use
        # so that a thread pool sharing this object cannot mix two gain sets
        self._lock = threading.Lock()

    def _solve(self) -> str | None:
        """Solve with the current parameter values; return cvxpy's status."""
        try:
            self._problem.solve(solver=SOLVER)
        except self._cp.error.SolverError as exc:
            return f"solver error: {exc}"
        return self._problem.status

    def __call__(self, params: Parameters) -> Candidate:
        """Search constants for ``params``; raise unless the solver says optimal.

        Raises
        ------
        InfeasibleError
            If the solver reports infeasible or unbounded.
        InaccurateSolveError
            For ``optimal_inaccurate`` or any other non-optimal status.
        """
        import numpy as np

        if not isinstance(params, Parameters):
            raise ParameterError(f"params must be a Parameters instance; got {type(params).__name__}")
        r = _float(params.k_i / params.k_v)
        k_p = _float(params.k_p)
        m = self._m
        s = _greedy_point(r, k_p, m)
        s1, s2, s3, s4 = s
        s_obj = _lambda_max_K(*s) if self.mode == "tightest" else (s1 + s2 + s4)
        lam_min, lam_max = eigen_bounds_P(params)
        # the search works in double precision: refuse gains whose data leave its normal range
        if not all(math.isfinite(x) and x >= sys.float_info.min for x in (r, k_p, s4, s_obj, lam_min, lam_max)):
            raise InaccurateSolveError(
                f"gains {params} are outside the double-precision range of the search "
                f"(k_i/k_v = {r:.3g}, k_p = {k_p:.3g}, λ_min(P) = {lam_min:.3g}, λ_max(P) = {lam_max:.3g}); no certificate"
            )
        with self._lock:
            self._floor.value = np.array([2.0 / s1, 2.0 / s2, 2.0 / s4])
            self._alpha.value = np.array([m * r * s1 / s3, m * s2 / s3, m * r * s3 / s4, m * k_p * s2 / s4])
            self._beta.value = s3 / math.sqrt(s1 * s4)
            self._gamma.value = np.array(s) / (2.0 * s_obj)
            status = self._solve()
            y = None if self._y.value is None else np.array(self._y.value)
            t = None if self._t.value is None else float(self._t.value)
        _interpret_status(status, params, self.mode)
        if y is None or not np.all(np.isfinite(y)):
            raise InaccurateSolveError(f"{SOLVER} reported optimal but returned no finite point for {params}")
        k = tuple(float(v) for v in np.asarray(y) * np.array(s))
        if self.mode == "tightest":
            objective = t * s_obj  # type: ignore[operator]
        else:
            objective = (k[0] + k[1] + k[3]) / 2.0
        return Candidate(
            params=params,
            mode=self.mode,
            margin=self.margin,
            solver=SOLVER,
            status=status,  # type: ignore[arg-type]
            k=k,  # type: ignore[arg-type]
            objective=objective,
            lambda_min_P=lam_min,
            lambda_max_P=lam_max,
        )


_CACHE: dict[tuple[str, Fraction], Search] = {}
_CACHE_LOCK = threading.Lock()


def find_candidate(params: Parameters, *, mode: str = "tightest", margin: Any = None) -> Candidate:
    """Search a candidate for ``params``, reusing one compiled problem per (mode, margin)."""
    mode = check_mode(mode)
    key = (mode, check_margin(margin, mode))
    with _CACHE_LOCK:
        searcher = _CACHE.get(key)
        if searcher is None:
            searcher = _CACHE[key] = Search(mode=mode, margin=key[1])
    return searcher(params)
