"""Re-parse only what changed: a file is cut into top-level chunks, each parsed on its own and cached.

OpenPLX is line based and a statement at column 0 always closes every open block, so a top-level
statement with its block is a unit the parser handles the same alone or in the whole file. Typing
in one model re-parses that model; the other chunks are reused (moved to their new offsets and
lines when text before them changed). Whenever a chunk is not lexically self-contained (an
unclosed bracket or string), the whole file is parsed as usual, so the result is always exactly
`parse_text`'s.
"""

from __future__ import annotations

import re
from dataclasses import fields, is_dataclass

from plxtools.diagnostics import Diagnostic, Edit, Fix, Pos, Span
from plxtools.syntax import ast, parse_text
from plxtools.syntax.source import BOM, LineIndex, detect_newline

# codes that mean a chunk may not be self-contained: re-parse the whole file instead
_CROSSING = {"S004", "S009"}
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
    __slots__ = ("text", "line", "offset", "statements", "comments", "diagnostics", "nodes", "stmts")

    def __init__(self, text: str, line: int, offset: int, tree: ast.File):
        self.text = text
        self.line = line
        self.offset = offset
        self.statements = tree.statements
        self.comments = tree.comments
        self.diagnostics = tree.diagnostics
        self.nodes: list | None = None  # every node, flattened on the first move
        self.stmts: list | None = None


class IncrementalParser:
    """Parses successive versions of one document, re-using unchanged top-level chunks."""

    def __init__(self) -> None:
        self._chunks: dict[str, list[_Chunk]] = {}
        self.stats = {"full": 0, "incremental": 0, "reused": 0, "parsed": 0}

    def parse(self, text: str, path: str) -> ast.File:
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
                # prefer the copy already at the right place: no moving at all
                best = next((c for c in cands if c.offset == off and c.line == line), cands[0])
                cands.remove(best)
                if best.offset != off or best.line != line:
                    _move(best, off - best.offset, line - best.line)
                    best.offset, best.line = off, line
                self.stats["reused"] += 1
                chunks.append(best)
                continue
            tree = parse_text(piece, path)
            if any(d.code in _CROSSING for d in tree.diagnostics):
                self._chunks.pop(path, None)
                return self._full(text, path)
            c = _Chunk(piece, 0, 0, tree)
            if off or line:
                _move(c, off, line)
                c.offset, c.line = off, line
            self.stats["parsed"] += 1
            chunks.append(c)
        self._chunks[path] = chunks
        self.stats["incremental"] += 1
        statements: list[ast.Stmt] = []
        comments: list[ast.Comment] = []
        diags: list[Diagnostic] = []
        for c in chunks:
            statements.extend(c.statements)
            comments.extend(c.comments)
            diags.extend(c.diagnostics)
        for d in diags:
            d.file = path
        diags.sort(key=lambda d: d.span.start.offset)
        return ast.File(path, text, statements, comments, diags, LineIndex(text), False, detect_newline(text))

    def forget(self, path: str) -> None:
        self._chunks.pop(path, None)

    def _full(self, text: str, path: str) -> ast.File:
        self.stats["full"] += 1
        return parse_text(text, path)


# ------------------------------------------------------------------ moving a parsed chunk

_NODE_FIELDS: dict[type, tuple[str, ...]] = {}


def _fields_of(cls: type) -> tuple[str, ...]:
    out = _NODE_FIELDS.get(cls)
    if out is None:
        out = tuple(f.name for f in fields(cls) if f.name not in ("span", "header"))
        _NODE_FIELDS[cls] = out
    return out


def _flatten(chunk: _Chunk) -> None:
    nodes: list = []
    stmts: list = []
    stack: list[object] = list(chunk.statements)
    while stack:
        node = stack.pop()
        nodes.append(node)
        if isinstance(node, ast.Stmt):
            stmts.append(node)
        for name in _fields_of(type(node)):
            v = getattr(node, name)
            if isinstance(v, ast.Node):
                stack.append(v)
            elif isinstance(v, list):
                for item in v:
                    if isinstance(item, ast.Node):
                        stack.append(item)
    nodes.extend(chunk.comments)
    chunk.nodes = nodes
    chunk.stmts = stmts


_tuple_new = tuple.__new__


def _move(chunk: _Chunk, d_off: int, d_line: int) -> None:
    """Shift every position in a chunk by an offset and a line delta (columns do not change)."""
    if chunk.nodes is None:
        _flatten(chunk)
    memo: dict[int, Span] = {}
    new = _tuple_new

    def sp(s: Span) -> Span:
        got = memo.get(id(s))
        if got is None:
            a, b = s
            got = new(Span, (new(Pos, (a[0] + d_off, a[1] + d_line, a[2])),
                             new(Pos, (b[0] + d_off, b[1] + d_line, b[2]))))
            memo[id(s)] = got
        return got

    for node in chunk.nodes:
        s = node.span
        got = memo.get(id(s))
        node.span = got if got is not None else sp(s)
    for node in chunk.stmts:
        node.header = sp(node.header)
    moved = []
    for d in chunk.diagnostics:
        d.span = sp(d.span)
        if d.fix is not None:
            d.fix = Fix(d.fix.message, tuple(Edit(e.start + d_off, e.end + d_off, e.text) for e in d.fix.edits),
                        d.fix.safe)
        if d.related:
            d.related = [(f, sp(sp_), m) for (f, sp_, m) in d.related]
        moved.append(d)
    chunk.diagnostics = moved


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
