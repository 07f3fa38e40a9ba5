"""`ggrun --repl [FILE]`: explore a grammar one rewrite at a time.

The session holds one `generate.Engine` (the same engine `ggrun` runs) and drives it one
operation at a time: list a rule's matches, apply a rule at a chosen match in either direction,
step the schedule, undo and redo. Everything that changes the drawing goes through the engine's
history, `reset` and `open` included, so `undo` always leads back to the start.

On a terminal the loop reads lines with prompt_toolkit (history across runs, completion) and
prints through rich; otherwise it reads commands line by line, prints plain text (errors on
stderr) and exits 1 if any command failed. The commands themselves are in
runtime.repl.commands, tab completion in runtime.repl.complete.
"""

from __future__ import annotations

import argparse
import os
import shlex
import signal
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import TextIO

from grammar_lang.diagnostics import UserError, did_you_mean, error
from grammar_lang.rules import Grammar, Rule

from ..engine.costs import parse_cost
from ..engine.generate import Engine
from ..engine.rewrite import DirectedRule
from ..run_cmd import (DEFAULT_STEPS, check_limits, load_grammar, parse_extent, parse_limits,
                       size_target, write_drawing)

PROMPT = "gg> "


class Interrupted(Exception):
    """Ctrl-C during a long command; raised between steps, never inside one."""


class Quit(Exception):
    """`quit`: leave the loop."""


@dataclass
class Options:
    """What `ggrun`'s flags say about generation; the REPL builds its engine the same way."""

    seed: int = 0
    steps: int = DEFAULT_STEPS        # the size cost's target, as for `ggrun --steps`
    cost: str | None = None
    temperature: float = 1.0
    limits: tuple[tuple[int, int], ...] = ()
    bidirectional: bool | None = None
    extent: str | None = None         # `--extent W×H`, read against each grammar loaded

    @staticmethod
    def from_args(args: argparse.Namespace) -> "Options":
        both = None if args.direction is None else args.direction == "both"
        return Options(args.seed, size_target(args.steps, args.iterations), args.cost,
                       args.temperature, parse_limits(args.limit), both, args.extent)


class Output:
    """Where command output goes: rich with colours on a terminal, plain text otherwise."""

    def __init__(self, out: TextIO, err: TextIO, colour: bool):
        self.out, self.err = out, err
        self.console = None
        if colour:
            from rich.console import Console
            self.console = Console(file=out, highlight=False, soft_wrap=True)

    def line(self, text: str = "", style: str | None = None) -> None:
        if self.console is not None:
            self.console.print(text, style=style, markup=False, highlight=False)
        else:
            self.out.write(text + "\n")

    def problem(self, text: str, first: str = "bold red") -> None:
        """An error (or, with `first` another style, a warning), to stderr off a terminal."""
        if self.console is not None:
            for k, part in enumerate(text.split("\n")):
                hint = part.lstrip().startswith("hint:")
                self.console.print(part, style="yellow" if hint else first if k == 0 else None,
                                   markup=False, highlight=False)
        else:
            self.out.flush()
            self.err.write(text + "\n")
            self.err.flush()


@dataclass
class Session:
    out: Output
    options: Options = field(default_factory=Options)
    path: str | None = None
    grammar: Grammar | None = None
    engine: Engine | None = None
    watch: str | None = None
    interrupted: bool = False
    compile_example: object = None      # the compiler, when the entry point hands it in
    _directed: dict = field(default_factory=dict)

    # --- the grammar ------------------------------------------------------------------------
    def load(self, path: str) -> None:
        """Load a grammar (.ggr) or compile an example (.gg, .svg); the old session stays on
        any error. Its warnings are shown as ggrun shows them."""
        from grammar_lang.reach import connected_warning
        warnings: list = []
        grammar = load_grammar(path, self.compile_example, warnings.append)
        self.use(grammar, path)
        gap = connected_warning(grammar)
        for w in warnings + ([gap] if gap is not None else []):
            self.out.problem(w.render(), first="bold yellow")

    def use(self, grammar: Grammar, path: str) -> None:
        """Start a session on a grammar already in memory."""
        if grammar.is_free:
            raise error(f"{Path(path).name} holds hand-written productions; the REPL explores "
                        "angle-graph rules", None,
                        f"run them with 'ggrun {Path(path).name} --steps N --out FILE.svg'")
        o = self.options
        check_limits(o.limits, grammar)
        try:
            engine = Engine(grammar, o.seed, parse_cost(o.cost, grammar.header.labels, o.steps,
                                                      grammar.header),
                            o.temperature, bidirectional=o.bidirectional, limits=dict(o.limits),
                            extent=parse_extent(o.extent, grammar))
        except ValueError as exc:
            raise error(f"cannot run '{Path(path).name}': {exc}", None,
                        "check the grammar with 'ggc check'") from None
        self.path, self.grammar, self.engine = path, grammar, engine
        self._directed = {}

    def need_engine(self) -> Engine:
        if self.engine is None:
            raise error("no grammar loaded", None, "load one first: 'load FILE.ggr' "
                        "(or .gg, .svg)")
        return self.engine

    @property
    def name(self) -> str:
        return Path(self.path).name if self.path else "(none)"

    def rule(self, name: str) -> Rule:
        self.need_engine()
        for r in self.grammar.rules:
            if r.name == name:
                return r
        known = [r.name for r in self.grammar.rules]
        raise error(f"no rule '{name}'", None,
                    did_you_mean(name, known) or "rules: " + ", ".join(known[:20])
                    + (" …" if len(known) > 20 else ""))

    def directed(self, rule: Rule, forward: bool) -> DirectedRule:
        """The rule in one direction, built once; the schedule's own when it has it."""
        key = (rule.name, forward)
        if key not in self._directed:
            found = [m for m in self.engine.moves() if m.rule is rule and m.forward == forward]
            self._directed[key] = found[0] if found else \
                DirectedRule.build(rule, forward, self.grammar.rings)
        return self._directed[key]

    # --- after every change -----------------------------------------------------------------
    def changed(self) -> None:
        if self.watch is not None and self.engine is not None:
            try:
                self.render(self.watch)
            except UserError as exc:
                self.out.problem(f"watch: {exc.render()}")

    def drawing(self):
        e = self.need_engine()
        return e.host.to_drawing({"grammar": self.name, "seed": e.seed,
                                  "steps": len(e.history)})

    def render(self, path: str) -> None:
        write_drawing(self.drawing(), self.grammar, path)

    def check_interrupt(self, _summary=None) -> None:
        if self.interrupted:
            self.interrupted = False
            raise Interrupted()


