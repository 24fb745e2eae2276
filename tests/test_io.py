"""Atomic writes: nothing is lost when a write fails."""

import os
import socket
import stat
import threading
from pathlib import Path

import pytest

import symbolic_friction._infra.io as io_module

from symbolic_friction._infra.errors import OutputPathError
from symbolic_friction._infra.io import atomic_write, atomic_write_text
from symbolic_friction._infra.io import atomic_write_text as _write


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

    from symbolic_friction.errors import InputFileError
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
    from symbolic_friction.errors import OutputPathError
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


# -- special files given as the output: written into, or refused, never replaced ----------------


def test_dev_null_is_written_into_and_stays_a_character_device():
    before = os.stat("/dev/null")
    assert stat.S_ISCHR(before.st_mode)
    _write("/dev/null", "some text\n")
    after = os.stat("/dev/null")
    assert stat.S_ISCHR(after.st_mode) and after.st_rdev == before.st_rdev and after.st_ino == before.st_ino


def test_dev_full_is_an_error_that_says_so():
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full here")
    with pytest.raises(OutputPathError, match="no space left"):
        _write("/dev/full", "x" * 100_000)
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode)


def test_a_fifo_without_a_reader_is_refused_not_waited_on(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    with pytest.raises(OutputPathError, match="FIFO with no reader"):
        _write(fifo, "hello\n")
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_a_fifo_with_a_reader_receives_the_whole_text(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got = []
    fd = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)  # a reader is there before the write
    text = "line\n" * 50_000  # more than a pipe buffer: the writer must block until read

    def read():
        # until the writer has opened, a read sees end-of-file: keep reading until all has come
        import time

        data, deadline = b"", time.monotonic() + 10
        while len(data) < len(text) and time.monotonic() < deadline:
            try:
                chunk = os.read(fd, 1 << 16)
            except BlockingIOError:
                chunk = b""
            data += chunk
            if not chunk:
                time.sleep(0.001)
        os.close(fd)
        got.append(data)

    reader = threading.Thread(target=read)
    reader.start()
    _write(fifo, text)
    reader.join(10)
    assert got == [text.encode()] and stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_a_symbolic_link_is_refused_and_left_alone(tmp_path):
    target = tmp_path / "target.txt"
    target.write_text("keep\n")
    link = tmp_path / "link.txt"
    os.symlink(target, link)
    with pytest.raises(OutputPathError, match="symbolic link"):
        _write(link, "new\n")
    assert os.path.islink(link) and target.read_text() == "keep\n"


def test_a_socket_is_refused(tmp_path):
    path = tmp_path / "sock"
    with socket.socket(socket.AF_UNIX) as s:
        s.bind(str(path))
        with pytest.raises(OutputPathError, match="not a regular file"):
            _write(path, "x\n")
        assert stat.S_ISSOCK(os.lstat(path).st_mode)


def test_a_regular_file_is_still_replaced_atomically(tmp_path):
    path = tmp_path / "out.txt"
    path.write_text("old\n")
    _write(path, "new\n")
    assert path.read_text() == "new\n" and stat.S_ISREG(os.lstat(path).st_mode)


@pytest.mark.parametrize("target, code, says", [("/dev/null", 0, None), ("/dev/full", 2, "no space left")])
def test_verify_junit_xml_to_a_device(target, code, says, capsys):
    """``verify … --junit-xml /dev/null`` leaves /dev/null a device; ``/dev/full`` is exit 2 with one line."""
    from symbolic_friction.cli import main

    if not os.path.exists(target):
        pytest.skip(f"no {target} here")
    root = Path(__file__).resolve().parents[1]
    assert main(["verify", str(root / "proofs" / "case_a_feasible.json"), "--junit-xml", target]) == code
    assert stat.S_ISCHR(os.stat(target).st_mode)
    if says:
        lines = capsys.readouterr().err.strip().splitlines()
        assert len(lines) == 1 and says in lines[0]


@pytest.mark.parametrize("stem", ["../x", "/abs/path", "a/b", " ", " x", "x ", ".hidden", "..", "", "a\nb", "x" * 201])
def test_a_name_is_a_plain_stem(stem):
    from symbolic_friction._infra.io import check_stem

    with pytest.raises(OutputPathError):
        check_stem(stem)


@pytest.mark.parametrize("command", [["certify", "--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1"],
                                     ["hunting", "--k-p", "3", "--k-i", "4", "--k-v", "6.4", "--f-c", "1", "--f-s", "1.2"]])
@pytest.mark.parametrize("stem", ["../x", "/tmp/abs", " "])
def test_certify_and_hunting_refuse_a_name_outside_out(command, stem, tmp_path, capsys, monkeypatch):
    from symbolic_friction.cli import main

    monkeypatch.chdir(tmp_path)
    assert main([*command, "--out", str(tmp_path / "out"), "--name", stem]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--name" in err[0]
    assert not any(tmp_path.rglob("*.json"))


def test_an_empty_path_or_a_trailing_slash_is_refused(tmp_path):
    """``Path("")`` is the working directory and ``Path("x/")`` is ``x``: both are refused on the text as typed."""
    from symbolic_friction._infra.errors import InputFileError
    from symbolic_friction._infra.io import check_output_directory, ensure_directory, read_limited

    for check in (ensure_directory, check_output_directory):
        with pytest.raises(OutputPathError, match="must name a directory; got ''"):
            check("")
    (tmp_path / "a.json").write_text("{}")
    with pytest.raises(InputFileError, match="a trailing / names a directory"):
        read_limited(f"{tmp_path}/a.json/", limit=100)
    with pytest.raises(OutputPathError, match="a trailing / names a directory"):
        atomic_write_text(f"{tmp_path}/new/", "x")
    with pytest.raises(OutputPathError, match="must name a file"):
        atomic_write_text("", "x")
    assert not (tmp_path / "new").exists()


def test_check_output_file_refuses_early_what_atomic_write_refuses_late(tmp_path):
    from symbolic_friction._infra.io import check_output_file

    os.symlink("/dev/null", tmp_path / "link")
    os.symlink(tmp_path / "link-loop", tmp_path / "link-loop")
    (tmp_path / "plain").write_text("x")
    with socket.socket(socket.AF_UNIX) as sock:
        sock.bind(str(tmp_path / "sock"))
    for bad, says in [
        ("", "must name a file"), (f"{tmp_path}/x/", "trailing /"), (str(tmp_path), "is a directory"),
        (f"{tmp_path}/link", "is a symbolic link"), (f"{tmp_path}/link-loop", "is a symbolic link"),
        (f"{tmp_path}/sock", "not a regular file, a character device or a FIFO"),
        (f"{tmp_path}/plain/r.xml", "is a file, not a directory"), (f"{tmp_path}/{'n' * 300}", "file name too long"),
    ]:
        with pytest.raises(OutputPathError, match=says):
            check_output_file(bad, what="--junit-xml")
    # a FIFO nobody reads is refused now, not after the work
    os.mkfifo(tmp_path / "fifo")
    with pytest.raises(OutputPathError, match="is a FIFO with no reader"):
        check_output_file(f"{tmp_path}/fifo", what="--figure")
    # what may be written: a new file (its directory is not created), a regular file, a device, a FIFO with a reader
    reader = os.open(tmp_path / "fifo", os.O_RDONLY | os.O_NONBLOCK)
    try:
        for good in (f"{tmp_path}/new/r.xml", f"{tmp_path}/plain", "/dev/null", f"{tmp_path}/fifo"):
            assert str(check_output_file(good)) == good
        # the probe holds the write end open: the reader has not seen the end of the stream
        assert io_module._FIFO_PROBES
    finally:
        os.close(reader)
    assert not (tmp_path / "new").exists()
