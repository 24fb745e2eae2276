"""A user's own proofs in CI, end to end, outside this checkout.

In a throw-away git repository a user certifies two gain sets of their own
(one normalised, one given as physical parameters, with a label), names them
in ``[tool.symbolic-friction]`` of their ``pyproject.toml``, and runs the
pre-commit hook as ``.pre-commit-hooks.yaml`` declares it, with ``--junit-xml``
added as a project's ``args:`` would add it: everything passes, the JUnit XML
has one test case per obligation and certificate.  Editing one constant makes
the hook (``check``) fail, naming the inequality in its output and its JUnit
XML.  (``pre-commit try-repo`` would build a fresh environment with cvxpy and
numba from the network; the package is installed instead into a fresh virtual
environment, and the passing hook is its console script, run as the hook's
entry declares it with those arguments; where that environment cannot be
built, the entry runs from this checkout.)  The other command lines run in a
child of one warm interpreter (``tests/forkserver.py``: its own working
directory, the exit status as the interpreter maps it), not each in a fresh
interpreter that imports numpy, sympy and python-flint again; the failing hook
and the installed console script run as real processes, and the check of a
missing listed certificate, whose every assertion is on the certificates
section, runs that section alone, in this process.
"""

from __future__ import annotations

import json
import os
import re
import resource
import shlex
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.slow


def _hook_entry(hook_id: str) -> list[str]:
    """The hook's ``entry`` from ``.pre-commit-hooks.yaml``, with the console script run as ``python -m``."""
    text = (REPO / ".pre-commit-hooks.yaml").read_text(encoding="utf-8")
    block = re.split(rf"^- id: {re.escape(hook_id)}$", text, flags=re.MULTILINE)[1].split("\n- id:", 1)[0]
    entry = shlex.split(re.search(r"^\s*entry:\s*(.+)$", block, re.MULTILINE).group(1))
    assert entry[0] == "symbolic-friction"
    assert re.search(r"^\s*language:\s*python\s*$", block, re.MULTILINE)
    return [sys.executable, "-m", "symbolic_friction", *entry[1:]]


def _run(cmd: list[str], cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    env.pop("COLUMNS", None)
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=600)


def _cli(*args: str) -> list[str]:
    return [sys.executable, "-m", "symbolic_friction", *args]


@pytest.fixture(scope="module")
def forks():
    """The warm interpreter of this module's command lines (one start instead of one per command line)."""
    from tests.forkserver import ForkServer

    server = ForkServer()
    yield server
    server.close()


def _forked(forks, argv: list[str], cwd: Path) -> subprocess.CompletedProcess:
    """``symbolic-friction ARGV`` (``argv`` as :func:`_cli` or :func:`_hook_entry` give it) in a forked child, as
    :func:`_run` runs it in a fresh interpreter: working directory ``cwd``, no address-space limit, text output."""
    assert argv[:3] == [sys.executable, "-m", "symbolic_friction"]
    run = forks.run(argv[3:], cwd=str(cwd), timeout=600, memory=resource.RLIM_INFINITY)
    return subprocess.CompletedProcess(argv, run.returncode, run.stdout.decode(), run.stderr.decode())


@pytest.fixture(scope="module")
def project(tmp_path_factory, forks):
    root = tmp_path_factory.mktemp("user-project")
    subprocess.run(["git", "init", "-q", str(root)], check=True)
    one = _forked(forks, _cli("certify", "--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--mode", "feasible",
                    "--out", "proofs", "--name", "slow_axis", "--label", "slow axis"), root)
    assert one.returncode == 0, one.stderr
    two = _forked(forks, _cli("certify", "--m", "2", "--k-p-bar", "1.32", "--k-i-bar", "0.16", "--k-d-bar", "2.5",
                    "--alpha-v", "0.5", "--f-c-bar", "2", "--mode", "feasible", "--out", "proofs",
                    "--name", "fast_axis", "--label", "fast axis, 2 kg"), root)
    assert two.returncode == 0, two.stderr
    (root / "pyproject.toml").write_text(
        '[project]\nname = "my-controller"\nversion = "0"\n\n'
        '[tool.symbolic-friction]\nproofs = "proofs"\ncertificates = ["slow_axis.json", "fast_axis.json"]\n',
        encoding="utf-8",
    )
    subprocess.run(["git", "-C", str(root), "add", "."], check=True)
    subprocess.run(["git", "-C", str(root), "-c", "user.name=u", "-c", "user.email=u@example.org", "commit", "-qm", "proofs"],
                   check=True)
    return root


