"""Every option of every command, and every number field of scenes, configurations and certificates, under hostile input.

The options come from the real argument parser (:func:`symbolic_friction._cli.main.build_parser`):
:data:`KINDS` says what each option is (a gain, a count, an output directory, …),
and a test fails when the parser has an option :data:`KINDS` does not classify,
so a new option cannot be forgotten.  Each kind has its hostile values
(:data:`VALUES`); each value is put into a command line that is otherwise
valid and cheap (:data:`BASE`), and must end in exit status 2, one line on
stderr, no traceback, within ``BOUND`` seconds, with no special file replaced
(the runner of ``test_hostile_inputs.py``).  The file fields (scenes,
configuration, certificates) get the same treatment from
:data:`NUMBER_FIELDS` and :data:`STRUCTURES`.

Special files given as *outputs* that may legitimately be written through
(``/dev/null``, a FIFO with a reader) are in :data:`WRITTEN_THROUGH`: exit 0
and the device still in place.  :data:`ENCODING_CASES` run in a fresh
interpreter (``PYTHONIOENCODING``); the rest in forks of one warm one
(``tests/forkserver.py``), which :func:`test_fork_and_fresh_interpreter_agree`
holds to what a fresh interpreter does.
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import stat

import pytest

from tests import test_hostile_inputs
from tests.test_hostile_inputs import BOUND, CERT, _cert_with, _scene, run_case

_case_root, case_dir = test_hostile_inputs._case_root, test_hostile_inputs.case_dir  # fixtures: a directory per case

BIG = "7" * 100_000
CERTS = str(CERT)
GAINS = ["--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"]

# --- what every option is ---------------------------------------------------------------------------------

KINDS: dict[tuple[str, str], str] = {
    # check
    ("check", "--json"): "flag", ("check", "--write"): "flag", ("check", "--no-certificates"): "flag",
    ("check", "--proofs"): "in-dir", ("check", "--config"): "in-file", ("check", "--only"): "names",
    ("check", "--junit-xml"): "out-file", ("check", "--strict"): "flag", ("check", "--smt"): "flag",
    ("check", "--smt-solver"): "choice", ("check", "--smt-timeout"): "real", ("check", "--smt-budget"): "real",
    # certify
    ("certify", "--mode"): "choice", ("certify", "--margin"): "fraction", ("certify", "--out"): "out-dir",
    ("certify", "--name"): "stem", ("certify", "--label"): "text", ("certify", "--json"): "flag",
    ("certify", "--search"): "choice", ("certify", "--pieces"): "count", ("certify", "--kappa-tol"): "real",
    ("certify", "--template"): "choice", ("certify", "--budget"): "real",
    **{("certify", f): "gain" for f in ("--k-p", "--k-i", "--k-v", "--f-c", "--m", "--k-p-bar", "--k-i-bar",
                                        "--k-d-bar", "--f-c-bar", "--alpha-v")},
    # verify
    ("verify", "files"): "in-file", ("verify", "--json"): "flag", ("verify", "--junit-xml"): "out-file",
    ("verify", "--independent-only"): "flag",
    # simulate
    ("simulate", "scene"): "in-file", ("simulate", "--out"): "out-dir", ("simulate", "--format"): "choice",
    ("simulate", "--png"): "flag", ("simulate", "--list"): "flag", ("simulate", "--json"): "flag",
    # figures
    ("figures", "--out"): "out-dir", ("figures", "--only"): "names", ("figures", "--list"): "flag",
    ("figures", "--format"): "formats",
    # crosscheck
    ("crosscheck", "certificates"): "in-file", ("crosscheck", "--trajectories"): "count",
    ("crosscheck", "--seed"): "seed", ("crosscheck", "--horizon"): "real", ("crosscheck", "--samples"): "count",
    ("crosscheck", "--rtol"): "real", ("crosscheck", "--theta"): "real", ("crosscheck", "--out"): "out-dir",
    ("crosscheck", "--no-adversarial"): "flag", ("crosscheck", "--decay"): "flag",
    ("crosscheck", "--max-events"): "count", ("crosscheck", "--json"): "flag",
    ("crosscheck", "--junit-xml"): "out-file", ("crosscheck", "--iss"): "flag", ("crosscheck", "--iss-search"): "flag",
    # hunting
    **{("hunting", f): "gain" for f in ("--k-p", "--k-i", "--k-v", "--f-c", "--f-s")},
    ("hunting", "--out"): "out-dir", ("hunting", "--name"): "stem", ("hunting", "--figure"): "out-file",
    ("hunting", "--sweep"): "sweep", ("hunting", "--no-iss"): "flag", ("hunting", "--no-simulation"): "flag",
    # settling
    **{("settling", f): "gain" for f in ("--k-p", "--k-i", "--k-v", "--f-c", "--f-s")},
    ("settling", "--reset-dwell"): "real", ("settling", "--z0"): "state", ("settling", "--tol"): "real",
    ("settling", "--t-end"): "real", ("settling", "--samples"): "count", ("settling", "--out"): "out-dir",
    ("settling", "--no-figure"): "flag", ("settling", "--json"): "flag", ("settling", "--contraction"): "flag",
    # tradeoff
    ("tradeoff", "--case"): "choice", ("tradeoff", "--z0"): "state", ("tradeoff", "--t-end"): "real",
    ("tradeoff", "--samples"): "count", ("tradeoff", "--repeats"): "count", ("tradeoff", "--quick"): "flag",
    ("tradeoff", "--no-cost"): "flag", ("tradeoff", "--json"): "flag", ("tradeoff", "--out"): "out-dir",
    ("tradeoff", "--no-figures"): "flag", ("tradeoff", "--format"): "formats",
    **{("tradeoff", f): "gain" for f in ("--k-p", "--k-i", "--k-v", "--f-c", "--m", "--k-p-bar", "--k-i-bar",
                                         "--k-d-bar", "--f-c-bar", "--alpha-v")},
    # extremes
    ("extremes", "--out"): "out-dir", ("extremes", "--only"): "names", ("extremes", "--format"): "formats",
    ("extremes", "--json"): "flag", ("extremes", "--theta"): "real",
    ("simulate", "--theta"): "real", ("tradeoff", "--theta"): "real", ("figures", "--jobs"): "count",
    # map
    **{("map", f): "axis" for f in ("--k-p", "--k-i", "--k-v", "--f-c", "--f-s", "--m", "--k-p-bar", "--k-i-bar",
                                    "--k-d-bar", "--alpha-v", "--f-c-bar", "--f-s-bar")},
    ("map", "--sample"): "count", ("map", "--tight"): "real", ("map", "--seed"): "seed", ("map", "--sdp"): "flag", ("map", "--adversary"): "count",
    ("map", "--chunk"): "count", ("map", "--out"): "out-dir", ("map", "--format"): "formats",
    ("map", "--workers"): "count", ("map", "--scheduler"): "text", ("map", "--plot"): "names",
    ("map", "--no-plot"): "flag", ("map", "--json"): "flag",
}
"""The kind of every option of every command (``--quiet``, ``--verbose`` and ``--help`` are everywhere and flags)."""


def parser_options() -> set[tuple[str, str]]:
    """(command, option) for every option and positional of every command, read from the real parser."""
    from symbolic_friction._cli.main import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    found = set()
    for command, p in sub.choices.items():
        for action in p._actions:
            if isinstance(action, argparse._HelpAction) or action.dest in ("quiet", "verbose"):
                continue
            long = [o for o in action.option_strings if o.startswith("--")]
            found.add((command, long[0] if long else action.dest))
    return found


# --- the cheapest valid command line of each command; the option under test replaces or joins it ----------

BASE: dict[str, list[str]] = {
    "check": ["check", "--only", "model.V_runtime", "--proofs", "{d}"],
    "certify": ["certify", *GAINS, "--out", "{d}/out"],
    "verify": ["verify", CERTS],
    "simulate": ["simulate", "paper-a", "--out", "{d}/out"],
    "figures": ["figures", "--only", "fig4", "--out", "{d}/out"],
    "crosscheck": ["crosscheck", CERTS, "--trajectories", "5", "--no-adversarial", "--out", "{d}/cx"],
    "hunting": ["hunting", *GAINS, "--f-s", "1.2", "--out", "{d}/out", "--no-iss", "--no-simulation"],
    "settling": ["settling", *GAINS, "--t-end", "5", "--samples", "11", "--out", "{d}/out"],
    "tradeoff": ["tradeoff", *GAINS, "--quick", "--no-cost", "--no-figures", "--repeats", "1", "--samples", "11",
                 "--t-end", "1"],
    "extremes": ["extremes", "--only", "f_c", "--out", "{d}/out"],
    "map": ["map", "--k-p", "1:3:2", "--k-i", "1:2:2", "--k-v", "2", "--f-c", "1", "--out", "{d}/out"],
}

# A positional's slot in BASE (the value it replaces).
POSITIONAL = {("verify", "files"): CERTS, ("simulate", "scene"): "paper-a", ("crosscheck", "certificates"): CERTS}


PHYSICAL = ["--m", "2", "--k-p-bar", "6", "--k-i-bar", "8", "--k-d-bar", "12.8", "--f-c-bar", "2"]
BASE_FOR: dict[tuple[str, str], list[str]] = {
    **{(command, option): [*BASE[command][:BASE[command].index("--k-p")], *PHYSICAL,
                           *BASE[command][BASE[command].index("--f-c") + 2:]]
       for command in ("certify", "tradeoff") if "--k-p" in BASE[command]
       for option in ("--m", "--k-p-bar", "--k-i-bar", "--k-d-bar", "--f-c-bar", "--alpha-v")},
    **{("map", option): ["map", "--m", "2", "--k-p-bar", "6:8:2", "--k-i-bar", "8:9:2", "--k-d-bar", "12.8",
                         "--f-c-bar", "2", "--out", "{d}/out"]
       for option in ("--m", "--k-p-bar", "--k-i-bar", "--k-d-bar", "--f-c-bar", "--alpha-v", "--f-s-bar")},
    ("tradeoff", "--out"): [a for a in BASE["tradeoff"] if a != "--no-figures"],
}
"""Where an option is only read with others: physical gains with the physical set, ``--out`` with figures on."""


def command_line(command: str, option: str, value: str) -> list[str]:
    argv = list(BASE_FOR.get((command, option), BASE[command]))
    if (command, option) in POSITIONAL:
        argv[argv.index(POSITIONAL[command, option])] = value
        return argv
    if option in argv:
        i = argv.index(option)
        argv[i + 1] = value
        return argv
    return [*argv, option, value]


# --- hostile values of each kind: (label, value, files to create in the case's directory) ------------------

NOPERM = "NOPERM"  # a directory (or file) the user may not enter or read: skipped as root
SOCKET = "SOCKET"  # a UNIX socket
ROOT = os.geteuid() == 0

_PATHS_IN = [
    ("directory", "{d}", {}),
    ("socket", "{d}/sock", {"sock": SOCKET}),
    ("fifo", "{d}/fifo", {"fifo": "FIFO"}),
    ("dev-null", "/dev/null", {}),
    ("dev-full", "/dev/full", {}),
    ("dev-zero", "/dev/zero", {}),
    ("symlink-to-device", "{d}/tty", {"tty": "->/dev/zero"}),
    ("symlink-loop", "{d}/loop", {"loop": "LOOP"}),
    ("dangling-symlink", "{d}/dangling", {"dangling": "->{d}/nowhere"}),
    ("through-a-file", "{d}/plain/x", {"plain": "text"}),
    ("name-too-long", "{d}/" + "n" * 300, {}),
    ("no-permission", "{d}/locked/x", {"locked": NOPERM}),
    ("empty", "", {}),
]
_PATHS_OUT_DIR = [
    ("a-file", "{d}/plain", {"plain": "text"}),
    ("fifo", "{d}/fifo", {"fifo": "FIFO"}),
    ("dev-null", "/dev/null", {}),
    ("dev-full", "/dev/full", {}),
    ("dev-zero", "/dev/zero", {}),
    ("symlink-to-device", "{d}/tty", {"tty": "->/dev/null"}),
    ("symlink-loop", "{d}/loop", {"loop": "LOOP"}),
    ("dangling-symlink", "{d}/dangling", {"dangling": "->{d}/nowhere"}),
    ("through-a-file", "{d}/plain/sub", {"plain": "text"}),
    ("name-too-long", "{d}/" + "n" * 300, {}),
    ("no-permission", "{d}/locked/sub", {"locked": NOPERM}),
    ("empty", "", {}),
]
_PATHS_OUT_FILE = [
    ("directory", "{d}", {}),
    ("socket", "{d}/sock", {"sock": SOCKET}),
    ("fifo-without-reader", "{d}/fifo", {"fifo": "FIFO"}),
    ("dev-full", "/dev/full", {}),
    ("symlink-to-device", "{d}/null", {"null": "->/dev/null"}),
    ("symlink-loop", "{d}/loop", {"loop": "LOOP"}),
    ("dangling-symlink", "{d}/dangling", {"dangling": "->{d}/nowhere"}),
    ("through-a-file", "{d}/plain/r.xml", {"plain": "text"}),
    ("name-too-long", "{d}/" + "n" * 300 + ".xml", {}),
    ("no-permission", "{d}/locked/r.xml", {"locked": NOPERM}),
    ("trailing-slash", "{d}/new/", {}),
    ("empty", "", {}),
]
_NUMBERS = [  # refused by every number reader, wherever a positive exact number is expected
    ("huge-integer", BIG, {}),
    ("huge-denominator", "1/" + BIG, {}),
    ("huge-exponent", "1e999999999", {}),
    ("tiny-exponent", "1e-999999999", {}),
    ("nan", "nan", {}),
    ("inf", "inf", {}),
    ("minus-infinity", "-Infinity", {}),
    ("arabic-digits", "٣", {}),
    ("fullwidth-digits", "３", {}),
    ("devanagari-digits", "३", {}),
    ("superscript", "³", {}),
    ("negative", "-3", {}),
    ("zero", "0", {}),
    ("zero-denominator", "1/0", {}),
    ("empty", "", {}),
    ("blank", " ", {}),
    ("space-in-number", "3 5", {}),
    ("underscore", "1_000", {}),
    ("hex", "0x10", {}),
    ("two-slashes", "1/2/3", {}),
]
_COUNTS = [
    ("huge", "1000000000000", {}),
    ("huge-digits", BIG, {}),
    ("zero", "0", {}),
    ("negative", "-1", {}),
    ("float", "2.5", {}),
    ("exponent", "1e3", {}),
    ("nan", "nan", {}),
    ("arabic-digits", "٣", {}),
    ("underscore", "1_0", {}),
    ("empty", "", {}),
]
_REALS = [
    ("overflow", "1e999", {}),
    ("huge-exponent", "1e999999999", {}),
    ("tiny-exponent", "1e-999999999", {}),
    ("huge", "1e308", {}),
    ("nan", "nan", {}),
    ("inf", "inf", {}),
    ("negative", "-1", {}),
    ("zero", "0", {}),
    ("arabic-digits", "٣", {}),
    ("underscore", "1_0", {}),
    ("empty", "", {}),
]
_STEMS = [
    ("parent", "../x", {}), ("absolute", "/tmp/x", {}), ("dotdot", "..", {}), ("dot", ".", {}), ("empty", "", {}),
    ("blank", " ", {}), ("newline", "a\nb", {}), ("tab", "a\tb", {}), ("too-long", "n" * 300, {}),
    ("backslash", "..\\x", {}), ("hidden", ".x", {}), ("nested", "a/b", {}),
]
VALUES: dict[str, list[tuple[str, str, dict]]] = {
    "in-file": _PATHS_IN + [("trailing-slash", CERTS + "/", {})],
    "in-dir": [v for v in _PATHS_OUT_DIR if v[0] not in ("no-permission",)],
    "out-dir": _PATHS_OUT_DIR,
    "out-file": _PATHS_OUT_FILE,
    "gain": _NUMBERS,
    "fraction": _NUMBERS + [("above-one", "2", {})],
    "count": _COUNTS,
    "real": _REALS,
    "seed": [("negative", "-1", {}), ("huge", BIG, {}), ("float", "1.5", {}), ("arabic-digits", "٣", {}),
             ("empty", "", {}), ("nan", "nan", {})],
    "stem": _STEMS,
    # a map axis: a value or LO:HI:N[:log]; zero and negative values are points outside Assumption 1, not errors
    "axis": [v for v in _NUMBERS if v[0] not in ("negative", "zero")] + [
        ("reversed", "2:1:5", {}), ("no-points", "1:2", {}), ("one-point", "1:2:1", {}),
        ("huge-grid", "1:2:100000000", {}), ("log-from-zero", "0:1:5:log", {}), ("five-parts", "1:2:3:4:5", {}),
        ("float-points", "1:2:2.5", {}), ("scale-alone", "log", {}), ("huge-text", "1:" * 50_000, {}),
    ],
    "text": [("huge", "x" * 100_000, {}), ("newline", "a\nb", {}), ("escape", "a\x1b[2Jb", {})],
    "names": [("unknown", "no-such-thing", {}), ("empty", "", {}), ("huge", "x" * 100_000, {})],
    "formats": [("unknown", "exe", {}), ("empty", "", {}), ("path", "../png", {}), ("huge", "x" * 100_000, {})],
    "choice": [("unknown", "frobnicate", {}), ("empty", "", {})],
    "sweep": [
        ("huge-exponent", "1e999999999", {}), ("tiny-exponent", "1.1,1e-999999999", {}), ("nan", "nan", {}),
        ("inf", "1.1,inf", {}), ("below-one", "0.5", {}), ("one", "1", {}), ("negative", "-2", {}),
        ("empty", "", {}), ("only-commas", ",,,", {}), ("too-many", ",".join(["1.1"] * 1000), {}),
        ("huge-list", ",".join(["1.1"] * 100_000), {}), ("arabic-digits", "١.١", {}), ("huge-digits", BIG, {}),
        ("huge-denominator", "1/" + BIG, {}),
    ],
    "state": [
        ("nan", "nan,0,0", {}), ("inf", "0,inf,0", {}), ("overflow", "0,1e999,0", {}), ("huge", "0,1e300,0", {}),
        ("two-values", "0,1", {}), ("four-values", "0,1,0,0", {}), ("arabic-digits", "٣,0,0", {}),
        ("empty", "", {}), ("huge-digits", "0," + BIG + ",0", {}), ("underscore", "0,1_0,0", {}),
    ],
}

# The class (prefix of the id) of each kind.
CLASS = {"in-file": "path", "in-dir": "path", "out-dir": "path", "out-file": "path", "stem": "name",
         "gain": "number", "axis": "number", "fraction": "number", "count": "number", "real": "number", "seed": "number",
         "sweep": "number", "state": "number", "text": "structure", "names": "usage", "formats": "usage",
         "choice": "usage"}

# Combinations that are not hostile: the value is valid for this option.
NOT_HOSTILE = {("certify", "--alpha-v", "zero"), ("tradeoff", "--alpha-v", "zero")}  # α_v = 0 is the default
NOT_HOSTILE |= {("map", "--sample", "zero"), ("map", "--adversary", "zero")}  # a grid; no adversary
NOT_HOSTILE |= {("certify", "--kappa-tol", "zero")}  # one gain set: every search within the budget
NOT_HOSTILE |= {("map", "--tight", "zero")}  # the tight columns off (the default)


PER_OPTION = {"gain": 5, "axis": 6, "fraction": 8, "count": 6, "real": 6}
"""Values tried per option of these kinds, rotating through the kind's list so that every value is tried on some
option (the number readers are shared; the path kinds try every value on every option)."""


def _rotate(values: list, turn: int, k: int | None) -> list:
    if k is None or k >= len(values):
        return list(values)
    return [values[(turn * k + j) % len(values)] for j in range(k)]


def _option_cases():
    turns: dict[str, int] = {}
    for (command, option), kind in sorted(KINDS.items()):
        if kind == "flag":
            continue
        turn = turns[kind] = turns.get(kind, -1) + 1
        for label, value, files in _rotate(VALUES[kind], turn, PER_OPTION.get(kind)):
            if (command, option, label) in NOT_HOSTILE:
                continue
            yield (f"{CLASS[kind]}-{command}-{option.lstrip('-')}-{label}", command_line(command, option, value), files)


def _range_cases():
    """Numbers that parse but leave what a command can do in bounded time: refused before any work."""
    hunting, tradeoff, crosscheck = BASE["hunting"], BASE["tradeoff"], BASE["crosscheck"]
    gains = {"tiny": ["--k-p", "1e-300", "--k-i", "1e-300", "--k-v", "3"], "huge": ["--k-p", "1e300", "--k-i", "1e300",
                                                                                  "--k-v", "1e300"]}
    for label, values in gains.items():
        yield (f"number-hunting-gains-{label}", _with(hunting, values), {})
    for label, f_s in (("barely-above-f-c", "1.0000000000000000000000001"), ("huge", "1e300"), ("hundredfold", "101")):
        yield (f"number-hunting-f-s-{label}", _with(hunting, ["--f-s", f_s]), {})
    yield ("number-hunting-sweep-barely-above-one", [*hunting, "--sweep", "1.0000000000000000001"], {})
    yield ("number-tradeoff-t-end-ceiling", _with(tradeoff, ["--t-end", "1001"]), {})
    yield ("number-tradeoff-gains-stiff", _with(tradeoff, ["--k-p", "1e6", "--k-i", "1e6", "--k-v", "1e6"]), {})
    yield ("number-tradeoff-gains-huge", _with(tradeoff, ["--k-p", "1e300", "--k-i", "1e300", "--k-v", "1e300"]), {})
    yield ("number-tradeoff-z0-above-ceiling", [*tradeoff, "--z0", "1e13,0,0"], {})
    yield ("number-crosscheck-trajectories-times-samples", _with(crosscheck, ["--trajectories", "1000"]) + ["--samples", "100000"], {})
    yield ("number-crosscheck-horizon-ceiling", [*crosscheck, "--horizon", "1000001"], {})


def _with(argv: list[str], changes: list[str]) -> list[str]:
    """``argv`` with each ``option value`` pair of ``changes`` replacing the option's value (or appended)."""
    out = list(argv)
    for option, value in zip(changes[::2], changes[1::2]):
        if option in out:
            out[out.index(option) + 1] = value
        else:
            out += [option, value]
    return out


