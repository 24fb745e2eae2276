"""``symbolic-friction certify``: find and exactly verify proof certificates.

Without gains it regenerates ``proofs/`` for Table I's cases (a) and (b): the
paper's template in both modes and the quadratic template (``proofs/quadratic/``);
with ``--k-p --k-i --k-v --f-c`` (normalised) or the physical
``--m --k-p-bar --k-i-bar --k-d-bar [--alpha-v] --f-c-bar`` it certifies one
gain set with ``--template`` (default ``auto``: every template ``check`` covers,
keeping the smallest proved κ; :func:`~symbolic_friction._certify.choose.certify_template`).
Nothing is written unless the exact verifier proves it.
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
  symbolic-friction certify                      # regenerate proofs/ (Table I, cases a and b, every template)
  symbolic-friction certify --k-p 3 --k-i 4 --k-v 6.4 --f-c 1 --out my_proofs              # the tightest template
  symbolic-friction certify --k-p 1000 --k-i 0.001 --k-v 1000 --f-c 1 --kappa-tol 0 --budget 30   # tightest within 30 s
  symbolic-friction certify --k-p 3 --k-i 4 --k-v 6.4 --f-c 1 --template paper --search sdp
  symbolic-friction certify --k-p 2.7:3.3 --k-i 3.6:4.4 --k-v 5.76:7.04 --f-c 1 --pieces 16   # a box of gains
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
        "--template",
        choices=("auto", "paper", "quadratic", "sup-flow"),
        default="auto",
        help="which proof: 'paper' (Lemmas 2 and 3, Table I's constants), 'quadratic' (a free P and U = y'Ky, "
        "beyond the paper; an SDP), 'sup-flow' (the peak of the friction-free flow bounded by one Lyapunov matrix, "
        "then by time pieces of U, beyond the paper; SDPs), or 'auto' (default): the closed form, then the others "
        "cheapest first until κ is within --kappa-tol of κ_lin or --budget is spent, keeping the smallest proved κ",
    )
    parser.add_argument(
        "--mode",
        choices=("feasible", "tightest"),
        default=None,
        help="paper's template: 'tightest' minimises the overshoot bound κ, 'feasible' keeps a wider margin "
        "(default: both for Table I, tightest for given gains)",
    )
    parser.add_argument(
        "--search",
        choices=("closed-form", "sdp"),
        default=None,
        help="paper's template only: how its constants are found: 'closed-form' (default) writes them down for any "
        "gains without a solver; 'sdp' solves the semidefinite program (cvxpy + Clarabel); the exact verifier decides",
    )
    parser.add_argument(
        "--margin",
        default=None,
        metavar="Q",
        help="paper's template: relative margin on the strict inequalities, e.g. 1/1000 "
        "(default 1/1000000 tightest, 1/100 feasible)",
    )
    parser.add_argument("--pieces", type=int, default=None, metavar="N",
                        help="for a box (intervals LO:HI): cover it by N pieces, κ the largest over them (default 1)")
    parser.add_argument("--kappa-tol", default=None, metavar="Q",
                        help="one gain set: stop searching once κ ≤ (1 + Q)·κ_lin, the proven lower end of the friction-free "
                        "limit no template can beat (default 1/10; 0 tries every search within the budget); a box: halve "
                        "pieces until κ is within Q (relative) of the largest pointwise κ at their corners")
    parser.add_argument("--budget", default=None, metavar="SECONDS",
                        help="one gain set: start no further search after this many seconds and keep the smallest κ "
                        "proved so far (default 5; the cheap searches take well under a second)")
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


def _is_box(args: argparse.Namespace) -> bool:
    """Whether any gain is given as an interval ``LO:HI``."""
    return any(isinstance(getattr(args, n, None), str) and ":" in getattr(args, n) for n in _NORMALISED + _PHYSICAL + _PHYSICAL_OPTIONAL)


def _intervals(args: argparse.Namespace) -> tuple[dict | None, dict | None]:
    """``(box, physical)`` of exact intervals (a plain number is the interval [q, q]); one of them is None."""
    from .._infra.rational import to_rational

    def interval(name: str, text: str):
        lo, sep, hi = str(text).partition(":")
        lo_q = to_rational(lo, name=_flag(name))
        hi_q = to_rational(hi, name=_flag(name)) if sep else lo_q
        if not lo_q <= hi_q:
            raise ParameterError(f"{_flag(name)} {text}: an interval LO:HI needs LO ≤ HI")
        return lo_q, hi_q

    params = _gains(args, probe=True)
    del params
    if any(getattr(args, n) is not None for n in _NORMALISED):
        return {n: interval(n, getattr(args, n)) for n in _NORMALISED}, None
    physical = {n: interval(n, getattr(args, n)) for n in _PHYSICAL}
    physical["alpha_v"] = interval("alpha_v", args.alpha_v if args.alpha_v is not None else "0")
    return None, {n: physical[n] for n in ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar")}


def _gains(args: argparse.Namespace, *, probe: bool = False):  # -> Parameters | None
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
        if probe:
            return None
        return Parameters(**{n: getattr(args, n) for n in _NORMALISED})
    if given_phys:
        missing = [n for n in _PHYSICAL if getattr(args, n) is None]
        if missing:
            raise ParameterError(
                "certify needs all of --m --k-p-bar --k-i-bar --k-d-bar --f-c-bar (and optionally --alpha-v); "
                f"missing {' '.join(map(_flag, missing))}"
            )
        if probe:
            return None
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
    """Certify (with the template asked for, or the tightest), verify, write; print one line per certificate written."""
    from pathlib import Path

    from .._certify import MODES, default_stem
    from .._certify.choose import certify_template, paper_only_options, refuse_paper_only
    from .._certify.pipeline import BEYOND_TABLE_I_FILES, TABLE_I_LABELS, table_i_stem
    from .._certify.search import check_margin
    from .._infra.io import check_stem, ensure_directory
    from .._model.parameters import Parameters

    if _is_box(args):
        return _run_box(args)
    if args.pieces is not None:
        raise ParameterError("--pieces applies to a box: give at least one gain as an interval LO:HI")
    params = _gains(args)
    search_options = _search_options(args)
    physical = _physical(args) if params is not None else None
    paper_only = paper_only_options(mode=args.mode, margin=args.margin, search=args.search, physical=physical)
    refuse_paper_only(args.template, paper_only)  # before any work
    out = Path(args.out)
    jobs = []  # (params, template, mode, label, json path)
    if params is None:
        if args.name is not None:
            raise ParameterError("--name applies to one gain set; Table I files are named case_<a|b>_<mode>")
        if args.label is not None:
            raise ParameterError("--label applies to one gain set; Table I's certificates are labelled by their case")
        if search_options:
            raise ParameterError("--kappa-tol and --budget apply to one gain set; Table I's files are regenerated in full")
        search_options = {"kappa_tol": 0, "budget": None}  # every search to its end: the committed files, reproducibly
        modes = MODES if args.mode is None else (args.mode,)
        for case, label in TABLE_I_LABELS.items():
            if args.template in ("auto", "paper"):
                for mode in modes:
                    jobs.append((Parameters.table_i(case), "paper", mode, label, out / f"{table_i_stem(case, mode)}.json"))
        for template, directory in (("quadratic", "quadratic"), ("sup-flow", "sup_flow")):
            if args.template == template or (args.template == "auto" and not paper_only):
                # the Table I files of the templates beyond the paper, as committed under proofs/<directory>/
                for name in BEYOND_TABLE_I_FILES:
                    case = Path(name).stem[-1]
                    jobs.append((Parameters.table_i(case), template, None, TABLE_I_LABELS[case], out / directory / name))
    else:
        label = args.label or ""
        if len(label) > 1000 or not label.isprintable():
            raise ParameterError(f"--label must be at most 1000 printable characters; got {len(label)} characters")
        stem = check_stem(args.name) if args.name is not None else None
        jobs.append((params, args.template, args.mode, label, stem))
    for _, template, mode, _, _ in jobs:  # validate before writing anything
        if template not in ("quadratic", "sup-flow") and args.margin is not None:
            check_margin(args.margin, mode or "tightest")
    ensure_directory(args.out)  # an unusable --out (or an empty one) fails now, not after the search
    for params_j, template, mode, label, path in jobs:
        choice = certify_template(params_j, template=template, mode=mode, margin=args.margin, search=args.search,
                                  label=label, physical=physical, **search_options)
        if not isinstance(path, Path):  # one gain set: the file is named after the template chosen
            kind = (mode or "tightest") if choice.template.name == "paper" else choice.template.name
            path = out / f"{path or default_stem(params_j, kind)}.json"
        if path.parent != out:
            ensure_directory(path.parent)
        written = choice.chosen.write(path)
        _render(args, choice, written, mode, one=params is not None)
    return 0


def _search_options(args: argparse.Namespace) -> dict:
    """``--kappa-tol`` and ``--budget`` for one gain set, exact and in range (the library's defaults when absent)."""
    from .._infra.rational import to_rational

    options: dict = {}
    if args.kappa_tol is not None:
        from .._certify.choose import MAX_KAPPA_TOL

        options["kappa_tol"] = to_rational(args.kappa_tol, name="--kappa-tol")
        if not 0 <= options["kappa_tol"] <= MAX_KAPPA_TOL:
            raise ParameterError(f"--kappa-tol must be in [0, {MAX_KAPPA_TOL}] for one gain set; got {args.kappa_tol}")
    if args.budget is not None:
        seconds = to_rational(args.budget, name="--budget")
        if not 0 < seconds <= 86_400:
            raise ParameterError(f"--budget must be a number of seconds in (0, 86400]; got {args.budget}")
        options["budget"] = float(seconds)
    return options


def _render(args: argparse.Namespace, choice, written: tuple, mode: str | None, *, one: bool = True) -> None:
    """One line per certificate written (JSON with ``--json``); for one gain set, what was tried and κ against κ_lin
    first."""
    from .._infra.output import emit
    from .._infra.rational import format_rational

    cert, name = choice.certificate, choice.template.name
    paper = name == "paper"
    mode = (mode or "tightest") if paper else None
    if args.json:
        physical = getattr(cert, "physical", None)
        emit(json.dumps({
            "file": str(written[0]), "report": str(written[1]) if len(written) > 1 else None,
            "template": name, "template_id": choice.template.id, "mode": mode,
            "search": (args.search or "closed-form") if paper else "sdp",
            "label": cert.provenance.label if cert.provenance is not None else "",
            "parameters": {k: format_rational(v) for k, v in cert.parameters.items()},
            "physical": None if physical is None else {k: format_rational(v) for k, v in physical.items()},
            "overshoot_bound": cert.overshoot_bound, "proved": True,
            "alternatives": [{"template": a.template.name, "search": a.search or None, "overshoot_bound": None
                              if a.certificate is None else a.certificate.overshoot_bound, "reason": a.reason or None,
                              "seconds": round(a.seconds, 4)} for a in choice.others],
            "note": choice.note or None,
            "template_search": choice.chosen.search or None, "seconds": round(choice.chosen.seconds, 4),
            "kappa_lin_lower": None if choice.kappa_lin_lower is None else format_rational(choice.kappa_lin_lower),
        }, ensure_ascii=False), level=0)
        return
    if one and (choice.others or choice.note):
        emit(choice.describe(timed=True), level=0)
    if one and choice.against_kappa_lin():
        emit(choice.against_kappa_lin(), level=0)
    what = f"{written[0]} and {written[1].name} ({mode})" if paper else f"{written[0]} ({name} template)"
    # the normalised gains that were certified (physical values, when given, follow in parentheses)
    emit(f"wrote {what} for {cert.gains_text()}: |x(t)|_A <= {cert.overshoot_bound}·|x(0)|_A", level=0)


def _run_box(args: argparse.Namespace) -> int:
    """Certify a box of gains (intervals), verify it at every piece's corners, write it; print one line."""
    from pathlib import Path

    from .._certify.box import certify_box, default_box_stem, write_box
    from .._infra.io import check_stem, ensure_directory
    from .._infra.output import emit
    from .._infra.rational import to_rational

    if args.template in ("quadratic", "sup-flow"):
        raise ParameterError("a box (intervals LO:HI) is certified with the paper's template only (the closed form at "
                             f"its corners); --template {args.template} certifies one gain set")
    if args.search not in (None, "closed-form"):
        raise ParameterError("a box is certified by the closed form only (--search closed-form)")
    if args.mode not in (None, "tightest"):
        raise ParameterError("a box certificate has one mode (tightest); --mode feasible applies to one gain set")
    if args.pieces is not None and args.kappa_tol is not None:
        raise ParameterError("give --pieces or --kappa-tol, not both")
    box, physical = _intervals(args)
    label = args.label or ""
    if len(label) > 1000 or not label.isprintable():
        raise ParameterError(f"--label must be at most 1000 printable characters; got {len(label)} characters")
    out = Path(args.out)
    stem = check_stem(args.name) if args.name is not None else None
    ensure_directory(out)
    tol = None if args.kappa_tol is None else to_rational(args.kappa_tol, name="--kappa-tol")
    cert = certify_box(box, physical=physical, pieces=args.pieces or 1, kappa_tol=tol, margin=args.margin, label=label)
    path = write_box(cert, out / f"{stem or default_box_stem(cert)}.json")
    if args.json:
        emit(json.dumps({"file": str(path), "kind": "box", "pieces": len(cert.pieces), "label": label,
                         "box": cert.to_dict()["box"], "physical": cert.to_dict().get("physical"),
                         "overshoot_bound": cert.overshoot_bound, "proved": True}, ensure_ascii=False), level=0)
    else:
        emit(f"wrote {path} ({len(cert.pieces)} piece(s)): |x(t)|_A <= {cert.overshoot_bound}·|x(0)|_A "
             "for every gain set in the box", level=0)
    return 0
