"""Input limits (docs/limits.md): each one refuses what is over it with a located diagnostic that
names its variable, every reader applies them, and the documented table is the code's."""

from __future__ import annotations

import contextlib
import io
import os
import re

import pytest

from compiler.canon import split
from compiler.cli import main as ggc
from compiler.infer import affordable
from conftest import CORPUS, ILLUSTRATIONS, ROOT
from grammar_lang import limits
from grammar_lang.diagnostics import UserError
from grammar_lang.fileio import read_text
from report.ggrun import main as ggrun

EXAMPLES = ROOT / "examples"


def run(cmd, argv) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = cmd(argv)
    return code, err.getvalue()


def test_the_documented_table_is_the_code():
    doc = (ROOT / "docs" / "limits.md").read_text(encoding="utf-8")
    rows = re.findall(r"^\| (\w+) \| `(GG_\w+)` \| ([\d,]+) \|", doc, re.M)
    assert rows == [(l.name, l.env, f"{l.default:,}") for l in limits.ALL]


@pytest.mark.parametrize("env, value, argv", [
    ("GG_MAX_BYTES", "100", ["check", str(EXAMPLES / "house.gg")]),
    ("GG_MAX_TOKENS", "50", ["check", str(EXAMPLES / "house.gg")]),
    ("GG_MAX_ELEMENTS", "3", ["check", str(EXAMPLES / "cottage.svg")]),
    ("GG_MAX_POINTS", "5", ["check", str(EXAMPLES / "house.gg")]),
    ("GG_MAX_POINTS", "5", ["check", str(CORPUS / "plus.svg")]),
    ("GG_MAX_POINTS", "5", ["check", str(CORPUS / "plus.json")]),
    ("GG_MAX_TOKENS", "50", ["verify", str(EXAMPLES / "square-walls.ggr")]),
])
def test_a_lowered_limit_refuses_with_its_name_and_variable(monkeypatch, env, value, argv):
    monkeypatch.setenv(env, value)
    code, err = run(ggc, argv)
    assert code == 2, err
    name = next(l.name for l in limits.ALL if l.env == env)
    assert f"over the {name} limit" in err and f"set {env}=N" in err
    assert re.search(r"^\S+: error:", err, re.M)


def test_the_same_inputs_pass_at_the_defaults():
    for argv in (["check", str(EXAMPLES / "house.gg")], ["check", str(EXAMPLES / "cottage.svg")],
                 ["check", str(CORPUS / "plus.json")]):
        assert run(ggc, argv)[0] == 0


def test_a_bad_limit_value_is_a_user_error(monkeypatch):
    monkeypatch.setenv("GG_MAX_POINTS", "lots")
    code, err = run(ggc, ["check", str(EXAMPLES / "house.gg")])
    assert code == 2 and "GG_MAX_POINTS" in err


def test_a_drawing_stops_at_the_drawing_limit(monkeypatch, tmp_path):
    monkeypatch.setenv("GG_MAX_DRAWING", "12")
    out = tmp_path / "d.json"
    code, err = run(ggrun, [str(EXAMPLES / "square-walls.ggr"), "--steps", "500", "--cost",
                            "none", "--out", str(out)])
    assert code == 0, err
    assert "vertex limit (12)" in err and "GG_MAX_DRAWING" in err
    assert 12 <= out.read_text().count('"id"') <= 20      # stopped at the step that reached it


def test_only_regular_files_are_read(tmp_path):
    fifo = tmp_path / "pipe.gg"
    os.mkfifo(fifo)
    link = tmp_path / "zero.gg"
    link.symlink_to("/dev/zero")
    for path in (fifo, link, "/dev/zero"):
        with pytest.raises(UserError, match="not a regular file"):
            read_text(path)


def test_crossings_count_against_the_points_limit(monkeypatch, tmp_path):
    # 300 scattered points: within the limit, but their segments cross thousands of times.
    monkeypatch.setenv("GG_MAX_POINTS", "400")
    pts = " ".join(f"({(k * 7919) % 10007}, {(k * 104729) % 9973})" for k in range(300))
    f = tmp_path / "tangle.gg"
    f.write_text(f"polyline {pts}\n", encoding="utf-8")
    code, err = run(ggc, ["check", str(f)])
    assert code == 2 and "crossings" in err and "GG_MAX_POINTS" in err


def test_example_starters_are_bounded_by_work():
    """Components cost n² each, smallest first, until the budget is spent."""
    verts = [0] * 12
    edges = [(0, 0, 1, 1), (2, 0, 3, 1), (3, 0, 4, 1)] + [(k, 0, k + 1, 1) for k in range(5, 11)]
    parts = split(verts, edges)
    sizes = sorted(len(g.verts) for g in parts)
    assert sizes == [2, 3, 7]
    assert [len(g.verts) for g in affordable(parts, 4 + 9)] == [2, 3]
    assert [len(g.verts) for g in affordable(parts, 4 + 9 + 48)] == [2, 3]
    assert [len(g.verts) for g in affordable(parts, 4 + 9 + 49)] == [2, 3, 7]


def test_a_frame_over_the_extent_limit_is_refused_before_it_is_placed(monkeypatch, tmp_path):
    """A side is filed in every grid cell it crosses: a frame of 10,000,000 px took 76 s and
    736 MB for twenty steps. The limit counts those cells and names its variable; the shipped
    scenes, at their own extents and at the paper's, are far under it."""
    out = str(tmp_path / "c.svg")
    castle = str(ILLUSTRATIONS / "castle.gg")
    code, err = run(ggrun, [castle, "--extent", "10000000x5000000", "--steps", "2", "--out", out])
    assert code == 2 and "over the extent limit" in err and "set GG_MAX_EXTENT=N" in err
    assert "10,000,000 × 5,000,000 frame" in err
    assert run(ggrun, [castle, "--extent", "2720x1600", "--steps", "2", "--out", out])[0] == 0
    monkeypatch.setenv("GG_MAX_EXTENT", "100")
    code, err = run(ggrun, [str(EXAMPLES / "castle-scene.gg"), "--steps", "2", "--out", out])
    assert code == 2 and "over the extent limit" in err
