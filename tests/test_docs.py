"""The documentation site builds, offline, with warnings as errors, and holds what it promises.

The build is the one ``docs/conf.py`` documents, ``python -m sphinx -W --keep-going -b html docs OUT``, run
once for this module into a temporary directory (about 15 s on two cores).  It needs the ``[docs]`` extra
(Sphinx, myst-nb, numpydoc, furo); without it the tests that need a build are skipped, saying so.  Then:

* every name of ``symbolic_friction.__all__`` has its entry in the generated API pages;
* every command of the argument parser, and every option of every command, is in the CLI page;
* the getting-started page exists, with the README's two commands;
* every heading of the README as it was before the site (``docs/readme_sections.txt``) has its page, which
  holds it (no build needed);
* the README fits on a screen (at most 150 lines), starts with its two commands, and its links resolve.
"""

from __future__ import annotations

import argparse
import html
import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
README = ROOT / "README.md"
TWO_COMMANDS = (
    'python -m pip install . && python -m symbolic_friction check',
    'python -m pip install ".[test]" && python -m pytest -q',
)
BUILD_TIMEOUT = 600  # seconds; the build takes about 15 s on this project's 2-core machine

_DOC_PACKAGES = ("sphinx", "myst_nb", "numpydoc", "furo")


def _missing_doc_packages() -> list[str]:
    return [name for name in _DOC_PACKAGES if importlib.util.find_spec(name) is None]


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The built HTML site (skipped, naming what is missing, without the [docs] extra)."""
    missing = _missing_doc_packages()
    if missing:
        pytest.skip(f"the documentation extra is not installed (missing {', '.join(missing)}): "
                    'pip install ".[docs]" to build the site')
    out = tmp_path_factory.mktemp("site") / "html"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "COLUMNS")}
    result = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(DOCS), str(out)],
        capture_output=True, text=True, cwd=ROOT, env=env, timeout=BUILD_TIMEOUT, check=False,
    )
    assert result.returncode == 0, f"the site does not build (warnings are errors):\n{result.stderr[-8000:]}"
    return out


def _text(page: Path) -> str:
    """The visible text of an HTML page (tags dropped, entities decoded)."""
    return html.unescape(re.sub(r"<[^>]+>", "", page.read_text(encoding="utf-8")))


def _ids(pages) -> set[str]:
    found: set[str] = set()
    for page in pages:
        found |= set(re.findall(r'\bid="([^"]+)"', page.read_text(encoding="utf-8")))
    return found


def test_every_public_name_is_in_the_api_reference(site):
    import symbolic_friction

    pages = sorted((site / "api").glob("*.html"))
    assert pages, "no API pages were generated"
    ids = _ids(pages)
    missing = []
    for name in symbolic_friction.__all__:
        is_module = isinstance(getattr(symbolic_friction, name), type(symbolic_friction))
        anchor = f"module-symbolic_friction.{name}" if is_module else f"symbolic_friction.{name}"
        if anchor not in ids:
            missing.append(name)
    assert not missing, f"public names without an entry in docs/api/: {missing} (add them to a page of docs/api/)"


def test_every_member_of_the_public_modules_is_documented(site):
    import symbolic_friction

    ids = _ids((site / "api").glob("*.html"))
    missing = []
    for module in symbolic_friction._MODULES:
        for name in getattr(symbolic_friction, module).__all__:
            if f"symbolic_friction.{module}.{name}" not in ids and f"symbolic_friction.{name}" not in ids:
                missing.append(f"{module}.{name}")
    assert not missing, f"members of the public modules missing from their API pages: {missing}"


def _subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    raise AssertionError("the parser has no subcommands")


def test_every_command_and_option_is_in_the_cli_reference(site):
    from symbolic_friction._cli.main import COMMANDS, build_parser

    page = site / "cli.html"
    raw, text = page.read_text(encoding="utf-8"), _text(page)
    commands = _subparsers(build_parser())
    assert set(commands) == set(COMMANDS)
    for name, parser in commands.items():
        assert f'id="cli-{name}"' in raw, f"no section for `symbolic-friction {name}` in the CLI reference"
        assert f"symbolic-friction {name}" in text
        section = raw.split(f'id="cli-{name}"', 1)[1].split('<section id="cli-', 1)[0]
        for action in parser._actions:
            for flag in action.option_strings:
                assert flag in html.unescape(section), f"`symbolic-friction {name} {flag}` is not in the CLI reference"


def test_the_getting_started_page_exists_with_the_two_commands(site):
    page = site / "getting-started.html"
    assert page.exists()
    text = _text(page)
    assert "Getting started" in text
    for command in TWO_COMMANDS:
        assert command in text
    assert (site / "index.html").exists() and "getting-started.html" in (site / "index.html").read_text(encoding="utf-8")


def test_the_notebooks_are_rendered_from_their_stored_outputs(site):
    for notebook in sorted((ROOT / "notebooks").glob("*.ipynb")):
        page = site / "_generated" / "notebooks" / f"{notebook.stem}.html"
        assert page.exists(), f"{notebook.name} is not on the site"


def test_the_errata_and_obligations_are_generated_from_the_package(site):
    import symbolic_friction

    errata, correctness = _text(site / "guide" / "errata.html"), _text(site / "correctness.html")
    for erratum in symbolic_friction.all_errata():
        assert erratum.where in errata
    for obligation in symbolic_friction.all_obligations():
        assert obligation.id in correctness


# --- the README and where its sections went (no build needed) ---------------------------------------------


def _readme_sections() -> list[tuple[str, str]]:
    entries = []
    for line in (DOCS / "readme_sections.txt").read_text(encoding="utf-8").splitlines():
        if "\t" in line:  # lines without a tab are notes
            heading, page = line.split("\t")
            entries.append((heading.strip(), page.strip()))
    return entries


def _headings(text: str) -> set[str]:
    """The Markdown headings of ``text`` (outside fenced code), as written: ``## Gain maps``."""
    found, fence = set(), False
    for line in text.splitlines():
        if line.startswith("```"):
            fence = not fence
        elif not fence and re.match(r"^#{1,6} ", line):
            found.add(line.strip())
    return found


