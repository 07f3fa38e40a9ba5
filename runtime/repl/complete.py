"""Tab completion for the REPL on a terminal: commands, rule names, flags and file names."""

from __future__ import annotations

from .session import Session
from .commands import ALIASES, COMMANDS


def completions(session: Session, text: str) -> list[str]:
    """Candidates for the word being typed at the end of `text` (not files)."""
    words = text.split()
    current = "" if not words or text[-1:].isspace() else words[-1]
    if len(words) == 0 or (len(words) == 1 and current):
        pool = list(COMMANDS)
    else:
        cmd = COMMANDS.get(ALIASES.get(words[0], words[0]))
        kind = cmd.complete if cmd else ""
        if kind == "rule":
            pool = ["--backward"]
            if session.grammar is not None and len(words) - bool(current) == 1:
                pool = [r.name for r in session.grammar.rules] + pool
        elif kind == "command":
            pool = list(COMMANDS)
        elif kind == "watch":
            pool = ["off"]
        else:
            pool = []
    return [p for p in pool if p.startswith(current)]


def completer(session: Session):
    """A prompt_toolkit completer (imported only when a terminal session needs one)."""
    from prompt_toolkit.completion import Completer as Base, Completion, PathCompleter
    from prompt_toolkit.document import Document

    class Completer(Base):
        def __init__(self, session: Session):
            self.session = session
            self.paths = PathCompleter(expanduser=True)

        def get_completions(self, document, complete_event):
            text = document.text_before_cursor
            words = text.split()
            current = "" if not words or text[-1:].isspace() else words[-1]
            for c in completions(self.session, text):
                yield Completion(c, start_position=-len(current))
            cmd = COMMANDS.get(ALIASES.get(words[0], words[0])) if words else None
            if cmd is not None and cmd.complete in ("file", "watch") and \
                    (len(words) > 1 or not current):
                yield from self.paths.get_completions(Document(current), complete_event)

    return Completer(session)