OPTION_CASES = list(_option_cases()) + list(_range_cases())


def _materialise_links(directory, files: dict) -> dict:
    """Create the symlinks and unreadable directories of ``files``; return the rest for ``run_case``."""
    rest = {}
    for name, content in files.items():
        path = directory / name
        if isinstance(content, str) and content.startswith("->"):
            os.symlink(content[2:].format(d=directory), path)
        elif content == SOCKET:
            with socket.socket(socket.AF_UNIX) as sock:
                sock.bind(str(path))
        elif content == NOPERM:
            path.mkdir()
            (path / "x").write_text("{}")
            path.chmod(0)
        else:
            rest[name] = content
    return rest


SAYS = {
    "path-certify-out-empty": "must name a directory; got ''",
    "path-verify-junit-xml-trailing-slash": "a trailing / names a directory, not a file",
    "path-crosscheck-certificates-trailing-slash": "a trailing / names a directory, not a file",
    "path-verify-junit-xml-socket": "is not a regular file, a character device or a FIFO",
    "path-verify-junit-xml-fifo-without-reader": "is a FIFO with no reader",
    "path-verify-junit-xml-dev-full": "no space left on the device",
    "path-verify-junit-xml-symlink-to-device": "is a symbolic link",
    "path-hunting-figure-directory": "--figure",
    "number-crosscheck-samples-arabic-digits": "(ASCII digits)",
    "number-crosscheck-horizon-huge": "--horizon must lie in (0, 1e+06]",
    "number-certify-budget-huge": "--budget must be a number of seconds in (0, 86400]",
    "number-certify-kappa-tol-overflow": "--kappa-tol must be in [0, 1000] for one gain set",
    "number-tradeoff-repeats-float": "--repeats must be an integer from 1 to 1000",
    "number-hunting-sweep-empty": "--sweep takes 1 to 50",
    "structure-certificate-huge-array": "more than 10000 JSON values",
    "structure-certificate-duplicate-key": "duplicate key",
    "name-hunting-name-parent": "without directories",
    "number-hunting-gains-tiny": "beyond what a float64 simulation can represent",
    "number-hunting-f-s-barely-above-f-c": "f_s/f_c must be 1 (the paper's model) or lie in [1 + 1e-06, 100]",
    "number-hunting-sweep-barely-above-one": "--sweep ratios f_s/f_c must lie in [1 + 1e-06, 100]",
    "number-tradeoff-t-end-ceiling": "--t-end must lie in (0, 1000]",
    "number-tradeoff-gains-stiff": "spectral radius × t_end = 1e+06, at most 100000",
    "number-crosscheck-trajectories-times-samples": "at most 20000000 are supported",
    "structure-scene-too-many-states": "initial_states: at most 100000 initial states per scene are supported; the file "
                                       "opens 200002 arrays (at most 101000)",
    "structure-config-huge-array": "300000 commas outside strings (values in lists and tables); a configuration of at "
                                   "most 10000 certificates needs at most 80000",
}
"""What the one line must say, where the wording matters most (the rest: exit 2, one line)."""


