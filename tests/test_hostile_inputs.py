"""The command line under hostile input: every bad input ends in one line on stderr and exit status 2.

Each case runs the real CLI in a process of its own, forked from one warm
interpreter (``tests/forkserver.py``; a case that sets a start-up variable
such as ``PYTHONIOENCODING`` gets a fresh interpreter), with a bound on time
(a FIFO or ``/dev/zero`` must not hang it: killed at ``TIMEOUT``, and
expected to answer within ``BOUND``) and on memory (``RLIMIT_AS``; a
10⁵-digit number or a huge ``samples`` must not exhaust the machine), and
asserts: exit status 2, exactly one line on stderr, no ``Traceback``, and
every device, FIFO or symlink the case names still in place afterwards.

Categories (the ids' prefixes): ``path`` (OS errors on input and output
paths: a file where a directory is needed, ``/dev/null``, a path through a
file, a name too long, a symlink loop, a FIFO, ``/dev/zero``, a directory, a
huge sparse file), ``number`` (10⁵-digit integers and denominators,
``1e999999999``, overflow to inf, non-ASCII digits, NaN), ``structure``
(10⁵-deep JSON and TOML nesting, huge ``samples``, ``grid_points``,
``trajectories``, keys, types), ``name`` (``certify --name`` escaping
``--out``), ``usage`` (bad options and combinations), ``encoding``
(``PYTHONIOENCODING=ascii``).
"""

from __future__ import annotations

import itertools
import json
import os
import stat
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
CERT = REPO / "proofs" / "case_a_tightest.json"
GAINS = ["--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"]
TIMEOUT = 60.0
BOUND = 10.0
"""Seconds a bad input may take before its one line (the hard kill is at TIMEOUT)."""
MEMORY = 3 * 1024**3  # address space: numba/llvmlite reserve a lot of it, a runaway allocation far more


def _cert_with(**changes) -> str:
    data = json.loads(CERT.read_text(encoding="utf-8"))
    for dotted, value in changes.items():
        obj = data
        *parents, last = dotted.split("__")
        for key in parents:
            obj = obj[key]
        obj[last] = value
    return json.dumps(data)


def _scene(body: str) -> str:
    return 't_end = 10\ninitial_states = [[0, 1, 0]]\n[gains]\nk_p = 3\nk_i = 4\nk_v = 6.4\nf_c = 1\n' + body