def test_certificates_keep_physical_gains_and_label(project):
    data = json.loads((project / "proofs" / "fast_axis.json").read_text(encoding="utf-8"))
    assert data["physical"] == {"m": "2", "k_p_bar": "33/25", "k_i_bar": "4/25", "k_d_bar": "5/2", "alpha_v": "1/2",
                                "f_c_bar": "2"}
    assert data["parameters"] == {"k_p": "33/50", "k_i": "2/25", "k_v": "3/2", "f_c": "1"}
    assert data["provenance"]["label"] == "fast axis, 2 kg"


def test_hook_and_check_pass_then_fail_on_an_edited_constant(project, passing_hook, forks, tmp_path):
    # One run serves as the hook, as `check --junit-xml` and as the installed copy's console script: the hook's entry
    # with the arguments a project's `args: [--junit-xml, FILE]` appends (:func:`passing_hook`)
    hook, report = passing_hook
    assert hook.returncode == 0, hook.stdout + hook.stderr
    assert hook.stdout.strip().splitlines()[-1].startswith("check: PASSED")
    assert "2 of 2 certificates proved exactly, 2 of 2 up to date" in hook.stdout
    root = ET.parse(report).getroot()
    assert root.tag == "testsuites" and root.get("failures") == "0" and root.get("errors") == "0"
    cases = root.findall("./testsuite/testcase")
    assert int(root.get("tests")) == len(cases)
    by_class: dict[str, list[str]] = {}
    for case in cases:
        by_class.setdefault(case.get("classname"), []).append(case.get("name"))
    assert by_class["check.certificates"] == [str(Path("proofs") / "slow_axis.json"), str(Path("proofs") / "fast_axis.json")]
    assert "lemma3.hatV_derivative" in by_class["check.obligations"] and len(by_class["check.obligations"]) >= 30
    assert "check.report" not in by_class  # the user's project keeps no obligations.md

    verify_hook = _forked(forks, _hook_entry("symbolic-friction-verify") + ["proofs/slow_axis.json", "proofs/fast_axis.json"],
                          project)
    assert verify_hook.returncode == 0, verify_hook.stderr

    # edit one constant: k3 = k2 breaks Lemma 3's condition k3 > k2
    path = project / "proofs" / "slow_axis.json"
    original = path.read_text(encoding="utf-8")
    data = json.loads(original)
    data["constants"]["k3"] = data["constants"]["k2"]
    path.write_text(json.dumps(data, indent=2, sort_keys=True) + "\n", encoding="utf-8")
    report = tmp_path / "check.xml"  # the failing run writes its own
    try:
        # a real process: the exit status pre-commit sees from a failing hook is the interpreter's own
        hook = _run(_hook_entry("symbolic-friction-check") + ["--junit-xml", str(report)], project)
        assert hook.returncode == 1
        assert "k3 > k2" in hook.stdout and "slow_axis.json" in hook.stdout
        assert hook.stdout.strip().splitlines()[-1].startswith("check: FAILED — 1 of 2 certificates proved exactly")
        failed = [c for c in ET.parse(report).getroot().iter("testcase") if c.find("failure") is not None]
        # both verifiers refuse the edited file: the main one in the certificates section, the independent one in its own
        assert [(c.get("classname"), c.get("name")) for c in failed] == [
            ("check.certificates", str(Path("proofs") / "slow_axis.json")), ("check.independent", str(Path("proofs") / "slow_axis.json"))]
        assert "k3 > k2" in failed[0].find("failure").text and "k3 > k2" in failed[1].find("failure").text
        verify_hook = _forked(forks, _hook_entry("symbolic-friction-verify") + ["proofs/slow_axis.json"], project)
        assert verify_hook.returncode == 1 and "k3 > k2" in verify_hook.stdout
    finally:
        path.write_text(original, encoding="utf-8")


def test_a_listed_certificate_that_is_missing_fails(project, monkeypatch, capsys):
    from symbolic_friction._cli import check as check_command
    from symbolic_friction._cli.main import main

    # Everything asserted here (the rows, the notes on the missing and the unlisted file, the failure) is the
    # certificates section's, and the hook test shows the other sections passing in this project: the run is that
    # section's, in this process
    monkeypatch.setattr(check_command, "SECTIONS", [check_command.certificates_section])
    monkeypatch.chdir(project)
    (project / "symbolic-friction.toml").write_text('certificates = ["slow_axis.json", "gone.json"]\n', encoding="utf-8")
    try:
        returncode = main(["check", "--json"])
        stdout, stderr = capsys.readouterr()
        assert returncode == 1
        payload = json.loads(stdout)
        assert [(Path(c["file"]).name, c["proved"]) for c in payload["certificates"]] == [("slow_axis.json", True), ("gone.json", False)]
        assert "gone.json: missing" in stderr
        assert "fast_axis.json" in stderr and "not listed" in stderr  # not checked, but said
    finally:
        (project / "symbolic-friction.toml").unlink()