def _check(result, name: str) -> None:
    err = result.stderr.decode("utf-8", errors="replace")
    assert not result.timed_out, f"{name}: killed after the timeout"
    assert "Traceback" not in err, err[-3000:]
    assert result.returncode == 2, (result.returncode, err[-2000:], result.stdout.decode(errors="replace")[-1000:])
    lines = err.strip().splitlines()
    assert len(lines) == 1, err[-2000:]
    assert "error" in lines[0]
    assert SAYS.get(name, "") in lines[0], lines[0]
    assert result.seconds < BOUND, f"{name}: {result.seconds:.1f} s"


@pytest.fixture(scope="module")
def server(fork_server):
    """The warm interpreter of tests/conftest.py, shared with tests/test_hostile_inputs.py (started once)."""
    return fork_server


def test_every_option_of_every_command_has_a_kind():
    """A new option (or command) must be classified here, which gives it its hostile cases."""
    options = parser_options()
    assert options == set(KINDS), (
        f"options without a kind: {sorted(options - set(KINDS))}; kinds of no option: {sorted(set(KINDS) - options)}"
    )
    assert set(BASE) == {command for command, _ in options}


def test_case_ids_are_unique_and_many():
    ids = [c[0] for c in OPTION_CASES + FILE_CASES + ENCODING_CASES]
    assert len(ids) == len(set(ids)), sorted({i for i in ids if ids.count(i) > 1})
    assert len(ids) >= 150
    assert set(SAYS) <= set(ids), sorted(set(SAYS) - set(ids))


