"""``symbolic-friction map``: Proposition 1's κ over a grid or a random sample of gains, with its heat map.

Each axis is ``VALUE`` (fixed), ``LO:HI:N[:log]`` (a grid of N points) or,
with ``--sample N``, ``LO:HI[:log]`` (drawn).  The chunks run in this
process, on ``--workers`` processes, or on a dask.distributed cluster
(``--scheduler ADDRESS``, ``pip install "symbolic-friction[dask]"``).  This
module imports only the standard library at top level.
"""

from __future__ import annotations

import argparse
import json
import re
import textwrap

HELP = "map Proposition 1's overshoot bound κ (closed-form certificates, exactly verified) over a grid or sample of gains"

_NORMALISED = ("k_p", "k_i", "k_v", "f_c", "f_s")
_PHYSICAL = ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar", "f_s_bar")
_HELP = {
    "k_p": "normalised proportional gain", "k_i": "normalised integral gain",
    "k_v": "normalised velocity gain", "f_c": "normalised Coulomb level (default 1)",
    "f_s": "normalised static level ≥ f_c: adds whether a hunting cycle is proved",
    "m": "mass", "k_p_bar": "physical proportional gain", "k_i_bar": "physical integral gain",
    "k_d_bar": "physical derivative gain", "alpha_v": "viscous coefficient (default 0)",
    "f_c_bar": "Coulomb force", "f_s_bar": "static force ≥ f_c_bar: adds the hunting columns",
}
_EPILOG = """examples:
  symbolic-friction map --k-p 0.1:100:200:log --k-i 0.1:100:200:log --k-v 6.4 --out kappa_map
  symbolic-friction map --k-p 1:10:log --k-i 1:10:log --k-v 1:10 --sample 100000 --seed 1 --workers 2
  symbolic-friction map --m 2 --k-p-bar 2:20:40 --k-i-bar 1:30:40 --k-d-bar 12.3 --f-c-bar 2 --sdp
  symbolic-friction map --k-p 0.5:5:20 --k-i 4 --k-v 6.4 --f-s 1.2 --adversary 64 --scheduler tcp://host:8786

load the result:  pandas.read_csv("kappa_map/map.csv")   or   xarray.open_dataset("kappa_map/map.nc")
"""


# a dask scheduler address: protocol://host[:port], checked before any connection is tried
_ADDRESS = re.compile(r"(tcp|tls|inproc|ucx|ws|wss)://[A-Za-z0-9_.\-\[\]:/]{1,280}")


