"""Benchmark: how tight and how fast the proven overshoot bound κ is, per template and for ``auto``.

Run from the repository root with the package installed::

    python tests/benchmarks/bench_tightness.py                  # Table I, the stiff sets, 50 random sets
    python tests/benchmarks/bench_tightness.py --random 0       # Table I and the stiff sets only
    python tests/benchmarks/bench_tightness.py --adversary all  # the worst overshoot on exact trajectories for every set
    python tests/benchmarks/bench_tightness.py --auto-only      # default `certify` only (no per-template columns): minutes

For every gain set it prints

* ``κ_lin ≥``: the proven lower end of ``κ_lin = sup_t ‖e^{At}‖₂`` (:func:`kappa_lin_lower`, arb), below which
  no certificate of any template can go;
* per search (the paper's closed form, the one-piece sup-flow certificate, the quadratic template's SDP, the
  sup-flow time pieces): the proven κ as a multiple of that lower end, and the seconds of search plus exact
  verification (``-`` with the reason where a search gives nothing; every search run, no target, 60 s budget);
* ``auto``: what default ``certify_template`` keeps (target ``κ ≤ 1.1·κ_lin``, budget 6 s), its κ/κ_lin
  and its seconds in this process;
* ``command``: the wall time of ``python -m symbolic_friction certify … --out <tmp>`` (imports included), the
  number the users see;
* ``worst``: with ``--adversary``, the worst overshoot ``sup_t |x(t)|_𝒜/|x(0)|_𝒜`` that the cross-check's
  adversary finds on exact trajectories (found, not proved; 2,000 trajectories on the horizon of
  :func:`worst_found`), and κ/worst.

The random sets are seeded: ``k_p``, ``k_i`` log-uniform over ``10⁻⁴..10⁴``, the Routh margin
``k_v·k_p/k_i`` log-uniform over ``1 + 10⁻³..1 + 10³`` and ``k_v`` then kept in ``10⁻⁴..10⁴`` (redrawn
otherwise), each rounded to 6 significant digits and read exactly.  A summary closes the table: the share
within ``2×`` and ``10×`` of the lower end, and the median and largest times.  Nothing is asserted.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import subprocess
import sys
import tempfile
import time
from fractions import Fraction as F

STIFF = {
    "k_p 1000, k_i 1, k_v 1": (F(1000), F(1), F(1)),
    "Routh 1+1e-6 (k_p 1, k_i 1e-3)": (F(1), F(1, 1000), F(1000001, 10**9)),
    "k_p 1e-3, k_i 1, k_v 1000.001": (F(1, 1000), F(1), F(1000001, 1000)),
    "Routh 1+1e-4 (k_p 100, k_i 1e4)": (F(100), F(10**4), F(10001, 100)),
    "weak integral (1000, 1e-3, 1000)": (F(1000), F(1, 1000), F(1000)),
}


def random_sets(count: int, seed: int) -> dict[str, tuple[F, F, F]]:
    import numpy as np

    rng = np.random.default_rng(seed)
    out: dict[str, tuple[F, F, F]] = {}
    while len(out) < count:
        k_p, k_i = (10.0 ** rng.uniform(-4, 4) for _ in range(2))
        margin = 1 + 10.0 ** rng.uniform(-3, 3)
        k_v = margin * k_i / k_p
        if not 1e-4 <= k_v <= 1e4:
            continue
        k_p, k_i = (F(f"{x:.6g}") for x in (k_p, k_i))
        k_v = F(f"{k_v:.6g}")
        if k_v * k_p <= k_i:
            continue
        out[f"random {len(out) + 1:02d}"] = (k_p, k_i, k_v)
    return out


def _fmt(q: F) -> str:
    return f"{float(q):.6g}"


def _command_seconds(k: tuple[F, F, F]) -> float:
    with tempfile.TemporaryDirectory() as out:
        argv = [sys.executable, "-m", "symbolic_friction", "certify", "--k-p", str(k[0]), "--k-i", str(k[1]),
                "--k-v", str(k[2]), "--f-c", "1", "--out", out, "-q"]
        start = time.perf_counter()
        subprocess.run(argv, check=True, capture_output=True)
        return time.perf_counter() - start


def measure(name: str, k: tuple[F, F, F], *, adversary: bool, command: bool, every_template: bool = True) -> dict:
    from symbolic_friction import Parameters
    from symbolic_friction._certify.choose import certify_template

    params = Parameters(k_p=k[0], k_i=k[1], k_v=k[2], f_c=1)
    row: dict = {"name": name, "k_p": str(k[0]), "k_i": str(k[1]), "k_v": str(k[2])}
    row["searches"] = {}
    if every_template:
        every = certify_template(params, kappa_tol=0, budget=60.0)
        row["searches"] = {a.title: {"kappa": None if a.certificate is None else a.certificate.overshoot_bound,
                                     "ratio": None if a.certificate is None or every.kappa_lin_lower is None
                                     else float(a.kappa / every.kappa_lin_lower),
                                     "seconds": a.seconds, "reason": a.reason} for a in every.attempts}
    start = time.perf_counter()
    auto = certify_template(params)
    lower = auto.kappa_lin_lower
    row["kappa_lin_lower"] = None if lower is None else float(lower)
    row["auto"] = {"search": auto.chosen.title, "kappa": auto.certificate.overshoot_bound,
                   "ratio": None if auto.ratio is None else float(auto.ratio), "seconds": time.perf_counter() - start}
    row["command_seconds"] = _command_seconds(k) if command else None
    if adversary:
        start = time.perf_counter()
        row["worst"], row["worst_horizon"] = worst_found(params, budget=2000)
        row["worst_seconds"] = time.perf_counter() - start
    return row


def worst_found(params, *, budget: int) -> tuple[float, float]:
    """The cross-check's adversary (differential evolution over directions and scales of ``x(0)``, exact event
    kernel, every trajectory checked), on a horizon of ``50·t* + 50/|Re λ|_max`` (``t*`` where ``‖e^{At}‖₂`` peaks)
    rather than the cross-check's ``40/|Re λ|_min``, which is ``10⁷`` time units and hours on the slow sets."""
    import numpy as np

    from symbolic_friction._certify import flow_bound
    from symbolic_friction._crosscheck._along import along
    from symbolic_friction._crosscheck._outcome import default_horizon, sample_times
    from symbolic_friction._crosscheck._overshoot import search_overshoot
    from symbolic_friction._model.coordinates import x_to_z
    from symbolic_friction._simulation.batch import simulate_batch

    rates = flow_bound.flow_rates(params)
    t_peak = flow_bound._peak(flow_bound._system(params), 40.0 / min(rates))
    horizon = min(default_horizon(params), 50 * t_peak + 50 / max(rates))
    t = sample_times(horizon, 101)

    def evaluate(x0, label):
        return along(simulate_batch(params, x_to_z(params, x0), float(t[-1]), t_eval=t)).overshoot

    found = search_overshoot(params, evaluate, budget=budget, seed=0, t_eval=t)
    ratio = found.ratio[np.isfinite(found.ratio)]
    return (float(ratio.max()) if ratio.size else math.nan), horizon