@pytest.mark.parametrize("case", OPTION_CASES, ids=[c[0] for c in OPTION_CASES])
def test_hostile_option_value(case, case_dir, server):
    name, argv, files = case
    if NOPERM in files.values() and ROOT:
        pytest.skip("running as root: permissions do not apply")
    try:
        result, _ = run_case(argv, _materialise_links(case_dir, files), {}, case_dir, server)
    finally:
        for path in case_dir.iterdir():
            if not path.is_symlink() and path.is_dir():
                path.chmod(0o755)
    _check(result, name)


# --- number fields and structure of the files: scenes, configuration, certificates -----------------------

_SCENE_NUMBER_FIELDS = {
    "t_end": lambda v: _scene("").replace("t_end = 10", f"t_end = {v}"),
    "gains.k_p": lambda v: _scene("").replace("k_p = 3", f"k_p = {v}"),
    "gains.k_v": lambda v: _scene("").replace("k_v = 6.4", f"k_v = {v}"),
    "gains.f_c": lambda v: _scene("").replace("f_c = 1", f"f_c = {v}"),
    "initial_states": lambda v: _scene("").replace("[[0, 1, 0]]", f"[[0, {v}, 0]]"),
    "friction.rho": lambda v: _scene(f'[friction]\nlaw = "inflated"\nrho = {v}\n[method]\nname = "moreau"\n'),
    "method.h": lambda v: _scene(f'[method]\nname = "moreau"\nh = {v}\n'),
    "method.epsilon": lambda v: _scene(f'[method]\nname = "regularized"\nepsilon = {v}\n'),
}
_SCENE_INTEGER_FIELDS = {
    "samples": lambda v: _scene("").replace("t_end = 10", f"t_end = 10\nsamples = {v}"),
    "method.grid_points": lambda v: _scene(f'[method]\nname = "event"\ngrid_points = {v}\n'),
    "method.max_events": lambda v: _scene(f'[method]\nname = "event"\nmax_events = {v}\n'),
    "method.max_steps": lambda v: _scene(f'[method]\nname = "moreau"\nmax_steps = {v}\n'),
}
_INTEGER_VALUES = [("huge", "1000000000000"), ("huge-digits", "1" + "0" * 4000), ("zero", "0"), ("negative", "-5"),
                   ("float", "2.5"), ("string", '"100"'), ("bool", "true"), ("inf", "inf")]
