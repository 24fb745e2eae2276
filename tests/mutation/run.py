"""Whole-pipeline mutation testing: is every single-point error caught by ``check`` or ``verify`` alone?

Usage (from the repository root)::

    python tests/mutation/run.py                      # every mutant, one at a time
    python tests/mutation/run.py --jobs 2 --out tests/mutation/report.md
    python tests/mutation/run.py --fast               # the subset the test suite runs
    python tests/mutation/run.py --only V.at_rest R.strict

For each mutant of :data:`mutants.MUTANTS` the package sources
(``symbolic_friction/``, ``proofs/``, ``pyproject.toml``: the files git
lists there, tracked or untracked-but-not-ignored) are copied to a fresh
temporary directory, the one snippet is replaced, and, with that directory
as working directory and ``PYTHONPATH``:

1. ``python -m symbolic_friction check --write`` regenerates ``proofs/`` first,
   so that a committed report going stale can never be what catches a mutant;
2. ``python -m symbolic_friction check --json`` must fail: the failing
   obligations, certificates and self-test rows are recorded;
3. ``python -m symbolic_friction verify proofs/*.json``: its ``FAILED`` lines
   are recorded.

A mutant is *caught* when step 2 or 3 exits non-zero.  A mutant that both
miss and that names tests (``Mutant.tests``) is then caught by the test
suite if those tests fail on the mutated copy (``tests/`` is copied too and
``python -m pytest -n 0`` runs them there); the table says which.  The unmutated
baseline is run the same way first and must pass both (otherwise every
"caught" would be vacuous).  A mutant whose snippet does not occur exactly
once is an error, never skipped.  The table is printed (and written
atomically with ``--out``); the exit status is 0 only if every mutant is
caught or listed as equivalent with its proof.

The test suite's fast subset (``run_one(..., regenerate=False)``) first tries
a cheaper route to the same verdict: one ``check --json --no-certificates`` on
the mutated copy *as committed*, with only those of its failures counted that
no file under ``proofs/`` can cause — an obligation that does not hold
(derived from the code alone) or a self-check row that fails (the verifiers on
the certificates shipped inside the package); for a mutant, ``check`` decides
only those two sections (:data:`COUNTED`), the baseline runs the command whole.  A stale or regenerated file can
then never be what catches the mutant, which is what step 1 is there to
ensure; a mutant not caught that way is decided by steps 1-3 as above.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from tests.mutation.mutants import FAST, MUTANTS, Mutant  # noqa: E402
from tests.mutation.warm import Warm  # noqa: E402

TIMEOUT = 300.0
SOURCES = ("symbolic_friction", "proofs", "pyproject.toml")
TESTS = ("tests",)


class DoesNotApply(ValueError):
    """A mutant's snippet does not occur exactly once in its file."""


@dataclass(frozen=True)
class Outcome:
    """What ``check`` and ``verify`` said about one mutant (or the baseline)."""

    mutant: Mutant | None
    check_rc: int | None
    verify_rc: int | None
    caught_by: str
    seconds: float
    error: str = ""
    tests_rc: int | None = None
    regenerated: bool = True
    """False: decided by the one ``check --no-certificates`` on the copy as committed (:func:`_check_sources`)."""

    @property
    def caught(self) -> bool:
        return not self.error and ((self.check_rc or 0) != 0 or (self.verify_rc or 0) != 0 or (self.tests_rc or 0) != 0)

    @property
    def verdict(self) -> str:
        if self.error:
            return self.error
        if self.mutant is not None and self.mutant.equivalent:
            return "equivalent" if not self.caught else "caught (listed as equivalent)"
        return "caught" if self.caught else "SURVIVED"

    @property
    def ok(self) -> bool:
        return not self.error and (self.caught or bool(self.mutant and self.mutant.equivalent))


def source_files(root: Path = ROOT, *, under: tuple[str, ...] = SOURCES) -> list[str]:
    """The files to copy: tracked and untracked-but-not-ignored, under :data:`SOURCES` (or ``under``)."""
    listed = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "--", *under],
        cwd=root, capture_output=True, text=True, check=True,
    ).stdout.splitlines()
    # proofs/smt/ is left out: check --write then exports no SMT-LIB (it writes them only where the directory
    # exists), and check without --smt never reads them, so no mutant can be caught or missed through them
    return sorted({f for f in listed if (root / f).is_file() and not f.startswith("proofs/smt/")})


