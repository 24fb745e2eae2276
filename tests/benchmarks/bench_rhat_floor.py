"""Research benchmark: the floor of the sup-flow certificate's R̂ part, now and under two relaxations (c), (d).

The sup-flow template (``symbolic-friction/sup-flow-certificate/v1``) bounds ``V_∞`` on ``R̂`` by forms
``U = yᵀKy``, ``y = (|σ|, |dz φ|, |v|)``, one per time piece ``I``, with ``γ_I·I − K`` copositive and
``U ≥ |e^{At}w|²`` on the exit planes for every ``t ∈ I``.  With unlimited pieces the best it can do is the
*floor* ``sup_t γ(t)``, ``γ(t)`` the least ``γ`` of an infinitesimal piece at the single time ``t`` (``G =
e^{At}ᵀe^{At}``; at ``t = 0`` also ``K − I`` copositive).  For each gain set this prints ``κ_lin²`` (float
peak of ``‖e^{At}‖₂²``) and, over a time grid refined around its largest values, ``max γ(t)`` and where it
is attained, for

(i)   the current template: one ``K``, ``K₁₂ = 0``, rate and band premises for both signs ``s`` of ``σ``,
      ``K₃ⱼ ≥ 0``, exits ``v = 0`` and ``φ = f_c`` for both ``s``;
(ii)  the sign split (c): ``U⁺`` (``σv > 0``; ``K₁₂ ≥ 0``; only the ``s = +1`` rate, band and exit premises)
      and ``U⁻`` (``σv < 0`` and ``σ = 0``; ``K₁₂ ≤ 0``; the ``s = −1`` ones), coupled by ``(K⁺ − K⁻)`` on
      rows/cols {2,3} copositive (``U⁻ ≤ U⁺`` on ``σ = 0``);
(iii) (c) plus the friction-drag split (d) with ``ℓ`` = :data:`ELL`: on ``R̂′ = {f > ℓᵀy}``, ``f = f_c − φ −
      |dz φ|``, the rate forms gain ``K e₃ℓᵀ + ℓ e₃ᵀK`` (the band form its 2×2 part) and the new exit surface
      ``f = ℓᵀy`` needs ``K − D_ℓᵀGD_ℓ`` copositive; on ``R̂ \\ R̂′`` ``V_∞ ≤ c₂′|y|²`` with ``c₂′ = max(κ_lin²,
      sup_t λ_max(D_ℓᵀGD_ℓ))`` (λ_max: an upper end of the sup over ``y ≥ 0``), so the bound is ``max(γ, c₂′)``.

It also prints the closed-form lower end of (i), ``γ ≥ (k_i/k_v)²·max(1, |e^{At}e₁|²)`` (the ``s = −1`` band
form has a zero diagonal entry, so ``k_vK₁₃ ≥ k_iK₁₁``, ``k_vK₃₃ ≥ k_iK₁₃``: ``K₃₃ ≥ (k_i/k_v)²K₁₁``), and
its ratio to (i)'s floor: ≈ 1 where it binds, whatever the number of pieces.  The design note
``docs/design/sup_flow_v2.md`` states the premises and why (c) and (d) are sound.

``--mc N`` adds Monte-Carlo checks of (ii) and (iii) at their worst ``t`` (``f_c = 1``): ``N`` states in
``R̂ ∩ {v > 0}`` (in ``R̂′`` for (iii)) flowed exactly (``w = x − e₂``, ``ẇ = Aw``) until ``v = 0`` or
``f = ℓᵀy``; it reports the largest rise of ``U`` along a step and the largest ``|e^{At}w|² − U`` at the exit,
both relative to ``U(x₀)`` (≤ 0 up to float noise if the premises hold), and how many runs did not exit.

Nothing is asserted; float SDPs (the package's ``_conic.Program`` on Clarabel), not proofs.  Run from the
repository root::

    python tests/benchmarks/bench_rhat_floor.py [--quick] [--mc N]
"""

from __future__ import annotations

