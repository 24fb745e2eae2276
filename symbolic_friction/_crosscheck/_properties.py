"""The certified inequalities, checked along sampled exact solutions.

Each property is one claim of the paper instantiated with a certificate's
constants (see :data:`PROPERTIES`):

* Lemma 2, item 2 (eq. Vdecrease): ``V(x(t₂)) - V(x(t₁)) ≤ -c ∫_{t₁}^{t₂} v² dt``
  for all sampled ``t₁ < t₂``, with ``V`` evaluated on *both sides* of every
  event (``V`` of eq. lyapLike is discontinuous exactly at mode changes);
  and its corollary ``V`` nonincreasing;
* Lemma 2, item 1: ``c₁|x|²_𝒜 ≤ V(x)`` everywhere; Lemma 3 (eq. VandR):
  ``V ≤ c₂|x|²_𝒜`` on ``R``;
* Lemma 3 (eqs. hatVandHatR, hatVdot): ``ĉ₁|x|²_𝒜 ≤ V̂ ≤ ĉ₂|x|²_𝒜`` on
  ``R̂`` and ``V̂`` nonincreasing on every time interval spent in ``R̂``;
* Proposition 1 (eq. stabState): ``|x(t)|_𝒜 ≤ κ|x(0)|_𝒜``; attractivity, in
  the finite-horizon form ``|x(T)|_𝒜 ≤ θ|x(0)|_𝒜``;
* the Remark after Lemma 2 (eq. armstrongRes): ``|σ|`` strictly decreases
  from one stick phase to the next;
* and, as a guard on the simulator itself, that each sample's mode agrees
  with its state (``sign v`` on a slip, ``v = 0`` and ``|φ| ≤ f_c`` on a
  stick), since the values of ``V`` are read through the modes, and that
  the closed-form flow gives ``v ≈ 0`` at every event time.

The integral ``∫ v²``
---------------------
Between two consecutive sampled points (samples and events merged in time
order) the solution stays in one affine mode (Claim 1).  On a slip ``k = ±1``,
``y = x - x*_k`` with ``x*_k = (0, k f_c, 0)`` solves ``y' = A y`` and
``v = e₃ᵀy``, so with ``W`` the observability Gramian of ``(A, e₃ᵀ)``,
i.e. the solution of ``AᵀW + WA = -e₃e₃ᵀ`` (``A`` is Hurwitz), the identity
``d/dt yᵀWy = -v²`` gives the closed form

.. math::

    \\int_{t_a}^{t_b} v(t)^2\\,dt = y(t_a)^\\top W y(t_a) - y(t_b)^\\top W y(t_b),

exact up to rounding, with no quadrature error.  ``W`` is computed from
``A`` alone by a Lyapunov solve (scipy); it shares nothing with ``P``, ``c``
or the certificate, so the check compares two independent computations.
(On a slip the paper's identity ``dV_k/dt = -c v²`` makes the inequality an
*equality*; its slack is ``0`` up to rounding there, and positive only
across the downward jumps of ``V``.)  The tests compare this closed form
with an mpmath quadrature of the exact solution.

Why consecutive points suffice
------------------------------
With ``S(t) = V(x(t)) + c∫_0^t v²``, the claim for *all* pairs ``t₁ < t₂``
is exactly "``S`` is nonincreasing on the sampled points", and the
integral is additive over adjacent intervals, so the consecutive
inequalities telescope into every pair.  Floating-point slack, however,
could add up over many steps; so the reported margin and failures are
computed over all pairs at once with a running minimum
(``min_{t₁<t₂} S(t₁) - S(t₂)``), in ``O(n)`` per trajectory.  The same holds
for ``V`` alone (``c = 0``).  For ``V̂`` on the intervals spent in ``R̂``
the same running minimum is restarted at the start of every interval.

Tolerance
---------
Every inequality ``lhs ≤ rhs`` is reported through its *relative slack*
``(rhs - lhs)/scale``, with ``scale`` the size the two sides can have on
that trajectory (``L = max_t |x(t)| + f_c`` for distances and ``|σ|``;
``coef·L²`` for quadratic forms, ``coef`` the largest coefficient
involved).  A violation is a relative slack below ``-rtol``.  The
event-driven simulator matches an independent mpmath reference to about
``1e-10`` relative (issue 4), so a state error ``δx`` is about
``1e-10·L`` and a quadratic form ``xᵀMx`` errs by about
``2·|M|·L·δx ≈ 2e-10·|M|L²``; with the default ``rtol = 1e-8`` the margin
of safety is a factor of at least 50, while every genuine violation found
by the tests is larger than ``1e-3`` relative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Callable

import numpy as np

from .._errors import ParameterError, SimulationError
from .._parameters import Parameters
from .._simulation._trajectories import Trajectories
from ._claims import Claims

__all__ = [
    "DEFAULT_RTOL",
    "DEFAULT_THETA",
    "PROPERTIES",
    "PropertySpec",
    "Counterexample",
    "PropertyResult",
    "BatchChecker",
    "observability_gramian",
]

DEFAULT_RTOL = 1e-8
"""Relative tolerance of every check (justified in the module docstring)."""

DEFAULT_THETA = 0.5
"""Attractivity on a finite horizon: ``|x(T)|_𝒜 ≤ θ |x(0)|_𝒜`` is required."""


@dataclass(frozen=True)
class PropertySpec:
    """One checked claim: id, paper reference and the inequality in words."""

    id: str
    paper: str
    inequality: str


PROPERTIES: tuple[PropertySpec, ...] = (
    PropertySpec(
        "lemma2.decrease", "Lemma 2, item 2 (eq. Vdecrease)", "V(x(t2)) - V(x(t1)) <= -c ∫ v² dt, all t1 < t2"
    ),
    PropertySpec("lemma2.nonincreasing", "Lemma 2, item 2", "V(x(t2)) <= V(x(t1)), both sides of every event"),
    PropertySpec("lemma2.lower_bound", "Lemma 2, item 1", "c1 |x|²_A <= V(x)"),
    PropertySpec("lemma3.V_upper", "Lemma 3 (eq. VandR)", "V(x) <= c2 |x|²_A on R"),
    PropertySpec("lemma3.hatV_lower", "Lemma 3 (eq. hatVandHatR)", "c1_hat |x|²_A <= V̂(x) on R̂"),
    PropertySpec("lemma3.hatV_upper", "Lemma 3 (eq. hatVandHatR)", "V̂(x) <= c2_hat |x|²_A on R̂"),
    PropertySpec("lemma3.hatV_nonincreasing", "Lemma 3 (eq. hatVdot)", "V̂(x(t2)) <= V̂(x(t1)) on intervals in R̂"),
    PropertySpec("prop1.stability", "Proposition 1, item 2 (eq. stabState)", "|x(t)|_A <= kappa |x(0)|_A"),
    PropertySpec("prop1.attractivity", "Proposition 1, item 1", "|x(T)|_A <= theta |x(0)|_A at the horizon T"),
    PropertySpec(
        "remark.stick_sigma", "Remark after Lemma 2 (eq. armstrongRes)", "|sigma| strictly decreases between stick phases"
    ),
    PropertySpec("model.modes", "Claim 1 / appendix table", "modes agree with the states; v = 0 at events"),
)
_SPEC = {p.id: p for p in PROPERTIES}


@dataclass(frozen=True)
class Counterexample:
    """A violated inequality on one trajectory.

    Attributes
    ----------
    property, certificate : str
        Property id and certificate label.
    trajectory : int
        Index of the trajectory in the cross-check run.
    source : str
        Where its initial state came from.
    z0, x0 : tuple of float
        Initial state in ``z = (e_i, s, v)`` and in ``x = (σ, φ, v)``.
    t : float
        Time of the violation (``t₂`` for a two-time inequality).
    t_start : float or None
        ``t₁`` for a two-time inequality.
    x : tuple of float
        State at ``t``.
    values : dict
        The two sides, the slack, the tolerance and any other number used
        (numbers or short lists of numbers).
    relative_slack : float
        ``(rhs - lhs)/scale`` (below ``-rtol`` for a violation).
    exact : bool or None
        For a pointwise inequality: whether it also fails in exact rational
        arithmetic at the (float) state ``x``; ``None`` when not applicable.
    """

    property: str
    certificate: str
    trajectory: int
    source: str
    z0: tuple[float, float, float]
    x0: tuple[float, float, float]
    t: float
    t_start: float | None
    x: tuple[float, float, float]
    values: dict[str, Any]
    relative_slack: float
    exact: bool | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready mapping (floats written with full precision)."""
        return {
            "property": self.property,
            "paper": _SPEC[self.property].paper if self.property in _SPEC else "",
            "inequality": _SPEC[self.property].inequality if self.property in _SPEC else "",
            "certificate": self.certificate,
            "trajectory": self.trajectory,
            "source": self.source,
            "z0": list(self.z0),
            "x0": list(self.x0),
            "t": self.t,
            "t_start": self.t_start,
            "x": list(self.x),
            "values": dict(self.values),
            "relative_slack": self.relative_slack,
            "confirmed_in_exact_arithmetic": self.exact,
        }


