"""The one place that owns numerical tolerance logic in the tests.

Errors are measured in tolerance units, as scipy's ``solve_ivp`` tests do:
``|got - want| / (atol + rtol·scale)`` must be ≤ 1, where ``scale`` defaults
to ``max(1, |want|)`` elementwise.
"""

from __future__ import annotations

import numpy as np

__all__ = ["error_units", "assert_close", "relative_error"]


def relative_error(got, want, *, scale=None) -> float:
    """``max |got - want| / scale`` with ``scale = max(1, max|want|)`` by default."""
    got = np.asarray(got, dtype=float)
    want = np.asarray(want, dtype=float)
    if scale is None:
        scale = max(1.0, float(np.max(np.abs(want))) if want.size else 1.0)
    return float(np.max(np.abs(got - want)) / scale) if got.size else 0.0


def error_units(got, want, *, rtol: float, atol: float = 0.0, scale=None) -> float:
    """Largest error in tolerance units; ≤ 1 means within tolerance."""
    got = np.asarray(got, dtype=float)
    want = np.asarray(want, dtype=float)
    if scale is None:
        scale = np.maximum(1.0, np.abs(want))
    return float(np.max(np.abs(got - want) / (atol + rtol * np.asarray(scale)))) if got.size else 0.0


def assert_close(got, want, *, rtol: float, atol: float = 0.0, scale=None, what: str = "value") -> None:
    """Assert ``got`` matches ``want`` within ``atol + rtol·scale``, reporting the error in units."""
    units = error_units(got, want, rtol=rtol, atol=atol, scale=scale)
    assert units <= 1.0, f"{what}: error is {units:.3g} tolerance units (rtol={rtol:g}, atol={atol:g})"
