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


# runtime/ by role: each subpackage holds these modules, and nothing else sits at the top.
RUNTIME_LAYOUT = {
    "engine": {"host", "matching", "rewrite", "schedule", "costs", "generate",
               "free_host", "free_match", "free_engine", "late"},
    "geometry": {"solver", "slides", "spatial", "faces", "landing", "framing", "tables",
                 "change", "rejections", "min_norm", "system", "rounds", "freeing",
                 "planarity", "stands"},
    "output": {"drawing", "svg_out", "bending", "graphml_out", "free_svg"},
    "repl": {"session", "commands", "complete"},
    "": {"cli", "run_cmd", "interrupt", "verifier"},
}
# Which roles a role may import from. The geometry is the layer below the engine: the engine
# plans a change and asks the solver where its vertices go, and the geometry sees the host only
# through its own `HostView`, so it imports no other role. The engine takes from output only
# the drawing value, and nothing below the front ends imports the REPL or the command line.
MAY_IMPORT = {
    "engine": {"geometry", "output.drawing"},
    "geometry": set(),
    "output": {"engine", "geometry", "verifier"},
    "verifier": {"geometry", "output"},
    "repl": {"engine", "geometry", "output", "verifier", "run_cmd"},
    "run_cmd": {"engine", "output", "interrupt"},
    "cli": {"repl", "run_cmd", "verifier"},
    "interrupt": set(),
}


def test_runtime_is_laid_out_by_role():
    found = {}
    for path in (ROOT / "runtime").rglob("*.py"):
        parts = path.relative_to(ROOT / "runtime").parts
        if path.name != "__init__.py":
            found.setdefault(parts[0] if len(parts) > 1 else "", set()).add(path.stem)
        assert len(parts) <= 2, f"{path}: one level of subpackages only"
    assert found == RUNTIME_LAYOUT
    for pkg in RUNTIME_LAYOUT:
        init = ROOT / "runtime" / pkg / "__init__.py"
        assert ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))), init


def runtime_imports(path: Path, text: str | None = None):
    """(line, role or role.module) of every import of another runtime module by `path` (whose
    source is `text`, when given)."""
    parts = path.relative_to(ROOT).with_suffix("").parts      # ('runtime', pkg..., module)
    source = path.read_text(encoding="utf-8") if text is None else text
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.ImportFrom):
            continue
        if node.level:
            base = list(parts[:len(parts) - node.level])
            target = base + (node.module.split(".") if node.module else [])
        elif node.module and node.module.split(".")[0] == "runtime":
            target = node.module.split(".")
        else:
            continue
        rest = target[1:] or [a.name for a in node.names][:1]
        yield node.lineno, ".".join(rest[:2]) if rest[0] in RUNTIME_LAYOUT else rest[0]


def test_runtime_roles_import_only_what_they_may():
    bad = []
    for path in sorted((ROOT / "runtime").rglob("*.py")):
        parts = path.relative_to(ROOT / "runtime").parts
        role = parts[0] if len(parts) > 1 else path.stem
        if role == "__init__.py" or role == "__init__":
            continue
        for line, target in runtime_imports(path):
            top = target.split(".")[0]
            if top != role and top not in MAY_IMPORT[role] and target not in MAY_IMPORT[role]:
                bad.append(f"{path.relative_to(ROOT)}:{line} ({role}) imports {target}")
    assert not bad, "\n".join(bad)



def test_the_geometry_may_not_import_the_engine_even_for_annotations():
    assert "engine" not in MAY_IMPORT["geometry"] and "geometry" in MAY_IMPORT["engine"]
    guarded = ("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
               "    from ..engine.host import Host\n")
    found = list(runtime_imports(ROOT / "runtime" / "geometry" / "solver.py", guarded))
    assert found == [(3, "engine.host")]
