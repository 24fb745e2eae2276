"""The package's layering is a tested fact (ARCHITECTURE.md).

The contracts live in ``[tool.importlinter]`` of ``pyproject.toml`` and are
checked by import-linter: each layer imports only from the layers below it,
no package has an import loop among its modules, and studies of the inclusion
reach the simulation only through its public surface.  A second test holds
every module to the size limit of ARCHITECTURE.md.
"""

from __future__ import annotations

from pathlib import Path


ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "symbolic_friction"

MAX_LINES = 500
"""No module of the package is longer than this."""

OVER_LIMIT: dict[str, int] = {}
"""Modules allowed over :data:`MAX_LINES`, each with its own ceiling: none."""


def test_import_contracts_hold(monkeypatch, capsys):
    """``lint-imports`` on the package: layers, no loops, the kernel's surface (import-linter)."""
    from importlinter import cli as lint  # in the test extra: the contracts are checked wherever the suite runs

    monkeypatch.chdir(ROOT)
    code = lint.lint_imports(config_filename=str(ROOT / "pyproject.toml"), no_cache=True, no_logo=True)
    out = capsys.readouterr().out
    assert code == 0, out
    assert "0 broken" in out and " kept" in out


def test_contracts_cover_every_layer():
    """Every package and loose module of the package is named in the layers contract."""
    import tomllib

    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    contracts = config["tool"]["importlinter"]["contracts"]
    layers = next(c for c in contracts if c["type"] == "layers")["layers"]
    named = {name.strip() for layer in layers for name in layer.replace(":", "|").split("|")}
    present = {p.stem if p.is_file() else p.name for p in PACKAGE.iterdir()
               if (p.is_dir() and (p / "__init__.py").exists()) or (p.suffix == ".py" and not p.name.startswith("__"))}
    assert present == named, f"not in a layer: {sorted(present - named)}; no such module: {sorted(named - present)}"


def test_no_module_is_over_the_size_limit():
    """No module exceeds :data:`MAX_LINES` lines (the listed exceptions their own ceiling)."""
    too_long = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).as_posix()
        with open(path, encoding="utf-8") as fh:
            lines = sum(1 for _ in fh)
        if lines > OVER_LIMIT.get(rel, MAX_LINES):
            too_long.append(f"{rel}: {lines} lines")
    assert not too_long, "modules over the limit: " + ", ".join(too_long)


def test_over_limit_list_names_existing_modules():
    for rel in OVER_LIMIT:  # an exception, when one is needed, names a module that exists
        assert (PACKAGE / rel).is_file(), rel
