"""The heat map of a gain map: Proposition 1's κ over two axes, with Assumption 1's boundary ``k_v·k_p = k_i``.

A grid is drawn cell by cell (other ranged axes reduced to their largest
proved κ, the worst case over them); a random sample is drawn point by point.
Points where the closed-form certificate is not proved, or Assumption 1
fails, are left grey.  The boundary is the zero contour of ``k_v·k_p − k_i``
(normalised through §II-A for physical axes), drawn when every other
quantity of the map is fixed.  matplotlib is imported here, lazily.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from .._infra.errors import ParameterError
from .gainmap import MapSpec, normalised

__all__ = ["plot_map", "default_axes"]


def default_axes(spec: MapSpec) -> tuple[str, str]:
    """The first two ranged axes of ``spec``.

    Raises
    ------
    ParameterError
        If fewer than two axes vary.
    """
    ranged = [a.name for a in spec.ranged]
    if len(ranged) < 2:
        raise ParameterError(f"a heat map needs two ranged axes; the map varies {', '.join(ranged) or 'nothing'}")
    return ranged[0], ranged[1]


def _boundary(spec: MapSpec, x: str, y: str, ax: object) -> bool:
    """Draw ``k_v·k_p = k_i`` over the ``(x, y)`` range if every other quantity is fixed; return whether drawn."""
    others = [a for a in spec.ranged if a.name not in (x, y)]
    if others:
        return False
    grids = []
    for name in (x, y):
        a = spec.axis(name)
        lo, hi = float(a.lo), float(a.hi)
        grids.append(np.geomspace(lo, hi, 400) if a.scale == "log" else np.linspace(lo, hi, 400))
    X, Y = np.meshgrid(*grids)
    values: dict[str, object] = {a.name: float(a.lo) for a in spec.axes}
    values[x], values[y] = X, Y
    g = normalised(values)
    G = np.asarray(g["k_v"]) * np.asarray(g["k_p"]) - np.asarray(g["k_i"]) + 0 * X
    if not (np.nanmin(G) < 0 < np.nanmax(G)):
        return False
    ax.contour(X, Y, G, levels=[0.0], colors="k", linewidths=1.5)  # type: ignore[attr-defined]
    ax.plot([], [], "k-", label="k_v·k_p = k_i (Assumption 1 boundary)")  # type: ignore[attr-defined]
    return True


def plot_map(spec: MapSpec, columns: dict[str, np.ndarray], path: str | os.PathLike[str] | None = None, *,
             x: str | None = None, y: str | None = None) -> Any:
    """The heat map of κ over ``(x, y)``: written to ``path`` (format from the suffix, e.g. ``.png``, ``.pdf``), or returned.

    Parameters
    ----------
    spec : MapSpec
    columns : dict of ndarray
        The map's columns (:func:`~.gainmap_run.read_columns`).
    path : path-like, optional
        Where to write the figure; without it the matplotlib figure is returned (for a notebook).
    x, y : str, keyword-only
        Axis names (default :func:`default_axes`); both must be ranged.

    Returns
    -------
    Path or matplotlib.figure.Figure

    Raises
    ------
    ParameterError
        If ``x`` or ``y`` is not a ranged axis of the map, or they are the same.
    """
    import matplotlib
    from matplotlib.figure import Figure
    from matplotlib.colors import LogNorm

    if x is None or y is None:
        dx, dy = default_axes(spec)
        x, y = x or dx, y or (dy if dx != x else dx)
    ranged = [a.name for a in spec.ranged]
    for name in (x, y):
        if name not in ranged:
            raise ParameterError(f"heat-map axis {name!r} is not a ranged axis of the map; ranged: {', '.join(ranged) or 'none'}")
    if x == y:
        raise ParameterError(f"a heat map needs two different axes; got {x!r} twice")
    kappa = np.where(columns["status"] == 0, columns["kappa"], np.nan)
    fig = Figure(figsize=(6.4, 5.0), layout="constrained")
    ax = fig.add_subplot()
    finite = kappa[np.isfinite(kappa)]
    norm = LogNorm(vmin=finite.min(), vmax=max(finite.max(), finite.min() * 1.0001)) if finite.size else None
    cmap = matplotlib.colormaps["viridis"].with_extremes(bad="0.85")
    if spec.sample:
        image = ax.scatter(columns[x], columns[y], c=np.where(np.isfinite(kappa), kappa, np.nan), s=6, cmap=cmap,
                           norm=norm, plotnonfinite=True)
    else:
        grid = kappa.reshape(spec.shape)
        ix, iy = ranged.index(x), ranged.index(y)
        rest = tuple(i for i in range(len(ranged)) if i not in (ix, iy))
        if rest:
            with np.errstate(all="ignore"):
                grid = np.fmax.reduce(grid, axis=rest) if grid.size else grid
        keep = [i for i in range(len(ranged)) if i not in rest]
        grid = np.transpose(grid, (keep.index(iy), keep.index(ix)))
        cx = _coordinate(columns[x].reshape(spec.shape), ix)
        cy = _coordinate(columns[y].reshape(spec.shape), iy)
        image = ax.pcolormesh(cx, cy, np.ma.masked_invalid(grid), cmap=cmap, norm=norm, shading="nearest")
    for name, setter in ((x, ax.set_xscale), (y, ax.set_yscale)):
        if spec.axis(name).scale == "log":
            setter("log")
    drawn = _boundary(spec, x, y, ax)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    fixed = ", ".join(f"{a.name} = {float(a.lo):g}" for a in spec.axes if not a.ranged)
    reduced = [n for n in ranged if n not in (x, y)]
    title = "κ of the proved closed-form certificate" + (f" (largest over {', '.join(reduced)})" if reduced else "")
    ax.set_title(title + (f"\n{fixed}" if fixed else ""), fontsize=10)
    fig.colorbar(image, ax=ax, label="κ  (grey: not proved or outside Assumption 1)")
    if drawn:
        ax.legend(loc="lower right", fontsize=8)
    if path is None:
        return fig
    from .._infra.io import atomic_write

    path = Path(path)
    fmt = path.suffix.lstrip(".") or "png"
    atomic_write(path, lambda handle: fig.savefig(handle, format=fmt, dpi=150))
    return path


def _coordinate(grid: np.ndarray, k: int) -> np.ndarray:
    """The values of axis ``k`` of a grid column (the others at their first index)."""
    return grid[tuple(slice(None) if i == k else 0 for i in range(grid.ndim))]
