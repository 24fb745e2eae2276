"""Every notebook in ``notebooks/`` runs top to bottom (code cells executed
with plain ``exec`` in one namespace; no Jupyter needed)."""

import json
from pathlib import Path

import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("*.ipynb"))


def test_there_are_notebooks():
    assert NOTEBOOKS, "no notebooks found in notebooks/"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs(path, capsys):
    nb = json.loads(path.read_text(encoding="utf-8"))
    assert nb["nbformat"] == 4
    cells = [c for c in nb["cells"] if c["cell_type"] == "code"]
    assert cells, f"{path.name} has no code cells"
    namespace = {"__name__": "__notebook__"}
    for n, cell in enumerate(cells, 1):
        source = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
        try:
            exec(compile(source, f"{path.name}[code cell {n}]", "exec"), namespace)
        except Exception as exc:  # report which cell failed, then fail the test
            pytest.fail(f"{path.name}, code cell {n} raised {type(exc).__name__}: {exc}")
    assert capsys.readouterr().out  # the walkthrough prints its derivations
