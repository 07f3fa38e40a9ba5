"""Files are read safely and written atomically, with the usual permissions."""

import os
import stat

import pytest

from grammar_lang.diagnostics import UserError
from grammar_lang.fileio import atomic_write, read_text


def test_atomic_write_replaces_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "out.svg"
    atomic_write(target, "first")
    atomic_write(target, "second")
    assert target.read_text() == "second"
    assert [p.name for p in tmp_path.iterdir()] == ["out.svg"]


def test_new_files_get_the_umask_mode_and_old_files_keep_theirs(tmp_path):
    fresh = tmp_path / "fresh.json"
    atomic_write(fresh, "{}")
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(fresh.stat().st_mode) == 0o666 & ~umask
    kept = tmp_path / "kept.json"
    kept.write_text("old")
    kept.chmod(0o640)
    atomic_write(kept, "new")
    assert stat.S_IMODE(kept.stat().st_mode) == 0o640


def test_unwritable_place_is_a_diagnostic(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(UserError) as info:
        atomic_write(blocker / "inside.txt", "text")
    assert "cannot write" in info.value.render()


@pytest.mark.parametrize("content, message", [
    (b"\xff\xfe\x00bad", "not valid UTF-8"),
    (b"a\x00b", "NUL bytes"),
])
def test_unreadable_text_is_a_diagnostic(tmp_path, content, message):
    f = tmp_path / "in.gg"
    f.write_bytes(content)
    with pytest.raises(UserError) as info:
        read_text(f)
    assert message in info.value.render()


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(UserError, match="no such file"):
        read_text(tmp_path / "nope.gg")
    with pytest.raises(UserError, match="is a directory"):
        read_text(tmp_path)


def test_an_interrupted_write_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    """Ctrl-C (or any exception) in the middle of a write: the old content stays whole and
    the temporary file is removed."""
    import os

    from grammar_lang.fileio import atomic_write
    target = tmp_path / "out.svg"
    target.write_text("old", encoding="utf-8")

    def interrupted(fd):
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "fsync", interrupted)
    try:
        atomic_write(target, "new")
    except KeyboardInterrupt:
        pass
    else:
        raise AssertionError("the interrupt was swallowed")
    assert target.read_text(encoding="utf-8") == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.svg"]
