"""The Remark after Lemma 2 (eq. armstrongRes, Armstrong's result) on trajectories.

``|σ|`` strictly decreases from one stick phase to the next: with ``σ_n``
the value of ``σ`` during the ``n``-th stick phase (of positive length),
``|σ_{n+1}| < |σ_n|``.  The strict part cannot be decided within rounding:
pairs whose slack is within the tolerance of ``0`` are counted as
*inconclusive*, never as holding.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._along import along
from ._property import DEFAULT_RTOL, Evaluation, Property

__all__ = ["StickSigma", "stick_pairs"]


def stick_pairs(batch: Any) -> tuple[np.ndarray, ...]:
    """``(σ_n, σ_{n+1}, t_n, t_{n+1}, x_{n+1}, mask)`` for consecutive stick phases of positive length.

    A stick phase starts at ``t = 0`` in mode 0 or at an event entering mode 0.
    """
    N = batch.size
    E = batch.event_t.shape[1]
    T = float(batch.t[-1])
    ev_ok = np.isfinite(batch.event_t)
    starts_t = np.concatenate([np.zeros((N, 1)), np.where(ev_ok, batch.event_t, np.inf)], axis=1)
    starts_x = np.concatenate([batch.x0[:, None, :], batch.event_x], axis=1)
    starts_sig = starts_x[..., 0]
    is_start = np.concatenate([(batch.mode[:, :1] == 0), (batch.event_after == 0) & ev_ok], axis=1)
    nxt = np.concatenate([starts_t[:, 1:], np.full((N, 1), np.inf)], axis=1)
    is_start &= np.minimum(nxt, T) > starts_t  # the phase lasts up to the next event (or the horizon)
    idx = np.where(is_start, np.arange(E + 1)[None, :], -1)
    last = np.maximum.accumulate(idx, axis=1)
    prev = np.concatenate([np.full((N, 1), -1), last[:, :-1]], axis=1)
    ok = is_start & (prev >= 0)
    prev_c = np.clip(prev, 0, None)
    sig_prev = np.take_along_axis(starts_sig, prev_c, axis=1)
    t_prev = np.take_along_axis(starts_t, prev_c, axis=1)
    return sig_prev, starts_sig, t_prev, starts_t, starts_x, ok


class StickSigma(Property):
    """Remark after Lemma 2: ``|σ|`` strictly decreases between stick phases."""

    id = "remark.stick_sigma"
    paper = "Remark after Lemma 2 (eq. armstrongRes)"
    statement = "|sigma| strictly decreases between stick phases"
    uses_certificate = False

    def __init__(self, *, rtol: float = DEFAULT_RTOL) -> None:
        self.rtol = float(rtol)

    def check(self, trajectories: Any, certificate: Any = None) -> Evaluation:
        a = along(trajectories)
        sig_prev, sig_next, t_prev, t_next, x_next, ok = stick_pairs(trajectories)
        rel = (np.abs(sig_prev) - np.abs(sig_next)) / a.L[:, None]

        def witness(idx: tuple[int, int]) -> Any:
            i, p = idx
            values = {"sigma_previous_stick": sig_prev[i, p], "sigma_next_stick": sig_next[i, p]}
            return a.counterexample(self.id, i, t=t_next[i, p], t_start=t_prev[i, p], x=x_next[i, p],
                                    values=values, rel=rel[i, p])

        unclear = int(np.count_nonzero(ok & (np.abs(rel) <= self.rtol)))
        return Evaluation(rel, ok, witness, inconclusive=unclear)
