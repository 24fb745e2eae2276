"""Atomic file writes: the one way this package writes a file.

A write to ``proofs/`` (or any output) must never leave a
truncated file behind.  Every writer goes through :func:`atomic_write`,
which writes a temporary file in the target's directory, flushes it to disk
and renames it over the target with ``os.replace`` (atomic on POSIX and
Windows).  Readers see the old file or the complete new one.  Only a regular
file (or a new one) is replaced: a character device or a FIFO given as the
target (``/dev/null``, a pipe) is written into, never replaced, and a
symbolic link, a directory or any other special file is refused.
"""

from __future__ import annotations

import errno
import os
import stat
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import IO

from .errors import InputFileError, OutputPathError
from .guards import check_path

__all__ = [
    "atomic_write", "atomic_write_text", "read_limited", "ensure_directory", "check_output_directory", "check_output_file",
    "check_stem", "describe_os_error",
]

# The longest file stem a --name may give.
STEM_MAX = 200


def describe_os_error(exc: OSError, path: str | os.PathLike[str] | None = None) -> str:
    """``"<path>: <what went wrong>"`` for an OS error, in words a user can act on."""
    if exc.errno is None and exc.filename is None and path is None:
        return str(exc) or type(exc).__name__  # an OSError raised with a message of its own
    name = exc.filename if exc.filename is not None else path
    what = {
        errno.ENAMETOOLONG: "file name too long",
        errno.ELOOP: "too many levels of symbolic links (a symlink loop?)",
        errno.ENOTDIR: "a component of the path is a file, not a directory",
        errno.EISDIR: "is a directory",
        errno.ENOENT: "no such file or directory",
        errno.EACCES: "permission denied",
        errno.EEXIST: "already exists",
        errno.ENOSPC: "no space left on the device",
        errno.EROFS: "read-only file system",
    }.get(exc.errno or 0, exc.strerror or type(exc).__name__)
    text = str(name) if name is not None else "?"
    if len(text) > 120:
        text = text[:60] + "…" + text[-40:] + f" ({len(text)} characters)"
    return f"{text}: {what}"


def read_limited(path: str | os.PathLike[str], *, limit: int, what: str = "file") -> bytes:
    """Read a regular file of at most ``limit`` bytes, refusing anything else.

    A FIFO, a device such as ``/dev/zero``, a directory, a symlink loop or a
    file larger than ``limit`` raises :class:`~symbolic_friction.InputFileError`
    with one line saying so, without blocking and without reading it whole;
    so does a path written with a trailing slash (a directory's spelling,
    which :class:`~pathlib.Path` would drop).
    """
    check_path(path, name="path", what=what)  # another type (3, None, b"x") or a NUL byte: refused by name
    if isinstance(path, str) and path.endswith(("/", os.sep)):
        raise InputFileError(f"cannot read {what} {path}: a trailing / names a directory, not a file")
    path = Path(path)
    try:
        # O_NONBLOCK: opening a FIFO must not wait for a writer.
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise InputFileError(f"cannot read {what} {describe_os_error(exc, path)}") from None
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise InputFileError(f"cannot read {what} {path}: is a directory")
        if not stat.S_ISREG(info.st_mode):
            raise InputFileError(f"cannot read {what} {path}: not a regular file (a FIFO, socket or device)")
        if info.st_size > limit:
            raise InputFileError(f"{what} {path} has {info.st_size} bytes; at most {limit} are accepted")
        with os.fdopen(fd, "rb", closefd=False) as handle:
            data = handle.read(limit + 1)
    except InputFileError:
        raise
    except OSError as exc:
        raise InputFileError(f"cannot read {what} {describe_os_error(exc, path)}") from None
    finally:
        os.close(fd)
    if len(data) > limit:
        raise InputFileError(f"{what} {path} has more than {limit} bytes; at most {limit} are accepted")
    return data


def ensure_directory(path: str | os.PathLike[str], *, what: str = "output directory") -> Path:
    """Create ``path`` (and its parents) if needed and check it is a writable directory.

    Called before any long computation, so that an unusable ``--out`` fails
    at once with one line instead of after the work.  An empty path is
    refused (it would silently mean the working directory).
    """
    if isinstance(path, str) and not path.strip():
        raise OutputPathError(f"{what} must name a directory; got {path!r} (use . for the working directory)")
    path = Path(path)
    try:
        if path.is_symlink() and not path.exists():
            raise OutputPathError(f"{what} {path} is a broken symbolic link or a symlink loop")
        if path.exists() and not path.is_dir():
            raise OutputPathError(f"{what} {path} exists and is not a directory")
        path.mkdir(parents=True, exist_ok=True)
        if not os.access(path, os.W_OK | os.X_OK):
            raise OutputPathError(f"{what} {path} is not writable")
    except OutputPathError:
        raise
    except OSError as exc:
        raise OutputPathError(f"cannot use {what} {describe_os_error(exc, path)}") from None
    return path


