"""The one place where positions change shape: LSP (line, character in the negotiated encoding)
<-> plxtools (offsets in code points), and the one place where an LSP edit is applied to a text.

LSP lines end at `\\n`, `\\r\\n` or `\\r` and nowhere else (not at U+2028/2029, form feed, VT, NEL,
FS, GS or RS, which Python's `str.splitlines` would split on). A character past a line's end means
the end of that line; a line past the last means the end of the text. Everything going out is
converted from offsets, so the syntax layer's own line numbering never reaches the client.

UTF-16 is LSP's default; UTF-8 and UTF-32 are used when the client offers them (negotiated in
`initialize` by pygls). ASCII lines, nearly all of OpenPLX, take a fast path.
"""

from __future__ import annotations

import re
from bisect import bisect_right

UTF8 = "utf-8"
UTF16 = "utf-16"
UTF32 = "utf-32"

_BREAK = re.compile(r"\r\n|\r|\n")


def _enc(encoding) -> str:
    value = getattr(encoding, "value", encoding)
    return value if value in (UTF8, UTF32) else UTF16


def _units(s: str, encoding: str) -> int:
    if encoding == UTF32 or s.isascii():
        return len(s)
    if encoding == UTF8:
        return len(s.encode("utf-8"))
    return len(s.encode("utf-16-le")) // 2


def _unit_of(ch: str, encoding: str) -> int:
    if encoding == UTF32:
        return 1
    if encoding == UTF8:
        return len(ch.encode("utf-8"))
    return 2 if ord(ch) > 0xFFFF else 1


def line_starts(text: str) -> list[int]:
    """Offsets where LSP lines start (after `\\n`, `\\r\\n` or a lone `\\r`)."""
    if "\r" not in text:
        starts = [0]
        i = text.find("\n")
        while i != -1:
            starts.append(i + 1)
            i = text.find("\n", i + 1)
        return starts
    return [0] + [m.end() for m in _BREAK.finditer(text)]


class Positions:
    """Conversions for one text (a buffer or a file) in one encoding."""

    __slots__ = ("text", "starts", "encoding", "index")

    def __init__(self, text: str, encoding=UTF16, index=None):
        self.text = text
        self.starts = line_starts(text)
        self.encoding = _enc(encoding)
        self.index = index  # the syntax layer's LineIndex of the same text, for (line, column) input

    @property
    def line_count(self) -> int:
        return len(self.starts)

    def line_end(self, line: int) -> int:
        """Offset of the end of a line's content (before its line break)."""
        if line + 1 < len(self.starts):
            end = self.starts[line + 1] - 1
            if self.text[end] == "\n" and end > self.starts[line] and self.text[end - 1] == "\r":
                end -= 1
            return end
        return len(self.text)

    def line_text(self, line: int) -> str:
        return self.text[self.starts[line]:self.line_end(line)]

    # plxtools -> LSP
    def line_character(self, offset: int) -> tuple[int, int]:
        """An offset as LSP's (line, character), without lsprotocol (quickstart answers before it loads)."""
        offset = max(0, min(offset, len(self.text)))
        line = bisect_right(self.starts, offset) - 1
        start = self.starts[line]
        offset = min(offset, self.line_end(line))  # never inside a \r\n pair
        piece = self.text[start:offset]
        ch = len(piece) if self.encoding == UTF32 or piece.isascii() else _units(piece, self.encoding)
        return line, ch

    def offset_position(self, offset: int):
        from lsprotocol import types

        line, ch = self.line_character(offset)
        return types.Position(line=line, character=ch)

    def offsets_range(self, start: int, end: int):
        from lsprotocol import types

        return types.Range(start=self.offset_position(start), end=self.offset_position(end))

    def range(self, span):
        return self.offsets_range(span.start.offset, span.end.offset)

    def position(self, line: int, col: int):
        """An LSP position from the syntax layer's (line, column)."""
        return self.offset_position(self._index().offset(line, col))

    def length(self, line: int, col: int, length: int) -> tuple[int, int]:
        """A token's column and length in client units (the syntax layer's line numbering)."""
        text = self._index().line_text(line)
        if self.encoding == UTF32 or text.isascii():
            return col, length
        return _units(text[:col], self.encoding), _units(text[col:col + length], self.encoding)

    def _index(self):
        if self.index is None:
            from plxtools.syntax.source import LineIndex

            self.index = LineIndex(self.text)
        return self.index

    # LSP -> plxtools
    def offset(self, pos) -> int:
        """Offset of an LSP position; characters past the end of a line clamp to its end, lines past
        the last to the end of the text."""
        return self.offset_at(pos.line, pos.character)

    def offset_at(self, line: int, character: int) -> int:
        if line >= len(self.starts):
            return len(self.text)
        if line < 0:
            return 0
        start = self.starts[line]
        end = self.line_end(line)
        ch = max(character, 0)
        if self.encoding == UTF32 or self.text[start:end].isascii():
            return min(start + ch, end)
        used = 0
        i = start
        while i < end and used < ch:
            used += _unit_of(self.text[i], self.encoding)
            i += 1
        return i


def apply_change(text: str, change, encoding=UTF16) -> str:
    """One `contentChanges` entry applied to a text (a range edit, or the whole text)."""
    rng = getattr(change, "range", None)
    if rng is None:
        return change.text
    pos = Positions(text, encoding)
    a = pos.offset(rng.start)
    b = pos.offset(rng.end)
    if b < a:
        a, b = b, a
    return text[:a] + change.text + text[b:]
