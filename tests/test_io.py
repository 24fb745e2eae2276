"""Atomic writes: nothing is lost when a write fails."""

import os

import pytest

from symbolic_friction._infra.io import atomic_write, atomic_write_text


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


# --------------------------------------------------------------------------- bounded reads and output directories


def test_read_limited_refuses_what_is_not_a_small_regular_file(tmp_path):
    import os

    from symbolic_friction import InputFileError
    from symbolic_friction._infra.io import read_limited

    (tmp_path / "ok").write_bytes(b"abc")
    assert read_limited(tmp_path / "ok", limit=3) == b"abc"
    with pytest.raises(InputFileError, match=r"has 3 bytes; at most 2 are accepted"):
        read_limited(tmp_path / "ok", limit=2, what="file")
    with pytest.raises(InputFileError, match="is a directory"):
        read_limited(tmp_path, limit=10)
    os.mkfifo(tmp_path / "fifo")
    with pytest.raises(InputFileError, match=r"not a regular file \(a FIFO, socket or device\)"):
        read_limited(tmp_path / "fifo", limit=10)  # returns at once: no writer is waited for
    with pytest.raises(InputFileError, match="not a regular file"):
        read_limited("/dev/zero", limit=10)
    os.symlink(tmp_path / "loop", tmp_path / "loop")
    with pytest.raises(InputFileError, match="symlink loop"):
        read_limited(tmp_path / "loop", limit=10)
    with pytest.raises(InputFileError, match="no such file or directory"):
        read_limited(tmp_path / "missing", limit=10)
    with pytest.raises(InputFileError, match="file name too long"):
        read_limited(tmp_path / ("n" * 300), limit=10)
    with pytest.raises(InputFileError, match="a component of the path is a file"):
        read_limited(tmp_path / "ok" / "x", limit=10)


def test_ensure_directory_and_check_output_directory(tmp_path):
    from symbolic_friction import OutputPathError
    from symbolic_friction._infra.io import check_output_directory, ensure_directory

    (tmp_path / "file").write_text("x", encoding="utf-8")
    assert ensure_directory(tmp_path / "a" / "b").is_dir()
    with pytest.raises(OutputPathError, match="exists and is not a directory"):
        ensure_directory(tmp_path / "file")
    with pytest.raises(OutputPathError, match="a component of the path is a file"):
        ensure_directory(tmp_path / "file" / "sub")
    with pytest.raises(OutputPathError, match="file name too long"):
        ensure_directory(tmp_path / ("n" * 300))
    assert check_output_directory(tmp_path / "new" / "deeper") == tmp_path / "new" / "deeper"
    assert not (tmp_path / "new").exists()  # checked, not created
    with pytest.raises(OutputPathError, match="exists and is not a directory"):
        check_output_directory(tmp_path / "file")
    with pytest.raises(OutputPathError, match="is a file, not a directory|a component of the path is a file"):
        check_output_directory(tmp_path / "file" / "sub")
    with pytest.raises(OutputPathError, match="file name too long"):
        check_output_directory(tmp_path / ("n" * 300))
