"""The pipeline's layers: grammar_lang below; compiler and runtime on it, never on each other;
report (the report and the two entry points) above both. Imports are read from the source,
so an import done through importlib or `__import__` with a string is caught too."""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
FORBIDDEN = {
    "grammar_lang": {"compiler", "runtime", "report"},
    "compiler": {"runtime", "report"},
    "runtime": {"compiler", "report"},
    "report": set(),
}


def imported(tree: ast.AST):
    """(line, top-level package) of every import, static or by a string."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield node.lineno, a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.lineno, node.module.split(".")[0]
        elif isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Constant) \
                and isinstance(node.args[0].value, str):
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
            if name in ("import_module", "__import__"):
                yield node.lineno, node.args[0].value.split(".")[0]


@pytest.mark.parametrize("package", sorted(FORBIDDEN))
def test_no_layer_imports_what_it_must_not(package):
    bad = []
    for path in sorted((ROOT / package).rglob("*.py")):
        for line, top in imported(ast.parse(path.read_text(encoding="utf-8"))):
            if top in FORBIDDEN[package]:
                bad.append(f"{path.relative_to(ROOT)}:{line} imports {top}")
    assert not bad, "\n".join(bad)


def test_the_check_sees_imports_by_string():
    tree = ast.parse("import importlib\nx = importlib.import_module('compiler.infer')\n"
                     "y = __import__('runtime')\n")
    assert {top for _, top in imported(tree)} >= {"compiler", "runtime"}