import argparse
import sys
import time
from fractions import Fraction as F
from pathlib import Path

import numpy as np
from scipy.linalg import expm

from symbolic_friction import Parameters
from symbolic_friction._certify import flow_bound
from symbolic_friction._certify._conic import Program
from symbolic_friction._model import quadratic as quad

ELL = (1e-3, 0.0, 1e-3)
EPS = 1e-7
VARIANTS = ("current", "signed", "drag")
TITLES = {"current": "(i) current, K₁₂ = 0", "signed": "(ii) (c) sign split", "drag": "(iii) (c)+(d) drag split"}


def gain_sets() -> dict[str, tuple[F, F, F]]:
    try:  # bench_tightness's seeded generator (seed 2026), exact
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from bench_tightness import random_sets
        r04 = random_sets(4, 2026)["random 04"]
    except ImportError:  # pragma: no cover - the decimals it gives
        r04 = (F("404.727"), F("0.386406"), F("0.00105771"))
    return {"Table I (a)": (F(3), F(4), F(32, 5)), "random 04": r04,
            "(1000, 1e-3, 1000)": (F(1000), F(1, 1000), F(1000)), "(100, 1e4, 100.01)": (F(100), F(10**4), F(10001, 100))}


def A_of(k):
    kp, ki, kv = k
    return np.array([[0.0, 0.0, -ki], [1.0, 0.0, -kp], [0.0, 1.0, -kv]])


def gram(k, t):
    E = expm(A_of(k) * t)
    return E.T @ E


def mm(a, b):
    return [[sum((a[i][m] * b[m][j] for m in range(len(b))), 0.0) for j in range(len(b[0]))] for i in range(len(a))]


def d_ell(s, ell):
    """``w = D_ℓ y`` on the surface ``f = ℓᵀy`` (``v > 0``, ``s = sign σ``)."""
    return np.array([[s, 0, 0], [-ell[0], -1 - ell[1], -ell[2]], [0, 0, 1]], float)


# --------------------------------------------------------------------------------------------------- premises
def new_form(pr):
    k11, k12, k13, k22, k23, k33 = (pr.variable() for _ in range(6))
    return [[k11, k12, k13], [k12, k22, k23], [k13, k23, k33]]


def form_premises(pr, k, K, gamma, signs, *, k12, ell=None, lower=False):
    """``U`` nonincreasing on ``R̂`` (or ``R̂′`` with ``ell``) for the signs ``s`` of ``σ`` in ``signs``,
    ``K₃ⱼ ≥ 0``, ``γI − K`` copositive, and at ``t = 0`` ``K − I`` copositive."""
    kp, ki, kv = k
    if k12 == "zero":
        pr.nonneg(K[0][1], -K[0][1])
    else:  # the sign split: 2sK₁₂ ≥ 0, the rate form's (1,1) entry
        pr.nonneg(K[0][1] * k12)
    for s in signs:
        KB = mm(K, quad.slip_rate_entries(kp, ki, kv, float(s)))
        M = [[-(KB[i][j] + KB[j][i]) for j in range(3)] for i in range(3)]
        off = ki * s * K[0][0] + kv * K[0][2]
        band = [[0.0, off], [off, 2 * ki * s * K[0][2] + 2 * kv * K[2][2]]]
        if ell is None:
            pr.copositive(M, [0 if k12 == "zero" else 1, 1, 1], EPS)
            pr.copositive(band, [0, 1], EPS)
            continue
        l1, _, l3 = ell  # friction f ≥ ℓᵀy adds 2(Ky)₃ℓᵀy to −U̇
        pr.copositive([[M[i][j] + K[i][2] * ell[j] + ell[i] * K[j][2] for j in range(3)] for i in range(3)], [1, 1, 1], EPS)
        drag = [[2 * K[0][2] * l1, K[0][2] * l3 + K[2][2] * l1], [K[0][2] * l3 + K[2][2] * l1, 2 * K[2][2] * l3]]
        pr.copositive([[band[i][j] + drag[i][j] for j in range(2)] for i in range(2)], [1, 1], EPS)
    pr.nonneg(K[2][0] - EPS, K[2][1] - EPS, K[2][2] - EPS)
    pr.copositive([[(gamma if i == j else 0.0) - K[i][j] for j in range(3)] for i in range(3)], [1, 1, 1], EPS)
    if lower:
        pr.copositive([[K[i][j] - (1.0 if i == j else 0.0) for j in range(3)] for i in range(3)], [1, 1, 1], EPS)


