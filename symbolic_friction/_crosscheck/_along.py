"""The package's one model evaluated along a batch of trajectories, once, for every property.

:func:`along` turns a :class:`~symbolic_friction._simulation.Trajectories`
into an :class:`Along`: the samples and events merged in time order (the
*chain*), and on it ``V`` (eq. lyapLike, both sides of every event),
``|x|²_𝒜``, ``R``/``R̂`` (Lemma 3), the closed-form ``∫ v²`` and the scales
of the tolerances.  Everything is computed by the package's model functions
(:mod:`symbolic_friction._model.lyapunov`, :mod:`symbolic_friction._model.attractor`);
nothing here is a private copy of a paper object.  The result is cached per
trajectories object, so the properties share it.

The integral ``∫ v²``
---------------------
Between two consecutive points of the chain the solution stays in one affine
mode (Claim 1).  On a slip ``k = ±1``, ``y = x - x*_k`` with
``x*_k = (0, k f_c, 0)`` solves ``y' = A y`` and ``v = e₃ᵀy``, so with ``W``
the observability Gramian of ``(A, e₃ᵀ)`` (``AᵀW + WA = -e₃e₃ᵀ``; ``A`` is
Hurwitz), ``d/dt yᵀWy = -v²`` gives
``∫_{t_a}^{t_b} v² dt = y(t_a)ᵀWy(t_a) - y(t_b)ᵀWy(t_b)``, exact up to
rounding.  ``W`` comes from ``A`` alone (a Lyapunov solve), sharing nothing
with ``P``, ``c`` or a certificate: the check compares two independent
computations.
"""

from __future__ import annotations

import functools
import math
import weakref
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from typing import Any

import numpy as np

from .._infra.errors import SimulationError
from .._model.parameters import Parameters

__all__ = ["Along", "along", "Chain", "build_chain", "observability_gramian"]


@functools.lru_cache(maxsize=64)
def observability_gramian(params: Parameters) -> np.ndarray:
    """``W`` with ``AᵀW + WA = -e₃e₃ᵀ``: ``∫_0^∞ v² dt = yᵀWy`` for ``y' = Ay``, ``v = e₃ᵀy``.

    It is the paper's ``P`` (eq. lyapLikeP) divided by ``c = 2(k_v k_p − k_i)``:
    Lemma 2's ``AᵀP + PA = −c e₃e₃ᵀ`` (the identity behind eq. dVdt, which
    the obligation ``lemma2.dVdt`` proves for the model's ``P``), so no
    Lyapunov solver (nor scipy.linalg, 0.27 s to import in ``check``) is
    needed.  Computed once per gain set; read-only.
    """
    from .._model.lyapunov import lyapunov_matrix

    k_p, k_i, k_v, _ = params.as_floats()
    W = lyapunov_matrix(params) / (2.0 * (k_v * k_p - k_i))
    W.setflags(write=False)
    return W


@dataclass(frozen=True, eq=False)
class Chain:
    """Samples and events of a batch, merged in time order (per trajectory).

    Each event appears three times, at the same time and state: its left
    limit (kind 0, the mode before), the value at the event (kind 1) and its
    right limit (kind 2, the mode after).  Samples have kind 3.
    """

    t: np.ndarray  # (N, L), +inf in the padding
    kind: np.ndarray  # (N, L)
    x: np.ndarray  # (N, L, 3)
    piece: np.ndarray  # (N, L) which V_k gives V here: -1, 0, 1, or 2 for the value at an event
    right_mode: np.ndarray  # (N, L) mode on the interval to the next point
    valid: np.ndarray  # (N, L)


def build_chain(batch: Any) -> Chain:
    """The :class:`Chain` of ``batch`` (samples after an incomplete stop are dropped)."""
    N, n = batch.mode.shape
    E = batch.event_t.shape[1]
    t = batch.t
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
    order = np.lexsort((kind, times), axis=-1)
    take = lambda a: np.take_along_axis(a, order, axis=1)  # noqa: E731
    times = take(times)
    x = np.take_along_axis(x, order[..., None], axis=1)
    kind_s = take(kind)
    # v = 0 at an event by definition of an event; the stored state may carry a rounding residue.
    x[..., 2] = np.where(kind_s < 3, 0.0, x[..., 2])
    return Chain(t=times, kind=kind_s, x=x, piece=take(piece), right_mode=take(right), valid=np.isfinite(times))


