"""Feedback during long work, the same for every verb of every system.

On a terminal (stderr is a TTY) a live status line with the stage and, for counted work, a
bar; when stderr is piped (a CI log), one line per stage (``lgw: <stage>``) and nothing for
the counts, so logs stay short.  A stage is shown only once it has lasted ``QUIET_S``: quick
commands print nothing but their results.  ``LGW_PROGRESS`` = ``auto`` (default) | ``never`` |
``always`` (one line per stage even on a terminal).  Progress never goes to stdout, where the
JSON and the tables are.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from typing import Any, TextIO

QUIET_S = 1.0  # s: a stage shorter than this is never shown


class Progress:
    """``stage(text)`` starts a named stage; ``advance(done, total)`` reports counted work in
    it; ``close()`` ends the display.  ``stages`` keeps (text, seconds) of every stage."""

    def __init__(self, stream: TextIO | None = None, mode: str | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        mode = mode or os.environ.get("LGW_PROGRESS", "auto")
        tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.live = mode == "auto" and tty
        self.lines = mode == "always" or (mode == "auto" and not tty)
        self.stages: list[tuple[str, float]] = []
        self._t0 = time.perf_counter()
        self._status: Any = None
        self._current = ""
        self._timer: threading.Timer | None = None
        self._lock = threading.Lock()

    def stage(self, text: str) -> None:
        now = time.perf_counter()
        if self.stages:
            self.stages[-1] = (self.stages[-1][0], now - self._t0)
        self._t0 = now
        self.stages.append((text, 0.0))
        self._current = text
        if self.lines or self.live:
            self._cancel()
            self._timer = threading.Timer(QUIET_S, self._show_stage, (text,))
            self._timer.daemon = True
            self._timer.start()

    def _show_stage(self, text: str) -> None:
        with self._lock:
            if text != self._current:
                return
            if self.lines:
                print(f"lgw: {text}", file=self.stream, flush=True)
            else:
                self._show(text)

    def _cancel(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None

    def advance(self, done: int, total: int) -> None:
        if self.live and total > 0 and self._status is not None:
            with self._lock:
                self._show(f"{self._current} ({done}/{total}, {100 * done / total:.0f} %)")

    def __call__(self, text: str) -> None:  # a Progress is also a plain callback(str)
        self.stage(text)

    def _show(self, text: str) -> None:
        if self._status is None:
            from rich.console import Console

            self._status = Console(file=self.stream).status(text)
            self._status.start()
        else:
            self._status.update(text)

    def close(self) -> None:
        self._cancel()
        self._current = ""
        if self.stages:
            self.stages[-1] = (self.stages[-1][0], time.perf_counter() - self._t0)
        with self._lock:
            if self._status is not None:
                self._status.stop()
                self._status = None


class Silent(Progress):
    """No output at all (library callers, tests)."""

    def __init__(self) -> None:
        super().__init__(mode="never")