def split_line(line: str) -> list[str]:
    try:
        return shlex.split(line, comments=True)
    except ValueError as exc:
        raise error(f"cannot read the command: {exc}", None,
                    "quote a name with spaces as \"my file.svg\"") from None


def execute(session: Session, line: str) -> bool:
    """Run one command line; True when it succeeded. Never raises for anything typed."""
    from .commands import dispatch
    try:
        words = split_line(line)
        if not words:
            return True
        return dispatch(session, words) is not False
    except Quit:
        raise
    except UserError as exc:
        session.out.problem(exc.render())
    except Interrupted:
        session.out.problem("interrupted; the drawing is as the last finished step left it")
    except RecursionError as exc:
        session.out.problem(f"error: input too deeply nested ({exc})")
    except Exception as exc:  # noqa: BLE001 - a bug must not end the session or lose its state
        session.out.problem(f"internal error: {type(exc).__name__}: {exc}\n"
                            "  hint: this is a bug in ggrun; the session goes on")
    return False


def run_script(session: Session, stream: TextIO, echo: bool = False) -> int:
    """Commands line by line: 0 when every one succeeded, else 1. `echo` writes each
    command after a prompt first, which makes the output a transcript."""
    ok = True
    for line in stream:
        if echo:
            session.out.line(PROMPT + line.rstrip("\n"))
        try:
            ok = execute(session, line.rstrip("\n")) and ok
        except Quit:
            break
    return 0 if ok else 1


def state_dir() -> Path:
    base = os.environ.get("XDG_STATE_HOME") or os.path.join(os.path.expanduser("~"), ".local",
                                                            "state")
    return Path(base) / "gg"


def run_terminal(session: Session) -> int:
    from prompt_toolkit import PromptSession
    from prompt_toolkit.history import FileHistory, InMemoryHistory

    from .complete import completer
    try:
        state_dir().mkdir(parents=True, exist_ok=True)
        history = FileHistory(str(state_dir() / "history"))
    except OSError:
        history = InMemoryHistory()
    prompt = PromptSession(history=history, completer=completer(session),
                           complete_while_typing=False)
    session.out.line("ggrun REPL: 'help' lists the commands, 'quit' leaves", style="dim")

    def on_sigint(_sig, _frame) -> None:
        session.interrupted = True

    while True:
        try:
            line = prompt.prompt(PROMPT)
        except KeyboardInterrupt:
            continue
        except EOFError:
            return 0
        old = signal.signal(signal.SIGINT, on_sigint)
        try:
            execute(session, line)
        except Quit:
            return 0
        finally:
            signal.signal(signal.SIGINT, old)
            session.interrupted = False


def repl_command(args: argparse.Namespace, stdin: TextIO | None = None,
                 stdout: TextIO | None = None, stderr: TextIO | None = None,
                 echo: bool = False) -> int:
    for flag, default in (("out", None), ("count", 1), ("jobs", 1)):
        if getattr(args, flag) != default:
            raise error(f"--{flag} has no meaning with --repl", None,
                        "in the REPL, 'save FILE.json' and 'render FILE.svg' write drawings")
    stdin, stdout, stderr = stdin or sys.stdin, stdout or sys.stdout, stderr or sys.stderr
    interactive = stdin.isatty() and stdout.isatty()
    session = Session(Output(stdout, stderr, colour=interactive), Options.from_args(args),
                      compile_example=getattr(args, "compile_example", None))
    if args.file is not None:
        session.load(args.file)
        session.out.line(f"loaded {session.name}: {len(session.grammar.rules)} rules")
    if interactive:
        return run_terminal(session)
    return run_script(session, stdin, echo)
