"""Re-parse only what changed: a file is cut into top-level chunks, each parsed on its own and cached.

OpenPLX is line based and a statement at column 0 always closes every open block, so a top-level
statement with its block is a unit the parser handles the same alone or in the whole file. Typing
in one model re-parses that model; the other chunks are reused. Whenever a chunk is not lexically
self-contained (an unclosed bracket or string), the whole file is parsed as usual, so the result is
always exactly `parse_text`'s.

A tree handed out is never changed afterwards: a reader may still hold the tree of the previous
version (a request being answered, an analysis running) while the next version is parsed. A
chunk parsed once keeps its nodes at the positions of the version that parsed it; when text before
it grows or shrinks, the new tree gets a copy of it at its new offsets and lines (the copy is kept
for the next version while it stays there), and the old tree keeps the original.
"""

from __future__ import annotations

import gc
import re
from dataclasses import fields, is_dataclass, replace

from plxtools.diagnostics import Diagnostic, Edit, Fix, Pos, Span
from plxtools.syntax import ast
from plxtools.syntax.lexer import UNBALANCED_BRACKET, UNTERMINATED_STRING
from plxtools.syntax.parser import parse_text
from plxtools.syntax.source import BOM, LineIndex, ShiftedLines, TextSpan, detect_newline

# codes that mean a chunk may not be self-contained: re-parse the whole file instead
_CROSSING = {UNBALANCED_BRACKET, UNTERMINATED_STRING}
_CODE_LINE = re.compile(r'(?:[^"#]|"[^"\n]*")*')


def split_chunks(text: str) -> list[tuple[int, int]] | None:
    """Line numbers where top-level chunks start, with their offsets; None when unsure."""
    starts: list[tuple[int, int]] = [(0, 0)]
    in_triple = False
    depth = 0
    offset = 0
    for lineno, line in enumerate(text.split("\n")):
        if in_triple:
            if line.count('"""') % 2 == 1:
                in_triple = False
                # the rest of the line after the closing quotes still counts for brackets
                rest = line[line.rfind('"""') + 3:]
                depth += _bracket_delta(rest)
        else:
            first = line[:1]
            if lineno and first and first not in " \t\f\r#" and depth == 0:
                starts.append((lineno, offset))
            if '"""' in line:
                code = line
                if "#" in line.split('"""', 1)[0]:
                    code = _CODE_LINE.match(line).group()
                n = code.count('"""')
                if n % 2 == 1:
                    in_triple = True
                    depth += _bracket_delta(code[: code.find('"""')])
                else:
                    depth += _bracket_delta(code)
            elif "(" in line or "[" in line or "{" in line or ")" in line or "]" in line or "}" in line:
                depth += _bracket_delta(line)
            if depth < 0:
                return None
        offset += len(line) + 1
    if in_triple or depth:
        return None
    return starts


def _bracket_delta(line: str) -> int:
    code = _CODE_LINE.match(line).group() if ('"' in line or "#" in line) else line
    return (code.count("(") + code.count("[") + code.count("{")
            - code.count(")") - code.count("]") - code.count("}"))


class _Chunk:
    """One top-level statement with its block, at the position of the version it was built for;
    its nodes are shared by every tree that contains it there, and never changed."""

    __slots__ = ("text", "line", "offset", "statements", "comments", "diagnostics")

    def __init__(self, text: str, line: int, offset: int, statements, comments, diagnostics):
        self.text = text
        self.line = line
        self.offset = offset
        self.statements = statements
        self.comments = comments
        self.diagnostics = diagnostics

    def at(self, offset: int, line: int) -> "_Chunk":
        """This chunk at another place: itself when it is there already, else a moved copy."""
        if offset == self.offset and line == self.line:
            return self
        d_off, d_line = offset - self.offset, line - self.line
        mover = _Mover(d_off, d_line)
        return _Chunk(self.text, line, offset, [mover.copy(s) for s in self.statements],
                      [mover.copy(c) for c in self.comments], [mover.diagnostic(d) for d in self.diagnostics])


