"""The slip's closed form and the end-of-slip rule: the kernel's surface for callers outside the simulation.

A slip in direction ``d`` from the offset ``y0 = x - (0, d f_c, 0)`` follows
``y(τ) = e^{Aτ} y0`` (eq. xPhDot with constant friction); it ends at the first
zero of ``v``, found by the kernel's certified search, and the mode table of
the Appendix (with the stick boundary at ``±f_s``) decides what follows.
Studies of the inclusion (the hunting map, :mod:`symbolic_friction._hunting`)
import these names from here, never from the kernel's private modules.

* :func:`slip_model` — the closed form, its bounds and scan table for a gain set;
* :func:`first_zero` — the first ``τ`` with ``v(τ) = 0`` along a slip;
* :func:`mode_after_slip` — the kernel's end-of-slip rule (stick or reversal);
* ``UNDERFLOW``, ``EPS``, ``SNAP_ULPS`` — the kernel's decay floor and snapping tolerances.
"""

from __future__ import annotations

from ._kernel import EPS, SNAP_ULPS, mode_after_slip
from .search import UNDERFLOW, SlipModel, first_zero, slip_model

__all__ = ["SlipModel", "slip_model", "first_zero", "mode_after_slip", "UNDERFLOW", "EPS", "SNAP_ULPS"]
