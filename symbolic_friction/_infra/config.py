"""Project configuration: which proofs ``symbolic-friction check`` must find.

A project names its proofs directory and the certificates that must exist in
``[tool.symbolic-friction]`` of its ``pyproject.toml``, or at the top level of a
``symbolic-friction.toml``::

    [tool.symbolic-friction]
    proofs = "proofs"                                  # relative to the file
    certificates = ["slow_axis.json", "fast_axis.json"]
    report = false                                     # keep proofs/obligations.md?
    strict = false                                     # fail on drift too (see below)

An entry of ``certificates`` may also be a table that states what the file
must prove, so that a hand-edited gain or label fails ``check``::

    certificates = [{file = "stage.json", label = "stage", gains = {k_p = "3", k_i = "4", k_v = "32/5", f_c = "1"}}]

A certificate that still proves the configured statement but differs from what
``certify`` writes now (a newer solver or package rounded differently) is
*drift*: reported, and a failure only with ``strict = true`` or ``check --strict``.

``check`` then verifies exactly the listed certificates (each must exist, be
proved by the exact verifier and be what ``certify`` writes now), plus the
package's own derivations (the proof obligations of the paper, for symbolic
gains).  ``report = true`` also keeps the rendered derivations
``obligations.md`` in the proofs directory and fails when it is stale; the
package's own checkout does so for Table I's certificates.

The file is found by walking up from the working directory: the first
``symbolic-friction.toml``, or ``pyproject.toml`` holding the table, wins; the
walk stops at the root of a git repository.  Only the standard library is
imported (fast start).
"""

from __future__ import annotations

import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Any

from .errors import ConfigError
from .io import read_limited

__all__ = ["ProjectConfig", "find_config", "load_config", "parse_config", "CONFIG_FILE", "MAX_CONFIG_BYTES"]

CONFIG_FILE = "symbolic-friction.toml"
MAX_CONFIG_BYTES = 1_000_000
"""A configuration file larger than this is refused (it names a directory and a list of files)."""

_KEYS = ("proofs", "certificates", "report", "strict")
_ENTRY_KEYS = ("file", "label", "gains")
GAIN_NAMES = ("k_p", "k_i", "k_v", "f_c")
MAX_CERTIFICATES = 10_000
MAX_CONFIG_COMMAS = 8 * MAX_CERTIFICATES
"""Most ``,`` a configuration file may have outside strings: 6 per certificate entry (``{file, label, gains = {k_p, k_i,
k_v, f_c}}`` and the comma after it), with room to spare; counted before parsing (see :func:`toml_syntax_count`)."""

_TOML_NOT_SYNTAX = re.compile(
    r'"""(?:[^"\\]|\\.|"(?!""))*"{3,5}'  # a multi-line basic string (it may end in up to two quotes of its own)
    r"|'''.*?'{3,5}"  # a multi-line literal string
    r'|"(?:[^"\\\n]|\\.)*"'  # a basic string
    r"|'[^'\n]*'"  # a literal string
    r"|#[^\n]*",  # a comment
    re.DOTALL,
)


def toml_syntax_count(text: str, char: str, *, above: int) -> int:
    """How many ``char`` (``[``, ``,``) a TOML text has outside its strings and comments, when more than ``above``.

    An upper bound on the arrays or values ``tomllib`` would build, found without building them: a huge file is
    refused in milliseconds, not after seconds of parsing and a million objects.  At most ``above`` plain
    occurrences (every ordinary file) are returned as they are, without looking for strings.
    """
    count = text.count(char)
    return count if count <= above else _TOML_NOT_SYNTAX.sub("", text).count(char)


@dataclass(frozen=True)
class ProjectConfig:
    """What ``check`` must verify for one project.

    Attributes
    ----------
    source : Path
        The file the configuration was read from.
    proofs : Path
        The proofs directory (resolved against the file's directory).
    certificates : tuple of str
        Certificate files, relative to ``proofs``, that must exist and verify.
    report : bool
        Whether ``proofs/obligations.md`` (the derivations in LaTeX) is kept
        and compared.
    strict : bool
        Whether drift (a file that proves the configured statement but is not
        what ``certify`` writes now) fails ``check``.
    expectations : dict
        ``{file: {"label": str, "gains": {name: Fraction}}}`` for the entries
        that state what their file must prove.
    """

    source: Path
    proofs: Path
    certificates: tuple[str, ...]
    report: bool = False
    strict: bool = False
    expectations: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        for name in self.certificates:
            _check_certificate_name(name, self.source)