@dataclass(frozen=True)
class PropertyResult:
    """Outcome of one property on one certificate.

    Attributes
    ----------
    id, paper, inequality : str
    trajectories : int
        Trajectories on which the inequality was checked at least once.
    samples : int
        Instances of the inequality checked (sampled points or pairs).
    worst_margin : float
        Smallest relative slack seen (``nan`` if nothing was checked).
    failures : int
        Instances with relative slack below ``-rtol``.
    counterexample : Counterexample or None
        The worst violation, if any.
    inconclusive : int
        Instances that can neither pass nor fail on this horizon (e.g. a
        trajectory still in its first stick phase at ``T``).
    details : dict
        Extra statistics (e.g. the largest observed overshoot).
    """

    id: str
    paper: str
    inequality: str
    trajectories: int
    samples: int
    worst_margin: float
    failures: int
    counterexample: Counterexample | None = None
    inconclusive: int = 0
    details: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        return self.failures == 0


# ---------------------------------------------------------------------------------------------
def observability_gramian(params: Parameters) -> np.ndarray:
    """``W`` with ``AᵀW + WA = -e₃e₃ᵀ``: ``∫_0^∞ v² dt = yᵀWy`` for ``y' = Ay``, ``v = e₃ᵀy``."""
    from scipy.linalg import solve_continuous_lyapunov

    from .._coordinates import system_matrix

    A = system_matrix(params)
    Q = np.zeros((3, 3))
    Q[2, 2] = -1.0
    W = solve_continuous_lyapunov(A.T, Q)
    return 0.5 * (W + W.T)


class _Acc:
    """Running min/failure count of one property over chunks of trajectories."""

    def __init__(self, spec: PropertySpec, rtol: float) -> None:
        self.spec = spec
        self.rtol = rtol
        self.trajectories = 0
        self.samples = 0
        self.failures = 0
        self.inconclusive = 0
        self.worst = math.inf
        self.counterexample: Counterexample | None = None
        self.details: dict[str, Any] = {}

    def add(
        self,
        rel: np.ndarray,
        mask: np.ndarray,
        make: Callable[[tuple[int, ...]], Counterexample],
        *,
        count_trajectories: bool = True,
    ) -> None:
        """Fold in relative slacks ``rel`` where ``mask`` (first axis = trajectory).

        ``count_trajectories=False`` for a second call on the same trajectories.
        """
        if not np.any(mask):
            return
        self.samples += int(np.count_nonzero(mask))
        if count_trajectories:
            per_traj = mask.reshape(mask.shape[0], -1).any(axis=1)
            self.trajectories += int(np.count_nonzero(per_traj))
        r = np.where(mask, rel, np.inf)
        # NaN slack (should not happen) counts as a failure rather than being hidden
        r = np.where(np.isnan(r) & mask, -np.inf, r)
        self.failures += int(np.count_nonzero(r < -self.rtol))
        idx = np.unravel_index(int(np.argmin(r)), r.shape)
        low = float(r[idx])
        if low < self.worst:
            self.worst = low
            if low < -self.rtol:
                self.counterexample = make(tuple(int(i) for i in idx))

    def extreme(self, key: str, values: np.ndarray, mask: np.ndarray, *, largest: bool) -> None:
        """Track the smallest (or largest) of ``values`` where ``mask`` in ``details[key]``."""
        if not np.any(mask):
            return
        v = float(np.max(values[mask]) if largest else np.min(values[mask]))
        old = self.details.get(key)
        if old is None or (v > old if largest else v < old):
            self.details[key] = v

    def result(self) -> PropertyResult:
        return PropertyResult(
            id=self.spec.id,
            paper=self.spec.paper,
            inequality=self.spec.inequality,
            trajectories=self.trajectories,
            samples=self.samples,
            worst_margin=self.worst if self.samples else math.nan,
            failures=self.failures,
            counterexample=self.counterexample,
            inconclusive=self.inconclusive,
            details=dict(self.details),
        )