def test_every_readme_section_has_a_home_on_the_site():
    entries = _readme_sections()
    assert len(entries) >= 20
    for heading, page in entries:
        path = ROOT / page
        assert path.exists(), f"{heading!r}: its page {page} does not exist"
        text = path.read_text(encoding="utf-8")
        title = heading.lstrip("#").strip()
        assert any(h.lstrip("#").strip() == title for h in _headings(text)), f"{page} has no heading {title!r}"


def test_the_readme_fits_on_a_screen_and_starts_with_the_two_commands():
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 150
    blocks = re.findall(r"^```bash\n(.*?)\n```", text, flags=re.MULTILINE | re.DOTALL)
    assert tuple(blocks[:2]) == TWO_COMMANDS
    assert text.index(TWO_COMMANDS[0]) < text.index("## ")  # first, before any section
    assert TWO_COMMANDS[1] in (ROOT / ".ci" / "run").read_text(encoding="utf-8")


def test_the_readme_links_resolve():
    text = README.read_text(encoding="utf-8")
    links = [target for target in re.findall(r"\]\(([^)\s]+)\)", text) if "://" not in target]
    assert links
    for target in links:
        path = ROOT / target.split("#", 1)[0]
        assert path.exists(), f"README links to {target}, which does not exist"


def test_the_pages_include_what_they_promise():
    # the python-control snippet, written beside the package's from_control / to_control
    assert "{include} _snippets/control.md" in (DOCS / "getting-started.md").read_text(encoding="utf-8")
    assert (DOCS / "_snippets" / "control.md").exists()
    conf = (DOCS / "conf.py").read_text(encoding="utf-8")
    assert 'nb_execution_mode = "off"' in conf
    assert "intersphinx" not in conf and "viewcode" not in conf  # offline and fast
