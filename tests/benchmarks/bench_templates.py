"""Benchmark: certify and verify time per certificate template, on Table I.

Run from the repository root with the package installed::

    python tests/benchmarks/bench_templates.py [--repeats N]

For each template and search it prints the first (cold: imports and problem
compilation) and the median warm time of ``certify`` (search, rounding and
exact verification) and of the exact verification alone, with the proven κ:

* ``paper`` (the constants of Lemmas 2 and 3), searched by the closed form and by the SDP;
* ``quadratic`` (beyond the paper: free ``P`` with ``P₁₂ = 0``, ``U = yᵀKy``), searched by an SDP;
* ``sup-flow`` (beyond the paper: ``V_∞`` on ``R``, time pieces of ``U`` on ``R̂``), searched by SDPs on adaptive
  pieces, verified in exact rationals and arb balls (its ``certify`` is timed once: about 20 s);
* ``auto`` (what ``certify`` does by default): every template (the paper's by the closed form), the smallest
  proved κ kept; its verify column is the chosen template's verifier (``--auto`` to include it: it runs the
  sup-flow search again).

The machine's load average is printed before and after (the timings are wall-clock).
"""

from __future__ import annotations

import argparse
import inspect
import os
import statistics
import time


def _time(fn, repeats: int):
    start = time.perf_counter()
    result = fn()
    cold = time.perf_counter() - start
    warm = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        warm.append(time.perf_counter() - start)
    return result, cold, statistics.median(warm) if warm else float("nan")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--auto", action="store_true", help="also time certify's default (every template)")
    args = parser.parse_args()

    from symbolic_friction import Parameters
    from symbolic_friction._certify.pipeline import certify
    from symbolic_friction._certify.quadratic import verify_quadratic
    from symbolic_friction._certify.quadratic_search import certify_quadratic
    from symbolic_friction._certify.sup_flow import verify_sup_flow
    from symbolic_friction._certify.sup_flow_search import certify_sup_flow
    from symbolic_friction._certify.verify import verify_certificate
    from symbolic_friction._certify.choose import certify_template

    print("load average (1, 5, 15 min) before: " + ", ".join(f"{x:.2f}" for x in os.getloadavg())
          + f"; {os.cpu_count()} cores; {args.repeats} warm repeats")

    searches = ["closed-form", "sdp"] if "search" in inspect.signature(certify).parameters else ["sdp"]
    print(f"{'case':5s} {'template':10s} {'search':12s} {'certify cold':>13s} {'certify warm':>13s} {'verify warm':>12s}  kappa")
    for case in "ab":
        params = Parameters.table_i(case)
        for search in searches:
            kwargs = {"search": search} if len(searches) > 1 else {}
            cert, cold, warm = _time(lambda: certify(params, **kwargs), args.repeats)
            _, _, verify = _time(lambda: verify_certificate(cert), args.repeats)
            print(f"({case})   {'paper':10s} {search:12s} {cold * 1e3:10.1f} ms {warm * 1e3:10.2f} ms {verify * 1e3:9.2f} ms  {cert.overshoot_bound}")
        cert, cold, warm = _time(lambda: certify_quadratic(params), args.repeats)
        _, _, verify = _time(lambda: verify_quadratic(cert), args.repeats)
        print(f"({case})   {'quadratic':10s} {'sdp':12s} {cold * 1e3:10.1f} ms {warm * 1e3:10.2f} ms {verify * 1e3:9.2f} ms  {cert.overshoot_bound}")
        cert, cold, _ = _time(lambda: certify_sup_flow(params), 0)
        _, _, verify = _time(lambda: verify_sup_flow(cert), args.repeats)
        print(f"({case})   {'sup-flow':10s} {'sdp':12s} {cold * 1e3:10.1f} ms {'-':>13s} {verify * 1e3:9.2f} ms  "
              f"{cert.overshoot_bound} ({len(cert.pieces)} pieces)")
        if not args.auto:
            continue
        choice, cold, warm = _time(lambda: certify_template(params), 0)
        _, _, verify = _time(lambda: choice.template.verify(choice.certificate, "<bench>"), args.repeats)
        print(f"({case})   {'auto':10s} {'→ ' + choice.template.name:12s} {cold * 1e3:10.1f} ms {warm * 1e3:10.2f} ms "
              f"{verify * 1e3:9.2f} ms  {choice.certificate.overshoot_bound}")
    print("load average (1, 5, 15 min) after: " + ", ".join(f"{x:.2f}" for x in os.getloadavg()))


if __name__ == "__main__":
    main()