@dataclass(frozen=True, eq=False)
class _Chain:
    """Samples and events of a chunk, merged in time order (per trajectory).

    Each event appears three times, at the same time and state: its left
    limit (kind 0, the mode before), the value at the event (kind 1) and its
    right limit (kind 2, the mode after).  Samples have kind 3.
    """

    t: np.ndarray  # (N, L), +inf in the padding
    kind: np.ndarray  # (N, L)
    x: np.ndarray  # (N, L, 3)
    piece: np.ndarray  # (N, L) which V_k gives V here: -1, 0, 1, or 2 for the value at an event
    right_mode: np.ndarray  # (N, L) mode on the interval to the next point
    sample: np.ndarray  # (N, L) sample index j, or -1
    valid: np.ndarray  # (N, L)


def _build_chain(batch: Trajectories) -> _Chain:
    N, n = batch.mode.shape
    E = batch.event_t.shape[1]
    t = batch.t
    # samples after an incomplete simulation stopped are NaN: they were never simulated, drop them
    keep = np.isfinite(batch.x).all(axis=-1)
    ev_valid = np.isfinite(batch.event_t)
    if E:
        # A sample at an event time duplicates the event and its mode is ambiguous: drop it.
        eps = 1e-12 * max(1.0, float(t[-1]))
        et = np.where(ev_valid, batch.event_t, -np.inf)
        j = np.clip(np.searchsorted(t, et), 0, n - 1)
        for jj in (j, np.clip(j - 1, 0, n - 1)):
            hit = ev_valid & (np.abs(t[jj] - et) <= eps)
            rows, cols = np.nonzero(hit)
            keep[rows, jj[rows, cols]] = False
    s_t = np.where(keep, t[None, :], np.inf)
    e_t = np.where(ev_valid, batch.event_t, np.inf)
    times = np.concatenate([e_t, e_t, e_t, s_t], axis=1)
    kind = np.concatenate(
        [np.zeros((N, E), np.int8), np.ones((N, E), np.int8), np.full((N, E), 2, np.int8), np.full((N, n), 3, np.int8)],
        axis=1,
    )
    x = np.concatenate([batch.event_x, batch.event_x, batch.event_x, batch.x], axis=1)
    before = batch.event_before.astype(np.int8)
    after = batch.event_after.astype(np.int8)
    smode = batch.mode.astype(np.int8)
    piece = np.concatenate([before, np.full((N, E), 2, np.int8), after, smode], axis=1)
    right = np.concatenate([before, after, after, smode], axis=1)
    sample = np.concatenate([np.full((N, 3 * E), -1), np.broadcast_to(np.arange(n), (N, n))], axis=1)
    order = np.lexsort((kind, times), axis=-1)
    take = lambda a: np.take_along_axis(a, order, axis=1)  # noqa: E731
    times = take(times)
    x = np.take_along_axis(x, order[..., None], axis=1)
    # v = 0 at an event by definition of an event; the stored state may carry a rounding residue.
    kind_s = take(kind)
    x[..., 2] = np.where(kind_s < 3, 0.0, x[..., 2])
    return _Chain(
        t=times,
        kind=kind_s,
        x=x,
        piece=take(piece),
        right_mode=take(right),
        sample=take(sample),
        valid=np.isfinite(times),
    )


