"""The mode table of the appendix (Claim 1) on trajectories: modes agree with states.

The values of ``V`` are read through the modes (eq. subcasesAffine:Vs), so
the simulator itself is checked first: on a slip ``k = ±1`` a sample has
``k v ≥ 0``; on a stick ``v = 0`` and ``|φ| ≤ f_c`` (Claim 1, the table of
the appendix, from :mod:`symbolic_friction._simulation.modes`); and every
event is a zero of ``v``: the closed-form flow up to the event time gives
``v ≈ 0`` there.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._along import along
from ._property import Evaluation, Property

__all__ = ["Modes"]


class Modes(Property):
    """The appendix's mode table: ``sign v`` on a slip, ``v = 0``, ``|φ| ≤ f_c`` on a stick; ``v = 0`` at events."""

    id = "model.modes"
    paper = "Claim 1 / appendix table"
    statement = "modes agree with the states; v = 0 at events"
    uses_certificate = False

    def check(self, trajectories: Any, certificate: Any = None) -> Evaluation:
        a = along(trajectories)
        b = trajectories
        xs, piece, f_c = a.xs, a.ch.piece, a.f_c
        v = xs[..., 2]
        L = a.L[:, None]
        stick = a.valid & a.is_sample & (piece == 0)
        slip = a.valid & a.is_sample & (piece != 0)
        rel = np.where(stick, -np.maximum(np.abs(v), np.abs(xs[..., 1]) - f_c) / L,
                       np.where(slip, piece * v / L, np.inf))

        def witness(idx: tuple[int, int]) -> Any:
            values = {"mode": float(piece[idx]), "v": float(v[idx]), "phi": float(xs[idx][1]), "f_c": f_c}
            return a.point_counterexample(self.id, idx, values, rel[idx])

        rel_ev = -b.event_residual / L

        def at_event(idx: tuple[int, int]) -> Any:
            return a.counterexample(self.id, idx[0], t=b.event_t[idx], x=b.event_x[idx],
                                    values={"v_at_event_time": float(b.event_residual[idx])}, rel=rel_ev[idx])

        events = Evaluation(rel_ev, np.isfinite(b.event_t), at_event)
        return Evaluation(rel, a.valid & a.is_sample, witness, more=(events,))