def exit_premises(pr, K, G, s, ell=None):
    """``U ≥ |e^{At}w|²`` where a solution leaves: ``v = 0`` (``w = (s y₁, −y₂, 0)``), ``φ = f_c``
    (``w = (s y₁, 0, y₃)``) and, with ``ell``, ``f = ℓᵀy`` (``w = D_ℓ y``; 3×3, and its band face ``y₂ = 0``)."""
    margin = EPS * max(1.0, float(np.abs(G).max()))
    for D, idx in ((np.array([[s, 0], [0, -1], [0, 0]], float), (0, 1)), (np.array([[s, 0], [0, 0], [0, 1]], float), (0, 2))):
        M = D.T @ G @ D
        pr.copositive([[K[i][j] - M[a, b] for b, j in enumerate(idx)] for a, i in enumerate(idx)], [1, 1], margin)
    if ell is None:
        return
    D = d_ell(s, ell)
    M = D.T @ G @ D
    pr.copositive([[K[i][j] - M[i, j] for j in range(3)] for i in range(3)], [1, 1, 1], margin)
    Db = D[:, [0, 2]]
    M = Db.T @ G @ Db
    pr.copositive([[K[i][j] - M[a, b] for b, j in enumerate((0, 2))] for a, i in enumerate((0, 2))], [1, 1], margin)


def gamma_at(k, t, variant):
    """``(γ(t), {s: K})`` for one infinitesimal piece at time ``t`` (``s = 0``: the one form of (i))."""
    G, lower, pr = gram(k, t), t == 0, Program()
    gamma = pr.variable()
    if variant == "current":
        forms = {0: new_form(pr)}
        form_premises(pr, k, forms[0], gamma, (1, -1), k12="zero", lower=lower)
        for s in (1, -1):
            exit_premises(pr, forms[0], G, s)
    else:
        ell = ELL if variant == "drag" else None
        forms = {s: new_form(pr) for s in (1, -1)}
        for s, K in forms.items():
            form_premises(pr, k, K, gamma, (s,), k12=s, ell=ell, lower=lower)
            exit_premises(pr, K, G, s, ell)
        P, M = forms[1], forms[-1]  # U⁻ ≤ U⁺ on σ = 0
        pr.copositive([[P[i][j] - M[i][j] for j in (1, 2)] for i in (1, 2)], [1, 1], 0.0)
    _, x = pr.solve(gamma)
    if not x:
        return np.inf, None
    return Program.value(gamma, x), {s: np.array([[Program.value(e, x) for e in row] for row in K]) for s, K in forms.items()}


# ------------------------------------------------------------------------------------------------- time grids
def time_grid(k, quick):
    """``{0}``, a linear grid over ``max(4t_peak, two periods)`` and a geometric one out to ``40/|Re λ|_min``."""
    kp, ki, kv = (F(x) for x in k)
    params = Parameters(k_p=kp, k_i=ki, k_v=kv, f_c=1)
    rates = flow_bound.flow_rates(params)
    t_peak = flow_bound._peak(flow_bound._system(params), 40.0 / min(rates))
    omega = max(abs(np.linalg.eigvals(A_of(k)).imag))
    span = max(4 * t_peak, 4 * np.pi / omega if omega > 0 else 0.0)
    n_lin, n_log = (80, 30) if quick else (240, 60)
    ts = np.unique(np.concatenate([[0.0], np.linspace(0, span, n_lin), np.geomspace(1e-4 * t_peak, 40 / min(rates), n_log)]))
    return ts, t_peak, span