_CERT_NUMBER_FIELDS = ("parameters__k_p", "parameters__f_c", "constants__c1", "constants__k4", "overshoot_bound",
                       "provenance__margin")
_FIELD_VALUES = [  # as TOML/JSON strings (the files' exact-number spelling), and two bare TOML values
    ("huge-exponent", '"1e999999999"'), ("tiny-exponent", '"1e-999999999"'), ("nan-string", '"nan"'),
    ("inf-string", '"inf"'), ("arabic-digits", '"٣"'), ("negative", '"-3"'), ("zero", '"0"'),
    ("space-in-number", '"3 5"'), ("huge-denominator", '"1/' + BIG + '"'), ("bare-nan", "nan"),
    ("bare-inf", "inf"), ("bool", "true"),
]


_FIELD_VALID = {("initial_states", "negative"), ("initial_states", "zero"), ("friction.rho", "zero")}
"""Values that are valid in that field (a state may be negative or zero; ρ = 0 is Coulomb's law)."""
_CERT_SIGN_PREMISES = {"parameters__k_p": "k_p > 0", "parameters__f_c": "f_c > 0", "constants__c1": "c1 > 0",
                       "constants__k4": "k4 > 0", "overshoot_bound": "overshoot_bound > 0"}
"""A well-formed certificate number of the wrong sign is a *false* certificate, not bad input: ``verify`` reads it and
refuses it with exit 1, naming the premise (``provenance.margin`` is no premise: its sign stays format, exit 2)."""


