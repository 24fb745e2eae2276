"""``symbolic-friction certify``: find and exactly verify proof certificates.

Without gains it regenerates ``proofs/`` for Table I's cases (a) and (b) in
both modes; with ``--k-p --k-i --k-v --f-c`` (normalised) or the physical
``--m --k-p-bar --k-i-bar --k-d-bar [--alpha-v] --f-c-bar`` it certifies one
gain set.  Nothing is written unless the exact verifier proves it.
"""

from __future__ import annotations

import argparse
import json
import textwrap

from .._infra.errors import ParameterError

HELP = "find, exactly verify and write proof certificates (Lemma 2, Lemma 3, Proposition 1)"

_NORMALISED = ("k_p", "k_i", "k_v", "f_c")
_HELP = {
    "k_p": "normalised proportional gain k_p = k̄_p/m",
    "k_i": "normalised integral gain k_i = k̄_i/m",
    "k_v": "normalised velocity gain k_v = (k̄_d + α_v)/m",
    "f_c": "normalised Coulomb level f_c = f̄_c/m",
    "m": "mass m > 0",
    "k_p_bar": "physical proportional gain k̄_p",
    "k_i_bar": "physical integral gain k̄_i",
    "k_d_bar": "physical derivative gain k̄_d",
    "f_c_bar": "Coulomb friction force f̄_c",
    "alpha_v": "viscous friction coefficient α_v ≥ 0 (default 0)",
}
_EPILOG = """examples:
  symbolic-friction certify                      # regenerate proofs/ (Table I, cases a and b, both modes)
  symbolic-friction certify --k-p 3 --k-i 4 --k-v 6.4 --f-c 1 --out my_proofs
  symbolic-friction certify --m 2 --k-p-bar 6 --k-i-bar 8 --k-d-bar 12.3 --alpha-v 0.5 --f-c-bar 2 --mode feasible
"""
_PHYSICAL = ("m", "k_p_bar", "k_i_bar", "k_d_bar", "f_c_bar")
_PHYSICAL_OPTIONAL = ("alpha_v",)


