"""Node spans are offsets into the file's line table (syntax/source.py TextSpan): their lines and
columns must be those of the text, and they must behave as the Span of the same positions."""

from __future__ import annotations

import pickle
import re

from plxtools.diagnostics import Diagnostic, Pos, Severity, Span
from plxtools.syntax import ast, parse_text
from plxtools.syntax.incremental import IncrementalParser, same_tree

TEXT = (
    "# a model with every kind of line break\r\n"
    "Wheel is Physics3D.Bodies.RigidBody:\r\n"
    "    `odd name` is Real: 1.5\r\n"
    "    doc is String: \"\"\"two\r\nlines\"\"\"\n"
    "    size: Math.Vec3.from_xyz(\r\n        1, 2,\r        3)  # trailing\n"
    "\tmass: -2 * (3 + 4)\n"
)


def _names(tree):
    stack = list(tree.statements)
    while stack:
        n = stack.pop()
        if isinstance(n, ast.Ident):
            yield n
        if isinstance(n, list):
            stack.extend(n)
        elif isinstance(n, ast.Node):
            stack.extend(getattr(n, f) for f in n.__dataclass_fields__ if f not in ("span", "header"))


def test_every_name_span_has_the_line_and_column_of_its_text():
    tree = parse_text(TEXT)
    lines = re.split(r"\r\n?|\n", TEXT)
    names = list(_names(tree))
    assert len(names) >= 12
    for ident in names:
        start, end = ident.span.start, ident.span.end
        written = f"`{ident.name}`" if ident.backtick else ident.name
        assert TEXT[start.offset:end.offset] == written
        assert lines[start.line][start.column:].startswith(written)
        assert (end.line, end.column) == (start.line, start.column + len(written))


def test_a_span_reads_compares_hashes_and_pickles_as_a_span_of_positions():
    tree = parse_text(TEXT)
    span = tree.statements[0].header
    plain = Span(span.start, span.end)
    assert span == plain and plain == span and not (span != plain)
    assert hash(span) == hash(plain)
    assert tuple(span) == tuple(plain) and span[0] == plain.start and len(span) == 2
    assert repr(span) == repr(plain)
    assert span.start == Pos(41, 1, 0) and span.contains(50) and not span.contains(10)
    back = pickle.loads(pickle.dumps(span))
    assert type(back) is Span and back == span
    # a diagnostic on a node is sent between processes without the file's text and line table
    d = Diagnostic("N001", "x", tree.statements[0].path.span, Severity.ERROR)
    sent = pickle.dumps(d)
    assert b"lines" not in sent and b"Wheel" not in sent and len(sent) < 600
    assert pickle.loads(pickle.dumps(d)).span == d.span


def test_moved_chunks_have_the_positions_of_a_fresh_parse():
    first = "A is B:\n    x: 1\n\nC is D:\n    y: foo.bar(2)\n"
    parser = IncrementalParser()
    parser.parse(first, "f.openplx")
    for before in ("Z is Y\n", "Z is Y\n\n\n", ""):
        text = before + first.replace("x: 1", "x: 12345")
        moved = parser.parse(text, "f.openplx")
        fresh = parse_text(text, "f.openplx")
        assert same_tree(moved, fresh)
        last = moved.statements[-1].body[0].value
        assert (last.span.start.line, last.span.start.column) == (fresh.statements[-1].body[0].value.span.start.line, 7)
