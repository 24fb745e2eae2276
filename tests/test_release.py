"""The install paths the documentation quotes exist: every ``rev:`` and ``@vX.Y.Z`` names the package's
own version, which the changelog describes and which is a tag of this repository.

A clone made without tags (``git clone --single-branch --no-tags``, as CI systems often do) cannot
list them: there the tag check is skipped with that reason, while the version and changelog checks
still run.  In a checkout that has tags, a quoted ref that is not one of them fails."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
_REF = re.compile(r"(?:\brev:\s*|@)(v\d+\.\d+\.\d+\S*?)(?=[\s\"'`]|$)", re.MULTILINE)


def _documents() -> dict[str, str]:
    texts = {"README.md": (ROOT / "README.md").read_text(encoding="utf-8")}
    # the documentation site's pages (the CI snippets that pin a release moved there from the README)
    for path in sorted((ROOT / "docs").rglob("*.md")):
        if "_build" not in path.parts and "_generated" not in path.parts:
            texts[path.relative_to(ROOT).as_posix()] = path.read_text(encoding="utf-8")
    for path in sorted((ROOT / "notebooks").glob("*.ipynb")):
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        texts[path.name] = "\n".join("".join(cell["source"]) for cell in cells)
    return texts


def quoted_refs() -> dict[str, set[str]]:
    """``{document: {"v0.1.0", …}}`` for every version reference a document quotes."""
    return {name: set(_REF.findall(text)) for name, text in _documents().items()}


def _version() -> str:
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]


def _tags() -> set[str]:
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout: the tags cannot be listed")
    out = subprocess.run(["git", "-C", str(ROOT), "tag", "--list"], capture_output=True, text=True, check=True)
    tags = set(out.stdout.split())
    if not tags:
        pytest.skip("this clone has no tags at all (cloned without them): whether the quoted refs are tags cannot be seen here")
    return tags


def test_the_readme_quotes_a_release():
    assert quoted_refs()["README.md"], "the README quotes no release to pin"


def test_every_quoted_rev_is_a_tag():
    tags = _tags()
    missing = {name: sorted(refs - tags) for name, refs in quoted_refs().items() if refs - tags}
    assert not missing, f"documented refs that are not tags of this repository: {missing}; tags: {sorted(tags)}"


def test_every_quoted_rev_is_the_package_version():
    # a pin to an older release would install a package whose commands the README no longer describes
    expected = f"v{_version()}"
    wrong = {name: sorted(refs - {expected}) for name, refs in quoted_refs().items() if refs - {expected}}
    assert not wrong, f"documented refs that are not the package's version {expected}: {wrong}"


def test_the_pattern_finds_refs():
    # the check above is only as good as the pattern
    text = 'rev: v1.2.3\n pip install "x @ git+https://h/x.git@v0.1.0"\n'
    assert set(_REF.findall(text)) == {"v1.2.3", "v0.1.0"}


def test_the_changelog_has_the_package_version():
    version = _version()
    changelog = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert re.search(rf"^## \[{re.escape(version)}\]", changelog, re.MULTILINE), f"CHANGELOG.md has no section for {version}"
