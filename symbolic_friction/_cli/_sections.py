"""What ``symbolic-friction check`` prints: its sections, the configured target and the obligations table.

A section (:class:`Section`) is one part of the command's output: its table,
its ``--json`` members, its JUnit cases, its notes and one summary line; the
target (:class:`Target`) is what the configuration and the options ask to check.
Only the standard library is imported at module level (fast ``--help``)."""

from __future__ import annotations

import argparse
import json
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any


@dataclass(frozen=True)
class Target:
    """What ``check`` verifies, resolved from the configuration and the options.

    Attributes
    ----------
    proofs : Path
        The proofs directory.
    certificates : tuple of str or None
        Files (relative to ``proofs``) that must exist and verify; None means
        every ``*.json`` under ``proofs`` (``--proofs DIR`` without a
        configuration).
    report : bool
        Whether ``proofs/obligations.md`` is kept and compared.
    origin : str
        Where this came from, for the output (``"pyproject.toml"``, …).
    strict : bool
        Whether drift fails (``strict = true`` in the configuration, or ``--strict``).
    expectations : dict
        What the configuration says each listed file must prove (label, gains).
    """

    proofs: Path
    certificates: tuple[str, ...] | None
    report: bool
    origin: str
    strict: bool = False
    expectations: dict = field(default_factory=dict)


_NO_CONFIG = (
    "no configuration found: no symbolic-friction.toml, and no pyproject.toml with [tool.symbolic-friction], "
    "in {cwd} or above (up to the git root); add one naming your proofs directory and certificates "
    "(see docs/guide/ci.md), pass --proofs DIR, or --no-certificates to check only the derivations"
)


def _relative(path: Path) -> Path:
    """``path`` relative to the working directory when it lies below it (shorter output), else as is."""
    try:
        return path.relative_to(Path.cwd().resolve())
    except ValueError:
        return path


def resolve_target(args: argparse.Namespace) -> Target:
    """The proofs directory, required certificates and report flag for this run.

    ``--config FILE`` or the first configuration found upwards from the
    working directory names them; ``--proofs DIR`` overrides the directory.
    With no configuration, ``--proofs DIR`` checks every certificate in DIR
    (and ``DIR/obligations.md`` only if it exists); with neither, ``check``
    refuses (exit 2) unless ``--no-certificates`` asks for the derivations only.
    """
    cached = getattr(args, "_target", None)
    if cached is not None:
        return cached
    from .._infra.config import find_config, load_config
    from .._infra.errors import ConfigError, UsageError

    config_file = getattr(args, "config", None)
    config = load_config(config_file) if config_file is not None else find_config()
    proofs_arg = getattr(args, "proofs", None)
    if proofs_arg is not None and not str(proofs_arg).strip():
        raise UsageError("--proofs must name a directory; got an empty string")
    if config is not None:
        proofs = Path(proofs_arg) if proofs_arg is not None else _relative(config.proofs)
        target = Target(proofs, config.certificates, config.report, str(config.source),
                        strict=config.strict or bool(getattr(args, "strict", False)), expectations=config.expectations)
    elif proofs_arg is not None:
        proofs = Path(proofs_arg)
        target = Target(proofs, None, (proofs / "obligations.md").is_file(), "--proofs", strict=bool(getattr(args, "strict", False)))
    elif getattr(args, "no_certificates", False):
        target = Target(Path("proofs"), (), False, "none")
    else:
        raise ConfigError(_NO_CONFIG.format(cwd=Path.cwd()))
    try:
        args._target = target
    except AttributeError:  # pragma: no cover - a frozen namespace
        pass
    return target


@dataclass
class Section:
    """What one part of ``check`` found.

    Attributes
    ----------
    title : str
        Heading of the printed table.
    columns : tuple of str
        Column names of the printed table.
    rows : list of tuple of str
        Printed rows.
    json : dict
        Members merged into the ``--json`` object.
    ok : bool
        Whether this section is satisfied.
    notes : list of str
        Lines printed after the table (to stderr under ``--json``).
    summary : str
        One line saying what was checked, with counts (e.g. ``"27 of 27
        obligations hold"``); the closing line of ``check`` joins them.
    counts : dict
        The numbers behind ``summary`` (``--json``'s ``"counts"``).
    cases : list of Case
        One JUnit test case per item checked (``--junit-xml``).
    streamed : bool
        True if the rows were already printed while they were decided.
    """

    title: str
    columns: tuple[str, ...]
    rows: list[tuple[str, ...]]
    json: dict[str, Any]
    ok: bool
    notes: list[str] = field(default_factory=list)
    summary: str = ""
    counts: dict[str, int] = field(default_factory=dict)
    cases: list[Any] = field(default_factory=list)
    streamed: bool = False


