"""Every command shown in docs/cli.md, docs/scenes.md and the README runs as shipped."""

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
README_COMMANDS = commands(ROOT / "README.md")
SCENES_COMMANDS = commands(ROOT / "docs" / "scenes.md")
REPORT_COMMANDS = commands(ROOT / "docs" / "report.md")


def run(command: str, cwd: Path) -> subprocess.CompletedProcess:
    argv = shlex.split(command, comments=True)
    assert argv[0] in ("ggc", "ggrun")
    env = dict(os.environ, PATH=f"{BIN}{os.pathsep}{os.environ.get('PATH', '')}")
    return subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=300,
                          stdin=subprocess.DEVNULL)


def test_the_docs_have_commands():
    assert len(CLI_COMMANDS) >= 8 and len(README_COMMANDS) >= 6


DOCS = {"cli.md": CLI_COMMANDS, "README.md": README_COMMANDS, "scenes.md": SCENES_COMMANDS,
        "report.md": REPORT_COMMANDS}


@pytest.mark.parametrize("doc", sorted(DOCS))
def test_documented_commands_run_in_order(doc, tmp_path):
    # A page's commands build on each other (compile, then verify the file it wrote), so they
    # run in order in one directory of their own, whichever test worker takes the page.
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    (tmp_path / "out").mkdir()
    for command in DOCS[doc]:
        res = run(command, tmp_path)
        assert res.returncode == 0, f"{doc}: $ {command}\n{res.stderr}"
        assert "Traceback" not in res.stderr, f"{doc}: $ {command}\n{res.stderr}"
        verify_drawing(command, tmp_path, doc)


def verify_drawing(command: str, cwd: Path, doc: str) -> None:
    """A documented drawing of an example (or of a grammar ggc compiled from one) is locally
    similar to it: the same run, written as JSON, passes `ggrun check`. (`--extent 2400x900`
    on the castle scene once drew a frame side its border class refused.)"""
    argv = shlex.split(command, comments=True)
    if argv[0] != "ggrun" or argv[1] in ("check", "--repl") or "--count" in argv:
        return
    source = cwd / argv[1]
    if source.suffix == ".ggr" and not source.read_text().startswith("# Graph grammar rules "
                                                                      "written by ggc"):
        return                       # hand-written productions: no example to check against
    argv[argv.index("--out") + 1] = "verify.json"
    if "--width" in argv:                        # a PNG's option
        del argv[argv.index("--width"):argv.index("--width") + 2]
    assert run(shlex.join(argv), cwd).returncode == 0
    res = run(shlex.join(["ggrun", "check", argv[1], "verify.json"]), cwd)
    assert res.returncode == 0, f"{doc}: $ {command}: its drawing fails the verifier\n{res.stdout}"


def test_readme_main_command_draws(workdir):
    text = (ROOT / "README.md").read_text()
    main = re.search(r"```sh\n(python3 -m venv .*)\n```", text).group(1)
    command = main.split("&&")[-1].strip()
    assert command.startswith("ggrun examples/")
    res = run(command, workdir)
    assert res.returncode == 0, res.stderr
    out = workdir / shlex.split(command)[-1]
    assert out.read_text().startswith("<svg")
