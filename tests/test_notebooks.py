"""The notebooks in ``notebooks/``, executed for real with a Jupyter kernel.

Each notebook is stored *executed* (outputs and figures included) so that it
reads top to bottom on a code host. The tests run every notebook with an
IPython kernel (nbclient), within a time limit, and compare the fresh text
outputs with the stored ones: a notebook whose stored outputs are stale fails.
The kernels are forked from one warm interpreter (``tests/kernel_forks.py``:
the kernel's start-up and the libraries several notebooks import are imported
once, about 1 to 1.6 s of CPU less per notebook); one test holds a forked
kernel to one started as its kernel spec says.
Timings and memory addresses are ignored; images are not compared (they
depend on the matplotlib version), but every stored figure must be there.

Regenerate the stored outputs after a change::

    python -m tests.test_notebooks --write            # every notebook
    python -m tests.test_notebooks --write 02         # those whose name starts with 02
"""

from __future__ import annotations

import argparse
import copy
import difflib
import re
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK_DIR = ROOT / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))
CELL_TIMEOUT = 300  # seconds for one cell (nbclient's timeout)
TIME_LIMIT = 240.0  # seconds for one whole notebook, kernel start included

_TEXT_TYPES = ("text/plain", "text/latex", "text/markdown")
_ADDRESS = re.compile(r"\b0x[0-9a-fA-F]{6,}\b")
_TIME = re.compile(r"(?<![\w.])\d+(?:\.\d+)?(?:e[-+]?\d+)?\s?(?:s|ms|µs|us|seconds)\b(?!\w)")


def normalise(text: str) -> str:
    """``text`` with memory addresses and durations replaced by placeholders."""
    return _TIME.sub("<time>", _ADDRESS.sub("0x…", text))


def text_outputs(nb) -> list[list[str]]:
    """Per code cell, its outputs as normalised text (streams, rich text, errors)."""
    cells = []
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        texts = []
        stream = None  # consecutive writes to one stream are split by flush timing: join them
        for out in cell.get("outputs", []):
            if out.output_type == "stream":
                if stream == out.name:
                    texts[-1] += normalise(out.text)
                else:
                    texts.append(f"{out.name}: " + normalise(out.text))
                stream = out.name
                continue
            stream = None
            if out.output_type in ("execute_result", "display_data"):
                for mime in _TEXT_TYPES:
                    if mime in out.data:
                        texts.append(f"{mime}: " + normalise(out.data[mime]))
            elif out.output_type == "error":
                texts.append(f"error: {out.ename}: {normalise(out.evalue)}")
        cells.append(texts)
    return cells


def image_count(nb) -> int:
    return sum(
        "image/png" in out.get("data", {})
        for cell in nb.cells if cell.cell_type == "code"
        for out in cell.get("outputs", [])
    )


def differences(stored, fresh) -> list[str]:
    """Where the text outputs of ``fresh`` differ from ``stored`` (empty: up to date)."""
    a, b = text_outputs(stored), text_outputs(fresh)
    if len(a) != len(b):
        return [f"{len(a)} code cells stored, {len(b)} executed"]
    found = []
    for n, (x, y) in enumerate(zip(a, b), 1):
        if x != y:
            diff = difflib.unified_diff("\n".join(x).splitlines(), "\n".join(y).splitlines(), "stored", "fresh", lineterm="", n=1)
            found.append(f"code cell {n}:\n" + "\n".join(list(diff)[:40]))
    if image_count(stored) != image_count(fresh):
        found.append(f"{image_count(stored)} figures stored, {image_count(fresh)} produced")
    return found


def run_kernel(nb, cwd: Path, forks=None, **options) -> None:
    """Execute ``nb`` in place in a new IPython kernel working in ``cwd``: started as its kernel spec says, or forked by
    ``forks`` (a :class:`tests.kernel_forks.KernelForks`)."""
    from nbclient import NotebookClient

    if forks is not None:
        from tests.kernel_forks import ForkedKernelManager

        options["kernel_manager_class"] = type("KernelManager", (ForkedKernelManager,), {"forks": forks})
    # the kernel is killed once the last cell has answered ("immediate"): every output is in by then, and a graceful
    # shutdown waited 0.5 to 3 s per notebook for the kernel to tidy up (measured), which nothing here looks at
    NotebookClient(
        nb, timeout=CELL_TIMEOUT, kernel_name="python3", resources={"metadata": {"path": str(cwd)}},
        shutdown_kernel="immediate", **options,
    ).execute()


def execute(path: Path, forks=None):
    """Run ``path`` top to bottom in a new IPython kernel (:func:`run_kernel`); returns the stored and the executed
    notebook and the seconds taken."""
    import nbformat

    nb = nbformat.read(path, as_version=4)
    fresh = copy.deepcopy(nb)
    start = time.perf_counter()
    run_kernel(fresh, path.parent, forks)
    return nb, fresh, time.perf_counter() - start


@pytest.fixture(scope="module")
def kernel_forks():
    """The warm interpreter the notebooks' kernels are forked from (started on first use).

    Its kernels (and a kernel started as its spec says, in this module) import the package from this checkout, as
    every other test does (``PYTHONPATH``): after a non-editable install the installed copy is a second tree of the
    same files, for which numba would compile the simulation kernel a second time (about 13 s of CPU on a fresh
    install, measured in ``.ci/run``)."""
    import os

    from tests.kernel_forks import KernelForks

    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("PYTHONPATH", os.pathsep.join(filter(None, (str(ROOT), os.environ.get("PYTHONPATH")))))
        forks = KernelForks()
        yield forks
        forks.close()


