"""Reading users' files safely and writing ours atomically."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from .diagnostics import Span, error


def read_text(path: str | Path) -> str:
    """Read a user's file as UTF-8, turning every OS and decoding failure into a diagnostic."""
    p = Path(path)
    try:
        data = p.read_bytes()
    except FileNotFoundError:
        raise error(f"no such file: {p}", Span(str(p)), "check the path and the current directory")
    except IsADirectoryError:
        raise error(f"{p} is a directory, not a file", Span(str(p)))
    except OSError as exc:
        raise error(f"cannot read {p}: {exc.strerror or exc}", Span(str(p)))
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
    except OSError as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise error(f"cannot write {p}: {exc.strerror or exc}", Span(str(p)))


def _umask() -> int:
    current = os.umask(0)
    os.umask(current)
    return current
