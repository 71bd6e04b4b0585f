"""Laying out a whole file: statements at their block level, comments, blank lines, regions.

The syntax tree says which block each statement belongs to; the lexer's logical lines give each
statement's tokens and the comments inside it. Both come from the same text, one logical line per
statement, in the same order, so they are walked side by side.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterator

from plxtools.fmt.brackets import LayoutError, Note, Tok, nest
from plxtools.fmt.directives import directive, is_line_suppression
from plxtools.fmt.printer import print_line
from plxtools.fmt.style import COMMENT_GAP, INDENT, blank_cap, token_kinds
from plxtools.fmt.verbatim import indent_width, rebased_lines
from plxtools.syntax import ast
from plxtools.syntax.lexer import Lexer, LogicalLine
from plxtools.syntax.source import line_start


@dataclass(slots=True)
class Piece:
    """One statement header or one own-line comment between statements, in file order."""

    depth: int
    first_line: int  # source lines, 0-based
    last_line: int
    stmt: ast.Stmt | None = None
    line: LogicalLine | None = None
    comment_text: str = ""  # for a comment piece: its text
    trailing: tuple[int, str] | None = None  # a statement's trailing comment: (end offset, text)
    inner: list[Note] = field(default_factory=list)
    opens_block: bool = False
    verbatim: bool = False
    pinned: bool = False  # covered by a `# plx: ignore`: its line structure must not change
    out: list[str] = field(default_factory=list)  # printed code, without the trailing comment
    blanks: int = 0  # blank lines printed before the piece
    indent: int = -1  # a statement's source indentation (its tokens are not kept once printed)


@dataclass(slots=True)
class Layout:
    text: str  # the formatted text
    pieces: list[Piece]  # what it was made of, for range formatting


def _statements_with_depth(stmts: list[ast.Stmt]) -> Iterator[tuple[ast.Stmt, int]]:
    stack = [(iter(stmts), 0)]
    while stack:
        it, depth = stack[-1]
        for s in it:
            yield s, depth
            body = ast.body_of(s)
            if body:
                stack.append((iter(body), depth + 1))
            break
        else:
            stack.pop()


def _comment_depth(column: int, cols: list[int], lowest: int) -> int:
    """The deepest open block, no deeper than the comment's column, and not above `lowest`.

    `cols[d]` is the source column of the enclosing statement at depth d of the statement before
    the comment; `lowest` is the depth of the statement after it (the comment belongs there
    unless it is indented into a block that is still open).
    """
    for d in range(len(cols) - 1, lowest - 1, -1):
        if cols[d] <= column:
            return d
    return lowest


class _Marks:
    """What a piece's marks depend on in the pieces before it: an open `fmt: off` region and the
    piece just before (a `# plx: ignore` line)."""

    __slots__ = ("off", "prev")

    def __init__(self) -> None:
        self.off = False
        self.prev: Piece | None = None

    def mark(self, p: Piece) -> None:
        """`# plx: fmt: off` ... `# plx: fmt: on` regions, statements ending in `# plx: fmt: skip`,
        and statements a `# plx: ignore` comment covers (before, after or inside them): those keep
        their lines (the suppression covers one line; splitting or joining the statement would move
        the code it covers off that line, and a clean file would get errors after formatting)."""
        if p.stmt is None:
            d = directive(p.comment_text)
            if d == "off" and not self.off:
                self.off = True
                p.verbatim = True
            elif self.off:
                p.verbatim = True
                if d == "on":
                    self.off = False
        else:
            p.verbatim = self.off or (p.trailing is not None and directive(p.trailing[1]) == "skip")
            p.pinned = _pinned(p, self.prev)
        self.prev = p


def _pinned(p: Piece, prev: Piece | None) -> bool:
    """Is this statement covered by a `# plx: ignore` before, after or inside it?"""
    return ((prev is not None and prev.stmt is None and is_line_suppression(prev.comment_text))
            or (p.trailing is not None and is_line_suppression(p.trailing[1]))
            or any(is_line_suppression(n.text) for n in p.inner))


def rendered_pieces(text: str, tree: ast.File, lexer: Lexer) -> Iterator[Piece]:
    """Every piece in file order, marked and printed (`out`), as the lexer gives the logical lines:
    a statement's tokens live only until its piece is printed (the tokens of a whole file take
    more memory than its tree).

    Each comment is inside a logical line, trails one, or stands alone between statements; the
    comments up to a line's start are all lexed when the lexer gives that line, so the statement
    before it is complete (its inner and trailing comments known) and can be printed then."""
    stmts = _statements_with_depth(tree.statements)
    cols: list[int] = []  # source columns of the statement before and of its enclosing statements
    marks = _Marks()
    ci = 0  # the first comment not yet placed
    cur: Piece | None = None  # the last statement's piece, not yet printed
    cur_line: LogicalLine | None = None
    lines = lexer.iter_lines()
    while True:
        ln = next(lines, None)
        limit = ln.start if ln is not None else len(text) + 1
        comments = lexer.comments
        standalone: list[Piece] = []
        while ci < len(comments) and comments[ci][0] < limit:
            start, line, _col, end, ctext, own = comments[ci]
            ci += 1
            if cur_line is not None and start < cur_line.end:
                cur.inner.append(Note(ctext.rstrip(), own, line, start))  # type: ignore[union-attr]
            elif cur_line is not None and not own and line == cur_line.tokens[-1].end_line:
                cur.trailing = (end, ctext.rstrip())  # type: ignore[union-attr]
            else:
                column, _ = indent_width(text[line_start(text, start):start])
                standalone.append(Piece(0, line, line, comment_text=ctext.rstrip(), indent=column))
        if cur is not None:
            marks.mark(cur)
            _render(text, cur)
            cur.line = None  # (its tokens are printed)
            yield cur
            cur = cur_line = None
        if ln is None:
            stmt_depth = None
        else:
            stmt_depth = next(stmts, None)
            if stmt_depth is None or stmt_depth[0].header.start.offset != ln.start:
                raise LayoutError("statements and logical lines do not match")
        for c in standalone:
            c.depth = _comment_depth(c.indent, cols, stmt_depth[1] if stmt_depth is not None else 0)
            c.indent = -1
            marks.mark(c)
            _render(text, c)
            yield c
        if ln is None:
            break
        stmt, depth = stmt_depth  # type: ignore[misc]
        del cols[depth:]
        cols.append(ln.indent)
        cur = Piece(depth, ln.tokens[0].line, ln.tokens[-1].end_line, stmt=stmt, line=ln, indent=ln.indent)
        cur.opens_block = bool(ast.body_of(stmt))
        cur_line = ln
    if next(stmts, None) is not None:
        raise LayoutError("statements and logical lines do not match")


def _render(text: str, p: Piece) -> None:
    indent = p.depth * INDENT
    if p.stmt is None:
        p.out = [" " * indent + p.comment_text]
        return
    ln = p.line
    assert ln is not None
    if p.verbatim:
        end = p.trailing[0] if p.trailing else ln.end
        strings = [(t.start_pos, t.end_pos) for t in ln.tokens if t.type == "STRING"]
        p.out = rebased_lines(text, ln.start, end, ln.indent, indent, strings)
        return
    kinds = token_kinds([t.type for t in ln.tokens])
    toks = [Tok(k, text[t.start_pos : t.end_pos], t.line, t.end_line, t.start_pos) for t, k in zip(ln.tokens, kinds)]
    p.out = print_line(nest(toks, p.inner), indent)
    if p.pinned and (len(p.out) != 1 or "\n" in p.out[0] or ln.tokens[0].line != ln.tokens[-1].end_line):
        p.verbatim = True  # only a one-line statement that stays one line may be re-spaced
        _render(text, p)


def _blank_lines(pieces: list[Piece]) -> None:
    prev: Piece | None = None
    for p in pieces:
        if prev is None:
            p.blanks = 0
        else:
            found = max(0, p.first_line - prev.last_line - 1)
            if prev.verbatim and p.verbatim:
                p.blanks = found  # inside a `fmt: off` region
            elif prev.opens_block and p.depth > prev.depth:
                p.blanks = 0  # nothing between a block's header and its first line
            else:
                p.blanks = min(found, blank_cap(p.depth))
        prev = p


def _single_line(p: Piece) -> bool:
    return p.stmt is not None and not p.verbatim and len(p.out) == 1 and "\n" not in p.out[0]


def _attach_trailing(pieces: list[Piece]) -> None:
    """Trailing comments: two spaces after the code, aligned across a run of sibling lines.

    A run is a stretch of one-line statements of the same block with no blank line or comment
    line between them; the comments in it line up two spaces after its longest commented line.
    """
    i = 0
    n = len(pieces)
    while i < n:
        p = pieces[i]
        if not _single_line(p):
            if p.trailing is not None and not p.verbatim:
                p.out[-1] += " " * COMMENT_GAP + p.trailing[1]
            i += 1
            continue
        j = i + 1
        while j < n and _single_line(pieces[j]) and pieces[j].depth == p.depth and pieces[j].blanks == 0:
            j += 1
        run = [q for q in pieces[i:j] if q.trailing is not None]
        if run:
            col = max(len(q.out[0]) for q in run) + COMMENT_GAP
            for q in run:
                q.out[0] = q.out[0].ljust(col) + q.trailing[1]  # type: ignore[index]
        i = j


def layout(text: str, tree: ast.File, lexer: Lexer, newline: str) -> Layout:
    """The formatted text of an error-free tree; `lexer` is a fresh Lexer of the same text."""
    pieces = list(rendered_pieces(text, tree, lexer))
    _blank_lines(pieces)
    _attach_trailing(pieces)
    out: list[str] = []
    for p in pieces:
        out.extend([""] * p.blanks)
        out.extend(p.out)
    body = newline.join(out) + newline if out else ""
    return Layout(body, pieces)
