"""Ctrl-C while drawings grow: finish the step, write the last valid drawing, exit 130.

The first Ctrl-C only sets a stop event; `Engine.run` looks at it before each step, so the
drawing it has is whole and gets written as usual (atomically). Worker processes of `--jobs`
share the event and ignore SIGINT themselves, so they too stop within one step, whether the
terminal signalled the whole process group or only the main process. A second Ctrl-C
interrupts at once.
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager

_stop = None        # the stop event of this process (a threading or multiprocessing Event)


def requested() -> bool:
    return _stop is not None and _stop.is_set()


@contextmanager
def catching(event):
    """While inside, the first SIGINT sets `event`; the second raises KeyboardInterrupt."""
    global _stop
    if threading.current_thread() is not threading.main_thread():
        yield      # signal handlers belong to the main thread; Ctrl-C stays a plain interrupt
        return

    def handler(signum, frame):
        if event.is_set():
            raise KeyboardInterrupt
        event.set()

    _stop = event
    old = signal.signal(signal.SIGINT, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)
        _stop = None


def worker_init(event) -> None:
    """Pool initializer: stop on the shared event, leave SIGINT to the main process."""
    global _stop
    _stop = event
    signal.signal(signal.SIGINT, signal.SIG_IGN)