class _ObligationLayout:
    """Fixed column widths for the obligations table, fitted to the terminal, so rows print as they are decided."""

    columns = ("id", "paper", "statement", "method", "status", "seconds")

    def __init__(self) -> None:
        from .._infra.output import terminal_width

        width = terminal_width()
        fixed = {"id": 24, "status": 6, "seconds": 7}
        free = max(30, width - sum(fixed.values()) - 2 * (len(self.columns) - 1))
        # paper : statement : method = 3 : 5 : 3 of what is left (the statement says the most)
        paper, method = free * 3 // 11, free * 3 // 11
        self.widths = (fixed["id"], paper, free - paper - method, method, fixed["status"], fixed["seconds"])
        self.title = "Proof obligations"
        self.head = "  ".join(c.ljust(w) for c, w in zip(self.columns, self.widths)).rstrip()
        self.rule = "  ".join("-" * w for w in self.widths)

    def row(self, r: Any) -> str:
        from .._infra.output import fit

        cells = (r.id, r.paper, r.statement, r.method, r.status, f"{r.seconds:.2f}")
        return "  ".join(fit(c, w).ljust(w) for c, w in zip(cells, self.widths)).rstrip()


def dataclasses_asdict(obj: Any) -> dict[str, Any]:
    import dataclasses

    return {k: (list(v) if isinstance(v, tuple) else v) for k, v in dataclasses.asdict(obj).items()}


def _format_table(section: Section) -> str:
    from .._infra.output import format_table

    return format_table(section.title, section.columns, section.rows)


def _crashed(make: Callable[[argparse.Namespace], Section], exc: Exception) -> Section:
    """A section that raised: reported as failing, never as passing."""
    name = getattr(make, "__name__", "section")
    from .._infra.junit import Case

    reason = f"{name} crashed: {type(exc).__name__}: {exc}"
    return Section(name, ("error",), [(reason,)], {}, False, [f"FAILED {reason}"], summary=reason,
                   cases=[Case(name=name, classname="check.sections", error=reason)])


_FAILURE_MARK = re.compile(r"\b(FAILED|FAILS|NOT PROVED|NOT CAUGHT|STALE|MALFORMED)\b")
"""Words that mark a failing line; a section that prints one cannot pass, whatever its ``ok`` says."""


def _selected(obligation_id: str, only: list[str] | None) -> bool:
    """Whether ``--only`` selects this obligation (its id, or a dotted prefix of it)."""
    return only is None or any(obligation_id == p or obligation_id.startswith(p + ".") for p in only)


def gate(section: Section) -> Section:
    """The one gate between a section's lines and ``check``'s exit code.

    A section passes only if it says so *and* none of its printed lines (notes
    and table rows) says ``FAILED``, ``FAILS``, ``NOT PROVED``, ``NOT CAUGHT``,
    ``STALE`` or ``MALFORMED``: a section whose flag and lines disagree fails,
    so the exit code, the closing line and ``--json``'s ``passed`` always
    agree with what was printed.  Returns the section, with ``ok`` cleared and
    a note naming the line when they disagree.
    """
    lines = [str(note) for note in section.notes] + ["  ".join(str(cell) for cell in row) for row in section.rows]
    marked = [line for line in lines if _FAILURE_MARK.search(line)]
    if marked and section.ok:
        section.ok = False
        section.notes.append(f"FAILED {section.title}: it reported success but printed {marked[0]!r}")
    return section


def closing_line(sections: list[Section]) -> str:
    """``check: PASSED — …`` or ``check: FAILED — …`` (failed sections named first)."""
    failed = [s for s in sections if not s.ok]
    passed = [s for s in sections if s.ok]
    parts = [s.summary or s.title for s in failed + passed]
    return f"check: {'FAILED' if failed else 'PASSED'} — " + "; ".join(parts)


def _wrap(note: str) -> str:
    """A long note wrapped to the terminal width, continuation lines indented."""
    import textwrap

    from .._infra.output import terminal_width

    import os

    if not (sys.stdout.isatty() or os.environ.get("COLUMNS")):
        return note  # a log or a pipe keeps each note on one line, for grep
    width = terminal_width()
    if len(note) <= width:
        return note
    indent = " " * min(8, len(note) - len(note.lstrip()) + 5)
    return textwrap.fill(note, width=width, subsequent_indent=indent, break_long_words=True, break_on_hyphens=False)


def _is_verdict(note: str) -> bool:
    """Notes that ``--quiet`` still prints: what failed or is stale."""
    return note.startswith(("FAILS", "FAILED", "STALE", "MALFORMED"))
