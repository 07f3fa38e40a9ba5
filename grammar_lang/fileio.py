"""Reading users' files safely and writing ours atomically."""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path

from . import limits
from .diagnostics import Span, error


def read_text(path: str | Path) -> str:
    """Read a user's file as UTF-8, turning every OS and decoding failure into a diagnostic.
    Only regular files are read (a FIFO or a device would block or never end), and only up to
    the input byte limit."""
    p = Path(path)
    data = read_bytes(p)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        col = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise error("the file is not valid UTF-8 text", Span(str(p), line, col),
                    "save the file with UTF-8 encoding")
    if "\x00" in text:
        raise error("the file contains NUL bytes; is it a binary file?", Span(str(p)))
    return text


def read_bytes(p: Path) -> bytes:
    """The bytes of a regular file of at most `limits.BYTES`, checked on the open file."""
    try:
        # O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        raise error(f"no such file: {p}", Span(str(p)), "check the path and the current directory")
    except IsADirectoryError:
        raise error(f"{p} is a directory, not a file", Span(str(p)))
    except (OSError, ValueError) as exc:
        raise error(f"cannot read {p}: {getattr(exc, 'strerror', None) or exc}", Span(str(p)))
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise error(f"{p} is a directory, not a file", Span(str(p)))
        if not stat.S_ISREG(info.st_mode):
            raise error(f"{p} is not a regular file (a pipe, device or socket)", Span(str(p)),
                        "give a file saved on disk")
        limit = limits.BYTES.value()
        if info.st_size > limit:
            raise limits.BYTES.exceeded(info.st_size, Span(str(p)))
        with os.fdopen(fd, "rb", closefd=False) as fh:
            data = fh.read(limit + 1)
    except OSError as exc:
        raise error(f"cannot read {p}: {exc.strerror or exc}", Span(str(p)))
    finally:
        os.close(fd)
    if len(data) > limit:     # the file grew while it was read
        raise limits.BYTES.exceeded(len(data), Span(str(p)))
    return data


def atomic_write(path: str | Path, text: str | bytes) -> None:
    """Write `text` (or bytes) so that `path` holds either its old or its new content, never a
    torn file."""
    p = Path(path)
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent)
    except OSError as exc:
        raise error(f"cannot write {p}: {exc.strerror or exc}", Span(str(p)))
    try:
        # mkstemp makes the file private (0600); a user's output should get the usual mode,
        # or keep the mode of the file it replaces.
        try:
            mode = p.stat().st_mode & 0o777
        except OSError:
            mode = 0o666 & ~_umask()
        os.chmod(tmp, mode)
        binary = isinstance(text, bytes)
        with (os.fdopen(fd, "wb") if binary else
              os.fdopen(fd, "w", encoding="utf-8", newline="\n")) as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, p)
    except BaseException as exc:
        # Also on Ctrl-C: the old file stays whole and no temporary file is left behind.
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError):
            raise error(f"cannot write {p}: {exc.strerror or exc}", Span(str(p))) from None
        raise


def _umask() -> int:
    current = os.umask(0)
    os.umask(current)
    return current