def _lstat_or_none(path: Path, prefix: str) -> os.stat_result | None:
    """``os.lstat(path)``, None if nothing is there; any other error is an :class:`OutputPathError` (``prefix`` + why)."""
    try:
        return os.lstat(path)
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise OutputPathError(prefix + describe_os_error(exc, path)) from None


def atomic_write(path: str | os.PathLike[str], write: Callable[[IO[bytes]], object]) -> Path:
    """Call ``write(handle)`` on a binary temporary file, then rename it to ``path``.

    Parameters
    ----------
    path : path-like
        Target file; its parent directories are created.
    write : callable
        Receives the open binary handle and writes the whole content.

    Returns
    -------
    Path
        ``path``.
    """
    _check_file_spelling(path, what="output file")
    path = Path(path)
    st = _lstat_or_none(path, "")
    if st is not None and not stat.S_ISREG(st.st_mode):
        return _write_through(path, st, write)
    path.parent.mkdir(parents=True, exist_ok=True)
    # mkstemp creates the file 0600; give the result the mode of the file it
    # replaces (or the usual 0644) so committed files stay world-readable.
    mode = st.st_mode & 0o777 if st is not None else 0o644
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        os.chmod(tmp, mode)
        with os.fdopen(fd, "wb") as handle:
            write(handle)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    return path


def _write_through(path: Path, st: os.stat_result, write: Callable[[IO[bytes]], object]) -> Path:
    """Write into a character device or a FIFO (``/dev/null``, a pipe), never replace it; refuse anything else.

    Replacing ``/dev/null`` by a regular file (as root, in a CI container) would
    break the system; a symbolic link is refused rather than followed or
    replaced, and so are directories, sockets and block devices.  A FIFO
    without a reader is refused rather than waited on; a write that fails
    (``/dev/full``: no space left) is an error.
    """
    mode = st.st_mode
    _refuse_special(path, mode)
    flags = os.O_WRONLY | (os.O_NONBLOCK if stat.S_ISFIFO(mode) else 0)
    try:
        fd = os.open(path, flags)
    except OSError as exc:
        if exc.errno == errno.ENXIO:  # a FIFO with no reader
            raise OutputPathError(f"{path}: is a FIFO with no reader; refusing to wait for one") from None
        raise OutputPathError(describe_os_error(exc, path)) from None
    try:
        if stat.S_ISFIFO(mode):
            os.set_blocking(fd, True)  # a reader is there: write all of it
        with os.fdopen(fd, "wb") as handle:
            write(handle)
            handle.flush()
    except OSError as exc:
        raise OutputPathError(describe_os_error(exc, path)) from None
    return path


def _refuse_special(path: Path, mode: int) -> None:
    """Refuse what is neither a regular file, a character device nor a FIFO (see :func:`_write_through`)."""
    if stat.S_ISLNK(mode):
        raise OutputPathError(f"{path}: is a symbolic link; give the file it points to (it is not replaced)")
    if stat.S_ISDIR(mode):
        raise OutputPathError(f"{path}: is a directory; give a file name")
    if not (stat.S_ISREG(mode) or stat.S_ISCHR(mode) or stat.S_ISFIFO(mode)):
        raise OutputPathError(f"{path}: is not a regular file, a character device or a FIFO; refusing to write to it")


def _check_file_spelling(path: str | os.PathLike[str], *, what: str) -> None:
    """Refuse an empty file name and a trailing slash, both lost once the text becomes a Path (``Path("x/")`` is ``x``)."""
    text = os.fspath(path)
    if not isinstance(text, str):  # pragma: no cover - the package passes str paths
        return
    if not text.strip():
        raise OutputPathError(f"{what} must name a file; got {text!r}")
    if text.endswith(("/", os.sep)):
        raise OutputPathError(f"{what} {text}: a trailing / names a directory, not a file")


_FIFO_PROBES: list[int] = []
"""Write ends of FIFOs probed by :func:`check_output_file`, held open until the process exits."""


