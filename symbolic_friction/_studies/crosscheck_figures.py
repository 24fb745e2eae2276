"""Figures of the cross-check: how tight the certified overshoot
bound κ of Proposition 1 (eq. stabState) is, and the empirical ISS gain of
Corollary 1.

* :func:`plot_tightness` — observed ``sup_t |x(t)|_𝒜/|x(0)|_𝒜`` of every
  cross-checked trajectory against ``|x(0)|_𝒜``, by search mode, with the
  certified κ of each certificate of the gain set;
* :func:`plot_iss` — ``γ̂(ρ)`` against ``ρ`` (log–log) for the greedy
  selection of the inflated law, Stribeck laws inside it, the worst found by
  the search over selections (never called a worst case: it is not a proved
  upper bound) and the exact rest point ``ρ f_c/k_i`` (a proved lower bound).

Both are registered for ``symbolic-friction figures`` (names
``crosscheck_tightness`` and ``crosscheck_iss``) once this module is listed
in :data:`symbolic_friction._studies.figures.FIGURE_MODULES`.  matplotlib (Agg) is
imported only when a figure is drawn.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .figures import Task, _pyplot, _save, register_split

__all__ = [
    "plot_tightness",
    "plot_iss",
    "table_i_certificates",
    "figure_tightness",
    "figure_iss",
    "TIGHTNESS_TRAJECTORIES",
]

TIGHTNESS_TRAJECTORIES = 2000
"""Trajectories per gain set behind the tightness figure (the CLI default is 100000)."""

_MODE_STYLE = {
    "random spheres": ("tab:blue", "."),
    "grid": ("tab:green", "+"),
    "special": ("tab:purple", "x"),
    "adversarial": ("tab:red", "o"),
}


def table_i_certificates(directory: str | Path = "proofs", *, cases: Sequence[str] = ("a", "b")) -> list[Any]:
    """The Table I certificates (feasible, tightest) of ``cases``: from ``directory`` if present, else certified
    now (exactly verified)."""
    from .._certify import certify, verify_certificate
    from .._model.parameters import Parameters

    out = []
    for case in cases:
        for mode in ("feasible", "tightest"):
            path = Path(directory) / f"case_{case}_{mode}.json"
            if path.exists():
                out.append(path)
            else:
                cert = certify(Parameters.table_i(case), mode=mode, label=f"Table I, case ({case})")
                verify_certificate(cert).raise_if_failed()
                out.append(cert)
    return out


def plot_tightness(checks: Sequence[Any], path: str | Path, *, labels: Sequence[str] | None = None) -> Path:
    """Draw the tightness figure from :class:`~._crosscheck.CertificateCheck` results.

    One panel per gain set: each dot is a trajectory, at ``(|x(0)|_𝒜,
    observed overshoot)``; horizontal lines are the κ of the certificates,
    named by ``labels`` (one per check; default: each check's label).
    """
    import numpy as np

    plt = _pyplot()
    names = dict(zip(map(id, checks), labels)) if labels is not None else {}
    groups: dict[Any, list[Any]] = {}
    for c in checks:
        groups.setdefault(c.claims.params, []).append(c)
    fig, axes = plt.subplots(1, len(groups), figsize=(5.6 * len(groups), 4.4), squeeze=False)
    for ax, (params, members) in zip(axes[0], groups.items()):
        first = members[0]
        ov, d0, modes = first.overshoots, first.initial_distance, first.modes
        ok = np.isfinite(ov) & (d0 > 0)
        # states on 𝒜 up to rounding (|x(0)|_𝒜 below 1e-12 of the largest) would stretch the log axis
        # over ten empty decades: counted in the title instead of drawn
        on_a = ok & (d0 < 1e-12 * (d0[ok].max() if np.any(ok) else 1.0))
        ok &= ~on_a
        for mode, (color, marker) in _MODE_STYLE.items():
            m = ok & (modes == mode)
            if np.any(m):
                ax.scatter(d0[m], ov[m], s=6 if marker == "." else 14, c=color, marker=marker, alpha=0.6,
                           linewidths=0.7, label=f"{mode} (max {ov[m].max():.3f})")
        for c, ls in zip(members, ("-", "--", ":", "-.")):
            ax.axhline(c.claims.kappa, color="black", ls=ls, lw=1.2,
                       label=f"κ {names.get(id(c), c.label)}: {c.claims.kappa:.4g} "
                             f"(ratio {c.tightness.get('all', float('nan')):.3f})")
        ax.axhline(1.0, color="grey", lw=0.6)
        ax.set_xscale("log")
        top = max(c.claims.kappa for c in members)
        shown = ok & (ov <= 1.15 * top)
        if np.any(shown):  # fit the axis to the trajectories drawn
            ax.set_xlim(d0[shown].min() / 2, d0[shown].max() * 2)
        ax.set_xlabel(r"$|x(0)|_{\mathcal{A}}$")
        ax.set_ylabel(r"observed $\sup_t |x(t)|_{\mathcal{A}} / |x(0)|_{\mathcal{A}}$")
        ax.set_title(
            f"k_p={float(params.k_p):g}, k_i={float(params.k_i):g}, k_v={float(params.k_v):g}, "
            f"f_c={float(params.f_c):g}: "
            f"{first.trajectories} trajectories"
            + (f"\n({int(on_a.sum())} on $\\mathcal{{A}}$ up to rounding, not drawn)" if on_a.any() else ""),
            fontsize=9,
        )
        ax.legend(fontsize=7, loc="upper right")
        top = max(c.claims.kappa for c in members)
        ax.set_ylim(0.9, 1.15 * top)
    fig.suptitle("Proposition 1: observed overshoot against the certified bound κ", fontsize=10)
    fig.tight_layout()
    return _save(fig, Path(path))


def plot_iss(estimates: Sequence[Any], path: str | Path, *, labels: Sequence[str] | None = None) -> Path:
    """Draw ``γ̂(ρ)`` (log–log) for :class:`~._crosscheck.IssEstimate` results."""
    import numpy as np

    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    colors = ("tab:blue", "tab:orange", "tab:green", "tab:red")
    for j, est in enumerate(estimates):
        p = est.params
        name = labels[j] if labels else f"k_p={float(p.k_p):g}, k_i={float(p.k_i):g}, k_v={float(p.k_v):g}"
        rho = np.array(est.rhos)
        color = colors[j % len(colors)]
        for law, ls, marker in (("greedy", "-", "o"), ("stribeck", "--", "s")):
            if law not in est.gamma:
                continue
            g = np.asarray(est.gamma[law])
            m = rho > 0
            ax.plot(rho[m], g[m], ls=ls, marker=marker, color=color, ms=4,
                    label=f"{name}: {'SGN_ρ greedy selection' if law == 'greedy' else 'Stribeck f_s=(1+ρ)f_c'}")
            base = est.gamma[law][list(rho).index(0.0)] if 0.0 in list(rho) else None
            if base is not None and law == "greedy":
                ax.axhline(base, color=color, lw=0.6, ls=":")
        found = getattr(est, "worst_found", {}) or {}
        if found:
            rf = np.array(sorted(found))
            ax.plot(rf, [found[r].bound for r in rf], ls="none", marker="*", ms=10, color=color,
                    label=f"{name}: SGN_ρ worst found (search over selections)")
        rr = rho[rho > 0]
        if rr.size:
            ax.plot(rr, rr * float(p.f_c / p.k_i), lw=0.8, ls=(0, (5, 2)), color=color, alpha=0.6,
                    label=f"{name}: rest point ρ f_c/k_i (proved lower bound)")
    rr = np.geomspace(1e-3, 1, 20)
    ax.plot(rr, 0.5 * np.sqrt(rr), color="grey", lw=0.8, ls="-.", label=r"$\propto\sqrt{\rho}$")
    ax.plot(rr, 2.0 * rr, color="grey", lw=0.8, ls=(0, (1, 3)), label=r"$\propto\rho$")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"inflation $\rho$")
    ax.set_ylabel(r"ultimate bound $\hat\gamma(\rho)$ of $|z|_{\mathcal{A}}$")
    ax.set_title("Corollary 1: ultimate bounds found, not upper bounds (dotted: transient left at ρ = 0)", fontsize=9)
    ax.legend(fontsize=6.5, loc="lower right")
    fig.tight_layout()
    return _save(fig, Path(path))


# -- the two figures, each split into independent tasks (one per gain set, one per searched rho)
# so that ``symbolic-friction figures`` spreads them over the cores; run one after the other they
# compute exactly what one call of ``crosscheck`` / ``iss_gain`` computes.
_CASES = ("a", "b")
_MODES = ("feasible", "tightest")
ISS_RHOS = ("0", "0.001", "0.003", "0.01", "0.03", "0.1", "0.3", "1")
ISS_SEARCH_RHOS = ("0.01", "0.1", "1")


def _tightness_checks(case: str) -> list[Any]:
    """The cross-check of case ``case``'s Table I certificates, seeded as gain set ``case`` of the joint run.

    ``crosscheck`` seeds gain set ``gi`` (in the order of the certificates) with ``seed + 1000 gi``; the
    certificates of one case share a gain set, so case (a) is gain set 0 and case (b) gain set 1.
    """
    from .._crosscheck import crosscheck

    gi = _CASES.index(case)
    certs = table_i_certificates(cases=(case,))
    report = crosscheck(certs, trajectories=TIGHTNESS_TRAJECTORIES, seed=1000 * gi, progress=False)
    return list(report.checks)


def _tightness_tasks() -> list[Task]:
    return [Task(f"crosscheck_tightness ({c})", _tightness_checks, (c,), cost=4.0) for c in _CASES]


def _tightness_draw(out: Path, parts: list[list[Any]]) -> list[Path]:
    checks = [c for part in parts for c in part]
    # named by case and mode, whether the certificates came from proofs/ or were certified now
    # (so the legend does not depend on the working directory)
    labels: list[str] | None = [f"({case}) {mode}" for case in _CASES for mode in _MODES]
    if len(checks) != len(labels):
        labels = None
    return [plot_tightness(checks, Path(out) / "crosscheck_tightness.png", labels=labels)]


def _iss_defaults() -> dict[str, Any]:
    """The horizon and step ``iss_gain`` simulates with (its defaults), which its searches are given too."""
    import inspect

    from .._crosscheck import iss_gain

    params = inspect.signature(iss_gain).parameters
    return {"horizon": params["horizon"].default, "h": params["h"].default}


def _iss_sweep(case: str) -> Any:
    """``γ̂(ρ)`` of case ``case`` over :data:`ISS_RHOS`, without the search (``iss_gain`` as the figure calls it)."""
    from .._crosscheck import iss_gain
    from .._model.parameters import Parameters

    return iss_gain(Parameters.table_i(case), ISS_RHOS)


def _iss_search(case: str, rho: str) -> Any:
    """The worst selection found at ``rho`` for case ``case``, with the arguments ``iss_gain`` passes."""
    import numpy as np

    from .._crosscheck import worst_found
    from .._crosscheck._initial import default_initial_states
    from .._model.parameters import Parameters

    params = Parameters.table_i(case)
    Z0 = np.asarray(default_initial_states(params), dtype=float).reshape(-1, 3)
    return worst_found(params, rho, initial_states=Z0, **_iss_defaults())


def _iss_tasks() -> list[Task]:
    tasks = [Task(f"crosscheck_iss sweep ({c})", _iss_sweep, (c,), cost=6.0) for c in _CASES]
    tasks += [Task(f"crosscheck_iss search rho={r} ({c})", _iss_search, (c, r), cost=20.0)
              for c in _CASES for r in ISS_SEARCH_RHOS]
    return tasks


def _iss_draw(out: Path, parts: list[Any]) -> list[Path]:
    from dataclasses import replace

    n = len(ISS_SEARCH_RHOS)
    sweeps, searches = parts[: len(_CASES)], parts[len(_CASES):]
    estimates = []
    for i, sweep in enumerate(sweeps):
        found = {w.rho: w for w in searches[i * n: (i + 1) * n]}
        estimates.append(replace(sweep, worst_found=found))
    return [plot_iss(estimates, Path(out) / "crosscheck_iss.png", labels=[f"case ({c})" for c in _CASES])]


FIGURE_TIGHTNESS = register_split(
    "crosscheck_tightness", "Cross-check: observed overshoot against the certified kappa (Table I certificates)",
    tasks=_tightness_tasks, draw=_tightness_draw,
)
FIGURE_ISS = register_split(
    "crosscheck_iss", "Cross-check: empirical ISS gain gamma(rho) of Corollary 1 (Table I cases)",
    tasks=_iss_tasks, draw=_iss_draw,
)


def figure_tightness(out: Path) -> list[Path]:
    """Cross-check the Table I certificates and draw :func:`plot_tightness`."""
    return FIGURE_TIGHTNESS.function(out)


def figure_iss(out: Path) -> list[Path]:
    """Estimate ``γ̂(ρ)`` for Table I's cases (with the search at :data:`ISS_SEARCH_RHOS`) and draw :func:`plot_iss`."""
    return FIGURE_ISS.function(out)
