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
_tuple_new = tuple.__new__  # Pos and Span built without their (Python-level) NamedTuple constructors


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
        starts = self.starts
        line = bisect_right(starts, offset) - 1
        return _tuple_new(Pos, (offset, line, offset - starts[line]))

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


class ShiftedLines:
    """The line table of a chunk parsed alone, seen at another place of a bigger text (incremental
    parsing moves chunks): positions are the chunk's, shifted by an offset and a line delta."""

    __slots__ = ("inner", "d_off", "d_line")

    def __init__(self, inner, d_off: int, d_line: int):
        if type(inner) is ShiftedLines:  # a moved copy moved again: one shift over the chunk's own table
            inner, d_off, d_line = inner.inner, inner.d_off + d_off, inner.d_line + d_line
        self.inner, self.d_off, self.d_line = inner, d_off, d_line

    def pos(self, offset: int) -> Pos:
        p = self.inner.pos(offset - self.d_off)
        return _tuple_new(Pos, (offset, p[1] + self.d_line, p[2]))


class TextSpan:
    """A node's span: two offsets and its file's line table. Lines and columns are computed when
    asked (`start`, `end`), so a tree keeps two ints per node, not two position tuples of three:
    it reads, compares, hashes and pickles as the `Span` of the same positions.

    Spans are immutable; nodes with one child share their child's span."""

    __slots__ = ("s", "e", "lines")

    def __init__(self, s: int, e: int, lines):
        self.s, self.e, self.lines = s, e, lines

    @property
    def start(self) -> Pos:
        return self.lines.pos(self.s)

    @property
    def end(self) -> Pos:
        return self.lines.pos(self.e)

    def contains(self, offset: int) -> bool:
        return self.s <= offset <= self.e

    def cover(self, other) -> "TextSpan | Span":
        if type(other) is TextSpan and other.lines is self.lines:
            return TextSpan(min(self.s, other.s), max(self.e, other.e), self.lines)
        return Span(*self).cover(other)

    def concrete(self) -> Span:
        """The same span as a `Span` of positions (what is pickled)."""
        return _tuple_new(Span, (self.lines.pos(self.s), self.lines.pos(self.e)))

    def __iter__(self):
        return iter(self.concrete())

    def __len__(self) -> int:
        return 2

    def __getitem__(self, i):
        return self.concrete()[i]

    def __eq__(self, other):
        if type(other) is TextSpan:
            if other.lines is self.lines:
                return self.s == other.s and self.e == other.e
            return self.concrete() == other.concrete()
        if isinstance(other, tuple):
            return self.concrete() == other
        return NotImplemented

    def __ne__(self, other):
        eq = self.__eq__(other)
        return eq if eq is NotImplemented else not eq

    def __lt__(self, other):
        return self.concrete() < tuple(other)

    def __le__(self, other):
        return self.concrete() <= tuple(other)

    def __gt__(self, other):
        return self.concrete() > tuple(other)

    def __ge__(self, other):
        return self.concrete() >= tuple(other)

    def __hash__(self) -> int:
        return hash(self.concrete())

    def __repr__(self) -> str:
        return repr(self.concrete())

    def __reduce__(self):
        # pickled (and copied) as the Span it reads as: a cached tree or a diagnostic sent from a
        # worker must not carry the file's whole line table with it
        return (_tuple_new, (Span, tuple(self.concrete())))


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