def apply(text: str, mutant: Mutant) -> str:
    """``text`` with the mutant's one snippet replaced.

    Raises
    ------
    DoesNotApply
        If ``mutant.old`` occurs zero times or more than once.
    """
    count = text.count(mutant.old)
    if count != 1:
        raise DoesNotApply(f"mutant {mutant.id}: its snippet occurs {count} times in {mutant.path}, expected once")
    return text.replace(mutant.old, mutant.new)


def line_of(mutant: Mutant, root: Path = ROOT) -> int:
    text = (root / mutant.path).read_text(encoding="utf-8")
    return text[: text.find(mutant.old)].count("\n") + 1


def _copy_tree(dest: Path, files: list[str], root: Path) -> None:
    for rel in files:
        target = dest / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(root / rel, target)  # its modification time too: the bytecode below is checked against it
        if rel.endswith(".py"):
            _copy_bytecode(root / rel, target)


def _copy_bytecode(source: Path, target: Path) -> None:
    """The checkout's compiled ``source`` (``__pycache__``), if any, beside ``target``.

    Each run imports the package from the copy under ``PYTHONDONTWRITEBYTECODE``, so without it every run (and
    ``check``'s forked child) compiles every module it imports again (measured: ``check``'s imports take 1.1 CPU-s
    from source, 0.9 from bytecode, in each process).  The
    interpreter uses the file only while it matches the source's modification time and size (else it compiles
    the source, as without it); the mutated file's is removed outright (:func:`_mutated_copy`).
    """
    cached = Path(importlib.util.cache_from_source(str(source)))
    if cached.is_file():
        copied = Path(importlib.util.cache_from_source(str(target)))
        copied.parent.mkdir(exist_ok=True)
        shutil.copyfile(cached, copied)


def _run(args: list[str], cwd: Path, *, sections: tuple[str, ...] | None = None,
         warm: Warm | None = None) -> subprocess.CompletedProcess:
    """``python -m symbolic_friction ARGS`` on the copy ``cwd``; with ``sections``, ``check`` runs only those of its
    :data:`~symbolic_friction._cli.check.SECTIONS` (by function name, all of them or the run fails); with ``warm``,
    in a child forked by that warm interpreter (:mod:`tests.mutation.warm`) instead of a new one."""
    env = dict(os.environ, PYTHONPATH=str(cwd), PYTHONDONTWRITEBYTECODE="1")
    command = ["-m", "symbolic_friction"]
    if sections is not None:
        code = ("from symbolic_friction._cli import check\n"
                f"kept = [s for s in check.SECTIONS if s.__name__ in {sections!r}]\n"
                f"assert len(kept) == {len(sections)}, kept\n"
                "check.SECTIONS[:] = kept\n"
                "from symbolic_friction._cli.main import entry_point\nentry_point()")
        command = ["-c", code]
    if warm is not None:
        return warm.run([*command, *args], cwd=cwd, timeout=TIMEOUT)
    return subprocess.run([sys.executable, *command, *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=TIMEOUT)


def _run_tests(tests: tuple[str, ...], cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(cwd), PYTHONDONTWRITEBYTECODE="1")
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-x", "-n", "0", "-p", "no:cacheprovider", *tests],
                          cwd=cwd, env=env, capture_output=True, text=True, timeout=TIMEOUT)


def _failed_tests(output: str) -> list[str]:
    return [line.split(" ")[1] for line in output.splitlines() if line.startswith(("FAILED ", "ERROR "))]


def _what_failed(check: subprocess.CompletedProcess, verify: subprocess.CompletedProcess) -> str:
    parts: list[str] = []
    try:
        payload = json.loads(check.stdout)
    except json.JSONDecodeError:
        payload = None
    if payload is not None:
        parts += [o["id"] for o in payload.get("obligations", []) if o.get("status") != "holds"]
        parts += [f"certificate {Path(c['file']).name}" for c in payload.get("certificates", []) if not c.get("proved")]
        parts += [f"self-test ({r['case']}) {r['variant']}" for r in payload.get("crosscheck_self_test", []) if not r.get("ok")]
        if not parts and check.returncode:
            last = check.stderr.strip().splitlines()[-1:] or ["?"]
            parts.append(last[0][:90])
    elif check.returncode:
        last = (check.stderr or check.stdout).strip().splitlines()[-1:] or ["?"]
        parts.append("check crashed: " + last[0][:80])
    out = []
    if check.returncode:
        out.append("check: " + ", ".join(dict.fromkeys(parts)))
    if verify.returncode:
        failed = [line.split(":")[0].replace("FAILED ", "") for line in verify.stdout.splitlines() if line.startswith("FAILED")]
        out.append("verify: " + (", ".join(Path(f).name for f in failed) or f"exit {verify.returncode}"))
    return "; ".join(out) or "-"


