"""Turning bytes into text without ever raising, and mapping offsets to lines and columns."""

from __future__ import annotations

import codecs
import re
from bisect import bisect_right
from dataclasses import dataclass, field

from plxtools.diagnostics import EMPTY_SPAN, Diagnostic, Pos, Severity, Span

BINARY_FILE = "S001"  # the bytes are not text: nothing else is checked
UNREADABLE_FILE = "E001"

BOM = "\ufeff"


@dataclass(slots=True)
class DecodedSource:
    text: str
    had_bom: bool = False
    newline: str = "\n"
    diagnostics: list[Diagnostic] = field(default_factory=list)
    is_binary: bool = False


class LineIndex:
    """Offsets <-> (line, column), both 0-based, over the exact text the parser saw."""

    __slots__ = ("text", "starts")

    def __init__(self, text: str):
        self.text = text
        starts = [0]
        if "\r" in text:  # \r\n, a lone \r and \n each end a line, as in the lexer and LSP
            starts.extend(m.end() for m in _BREAK_RE.finditer(text))
        else:
            i = text.find("\n")
            while i != -1:
                starts.append(i + 1)
                i = text.find("\n", i + 1)
        self.starts = starts

    @property
    def line_count(self) -> int:
        return len(self.starts)

    def pos(self, offset: int) -> Pos:
        offset = max(0, min(offset, len(self.text)))
        line = bisect_right(self.starts, offset) - 1
        return Pos(offset, line, offset - self.starts[line])

    def offset(self, line: int, column: int) -> int:
        if line >= len(self.starts):
            return len(self.text)
        if line < 0:
            return 0
        end = self.line_end(line)
        return min(self.starts[line] + max(column, 0), end)

    def line_end(self, line: int) -> int:
        """Offset of the end of a line's content (before its \\r\\n, \\r or \\n)."""
        if line + 1 < len(self.starts):
            end = self.starts[line + 1] - 1
            if self.text[end] == "\n" and end > self.starts[line] and self.text[end - 1] == "\r":
                end -= 1
            return end
        return len(self.text)

    def line_text(self, line: int) -> str:
        if line < 0 or line >= len(self.starts):
            return ""
        return self.text[self.starts[line] : self.line_end(line)]

    def span(self, start: int, end: int) -> Span:
        return Span(self.pos(start), self.pos(end))


_BREAK_RE = re.compile(r"\r\n?|\n")


def detect_newline(text: str) -> str:
    """The file's line break: its first one (\\n when it has none)."""
    m = _BREAK_RE.search(text)
    return m.group() if m else "\n"


def line_start(text: str, offset: int) -> int:
    """Offset of the start of the line holding `offset`."""
    return max(text.rfind("\n", 0, offset), text.rfind("\r", 0, offset)) + 1


def unreadable(path: str, exc: OSError) -> Diagnostic:
    """E001 for a file that cannot be read: the one message lint and check both give."""
    return Diagnostic(UNREADABLE_FILE, f"cannot read file: {exc.strerror}", EMPTY_SPAN, Severity.ERROR, file=path)


def decode(data: bytes) -> DecodedSource:
    """Decode file bytes as UTF-8; binary files and invalid bytes become located diagnostics."""
    if b"\x00" in data[:8192]:
        d = Diagnostic(
            BINARY_FILE,
            "this looks like a binary file (it contains NUL bytes), not OpenPLX source",
            Span(Pos(0, 0, 0), Pos(0, 0, 0)),
            Severity.ERROR,
        )
        return DecodedSource("", diagnostics=[d], is_binary=True)
    had_bom = data.startswith(codecs.BOM_UTF8)
    if had_bom:
        data = data[len(codecs.BOM_UTF8) :]
    diagnostics: list[Diagnostic] = []
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        good = data[: exc.start].decode("utf-8", errors="replace")
        text = data.decode("utf-8", errors="replace")
        index = LineIndex(good)
        at = index.pos(len(good))
        d = Diagnostic(
            "S002",
            f"invalid UTF-8: byte 0x{data[exc.start]:02x} cannot be decoded "
            "(OpenPLX files must be UTF-8)",
            Span(at, Pos(at.offset + 1, at.line, at.column + 1)),
            Severity.ERROR,
            help="re-save the file as UTF-8",
        )
        diagnostics.append(d)
    return DecodedSource(text, had_bom=had_bom, newline=detect_newline(text), diagnostics=diagnostics)


def decode_text(text: str) -> DecodedSource:
    """Text from an editor buffer or stdin: only a leading BOM needs handling."""
    had_bom = text.startswith(BOM)
    if had_bom:
        text = text[1:]
    return DecodedSource(text, had_bom=had_bom, newline=detect_newline(text))
