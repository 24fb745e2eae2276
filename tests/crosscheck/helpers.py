"""Shared helpers of the cross-check tests: the committed certificates and hand-made trajectories."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from symbolic_friction._certify import load
from symbolic_friction._model.coordinates import x_to_z
from symbolic_friction._simulation import Trajectories

PROOFS = Path(__file__).resolve().parents[2] / "proofs"
N_SMALL = 300


def _cert(case: str, mode: str = "tightest"):
    return load(PROOFS / f"case_{case}_{mode}.json")


def _result(check, pid: str):
    return next(r for r in check.results if r.id == pid)


def _trajectories(params, t, x, mode, ev_t, ev_x, before, after, residual=None):
    N, E = ev_t.shape
    return Trajectories(
        params=params, method="synthetic", t=np.asarray(t, float), z=x_to_z(params, x), x=x, mode=mode,
        event_t=ev_t, event_x=ev_x, event_before=before, event_after=after,
        event_residual=np.zeros((N, E)) if residual is None else np.asarray(residual, float)[None],
        n_events=np.isfinite(ev_t).sum(axis=1), status=np.full(N, "t_end reached", dtype=object),
        t_stop=np.full(N, float(np.asarray(t)[-1])), z0=x_to_z(params, x[:, 0]), x0=x[:, 0],
    )


def _synthetic(params, t, x, mode, ev_t=None, ev_x=None, before=None, after=None, residual=None):
    """One hand-made trajectory (a *wrong* one, when a test needs it)."""
    x = np.asarray(x, dtype=float)[None]
    mode = np.asarray(mode)[None]
    if ev_t is None:
        ev_t, ev_x, before, after = np.zeros((1, 0)), np.zeros((1, 0, 3)), np.zeros((1, 0)), np.zeros((1, 0))
    else:
        ev_t, ev_x = np.asarray(ev_t, float)[None], np.asarray(ev_x, float)[None]
        before, after = np.asarray(before)[None], np.asarray(after)[None]
    return _trajectories(params, t, x, mode, ev_t, ev_x, before, after, residual)
