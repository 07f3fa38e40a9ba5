"""Start-up stays light: `ggrun --version`, `ggc --version` and their `--help` load none of the
heavy libraries (numpy, scipy, lark, rich, networkx, shapely). A structural test, not a timed
one: each console script of pyproject.toml runs in a fresh interpreter, which then reports
what is in `sys.modules`. Importing one of these at a module's top on the start-up path (the
CLI modules, the argument set-up, the shared model they annotate with) makes it fail."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
HEAVY = {"numpy", "scipy", "lark", "rich", "networkx", "shapely", "prompt_toolkit"}

PROBE = """
import json, sys
from {module} import {func} as main
try:
    main(*{args!r})
except SystemExit:
    pass
print(json.dumps(sorted({{m.split('.')[0] for m in sys.modules}})), file=sys.stderr)
"""


def console_scripts() -> dict[str, str]:
    """name → "module:function", read from pyproject.toml's [project.scripts]."""
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    section = re.search(r"^\[project\.scripts\]\n(.*?)(?=^\[|\Z)", text, re.M | re.S)
    assert section, "pyproject.toml has no [project.scripts]"
    return dict(re.findall(r'^(\w+)\s*=\s*"([\w.]+:\w+)"', section.group(1), re.M))


def loaded_packages(target: str, *args) -> set[str]:
    """The top-level packages loaded after `module.function(*args)` ran in a fresh process."""
    module, func = target.split(":")
    proc = subprocess.run([sys.executable, "-c", PROBE.format(module=module, func=func,
                                                              args=args)],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    return set(json.loads(proc.stderr.strip().splitlines()[-1]))


def test_both_commands_are_declared():
    assert set(console_scripts()) == {"ggc", "ggrun"}


@pytest.mark.parametrize("flag", ["--version", "--help"])
@pytest.mark.parametrize("name", ["ggc", "ggrun"])
def test_start_up_loads_no_heavy_library(name, flag):
    loaded = loaded_packages(console_scripts()[name], [flag])
    assert "grammar_lang" in loaded            # the probe did run the command
    assert not loaded & HEAVY, f"{name} {flag} imports {sorted(loaded & HEAVY)}"


def test_the_probe_sees_a_heavy_import():
    # The check can fail: a command that does load numpy is reported.
    assert "numpy" in loaded_packages("grammar_lang.blas:pin_blas_threads")