class BatchChecker:
    """Check certificates sharing one gain set on batches of trajectories.

    Parameters
    ----------
    params : Parameters
    claims : sequence of Claims
        Certificates for ``params`` (e.g. the feasible and the tightest one).
    rtol : float, keyword-only
        Relative tolerance (module docstring).
    theta : float, keyword-only
        Attractivity factor at the horizon.

    Feed batches with :meth:`add`; read :meth:`results`.
    """

    def __init__(
        self, params: Parameters, claims: list[Claims], *, rtol: float = DEFAULT_RTOL, theta: float = DEFAULT_THETA
    ) -> None:
        from .._lyapunov import lyapunov_matrix

        for cl in claims:
            if cl.params != params:
                raise ParameterError(
                    f"certificate {cl.label} has gains {cl.params}; a checker for {params} takes only those gains"
                )
        self.params = params
        self.claims = list(claims)
        self.rtol = float(rtol)
        self.theta = float(theta)
        self.k_p, self.k_i, self.k_v, self.f_c = params.as_floats()
        self.W = observability_gramian(params)
        self.lam_P = float(np.linalg.eigvalsh(lyapunov_matrix(params))[-1])
        self._accs = [{spec.id: _Acc(spec, self.rtol) for spec in PROPERTIES} for _ in self.claims]
        self._offset = 0
        self._overshoot: list[np.ndarray] = []
        self._sources: list[np.ndarray] = []
        self._final_ratio: list[np.ndarray] = []
        self._final_z: list[np.ndarray] = []
        self._pending: list[tuple] = []
        self.incomplete = 0
        """Trajectories the simulator could not finish (event limit): never checked as holding."""
        self.incomplete_examples: list[tuple[str, tuple[float, float, float]]] = []
        self.max_events = 10_000
        from .._simulation.affine import MatrixExponential

        self._expm = MatrixExponential.from_params(params)

    # -- the functions of the paper: the package's one model, vectorised ----------------
    def _V_piece(self, x: np.ndarray, piece: np.ndarray) -> np.ndarray:
        """``V_k`` of eq. (subcasesAffine:Vs) for ``k = piece``; ``piece = 2``: ``V`` of eq. (lyapLike) at ``v = 0``."""
        from .._lyapunov import V, V_k

        at_rest = x * np.array([1.0, 1.0, 0.0])
        out = np.where(piece == 1, V_k(self.params, x, 1), 0.0)
        out = np.where(piece == -1, V_k(self.params, x, -1), out)
        out = np.where(piece == 0, V_k(self.params, x, 0), out)
        return np.where(piece == 2, V(self.params, at_rest), out)

    def _d2(self, x: np.ndarray) -> np.ndarray:
        from .._attractor import squared_distance_x

        return squared_distance_x(self.params, x)

    def _gram(self, x: np.ndarray, k: np.ndarray) -> np.ndarray:
        """``yᵀWy`` with ``y = x - (0, k f_c, 0)``."""
        y = x.copy()
        y[..., 1] -= k * self.f_c
        return np.einsum("...i,ij,...j->...", y, self.W, y)

    # -- main entry ----------------------------------------------------------------------
    def add(self, batch: Trajectories, *, attractivity: bool = True) -> None:
        """Check every certificate on the trajectories of ``batch``.

        ``attractivity=False`` skips the horizon test (for short adversarial runs).
        """
        if batch.params != self.params:
            raise ParameterError(f"the batch was simulated with {batch.params}; this checker is for {self.params}")
        if batch.t.size > 1 and not np.all(batch.t[1:] > batch.t[:-1]):
            # the chain of samples and events below divides by the time between samples
            raise SimulationError("the cross-check needs strictly increasing sample times")
        N = batch.size
        if N == 0:
            return
        complete = np.asarray(batch.complete, dtype=bool)
        if not complete.all():
            self.incomplete += int(np.count_nonzero(~complete))
            for i in np.flatnonzero(~complete)[: 5 - len(self.incomplete_examples)]:
                self.incomplete_examples.append((str(batch.source[i]), tuple(float(q) for q in batch.z0[i])))
        ch = _build_chain(batch)
        f_c = self.f_c
        valid = ch.valid
        xs = ch.x
        # Per-trajectory scales (module docstring): L = max |x| + f_c.
        norms = np.where(valid, np.linalg.norm(xs, axis=-1), 0.0)
        L = np.maximum(norms.max(axis=1), np.linalg.norm(batch.x0, axis=1)) + f_c
        Q = L * L
        Vv = np.where(valid, self._V_piece(xs, ch.piece), np.nan)
        d2 = self._d2(xs)
        d = np.sqrt(d2)
        d0 = np.sqrt(self._d2(batch.x0))
        pair = valid[:, 1:] & valid[:, :-1]
        dt_pos = pair & (ch.t[:, 1:] > ch.t[:, :-1])
        k_int = ch.right_mode[:, :-1]
        slip = dt_pos & (k_int != 0)
        # ∫ v² between consecutive points (closed form, module docstring)
        kk = np.where(slip, k_int, 0).astype(float)
        I = np.where(slip, self._gram(xs[:, :-1], kk) - self._gram(xs[:, 1:], kk), 0.0)
        cumI = np.concatenate([np.zeros((N, 1)), np.cumsum(I, axis=1)], axis=1)
        is_sample = ch.kind == 3
        at_event = ch.kind == 1
        point = valid & (is_sample | at_event)  # distinct states (limits duplicate the event state)
        # R and R̂ (Lemma 3) with sign(v) read from the mode (the sample's own mode is the
        # mode of the solution through it; v's float sign is unreliable next to an event).
        smode = np.where(is_sample, ch.piece, 0)
        from .._lyapunov import in_R as _in_R

        # the package's R with v replaced by the mode's sign (R depends on v only through it, and through v ≠ 0)
        signed = np.stack([xs[..., 0], xs[..., 1], smode.astype(float)], axis=-1)
        in_Rhat = valid & is_sample & ~_in_R(self.params, np.where(np.isfinite(signed), signed, 0.0))
        in_R = point & ~in_Rhat
        # Points of 𝒜 make both sides of the homogeneous bounds vanish identically (V = V̂ = 0
        # there, Lemma 2 item 1): they are left out of those bounds so the margins stay informative.
        off_A = d2 > 0

        helpers = dict(batch=batch, ch=ch, L=L, d=d, d0=d0)
        # model.modes (certificate-independent, computed once)
        v = xs[..., 2]
        tol_lin = self.rtol * L[:, None]
        stick = valid & is_sample & (ch.piece == 0)
        slipmask = valid & is_sample & (ch.piece != 0)
        rel_modes = np.where(
            stick,
            -np.maximum(np.abs(v), np.abs(xs[..., 1]) - f_c) / L[:, None],
            np.where(slipmask, ch.piece * v / L[:, None], np.inf),
        )
        # Stick phases (Remark after Lemma 2): starts at events entering mode 0, or at t = 0.
        sig_prev, sig_next, t_prev, t_next, stick_ok = self._stick_pairs(batch)
        # Overshoot and attractivity (certificate-independent numbers)
        dmax = np.where(point, d, -np.inf).max(axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            # an incomplete trajectory's maximum is over part of [0, T] only: not a measurement
            overshoot = np.where((d0 > 0) & complete, dmax / d0, np.nan)
        d_final = d[:, :][np.arange(N), self._last_sample_pos(ch)]
        if attractivity:
            with np.errstate(divide="ignore", invalid="ignore"):
                self._final_ratio.append(np.where(complete, np.where(d0 > 0, d_final / d0, 0.0), np.nan))
            # In z (Proposition 1, item 1): s, v → 0 and e_i enters [-f_c/k_i, f_c/k_i].
            from .._coordinates import x_to_z

            zT = x_to_z(self.params, batch.x[:, -1, :])
            from .._attractor import attractor_bound_z

            bound = float(attractor_bound_z(self.params))
            self._final_z.append(np.stack([np.abs(zT[:, 1]), np.abs(zT[:, 2]),
                                           np.maximum(np.abs(zT[:, 0]) - bound, 0.0)], axis=1))
        self._overshoot.append(overshoot)
        self._sources.append(np.asarray(batch.source))

        for ci, cl in enumerate(self.claims):
            acc = self._accs[ci]
            coefV = max(self.lam_P, cl.c1, cl.c2)
            scaleV = (coefV * Q)[:, None]
            # Lemma 2, item 2 over all pairs: S = V + c ∫v² nonincreasing (running min)
            for pid, c in (("lemma2.decrease", cl.c), ("lemma2.nonincreasing", 0.0)):
                S = np.where(valid, Vv + c * cumI, np.nan)
                Sm = np.where(valid, S, np.inf)
                run_min = np.minimum.accumulate(Sm, axis=1)
                slack = run_min[:, :-1] - S[:, 1:]
                rel = slack / scaleV
                acc[pid].add(rel, pair, lambda idx, S=S, run_min=run_min, c=c, pid=pid: self._cx_pair(
                    pid, cl, helpers, idx, S, Vv, cumI, c, scaleV))
            # Lemma 2, item 1 at every point (both limits at events too)
            rel = (Vv - cl.c1 * d2) / scaleV
            acc["lemma2.lower_bound"].add(rel, valid & off_A, lambda idx: self._cx_point(
                "lemma2.lower_bound", cl, helpers, idx, {"V": Vv[idx], "c1": cl.c1, "dist2": d2[idx]},
                rel[idx], exact="lower"))
            # Lemma 3 (eq. VandR): V <= c2 |x|² on R (samples and event values)
            rel = (cl.c2 * d2 - Vv) / scaleV
            acc["lemma3.V_upper"].add(rel, in_R & off_A, lambda idx: self._cx_point(
                "lemma3.V_upper", cl, helpers, idx, {"V": Vv[idx], "c2": cl.c2, "dist2": d2[idx]},
                rel[idx], exact="upper"))
            # Lemma 3 (eq. hatVandHatR) on R̂
            Vh = self._V_hat(xs, cl)
            coefH = max(cl.lambda_max_K_half(), cl.c1_hat, cl.c2_hat)
            scaleH = (coefH * Q)[:, None]
            rel = (Vh - cl.c1_hat * d2) / scaleH
            acc["lemma3.hatV_lower"].add(rel, in_Rhat & off_A, lambda idx: self._cx_point(
                "lemma3.hatV_lower", cl, helpers, idx, {"V_hat": Vh[idx], "c1_hat": cl.c1_hat, "dist2": d2[idx]},
                rel[idx], exact="hat_lower"))
            rel = (cl.c2_hat * d2 - Vh) / scaleH
            acc["lemma3.hatV_upper"].add(rel, in_Rhat & off_A, lambda idx: self._cx_point(
                "lemma3.hatV_upper", cl, helpers, idx, {"V_hat": Vh[idx], "c2_hat": cl.c2_hat, "dist2": d2[idx]},
                rel[idx], exact="hat_upper"))
            # How tight each constant is: the extreme observed ratios V/|x|²_𝒜 and V̂/|x|²_𝒜,
            # away from 𝒜 (|x|²_𝒜 ≥ 1e-6 L², where rounding cannot blur the ratio).
            far = d2 >= 1e-6 * Q[:, None]
            with np.errstate(divide="ignore", invalid="ignore"):
                rV = Vv / d2
                rH = Vh / d2
            acc["lemma2.lower_bound"].extreme("min V/|x|²", rV, valid & far, largest=False)
            acc["lemma3.V_upper"].extreme("max V/|x|² on R", rV, in_R & far, largest=True)
            acc["lemma3.hatV_lower"].extreme("min V̂/|x|² on R̂", rH, in_Rhat & far, largest=False)
            acc["lemma3.hatV_upper"].extreme("max V̂/|x|² on R̂", rH, in_Rhat & far, largest=True)
            # Lemma 3 (eq. hatVdot): V̂ nonincreasing on intervals spent in R̂
            run = self._rhat_pairs(batch, ch, in_Rhat, dt_pos, k_int)
            slack, first = self._run_slack(Vh, run)
            rel = slack / scaleH
            acc["lemma3.hatV_nonincreasing"].add(
                rel, run, lambda idx: self._cx_hat_pair(cl, helpers, idx, Vh, first, rel)
            )
            # Proposition 1, stability, at samples and events
            rel = (cl.kappa * d0[:, None] - d) / L[:, None]
            acc["prop1.stability"].add(rel, point, lambda idx: self._cx_point(
                "prop1.stability", cl, helpers, idx,
                {"dist": d[idx], "dist0": d0[idx[0]], "kappa": cl.kappa,
                 "observed_ratio": d[idx] / d0[idx[0]] if d0[idx[0]] > 0 else math.inf}, rel[idx]))
            # Proposition 1, attractivity at the horizon (finite-horizon surrogate)
            if attractivity:
                # Finite-horizon surrogate of |x(t)|_𝒜 → 0: reach θ|x(0)|_𝒜 by T.  Decay can be
                # very slow (a stick phase from σ̄ lasts ≈ 2f_c/|σ̄| with |x|_𝒜 = |σ̄| constant),
                # so trajectories that have not yet made it are re-simulated on a longer
                # horizon by :meth:`resolve_attractivity` before being called failures.
                rel = (self.theta * d0 - d_final) / L
                conclusive = (d0 > 0) & complete
                ok = conclusive & (rel >= -self.rtol)
                acc["prop1.attractivity"].add(rel, ok, lambda idx: None)  # type: ignore[arg-type,return-value]
                if ci == 0:
                    for i in np.nonzero(conclusive & ~ok)[0]:
                        self._pending.append((self._offset + int(i), batch.z0[i].copy(), batch.x0[i].copy(),
                                              float(d0[i]), float(L[i]), str(batch.source[i]), float(batch.t[-1])))
            # Remark after Lemma 2
            rel = (np.abs(sig_prev) - np.abs(sig_next)) / L[:, None]
            acc["remark.stick_sigma"].add(rel, stick_ok, lambda idx: self._cx_stick(
                cl, helpers, idx, sig_prev, sig_next, t_prev, t_next, rel))
            strict_unclear = stick_ok & (np.abs(rel) <= self.rtol)
            acc["remark.stick_sigma"].inconclusive += int(np.count_nonzero(strict_unclear))
            # model.modes
            acc["model.modes"].add(rel_modes, valid & is_sample, lambda idx: self._cx_point(
                "model.modes", cl, helpers, idx, {"mode": float(ch.piece[idx]), "v": float(v[idx]),
                                                  "phi": float(xs[idx][1]), "f_c": f_c}, rel_modes[idx]))
            # ... and every event is a zero of v: the flow up to the event time must give v ≈ 0
            rel_ev = -batch.event_residual / L[:, None]
            acc["model.modes"].add(rel_ev, np.isfinite(batch.event_t), lambda idx: Counterexample(
                **self._base("model.modes", cl, helpers, idx[0]), t=float(batch.event_t[idx]), t_start=None,
                x=tuple(float(q) for q in batch.event_x[idx]),
                values={"v_at_event_time": float(batch.event_residual[idx]), "tolerance_relative": self.rtol},
                relative_slack=float(rel_ev[idx])), count_trajectories=False)
        self._offset += N

    # -- pieces ---------------------------------------------------------------------------
    def _V_hat(self, x: np.ndarray, cl: Claims) -> np.ndarray:
        from .._lyapunov import V_hat

        return V_hat(self.params, x, cl.k)

    def _last_sample_pos(self, ch: _Chain) -> np.ndarray:
        pos = np.where(ch.valid & (ch.kind == 3), np.arange(ch.t.shape[1])[None, :], -1)
        return pos.max(axis=1)

    def _rhat_pairs(self, batch: Trajectories, ch: _Chain, in_Rhat: np.ndarray, dt_pos: np.ndarray,
                    k_int: np.ndarray) -> np.ndarray:
        """Consecutive points whose open interval lies in R̂ (so V̂ must not increase)."""
        f_c = self.f_c
        end_ok = in_Rhat | (ch.valid & (ch.kind < 3))  # events bound R̂ intervals (V̂ is continuous)
        run = dt_pos & (k_int != 0) & end_ok[:, :-1] & end_ok[:, 1:]
        # An interval between two events, with no sample in R̂, may lie in R: skip it.
        run &= in_Rhat[:, :-1] | in_Rhat[:, 1:]
        # The solution may leave R̂ (φ crossing k f_c) and come back between two points
        # without any event: look at interior points of the exact closed-form flow.
        if np.any(run):
            rows, cols = np.nonzero(run)
            k = k_int[rows, cols].astype(float)
            star = np.zeros((rows.size, 3))
            star[:, 1] = k * f_c
            y = ch.x[rows, cols] - star
            h = ch.t[rows, cols + 1] - ch.t[rows, cols]
            q = np.array([0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875])
            taus = h[:, None] * q[None, :]
            mids = self._expm.apply(taus, np.broadcast_to(y[:, None, :], taus.shape + (3,))) + star[:, None, :]
            from .._lyapunov import in_R as _in_R

            # still in the same slip (k v > 0) and in the package's R̂
            inside = ((k[:, None] * mids[..., 2]) > 0) & ~_in_R(self.params, mids)
            run[rows, cols] = inside.all(axis=1)
        return run

    def _stick_pairs(self, batch: Trajectories):
        """``(σ_n, σ_{n+1}, t_n, t_{n+1}, mask)`` for consecutive stick phases of positive length."""
        N = batch.size
        E = batch.event_t.shape[1]
        T = float(batch.t[-1])
        ev_ok = np.isfinite(batch.event_t)
        starts_t = np.concatenate([np.zeros((N, 1)), np.where(ev_ok, batch.event_t, np.inf)], axis=1)
        starts_x = np.concatenate([batch.x0[:, None, :], batch.event_x], axis=1)
        starts_sig = starts_x[..., 0]
        is_start = np.concatenate([(batch.mode[:, :1] == 0), (batch.event_after == 0) & ev_ok], axis=1)
        # length of the stick phase: up to the next event (or the horizon)
        nxt = np.concatenate([starts_t[:, 1:], np.full((N, 1), np.inf)], axis=1)
        end = np.minimum(nxt, T)
        is_start &= end > starts_t
        idx = np.where(is_start, np.arange(E + 1)[None, :], -1)
        last = np.maximum.accumulate(idx, axis=1)
        prev = np.concatenate([np.full((N, 1), -1), last[:, :-1]], axis=1)
        ok = is_start & (prev >= 0)
        prev_c = np.clip(prev, 0, None)
        sig_prev = np.take_along_axis(starts_sig, prev_c, axis=1)
        t_prev = np.take_along_axis(starts_t, prev_c, axis=1)
        self._stick_x = starts_x
        return sig_prev, starts_sig, t_prev, starts_t, ok

    # -- counterexamples ------------------------------------------------------------------------
    def _base(self, prop: str, cl: Claims, h: dict, i: int) -> dict[str, Any]:
        b: Trajectories = h["batch"]
        return dict(
            property=prop,
            certificate=cl.label,
            trajectory=self._offset + i,
            source=str(b.source[i]),
            z0=tuple(float(q) for q in b.z0[i]),
            x0=tuple(float(q) for q in b.x0[i]),
        )

    def _cx_point(self, prop: str, cl: Claims, h: dict, idx: tuple[int, int], values: dict, rel: float,
                  exact: str | None = None) -> Counterexample:
        ch: _Chain = h["ch"]
        i, p = idx
        x = tuple(float(q) for q in ch.x[i, p])
        vals = {k: float(v) for k, v in values.items()}
        vals["tolerance_relative"] = self.rtol
        vals["scale"] = float(h["L"][i])
        return Counterexample(
            **self._base(prop, cl, h, i), t=float(ch.t[i, p]), t_start=None, x=x, values=vals,
            relative_slack=float(rel), exact=self._exact_pointwise(exact, cl, x) if exact else None,
        )

    def _cx_pair(self, prop, cl, h, idx, S, Vv, cumI, c, scaleV) -> Counterexample:
        ch: _Chain = h["ch"]
        i, p = idx  # pair (a, p+1) with a = argmin S over [0, p]
        b = p + 1
        a = int(np.nanargmin(np.where(ch.valid[i, : b], S[i, : b], np.inf)))
        integral = float(cumI[i, b] - cumI[i, a])
        vals = {
            "V_t1": float(Vv[i, a]), "V_t2": float(Vv[i, b]), "integral_v2": integral, "c": float(c),
            "lhs": float(Vv[i, b] - Vv[i, a]), "rhs": float(-c * integral),
            "tolerance_relative": self.rtol, "scale": float(scaleV[i, 0]),
        }
        rel = (S[i, a] - S[i, b]) / scaleV[i, 0]
        return Counterexample(
            **self._base(prop, cl, h, i), t=float(ch.t[i, b]), t_start=float(ch.t[i, a]),
            x=tuple(float(q) for q in ch.x[i, b]), values=vals, relative_slack=float(rel),
        )

    def _cx_hat_pair(self, cl, h, idx, Vh, first, rel) -> Counterexample:
        ch: _Chain = h["ch"]
        i, p = idx
        b = p + 1
        # the earlier point of the same R̂ interval with the smallest V̂
        seg = np.arange(int(first[i, p]), b)
        a = int(seg[np.argmin(Vh[i, seg])])
        vals = {"V_hat_t1": float(Vh[i, a]), "V_hat_t2": float(Vh[i, b]), "increase": float(Vh[i, b] - Vh[i, a]),
                "x_t1": [float(q) for q in ch.x[i, a]], "tolerance_relative": self.rtol}
        # Exact witness: V̂ grows at x(t1) itself (eq. hatVdot fails there) if its derivative
        # along the flow, in rational arithmetic, is positive.
        rate = self._exact_hat_rate(cl, tuple(float(q) for q in ch.x[i, a]))
        if rate is not None:
            vals["dV_hat_dt_at_t1"] = float(rate)
        return Counterexample(
            **self._base("lemma3.hatV_nonincreasing", cl, h, i), t=float(ch.t[i, b]), t_start=float(ch.t[i, a]),
            x=tuple(float(q) for q in ch.x[i, b]), values=vals, relative_slack=float(rel[i, p]),
            exact=None if rate is None else bool(rate > 0),
        )

    def _exact_hat_rate(self, cl: Claims, x: tuple[float, float, float]) -> Fraction | None:
        """``V̂°`` (eq. hatVdot) at ``x ∈ R̂``, exactly, from the package's model (``None`` outside R̂)."""
        from .._lyapunov import V_hat_rate, in_R

        if not all(math.isfinite(q) for q in x):
            return None
        xq = [Fraction(q) for q in x]
        if in_R(self.params, xq):
            return None
        k = tuple(Fraction(cl.exact[name]) for name in ("k1", "k2", "k3", "k4"))
        return V_hat_rate(self.params, xq, k)

    @staticmethod
    def _run_slack(F: np.ndarray, run: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """All-pairs slack ``min_{a<b in the same run} F_a - F_b`` for each pair ``(b-1, b)`` of a run.

        A run is a maximal chain of consecutive pairs with ``run`` true (one
        time interval spent in R̂).  The running minimum is restarted at each
        run by subtracting ``run id × K`` with ``K`` larger than the spread of
        ``F`` in the row, so that earlier runs never win the minimum.
        Returns the slack (shape of ``run``) and the index where each run starts.
        """
        N, L1 = run.shape
        prev = np.concatenate([np.zeros((N, 1), bool), run[:, :-1]], axis=1)
        start = run & ~prev  # pair p starts a run at point p
        node_start = np.concatenate([start, np.zeros((N, 1), bool)], axis=1)
        rid = np.cumsum(node_start, axis=1).astype(float)
        Ff = np.where(np.isfinite(F), F, 0.0)
        K = 2.0 * np.abs(Ff).max(axis=1, keepdims=True) + 1.0
        shifted = Ff - rid * K
        cm = np.minimum.accumulate(shifted, axis=1)
        run_min = cm[:, :-1] + rid[:, 1:] * K  # min over the run's points up to p, for the pair (p, p+1)
        slack = np.where(run, run_min - Ff[:, 1:], np.inf)
        pos = np.where(node_start, np.arange(L1 + 1)[None, :], 0)
        first = np.maximum.accumulate(pos, axis=1)[:, :-1]
        return slack, first

    def _cx_final(self, cl, h, idx, d_final, rel) -> Counterexample:
        b: Trajectories = h["batch"]
        (i,) = idx
        vals = {"dist_T": float(d_final[i]), "dist0": float(h["d0"][i]), "theta": self.theta,
                "tolerance_relative": self.rtol}
        return Counterexample(
            **self._base("prop1.attractivity", cl, h, i), t=float(b.t[-1]), t_start=0.0,
            x=tuple(float(q) for q in b.x[i, -1]), values=vals, relative_slack=float(rel[i]),
        )

    def _cx_stick(self, cl, h, idx, sig_prev, sig_next, t_prev, t_next, rel) -> Counterexample:
        b: Trajectories = h["batch"]
        i, p = idx
        vals = {"sigma_previous_stick": float(sig_prev[i, p]), "sigma_next_stick": float(sig_next[i, p]),
                "tolerance_relative": self.rtol}
        return Counterexample(
            **self._base("remark.stick_sigma", cl, h, i), t=float(t_next[i, p]), t_start=float(t_prev[i, p]),
            x=tuple(float(q) for q in self._stick_x[i, p]), values=vals, relative_slack=float(rel[i, p]),
        )

    def _exact_pointwise(self, which: str, cl: Claims, x: tuple[float, float, float]) -> bool | None:
        """Re-decide a pointwise inequality at the float state ``x`` in exact rational arithmetic."""
        from .._attractor import squared_distance_x
        from .._lyapunov import V, V_hat, in_R

        if not all(math.isfinite(q) for q in x):
            return None
        xq = np.array([Fraction(q) for q in x], dtype=object)
        p = self.params
        d2 = squared_distance_x(p, xq)
        ex = {k: Fraction(v) for k, v in cl.exact.items() if k != "overshoot_bound"}
        inR = bool(in_R(p, xq))
        if which == "lower":
            return not (ex["c1"] * d2 <= V(p, xq))
        if which == "upper":
            return inR and not (V(p, xq) <= ex["c2"] * d2)
        kk = (ex["k1"], ex["k2"], ex["k3"], ex["k4"])
        if which == "hat_lower":
            return (not inR) and not (ex["c1_hat"] * d2 <= V_hat(p, xq, kk))
        if which == "hat_upper":
            return (not inR) and not (V_hat(p, xq, kk) <= ex["c2_hat"] * d2)
        return None

    def resolve_attractivity(self, *, doublings: int = 60, samples: int = 40) -> None:
        """Follow the trajectories that had not reached ``θ|x(0)|_𝒜`` by their horizon.

        Each is continued (the solution is a semigroup: restart from the last
        state) on windows of doubling length ``T, 2T, 4T, …`` (at most
        ``300/|Re λ|``, λ the slowest root) until a sample has
        ``|x(t)|_𝒜 ≤ θ|x(0)|_𝒜``; it fails only if ``doublings`` windows do
        not bring it there.  Near 𝒜 the
        stick phases last ``≈ 2f_c/|σ|``, so the time needed grows like
        ``1/|x(0)|_𝒜``; restarting window by window also keeps every single
        simulation short.
        """
        from .._attractor import distance_x
        from .._coordinates import x_to_z
        from .._simulation.batch import simulate_batch

        n = len(self._pending)
        if n == 0:
            return
        # all pending trajectories advance together, window by window (one batch per window)
        z = np.array([p[1] for p in self._pending], dtype=float)
        target = np.array([self.theta * p[3] for p in self._pending])
        window = max(p[6] for p in self._pending)
        # Windows stop growing at 300/|Re λ| (λ the slowest root): a slip converging to x*_k
        # for much longer underflows to denormals, where the event search of the simulator
        # crawls; e^{-300} is still far from underflow.
        from ._run import slowest_root

        slowest = slowest_root(self.params)
        cap = max(window, 300.0 / abs(slowest))
        start = 0.0
        outcome: list[tuple[bool, float, float, tuple]] = [
            (False, 0.0, float(p[3]), tuple(float(q) for q in p[2])) for p in self._pending
        ]
        active = np.arange(n)
        for _ in range(doublings):
            if active.size == 0:
                break
            t = np.concatenate([[0.0], np.geomspace(window / samples, window, samples)])
            b = simulate_batch(self.params, z[active], float(t[-1]), t_eval=t, max_events=self.max_events)
            d = distance_x(self.params, b.x)
            still = []
            for row, k in enumerate(active):
                if not b.complete[row]:
                    outcome[k] = None  # incomplete: neither holds nor fails
                    self.incomplete += 1
                    continue
                hit = np.nonzero(d[row, 1:] <= target[k])[0]
                if hit.size:
                    j = int(hit[0]) + 1
                    outcome[k] = (True, start + float(t[j]), float(d[row, j]), tuple(float(q) for q in b.x[row, j]))
                else:
                    outcome[k] = (False, start + window, float(d[row, -1]), tuple(float(q) for q in b.x[row, -1]))
                    z[k] = x_to_z(self.params, b.x[row, -1])
                    still.append(k)
            active = np.array(still, dtype=int)
            start += window
            window = min(2.0 * window, cap)
        for ci, cl in enumerate(self.claims):
            acc = self._accs[ci]["prop1.attractivity"]
            times = []
            for (gi, z0, x0, d0, L, source, _T), result in zip(self._pending, outcome):
                if result is None:
                    continue
                ok, tk, dk, xk = result
                rel = np.array([(self.theta * d0 - dk) / L])
                if ok:
                    times.append(tk)

                def make(idx, tk=tk, dk=dk, xk=xk, rel=rel, gi=gi, z0=z0, x0=x0, d0=d0, source=source, cl=cl):
                    return Counterexample(
                        property="prop1.attractivity", certificate=cl.label, trajectory=gi, source=source,
                        z0=tuple(float(q) for q in z0), x0=tuple(float(q) for q in x0), t=tk, t_start=0.0, x=xk,
                        values={"dist_T": dk, "dist0": d0, "theta": self.theta, "tolerance_relative": self.rtol},
                        relative_slack=float(rel[0]),
                    )

                acc.add(rel, np.array([True]), make)
            acc.details_times = times  # type: ignore[attr-defined]
        self._pending = []

    # -- results ----------------------------------------------------------------------------------
    def results(self) -> list[list[PropertyResult]]:
        """Per certificate, the results in the order of :data:`PROPERTIES`."""
        out = []
        final = np.concatenate(self._final_ratio) if self._final_ratio else np.zeros(0)
        ov = self.overshoots()
        ov = ov[np.isfinite(ov)]
        for ci, cl in enumerate(self.claims):
            accs = self._accs[ci]
            if ov.size:
                accs["prop1.stability"].details |= {
                    "max_overshoot": float(ov.max()),
                    "kappa": cl.kappa,
                    "tightness": float(ov.max()) / cl.kappa,
                }
            if final.size:
                times = getattr(accs["prop1.attractivity"], "details_times", [])
                accs["prop1.attractivity"].details |= {
                    "theta": self.theta,
                    "median_final_ratio": float(np.nanmedian(final)) if np.any(np.isfinite(final)) else math.nan,
                    "max_final_ratio": float(np.nanmax(final)) if np.any(np.isfinite(final)) else math.nan,
                    "extended": len(times),
                    "latest_time_to_theta": max(times) if times else None,
                }
                fz = np.concatenate(self._final_z)
                accs["prop1.attractivity"].details |= {
                    "median |s(T)|": float(np.nanmedian(fz[:, 0])) if np.any(np.isfinite(fz[:, 0])) else math.nan,
                    "median |v(T)|": float(np.nanmedian(fz[:, 1])) if np.any(np.isfinite(fz[:, 1])) else math.nan,
                    "share e_i(T) in [-f_c/k_i, f_c/k_i]": float(np.mean(fz[np.isfinite(fz[:, 2]), 2] == 0.0))
                    if np.any(np.isfinite(fz[:, 2])) else math.nan,
                }
            out.append([accs[spec.id].result() for spec in PROPERTIES])
        return out

    def overshoots(self) -> np.ndarray:
        """Observed ``max_t |x(t)|_𝒜/|x(0)|_𝒜`` of every trajectory added so far (NaN if ``x(0) ∈ 𝒜``)."""
        return np.concatenate(self._overshoot) if self._overshoot else np.zeros(0)

    def sources(self) -> np.ndarray:
        """Source label of every trajectory added so far (aligned with :meth:`overshoots`)."""
        return np.concatenate(self._sources) if self._sources else np.zeros(0, dtype=object)
