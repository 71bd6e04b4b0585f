"""Formatting through `plx fmt`'s functions, as small edits (so cursors and marks survive)."""

from __future__ import annotations

import difflib

from plxtools.ide.types import TextEdit
from plxtools.fmt import format_range, format_text


class FormattingRefused(Exception):
    """The formatter will not touch this text (syntax errors, or it could not verify its output).

    `syntax` says which: a file with syntax errors is a normal state while typing, not a failure."""

    def __init__(self, message: str, syntax: bool = False):
        super().__init__(message)
        self.syntax = syntax


def _formatter():
    return format_text, format_range


def format_document(text: str, path: str = "") -> list[TextEdit]:
    format_text, _ = _formatter()
    result = format_text(text, path)
    if result.text is None:
        if result.diagnostics:
            d = result.diagnostics[0]
            raise FormattingRefused(f"not formatted: the file has syntax errors (line {d.span.start.line + 1}: "
                                    f"{d.message})", syntax=True)
        raise FormattingRefused(f"not formatted: {result.internal_error or 'the formatter refused the file'}")
    new = result.text
    if new.startswith("\ufeff") and not text.startswith("\ufeff"):
        new = new[1:]
    if new == text:
        return []
    return diff_edits(text, new)


def format_lines(text: str, start_line: int, end_line: int) -> list[TextEdit]:
    _, format_range = _formatter()
    return [TextEdit(e.start, e.end, e.text) for e in format_range(text, start_line, end_line)]


def diff_edits(old: str, new: str) -> list[TextEdit]:
    """Line-based edits turning `old` into `new`."""
    a = old.splitlines(keepends=True)
    b = new.splitlines(keepends=True)
    starts = [0]
    for line in a:
        starts.append(starts[-1] + len(line))
    out = []
    sm = difflib.SequenceMatcher(None, a, b, autojunk=False)
    for tag, i1, i2, j1, j2 in sm.get_opcodes():
        if tag == "equal":
            continue
        out.append(TextEdit(starts[i1], starts[i2], "".join(b[j1:j2])))
    return out
