"""Benchmark: how close each template's proven κ comes to the friction-free limit on stiff and near-boundary gains.

Run from the repository root with the package installed::

    python tests/benchmarks/bench_stiff_kappa.py

For each gain set (Routh margin ``k_v·k_p/k_i = 1 + 10⁻⁶``, gain ratios of ``10⁶``) it prints

* ``κ_lin = sup_{t≥0} ‖e^{At}‖₂``, the friction-free limit no certificate can go below (floats: ``expm`` on a
  dense linear and logarithmic grid of ``[0, 40/|Re λ|_min]``; an estimate, not a proof), and its exact
  enclosure by :func:`~symbolic_friction._certify.flow_bound.kappa_lin_bound` where that succeeds within
  20,000 intervals (slowly decaying oscillations and slow real modes need more; shown as ``-``);
* the proven κ of the ``paper`` template (closed form, verified exactly) and of the ``quadratic`` template
  (SDP, rounded, verified exactly), each as a multiple of ``κ_lin``, with the certify time;
* the proven κ of the ``sup-flow`` template (SDPs on adaptive time pieces, verified in rationals and arb balls),
  as a multiple of ``κ_lin``, with its certify time (``-`` and the reason where its search gives nothing);
* ``√γ*``, where ``γ*`` is the smallest ``γ`` with a ``P`` such that ``I ⪯ P ⪯ γI``, ``AᵀP + PA ⪯ 0`` and
  ``P₁₂ = 0`` (the SDP of the quadratic template's linear part alone).  Every quadratic-template
  certificate has ``κ² ≥ λ_max(P) ≥ γ*``, so ``√γ*/κ_lin`` is what no certificate of that template can beat
  (a solver estimate), and the same without ``P₁₂ = 0`` (any quadratic Lyapunov function of the linear part)
  shows what the constraint ``P₁₂ = 0`` costs.

Nothing is asserted.
"""

from __future__ import annotations

import time
from fractions import Fraction as F

import numpy as np

CASES = {
    "Routh margin 1 + 1e-6": dict(k_p=F(1), k_i=F(1), k_v=1 + F(1, 10**6)),
    "k_v/k_i = 1e6 (k_i = 1e-6)": dict(k_p=F(1), k_i=F(1, 10**6), k_v=F(1)),
    "k_p = 1e6": dict(k_p=F(10**6), k_i=F(1), k_v=F(1)),
    "k_v = 1e6": dict(k_p=F(1), k_i=F(1), k_v=F(10**6)),
    "k_i = 1e6 (k_p = 1e3)": dict(k_p=F(10**3), k_i=F(10**6), k_v=F(10**3) + 1),
}


def _A(p) -> np.ndarray:
    k_p, k_i, k_v = (float(q) for q in (p.k_p, p.k_i, p.k_v))
    return np.array([[0.0, 0.0, -k_i], [1.0, 0.0, -k_p], [0.0, 1.0, -k_v]])


def kappa_lin(p) -> float:
    from scipy.linalg import expm

    A = _A(p)
    slow = min(abs(np.linalg.eigvals(A).real))
    T = 40.0 / slow
    ts = np.unique(np.concatenate([np.linspace(0.0, T, 20001), np.geomspace(1e-9 * T, T, 20001)]))
    return max(np.linalg.norm(expm(A * t), 2) for t in ts)


def quadratic_floor(p, *, p12_zero: bool) -> tuple[float, str]:
    import cvxpy as cp

    A = _A(p)
    P = cp.Variable((3, 3), symmetric=True)
    gamma = cp.Variable()
    cons = [P >> np.eye(3), gamma * np.eye(3) - P >> 0, -(A.T @ P + P @ A) >> 0]
    if p12_zero:
        cons.append(P[0, 1] == 0)
    problem = cp.Problem(cp.Minimize(gamma), cons)
    try:
        problem.solve(solver=cp.CLARABEL)
    except cp.error.SolverError as exc:
        return float("nan"), f"solver error {exc}"[:40]
    return (float(np.sqrt(gamma.value)) if gamma.value is not None else float("nan")), problem.status


def main() -> None:
    from symbolic_friction import Parameters
    from symbolic_friction._certify.pipeline import certify
    from symbolic_friction._certify.quadratic_search import certify_quadratic
    from symbolic_friction._certify.sup_flow_search import certify_sup_flow

    import os

    print("load average", ", ".join(f"{x:.2f}" for x in os.getloadavg()))
    from symbolic_friction._certify.flow_bound import kappa_lin_bound
    from symbolic_friction.errors import ParameterError

    header = f"{'gain set':28s} {'κ_lin':>9s} {'proven':>19s} | {'paper κ':>10s} {'×κ_lin':>9s} | {'quadratic κ':>11s} {'×κ_lin':>8s} {'s':>5s} | {'sup-flow κ':>10s} {'×κ_lin':>8s} {'s':>5s} | {'√γ* P12=0':>10s} {'×':>7s} | {'√γ* free':>9s} {'×':>6s}"
    print(header)
    print("-" * len(header))
    for name, gains in CASES.items():
        p = Parameters(**gains, f_c=F(1))
        kl = kappa_lin(p)
        try:
            bound = kappa_lin_bound(p, max_pieces=20_000)
            proven = f"[{float(bound.lower):.6g}, {float(bound.upper):.6g}]"
        except ParameterError:
            proven = "-"
        paper = float(F(certify(p).overshoot_bound))
        start = time.perf_counter()
        try:
            quad = float(F(certify_quadratic(p).overshoot_bound))
        except Exception as exc:  # infeasible or inaccurate: shown, not hidden
            quad, why = float("nan"), type(exc).__name__
        else:
            why = ""
        seconds = time.perf_counter() - start
        start = time.perf_counter()
        try:
            sup = float(F(certify_sup_flow(p).overshoot_bound))
        except Exception as exc:  # infeasible or inaccurate: shown, not hidden
            sup, why_sup = float("nan"), " ".join(str(exc).split())[-90:]
        else:
            why_sup = ""
        sup_seconds = time.perf_counter() - start
        floor0, status0 = quadratic_floor(p, p12_zero=True)
        floor1, status1 = quadratic_floor(p, p12_zero=False)
        print(f"{name:28s} {kl:9.4g} {proven:>19s} | {paper:10.4g} {paper / kl:9.3g} | {quad:11.4g} {quad / kl:8.3g} {seconds:5.1f} | "
              f"{sup:10.4g} {sup / kl:8.3g} {sup_seconds:5.1f} | "
              f"{floor0:10.4g} {floor0 / kl:7.3g} | {floor1:9.4g} {floor1 / kl:6.3g}"
              + (f"  [quadratic: {why}]" if why else "")
              + (f"  [sup-flow: {why_sup}]" if why_sup else "")
              + (f"  [floor P12=0: {status0}]" if status0 != "optimal" else "")
              + (f"  [floor free: {status1}]" if status1 != "optimal" else ""))


if __name__ == "__main__":
    main()