ORDER = ("paper", "sup-flow (one piece)", "quadratic", "sup-flow (pieces)")


def _rounded(x: float | None, digits: int, direction: str) -> str:
    """A lower end printed rounded down, a ratio to it rounded up: as printed, both stay true."""
    from symbolic_friction._certify.rounding import round_significant

    if x is None:
        return "nan"
    return f"{float(round_significant(F(x), digits, direction=direction)):.{digits}g}"


def render(row: dict) -> str:
    cells = [f"{row['name']:<34}", f"{_rounded(row['kappa_lin_lower'], 6, 'down'):>10}"]
    for title in ORDER:
        s = row["searches"].get(title)
        if s is None or s["ratio"] is None:
            cells.append(f"{'-':>9} {s['seconds'] if s else 0:>6.2f}s")
        else:
            cells.append(f"{_rounded(s['ratio'], 4, 'up'):>8}× {s['seconds']:>6.2f}s")
    a = row["auto"]
    cells.append(f"{a['search']:<22} {_rounded(a['ratio'], 4, 'up'):>8}× {a['seconds']:>5.2f}s")
    cells.append(f"{row['command_seconds']:>6.2f}s" if row["command_seconds"] is not None else "     -")
    if "worst" in row:
        kappa = float(a["kappa"])
        cells.append(f"{row['worst']:>9.6g} ({_rounded(kappa / row['worst'], 4, 'up')})")
    return " | ".join(cells)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--random", type=int, default=50, help="random admissible gain sets (default 50)")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--adversary", choices=("none", "named", "all"), default="named",
                        help="search the worst overshoot on exact trajectories: for none, Table I and the stiff sets "
                        "(default), or every set")
    parser.add_argument("--no-command", action="store_true", help="skip timing the certify command")
    parser.add_argument("--auto-only", action="store_true", help="only default certify (auto), not every template to its end")
    parser.add_argument("--json", default=None, help="also write every row to this file")
    args = parser.parse_args(argv)
    sets = {"Table I (a)": (F(3), F(4), F(32, 5)), "Table I (b)": (F(66, 100), F(8, 100), F(3, 2)), **STIFF,
            **random_sets(args.random, args.seed)}
    header = (f"{'gain set':<34} | {'κ_lin ≥':>10} | " + " | ".join(f"{t[:16]:>16}" for t in ORDER)
              + f" | {'auto: search, κ/κ_lin, s':<38} | command" + (" | worst (κ/worst)" if args.adversary != "none" else ""))
    print(header)
    print("-" * len(header))
    rows = []
    for name, k in sets.items():
        adversary = args.adversary == "all" or (args.adversary == "named" and not name.startswith("random"))
        row = measure(name, k, adversary=adversary, command=not args.no_command, every_template=not args.auto_only)
        rows.append(row)
        print(render(row), flush=True)
    ratios = [r["auto"]["ratio"] for r in rows if r["auto"]["ratio"] is not None]
    times = [r["command_seconds"] for r in rows if r["command_seconds"] is not None]
    auto_times = [r["auto"]["seconds"] for r in rows]
    print()
    print(f"auto: κ ≤ 2·κ_lin on {sum(x <= 2 for x in ratios)} of {len(ratios)}, ≤ 10·κ_lin on "
          f"{sum(x <= 10 for x in ratios)}; largest κ/κ_lin {_rounded(max(ratios), 4, 'up')}")
    print(f"auto in-process: median {statistics.median(auto_times):.2f} s, max {max(auto_times):.2f} s")
    if times:
        print(f"certify command (imports included): median {statistics.median(times):.2f} s, max {max(times):.2f} s")
    for r in rows:
        if "worst" in r and r["auto"]["ratio"] is not None and r["auto"]["ratio"] > 2 and math.isfinite(r["worst"]):
            print(f"{r['name']}: κ/κ_lin ≤ {_rounded(r['auto']['ratio'], 4, 'up')} > 2; worst found {r['worst']:.6g} "
                  f"= {r['worst'] / r['kappa_lin_lower']:.4g}·κ_lin; κ/worst {_rounded(float(r['auto']['kappa']) / r['worst'], 4, 'up')}")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(rows, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
