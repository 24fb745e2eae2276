"""Lemma 3 on trajectories: the bounds on ``R`` and ``R̂``, and ``V̂`` nonincreasing in ``R̂``.

* eq. (VandR): ``V ≤ c₂|x|²_𝒜`` on ``R`` (samples and event values);
* eq. (hatVandHatR): ``ĉ₁|x|²_𝒜 ≤ V̂ ≤ ĉ₂|x|²_𝒜`` on ``R̂``;
* eq. (hatVdot): ``V̂`` nonincreasing on every time interval spent in ``R̂``.
  The solution may leave ``R̂`` (``φ`` crossing ``k f_c``) and come back
  between two points without an event, so interior points of the exact
  closed-form flow are looked at too.  The slack is over all pairs of an
  interval (a running minimum restarted at each interval).

Pointwise violations are re-decided in exact rational arithmetic at the float
state; a growth of ``V̂`` comes with ``V̂°`` (eq. hatVdot) evaluated exactly at
its start.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np

from ._along import along, exact_state
from ._property import Evaluation, Property

__all__ = ["VUpper", "HatVLower", "HatVUpper", "HatVNonincreasing", "run_slack", "rhat_intervals", "slip_points"]


def _k_exact(certificate: Any) -> tuple[Fraction, ...]:
    return tuple(Fraction(certificate.exact[name]) for name in ("k1", "k2", "k3", "k4"))


class VUpper(Property):
    """Lemma 3, eq. (VandR): ``V ≤ c₂|x|²_𝒜`` on ``R``."""

    id = "lemma3.V_upper"
    paper = "Lemma 3 (eq. VandR)"
    statement = "V(x) <= c2 |x|²_A on R"

    def check(self, trajectories: Any, certificate: Any) -> Evaluation:
        a = along(trajectories)
        c2 = certificate.c2
        scale = (max(a.lam_P, certificate.c1, c2) * a.Q)[:, None]
        rel = (c2 * a.d2 - a.V) / scale

        def witness(idx: tuple[int, int]) -> Any:
            return a.point_counterexample(self.id, idx, {"V": a.V[idx], "c2": c2, "dist2": a.d2[idx]}, rel[idx],
                                          exact=self.exact_violation(a.params, certificate, a.xs[idx]))

        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = a.V / a.d2
        return Evaluation(rel, a.in_R & a.off_A, witness,
                          extremes=(("max V/|x|² on R", ratio, a.in_R & a.far, True),))

    @staticmethod
    def exact_violation(params: Any, certificate: Any, x: Any) -> bool | None:
        from .._model.attractor import squared_distance_x
        from .._model.lyapunov import V, in_R

        xq = exact_state(x)
        if xq is None:
            return None
        return bool(in_R(params, xq)) and not (V(params, xq) <= Fraction(certificate.exact["c2"]) * squared_distance_x(params, xq))


class _HatBound(Property):
    """``ĉ₁|x|²_𝒜 ≤ V̂`` (``lower``) or ``V̂ ≤ ĉ₂|x|²_𝒜`` on ``R̂`` (eq. hatVandHatR)."""

    paper = "Lemma 3 (eq. hatVandHatR)"
    lower: bool

    def check(self, trajectories: Any, certificate: Any) -> Evaluation:
        a = along(trajectories)
        Vh = a.V_hat(certificate.k)
        scale = (max(certificate.lambda_max_K_half(), certificate.c1_hat, certificate.c2_hat) * a.Q)[:, None]
        name = "c1_hat" if self.lower else "c2_hat"
        const = getattr(certificate, name)
        rel = ((Vh - const * a.d2) if self.lower else (const * a.d2 - Vh)) / scale

        def witness(idx: tuple[int, int]) -> Any:
            return a.point_counterexample(self.id, idx, {"V_hat": Vh[idx], name: const, "dist2": a.d2[idx]}, rel[idx],
                                          exact=self.exact_violation(a.params, certificate, a.xs[idx]))

        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = Vh / a.d2
        key = "min V̂/|x|² on R̂" if self.lower else "max V̂/|x|² on R̂"
        return Evaluation(rel, a.in_Rhat & a.off_A, witness,
                          extremes=((key, ratio, a.in_Rhat & a.far, not self.lower),))

    def exact_violation(self, params: Any, certificate: Any, x: Any) -> bool | None:
        from .._model.attractor import squared_distance_x
        from .._model.lyapunov import V_hat, in_R

        xq = exact_state(x)
        if xq is None:
            return None
        d2 = squared_distance_x(params, xq)
        Vh = V_hat(params, xq, _k_exact(certificate))
        holds = (Fraction(certificate.exact["c1_hat"]) * d2 <= Vh) if self.lower else \
            (Vh <= Fraction(certificate.exact["c2_hat"]) * d2)
        return (not bool(in_R(params, xq))) and not holds


class HatVLower(_HatBound):
    """Lemma 3, eq. (hatVandHatR), left: ``ĉ₁|x|²_𝒜 ≤ V̂`` on ``R̂``."""

    id = "lemma3.hatV_lower"
    statement = "c1_hat |x|²_A <= V̂(x) on R̂"
    lower = True


class HatVUpper(_HatBound):
    """Lemma 3, eq. (hatVandHatR), right: ``V̂ ≤ ĉ₂|x|²_𝒜`` on ``R̂``."""

    id = "lemma3.hatV_upper"
    statement = "V̂(x) <= c2_hat |x|²_A on R̂"
    lower = False


def run_slack(F: np.ndarray, run: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """All-pairs slack ``min_{a<b in the same run} F_a - F_b`` for each pair ``(b-1, b)`` of a run.

    A run is a maximal chain of consecutive pairs with ``run`` true (one time
    interval spent in ``R̂``).  The running minimum is restarted at each run by
    subtracting ``run id × K``, ``K`` larger than the spread of ``F`` in the
    row, so that earlier runs never win the minimum.  Returns the slack
    (shape of ``run``) and the index where each run starts.
    """
    N, L1 = run.shape
    prev = np.concatenate([np.zeros((N, 1), bool), run[:, :-1]], axis=1)
    start = run & ~prev
    node_start = np.concatenate([start, np.zeros((N, 1), bool)], axis=1)
    rid = np.cumsum(node_start, axis=1).astype(float)
    Ff = np.where(np.isfinite(F), F, 0.0)
    K = 2.0 * np.abs(Ff).max(axis=1, keepdims=True) + 1.0
    cm = np.minimum.accumulate(Ff - rid * K, axis=1)
    run_min = cm[:, :-1] + rid[:, 1:] * K
    slack = np.where(run, run_min - Ff[:, 1:], np.inf)
    pos = np.where(node_start, np.arange(L1 + 1)[None, :], 0)
    first = np.maximum.accumulate(pos, axis=1)[:, :-1]
    return slack, first


def slip_points(a: Any, rows: np.ndarray, cols: np.ndarray, fractions: Any) -> np.ndarray:
    """States inside the slip intervals ``(rows, cols) → (rows, cols + 1)`` of the chain, at ``fractions`` of their length.

    On a slip ``k = ±1`` the offset ``y = x − x*_k``, ``x*_k = (0, k f_c, 0)``
    (eq. subcasesAffine), solves ``y' = Ay``, so the state at ``t_p + τ`` is
    ``x*_k + e^{Aτ}(x_p − x*_k)``: the exact closed-form flow, shape
    ``(rows.size, len(fractions), 3)``.  At fraction 1 it is the chain's next
    point; ``check``'s kernel rows hold it to the kernel's there at
    ``f_c ≠ 1`` (:mod:`._kernel_check`), where an ``x*_k`` without ``f_c`` shows.
    """
    ch = a.ch
    k = a.k_int[rows, cols].astype(float)
    star = np.zeros((rows.size, 3))
    star[:, 1] = k * a.f_c
    h = ch.t[rows, cols + 1] - ch.t[rows, cols]
    taus = h[:, None] * np.asarray(fractions, dtype=float)[None, :]
    y = np.broadcast_to((ch.x[rows, cols] - star)[:, None, :], taus.shape + (3,))
    return _distinct_times(a.params).apply(taus, y) + star[:, None, :]


def _distinct_times(params: Any) -> Any:
    """The package's ``e^{Aτ}`` (:class:`~.._simulation.affine.MatrixExponential`) for ``params``, whose ``w``
    evaluates each distinct time once.

    The intervals of a uniform sample grid have one length, so the times of :func:`slip_points` repeat (about six
    times over in ``check``'s self-test), and ``w`` is the costly part of the flow in plain Python.  Each time gets
    the very numbers ``w`` gives it, so ``apply`` returns the same flow, bit for bit.
    """
    from .._simulation.affine import MatrixExponential

    class DistinctTimes(MatrixExponential):
        def w(self, t: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            t = np.asarray(t, dtype=float)
            distinct, where = np.unique(t.reshape(-1), return_inverse=True)
            w0, w1, w2 = super().w(distinct)
            return w0[where].reshape(t.shape), w1[where].reshape(t.shape), w2[where].reshape(t.shape)

    return DistinctTimes.from_params(params)


def rhat_intervals(a: Any) -> np.ndarray:
    """Consecutive points whose open interval lies in ``R̂`` (so ``V̂`` must not increase there).

    An end is a sample in ``R̂`` or an event (``V̂`` is continuous, so an
    interval that ends at a slip's end is held to ``V̂`` there too; ``check``'s
    self-test samples a growth run at its start and horizon only, so that every
    interval in ``R̂`` ends at an event).
    """
    from .._model.lyapunov import in_R

    ch = a.ch
    end_ok = a.in_Rhat | (ch.valid & (ch.kind < 3))  # events bound R̂ intervals (V̂ is continuous)
    run = a.dt_pos & (a.k_int != 0) & end_ok[:, :-1] & end_ok[:, 1:]
    # An interval between two events, with no sample in R̂, may lie in R: skip it.
    run &= a.in_Rhat[:, :-1] | a.in_Rhat[:, 1:]
    if np.any(run):
        rows, cols = np.nonzero(run)
        k = a.k_int[rows, cols].astype(float)
        mids = slip_points(a, rows, cols, (0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875))
        # still in the same slip (k v > 0) and in the package's R̂
        inside = ((k[:, None] * mids[..., 2]) > 0) & ~in_R(a.params, mids)
        run[rows, cols] = inside.all(axis=1)
    return run


class HatVNonincreasing(Property):
    """Lemma 3, eq. (hatVdot): ``V̂`` does not increase while the solution stays in ``R̂``."""

    id = "lemma3.hatV_nonincreasing"
    paper = "Lemma 3 (eq. hatVdot)"
    statement = "V̂(x(t2)) <= V̂(x(t1)) on intervals in R̂"

    def check(self, trajectories: Any, certificate: Any) -> Evaluation:
        a = along(trajectories)
        if "rhat_run" not in a.__dict__:
            a.__dict__["rhat_run"] = rhat_intervals(a)
        run = a.__dict__["rhat_run"]
        Vh = a.V_hat(certificate.k)
        scale = (max(certificate.lambda_max_K_half(), certificate.c1_hat, certificate.c2_hat) * a.Q)[:, None]
        slack, first = run_slack(Vh, run)
        rel = slack / scale

        def witness(idx: tuple[int, int]) -> Any:
            i, p = idx
            b = p + 1
            seg = np.arange(int(first[i, p]), b)
            j = int(seg[np.argmin(Vh[i, seg])])  # the earlier point of the interval with the smallest V̂
            values = {"V_hat_t1": Vh[i, j], "V_hat_t2": Vh[i, b], "increase": Vh[i, b] - Vh[i, j],
                      "x_t1": [float(q) for q in a.xs[i, j]]}
            # exact witness: V̂ grows at x(t1) itself if V̂° (eq. hatVdot) is positive there, in rationals
            rate = self.exact_rate(a.params, certificate, a.xs[i, j])
            if rate is not None:
                values["dV_hat_dt_at_t1"] = float(rate)
            return a.counterexample(self.id, i, t=a.ch.t[i, b], t_start=a.ch.t[i, j], x=a.xs[i, b], values=values,
                                    rel=rel[i, p], exact=None if rate is None else bool(rate > 0))

        return Evaluation(rel, run, witness)

    @staticmethod
    def exact_rate(params: Any, certificate: Any, x: Any) -> Fraction | None:
        """``V̂°`` (eq. hatVdot) at ``x ∈ R̂``, exactly, from the package's model (``None`` outside ``R̂``)."""
        from .._model.lyapunov import V_hat_rate, in_R

        xq = exact_state(x)
        if xq is None or in_R(params, list(xq)):
            return None
        return V_hat_rate(params, list(xq), _k_exact(certificate))
