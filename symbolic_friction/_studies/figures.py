"""The paper's figures, regenerated with matplotlib (Agg backend, imported lazily).

* Fig. 2 — the region ``R = {v (φ - sign(v) f_c) ≥ 0}`` of Lemma 3 in the
  ``(φ, v)`` plane, and its complement ``R̂``.
* Fig. 3 — for Table I cases (a) and (b): solutions of eq. (xPhDot) from
  several initial states (top), their phase portraits in ``(s, v, e_i)``
  with the attractor 𝒜 of eq. (Aph) and the stick strip
  ``|k_i e_i + k_p s| ≤ f_c`` of the plane ``v = 0`` (centre), and the
  Lyapunov-like function ``V`` of eq. (lyapLike) along them (bottom).  The
  solutions come from the exact ``event`` method.
* Fig. 4 — a Stribeck curve inside the inflated law ``f_c SGN_ρ`` of
  eq. (perturbed).

Figures are kept in a registry so that other modules can add theirs:
decorate a function ``f(out_dir: Path) -> list[Path]`` with
``@register("name", "one-line description")`` in a module listed in
:data:`FIGURE_MODULES`.  ``symbolic-friction figures`` imports those modules
and runs every registered figure (or the ones named with ``--only``).
File names are deterministic (``fig2_region_R.png``, ``fig3a_solutions.png``, …).

A figure whose data takes long to compute is registered with
:func:`register_split`: its computation is a list of independent
:class:`Task` objects and a ``draw(out_dir, results)`` function, so that
:mod:`.figures_run` can spread the tasks of every figure over the cores
(the results, and so the files, are those of the sequential run).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .._infra.errors import SymbolicFrictionError
from .._infra.io import atomic_write
from .figures_registry import FIGURES, FigureFunction, FigureSpec, Task, register, register_split

__all__ = [
    "FigureSpec",
    "FIGURES",
    "FIGURE_MODULES",
    "register",
    "register_split",
    "Task",
    "available_figures",
    "make_figures",
    "FIG3_INITIAL_STATES",
    "plot_scene",
]

FIGURE_MODULES: tuple[str, ...] = (
    "symbolic_friction._studies.figures",
    "symbolic_friction._studies.crosscheck_figures",
    "symbolic_friction._extremes",
)
"""Modules imported by :func:`available_figures` so that they register their figures.
Add a module here (e.g. the cross-check's figures) to extend ``symbolic-friction figures``."""


def available_figures() -> dict[str, FigureSpec]:
    """Import :data:`FIGURE_MODULES` and return the registry."""
    for module in FIGURE_MODULES:
        importlib.import_module(module)
    return dict(FIGURES)


def chosen_figures(names: Sequence[str] | None, formats: Sequence[str]) -> tuple[list[FigureSpec], tuple[str, ...]]:
    """The registered figures ``names`` (default: all) and the formats to write (png first), refusing unknown ones.

    Raises
    ------
    SymbolicFrictionError
        If a name is not a registered figure, or a format is not one of png, pdf, svg.
    """
    bad = [f for f in formats if f not in FIGURE_FORMATS]
    if bad:
        raise SymbolicFrictionError(f"unknown figure format(s) {', '.join(map(repr, bad))}; expected some of {', '.join(FIGURE_FORMATS)}")
    figures = available_figures()
    chosen = list(figures) if names is None else list(names)
    unknown = [n for n in chosen if n not in figures]
    if unknown:
        raise SymbolicFrictionError(
            f"unknown figure(s) {', '.join(map(repr, unknown))}; available: {', '.join(figures)}"
        )
    return [figures[n] for n in chosen], tuple(dict.fromkeys(("png", *formats)))


def drawn(out: Path, spec: FigureSpec, formats: tuple[str, ...], results: list | None = None) -> list[Path]:
    """Draw ``spec`` into ``out`` in ``formats`` (from its tasks' ``results`` if given); return every file written."""
    global _FORMATS
    written: list[Path] = []
    previous, _FORMATS = _FORMATS, formats
    try:
        paths = spec.function(out) if results is None else spec.draw(out, results)  # type: ignore[misc]
        for path in paths:
            written.append(path)
            if path.suffix == ".png":  # the same figure in the other formats asked for
                written += [path.with_suffix(f".{fmt}") for fmt in formats[1:] if path.with_suffix(f".{fmt}").exists()]
    finally:
        _FORMATS = previous
    return written


def draw_whole(name: str, out: Path, formats: tuple[str, ...]) -> list[Path]:
    """Draw the registered figure ``name`` (in a child process of the parallel run)."""
    return drawn(out, available_figures()[name], formats)


def make_figures(
    out_dir: str | Path,
    names: Sequence[str] | None = None,
    *,
    formats: Sequence[str] = ("png",),
    on_written: Any = None,
    jobs: int = 1,
    progress: Any = None,
) -> list[Path]:
    """Write the figures ``names`` (default: all) into ``out_dir``; return the files.

    Each figure is written as PNG and, if ``formats`` asks for it, as PDF and/or SVG too.
    ``on_written(path)``, if given, is called as soon as each file is written
    (the command line prints it at once instead of after every figure).
    With ``jobs > 1`` the figures, and the tasks of split figures, run in that many
    processes (:func:`.figures_run.run_parallel`; the files are the same);
    ``progress`` (a :class:`~symbolic_friction._infra.progress.Progress`) then counts the tasks.

    Raises
    ------
    SymbolicFrictionError
        If a name is not a registered figure, or a format is not one of png, pdf, svg.
    """
    specs, fmts = chosen_figures(names, formats)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    from .figures_run import can_fork, run_parallel

    if jobs > 1 and can_fork():  # without fork, one figure after the other gives the same files
        return run_parallel(out, specs, fmts, jobs=jobs, drawn=drawn, draw_whole=draw_whole, on_written=on_written,
                            progress=progress)
    written: list[Path] = []
    for spec in specs:
        for path in drawn(out, spec, fmts):
            written.append(path)
            if on_written is not None:
                on_written(path)
        if progress is not None:
            progress.update(len(spec.tasks()) if spec.tasks is not None else 1)
    return written


# ---------------------------------------------------------------- plotting helpers
def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


FIGURE_FORMATS = ("png", "pdf", "svg")
# the formats the figure being drawn is written in (set by make_figures for the duration of a call)
_FORMATS: tuple[str, ...] = ("png",)
# metadata that would change from run to run (dates, versions) is left out, so reruns give the same bytes
_METADATA = {"png": {"Software": None}, "pdf": {"Creator": None, "Producer": None, "CreationDate": None}, "svg": {"Date": None, "Creator": None}}


def _FORMATS_NOW() -> tuple[str, ...]:
    """The formats :func:`make_figures` is writing in now (for figures saved with :func:`save_figure`)."""
    return _FORMATS


def save_figure(fig: Any, stem: Path, formats: Sequence[str] = ("png",)) -> list[Path]:
    """Write ``fig`` as ``stem.png`` and as ``stem.pdf`` / ``stem.svg`` if asked; close it; return the files."""
    import matplotlib

    written = []
    for fmt in dict.fromkeys(formats):
        path = stem.parent / f"{stem.name}.{fmt}"
        with matplotlib.rc_context({"svg.hashsalt": "symbolic_friction"}):
            atomic_write(path, lambda fh, fmt=fmt: fig.savefig(fh, format=fmt, dpi=130, metadata=_METADATA[fmt]))
        written.append(path)
    _pyplot().close(fig)
    return written


def _save(fig: Any, path: Path) -> Path:
    """Save atomically (PNG, plus the other formats :func:`make_figures` was asked for); return the PNG."""
    save_figure(fig, path.with_suffix(""), _FORMATS)
    return path


# Initial states (e_i, s, v) for Fig. 3; the first one is drawn heavy black.
# Case (a): from s = 1 at rest the black solution sticks four times in 40 s,
# for 0.83, 2.0, 4.6 and 10.2 s (growing), while e_i ramps with slope s;
# (1, 1, 1) reverses at t ≈ 0.09 s without sticking, where V jumps down.
# Case (b): each solution sticks at most once, then converges only
# asymptotically with v ≠ 0 and e_i → ±f_c/k_i = ±12.5; the black one,
# from (0.2, 0, -2), sticks from t ≈ 0.78 to 11.4 s (shaded), the others
# stick briefly or never.  V jumps within the first second: its plot has a
# logarithmic time axis.
FIG3_INITIAL_STATES: dict[str, tuple[tuple[float, float, float], ...]] = {
    "a": ((0.0, 1.0, 0.0), (0.0, -1.5, 0.0), (1.0, 1.0, 1.0), (0.0, 0.0, 2.0), (0.2, 0.0, -1.5)),
    "b": ((0.2, 0.0, -2.0), (0.0, 3.0, 0.0), (0.0, -2.0, 0.0), (1.0, 1.0, 1.0), (0.0, 0.0, 3.0)),
}
FIG3_LOG_TIME = {"a": False, "b": True}
FIG3_HORIZON = {"a": 40.0, "b": 60.0}
FIG3_METHOD = "event"
_COLORS = ("black", "tab:blue", "tab:purple", "tab:orange", "tab:green", "tab:red", "tab:brown")


@dataclass(frozen=True)
class _Piece:
    """One mode segment of a solution, sampled densely, with V_k on it."""

    mode: int
    t: Any
    z: Any
    V: Any


def _pieces(params: Any, z0: tuple[float, float, float], t_end: float, n: int = 2001, log_from: float | None = None) -> list[_Piece]:
    """Sample a solution segment by segment (closed segments, V_k on each).

    ``V`` along a solution is ``V_k`` on the segment in mode ``k`` (Claim 1),
    so evaluating ``V_k`` on the closed segment gives both one-sided limits at
    the switching times, where ``V`` may jump (downwards).
    """
    import numpy as np

    from .._model.coordinates import z_to_x
    from .._model.lyapunov import V_k
    from .._simulation import simulate

    first = simulate(params, z0, t_end, method=FIG3_METHOD)
    inner = [(float(te), int(a), int(b)) for te, a, b in first.events if 0.0 < te < t_end]
    switch = [te for te, _, _ in inner]
    grid = np.union1d(np.linspace(0.0, t_end, n), np.array(switch))
    if log_from is not None:  # also dense on a logarithmic time axis
        grid = np.union1d(grid, np.geomspace(log_from, t_end, 600))
    sol = simulate(params, z0, t_end, method=FIG3_METHOD, t_eval=grid)
    bounds = [0.0, *switch, t_end]
    # The mode of each segment is the one the next switch leaves (the last one: the one it enters).
    modes = [a for _, a, _ in inner] + [inner[-1][2] if inner else int(sol.mode[-1])]
    pieces = []
    for a, b, k in zip(bounds[:-1], bounds[1:], modes):
        mask = (sol.t >= a) & (sol.t <= b)
        z = sol.z[mask]
        pieces.append(_Piece(k, sol.t[mask], z, V_k(params, z_to_x(params, z), k)))
    return pieces


def _clip_polygon(points: list[tuple[float, float]], halfplanes: list[tuple[float, float, float]]) -> list[tuple[float, float]]:
    """Clip a convex polygon to the half-planes ``a x + b y ≤ c`` (Sutherland–Hodgman)."""
    for a, b, c in halfplanes:
        out: list[tuple[float, float]] = []
        for i, p in enumerate(points):
            q = points[(i + 1) % len(points)]
            fp, fq = a * p[0] + b * p[1] - c, a * q[0] + b * q[1] - c
            if fp <= 0:
                out.append(p)
            if (fp < 0 < fq) or (fq < 0 < fp):
                lam = fp / (fp - fq)
                out.append((p[0] + lam * (q[0] - p[0]), p[1] + lam * (q[1] - p[1])))
        points = out
        if not points:
            break
    return points


def _z0_label(z0: tuple[float, float, float]) -> str:
    return "$z_0$ = (" + ", ".join(f"{float(c):g}" for c in z0) + ")"


def _fig3(case: str, out: Path) -> list[Path]:
    import numpy as np

    from .._model.parameters import Parameters

    plt = _pyplot()
    params = Parameters.table_i(case)
    k_p, k_i, k_v, f_c = params.as_floats()
    t_end = FIG3_HORIZON[case]
    runs = [_pieces(params, z0, t_end, log_from=1e-3 if FIG3_LOG_TIME[case] else None) for z0 in FIG3_INITIAL_STATES[case]]
    label = {"a": "(a): $k_v=6.4$, $k_p=3$, $k_i=4$", "b": "(b): $k_v=1.5$, $k_p=0.66$, $k_i=0.08$"}[case]
    written = []

    # Top: solutions.
    fig, axes = plt.subplots(3, 1, figsize=(7.5, 7.5), sharex=True)
    for idx, (pieces, z0) in enumerate(zip(runs, FIG3_INITIAL_STATES[case])):
        color, lw, zo = _COLORS[idx % len(_COLORS)], (2.2 if idx == 0 else 1.0), (3 if idx == 0 else 2)
        t = np.concatenate([p.t for p in pieces])
        z = np.concatenate([p.z for p in pieces])
        for j, ax in enumerate(axes):
            ax.plot(t, z[:, j], color=color, lw=lw, zorder=zo, label=_z0_label(z0) if j == 0 else None)
    bound = f_c / k_i
    axes[0].axhspan(-bound, bound, color="tab:red", alpha=0.12, lw=0, label=r"$|e_i|\leq f_c/k_i$")
    sticks = [(p.t[0], p.t[-1]) for p in runs[0] if p.mode == 0 and p.t[-1] > p.t[0]]
    if not sticks:  # the highlighted solution is chosen to stick (FIG3_INITIAL_STATES); say so if it stops
        raise SymbolicFrictionError(f"Fig. 3{case}: the highlighted solution from {FIG3_INITIAL_STATES[case][0]} never sticks")
    for j, (a, b) in enumerate(sticks):
        for ax in axes:
            ax.axvspan(a, b, color="0.85", lw=0, zorder=0, label="stick phases of the black solution" if (j == 0 and ax is axes[0]) else None)
    for ax, name in zip(axes, ("$e_i$", "$s$", "$v$")):
        ax.set_ylabel(name)
        ax.axhline(0.0, color="grey", lw=0.5)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("$t$ [s]")
    axes[-1].set_xlim(0.0, t_end)
    fig.legend(loc="lower center", ncol=4, fontsize=7, frameon=False)
    fig.suptitle(f"Fig. 3, top — solutions, case {label}", fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    written.append(_save(fig, out / f"fig3{case}_solutions.png"))

    # Centre: phase portrait (s, v, e_i) with 𝒜 and the stick strip.
    fig = plt.figure(figsize=(7.5, 6.5))
    ax = fig.add_subplot(projection="3d")
    all_z = np.concatenate([np.concatenate([p.z for p in pieces]) for pieces in runs])
    s_lim = (all_z[:, 1].min(), all_z[:, 1].max())
    e_lim = (all_z[:, 0].min(), all_z[:, 0].max())
    e_box = (min(e_lim[0], -bound), max(e_lim[1], bound))
    # Stick strip in v = 0: -f_c ≤ -k_i e_i - k_p s ≤ f_c, clipped to the plotted box
    # (3-D axes do not clip patches).
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    strip = _clip_polygon(
        [(s_lim[0], e_box[0]), (s_lim[1], e_box[0]), (s_lim[1], e_box[1]), (s_lim[0], e_box[1])],
        [(k_p, k_i, f_c), (-k_p, -k_i, f_c)],  # a·s + b·e ≤ c
    )
    if len(strip) >= 3:
        ax.add_collection3d(Poly3DCollection([[(p[0], 0.0, p[1]) for p in strip]], color="tab:cyan", alpha=0.18, lw=0))
    for idx, pieces in enumerate(runs):
        color, lw = _COLORS[idx % len(_COLORS)], (2.0 if idx == 0 else 0.9)
        z = np.concatenate([p.z for p in pieces])
        ax.plot(z[:, 1], z[:, 2], z[:, 0], color=color, lw=lw)
        ax.scatter([z[0, 1]], [z[0, 2]], [z[0, 0]], color=color, s=12)
    ax.plot([0, 0], [0, 0], [-bound, bound], color="tab:red", lw=4, label=r"attractor $\mathcal{A}$")
    ax.scatter([], [], color="black", s=12, label="initial states $z_0$ (colours as in the top figure)")
    ax.plot([], [], color="tab:cyan", alpha=0.5, lw=6, label=r"stick strip $v=0$, $|k_i e_i+k_p s|\leq f_c$")
    ax.set_xlabel("$s$")
    ax.set_ylabel("$v$")
    ax.set_zlabel("$e_i$")
    ax.set_xlim(*s_lim)
    ax.set_zlim(*e_box)
    ax.view_init(elev=22, azim=-60)
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title(f"Fig. 3, centre — phase portrait, case {label}", fontsize=10)
    fig.tight_layout()
    written.append(_save(fig, out / f"fig3{case}_phase.png"))

    # Bottom: V along the solutions (V_k on each closed segment: jumps show as gaps).
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    log_time = FIG3_LOG_TIME[case]
    t_min = 1e-3 if log_time else 0.0
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    for idx, pieces in enumerate(runs):
        color, lw, zo = _COLORS[idx % len(_COLORS)], (2.2 if idx == 0 else 1.0), (3 if idx == 0 else 2)
        for j, p in enumerate(pieces):
            keep = p.t >= t_min if log_time else slice(None)
            ax.plot(p.t[keep], p.V[keep], color=color, lw=lw, zorder=zo, solid_capstyle="butt")
            if j + 1 < len(pieces):
                nxt = pieces[j + 1]
                if abs(nxt.V[0] - p.V[-1]) > 1e-9 * max(1.0, abs(p.V[-1])):
                    ax.plot([p.t[-1]] * 2, [p.V[-1], nxt.V[0]], color=color, lw=0.7, ls=":", zorder=zo)
                    ax.plot([p.t[-1]], [nxt.V[0]], "o", color=color, ms=3, zorder=zo)
    for a, b in sticks:
        ax.axvspan(max(a, t_min) if log_time else a, b, color="0.88", lw=0, zorder=0)
    ax.set_yscale("log")
    if log_time:
        ax.set_xscale("log")
        ax.set_xlim(t_min, t_end)
    else:
        ax.set_xlim(0.0, t_end)
    ax.set_xlabel("$t$ [s]" + (" (logarithmic: the jumps come early)" if log_time else ""))
    ax.set_ylabel("$V(x(t))$")
    ax.grid(alpha=0.3, which="both")
    handles = [Line2D([], [], color=_COLORS[i % len(_COLORS)], lw=2.2 if i == 0 else 1.0, label=_z0_label(z0))
               for i, z0 in enumerate(FIG3_INITIAL_STATES[case])]
    handles += [Line2D([], [], color="grey", lw=0.7, ls=":", marker="o", ms=3, label="jump of $V$ at a switch (dot: value after)"),
                Patch(color="0.88", label="stick phases of the black solution")]
    # below the axes, so that it never hides a curve
    ax.legend(handles=handles, fontsize=7, ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False)
    ax.set_title(f"Fig. 3, bottom — $V$ along the solutions, case {label}\n"
                 "nonincreasing, flat during stick, dotted: downward jumps at switching times", fontsize=9)
    fig.tight_layout()
    written.append(_save(fig, out / f"fig3{case}_V.png"))
    return written


@register("fig3a", "Fig. 3, left column: solutions, phase portrait and V for Table I case (a)", cost=3.0)
def fig3a(out: Path) -> list[Path]:
    return _fig3("a", out)


@register("fig3b", "Fig. 3, right column: solutions, phase portrait and V for Table I case (b)", cost=3.0)
def fig3b(out: Path) -> list[Path]:
    return _fig3("b", out)


@register("fig2", "Fig. 2: the region R of Lemma 3 and its complement R-hat in the (phi, v) plane")
def fig2(out: Path) -> list[Path]:
    plt = _pyplot()
    f_c, L = 1.0, 3.0
    fig, ax = plt.subplots(figsize=(5.2, 4.2))
    ax.fill_between([f_c, L], 0, L, color="tab:blue", alpha=0.45, lw=0)
    ax.fill_between([-L, -f_c], -L, 0, color="tab:blue", alpha=0.45, lw=0)
    ax.plot([-L, L], [0, 0], color="tab:blue", lw=3)  # v = 0 belongs to R
    ax.plot([f_c, f_c], [0, L], color="tab:blue", lw=2)  # closed: φ = f_c with v > 0
    ax.plot([-f_c, -f_c], [-L, 0], color="tab:blue", lw=2)
    ax.text(2.0, 1.5, "$R$", fontsize=15, ha="center", color="white")
    ax.text(-2.0, -1.5, "$R$", fontsize=15, ha="center", color="white")
    ax.text(-1.0, 1.5, r"$\hat R$", fontsize=15, ha="center")
    ax.text(1.0, -1.5, r"$\hat R$", fontsize=15, ha="center")
    ax.annotate("$v=0$ (in $R$)", xy=(-2.5, 0), xytext=(-2.9, 0.6), fontsize=8, arrowprops={"arrowstyle": "->", "lw": 0.6})
    ax.set_xlim(-L, L)
    ax.set_ylim(-L, L)
    ax.set_xticks([-f_c, 0, f_c])
    ax.set_xticklabels(["$-f_c$", "0", "$f_c$"])
    ax.set_yticks([0])
    ax.set_xlabel(r"$\phi$")
    ax.set_ylabel("$v$")
    ax.set_title(r"Fig. 2 — $R=\{x: v(\phi-\mathrm{sign}(v)f_c)\geq 0\}$ (blue), $\hat R$ its complement", fontsize=9)
    fig.tight_layout()
    return [_save(fig, out / "fig2_region_R.png")]


@register("fig4", "Fig. 4: a Stribeck curve inside the inflated law f_c SGN_rho")
def fig4(out: Path) -> list[Path]:
    import numpy as np

    from .._simulation.friction import Stribeck

    plt = _pyplot()
    f_c = 1.0
    law = Stribeck(f_s="1.3", v_s="0.1")
    rho = float(law.required_rho(1))
    v = np.linspace(-1.0, 1.0, 4001)
    v = v[v != 0]
    fig, ax = plt.subplots(figsize=(6.0, 4.2))
    # The graph of f_c SGN_ρ (eq. perturbed) as one polygon: slip bands for |v| > ρ, the block |v| ≤ ρ.
    r = rho
    outline = [(-1, -1 + r), (-r, -1 + r), (-r, 1 + r), (1, 1 + r), (1, 1 - r), (r, 1 - r), (r, -1 - r), (-1, -1 - r)]
    ax.fill([p[0] for p in outline], [f_c * p[1] for p in outline], color="tab:grey", alpha=0.3, lw=0,
            label=rf"$f_c\,\mathrm{{SGN}}_\rho(v)$, $\rho={rho:g}$")
    ax.plot([-1, 0, 0, 1], [-f_c, -f_c, f_c, f_c], color="black", lw=1.0, ls="--", label=r"$f_c\,\mathrm{SGN}(v)$")
    f = law.force(v, f_c)
    ax.plot(v[v > 0], f[v > 0], color="tab:blue", lw=2, label=rf"Stribeck, $f_s={float(law.f_s):g}$, $v_s={float(law.v_s):g}$")
    ax.plot(v[v < 0], f[v < 0], color="tab:blue", lw=2)
    ax.plot([0, 0], [-float(law.f_s), float(law.f_s)], color="tab:blue", lw=2)
    ax.set_xlabel("$v$")
    ax.set_ylabel("friction (per unit mass)")
    ax.axhline(0, color="grey", lw=0.5)
    ax.axvline(0, color="grey", lw=0.5)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("Fig. 4 — the Stribeck effect is included in the perturbation (eq. perturbed)", fontsize=9)
    fig.tight_layout()
    return [_save(fig, out / "fig4_stribeck.png")]


# ---------------------------------------------------------------- scene figure
def plot_scene(result: Any, path: Path) -> Path:
    """A PNG of a scene's solutions: ``e_i, s, v`` (and ``V``, ``|x|_𝒜`` if computed) against ``t``."""
    plt = _pyplot()
    scene = result.scene
    rows = ["e_i", "s", "v"]
    if "V" in scene.outputs:
        rows.append("V")
    if "distance" in scene.outputs:
        rows.append("distance")
    fig, axes = plt.subplots(len(rows), 1, figsize=(7.5, 1.7 * len(rows) + 1.0), sharex=True)
    for i, sol in enumerate(result.solutions):
        color = _COLORS[i % len(_COLORS)]
        data = {"e_i": sol.z[:, 0], "s": sol.z[:, 1], "v": sol.z[:, 2]}
        if "V" in rows:
            data["V"] = sol.V
        if "distance" in rows:
            data["distance"] = sol.distance
        z0 = ", ".join(f"{float(c):g}" for c in scene.initial_states[i])
        for ax, key in zip(axes, rows):
            ax.plot(sol.t, data[key], color=color, lw=1.0, label=f"$z_0$ = ({z0})" if key == "e_i" else None)
    if len(result.solutions) <= 8:
        axes[0].legend(fontsize=7, ncol=2)
    labels = {"e_i": "$e_i$", "s": "$s$", "v": "$v$", "V": "$V$", "distance": r"$|x|_{\mathcal{A}}$"}
    for ax, key in zip(axes, rows):
        ax.set_ylabel(labels[key])
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("$t$")
    fig.suptitle(f"scene {scene.name} — method {scene.method}", fontsize=10)
    fig.tight_layout()
    return _save(fig, path)
