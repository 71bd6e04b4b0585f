"""The one place where positions change shape: LSP (line, character in the negotiated encoding)
<-> plxtools (offset, line, column in code points).

UTF-16 is LSP's default; UTF-8 and UTF-32 are used when the client offers them (negotiated in
`initialize` by pygls). ASCII lines, nearly all of OpenPLX, take a fast path.
"""

from __future__ import annotations

from lsprotocol import types

from plxtools.diagnostics import Span
from plxtools.syntax.source import LineIndex

UTF8 = types.PositionEncodingKind.Utf8
UTF16 = types.PositionEncodingKind.Utf16
UTF32 = types.PositionEncodingKind.Utf32


def _units(s: str, encoding) -> int:
    if s.isascii() or encoding == UTF32:
        return len(s)
    if encoding == UTF8:
        return len(s.encode("utf-8"))
    return len(s.encode("utf-16-le")) // 2


def _unit_of(ch: str, encoding) -> int:
    if encoding == UTF32:
        return 1
    if encoding == UTF8:
        return len(ch.encode("utf-8"))
    return 2 if ord(ch) > 0xFFFF else 1


class Positions:
    """Conversions for one text (a buffer or a file) in one encoding."""

    __slots__ = ("index", "encoding")

    def __init__(self, index: LineIndex, encoding=UTF16):
        self.index = index
        self.encoding = encoding or UTF16

    # plxtools -> LSP
    def column(self, line: int, col: int) -> int:
        text = self.index.line_text(line)
        if text.isascii() or self.encoding == UTF32:
            return col
        return _units(text[:col], self.encoding)

    def position(self, line: int, col: int) -> types.Position:
        return types.Position(line=line, character=self.column(line, col))

    def offset_position(self, offset: int) -> types.Position:
        p = self.index.pos(offset)
        return self.position(p.line, p.column)

    def range(self, span: Span) -> types.Range:
        return types.Range(start=self.position(span.start.line, span.start.column),
                           end=self.position(span.end.line, span.end.column))

    def offsets_range(self, start: int, end: int) -> types.Range:
        return types.Range(start=self.offset_position(start), end=self.offset_position(end))

    def length(self, line: int, col: int, length: int) -> tuple[int, int]:
        """A token's column and length in client units."""
        text = self.index.line_text(line)
        if text.isascii() or self.encoding == UTF32:
            return col, length
        return _units(text[:col], self.encoding), _units(text[col:col + length], self.encoding)

    # LSP -> plxtools
    def offset(self, pos: types.Position) -> int:
        """Offset of an LSP position; characters past the end of a line clamp to its end."""
        line = pos.line
        if line >= self.index.line_count:
            return len(self.index.text)
        if line < 0:
            return 0
        text = self.index.line_text(line)
        ch = max(pos.character, 0)
        if text.isascii() or self.encoding == UTF32:
            col = min(ch, len(text))
        else:
            col = 0
            used = 0
            for c in text:
                if used >= ch:
                    break
                used += _unit_of(c, self.encoding)
                col += 1
        return self.index.offset(line, col)