class Along:
    """The model along one batch (see the module docstring); build it with :func:`along`."""

    def __init__(self, batch: Any) -> None:
        if batch.t.size > 1 and not np.all(batch.t[1:] > batch.t[:-1]):
            # the chain divides by the time between samples
            raise SimulationError("the cross-check needs strictly increasing sample times")
        # not the batch itself: the cache is keyed weakly by it, and a value holding its key would never be freed
        self.source, self.z0, self.x0, self.t = batch.source, batch.z0, batch.x0, batch.t
        self.params: Parameters = batch.params
        self.k_p, self.k_i, self.k_v, self.f_c = self.params.as_floats()
        self.N = batch.size
        self.complete = np.asarray(batch.complete, dtype=bool)
        self.ch = build_chain(batch)
        ch = self.ch
        self.valid = ch.valid
        self.xs = ch.x
        norms = np.where(ch.valid, np.linalg.norm(ch.x, axis=-1), 0.0)
        self.L = np.maximum(norms.max(axis=1), np.linalg.norm(batch.x0, axis=1)) + self.f_c
        self.Q = self.L * self.L
        self.is_sample = ch.kind == 3
        self.at_event = ch.kind == 1
        self.point = ch.valid & (self.is_sample | self.at_event)  # distinct states
        self.pair = ch.valid[:, 1:] & ch.valid[:, :-1]
        self.dt_pos = self.pair & (ch.t[:, 1:] > ch.t[:, :-1])
        self.k_int = ch.right_mode[:, :-1]
        self._hat: dict[tuple, np.ndarray] = {}

    # -- the paper's functions, from the package's model ------------------------------------
    @cached_property
    def V(self) -> np.ndarray:
        """``V`` of eq. (lyapLike): ``V_k`` of the mode on each side of an event, ``V`` itself at it."""
        from .._model.lyapunov import V, V_k

        x, piece = self.xs, self.ch.piece
        at_rest = x * np.array([1.0, 1.0, 0.0])
        out = np.where(piece == 1, V_k(self.params, x, 1), 0.0)
        out = np.where(piece == -1, V_k(self.params, x, -1), out)
        out = np.where(piece == 0, V_k(self.params, x, 0), out)
        return np.where(self.valid, np.where(piece == 2, V(self.params, at_rest), out), np.nan)

    @cached_property
    def d2(self) -> np.ndarray:
        """``|x|²_𝒜`` (eq. distance) at every point."""
        from .._model.attractor import squared_distance_x

        return squared_distance_x(self.params, self.xs)

    @cached_property
    def d(self) -> np.ndarray:
        return np.sqrt(self.d2)

    @cached_property
    def d0(self) -> np.ndarray:
        from .._model.attractor import squared_distance_x

        return np.sqrt(squared_distance_x(self.params, self.x0))

    @cached_property
    def off_A(self) -> np.ndarray:
        """Points outside 𝒜: there both sides of the homogeneous bounds vanish identically (Lemma 2, item 1)."""
        return self.d2 > 0

    @cached_property
    def far(self) -> np.ndarray:
        """``|x|²_𝒜 ≥ 1e-6 L²``: where rounding cannot blur a ratio ``V/|x|²_𝒜``."""
        return self.d2 >= 1e-6 * self.Q[:, None]

    @cached_property
    def in_Rhat(self) -> np.ndarray:
        """Samples in ``R̂`` (Lemma 3), with ``sign v`` read from the mode of the solution through them."""
        from .._model.lyapunov import in_R

        xs = self.xs
        smode = np.where(self.is_sample, self.ch.piece, 0).astype(float)
        # R depends on v only through sign v and v ≠ 0; v's float sign is unreliable next to an event
        signed = np.stack([xs[..., 0], xs[..., 1], smode], axis=-1)
        return self.valid & self.is_sample & ~in_R(self.params, np.where(np.isfinite(signed), signed, 0.0))

    @cached_property
    def in_R(self) -> np.ndarray:
        return self.point & ~self.in_Rhat

    @cached_property
    def cumI(self) -> np.ndarray:
        """``∫_0^{t_p} v² dt`` at every point of the chain (closed form, module docstring)."""
        W = observability_gramian(self.params)
        slip = self.dt_pos & (self.k_int != 0)
        kk = np.where(slip, self.k_int, 0).astype(float)

        def gram(x: np.ndarray) -> np.ndarray:
            y = x.copy()
            y[..., 1] -= kk * self.f_c
            return np.einsum("...i,ij,...j->...", y, W, y)

        I = np.where(slip, gram(self.xs[:, :-1]) - gram(self.xs[:, 1:]), 0.0)
        return np.concatenate([np.zeros((self.N, 1)), np.cumsum(I, axis=1)], axis=1)

    def V_hat(self, k: tuple[float, float, float, float]) -> np.ndarray:
        """``V̂`` of eq. (Vhat) with the constants ``k`` at every point (memoised per ``k``)."""
        from .._model.lyapunov import V_hat

        key = tuple(float(q) for q in k)
        if key not in self._hat:
            self._hat[key] = V_hat(self.params, self.xs, key)
        return self._hat[key]

    @cached_property
    def lam_P(self) -> float:
        """Largest eigenvalue of ``P`` (eq. P), used only to scale tolerances."""
        from .._model.lyapunov import lyapunov_matrix

        return float(np.linalg.eigvalsh(lyapunov_matrix(self.params))[-1])

    @cached_property
    def last_sample(self) -> np.ndarray:
        pos = np.where(self.valid & self.is_sample, np.arange(self.ch.t.shape[1])[None, :], -1)
        return pos.max(axis=1)

    @cached_property
    def overshoot(self) -> np.ndarray:
        """Observed ``max |x(t)|_𝒜/|x(0)|_𝒜`` over samples and events (NaN: ``x(0) ∈ 𝒜`` or incomplete)."""
        dmax = np.where(self.point, self.d, -np.inf).max(axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where((self.d0 > 0) & self.complete, dmax / self.d0, np.nan)

    # -- counterexamples ------------------------------------------------------------------
    def counterexample(self, prop: str, i: int, *, t: float, x: Any, values: dict, rel: float,
                       t_start: float | None = None, exact: bool | None = None) -> Any:
        """A :class:`~._results.Counterexample` on trajectory ``i`` (certificate filled in by the tally)."""
        from ._results import Counterexample

        return Counterexample(
            property=prop, certificate="", trajectory=int(i), source=str(self.source[i]),
            z0=tuple(float(q) for q in self.z0[i]), x0=tuple(float(q) for q in self.x0[i]), t=float(t),
            t_start=None if t_start is None else float(t_start), x=tuple(float(q) for q in x),
            values={k: (float(v) if np.isscalar(v) else v) for k, v in values.items()},
            relative_slack=float(rel), exact=exact,
        )

    def point_counterexample(self, prop: str, idx: tuple[int, int], values: dict, rel: float,
                             exact: bool | None = None) -> Any:
        i, p = idx
        vals = dict(values, scale=float(self.L[i]))
        return self.counterexample(prop, i, t=float(self.ch.t[i, p]), x=self.xs[i, p], values=vals, rel=rel,
                                   exact=exact)


_CACHE: "weakref.WeakKeyDictionary[Any, Along]" = weakref.WeakKeyDictionary()


def along(trajectories: Any) -> Along:
    """The :class:`Along` view of ``trajectories`` (computed once per object)."""
    view = _CACHE.get(trajectories)
    if view is None:
        view = Along(trajectories)
        _CACHE[trajectories] = view
    return view


def exact_state(x: Any) -> np.ndarray | None:
    """``x`` (floats) as exact rationals, or ``None`` if not finite (for exact re-decisions)."""
    if not all(math.isfinite(float(q)) for q in x):
        return None
    return np.array([Fraction(float(q)) for q in x], dtype=object)
