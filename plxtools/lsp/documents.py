"""The editor's buffers as the server sees them, kept right when edits arrive out of order.

LSP says a client sends `didChange` in order, but Helix 25.01 and 25.07 write the notifications of a
fast burst of keystrokes to the pipe in a shuffled order (seen in a real Helix: versions 7, 8, 6).
Applied as they come, range edits land in the wrong places and the server checks a text the user
never wrote. Each document therefore keeps its recent edits sorted by version on top of a base text:
an edit that arrives late is put in its place and the text is rebuilt from the base. Clients whose
versions skip numbers (Neovim's `changedtick`) are fine: only the order matters, not the gaps.
"""

from __future__ import annotations

import bisect
import logging
from urllib.parse import unquote

from plxtools.lsp.convert import apply_change

log = logging.getLogger("plxtools.lsp")

# how many of the latest edits can still be re-ordered; older ones are folded into the base text
WINDOW = 32


class OpenDocument:
    __slots__ = ("uri", "text", "version", "base", "base_version", "recent", "arrivals", "reordered")

    def __init__(self, uri: str, text: str, version):
        self.uri = uri
        self.text = text
        self.version = version
        self.base, self.base_version = text, version  # the text before the edits in `recent`
        self.recent: list[tuple[int, int, list]] = []  # (version, arrival, changes), sorted
        self.arrivals = 0
        self.reordered = False

    def edit(self, version, changes, encoding) -> None:
        if not isinstance(version, int) or not isinstance(self.version, int):
            self._apply_plain(version, changes, encoding)
            return
        if any(getattr(c, "range", None) is None for c in changes) and version > self.version:
            # the whole text from here on: nothing before it matters any more
            for change in changes:
                self.text = apply_change(self.text, change, encoding)
            self.base, self.base_version, self.recent, self.version = self.text, version, [], version
            return
        self.arrivals += 1
        entry = (version, self.arrivals, list(changes))
        if version > self.version:
            self.recent.append(entry)
            for change in changes:
                self.text = apply_change(self.text, change, encoding)
            self.version = version
        elif version > self.base_version:
            # arrived late: put it in its place and rebuild the text from the base
            # the first time per document at WARNING (the client breaks LSP's ordering), then INFO
            log.log(logging.INFO if self.reordered else logging.WARNING,
                    "document version of %s went from %s to %s: edits out of order, re-applied in version order",
                    self.uri, self.version, version)
            self.reordered = True
            bisect.insort(self.recent, entry, key=lambda e: (e[0], e[1]))
            text = self.base
            for _, _, earlier in self.recent:
                for change in earlier:
                    text = apply_change(text, change, encoding)
            self.text = text
        else:
            log.warning("document version of %s went from %s to %s, older than every edit still held: "
                        "applied as it comes", self.uri, self.version, version)
            self._apply_plain(self.version, changes, encoding)
            return
        while len(self.recent) > WINDOW:
            self.base_version, _, folded = self.recent.pop(0)
            for change in folded:
                self.base = apply_change(self.base, change, encoding)

    def _apply_plain(self, version, changes, encoding) -> None:
        for change in changes:
            self.text = apply_change(self.text, change, encoding)
        self.base, self.base_version, self.recent, self.version = self.text, version, [], version


class Documents:
    """The open documents, keyed by the unquoted URI."""

    def __init__(self) -> None:
        self.by_key: dict[str, OpenDocument] = {}

    def get(self, uri: str) -> OpenDocument | None:
        return self.by_key.get(unquote(uri))

    def __iter__(self):
        return iter([d.uri for d in self.by_key.values()])

    def open(self, uri: str, text: str, version) -> None:
        self.by_key[unquote(uri)] = OpenDocument(uri, text, version)

    def change(self, uri: str, version, changes, encoding) -> bool:
        doc = self.get(uri)
        if doc is None:
            whole = [c for c in changes if getattr(c, "range", None) is None]
            if not whole:
                log.warning("didChange for %s, which is not open: ignored", uri)
                return False
            self.open(uri, whole[-1].text, version)
            return True
        doc.edit(version, changes, encoding)
        return True

    def close(self, uri: str) -> None:
        self.by_key.pop(unquote(uri), None)