def grid_max(f, ts, *, top, rounds, points):
    """``max f`` over ``ts``, then ``rounds`` zooms (``points`` each) between the neighbours of the ``top`` best."""
    vals = {float(t): f(t) for t in ts}
    for _ in range(rounds):
        keys = sorted(vals)
        order = sorted(range(len(keys)), key=lambda i: -vals[keys[i]][0])[:top]
        for i in order:
            for t in np.linspace(keys[max(i - 1, 0)], keys[min(i + 1, len(keys) - 1)], points):
                if float(t) not in vals:
                    vals[float(t)] = f(float(t))
    t = max(vals, key=lambda t: vals[t][0])
    return t, vals[t], len(vals)


def c2_prime(k, ts, span, ell):
    """``max(κ_lin², sup_t λ_max(D_ℓᵀ G(t) D_ℓ))`` for ``s = ±1`` (zoomed around the grid's best)."""
    def f(t):
        G = gram(k, t)
        return (max([np.linalg.eigvalsh(G)[-1]] + [np.linalg.eigvalsh(d_ell(s, ell).T @ G @ d_ell(s, ell))[-1] for s in (1, -1)]),)
    dense = np.unique(np.concatenate([ts, np.linspace(0, span, 4000)]))
    return grid_max(f, dense, top=4, rounds=4, points=21)[1][0]


def closed_form_lower(k, ts):
    """``(k_i/k_v)²·max(1, max_t |e^{At}e₁|²)`` over the grid: a lower end of (i)'s floor, any number of pieces."""
    _, ki, kv = k
    e1 = max(float(np.sum(expm(A_of(k) * t)[:, 0] ** 2)) for t in ts)
    return (ki / kv) ** 2 * max(1.0, e1)


# ------------------------------------------------------------------------------------------------ Monte Carlo
def monte_carlo(k, t, forms, ell, n, rng, max_steps=100_000):
    """Exact slip flow in ``R̂ ∩ {v > 0}`` (``f_c = 1``); ``U = yᵀK_{sign σ}y``; exit at ``v = 0`` or ``f = ℓᵀy``."""
    A = A_of(k)
    omega = max(abs(np.linalg.eigvals(A).imag))
    dt = min(1e-3, (2 * np.pi / omega) / 2000 if omega > 0 else 1e-3)
    Ed, Et, L = expm(A * dt), expm(A * t), np.array(ell if ell else (0.0, 0.0, 0.0))
    e2 = np.array([0.0, 1.0, 0.0])

    def dz(p):
        return np.where(p > 1, p - 1, np.where(p < -1, p + 1, 0.0))

    def y_f_u(x):
        y = np.abs(np.stack([x[:, 0], dz(x[:, 1]), x[:, 2]], 1))
        K = np.where((x[:, 0] > 0)[:, None, None], forms[1], forms[-1])
        return y, 1 - x[:, 1] - y[:, 1], np.einsum("ni,nij,nj->n", y, K, y)

    lo, hi = (-3, 1) if ell else (-2, 2)
    x = 10 ** rng.uniform(lo, hi, (n, 1)) * rng.normal(size=(n, 3))
    x[:, 2] = np.abs(x[:, 2])
    y, f, u = y_f_u(x)
    keep = (x[:, 1] < 1) & (f > y @ L)
    x, u0, u = x[keep], u[keep], u[keep]
    h = (f - y @ L)[keep]
    alive = np.ones(len(x), bool)
    rise = gap = -np.inf
    for _ in range(max_steps):
        if not alive.any():
            break
        xa = x[alive]
        xn = (xa - e2) @ Ed.T + e2
        yn, fn, un = y_f_u(xn)
        hn = fn - yn @ L
        at_v, at_f = xn[:, 2] <= 0, hn <= 0
        out = at_v | at_f
        ia = np.flatnonzero(alive)
        if (~out).any():
            rise = max(rise, float(((un - u[ia]) / u0[ia])[~out].max()))
        if out.any():
            with np.errstate(divide="ignore", invalid="ignore"):
                fr_v = np.where(at_v, xa[:, 2] / (xa[:, 2] - xn[:, 2]), np.inf)
                fr_f = np.where(at_f, h[ia] / (h[ia] - hn), np.inf)
            fr = np.clip(np.minimum(fr_v, fr_f), 0, 1)[out]
            xe = xa[out] + fr[:, None] * (xn[out] - xa[out])
            v_exit = fr_v[out] <= fr_f[out]
            xe[v_exit, 2] = 0.0
            w = np.where(v_exit[:, None], np.stack([xe[:, 0], dz(xe[:, 1]), 0 * xe[:, 0]], 1), xe - e2)
            target = np.sum((w @ Et.T) ** 2, 1)
            gap = max(gap, float(((target - y_f_u(xe)[2]) / u0[ia[out]]).max()))
        x[ia], u[ia], h[ia] = xn, un, hn
        alive[ia[out]] = False
    return len(x), rise, gap, int(alive.sum())


