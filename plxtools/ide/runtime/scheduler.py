"""When the language server checks documents: no fixed delay, one document per turn of the event
loop, and waiting messages first.

A document is queued (`add`) on every edit; the check runs as soon as no message is waiting to be
handled, so a burst of edits is checked once, at its last version (older versions are superseded
before they start), and requests are answered first. A check runs in two halves, parse then
analysis, with waiting messages handled in between: a completion typed right after an edit waits
for one half, not for the whole check. Without an event loop (tests that drive the server
directly) the queue is drained at once.
"""

from __future__ import annotations

from typing import Callable


class CheckQueue:
    """Documents waiting for a check (uri -> whether dependents are checked after it), oldest first.

    `check(uri, cascade)` checks one document; `parse_ahead(uri)` parses it and says whether it did
    (the analysis then waits one turn); `busy()` is true while messages wait to be handled;
    `blocked()` while the bundles load (their loader calls `wake` when done); `loop()` is the
    server's event loop (None before it runs)."""

    def __init__(self, check: Callable[[str, bool], None], parse_ahead: Callable[[str], bool],
                 busy: Callable[[], bool], blocked: Callable[[], bool], loop: Callable) -> None:
        self.dirty: dict[str, bool] = {}
        self._pending = False
        self._check, self._parse_ahead, self._busy, self._blocked, self._loop = check, parse_ahead, busy, blocked, loop

    def __contains__(self, uri: str) -> bool:
        return uri in self.dirty

    def add(self, uri: str, cascade: bool) -> None:
        self.dirty[uri] = self.dirty.pop(uri, False) or cascade
        self.wake()

    def discard(self, uri: str) -> None:
        self.dirty.pop(uri, None)

    def wake(self) -> None:
        loop = self._loop()
        if self._pending or loop is None:
            if loop is None:
                self._drain_now()
            return
        self._pending = True
        loop.call_soon(self._run)

    def _drain_now(self) -> None:
        while self.dirty:
            uri, cascade = next(iter(self.dirty.items()))
            del self.dirty[uri]
            self._check(uri, cascade)

    def _run(self) -> None:
        """One document per turn of the event loop; messages that arrived meanwhile go first."""
        self._pending = False
        if not self.dirty or self._blocked():
            return  # (the bundles' loader wakes the checks when it is done)
        if self._busy():
            # edits and requests are waiting: handle them first (a newer version supersedes this)
            self._pending = True
            self._loop().call_soon(self._run)
            return
        uri, cascade = next(iter(self.dirty.items()))
        if self._parse_ahead(uri):
            self.wake()  # the analysis next turn, after the messages that arrived while parsing
            return
        del self.dirty[uri]
        self._check(uri, cascade)
        if self.dirty:
            self.wake()
