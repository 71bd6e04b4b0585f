"""A progress bar on stderr for long runs, drawn only where a person watches.

Shown when stderr is a terminal, the output format is text and the run lasts longer than
PLX_PROGRESS_DELAY seconds (default 1.5; a run that ends sooner draws nothing). NO_COLOR does not
turn it off; PLX_NO_PROGRESS=1 or TERM=dumb does. rich is imported only once a bar is drawn, so a
run that never shows one (lint, fmt, anything piped) pays nothing.

While a bar is up, what the command writes to stderr (and to stdout when stdout is the same
terminal) goes above it, so each file's report is printed as soon as it is done.
"""

from __future__ import annotations

import os
import sys
import threading
import time


def enabled(output_format: str = "text") -> bool:
    """True when a bar would be drawn for a run with this output format."""
    if output_format != "text" or os.environ.get("PLX_NO_PROGRESS") or os.environ.get("TERM") == "dumb":
        return False
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


def _delay() -> float:
    try:
        return max(0.0, float(os.environ.get("PLX_PROGRESS_DELAY", "1.5")))
    except ValueError:
        return 1.5


class Bar:
    """`with Bar(total, "checking") as bar: ... bar.advance(label)`: a no-op unless `enabled()`.

    The bar appears after the delay, from a timer thread, so a single long item (one slow
    simulation) still shows it; `total=None` draws a pulsing bar (bytes of unknown size)."""

    def __init__(self, total: int | None, description: str, *, output_format: str = "text", unit: str = "files"):
        self.total = total
        self.description = description
        self.unit = unit
        self.done = 0
        self.current = ""
        self.on = enabled(output_format)
        self._lock = threading.Lock()
        self._progress = None
        self._task = None
        self._timer: threading.Timer | None = None
        self._closed = False

    def __enter__(self) -> "Bar":
        if self.on:
            self._started = time.monotonic()
            self._timer = threading.Timer(_delay(), self._show)
            self._timer.daemon = True
            self._timer.start()
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _show(self) -> None:
        with self._lock:
            if self._closed or self._progress is not None:
                return
            from rich.console import Console
            from rich.progress import (BarColumn, MofNCompleteColumn, Progress, SpinnerColumn, TextColumn,
                                       TimeElapsedColumn)

            columns = [SpinnerColumn(), TextColumn("[progress.description]{task.description}"), BarColumn()]
            if self.unit == "files" and self.total is not None:
                columns.append(MofNCompleteColumn())
            columns += [TimeElapsedColumn(), TextColumn("{task.fields[current]}", style="dim")]
            stdout_shared = _same_terminal()
            self._progress = Progress(*columns, console=Console(stderr=True), transient=True,
                                      redirect_stdout=stdout_shared, redirect_stderr=True)
            self._task = self._progress.add_task(self.description, total=self.total, completed=self.done,
                                                 current=self.current)
            self._progress.start()

    def advance(self, current: str = "", by: int = 1) -> None:
        """One more item done; `current` names what comes next (shown dim after the bar)."""
        with self._lock:
            self.done += by
            self.current = current
            if self._progress is not None:
                self._progress.update(self._task, completed=self.done, current=current)

    def update(self, done: int, total: int | None = None, current: str = "") -> None:
        with self._lock:
            self.done, self.current = done, current
            if total is not None:
                self.total = total
            if self._progress is not None:
                self._progress.update(self._task, completed=done, total=self.total, current=current)

    def close(self) -> None:
        with self._lock:
            self._closed = True
            if self._timer is not None:
                self._timer.cancel()
            if self._progress is not None:
                self._progress.stop()
                self._progress = None

    @property
    def drawn(self) -> bool:
        """True once the bar is on screen (reports are then printed as each item is done)."""
        return self._progress is not None


def _same_terminal() -> bool:
    try:
        if not sys.stdout.isatty():
            return False
        a, b = os.fstat(sys.stdout.fileno()), os.fstat(sys.stderr.fileno())
        return (a.st_dev, a.st_ino) == (b.st_dev, b.st_ino)
    except (AttributeError, ValueError, OSError):
        return False


def bytes_callback(label: str):
    """A `progress(done, total)` callback drawing a download bar, or None off a terminal. The bar
    closes itself when the download is complete."""
    if not enabled():
        return None
    state: dict = {}

    def report(done: int, total: int | None) -> None:
        bar = state.get("bar")
        if bar is None:
            bar = state["bar"] = Bar(total, f"downloading {label}", unit="bytes").__enter__()
        bar.update(done, total, f"{done / 1e6:.1f} MB")
        if total is not None and done >= total:
            bar.close()

    return report
