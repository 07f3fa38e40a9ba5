"""Ctrl-C during `ggrun`: exit 130, the drawings written so far are whole, the running ones are
written as they stood, workers stop promptly, and no temporary file is left behind."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from conftest import ROOT
from grammar_lang.ggr_parser import load_ggr
from runtime.output.drawing import load_drawing
from runtime.verifier import check_drawing

GRAMMAR = ROOT / "examples" / "square-walls.ggr"


def _interrupt(tmp_path, extra, group: bool):
    cmd = [sys.executable, "-m", "report.ggrun", str(GRAMMAR), "--steps", "400", "--cost", "none",
           "--count", "200", "--out", str(tmp_path / "d.json"), "--quiet", *extra]
    p = subprocess.Popen(cmd, stderr=subprocess.PIPE, text=True, start_new_session=True,
                         env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    deadline = time.monotonic() + 120
    # The first written drawing shows that generation (and its Ctrl-C handler) has started.
    while not any(f.name.endswith(".json") for f in tmp_path.iterdir()):
        assert p.poll() is None and time.monotonic() < deadline
        time.sleep(0.05)
    t0 = time.monotonic()
    (os.killpg if group else os.kill)(p.pid, signal.SIGINT)
    try:
        err = p.communicate(timeout=30)[1]
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        raise
    return p.returncode, time.monotonic() - t0, err


@pytest.mark.parametrize("extra, group", [([], True), (["--jobs", "2"], True),
                                          (["--jobs", "2"], False)])
def test_ctrl_c_writes_the_last_drawings_and_exits_130(tmp_path, extra, group):
    rc, seconds, err = _interrupt(tmp_path, extra, group)
    assert rc == 130, err
    assert "interrupted: wrote the last valid drawing" in err
    assert "Traceback" not in err
    # Prompt: the runs stop within a step; what remains is writing the drawings and exiting.
    assert seconds < 10
    files = sorted(tmp_path.iterdir())
    assert not [f for f in files if f.name.endswith(".tmp")]
    written = [f for f in files if f.suffix == ".json"]
    assert 1 <= len(written) < 200
    # Whole files, each a valid drawing. One interrupted mid-run may be empty: with no cost
    # the square's starter also takes the square away (seed 1 is empty at step 64).
    drawings = [load_drawing(f) for f in written]
    grammar = load_ggr(GRAMMAR)
    for d in drawings:
        assert check_drawing(grammar, d) == []
    assert any(d.vertices for d in drawings)
