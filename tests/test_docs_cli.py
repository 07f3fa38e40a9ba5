"""Every command shown in docs/cli.md and the README runs as shipped."""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent


def commands(doc: Path) -> list[str]:
    out = []
    for block in re.findall(r"```(?:console|sh)\n(.*?)```", doc.read_text(), re.S):
        out += [line[2:] for line in block.splitlines() if line.startswith("$ ")]
    return out


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    d = tmp_path_factory.mktemp("docs")
    shutil.copytree(ROOT / "examples", d / "examples")
    (d / "out").mkdir()
    return d


CLI_COMMANDS = commands(ROOT / "docs" / "cli.md")


def test_the_cli_doc_has_commands():
    assert len(CLI_COMMANDS) >= 8


@pytest.mark.parametrize("command", CLI_COMMANDS)
def test_cli_doc_command_runs(command, workdir):
    argv = shlex.split(command)
    assert argv[0] in ("ggc", "ggrun")
    env = dict(os.environ, PATH=f"{BIN}{os.pathsep}{os.environ.get('PATH', '')}")
    res = subprocess.run(argv, cwd=workdir, env=env, capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    assert "Traceback" not in res.stderr