SOURCES_ONLY = ["check", "--json", "--no-certificates"]
"""The command of :func:`_check_sources` (the certificates section is left out: its verdict reads ``proofs/``)."""

COUNTED = ("obligations_section", "self_check_section")
"""The sections of ``check`` that decide the payload's ``obligations`` and ``self_check``: all that
:func:`_failures_without_proofs` reads of a mutant's run, so a mutant's run decides only these (the cross-check
self-test and the independent checker, which read ``proofs/``, would be decided and then ignored)."""


def _failures_without_proofs(payload: dict) -> list[str]:
    """The failures of ``check --json`` that no file under ``proofs/`` can cause.

    The obligations are derived from the code alone (none reads ``proofs/``) and the self-check runs the verifiers
    on the certificates shipped inside the package; the other sections (certificates, the cross-check self-test,
    the independent checker, ``obligations.md``) read ``proofs/`` and are not counted here.
    """
    failed = [o["id"] for o in payload.get("obligations", []) if o.get("status") != "holds"]
    failed += [f"self-check {r.get('file') or r.get('case')}" for r in payload.get("self_check", []) if not r.get("ok")]
    return failed


def _mutated_copy(dest: Path, mutant: Mutant | None, files: list[str], root: Path) -> bool:
    """Copy ``files`` of ``root`` to ``dest`` and apply ``mutant`` there; False if it does not apply."""
    _copy_tree(dest, files, root)
    if mutant is not None:
        path = dest / mutant.path
        try:
            path.write_text(apply(path.read_text(encoding="utf-8"), mutant), encoding="utf-8")
        except DoesNotApply:
            return False
        # the unmutated module's bytecode: never run in its place, whatever its invalidation mode
        Path(importlib.util.cache_from_source(str(path))).unlink(missing_ok=True)
    return True


def _check_sources(mutant: Mutant | None, files: list[str], root: Path, warm: Warm | None = None) -> Outcome | None:
    """One ``check --json --no-certificates`` on a mutated copy as committed; ``None`` when it does not decide.

    The baseline (``mutant=None``) is returned as it ran (its ``check_rc`` must be 0: the very command each mutant
    must fail passes on the unmutated copy, whole; a mutant's run decides only the :data:`COUNTED` sections).  A mutant
    is returned as caught only if :func:`_failures_without_proofs` names something, so a committed file going stale
    (or being regenerated) can never be what catches it; otherwise (or if the output is not JSON, or on a timeout)
    ``None``: the caller runs the full pipeline.  ``verify`` is not run (its verdict reads ``proofs/``).  ``warm``:
    the run is a child of that warm interpreter.
    """
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="sf-mutant-") as tmp:
        dest = Path(tmp)
        if not _mutated_copy(dest, mutant, files, root):
            return Outcome(mutant, None, None, "-", time.perf_counter() - start, "does not apply", regenerated=False)
        try:
            check = _run(SOURCES_ONLY, dest, sections=None if mutant is None else COUNTED, warm=warm)
        except subprocess.TimeoutExpired:
            return None
    try:
        payload = json.loads(check.stdout)
    except json.JSONDecodeError:
        return None
    failed = _failures_without_proofs(payload)
    seconds = time.perf_counter() - start
    if mutant is None:
        last = check.stderr.strip().splitlines()[-1:] or ["?"]
        caught_by = "-" if not check.returncode else "check: " + ", ".join(failed or [last[0][:90]])
        return Outcome(None, check.returncode, None, caught_by, seconds, regenerated=False)
    if not failed or not check.returncode:
        return None
    caught_by = "check: " + ", ".join(dict.fromkeys(failed))
    return Outcome(mutant, check.returncode, None, caught_by, seconds, regenerated=False)