def _flag(name: str) -> str:
    return "--" + name.replace("_", "-")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Gains (normalised or physical), ``--mode``, ``--margin``, ``--out``, ``--name``."""
    parser.description = textwrap.fill(
        f"{HELP}. Without gains, regenerate proofs/ for Table I's cases (a) and (b) in both modes; "
        "with gains, certify that one gain set. Nothing is written unless the exact verifier proves it."
    )
    parser.epilog = _EPILOG
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.add_argument(
        "--mode",
        choices=("feasible", "tightest"),
        default=None,
        help="search mode: 'tightest' minimises the overshoot bound κ, 'feasible' keeps a wider margin "
        "(default: both for Table I, tightest for given gains)",
    )
    parser.add_argument(
        "--margin",
        default=None,
        metavar="Q",
        help="relative margin on the strict inequalities, e.g. 1/1000 (default 1/1000000 tightest, 1/100 feasible)",
    )
    parser.add_argument("--out", default="proofs", metavar="DIR", help="output directory (default: proofs)")
    parser.add_argument(
        "--name",
        default=None,
        metavar="STEM",
        help="file stem for one gain set, a plain name written inside --out (default: certificate_<hash of the gains>_<mode>)",
    )
    parser.add_argument("--label", default=None, metavar="TEXT",
                        help="free text kept in the certificate's provenance (e.g. 'slow axis, 2 kg payload')")
    parser.add_argument("--json", action="store_true",
                        help="print one JSON object per certificate written (path, gains, mode, kappa) instead of text")
    add_gain_arguments(parser)


def add_gain_arguments(parser: argparse.ArgumentParser) -> None:
    """The gain set, normalised (``--k-p …``) or physical (``--m --k-p-bar …``); read by :func:`_gains`."""
    normalised = parser.add_argument_group("normalised gains (exact: '6.4' is 32/5, '32/5' works too)")
    for name in _NORMALISED:
        normalised.add_argument(_flag(name), dest=name, default=None, metavar="Q", help=_HELP[name])
    physical = parser.add_argument_group("physical parameters (paper §II-A: k_p = k̄_p/m, k_v = (k̄_d + α_v)/m, …)")
    for name in _PHYSICAL + _PHYSICAL_OPTIONAL:
        physical.add_argument(_flag(name), dest=name, default=None, metavar="Q", help=_HELP[name])


def _gains(args: argparse.Namespace):  # -> Parameters | None
    from .._model.parameters import Parameters

    given_norm = [n for n in _NORMALISED if getattr(args, n) is not None]
    given_phys = [n for n in _PHYSICAL + _PHYSICAL_OPTIONAL if getattr(args, n) is not None]
    if given_norm and given_phys:
        raise ParameterError(
            "give either normalised gains (--k-p --k-i --k-v --f-c) or physical parameters "
            f"(--m --k-p-bar --k-i-bar --k-d-bar --f-c-bar), not both; got {', '.join(map(_flag, given_norm + given_phys))}"
        )
    if given_norm:
        missing = [n for n in _NORMALISED if getattr(args, n) is None]
        if missing:
            raise ParameterError(f"certify needs all of --k-p --k-i --k-v --f-c; missing {' '.join(map(_flag, missing))}")
        return Parameters(**{n: getattr(args, n) for n in _NORMALISED})
    if given_phys:
        missing = [n for n in _PHYSICAL if getattr(args, n) is None]
        if missing:
            raise ParameterError(
                "certify needs all of --m --k-p-bar --k-i-bar --k-d-bar --f-c-bar (and optionally --alpha-v); "
                f"missing {' '.join(map(_flag, missing))}"
            )
        kwargs = {n: getattr(args, n) for n in _PHYSICAL}
        if args.alpha_v is not None:
            kwargs["alpha_v"] = args.alpha_v
        return Parameters.from_physical(**kwargs)
    return None


def _physical(args: argparse.Namespace) -> dict | None:
    """The physical parameters as exact rationals (kept in the certificate), or None for normalised gains."""
    from .._infra.rational import to_rational

    if all(getattr(args, n) is None for n in _PHYSICAL):
        return None
    values = {n: to_rational(getattr(args, n), name=_flag(n)) for n in _PHYSICAL}
    values["alpha_v"] = to_rational(args.alpha_v if args.alpha_v is not None else 0, name="--alpha-v")
    return {n: values[n] for n in ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar")}


def run(args: argparse.Namespace) -> int:
    """Certify, verify, write; print one line per certificate written."""
    from pathlib import Path

    from .._certify import MODES, certify, default_stem, write_certificate
    from .._certify.pipeline import TABLE_I_LABELS, table_i_stem
    from .._certify.search import check_margin
    from .._infra.io import check_stem, ensure_directory
    from .._model.parameters import Parameters
    from .._infra.rational import format_rational
    from .._infra.output import emit

    params = _gains(args)
    physical = _physical(args) if params is not None else None
    out = Path(args.out)
    jobs = []  # (params, mode, label, json path)
    if params is None:
        if args.name is not None:
            raise ParameterError("--name applies to one gain set; Table I files are named case_<a|b>_<mode>")
        if args.label is not None:
            raise ParameterError("--label applies to one gain set; Table I's certificates are labelled by their case")
        modes = MODES if args.mode is None else (args.mode,)
        for case, label in TABLE_I_LABELS.items():
            for mode in modes:
                jobs.append((Parameters.table_i(case), mode, label, out / f"{table_i_stem(case, mode)}.json"))
    else:
        mode = args.mode or "tightest"
        stem = check_stem(args.name) if args.name is not None else default_stem(params, mode)
        label = args.label or ""
        if len(label) > 1000 or not label.isprintable():
            raise ParameterError(f"--label must be at most 1000 printable characters; got {len(label)} characters")
        jobs.append((params, mode, label, out / f"{stem}.json"))
    for _, mode, _, _ in jobs:  # validate before writing anything
        check_margin(args.margin, mode)
    ensure_directory(out)  # an unusable --out fails now, not after the search
    for params, mode, label, path in jobs:
        cert = certify(params, mode=mode, margin=args.margin, label=label, physical=physical)
        json_path, md_path = write_certificate(cert, path)
        if args.json:
            emit(json.dumps({
                "file": str(json_path), "report": str(md_path), "mode": mode, "label": label,
                "parameters": {k: format_rational(v) for k, v in cert.parameters.items()},
                "physical": None if cert.physical is None else {k: format_rational(v) for k, v in cert.physical.items()},
                "overshoot_bound": cert.overshoot_bound, "proved": True,
            }, ensure_ascii=False), level=0)
        else:
            # the normalised gains that were certified (physical values, when given, follow in parentheses)
            emit(f"wrote {json_path} and {md_path.name} ({mode}) for {cert.gains_text()}: "
                 f"|x(t)|_A <= {cert.overshoot_bound}·|x(0)|_A", level=0)
    return 0