def _file_cases():
    for turn, (field, make) in enumerate(_SCENE_NUMBER_FIELDS.items()):
        for label, value in _rotate(_FIELD_VALUES, turn, 7):
            if (field, label) in _FIELD_VALID:
                continue
            yield (f"number-scene-{field}-{label}", ["simulate", "{d}/s.toml", "--out", "{d}/out"], {"s.toml": make(value)})
    for field, make in _SCENE_INTEGER_FIELDS.items():
        for label, value in _INTEGER_VALUES:
            yield (f"number-scene-{field}-{label}", ["simulate", "{d}/s.toml", "--out", "{d}/out"], {"s.toml": make(value)})
    yield ("structure-scene-too-many-states", ["simulate", "{d}/s.toml", "--out", "{d}/out"],
           {"s.toml": _scene("").replace("[[0, 1, 0]]", "[" + ", ".join(["[0, 1, 0]"] * 200_000) + "]")})
    for turn, field in enumerate(_CERT_NUMBER_FIELDS):
        for label, value in _rotate(_FIELD_VALUES, turn, 7):
            if field in _CERT_SIGN_PREMISES and label in ("negative", "zero"):
                continue  # SIGN_CASES
            if value in ("nan", "inf", "true"):
                value = {"nan": "NaN", "inf": "Infinity", "true": "true"}[value]
            text = _cert_with(**{field: json.loads(value)})
            yield (f"number-certificate-{field.replace('__', '.')}-{label}", ["verify", "{d}/c.json"], {"c.json": text})
    yield from (
        (f"structure-{where}-{label}", argv, {name: content})
        for where, argv, name, valid in (
            ("scene", ["simulate", "{d}/s.toml", "--out", "{d}/out"], "s.toml", _scene("")),
            ("config", ["check", "--config", "{d}/symbolic-friction.toml", "--only", "model.V_runtime"], "symbolic-friction.toml",
             'proofs = "."\ncertificates = ["c.json"]\n'),
            ("certificate", ["verify", "{d}/c.json"], "c.json", CERT.read_text(encoding="utf-8")),
        )
        for label, content in _structures(where, valid)
    )