class IncrementalParser:
    """Parses successive versions of one document, re-using unchanged top-level chunks."""

    def __init__(self) -> None:
        self._chunks: dict[str, list[_Chunk]] = {}
        self.stats = {"full": 0, "incremental": 0, "reused": 0, "parsed": 0}

    def parse(self, text: str, path: str) -> ast.File:
        # copying moved chunks allocates many objects that all live on: the cyclic collector would
        # scan the whole heap several times per keystroke for nothing (5x the time, measured)
        enabled = gc.isenabled()
        gc.disable()
        try:
            return self._parse(text, path)
        finally:
            if enabled:
                gc.enable()

    def _parse(self, text: str, path: str) -> ast.File:
        if text.startswith(BOM) or "\r" in text:
            return self._full(text, path)
        starts = split_chunks(text)
        if starts is None or len(starts) < 2:
            return self._full(text, path)
        old: dict[str, list[_Chunk]] = {}
        for c in self._chunks.get(path, ()):
            old.setdefault(c.text, []).append(c)
        chunks: list[_Chunk] = []
        bounds = starts + [(None, len(text))]
        for (line, off), (_nl, end) in zip(bounds, bounds[1:]):
            piece = text[off:end]
            cands = old.get(piece)
            if cands:
                # prefer the copy already at the right place: nothing to copy at all
                best = next((c for c in cands if c.offset == off and c.line == line), cands[0])
                cands.remove(best)
                try:
                    chunks.append(best.at(off, line))
                except RecursionError:  # a pathologically deep expression: parse the file as usual
                    self._chunks.pop(path, None)
                    return self._full(text, path)
                self.stats["reused"] += 1
                continue
            tree = parse_text(piece, path)
            if any(d.code in _CROSSING for d in tree.diagnostics):
                self._chunks.pop(path, None)
                return self._full(text, path)
            c = _Chunk(piece, 0, 0, tree.statements, tree.comments, tree.diagnostics)
            try:
                chunks.append(c.at(off, line))
            except RecursionError:
                self._chunks.pop(path, None)
                return self._full(text, path)
            self.stats["parsed"] += 1
        self._chunks[path] = chunks
        self.stats["incremental"] += 1
        statements: list[ast.Stmt] = []
        comments: list[ast.Comment] = []
        diags: list[Diagnostic] = []
        for c in chunks:
            statements.extend(c.statements)
            comments.extend(c.comments)
            diags.extend(replace(d, file=path) for d in c.diagnostics)  # a tree's readers may change these
        diags.sort(key=lambda d: d.span.start.offset)
        return ast.File(path, text, statements, comments, diags, LineIndex(text), False, detect_newline(text))

    def forget(self, path: str) -> None:
        self._chunks.pop(path, None)

    def _full(self, text: str, path: str) -> ast.File:
        self.stats["full"] += 1
        # the chunks of an older version would outlive it (a 200,000-line document shrunk to one
        # line kept its whole tree here): a full parse starts over
        self._chunks.pop(path, None)
        return parse_text(text, path)


# ------------------------------------------------------------------ copying a chunk to a new place

_NODE_FIELDS: dict[type, tuple[tuple[str, ...], tuple[str, ...]]] = {}
_tuple_new = tuple.__new__


