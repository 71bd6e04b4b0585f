"""The bracket structure of one logical line, with the comments that sit inside its brackets.

The printer needs to know, for each `(...)`, `[...]` and `{...}`: its items, which comments lead,
trail or interrupt each item, where the user broke lines between items, and whether the bracket
is written on one line or split. That is computed here from token and comment positions only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Union

from plxtools.fmt.style import CLOSERS, OPENERS


@dataclass(slots=True)
class Tok:
    kind: str  # lexer type, or style.NEG / style.OPSYM
    text: str  # exactly as in the source
    line: int
    end_line: int  # differs from `line` for a multi-line \"\"\" string
    start: int


@dataclass(slots=True)
class Note:
    """A comment inside a logical line."""

    text: str
    own: bool  # alone on its line
    line: int
    start: int

    @property
    def end_line(self) -> int:
        return self.line


@dataclass(slots=True)
class Item:
    leading: list[Note] = field(default_factory=list)  # own-line comments before the item
    core: list["Elem"] = field(default_factory=list)  # tokens, groups and interrupting comments
    trailing: list[Note] = field(default_factory=list)  # comments after the item's last token
    comma: Tok | None = None


@dataclass(slots=True)
class Group:
    open: Tok
    close: Tok
    elems: list["Elem"] = field(default_factory=list)
    # filled in by `analyse`:
    split: bool = False
    opener_notes: list[Note] = field(default_factory=list)
    items: list[Item] = field(default_factory=list)
    row_breaks: list[bool] = field(default_factory=list)  # before each item
    closing_notes: list[Note] = field(default_factory=list)

    @property
    def line(self) -> int:
        return self.open.line

    @property
    def end_line(self) -> int:
        return self.close.end_line


Elem = Union[Tok, Group, Note]


class LayoutError(Exception):
    """The printer met a shape it cannot lay out; the caller reports an internal error."""


def nest(tokens: list[Tok], notes: list[Note]) -> list[Elem]:
    """Tokens and inner comments (both in source order) as a tree of bracket groups."""
    root: list[Elem] = []
    cur = root
    stack: list[tuple[Tok, list[Elem]]] = []
    ti = ni = 0
    while ti < len(tokens) or ni < len(notes):
        if ni < len(notes) and (ti >= len(tokens) or notes[ni].start < tokens[ti].start):
            if cur is root:
                raise LayoutError("a comment outside brackets inside a logical line")
            cur.append(notes[ni])
            ni += 1
            continue
        t = tokens[ti]
        ti += 1
        if t.kind in OPENERS:
            stack.append((t, cur))
            cur = []
        elif t.kind in CLOSERS:
            if not stack:
                raise LayoutError("unbalanced brackets")
            opener, parent = stack.pop()
            group = Group(opener, t, cur)
            analyse(group)
            parent.append(group)
            cur = parent
        else:
            cur.append(t)
    if stack:
        raise LayoutError("unbalanced brackets")
    return root


def _first_line(e: Elem) -> int:
    return e.line


def _last_line(e: Elem) -> int:
    return e.end_line


def analyse(g: Group) -> None:
    """Cut a group into items, attach its comments, and decide whether it is split."""
    raw: list[tuple[list[Elem], Tok | None]] = []
    chunk: list[Elem] = []
    for e in g.elems:
        if isinstance(e, Tok) and e.kind == "COMMA":
            raw.append((chunk, e))
            chunk = []
        else:
            chunk.append(e)
    raw.append((chunk, None))

    items: list[Item] = []
    for elems, comma in raw:
        core_at = [i for i, e in enumerate(elems) if not isinstance(e, Note)]
        if not core_at:  # after a trailing comma, or an empty bracket
            notes = list(elems)
            _hand_back(notes, items, g)
            g.closing_notes.extend(notes)
            continue
        lo, hi = core_at[0], core_at[-1]
        prefix = [e for e in elems[:lo] if isinstance(e, Note)]
        _hand_back(prefix, items, g)
        item = Item(prefix, elems[lo : hi + 1], [e for e in elems[hi + 1 :] if isinstance(e, Note)], comma)
        items.append(item)
    g.items = items

    breaks = []
    for i, item in enumerate(items):
        if i == 0:
            breaks.append(item.leading != [] or _first_line(item.core[0]) != g.open.end_line)
        else:
            prev = items[i - 1]
            breaks.append(bool(prev.trailing or item.leading) or _last_line(prev.core[-1]) != _first_line(item.core[0]))
    g.row_breaks = breaks
    has_notes = any(isinstance(e, Note) for e in g.elems)
    closes_apart = bool(items) and _last_line(items[-1].core[-1]) != g.close.line
    g.split = has_notes or any(breaks) or closes_apart


def _hand_back(notes: list[Note], items: list[Item], g: Group) -> None:
    """A comment right after a comma or the opener, on its line, trails what came before it."""
    if notes and not notes[0].own:
        first = notes.pop(0)
        (items[-1].trailing if items else g.opener_notes).append(first)