def _check_certificate_name(name: object, source: Path) -> None:
    if not isinstance(name, str) or not name:
        raise ConfigError(f"{source}: every entry of 'certificates' must be a non-empty string; got {name!r}")
    pure = PurePosixPath(name)
    if pure.is_absolute() or ".." in pure.parts or "\\" in name or "\x00" in name:
        raise ConfigError(
            f"{source}: certificate {name!r} must be a path inside the proofs directory (relative, without '..')"
        )
    if pure.suffix != ".json":
        raise ConfigError(f"{source}: certificate {name!r} must be a .json file")


def parse_config(table: object, *, source: Path) -> ProjectConfig:
    """Build a :class:`ProjectConfig` from the parsed ``[tool.symbolic-friction]`` table.

    Raises
    ------
    ConfigError
        Naming the file and the key: an unknown key, a wrong type, a
        certificate outside the proofs directory.
    """
    if not isinstance(table, dict):
        raise ConfigError(f"{source}: [tool.symbolic-friction] must be a table; got {type(table).__name__}")
    unknown = sorted(set(table) - set(_KEYS))
    if unknown:
        raise ConfigError(f"{source}: unknown key(s) {', '.join(map(repr, unknown))} (allowed: {', '.join(_KEYS)})")
    proofs = table.get("proofs", "proofs")
    if not isinstance(proofs, str) or not proofs or "\x00" in proofs:
        raise ConfigError(f"{source}: 'proofs' must be a directory name (a non-empty string); got {proofs!r}")
    certificates = table.get("certificates", [])
    if not isinstance(certificates, list):
        raise ConfigError(f"{source}: 'certificates' must be a list of file names; got {type(certificates).__name__}")
    if len(certificates) > MAX_CERTIFICATES:
        raise ConfigError(f"{source}: 'certificates' lists {len(certificates)} files; at most {MAX_CERTIFICATES} are accepted")
    report = table.get("report", False)
    if not isinstance(report, bool):
        raise ConfigError(f"{source}: 'report' must be true or false; got {report!r}")
    strict = table.get("strict", False)
    if not isinstance(strict, bool):
        raise ConfigError(f"{source}: 'strict' must be true or false; got {strict!r}")
    expectations: dict[str, dict] = {}
    names = []
    for entry in certificates:
        if isinstance(entry, dict):
            name, expected = _parse_entry(entry, source)
            expectations[name] = expected
            names.append(name)
        else:
            names.append(entry)
    certificates = names
    for name in certificates:
        _check_certificate_name(name, source)
    if len(set(certificates)) != len(certificates):
        dupes = sorted({c for c in certificates if certificates.count(c) > 1})
        raise ConfigError(f"{source}: 'certificates' lists {', '.join(map(repr, dupes))} more than once")
    return ProjectConfig(source=source, proofs=source.parent / proofs, certificates=tuple(certificates), report=report,
                         strict=strict, expectations=expectations)


