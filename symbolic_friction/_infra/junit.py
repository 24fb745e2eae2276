"""JUnit XML reports, so that CI systems show each obligation, certificate or property as a test.

``check``, ``verify`` and ``crosscheck`` take ``--junit-xml FILE``.  The file
follows the common JUnit schema (Jenkins' ``junit-10.xsd``, which GitHub,
GitLab and most report viewers read): one ``<testsuite>`` per command inside
``<testsuites>``, one ``<testcase>`` per item, with ``<failure>`` when it does
not hold, ``<error>`` when it could not be decided (a malformed file, a
crash) and ``<skipped>`` when it was not checked.  Written atomically with
the standard library only.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from .io import atomic_write, check_output_file, ensure_directory

__all__ = ["Case", "write_junit", "render_junit", "check_writable"]


@dataclass(frozen=True)
class Case:
    """One test case of the report.

    Attributes
    ----------
    name : str
        What was checked (an obligation id, a certificate file, a property).
    classname : str
        The group it belongs to (``check.obligations``, ``verify`` …).
    seconds : float
        Time it took (0 when not measured).
    failure : str or None
        Why it does not hold (a ``<failure>``).
    error : str or None
        Why it could not be decided (an ``<error>``).
    skipped : str or None
        Why it was not checked (a ``<skipped>``).
    output : str
        Text shown with the case (``<system-out>``).
    """

    name: str
    classname: str
    seconds: float = 0.0
    failure: str | None = None
    error: str | None = None
    skipped: str | None = None
    output: str = ""


def _clean(text: str) -> str:
    # XML 1.0 forbids most control characters; a hostile file name must not break the report
    return "".join(ch if ch in "\t\n\r" or ord(ch) >= 0x20 else "?" for ch in text)


def render_junit(suite: str, cases: list[Case]) -> bytes:
    """The XML document for ``cases`` under one test suite named ``suite``."""
    failures = sum(c.failure is not None for c in cases)
    errors = sum(c.error is not None for c in cases)
    skipped = sum(c.skipped is not None for c in cases)
    total = sum(c.seconds for c in cases)
    root = ET.Element("testsuites", name=suite, tests=str(len(cases)), failures=str(failures), errors=str(errors),
                      skipped=str(skipped), time=f"{total:.3f}")
    node = ET.SubElement(root, "testsuite", name=suite, tests=str(len(cases)), failures=str(failures),
                         errors=str(errors), skipped=str(skipped), time=f"{total:.3f}")
    for case in cases:
        element = ET.SubElement(node, "testcase", name=_clean(case.name), classname=_clean(case.classname),
                                time=f"{case.seconds:.3f}")
        for tag, text in (("failure", case.failure), ("error", case.error), ("skipped", case.skipped)):
            if text is not None:
                first = _clean(text.splitlines()[0] if text else tag)
                child = ET.SubElement(element, tag, message=first[:500])
                child.text = _clean(text)
        if case.output:
            ET.SubElement(element, "system-out").text = _clean(case.output)
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"


def check_writable(path: str | os.PathLike[str]) -> Path:
    """Refuse an unusable ``--junit-xml`` path before any work (its directory is created)."""
    path = check_output_file(path, what="--junit-xml")
    ensure_directory(path.parent if str(path.parent) else Path("."), what="directory of --junit-xml")
    return path


def write_junit(path: str | os.PathLike[str], suite: str, cases: list[Case]) -> Path:
    """Write the report atomically; returns ``path``."""
    data = render_junit(suite, cases)
    return atomic_write(check_writable(path), lambda handle: handle.write(data))