def _structures(where: str, valid: str):
    """Malformed files of one kind, built from a valid one."""
    toml = where != "certificate"
    yield "empty", ""
    yield "blank", " \n\t\n"
    yield "bom-then-garbage", "\ufeff" + "garbage"
    yield "bom-then-valid", "\ufeff" + valid  # refused, and said so: an editor's byte-order mark is not JSON or TOML
    yield "nul-bytes", valid[:20] + "\x00" * 10 + valid[20:]
    yield "only-nul", b"\x00" * 1000
    yield "latin1", valid.encode("utf-8") + "é".encode("latin-1")
    yield "binary", bytes(range(256)) * 10
    yield "truncated", valid[: len(valid) // 2]
    if toml:
        yield "duplicate-key", valid + valid.splitlines()[0] + "\n"
        yield "wrong-type-table", "t_end = { a = 1 }\n" + valid.split("\n", 1)[1] if where == "scene" else "proofs = [1]\n"
        yield "deep-inline-table", "a = " + "{b = " * 5000 + "1" + "}" * 5000
        yield "huge-array", "a = [" + "1," * 300_000 + "]"
        yield "long-key", "k" * 100_000 + " = 1\n" + valid
        yield "array-of-tables", valid + "[[gains]]\nk_p = 1\n"
    else:
        data = json.loads(valid)
        yield "duplicate-key", valid.rstrip()[:-1] + ', "schema": "symbolic-friction/certificate/v1"}'
        yield "wrong-type-parameters", json.dumps({**data, "parameters": ["3", "4"]})
        yield "wrong-type-constants", json.dumps({**data, "constants": "1"})
        yield "schema-number", json.dumps({**data, "schema": 1})
        yield "unknown-nested-key", json.dumps({**data, "parameters": {**data["parameters"], "bogus": "1"}})
        yield "missing-key", json.dumps({k: v for k, v in data.items() if k != "constants"})
        yield "huge-array", json.dumps({**data, "provenance": {**data["provenance"], "obligations": ["x"] * 300_000}})
        yield "deep-in-field", json.dumps({**data, "provenance": {**data["provenance"], "label": None}}).replace(
            "null", "[" * 5000 + "]" * 5000)
        yield "string-escape-nul", json.dumps({**data, "parameters": {**data["parameters"], "k_p": "3\u0000"}})


FILE_CASES = list(_file_cases())


@pytest.mark.parametrize("case", FILE_CASES, ids=[c[0] for c in FILE_CASES])
def test_hostile_file_content(case, case_dir, server):
    name, argv, files = case
    result, _ = run_case(argv, files, {}, case_dir, server)
    _check(result, name)


SIGN_CASES = [(f"sign-certificate-{field.replace('__', '.')}-{label}", field, value, premise)
              for field, premise in _CERT_SIGN_PREMISES.items() for label, value in (("negative", "-3"), ("zero", "0"))]


@pytest.mark.parametrize("case", SIGN_CASES, ids=[c[0] for c in SIGN_CASES])
def test_a_number_of_the_wrong_sign_in_a_certificate_is_refused_by_the_verifier(case, case_dir, server):
    name, field, value, premise = case
    result, _ = run_case(["verify", "{d}/c.json"], {"c.json": _cert_with(**{field: value})}, {}, case_dir, server)
    out, err = result.stdout.decode("utf-8", errors="replace"), result.stderr.decode("utf-8", errors="replace")
    assert not result.timed_out and "Traceback" not in err and err == "", err[-2000:]
    assert result.returncode == 1 and out.startswith("FAILED ") and f"{premise}: {value} > 0 is false" in out, out[-2000:]
    assert result.seconds < BOUND, f"{name}: {result.seconds:.1f} s"


# --- encoding: the one line survives a stream that cannot print the input (a fresh interpreter each) -------

ENCODING_CASES = [
    ("encoding-ascii-missing-non-ascii-path", ["verify", "{d}/κ≤.json"], {"PYTHONIOENCODING": "ascii"}),
    ("encoding-ascii-undecodable-path", ["verify", "{d}/\udcff\udcfe.json"], {"PYTHONIOENCODING": "ascii"}),
    ("encoding-ascii-sweep-arabic", [*BASE["hunting"], "--sweep", "١.١"], {"PYTHONIOENCODING": "ascii"}),
    ("encoding-ascii-z0-arabic", [*BASE["tradeoff"], "--z0", "٣,0,0"], {"PYTHONIOENCODING": "ascii"}),
    ("encoding-latin1-name-control", [*BASE["certify"], "--name", "κ\x1b"], {"PYTHONIOENCODING": "latin-1"}),
    ("encoding-ascii-out-non-ascii-file", [*BASE["simulate"][:2], "--out", "{d}/κ"], {"PYTHONIOENCODING": "ascii"}),
]


@pytest.mark.parametrize("case", ENCODING_CASES, ids=[c[0] for c in ENCODING_CASES])
def test_hostile_encoding(case, case_dir, server):
    name, argv, env = case
    files = {"κ": "text"} if "{d}/κ" in argv else {}
    result, _ = run_case(argv, files, env, case_dir, server)
    _check(result, name)


# --- special files given as outputs: written through (exit 0), the device or FIFO left in place -----------

WRITTEN_THROUGH = [
    ("verify-junit-dev-null", ["verify", CERTS, "--junit-xml", "/dev/null"]),
    ("verify-junit-fifo-with-reader", ["verify", CERTS, "--junit-xml", "{d}/fifo"]),
    ("check-junit-dev-null", ["check", "--only", "model.V_runtime", "--no-certificates", "--junit-xml", "/dev/null"]),
    ("crosscheck-junit-dev-null", [*BASE["crosscheck"], "--junit-xml", "/dev/null"]),
]


@pytest.mark.parametrize("case", WRITTEN_THROUGH, ids=[c[0] for c in WRITTEN_THROUGH])
def test_special_output_is_written_through(case, case_dir, server):
    name, argv = case
    fd = None
    if "{d}/fifo" in argv:
        os.mkfifo(case_dir / "fifo")
        fd = os.open(case_dir / "fifo", os.O_RDONLY | os.O_NONBLOCK)  # the reader a pipe output needs, there first
    try:
        result, _ = run_case(argv, {}, {}, case_dir, server)
        if fd is not None:
            assert b"<testsuite" in os.read(fd, 1 << 20)
            assert stat.S_ISFIFO(os.lstat(case_dir / "fifo").st_mode)
    finally:
        if fd is not None:
            os.close(fd)
    assert result.returncode == 0, result.stderr.decode(errors="replace")[-2000:]
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_fork_and_fresh_interpreter_agree(tmp_path, server):
    """The fast path (a fork of the warm server) gives what a fresh ``python -m symbolic_friction`` gives."""
    from tests.forkserver import run_fresh

    for argv in (["verify", "/dev/zero"], ["certify", "--k-p", "٣", *GAINS[2:]], ["frobnicate"], ["verify", CERTS]):
        forked = server.run(argv, cwd=str(tmp_path), timeout=60, memory=3 * 1024**3)
        fresh = run_fresh(argv, cwd=str(tmp_path), timeout=60, memory=3 * 1024**3)
        assert (forked.returncode, forked.stdout, forked.stderr) == (fresh.returncode, fresh.stdout, fresh.stderr)


def test_brackets_inside_strings_and_comments_do_not_count_as_states():
    """The scene reader refuses too many states before parsing by counting ``[``: those of strings and comments don't."""
    from symbolic_friction._studies._scene_parse import MAX_ARRAYS
    from symbolic_friction._studies.scenes import Scene

    many = "[" * (MAX_ARRAYS + 1)
    for description in (f'"{many}"', f"'{many}'", f'"""\n{many}"""', f"'''{many}\n'''"):
        scene = Scene.from_text(f"description = {description}\n# {many}\n" + _scene(""))
        assert scene.description.strip() == many and len(scene.initial_states) == 1


def test_the_configurations_comma_bound_admits_its_most_certificates_with_every_key():
    """The configuration reader refuses a file by its commas before parsing it: never one of valid size."""
    from symbolic_friction._infra.config import MAX_CERTIFICATES, MAX_CONFIG_COMMAS, toml_syntax_count

    entry = '{file = "c{i}.json", label = "a, b", gains = {k_p = "3", k_i = "4", k_v = "32/5", f_c = "1"}},'
    text = "# a, b\ncertificates = [\n" + "\n".join(entry.replace("{i}", str(i)) for i in range(MAX_CERTIFICATES)) + "]\n"
    assert toml_syntax_count(text, ",", above=0) == 6 * MAX_CERTIFICATES  # the string's and the comment's: not counted
    assert toml_syntax_count(text, ",", above=MAX_CONFIG_COMMAS) <= MAX_CONFIG_COMMAS
