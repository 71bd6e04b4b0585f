"""Diagnostics shared by every layer: one shape for syntax, lint, check and the language server.

Positions inside the tool are 0-based (line, column in code points, offset in code points); the CLI
adds one when printing and the LSP layer converts columns to the client's encoding.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from enum import Enum
from typing import NamedTuple


class Severity(str, Enum):
    ERROR = "error"
    WARNING = "warning"
    INFO = "info"

    @property
    def rank(self) -> int:
        return {"error": 2, "warning": 1, "info": 0}[self.value]


class Pos(NamedTuple):
    """A position; a tuple so that trees of them are cheap to build and to (un)pickle."""

    offset: int
    line: int
    column: int


class Span(NamedTuple):
    start: Pos
    end: Pos

    def contains(self, offset: int) -> bool:
        return self.start.offset <= offset <= self.end.offset

    def cover(self, other: "Span") -> "Span":
        start = self.start if self.start.offset <= other.start.offset else other.start
        end = self.end if self.end.offset >= other.end.offset else other.end
        return Span(start, end)


ZERO = Pos(0, 0, 0)
EMPTY_SPAN = Span(ZERO, ZERO)


@dataclass(frozen=True, slots=True)
class Edit:
    """Replace the text between two offsets of the file."""

    start: int
    end: int
    text: str


@dataclass(frozen=True, slots=True)
class Fix:
    message: str
    edits: tuple[Edit, ...]
    safe: bool = True


@dataclass(slots=True)
class Diagnostic:
    code: str
    message: str
    span: Span
    severity: Severity = Severity.ERROR
    file: str = ""
    help: str | None = None
    fix: Fix | None = None
    related: list[tuple[str, Span, str]] = field(default_factory=list)
    # U001/U002: the newest official version the written name belongs to (what a migration starts from)
    older_version: str | None = None

    def sort_key(self) -> tuple:
        return (self.file, self.span.start.offset, self.code)

    def to_json(self) -> dict:
        """The JSON shape of design.md: 1-based lines and columns."""
        out = {
            "file": self.file,
            "code": self.code,
            "severity": self.severity.value,
            "message": self.message,
            "range": {
                "start": {"line": self.span.start.line + 1, "column": self.span.start.column + 1},
                "end": {"line": self.span.end.line + 1, "column": self.span.end.column + 1},
            },
        }
        out["help"] = self.help or None
        out["fix"] = None
        if self.fix is not None:
            out["fix"] = {
                "message": self.fix.message,
                "applicability": "safe" if self.fix.safe else "unsafe",
                "edits": [{"start": e.start, "end": e.end, "content": e.text} for e in self.fix.edits],
            }
        return out


def apply_edits(text: str, edits: list[Edit]) -> str:
    """Apply non-overlapping edits (later ones first); overlapping edits are skipped."""
    out = text
    last_start = len(text) + 1
    for e in sorted(edits, key=lambda e: (e.start, e.end), reverse=True):
        if e.end > last_start:
            continue
        out = out[: e.start] + e.text + out[e.end :]
        last_start = e.start
    return out


# C0 controls (tab and line feed aside: messages may hold several lines), DEL, C1 controls, and the bidirectional overrides that reorder a line
# as it is shown (Trojan Source): what a file name or an `@"..."` path can carry to a terminal
_UNPRINTABLE = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u200e\u200f\u202a-\u202e\u2066-\u2069]")


def _escape(m: re.Match) -> str:
    c = ord(m.group())
    return f"\\x{c:02x}" if c < 0x100 else f"\\u{c:04x}"


def printable(text: str) -> str:
    """`text` with every character a terminal or a CI log would act on (escape sequences, line
    returns, bidirectional overrides) written as a Python-style escape: what text and GitHub output
    print, so a message can never move the cursor, erase lines above it or start a new annotation."""
    return _UNPRINTABLE.sub(_escape, text) if _UNPRINTABLE.search(text) else text