def run_one(mutant: Mutant | None, files: list[str], root: Path = ROOT, *, regenerate: bool = True,
            warm: Warm | None = None) -> Outcome:
    """Apply ``mutant`` (``None``: the baseline) to a fresh copy and run ``check --write``, ``check``, ``verify``.

    ``regenerate=False`` tries :func:`_check_sources` first (one ``check``, no ``--write``; in a child of ``warm`` if
    given) and runs the three steps only when that does not decide; the outcome's ``regenerated`` says which decided.
    """
    if not regenerate:
        quick = _check_sources(mutant, files, root, warm)
        if quick is not None:
            return quick
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="sf-mutant-") as tmp:
        dest = Path(tmp)
        if not _mutated_copy(dest, mutant, files, root):
            return Outcome(mutant, None, None, "-", time.perf_counter() - start, "does not apply")
        try:
            _run(["check", "--write"], dest)
            check = _run(["check", "--json"], dest)
            certs = sorted(str(p.relative_to(dest)) for p in (dest / "proofs").glob("*.json"))
            verify = _run(["verify", *certs], dest)
            tests = None
            if mutant is not None and mutant.tests and not (check.returncode or verify.returncode):
                _copy_tree(dest, source_files(root, under=TESTS), root)
                tests = _run_tests(mutant.tests, dest)
        except subprocess.TimeoutExpired:
            return Outcome(mutant, None, None, "-", time.perf_counter() - start, "timeout")
        caught_by = _what_failed(check, verify)
        if tests is not None and tests.returncode not in (0, 1):
            # 2-5: interrupted, internal error, usage error, nothing collected: never a catch
            return Outcome(mutant, check.returncode, verify.returncode, "-", time.perf_counter() - start,
                           f"tests could not run (pytest exit {tests.returncode})")
        if tests is not None and tests.returncode:
            failed = _failed_tests(tests.stdout) or [f"exit {tests.returncode}"]
            caught_by = "tests: " + ", ".join(failed)
        return Outcome(mutant, check.returncode, verify.returncode, caught_by, time.perf_counter() - start,
                       tests_rc=None if tests is None else tests.returncode)


def table(outcomes: list[Outcome], root: Path = ROOT) -> str:
    rows = [
        "| id | target | where | mutation | caught by | verdict |",
        "|---|---|---|---|---|---|",
    ]
    for o in outcomes:
        m = o.mutant
        assert m is not None
        where = f"{m.path}:{line_of(m, root)}" if o.error != "does not apply" else m.path
        verdict = o.verdict if not (m.equivalent and not o.caught) else f"equivalent: {m.equivalent}"
        rows.append(f"| {m.id} | {m.target} | `{where}` | {m.description} | {o.caught_by} | {verdict} |")
    caught = sum(o.caught for o in outcomes)
    equivalent = sum(bool(o.mutant and o.mutant.equivalent) and not o.caught and not o.error for o in outcomes)
    survived = sum(o.verdict == "SURVIVED" for o in outcomes)
    errors = sum(bool(o.error) for o in outcomes)
    rows.append("")
    rows.append(f"{len(outcomes)} mutants: {caught} caught, {equivalent} equivalent, {survived} survived, {errors} errors")
    return "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="+", metavar="ID", help="run only these mutants")
    parser.add_argument("--fast", action="store_true", help="run only the fast subset (the default test run's)")
    parser.add_argument("--jobs", type=int, default=1, help="mutants run in parallel (default 1)")
    parser.add_argument("--out", metavar="FILE", help="also write the table to FILE (atomically)")
    args = parser.parse_args(argv)
    selected = list(MUTANTS)
    if args.fast:
        selected = [m for m in MUTANTS if m.id in FAST]
    if args.only:
        unknown = set(args.only) - {m.id for m in MUTANTS}
        if unknown:
            parser.error(f"unknown mutant id(s): {', '.join(sorted(unknown))}")
        selected = [m for m in MUTANTS if m.id in args.only]
    files = source_files()
    base = run_one(None, files)
    if base.check_rc != 0 or base.verify_rc != 0:
        print(f"baseline fails (check exit {base.check_rc}, verify exit {base.verify_rc}): {base.caught_by}; "
              "every 'caught' would be vacuous, so nothing was run", file=sys.stderr)
        return 2
    print(f"baseline: check and verify pass ({base.seconds:.0f} s); {len(selected)} mutants", file=sys.stderr, flush=True)
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        outcomes = list(pool.map(lambda m: run_one(m, files), selected))
    text = table(outcomes)
    print(text)
    if args.out:
        from symbolic_friction._infra.io import atomic_write_text

        atomic_write_text(Path(args.out), text + "\n")
    return 0 if all(o.ok for o in outcomes) else 1


if __name__ == "__main__":
    sys.exit(main())