def check_output_file(path: str | os.PathLike[str], *, what: str = "output file") -> Path:
    """Refuse, before any work, an output file that :func:`atomic_write` would refuse or could not create.

    Empty, ending in ``/``, a directory, a symbolic link (dangling or looping
    too), a socket or block device, a name too long, a path through a file or
    an unwritable directory: :class:`~symbolic_friction.OutputPathError`.  A
    regular file, a character device (``/dev/null``) or a FIFO with a reader
    passes; a FIFO without one is refused now rather than after the work.  A
    FIFO's probe keeps its write end open until the process ends, so that the
    reader does not see the end of the stream before the output is written.
    Nothing is created.
    """
    _check_file_spelling(path, what=what)
    path = Path(path)
    st = _lstat_or_none(path, f"cannot use {what} ")
    if st is not None:
        try:
            _refuse_special(path, st.st_mode)
        except OutputPathError as exc:
            raise OutputPathError(f"{what} {exc}") from None
        if stat.S_ISFIFO(st.st_mode):
            try:
                _FIFO_PROBES.append(os.open(path, os.O_WRONLY | os.O_NONBLOCK))
            except OSError as exc:
                if exc.errno == errno.ENXIO:
                    raise OutputPathError(f"{what} {path}: is a FIFO with no reader; refusing to wait for one") from None
                raise OutputPathError(f"cannot use {what} {describe_os_error(exc, path)}") from None
        return path
    check_output_directory(path.parent if str(path.parent) else Path("."), what=f"directory of {what}")
    return path


def atomic_write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` as UTF-8 with ``\\n`` line endings, atomically (see :func:`atomic_write`)."""
    data = text.encode("utf-8")
    return atomic_write(path, lambda handle: handle.write(data))


def check_output_directory(path: str | os.PathLike[str], *, what: str = "output directory") -> Path:
    """Check, without creating anything, that ``path`` could be created (or is) a writable directory.

    For outputs written only sometimes (counterexamples): the run fails at
    once on an unusable path, and a run that writes nothing leaves no empty
    directory behind.  An empty path is refused, as by :func:`ensure_directory`.
    """
    if isinstance(path, str) and not path.strip():
        raise OutputPathError(f"{what} must name a directory; got {path!r} (use . for the working directory)")
    path = Path(path)
    try:
        for part in path.parts:
            if len(part.encode("utf-8", "surrogateescape")) > 255:
                raise OSError(errno.ENAMETOOLONG, os.strerror(errno.ENAMETOOLONG), str(path))
        if path.is_symlink() and not path.exists():
            raise OutputPathError(f"{what} {path} is a broken symbolic link or a symlink loop")
        if path.exists():
            if not path.is_dir():
                raise OutputPathError(f"{what} {path} exists and is not a directory")
            existing = path
        else:
            os.lstat(path.parent) if str(path.parent) else None  # raises ENOTDIR / ELOOP on a bad component
            existing = path.parent
            while not existing.exists():
                existing = existing.parent
            if not existing.is_dir():
                raise OutputPathError(f"cannot use {what} {path}: {existing} is a file, not a directory")
        if not os.access(existing, os.W_OK | os.X_OK):
            raise OutputPathError(f"{what} {path} is not writable")
    except FileNotFoundError:
        pass  # a missing parent is created when the output is written
    except OSError as exc:
        if isinstance(exc, OutputPathError):
            raise
        raise OutputPathError(f"cannot use {what} {describe_os_error(exc, path)}") from None
    return path


def check_stem(stem: str, *, what: str = "--name") -> str:
    """A file stem written inside an output directory: no directory part, no ``..``, printable, not blank, bounded.

    Raises
    ------
    OutputPathError
        Naming what is wrong with ``stem`` (``certify --name ../x``, ``hunting --name /abs``, ``" "``).
    """
    if not stem or stem in (".", "..") or "/" in stem or "\\" in stem or stem.startswith("."):
        raise OutputPathError(
            f"{what} must be a plain file name without directories (it is written inside --out); got {stem!r}"
        )
    if len(stem) > STEM_MAX:
        raise OutputPathError(f"{what} must be at most {STEM_MAX} characters; got {len(stem)} characters")
    if not stem.isprintable():
        raise OutputPathError(f"{what} must hold printable characters only (no newlines or control characters); got {stem!r}")
    if stem != stem.strip():
        raise OutputPathError(f"{what} must not begin or end with white space; got {stem!r}")
    return stem
