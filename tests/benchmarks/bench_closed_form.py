"""Benchmark: the closed-form certificate per gain set (build + exact verification) against the SDP's ``certify``.

Run from the repository root with the package installed::

    python tests/benchmarks/bench_closed_form.py            # 2,000 gain sets
    python tests/benchmarks/bench_closed_form.py --quick    # 200
    python tests/benchmarks/bench_closed_form.py --repeats 5

It prints, warm (after one certificate of each kind), the median and mean time per gain set of

1. building the closed-form certificate (:func:`closed_form_certificate`);
2. verifying it exactly (:func:`verify_certificate`, the only judge);
3. both together, against the goal of 0.5 ms;
4. ``certify(search="sdp")`` (search + rounding + verification) on a subset, for comparison;

and, for a box certificate of Table I case (a) ±10 %, certify (1 and 16 pieces) and verify.
Each of 1–3 is timed ``--repeats`` times over all gain sets and the pass with the smallest median is
printed (the machine's other load only ever adds time), with its mean and the load average.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_certify import sweep_gains  # noqa: E402  (the same 1e-6..1e6 gain sets as the SDP benchmark)


def _times(fn, items, repeats: int = 1) -> list[float]:
    """Per-item times of the pass (of ``repeats``) with the smallest median."""
    passes = []
    for _ in range(repeats):
        out = []
        for item in items:
            start = time.perf_counter()
            fn(item)
            out.append(time.perf_counter() - start)
        passes.append(out)
    return min(passes, key=statistics.median)


def _line(what: str, times: list[float]) -> str:
    return (f"{what:<44} median {1e3 * statistics.median(times):7.3f} ms   mean {1e3 * statistics.fmean(times):7.3f} ms"
            f"   ({len(times)} gain sets)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--repeats", type=int, default=3, help="passes per timing; the best median is printed")
    args = parser.parse_args()
    n = 200 if args.quick else 2000

    from symbolic_friction import Parameters
    from symbolic_friction._certify import certify, verify_certificate
    from symbolic_friction._certify.box import certify_box, verify_box
    from symbolic_friction._certify.closed_form import DEFAULT_MU, closed_form_certificate

    gains = [Parameters.table_i("a"), Parameters.table_i("b")] + sweep_gains(n - 2)
    build = lambda p: closed_form_certificate(p, mode="tightest", margin=DEFAULT_MU)  # noqa: E731
    verify_certificate(build(gains[0]))  # warm
    certs = [build(p) for p in gains]
    assert all(verify_certificate(c).proved for c in certs), "a closed-form certificate did not verify"
    t_build = _times(build, gains, args.repeats)
    t_verify = _times(verify_certificate, certs, args.repeats)
    t_both = _times(lambda p: verify_certificate(build(p)), gains, args.repeats)
    print(_line("closed form: build", t_build))
    print(_line("closed form: exact verification", t_verify))
    print(_line("closed form: build + exact verification", t_both)
          + f"   goal ≤ 0.5 ms: {'met' if statistics.median(t_both) <= 5e-4 else 'NOT met'}")
    print(f"(best of {args.repeats} passes each; load average {os.getloadavg()[0]:.2f})")

    sdp = gains[: max(20, n // 20)]
    certify(sdp[0], search="sdp")  # warm: compiles the cvxpy problem
    t_sdp = _times(lambda p: certify(p, search="sdp"), sdp)
    print(_line("SDP: certify(search='sdp')", t_sdp)
          + f"   ({statistics.median(t_sdp) / statistics.median(t_both):.0f}× the closed form)")

    F = Fraction
    box = {"k_p": (F(27, 10), F(33, 10)), "k_i": (F(18, 5), F(22, 5)), "k_v": (F(144, 25), F(176, 25)), "f_c": (F(1), F(1))}
    for pieces in (1, 16):
        start = time.perf_counter()
        cert = certify_box(box, pieces=pieces)
        made = time.perf_counter() - start
        start = time.perf_counter()
        assert verify_box(cert).proved
        print(f"box case (a) ±10 %, {pieces:>2} piece(s): κ ≤ {cert.overshoot_bound}; certify {1e3 * made:7.1f} ms "
              f"(includes one verification), verify {1e3 * (time.perf_counter() - start):7.1f} ms")


if __name__ == "__main__":
    main()
