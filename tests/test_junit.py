"""JUnit XML: well formed, counts agree with the cases, hostile text cannot break it."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from symbolic_friction._infra.errors import OutputPathError
from symbolic_friction._infra.junit import Case, render_junit, write_junit


def test_counts_and_elements(tmp_path):
    cases = [
        Case("lemma2.P", "check.obligations", 0.5),
        Case("a.json", "check.certificates", failure="k3 > k2: 1 > 2 is false"),
        Case("b.json", "verify", error="malformed: not JSON"),
        Case("c", "x", skipped="not checked"),
    ]
    path = write_junit(tmp_path / "r.xml", "suite", cases)
    root = ET.parse(path).getroot()
    assert root.tag == "testsuites"
    suite = root.find("testsuite")
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors"), suite.get("skipped")) == ("4", "1", "1", "1")
    got = [(c.get("name"), [child.tag for child in c]) for c in suite.findall("testcase")]
    assert got == [("lemma2.P", []), ("a.json", ["failure"]), ("b.json", ["error"]), ("c", ["skipped"])]
    assert suite.findall("testcase")[1].find("failure").get("message") == "k3 > k2: 1 > 2 is false"


def test_control_characters_and_markup_are_escaped():
    data = render_junit("s", [Case("a\x00b<&>\"", "c\x1b", failure="x\x07 </failure>")])
    root = ET.fromstring(data)
    case = root.find("testsuite/testcase")
    assert case.get("name") == 'a?b<&>"' and case.find("failure").text == "x? </failure>"


def test_a_directory_is_refused(tmp_path):
    with pytest.raises(OutputPathError, match="is a directory"):
        write_junit(tmp_path, "s", [])