def test_there_are_five_notebooks():
    assert [p.name[:3] for p in NOTEBOOKS] == ["01_", "02_", "03_", "04_", "05_"]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_stored_notebook_is_executed(path):
    import nbformat

    nb = nbformat.read(path, as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code, f"{path.name} has no code cells"
    unrun = [n for n, c in enumerate(code, 1) if c.get("execution_count") is None]
    assert not unrun, f"{path.name}: code cells {unrun} are stored without being executed"
    assert sum(bool(c.get("outputs")) for c in code) >= len(code) // 2, f"{path.name} is stored nearly without outputs"
    errors = [n for n, c in enumerate(code, 1) for o in c.get("outputs", []) if o.output_type == "error"]
    assert not errors, f"{path.name}: code cells {errors} store an error"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_uses_only_the_public_api(path):
    import nbformat

    nb = nbformat.read(path, as_version=4)
    for n, cell in enumerate((c for c in nb.cells if c.cell_type == "code"), 1):
        private = re.findall(r"symbolic_friction\.(_\w+)|from symbolic_friction\S* import .*\b(_\w+)", cell.source)
        assert not private, f"{path.name}, code cell {n} reaches into a private name: {private}"


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_executes_and_its_stored_outputs_are_current(path, kernel_forks):
    stored, fresh, seconds = execute(path, kernel_forks)
    assert seconds <= TIME_LIMIT, f"{path.name} took {seconds:.0f} s (limit {TIME_LIMIT:.0f} s)"
    stale = differences(stored, fresh)
    assert not stale, (
        f"{path.name}: the stored outputs are stale (regenerate with `python -m tests.test_notebooks --write`):\n"
        + "\n".join(stale)
    )


# What a notebook could see of how its kernel was started: the process, its paths and environment (MPLBACKEND, the
# inline back end ipykernel sets, among them), the modules whose import changes what a notebook does (not imported
# before the notebook imports them), the display machinery, an error's report.
_PROBE_CELLS = [
    "import os, sys\nprint(os.getcwd(), sys.executable, sys.argv[0], len(sys.argv), sys.path, __name__)",
    "print([name for name in ('matplotlib', 'numba') if name in sys.modules])",
    "print(sorted(os.environ.items()))",
    (
        "from ipykernel.kernelapp import IPKernelApp\n"
        "print(os.getpgid(0) == os.getpid(), IPKernelApp.instance().parent_handle == int(os.environ['JPY_PARENT_PID']))\n"
        "print(sys.flags, sys.stdin.__class__.__name__, sys.stdout.__class__.__name__)"
    ),
    "from IPython.display import Markdown, display\ndisplay(Markdown('*shown*'))\nget_ipython().__class__.__name__",
    "1 / 0",
]


def test_a_forked_kernel_is_the_kernel_its_spec_starts(kernel_forks, tmp_path):
    """The notebooks run in forked kernels: what a notebook sees is what a kernel started as a subprocess shows."""
    import nbformat

    outputs = []
    for forks in (None, kernel_forks):
        nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(code) for code in _PROBE_CELLS])
        run_kernel(nb, tmp_path, forks, allow_errors=True)
        outputs.append(text_outputs(nb))
    started, forked = outputs
    assert forked == started
    assert started[-1] == ["error: ZeroDivisionError: division by zero"]
    assert started[0][0].startswith(f"stdout: {tmp_path} {sys.executable} ")
    assert repr(str(ROOT)) in started[0][0]  # the package of this checkout (kernel_forks)
    assert started[1] == ["stdout: []\n"]
    assert "('MPLBACKEND', 'module://matplotlib_inline.backend_inline')" in started[2][0]


def test_a_stale_output_is_detected():
    import nbformat

    nb = nbformat.read(NOTEBOOKS[0], as_version=4)
    assert differences(nb, copy.deepcopy(nb)) == []
    tampered = copy.deepcopy(nb)
    cell = next(c for c in tampered.cells if c.cell_type == "code" and c.outputs)
    cell.outputs.append(nbformat.v4.new_output("stream", name="stdout", text="a line the code no longer prints\n"))
    found = differences(nb, tampered)
    assert found and "a line the code no longer prints" in found[0]


def test_timings_and_addresses_are_ignored_but_numbers_are_not():
    assert normalise("check (1.7 s), 31.6 µs, 12 ms at 0x7f3a2b1c9d40") == "check (<time>), <time>, <time> at 0x…"
    assert normalise("kappa = 3.46703") == "kappa = 3.46703"
    assert normalise("10 events, 301 samples") == "10 events, 301 samples"


def main(argv: list[str] | None = None) -> int:
    import nbformat

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from symbolic_friction._infra.io import atomic_write_text

    parser = argparse.ArgumentParser(description="Execute the notebooks and store their outputs.")
    parser.add_argument("--write", action="store_true", help="store the fresh outputs (default: only report)")
    parser.add_argument("prefix", nargs="*", help="only notebooks whose file name starts with one of these")
    args = parser.parse_args(argv)
    stale_any = False
    for path in NOTEBOOKS:
        if args.prefix and not any(path.name.startswith(p) for p in args.prefix):
            continue
        stored, fresh, seconds = execute(path)
        stale = differences(stored, fresh)
        stale_any |= bool(stale)
        print(f"{path.name}: {seconds:.1f} s, {'stale' if stale else 'up to date'}, {image_count(fresh)} figures")
        if args.write:
            atomic_write_text(path, nbformat.writes(fresh) + "\n")
    return 1 if stale_any and not args.write else 0


if __name__ == "__main__":
    raise SystemExit(main())
