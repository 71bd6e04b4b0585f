"""Printing one logical line (a statement's header) in the canonical style.

Tokens are written with the spacing of `style.gap`; brackets are written on one line or split
(opening bracket ends the line, the user's rows of items one level deeper, closing bracket on
its own line). The statement's trailing comment is added by the caller, which aligns it.
"""

from __future__ import annotations

from plxtools.fmt.brackets import Elem, Group, Item, Note, Tok
from plxtools.fmt.style import COMMENT_GAP, INDENT, gap


class Writer:
    """Output lines under construction; `fresh` means nothing but indentation on the line yet."""

    __slots__ = ("lines", "cur", "fresh", "prev")

    def __init__(self, indent: int):
        self.lines: list[str] = []
        self.cur: list[str] = [" " * indent]
        self.fresh = True
        self.prev = ""

    def tok(self, t: Tok) -> None:
        if not self.fresh:
            self.cur.append(gap(self.prev, t.kind))
        self.cur.append(t.text)
        self.fresh = False
        self.prev = t.kind

    def comment_after(self, note: Note) -> None:
        self.cur.append(" " * COMMENT_GAP + note.text)
        self.fresh = False

    def comment_alone(self, note: Note) -> None:
        self.cur.append(note.text)
        self.fresh = False

    def newline(self, indent: int) -> None:
        self.lines.append("".join(self.cur))
        self.cur = [" " * indent]
        self.fresh = True

    def finish(self) -> list[str]:
        self.lines.append("".join(self.cur))
        return self.lines


def print_line(elems: list[Elem], indent: int) -> list[str]:
    """Output lines of one logical line whose first line is indented `indent` spaces."""
    w = Writer(indent)
    _seq(w, elems, indent)
    return w.finish()


def _seq(w: Writer, elems: list[Elem], indent: int) -> None:
    for e in elems:
        if isinstance(e, Tok):
            w.tok(e)
        elif isinstance(e, Group):
            _group(w, e, indent)
        else:  # pragma: no cover - `brackets.nest` keeps comments inside groups
            raise AssertionError("comment outside brackets")


def _group(w: Writer, g: Group, indent: int) -> None:
    w.tok(g.open)
    if not g.split:
        elems = g.elems
        if elems and isinstance(elems[-1], Tok) and elems[-1].kind == "COMMA":
            elems = elems[:-1]  # no trailing comma
        _seq(w, elems, indent)
        w.tok(g.close)
        return
    inner = indent + INDENT
    for n in g.opener_notes:
        w.comment_after(n)
    last = len(g.items) - 1
    for i, item in enumerate(g.items):
        if i == 0 or g.row_breaks[i]:
            w.newline(inner)
            for n in item.leading:
                w.comment_alone(n)
                w.newline(inner)
        _item(w, item, inner)
        if i < last:
            assert item.comma is not None
            w.tok(item.comma)
        for k, n in enumerate(item.trailing):
            if k == 0 and not n.own:
                w.comment_after(n)
            else:
                w.newline(inner)
                w.comment_alone(n)
    for n in g.closing_notes:
        w.newline(inner)
        w.comment_alone(n)
    w.newline(indent)
    w.tok(g.close)


def _item(w: Writer, item: Item, indent: int) -> None:
    """An item's tokens; a comment inside the item breaks the line and the item continues deeper."""
    cur = indent
    for e in item.core:
        if isinstance(e, Note):
            cur = indent + INDENT
            if e.own:
                if not w.fresh:
                    w.newline(cur)
                w.comment_alone(e)
            else:
                w.comment_after(e)
            w.newline(cur)
        elif isinstance(e, Group):
            _group(w, e, cur)
        else:
            w.tok(e)
