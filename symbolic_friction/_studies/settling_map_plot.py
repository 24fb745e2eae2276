"""The heat map of a settling map (:mod:`.settling_map`): PID's settling time over reset PID's on ``(k_p, k_i)`` (beyond the paper).

One panel per friction level ``f_s/f_c``; the colour is the ratio on a log
scale.  A cell where only reset PID settles by ``t_end`` is coloured by the
strict lower bound ``t_end/t_reset`` and marked ``>``; grey (``–``) where
neither settles.  matplotlib is imported here, lazily, and only its
object-oriented ``Figure`` is used (no pyplot state).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from .settling_map import SettlingMap

__all__ = ["plot_settling_map", "write_settling_map_figure"]


def _label(q: Fraction) -> str:
    return f"{float(q):.3g}"


def _shown(result: SettlingMap, ratio: Fraction) -> np.ndarray:
    """The coloured values: the ratio, ``t_end/t_reset`` where only reset settles, nan where neither does."""
    value = []
    for c in result.cells_at(ratio):
        r = c.ratio
        if r is None:
            value.append(math.nan)
        elif math.isinf(r):
            value.append(result.t_end / c.reset_time if c.reset_time else math.nan)
        else:
            value.append(max(r, 1e-3))
    return np.array(value).reshape(len(result.k_i), len(result.k_p))


def plot_settling_map(result: SettlingMap):
    """One heat map per friction level: PID's settling time over reset's, on ``(k_p, k_i)``.

    Colour is the ratio on a log scale; a cell where only reset PID settles is
    coloured by its lower bound ``t_end/t_reset`` and marked ``>``; grey
    (``–``) where neither settles.  Returns a matplotlib ``Figure`` (no
    pyplot state: it displays in a notebook and saves anywhere).
    """
    import matplotlib
    from matplotlib.colors import LogNorm
    from matplotlib.figure import Figure

    n = len(result.f_s_ratios)
    fig = Figure(figsize=(5.2 * n + 1.2, 4.8), layout="constrained")
    axes = fig.subplots(1, n, squeeze=False)[0]
    shown = [_shown(result, r) for r in result.f_s_ratios]
    finite = np.concatenate([v[np.isfinite(v)].ravel() for v in shown])
    lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (1.0, 10.0)
    norm = LogNorm(vmin=min(lo, 1.0), vmax=max(hi, 1.01))
    cmap = matplotlib.colormaps["viridis"].with_extremes(bad="0.85")
    image = None
    for ax, ratio, grid in zip(axes, result.f_s_ratios, shown):
        image = ax.imshow(np.ma.masked_invalid(grid), origin="lower", cmap=cmap, norm=norm, aspect="auto")
        for j, c in enumerate(result.cells_at(ratio)):
            r, v = c.ratio, grid.flat[j]
            label = "–" if r is None else (f">{v:.2g}" if math.isinf(r) else f"{r:.2g}")
            dark = math.isfinite(v) and norm(v) < 0.6
            ax.text(j % len(result.k_p), j // len(result.k_p), label, ha="center", va="center", fontsize=7,
                    color="w" if dark else "k")
        ax.set_xticks(range(len(result.k_p)), [_label(q) for q in result.k_p], rotation=45, fontsize=7)
        ax.set_yticks(range(len(result.k_i)), [_label(q) for q in result.k_i], fontsize=7)
        ax.set_xlabel("k_p")
        ax.set_ylabel("k_i")
        what = "|s| ≤ tol·|s(0)|" if ratio == 1 else f"|s| ≤ {float(result.band):g}·a* (hunting)"
        ax.set_title(f"f_s/f_c = {float(ratio):g}: t_PID / t_reset to {what}", fontsize=9)
    if image is not None:
        fig.colorbar(image, ax=list(axes), label="settling-time ratio PID / reset")
    fig.suptitle(f"k_v k_p/k_i = {float(result.margin):g}, z0 = ({', '.join(str(q) for q in result.z0)}), "
                 f"t_end = {result.t_end:g}; '>': only reset settles (lower bound), '–': neither", fontsize=9)
    return fig


def write_settling_map_figure(result: SettlingMap, path) -> None:
    """:func:`plot_settling_map` written as a PNG to ``path``, atomically."""
    from .._infra.io import atomic_write

    fig = plot_settling_map(result)
    atomic_write(path, lambda handle: fig.savefig(handle, format="png", dpi=110))