# (id, argv after "symbolic-friction", files to create {name: content}, extra environment)
# In argv and contents, "{d}" is the case's temporary directory.
BIG = "7" * 100_000
CASES: list[tuple[str, list[str], dict[str, object], dict[str, str]]] = [
    # --- path: input files
    ("path-verify-missing", ["verify", "{d}/nope.json"], {}, {}),
    ("path-verify-directory", ["verify", "{d}"], {}, {}),
    ("path-verify-fifo", ["verify", "{d}/fifo.json"], {"fifo.json": "FIFO"}, {}),
    ("path-verify-dev-zero", ["verify", "/dev/zero"], {}, {}),
    ("path-verify-symlink-loop", ["verify", "{d}/loop.json"], {"loop.json": "LOOP"}, {}),
    ("path-verify-name-too-long", ["verify", "{d}/" + "n" * 300 + ".json"], {}, {}),
    ("path-verify-through-a-file", ["verify", "{d}/plain/x.json"], {"plain": "text"}, {}),
    ("path-verify-huge-file", ["verify", "{d}/huge.json"], {"huge.json": "SPARSE"}, {}),
    ("path-simulate-fifo", ["simulate", "{d}/fifo.toml"], {"fifo.toml": "FIFO"}, {}),
    ("path-simulate-dev-zero", ["simulate", "/dev/zero"], {}, {}),
    ("path-simulate-huge-file", ["simulate", "{d}/huge.toml"], {"huge.toml": "SPARSE"}, {}),
    ("path-simulate-symlink-loop", ["simulate", "{d}/loop.toml"], {"loop.toml": "LOOP"}, {}),
    ("path-simulate-name-too-long", ["simulate", "{d}/" + "n" * 300 + ".toml"], {}, {}),
    ("path-crosscheck-fifo", ["crosscheck", "{d}/fifo.json"], {"fifo.json": "FIFO"}, {}),
    ("path-crosscheck-missing", ["crosscheck", "{d}/nope.json"], {}, {}),
    ("path-check-config-fifo", ["check", "--config", "{d}/fifo.toml"], {"fifo.toml": "FIFO"}, {}),
    ("path-check-config-missing", ["check", "--config", "{d}/nope.toml"], {}, {}),
    ("path-check-config-dev-zero", ["check", "--config", "/dev/zero"], {}, {}),
    # --- path: outputs
    ("path-certify-out-file", ["certify", *GAINS, "--out", "{d}/plain"], {"plain": "text"}, {}),
    ("path-certify-out-dev-null", ["certify", *GAINS, "--out", "/dev/null"], {}, {}),
    ("path-certify-out-through-file", ["certify", *GAINS, "--out", "{d}/plain/sub"], {"plain": "text"}, {}),
    ("path-certify-out-name-too-long", ["certify", *GAINS, "--out", "{d}/" + "n" * 300], {}, {}),
    ("path-certify-out-symlink-loop", ["certify", *GAINS, "--out", "{d}/loop"], {"loop": "LOOP"}, {}),
    ("path-simulate-out-through-file", ["simulate", "paper-a", "--out", "{d}/plain/sub"], {"plain": "text"}, {}),
    ("path-simulate-out-dev-null", ["simulate", "paper-a", "--out", "/dev/null"], {}, {}),
    ("path-figures-out-file", ["figures", "--out", "{d}/plain"], {"plain": "text"}, {}),
    ("path-check-write-proofs-file", ["check", "--write", "--proofs", "{d}/plain"], {"plain": "text"}, {}),
    ("path-check-proofs-dev-null", ["check", "--proofs", "/dev/null"], {}, {}),
    ("path-check-junit-directory", ["check", "--proofs", "{d}", "--junit-xml", "{d}"], {}, {}),
    ("path-verify-junit-through-file", ["verify", str(CERT), "--junit-xml", "{d}/plain/r.xml"], {"plain": "text"}, {}),
    ("path-crosscheck-out-file", ["crosscheck", str(CERT), "--out", "{d}/plain", "--trajectories", "5"], {"plain": "text"}, {}),
    # --- number
    ("number-certify-huge-integer", ["certify", "--k-p", BIG, "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {}),
    ("number-certify-huge-denominator", ["certify", "--k-p", "1/" + BIG, "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {}),
    ("number-certify-huge-exponent", ["certify", "--k-p", "1e999999999", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {}),
    ("number-crosscheck-f-c-overflow", ["crosscheck", "{d}/c.json", "--trajectories", "5"],
     {"c.json": _cert_with(parameters__f_c="1" + "0" * 999, provenance__label="")}, {}),
    ("number-scene-f-c-underflow", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("f_c = 1", 'f_c = "1e-999"')}, {}),
    ("number-certify-arabic-digit", ["certify", "--k-p", "٣", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {}),
    ("number-certify-fullwidth-digit", ["certify", "--k-p", "３", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {}),
    ("number-certify-nan", ["certify", "--k-p", "nan", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {}),
    # the SDP works in double precision (the default closed form certifies these gains exactly)
    ("number-certify-physical-overflow", ["certify", "--m", "1e-999", "--k-p-bar", "3", "--k-i-bar", "4", "--k-d-bar", "6",
                                          "--f-c-bar", "1", "--search", "sdp"], {}, {}),
    ("number-certify-margin-exponent", ["certify", *GAINS, "--margin", "1e-999999999"], {}, {}),
    ("number-certify-margin-arabic", ["certify", *GAINS, "--margin", "١/١٠٠"], {}, {}),
    ("number-verify-huge-integer", ["verify", "{d}/c.json"], {"c.json": _cert_with(constants__k1=BIG)}, {}),
    ("number-verify-huge-denominator", ["verify", "{d}/c.json"], {"c.json": _cert_with(constants__c1="1/" + BIG)}, {}),
    ("number-verify-arabic-digit", ["verify", "{d}/c.json"], {"c.json": _cert_with(parameters__k_p="٣")}, {}),
    ("number-verify-fullwidth-digit", ["verify", "{d}/c.json"], {"c.json": _cert_with(overshoot_bound="３.5")}, {}),
    ("number-verify-json-huge-int", ["verify", "{d}/c.json"], {"c.json": '{"schema": ' + BIG + "}"}, {}),
    ("number-verify-json-float", ["verify", "{d}/c.json"], {"c.json": _cert_with(constants__k1=1e999)}, {}),
    ("number-scene-huge-exponent", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("f_c = 1", 'f_c = "1e999999999"')}, {}),
    ("number-scene-huge-integer", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("k_p = 3", "k_p = " + BIG)}, {}),
    ("number-scene-arabic-digit", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("k_p = 3", 'k_p = "٣"')}, {}),
    ("number-scene-f-c-overflow", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("f_c = 1", 'f_c = "1e999"')}, {}),
    ("number-scene-inf", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("t_end = 10", "t_end = inf")}, {}),
    ("number-crosscheck-seed-negative", ["crosscheck", str(CERT), "--seed", "-1"], {}, {}),
    ("number-crosscheck-seed-huge", ["crosscheck", str(CERT), "--seed", BIG[:5000]], {}, {}),
    ("number-crosscheck-horizon-overflow", ["crosscheck", str(CERT), "--horizon", "1e999"], {}, {}),
    # --- structure
    ("structure-verify-deep-json-array", ["verify", "{d}/c.json"], {"c.json": "[" * 100_000 + "]" * 100_000}, {}),
    ("structure-verify-deep-json-object", ["verify", "{d}/c.json"], {"c.json": '{"a":' * 100_000 + "1" + "}" * 100_000}, {}),
    ("structure-verify-not-json", ["verify", "{d}/c.json"], {"c.json": "\x00\x01\x02 not json"}, {}),
    ("structure-verify-not-utf8", ["verify", "{d}/c.json"], {"c.json": b"\xff\xfe{}"}, {}),
    ("structure-verify-empty", ["verify", "{d}/c.json"], {"c.json": ""}, {}),
    ("structure-verify-array", ["verify", "{d}/c.json"], {"c.json": "[]"}, {}),
    ("structure-verify-unknown-key", ["verify", "{d}/c.json"], {"c.json": _cert_with(extra="x")}, {}),
    ("structure-verify-huge-label", ["verify", "{d}/c.json"], {"c.json": _cert_with(provenance__label="x" * 100_000)}, {}),
    ("structure-scene-deep-toml-array", ["simulate", "{d}/s.toml"], {"s.toml": "a = " + "[" * 100_000 + "]" * 100_000}, {}),
    ("structure-scene-deep-toml-table", ["simulate", "{d}/s.toml"], {"s.toml": "a = " + "{b = " * 100_000 + "1" + "}" * 100_000}, {}),
    ("structure-scene-huge-samples", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("t_end = 10", "t_end = 10\nsamples = 1000000000000")}, {}),
    ("structure-scene-huge-grid-points", ["simulate", "{d}/s.toml"], {"s.toml": _scene("[method]\nname = \"event\"\ngrid_points = 1000000000000\n")}, {}),
    ("structure-scene-states-times-samples", ["simulate", "{d}/s.toml"],
     {"s.toml": _scene("").replace("initial_states = [[0, 1, 0]]", "initial_states = [" + ", ".join(["[0, 1, 0]"] * 100) + "]")
      .replace("t_end = 10", "t_end = 10\nsamples = 1000000")}, {}),
    ("structure-scene-not-utf8", ["simulate", "{d}/s.toml"], {"s.toml": b"\xff\xfe"}, {}),
    ("structure-scene-unknown-key", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("t_end = 10", "t_end = 10\nbogus = 1")}, {}),
    ("structure-config-deep-toml", ["check", "--config", "{d}/symbolic-friction.toml"], {"symbolic-friction.toml": "a = " + "[" * 100_000 + "]" * 100_000}, {}),
    ("structure-config-unknown-key", ["check", "--config", "{d}/symbolic-friction.toml"], {"symbolic-friction.toml": "bogus = 1\n"}, {}),
    ("structure-config-certificates-not-list", ["check", "--config", "{d}/symbolic-friction.toml"], {"symbolic-friction.toml": 'certificates = "a.json"\n'}, {}),
    ("structure-config-escaping-certificate", ["check", "--config", "{d}/symbolic-friction.toml"], {"symbolic-friction.toml": 'certificates = ["../../etc/passwd.json"]\n'}, {}),
    ("structure-crosscheck-huge-trajectories", ["crosscheck", str(CERT), "--trajectories", "1000000000000"], {}, {}),
    ("structure-crosscheck-huge-samples", ["crosscheck", str(CERT), "--samples", "1000000000000"], {}, {}),
    ("structure-crosscheck-huge-max-events", ["crosscheck", str(CERT), "--max-events", "1000000000000"], {}, {}),
    # --- name
    ("name-certify-parent", ["certify", *GAINS, "--out", "{d}/out", "--name", "../../x"], {}, {}),
    ("name-certify-absolute", ["certify", *GAINS, "--out", "{d}/out", "--name", "/tmp/x"], {}, {}),
    ("name-certify-dotdot", ["certify", *GAINS, "--out", "{d}/out", "--name", ".."], {}, {}),
    ("name-certify-empty", ["certify", *GAINS, "--out", "{d}/out", "--name", ""], {}, {}),
    ("name-certify-too-long", ["certify", *GAINS, "--out", "{d}/out", "--name", "n" * 300], {}, {}),
    ("name-certify-control-char", ["certify", *GAINS, "--out", "{d}/out", "--name", "a\nb"], {}, {}),
    # --- usage
    ("usage-unknown-command", ["frobnicate"], {}, {}),
    ("usage-unknown-option", ["check", "--frobnicate"], {}, {}),
    ("usage-check-only-unknown", ["check", "--only", "lemma99"], {}, {}),
    ("usage-certify-missing-gain", ["certify", "--k-p", "3"], {}, {}),
    ("usage-certify-assumption", ["certify", "--k-p", "1", "--k-i", "4", "--k-v", "1", "--f-c", "1"], {}, {}),
    ("usage-certify-both-gain-kinds", ["certify", *GAINS, "--m", "1"], {}, {}),
    ("usage-simulate-unknown-scene", ["simulate", "no-such-scene"], {}, {}),
    ("usage-check-no-config-outside", ["check"], {}, {"_cwd": "{d}"}),
    ("usage-crosscheck-rtol", ["crosscheck", str(CERT), "--rtol", "5"], {}, {}),
    # --- bounded work: every count, horizon and sweep value refused before any loop or allocation
    ("number-hunting-sweep-huge-exponent", ["hunting", *GAINS, "--f-s", "1.2", "--sweep", "1e999999999"], {}, {}),
    ("number-hunting-sweep-tiny-exponent", ["hunting", *GAINS, "--f-s", "1.2", "--sweep", "1.1,1e-999999999"], {}, {}),
    ("number-hunting-sweep-ratio-huge", ["hunting", *GAINS, "--f-s", "1.2", "--sweep", "1e300"], {}, {}),
    ("number-hunting-sweep-too-many", ["hunting", *GAINS, "--f-s", "1.2", "--sweep", ",".join(["1.1"] * 51)], {}, {}),
    ("structure-tradeoff-samples-huge", ["tradeoff", "--samples", "1000000000000"], {}, {}),
    ("structure-tradeoff-t-end-huge", ["tradeoff", "--t-end", "1e308"], {}, {}),
    ("number-certify-tab-fraction", ["certify", "--k-p", "3\t/\t5", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {}),
    ("number-certify-newline-fraction", ["certify", "--k-p", "3\n/5", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {}),
    ("number-scene-gains-underflow", ["simulate", "{d}/s.toml"],
     {"s.toml": _scene("").replace("k_p = 3", "k_p = 1e-300").replace("k_i = 4", "k_i = 1e-300").replace("k_v = 6.4", "k_v = 3")}, {}),
    ("path-verify-trailing-slash", ["verify", str(CERT) + "/"], {}, {}),
    ("path-check-proofs-empty", ["check", "--proofs", ""], {}, {}),
    ("path-verify-junit-dev-full", ["verify", str(CERT), "--junit-xml", "/dev/full"], {}, {}),
    ("name-certify-name-blank", ["certify", *GAINS, "--name", " ", "--out", "{d}/out"], {}, {}),
    ("name-hunting-name-parent", ["hunting", *GAINS, "--f-s", "1.2", "--name", "../x", "--out", "{d}/out"], {}, {}),
    ("name-hunting-name-absolute", ["hunting", *GAINS, "--f-s", "1.2", "--name", "/tmp/x", "--out", "{d}/out"], {}, {}),
    # --- encoding: the one line must survive a stdout/stderr that cannot print κ, ≤ or ٣
    ("encoding-ascii-verify-malformed", ["verify", "{d}/c.json"], {"c.json": _cert_with(parameters__k_p="٣")}, {"PYTHONIOENCODING": "ascii"}),
    ("encoding-ascii-certify-arabic", ["certify", "--k-p", "٣", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"], {}, {"PYTHONIOENCODING": "ascii"}),
    ("encoding-ascii-assumption", ["certify", "--k-p", "1", "--k-i", "4", "--k-v", "1", "--f-c", "1"], {}, {"PYTHONIOENCODING": "ascii"}),
    ("encoding-latin1-scene", ["simulate", "{d}/s.toml"], {"s.toml": _scene("").replace("k_p = 3", 'k_p = "٣"')}, {"PYTHONIOENCODING": "latin-1"}),
]


# What the one line must say, for the cases where the wording matters most (the rest: exit 2, one line).
SAYS = {
    "path-verify-fifo": "not a regular file (a FIFO, socket or device)",
    "number-hunting-sweep-huge-exponent": "exponents beyond",
    "number-hunting-sweep-ratio-huge": "must lie in [1 + 1e-06, 100]",
    "structure-tradeoff-samples-huge": "--samples must be an integer from 2 to 100000",
    "structure-tradeoff-t-end-huge": "--t-end must lie in (0, 1000]",
    "number-certify-tab-fraction": "Assumption 1",
    "number-certify-newline-fraction": "Assumption 1",
    "number-scene-gains-underflow": "beyond what a float64 simulation can represent",
    "path-verify-trailing-slash": "trailing / names a directory",
    "path-check-proofs-empty": "--proofs must name a directory",
    "path-verify-junit-dev-full": "no space left",
    "name-certify-name-blank": "white space",
    "name-hunting-name-parent": "without directories",
    "path-verify-dev-zero": "not a regular file",
    "path-verify-symlink-loop": "symlink loop",
    "path-verify-name-too-long": "file name too long",
    "path-verify-through-a-file": "a component of the path is a file",
    "path-verify-huge-file": "bytes; at most 10000000 are accepted",
    "path-simulate-fifo": "not a regular file",
    "path-simulate-symlink-loop": "symlink loop",
    "path-certify-out-file": "exists and is not a directory",
    "path-certify-out-dev-null": "exists and is not a directory",
    "path-certify-out-symlink-loop": "symlink loop",
    "path-simulate-out-through-file": "a component of the path is a file",
    "path-check-write-proofs-file": "is not a directory",
    "number-certify-huge-integer": "at most 1000 are accepted",
    "number-certify-huge-exponent": "exponents beyond ±1000 are refused",
    "number-certify-arabic-digit": "ASCII digits only",
    "number-verify-arabic-digit": "ASCII digits",
    "number-scene-huge-integer": "an integer has more than 4300 digits",
    "number-scene-f-c-overflow": "outside the range of floating point",
    "structure-verify-deep-json-array": "nested too deeply",
    "structure-scene-deep-toml-table": "nested too deeply",
    "structure-scene-huge-samples": "at most 1000000 sample times",
    "structure-scene-huge-grid-points": "at most 10000000 is supported",
    "structure-crosscheck-huge-trajectories": "an integer from 1 to 1000000 (a bound on time and memory)",
    "name-certify-parent": "without directories (it is written inside --out)",
    "name-certify-control-char": "printable characters only",
    "usage-check-no-config-outside": "no configuration found",
    "encoding-ascii-assumption": "k_v*k_p > k_i; got 1 <= 4",
}


def _materialise(directory: Path, files: dict[str, object]) -> None:
    for name, content in files.items():
        path = directory / name
        if content == "FIFO":
            os.mkfifo(path)
        elif content == "LOOP":
            os.symlink(path, path)
        elif content == "SPARSE":
            with open(path, "wb") as handle:
                handle.truncate(3 * 1024**3)  # 3 GB, no disk used
        elif isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(str(content), encoding="utf-8")


FRESH_ENV = ("PYTHONIOENCODING", "PYTHONUTF8", "LANG", "LC_ALL")
"""Variables read at interpreter start-up: a case that sets one runs in a fresh interpreter, not a fork."""


@pytest.fixture(scope="module")
def server(fork_server):
    """The warm interpreter of tests/conftest.py, shared with tests/test_hostile_options.py (started once)."""
    return fork_server


_CASE_NUMBERS = itertools.count()


@pytest.fixture(scope="module")
def _case_root(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("cases")


@pytest.fixture
def case_dir(_case_root: Path) -> Path:
    """A new empty directory for one case, like ``tmp_path``, at a fraction of its cost.

    ``tmp_path`` numbers its directory by listing the ones its test's name already has (the name cut to 30 characters,
    the same for every case of a parametrized test): about 1 ms a case, a second over the thousand cases.
    """
    path = _case_root / str(next(_CASE_NUMBERS))
    path.mkdir()
    return path


def warm_jit(forks, directory: Path) -> None:
    """Compile the event kernel once, untimed, before any case is timed.

    numba caches its machine code on disk on first use (about 13 s on a fresh install, more on a loaded
    machine); whichever timed case first simulates would otherwise measure that one-time compile instead of
    how the command handles its input, and pass or fail by which test happened to run first.
    """
    result = forks.run(["hunting", "--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--f-s", "1.2", "--out",
                        str(directory / "out"), "--no-iss", "--no-simulation"], cwd=str(directory), env={},
                       timeout=600.0, memory=MEMORY)
    assert result.returncode == 0, result.stderr.decode(errors="replace")[-2000:]


def _special_files(args: list[str], directory: Path) -> dict[str, tuple[int, int, int]]:
    """Every non-regular file a case names or creates (devices, FIFOs, symlinks): its type, device and inode."""
    found = {}
    for candidate in [*args, *(str(p) for p in directory.iterdir())]:
        try:
            st = os.lstat(candidate)
        except (OSError, ValueError):
            continue
        if not (stat.S_ISREG(st.st_mode) or stat.S_ISDIR(st.st_mode)):
            found[candidate] = (stat.S_IFMT(st.st_mode), st.st_rdev, st.st_ino)
    return found


def run_case(argv: list[str], files: dict[str, object], env_extra: dict[str, str], directory: Path, server=None):
    """Run one case (in a fork of ``server`` unless it needs a fresh interpreter); check no special file was replaced."""
    from tests.forkserver import run_fresh

    _materialise(directory, files)
    cwd = str(directory)  # never the checkout: nothing a case writes can land in proofs/
    env = {}
    for key, value in env_extra.items():
        if key == "_cwd":
            cwd = value.format(d=directory)
        else:
            env[key] = value
    args = [a.format(d=directory) if "{d}" in a else a for a in argv]
    before = _special_files(args, directory)
    if server is None or any(key in FRESH_ENV for key in env):
        result = run_fresh(args, cwd=cwd, env=env, timeout=TIMEOUT, memory=MEMORY)
    else:
        result = server.run(args, cwd=cwd, env=env, timeout=TIMEOUT, memory=MEMORY)
    after = _special_files(args, directory)
    assert {k: before[k] for k in before} == {k: after.get(k) for k in before}, f"a special file was replaced: {before} → {after}"
    return result, result.seconds


def test_at_least_sixty_cases_in_every_category():
    ids = [c[0] for c in CASES]
    assert len(ids) == len(set(ids)) and len(ids) >= 60
    categories = {i.split("-")[0] for i in ids}
    assert categories == {"path", "number", "structure", "name", "usage", "encoding"}
    assert set(SAYS) <= set(ids)


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_bad_input_is_one_line_and_exit_2(case, case_dir, server):
    name, argv, files, env_extra = case
    proc, seconds = run_case(argv, files, env_extra, case_dir, server)
    err = proc.stderr.decode("utf-8", errors="replace")
    assert "Traceback" not in err, err[-3000:]
    assert proc.returncode == 2, (proc.returncode, err[-2000:], proc.stdout.decode(errors="replace")[-1000:])
    lines = err.strip().splitlines()
    assert len(lines) == 1, err[-2000:]
    assert "error" in lines[0]
    assert SAYS.get(name, "") in lines[0]
    assert seconds < BOUND


def test_certify_name_never_writes_outside_out(tmp_path, server):
    out = tmp_path / "a" / "b" / "out"
    proc, _ = run_case(["certify", *GAINS, "--out", str(out), "--name", "../../x"], {}, {}, tmp_path, server)
    assert proc.returncode == 2
    assert not any(p.name.startswith("x") for p in tmp_path.rglob("*"))


def test_huge_f_c_is_certified_and_its_report_has_no_inf(tmp_path, server):
    """f_c = 10⁹⁹⁹ is a valid gain (κ does not depend on f_c): certified, verified, and no 'inf' in the report."""
    proc, _ = run_case(["certify", "--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1e999", "--out", str(tmp_path),
                        "--name", "big"], {}, {}, tmp_path, server)
    assert proc.returncode == 0, proc.stderr.decode()
    report = (tmp_path / "big.md").read_text(encoding="utf-8")
    assert "inf" not in report.replace("info", "") and "beyond 1e308" in report
    proc, _ = run_case(["verify", str(tmp_path / "big.json")], {}, {}, tmp_path, server)
    assert proc.returncode == 0 and b"PROVED" in proc.stdout


def test_valid_certificate_with_5000_digit_denominators_verifies(tmp_path, server):
    """Exact arithmetic beyond Python's 4300-digit int/str limit: a valid certificate still verifies (exit 0)."""
    from fractions import Fraction

    from symbolic_friction._certify import dumps, load

    cert = load(CERT)
    # shrink c1 and c1_hat by a 5000-digit factor (integers past Python's 4300-digit str limit):
    # still a proof, with a larger kappa
    big = 10**5000 + 7
    import dataclasses
    from math import isqrt

    loose = dataclasses.replace(
        cert, c1=cert.c1 * Fraction(big - 1, big), c1_hat=cert.c1_hat * Fraction(big - 1, big),
        overshoot_bound=str(isqrt(int(cert.kappa_squared * 4)) + 2), provenance=None,
    )
    path = tmp_path / "long.json"
    path.write_text(dumps(loose), encoding="utf-8")
    assert len(json.loads(path.read_text())["constants"]["c1"]) > 10000
    back = load(path)  # the exact numbers survive the round trip through the file
    assert (back.c1, back.c1_hat, back.k4) == (loose.c1, loose.c1_hat, loose.k4)
    proc, _ = run_case(["verify", "-v", str(path)], {}, {}, tmp_path, server)
    assert proc.returncode == 0, proc.stderr.decode()[-2000:]
    assert b"PROVED" in proc.stdout and b"Traceback" not in proc.stderr
