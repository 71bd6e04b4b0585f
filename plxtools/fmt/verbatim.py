"""Statements kept as the user wrote them (`# plx: fmt: off` regions and `# plx: fmt: skip`).

Only the indentation moves: the statement's first line goes to its block level (the file's
meaning depends on it) and its continuation lines move by the same amount, so their layout
relative to the first line is kept. Lines inside a \"\"\" string are never touched.
"""

from __future__ import annotations

import re

_BREAK_RE = re.compile(r"\r\n?|\n")


def indent_width(line: str) -> tuple[int, int]:
    """(column, characters) of a line's leading whitespace, counting tabs as the lexer does."""
    col = 0
    i = 0
    for ch in line:
        if ch == "\t":
            col = (col // 4 + 1) * 4
        elif ch in " \f":
            col += 1
        else:
            break
        i += 1
    return col, i


def rebased_lines(
    text: str, start: int, end: int, column: int, indent: int, string_spans: list[tuple[int, int]]
) -> list[str]:
    """The source text[start:end] (which begins at `column`) as output lines starting at `indent`.

    `string_spans` are (start, end) offsets of the strings inside it; a line break inside one is
    part of the string, not a place to re-indent.
    """
    cuts = [  # (start, end) of each line break outside strings; \r\n, \r and \n all count
        (m.start(), m.end())
        for m in _BREAK_RE.finditer(text, start, end)
        if not any(s < m.start() < e for s, e in string_spans)
    ]
    delta = indent - column
    out: list[str] = []
    begin = start
    for n, (cut, after) in enumerate(cuts + [(end, end)]):
        piece = text[begin:cut].rstrip()
        if n == 0:
            out.append(" " * indent + piece)
        elif piece:
            col, skip = indent_width(piece)
            out.append(" " * max(0, col + delta) + piece[skip:])
        else:
            out.append("")
        begin = after
    return out
