"""`.gg` imports: find modules (standard library or beside the importing file), read each once,
refuse cycles, and lay the statements of a file and its imports out in one list, each import
expanded at the place of its `import` line."""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Callable

from . import gg_ast as A
from .diagnostics import did_you_mean, error
from .fileio import read_text

ParseSyntax = Callable[[str, str], tuple]


@dataclass
class Unit:
    """One loaded file: its statements, where it is, and how deep in the import tree."""

    path: str
    text: str
    stmts: tuple
    depth: int

    @property
    def base(self) -> Path:
        return Path(self.path).parent


def stdlib_modules() -> list[str]:
    """Names of the modules shipped in the `ggstdlib` package, sorted."""
    try:
        root = resources.files("ggstdlib")
        return sorted(p.name[:-3] for p in root.iterdir() if p.name.endswith(".gg"))
    except (ModuleNotFoundError, OSError):
        return []


def expand(text: str, path: Path, parse: ParseSyntax) -> tuple[Unit, list[tuple[object, Unit]]]:
    """The root unit, and every statement of it and its imports (imports replaced by the
    imported statements; a module already read is skipped)."""
    root = Unit(str(path), text, parse(text, str(path)), 0)
    flat: list[tuple[object, Unit]] = []
    loaded = {_key(path)}

    def walk(unit: Unit, stack: list[str]) -> None:
        for stmt in unit.stmts:
            if not isinstance(stmt, A.Import):
                flat.append((stmt, unit))
                continue
            found, source = _find(stmt, unit)
            key = _key(found)
            if key in stack:
                chain = " → ".join(Path(k).name for k in stack[stack.index(key):] + [key])
                raise error(f"import cycle: {chain}", stmt.span,
                            "a module must not import itself, directly or through others",
                            source=unit.text)
            if key in loaded:
                continue
            loaded.add(key)
            walk(Unit(str(found), source, parse(source, str(found)), unit.depth + 1),
                 stack + [key])

    walk(root, [_key(path)])
    return root, flat


def _find(stmt: A.Import, unit: Unit) -> tuple[Path, str]:
    """A plain name is a standard module, else NAME.gg beside the importing file; a name with
    '/', a leading '.' or the .gg suffix is a path relative to the importing file."""
    name = stmt.target
    explicit = name.startswith((".", "/")) or name.endswith(".gg") or "/" in name
    if name and not explicit:
        try:
            lib = resources.files("ggstdlib") / f"{name}.gg"
            if lib.is_file():
                return Path(str(lib)), lib.read_text(encoding="utf-8")
        except (ModuleNotFoundError, OSError, ValueError):
            pass
    local = unit.base / name
    # Only a .gg file is a module: importing any other file must not show a line of it.
    if name and local.name:
        cand = local if local.suffix == ".gg" else local.with_name(local.name + ".gg")
        try:
            found = cand.is_file()
        except (OSError, ValueError) as exc:     # a name too long for the file system
            raise error(f"cannot import '{name[:60]}': {getattr(exc, 'strerror', None) or exc}",
                        stmt.span, "import a module by a shorter name or path",
                        source=unit.text) from None
        if found:
            return cand, read_text(cand)
    modules = stdlib_modules()
    hint = did_you_mean(name, modules) or (
        "standard modules: " + ", ".join(modules) +
        "; a file beside this one is imported as \"./name\"")
    raise error(f"no module named '{name}'", stmt.span, hint, source=unit.text)


def _key(path) -> str:
    try:
        return str(Path(str(path)).resolve())
    except (OSError, RuntimeError):
        return str(path)