def _parse_entry(entry: dict, source: Path) -> tuple[object, dict]:
    """``(file, {"label": …, "gains": {…}})`` from a table entry of ``certificates``."""
    from .rational import to_rational
    from .errors import SymbolicFrictionError

    unknown = sorted(set(entry) - set(_ENTRY_KEYS))
    if unknown:
        raise ConfigError(f"{source}: a certificates entry has unknown key(s) {', '.join(map(repr, unknown))} "
                          f"(allowed: {', '.join(_ENTRY_KEYS)})")
    if "file" not in entry:
        raise ConfigError(f"{source}: a certificates entry given as a table needs 'file'; got {sorted(entry)}")
    expected: dict = {}
    if "label" in entry:
        if not isinstance(entry["label"], str) or len(entry["label"]) > 10_000:
            raise ConfigError(f"{source}: 'label' of {entry['file']!r} must be a string; got {entry['label']!r:.60}")
        expected["label"] = entry["label"]
    if "gains" in entry:
        gains = entry["gains"]
        if not isinstance(gains, dict) or not gains or set(gains) - set(GAIN_NAMES):
            raise ConfigError(f"{source}: 'gains' of {entry['file']!r} must be a table of {', '.join(GAIN_NAMES)}; got {gains!r:.80}")
        parsed = {}
        for key, value in gains.items():
            if isinstance(value, bool) or not isinstance(value, (str, int, float)):
                raise ConfigError(f"{source}: gains.{key} of {entry['file']!r} must be a number or a string such as '32/5'")
            try:
                parsed[key] = to_rational(value, name=f"gains.{key}")
            except SymbolicFrictionError as exc:
                raise ConfigError(f"{source}: {entry['file']!r}: {exc}") from None
        expected["gains"] = parsed
    return entry["file"], expected


def _read_toml(path: Path) -> dict[str, Any]:
    text = read_limited(path, limit=MAX_CONFIG_BYTES, what="configuration file").decode("utf-8", errors="strict")
    if path.name != "pyproject.toml":  # other tools' tables in a pyproject.toml are not bounded by this package
        commas = toml_syntax_count(text, ",", above=MAX_CONFIG_COMMAS)
        if commas > MAX_CONFIG_COMMAS:
            raise ConfigError(f"{path}: {commas} commas outside strings (values in lists and tables); a configuration of "
                              f"at most {MAX_CERTIFICATES} certificates needs at most {MAX_CONFIG_COMMAS}")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: not valid TOML: {exc}") from None
    except RecursionError:
        raise ConfigError(f"{path}: not valid TOML: nested too deeply") from None


def load_config(path: str | os.PathLike[str]) -> ProjectConfig:
    """Read the configuration from ``path`` (a ``pyproject.toml`` or a ``symbolic-friction.toml``).

    Raises
    ------
    ConfigError
        If the file cannot be read, is not TOML, or (a ``pyproject.toml``)
        has no ``[tool.symbolic-friction]`` table.
    """
    path = Path(path)
    try:
        doc = _read_toml(path)
    except UnicodeDecodeError as exc:
        raise ConfigError(f"{path}: not UTF-8 ({exc.reason} at byte {exc.start})") from None
    if path.name == "pyproject.toml":
        table = doc.get("tool", {}).get("symbolic-friction") if isinstance(doc.get("tool"), dict) else None
        if table is None:
            raise ConfigError(f"{path} has no [tool.symbolic-friction] table")
        return parse_config(table, source=path)
    if set(doc) == {"tool"} and isinstance(doc["tool"], dict) and "symbolic-friction" in doc["tool"]:
        return parse_config(doc["tool"]["symbolic-friction"], source=path)
    return parse_config(doc, source=path)


def _has_table(pyproject: Path) -> bool:
    try:
        doc = _read_toml(pyproject)
    except (ConfigError, UnicodeDecodeError):
        return False  # someone else's broken pyproject is not ours to report
    tool = doc.get("tool")
    return isinstance(tool, dict) and "symbolic-friction" in tool


def find_config(start: str | os.PathLike[str] | None = None) -> ProjectConfig | None:
    """The configuration that applies in ``start`` (default: the working directory), or None.

    Walks up from ``start``: in each directory a ``symbolic-friction.toml``
    wins over a ``pyproject.toml`` holding ``[tool.symbolic-friction]``; the
    walk stops after the directory holding ``.git``.
    """
    here = Path.cwd() if start is None else Path(start)
    here = here.resolve()
    for directory in (here, *here.parents):
        candidate = directory / CONFIG_FILE
        if candidate.is_file():
            return load_config(candidate)
        pyproject = directory / "pyproject.toml"
        if pyproject.is_file() and _has_table(pyproject):
            return load_config(pyproject)
        if (directory / ".git").exists():
            return None
    return None
