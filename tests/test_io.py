"""Atomic writes (Standard 3): nothing is lost when a write fails."""

import os

import pytest

from symbolic_friction._io import atomic_write, atomic_write_text


def test_writes_text_and_keeps_no_temporary(tmp_path):
    target = atomic_write_text(tmp_path / "sub" / "a.md", "x\ny\n")
    assert target.read_bytes() == b"x\ny\n"
    assert [p.name for p in target.parent.iterdir()] == ["a.md"]
    assert oct(target.stat().st_mode & 0o777) == oct(0o644)


def test_a_failing_write_leaves_the_old_file_intact(tmp_path):
    target = atomic_write_text(tmp_path / "a.json", "old\n")

    def broken(handle):
        handle.write(b"half")
        raise OSError("disk full")

    with pytest.raises(OSError, match="disk full"):
        atomic_write(target, broken)
    assert target.read_text() == "old\n"
    assert os.listdir(tmp_path) == ["a.json"]