def test_without_configuration_outside_the_checkout_check_refuses(tmp_path):
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    check = _run(_cli("check"), tmp_path)
    assert check.returncode == 2
    assert check.stderr.count("\n") == 1 and "no configuration found" in check.stderr


@pytest.fixture(scope="module")
def installed(project, tmp_path_factory):
    """The package installed (not imported from this checkout) into a fresh virtual environment: the directory of
    its console scripts and the environment to run them in, or ``None`` and why it could not be built.

    The dependencies come from the running environment through a ``.pth`` file; the build backend is fetched by
    pip.
    """
    import shutil
    import sysconfig

    tmp_path = tmp_path_factory.mktemp("installed")
    source = tmp_path / "src"
    source.mkdir()
    shutil.copytree(REPO / "symbolic_friction", source / "symbolic_friction",
                    ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(REPO / name, source / name)
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    purelib = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                             capture_output=True, text=True, check=True).stdout.strip()
    Path(purelib, "dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n", encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "COLUMNS")}
    install = subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "--quiet", "--no-deps",
                              str(source)], capture_output=True, text=True, env=env, timeout=600)
    if install.returncode != 0:
        return None, f"could not build the package here: {install.stderr.strip().splitlines()[-1:]}"
    where = subprocess.run([str(python), "-c", "import symbolic_friction; print(symbolic_friction.__file__)"],
                           capture_output=True, text=True, env=env, cwd=project, check=True).stdout
    assert where.startswith(purelib)  # the installed copy, not this checkout
    return venv / "bin", env


@pytest.fixture(scope="module")
def passing_hook(project, installed, forks, tmp_path_factory):
    """The check hook in the user's repository before any edit, with the arguments a project's ``args:`` appends
    (``--junit-xml FILE``): the installed copy's console script, a real process, run as the hook's entry declares
    it; this checkout's, forked, where the virtual environment could not be built.  The completed process and the
    JUnit file."""
    report = tmp_path_factory.mktemp("junit") / "check.xml"
    argv = _hook_entry("symbolic-friction-check") + ["--junit-xml", str(report)]
    scripts, env = installed
    if scripts is None:
        return _forked(forks, argv, project), report
    hook = subprocess.run([str(scripts / "symbolic-friction"), *argv[3:]], capture_output=True, text=True, env=env,
                          cwd=project, timeout=600)
    return hook, report


def test_in_a_fresh_virtual_environment_the_installed_hook_passes(project, installed, passing_hook):
    """The package installed (not imported from this checkout) into a fresh virtual environment: its console
    script, run as the hook's entry says (the passing hook's run), passes in the user's repository (the shipped
    JSON Schema and the configuration search work from an installed copy), and so does the verify hook's
    (skipped if the package cannot be built here)."""
    scripts, env = installed
    if scripts is None:
        pytest.skip(env)
    hook, _ = passing_hook
    assert hook.returncode == 0, hook.stdout + hook.stderr
    assert hook.stdout.strip().splitlines()[-1].startswith("check: PASSED")
    verify = subprocess.run([str(scripts / "symbolic-friction"), *_hook_entry("symbolic-friction-verify")[3:],
                             "proofs/fast_axis.json"], capture_output=True, text=True, env=env, cwd=project)
    assert verify.returncode == 0 and "PROVED" in verify.stdout, verify.stderr


def _hook_files(hook_id: str) -> re.Pattern:
    text = (REPO / ".pre-commit-hooks.yaml").read_text(encoding="utf-8")
    block = re.split(rf"^- id: {re.escape(hook_id)}$", text, flags=re.MULTILINE)[1].split("\n- id:", 1)[0]
    return re.compile(re.search(r"^\s*files:\s*'(.+)'\s*$", block, re.MULTILINE).group(1))


def test_hooks_run_when_a_certificate_or_the_configuration_changes():
    check, verify = _hook_files("symbolic-friction-check"), _hook_files("symbolic-friction-verify")
    for path in ("proofs/slow_axis.json", "proofs/slow_axis.md", "pyproject.toml", "sub/symbolic-friction.toml"):
        assert check.search(path), path
    for path in ("README.md", "src/data.json", "package.json"):
        assert not check.search(path) and not verify.search(path), path
    assert verify.search("proofs/slow_axis.json") and not verify.search("proofs/slow_axis.md")
