"""The parser's fast path for common lines builds exactly the tree the grammar builds."""

from __future__ import annotations

from dataclasses import fields
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plxtools.syntax import ast, parse_text, parser
from tests.conftest import bundle_files, campaign_size


def _dump(tree: ast.File) -> list:
    """Every node of every statement with its type, span and fields, plus the diagnostics."""
    out: list = []
    stack: list = [tree.statements]
    while stack:
        n = stack.pop()
        if isinstance(n, list):
            out.append(("[", len(n)))
            stack.extend(reversed(n))
        elif isinstance(n, ast.Node):
            out.append((type(n).__name__, n.span, getattr(n, "header", None)))
            for f in fields(n):
                if f.name not in ("span", "header"):
                    v = getattr(n, f.name)
                    if isinstance(v, (list, ast.Node)):
                        stack.append(v)
                    else:
                        out.append((f.name, v))
        else:
            out.append(repr(n))
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


EXPR_LINE = st.lists(st.sampled_from(["a", "b.c", "`d`", ":", ".", "1", "-", "2.5", '"s"', "true", "this", "(",
                                      ")", "[", "]", "{", "}", ",", "+", "*", "/", "f(", "x.y(", "is", "T",
                                      "or", "with", "reference", "optional", "const", "becomes", "fn", "static",
                                      "operator", "trait", "import", "as", "->", "a: T", "x: R[]"]),
                     min_size=1, max_size=10).map(" ".join)


@settings(max_examples=campaign_size(300), deadline=None)
@given(st.lists(EXPR_LINE, max_size=4))
def test_generated_expression_lines_same_tree(lines):
    text = "M is N:\n" + "".join(f"    a: {ln}\n    b is T: {ln}\n    {ln}\n" for ln in lines) \
        + "".join(f"{ln}\n" for ln in lines)
    fast, slow = _both(text)
    assert fast == slow


REPO = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("path", sorted((REPO / "examples").rglob("*.openplx")) + sorted(
    p for p in (REPO / "tests" / "cases").rglob("*.openplx") if "fmt" not in p.parts or "input" in p.name),
    ids=lambda p: str(p.relative_to(REPO)))
def test_example_and_case_files_same_tree(path):
    fast, slow = _both(path.read_bytes().decode("utf-8", "replace"))
    assert fast == slow


@settings(max_examples=campaign_size(200), deadline=None)
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
    p: Math.Vec3.from_xyz(0.5, 1.0, 2.0 * 3)
    q: [1, 2,
        3,]
    r: -a.b(c)[1] + -(2 - 3) * 4 / f() - {}
    s: {1, [], {2,}}
    optional t is A or B[] with C, D.E reference: this.u
    v becomes W reference
    x: `y`.z
Top
const Top2
const Top3:
    a: 1
const Top4 is A or B reference: 1
trait Tr
trait Tr2 is A.B:
    a is Real
import "x/y.openplx"
import "z" as Q.R
operator + (a: A, b: B) -> C
operator * (a: A, reference: B,)
M2:
    fn f()
    static fn g(x: Real[], y: A.B) -> Real[]
"""


def test_each_fast_shape_same_tree():
    fast, slow = _both(SHAPES)
    assert fast == slow
    assert parse_text(SHAPES).diagnostics == []
    from plxtools.syntax.lexer import lex

    slow_lines = [ln for ln in lex(SHAPES).lines if parser._fast(ln.tokens) is None]
    assert slow_lines == []  # every shape above is built by the fast path
