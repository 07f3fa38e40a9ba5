"""Random and mutated `.gg` text never crashes the parser or `ggc check`: it gives a diagnostic."""

from __future__ import annotations

import contextlib
import io
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings, strategies as st

from conftest import ROOT
from grammar_lang.diagnostics import EXCERPT_WIDTH, UserError
from grammar_lang.gg_parser import STATEMENT_KEYWORDS, parse_text
from grammar_lang.source import ExampleSource

EXAMPLES = ROOT / "examples"
SEEDS = [p.read_text(encoding="utf-8") for p in sorted(EXAMPLES.glob("*.gg"))] + [
    m.group(1) for m in re.finditer(r"^```gg\n(.*?)^```",
                                    (ROOT / "docs" / "gg-language.md").read_text(encoding="utf-8"),
                                    re.S | re.M)]
VOCAB = [*STATEMENT_KEYWORDS, "hole", "rect", "left", "right", "from", "(", ")", "[", "]", "{",
         "}", ",", ";", ":", "->", "*", "\n", "//", "/*", "*/", '"', "'", "\\", "#", "#c0f0ff",
         "#ggg", "0", "-1.5e3", "1e999", "10deg", "5s", "80%", "°", "wall", "exterior", "inside",
         '"cottage.svg"', '"pastel"', '"ground"', '"./x"', "\t", "\x0c", "\u2028", "\x00", "é",
         "min:", "max: -1", '"/"', '""', '".."', "rename", "a -> b", "rigid", "border", "fill: red", "(0, 0)", "(1e308, -1e308)"]
FUZZ = settings(max_examples=200, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def _check_outcome(text: str) -> None:
    """Parsing gives an ExampleSource or a UserError whose diagnostics render with a place."""
    try:
        result = parse_text(text, "fuzz.gg")
    except UserError as exc:
        rendered = exc.render()
        assert "error:" in rendered
        n_lines = text.count("\n") + 1
        for d in exc.diagnostics:
            assert d.span is not None and d.span.file
            assert 0 <= d.span.line <= n_lines + 1
            assert d.hint, d.message
            if d.source is not None and 1 <= d.span.line <= d.source.count("\n") + 1:
                # the excerpt shows the line the parser counted (lines end at "\n" only)
                shown = d.source.split("\n")[d.span.line - 1].rstrip("\r").expandtabs(1)
                first = d.excerpt().split("\n")[0]
                if len(shown) <= EXCERPT_WIDTH:
                    assert first.endswith(shown)
                else:       # a long line is shown around the column, clipped with '…'
                    assert first.split(" | ", 1)[1].strip("…") in shown
        return
    assert isinstance(result, ExampleSource)


@st.composite
def mutated(draw):
    text = draw(st.sampled_from(SEEDS))
    for _ in range(draw(st.integers(1, 4))):
        op = draw(st.sampled_from(["delete", "insert", "replace", "swap-lines", "dup-line",
                                   "truncate"]))
        n = len(text)
        i = draw(st.integers(0, n))
        if op == "delete":
            text = text[:i] + text[i + draw(st.integers(1, 12)):]
        elif op == "insert":
            text = text[:i] + draw(st.sampled_from(VOCAB)) + text[i:]
        elif op == "replace" and n:
            j = min(i, n - 1)
            text = text[:j] + draw(st.characters(blacklist_categories=("Cs",))) + text[j + 1:]
        elif op in ("swap-lines", "dup-line"):
            lines = text.split("\n")
            a = draw(st.integers(0, len(lines) - 1))
            b = draw(st.integers(0, len(lines) - 1))
            if op == "swap-lines":
                lines[a], lines[b] = lines[b], lines[a]
            else:
                lines.insert(b, lines[a])
            text = "\n".join(lines)
        elif op == "truncate":
            text = text[:i]
    return text


token_soup = st.lists(st.sampled_from(VOCAB), max_size=40).map(" ".join)


@FUZZ
@given(st.text(max_size=200))
def test_random_text_gives_a_diagnostic(text):
    _check_outcome(text)


@FUZZ
@given(token_soup)
def test_token_soup_gives_a_diagnostic(text):
    _check_outcome(text)


@FUZZ
@given(mutated())
def test_mutated_examples_give_a_diagnostic(text):
    _check_outcome(text)


_WORK = Path(tempfile.mkdtemp(prefix="gg-fuzz-"))
shutil.copy(EXAMPLES / "cottage.svg", _WORK / "cottage.svg")


def _ggc_check(text: str) -> tuple[int, str]:
    from compiler.cli import main
    path = _WORK / "fuzz.gg"
    path.write_text(text, encoding="utf-8")
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["check", str(path)])
    return code, err.getvalue()


@settings(max_examples=100, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(st.one_of(mutated(), token_soup))
def test_ggc_check_exits_0_or_2_never_crashes(text):
    code, err = _ggc_check(text)
    assert code in (0, 2), err
    if code == 2:
        assert "error:" in err and "Traceback" not in err and "internal error" not in err


def test_ggc_console_script_on_a_broken_file(tmp_path):
    bad = tmp_path / "bad.gg"
    bad.write_text("face wall\npolygon wal (0, 0) (1, 0) (1, 1\n", encoding="utf-8")
    run = subprocess.run([sys.executable, "-m", "compiler.cli", "check", str(bad)],
                         capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert run.returncode == 2
    assert f"{bad}:2:" in run.stderr and "^" in run.stderr and "hint:" in run.stderr
    assert "Traceback" not in run.stderr