def _fields_of(cls: type) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(position fields, other fields) of a node class."""
    out = _NODE_FIELDS.get(cls)
    if out is None:
        names = tuple(f.name for f in fields(cls))
        out = _NODE_FIELDS[cls] = (tuple(n for n in names if n in ("span", "header")),
                                   tuple(n for n in names if n not in ("span", "header")))
    return out


_COPIERS: dict[type, object] = {}
# fields that never hold a node: copied as they are, without testing the value
_PLAIN = {"str", "bool", "int", "float", "int | float", "str | None", "bool | None", "int | None"}


def _copier(cls: type):
    """A function that copies one node of ``cls`` (generated once per class: a loop over field
    names with getattr/setattr costs three times as much, and copying is what a keystroke pays).
    Spans are shifted in line; child nodes are copied through the table of copiers directly."""
    fn = _COPIERS.get(cls)
    if fn is None:
        spans, others = _fields_of(cls)
        plain = {f.name for f in fields(cls) if isinstance(f.type, str) and f.type in _PLAIN}
        lines = ["def copy(n, m, Node=Node, new=new, TS=TS, cls=cls, get=get, make=make):",
                 "    c = new(cls)", "    d = m.d_off"]
        for name in spans:
            lines.append(f"    a = n.{name}")
            lines.append(f"    c.{name} = TS(a.s + d, a.e + d, m.lines_of(a.lines)) if a.__class__ is TS else m.span(a)")
        for name in others:
            if name in plain:
                lines.append(f"    c.{name} = n.{name}")
                continue
            lines.append(f"    v = n.{name}")
            lines.append("    if isinstance(v, Node): v = (get(v.__class__) or make(v.__class__))(v, m)")
            lines.append("    elif v.__class__ is list: v = [(get(x.__class__) or make(x.__class__))(x, m) "
                         "if isinstance(x, Node) else x for x in v]")
            lines.append(f"    c.{name} = v")
        lines.append("    return c")
        env = {"Node": ast.Node, "new": object.__new__, "TS": TextSpan, "cls": cls,
               "get": _COPIERS.get, "make": _copier}
        exec("\n".join(lines), env)  # noqa: S102 - generated from the dataclass's own field names
        fn = _COPIERS[cls] = env["copy"]
    return fn


class _Mover:
    """Copies nodes with every position shifted by an offset and a line delta (columns stay)."""

    __slots__ = ("d_off", "d_line", "_from", "_to")

    def __init__(self, d_off: int, d_line: int):
        self.d_off, self.d_line = d_off, d_line
        self._from = self._to = None

    def lines_of(self, lines) -> ShiftedLines:
        """The line table of a moved span (one per chunk's table, not one per node)."""
        if lines is not self._from:
            self._from, self._to = lines, ShiftedLines(lines, self.d_off, self.d_line)
        return self._to

    def span(self, s: Span) -> Span:
        if type(s) is TextSpan:
            return TextSpan(s.s + self.d_off, s.e + self.d_off, self.lines_of(s.lines))
        a, b = s
        d_off, d_line, new = self.d_off, self.d_line, _tuple_new
        return new(Span, (new(Pos, (a[0] + d_off, a[1] + d_line, a[2])), new(Pos, (b[0] + d_off, b[1] + d_line, b[2]))))

    def copy(self, node):
        return _copier(type(node))(node, self)

    def diagnostic(self, d: Diagnostic) -> Diagnostic:
        fix = d.fix
        if fix is not None:
            fix = Fix(fix.message, tuple(Edit(e.start + self.d_off, e.end + self.d_off, e.text) for e in fix.edits),
                      fix.safe)
        related = [(f, self.span(sp_), m) for (f, sp_, m) in d.related] if d.related else d.related
        return replace(d, span=self.span(d.span), fix=fix, related=related)


def same_tree(a: ast.File, b: ast.File) -> bool:
    """Trees equal in structure and in every span (for tests and self-checks)."""
    return _dump(a.statements) == _dump(b.statements) and [
        (c.span, c.text, c.own_line) for c in a.comments] == [(c.span, c.text, c.own_line) for c in b.comments] and [
        (d.code, d.message, d.span) for d in a.diagnostics] == [(d.code, d.message, d.span) for d in b.diagnostics]


def _dump(node: object) -> object:
    if isinstance(node, list):
        return tuple(_dump(n) for n in node)
    if is_dataclass(node) and isinstance(node, ast.Node):
        out: list[object] = [type(node).__name__]
        for f in fields(node):
            out.append(_dump(getattr(node, f.name)))
        return tuple(out)
    return node