def _flag(name: str) -> str:
    return "--" + name.replace("_", "-")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Axes, grid or sample, optional columns, where to run, outputs."""
    parser.description = textwrap.fill(
        f"{HELP}. Writes DIR/map.csv and DIR/map.nc from chunks under DIR/chunks; a killed run is resumed by "
        "running the same command again."
    )
    parser.epilog = _EPILOG
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    normalised = parser.add_argument_group("normalised axes (VALUE, LO:HI:N[:log], or LO:HI[:log] with --sample; exact)")
    for name in _NORMALISED:
        normalised.add_argument(_flag(name), dest=name, default=None, metavar="AXIS", help=_HELP[name])
    physical = parser.add_argument_group("physical axes (paper §II-A: k_p = k̄_p/m, k_v = (k̄_d + α_v)/m, …)")
    for name in _PHYSICAL:
        physical.add_argument(_flag(name), dest=name, default=None, metavar="AXIS", help=_HELP[name])
    from .._infra.options import count_option, real_option

    MAX_TIGHT = 600.0  # = _studies.gainmap.MAX_TIGHT (the spec checks it again); not imported: --help stays light

    # bounds stated before any work (the spec checks them again for library callers)
    parser.add_argument("--sample", type=count_option("--sample", low=0, high=10**7), default=0, metavar="N",
                        help="N random points instead of a grid (at most 10⁷)")
    parser.add_argument("--seed", type=count_option("--seed", low=0, high=2**32 - 1), default=0,
                        help="seed of the sample and of the adversary (default 0)")
    parser.add_argument("--sdp", action="store_true", help="also the SDP's tightest κ (about 3 ms a point)")
    parser.add_argument("--tight", type=real_option("--tight", high=MAX_TIGHT, low=0, low_open=False), default=0.0,
                        metavar="SECONDS",
                        help="also the tight bound of default certify per point within SECONDS (closed form, then the "
                        "sup-flow and quadratic templates; columns kappa_tight, kappa_lin (proven lower end), tight_ratio)")
    parser.add_argument("--adversary", type=count_option("--adversary", low=0, high=100_000), default=0,
                        metavar="BUDGET",
                        help="trajectories per point for the worst overshoot found, and tightness = worst/κ (default 0: off)")
    parser.add_argument("--chunk", type=count_option("--chunk", low=1, high=10**6), default=1000, metavar="N",
                        help="points per chunk written (default 1000)")
    parser.add_argument("--out", default="gain_map", metavar="DIR", help="output directory (default gain_map)")
    parser.add_argument("--format", nargs="+", choices=("csv", "netcdf"), default=["csv", "netcdf"],
                        help="dataset files (default both)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--workers", type=count_option("--workers", low=1, high=256), default=1, metavar="N",
                       help="processes (default 1: this process)")
    where.add_argument("--scheduler", default=None, metavar="ADDRESS",
                       help="run on a dask.distributed scheduler, e.g. tcp://host:8786 (needs the [dask] extra)")
    parser.add_argument("--plot", default=None, metavar="X,Y", help="heat-map axes (default: the first two ranged axes)")
    parser.add_argument("--no-plot", action="store_true", help="do not draw the heat map DIR/kappa.png")
    parser.add_argument("--json", action="store_true", help="print the summary as one JSON object")


def run(args: argparse.Namespace) -> int:
    """Build the spec, run it, draw the heat map, print a summary."""
    from pathlib import Path

    from .._infra.errors import ParameterError
    from .._infra.output import emit
    from .._studies.gainmap import map_spec
    from .._studies.gainmap_run import read_columns, run_map

    values = {n: getattr(args, n) for n in _NORMALISED + _PHYSICAL if getattr(args, n) is not None}
    if not values:
        raise ParameterError("give the axes: normalised --k-p --k-i --k-v (and --f-c, --f-s) or physical --m --k-p-bar …")
    spec = map_spec(values, sample=args.sample, seed=args.seed, sdp=args.sdp, adversary=args.adversary, chunk=args.chunk,
                    tight=args.tight)
    axes = None
    if not args.no_plot:
        from .._studies.gainmap_plot import default_axes

        axes = tuple(p.strip() for p in args.plot.split(",")) if args.plot is not None else default_axes(spec)
        if len(axes) != 2 or any(a not in {x.name for x in spec.ranged} for a in axes) or axes[0] == axes[1]:
            raise ParameterError(f"--plot needs two different ranged axes X,Y of {', '.join(a.name for a in spec.ranged)}; got {args.plot!r}")
    if args.scheduler is not None and not _ADDRESS.fullmatch(args.scheduler):
        shown = args.scheduler if len(args.scheduler) <= 60 else args.scheduler[:60] + "…"
        raise ParameterError(f"--scheduler must be an address such as tcp://host:8786 (at most 300 characters); got {shown!r}")
    out = Path(args.out)
    executor, close = _executor(args)
    try:
        result = run_map(spec, args.out, executor=executor, formats=args.format)  # the text: an empty --out is refused
    finally:
        close()
    files = [str(f) for f in result.files]
    if axes is not None:
        from .._studies.gainmap_plot import plot_map

        files.append(str(plot_map(spec, read_columns(out, spec), out / "kappa.png", x=axes[0], y=axes[1])))
    summary = {
        "directory": str(out), "points": spec.points, "chunks": spec.chunks, "computed": result.computed,
        "skipped": result.skipped, "seconds": round(result.seconds, 3), "points_per_second": round(result.rate, 1) if result.computed else None,
        "counts": result.counts, "kappa_min": result.kappa_min, "kappa_max": result.kappa_max, "files": files,
    }
    if args.json:
        import math

        for key in ("kappa_min", "kappa_max"):
            summary[key] = None if math.isnan(summary[key]) else summary[key]
        emit(json.dumps(summary, ensure_ascii=False), level=0)
        return 1 if result.counts["not_proved"] else 0
    c = result.counts
    emit(f"{spec.points} points ({result.computed} chunks computed, {result.skipped} already done) in "
         f"{result.seconds:.1f} s: {c['proved']} proved, {c['not_proved']} not proved, "
         f"{c['outside_assumption_1']} outside Assumption 1", level=0)
    if c["proved"]:
        emit(f"κ from {result.kappa_min:.6g} to {result.kappa_max:.6g}", level=0)
    emit("wrote " + ", ".join(files), level=0)
    if c["not_proved"]:
        # inside Assumption 1 the closed form should always verify: a refusal is a finding, not bad input
        emit(f"{c['not_proved']} points inside Assumption 1 were not proved (status not_proved in {out}/map.csv)", level=0)
        return 1
    return 0


def _executor(args: argparse.Namespace):
    """``(executor, close)`` for ``--workers`` / ``--scheduler``."""
    if args.scheduler is not None:
        from .._infra.errors import UsageError

        try:
            from dask.distributed import Client
        except ImportError:
            raise UsageError('--scheduler needs dask.distributed: pip install "symbolic-friction[dask]"') from None
        try:
            client = Client(args.scheduler, timeout=30)
        except (OSError, TimeoutError, ValueError) as exc:
            raise UsageError(f"cannot reach the dask scheduler {args.scheduler}: {exc}") from None
        return client.get_executor(), client.close
    if args.workers > 1:
        from concurrent.futures import ProcessPoolExecutor

        pool = ProcessPoolExecutor(args.workers)
        return pool, lambda: pool.shutdown(cancel_futures=True)
    return None, lambda: None