# ------------------------------------------------------------------------------------------------------ main
def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="coarser time grids and fewer zoom rounds")
    parser.add_argument("--mc", type=int, default=0, metavar="N", help="Monte-Carlo check of (ii), (iii) with N states")
    args = parser.parse_args(argv)
    rounds, points = (2, 7) if args.quick else (4, 11)
    print(f"ℓ = {ELL}; γ(t) = least γ of one piece at the single time t; floor = max over the grid (zoomed).")
    print(f"{'':<4}{'template':<27} {'floor max γ(t)':>15} {'at t':>10} {'/κ_lin²':>8}  notes")
    start_all = time.perf_counter()
    for name, kq in gain_sets().items():
        start = time.perf_counter()
        k = tuple(float(q) for q in kq)
        ts, t_peak, span = time_grid(k, args.quick)
        kl2 = float(np.linalg.norm(expm(A_of(k) * t_peak), 2) ** 2)
        res, sdps = {}, 0
        for variant in VARIANTS:
            t, (g, forms), n = grid_max(lambda t, k=k, v=variant: gamma_at(k, t, v), ts, top=3, rounds=rounds, points=points)
            res[variant], sdps = (g, t, forms), sdps + n
        lower = closed_form_lower(k, ts)
        c2 = c2_prime(k, ts, span, ELL)
        print(f"{name}: k = ({', '.join(f'{x:.6g}' for x in k)}), κ_lin² = {kl2:.6g} (peak at t = {t_peak:.4g})")
        for variant in VARIANTS:
            g, t, _ = res[variant]
            note = ""
            if variant == "current":
                note = f"closed-form lower end {lower:.6g}, floor/it {g / lower:.4g}{' (binds)' if g <= 1.01 * lower else ''}"
            if variant == "drag":
                note = f"c₂′ {c2:.6g}, κ² = max(γ, c₂′) = {max(g, c2):.6g}"
            print(f"{'':<4}{TITLES[variant]:<27} {g:>15.6g} {t:>10.4g} {g / kl2:>8.4g}  {note}")
        print(f"{'':<4}({sdps} SDPs over {len(ts)} grid times and the zooms, {time.perf_counter() - start:.1f} s)", flush=True)
        if args.mc:
            for variant in ("signed", "drag"):
                g, t, forms = res[variant]
                ell = ELL if variant == "drag" else None
                cnt, rise, gap, left = monte_carlo(k, t, forms, ell, args.mc, np.random.default_rng(1))
                print(f"{'':<4}MC {TITLES[variant]:<24} at t={t:.4g}: {cnt} runs, max rise of U/U₀ {rise:.2e}, "
                      f"max exit (|e^{{At}}w|² − U)/U₀ {gap:.2e}, {left} not exited", flush=True)
    print(f"total {time.perf_counter() - start_all:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
