"""The parser's fast path for common lines builds exactly the tree the grammar builds."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plxtools.syntax import ast, parse_text, parser
from tests.conftest import bundle_files


def _dump(tree: ast.File) -> list:
    """Structure plus every statement's spans and the diagnostics: what a difference would show."""
    out = [ast.structure(tree.statements)]
    for s in ast.walk_statements(tree.statements):
        out.append((type(s).__name__, s.span, s.header, getattr(s, "colon", None)))
        for name in ("path", "type", "value"):
            node = getattr(s, name, None)
            if node is not None:
                out.append((name, node.span, type(node).__name__))
    out.append([(d.code, d.message, d.span) for d in tree.diagnostics])
    return out


def _both(text: str) -> tuple[list, list]:
    fast = _dump(parse_text(text))
    parser.FAST_PATH = False
    try:
        slow = _dump(parse_text(text))
    finally:
        parser.FAST_PATH = True
    return fast, slow


@pytest.mark.parametrize("path", bundle_files()[::5])
def test_bundle_files_same_tree(path):
    fast, slow = _both(path.read_text(encoding="utf-8-sig"))
    assert fast == slow


LINE = st.lists(st.sampled_from(["a", "b.c", "`d.e`", "is", "becomes", ":", ".", "1", "-", "2.5", '"s"',
                                 "true", "false", "this", "T", "[", "]", "reference", "const", "-", "-1", "x.y.z", "with", ",", "this.a", "Real"]), min_size=1,
                max_size=6).map(" ".join)


@settings(max_examples=200, deadline=None)
@given(st.lists(LINE, max_size=4))
def test_generated_lines_same_tree(lines):
    text = "M is N:\n" + "".join(f"    {ln}\n    .{ln}\n" for ln in lines) + "".join(f"{ln}\n" for ln in lines)
    fast, slow = _both(text)
    assert fast == slow


SHAPES = """M is N:
    with A.B, C
    with D
    .doc: "text"
    .n: -2
    a: this.x.y
    b.c: d.e
    e becomes F.G: 3
    f becomes G
    g is H: true
    h: -1.5
    i:
        j: 1
    k is L.M:
        n: false
"""


def test_each_fast_shape_same_tree():
    fast, slow = _both(SHAPES)
    assert fast == slow
    assert parse_text(SHAPES).diagnostics == []
