"""Hover: what a name is, its type, default and where that comes from, and its documentation."""

from __future__ import annotations

from plxtools.ide.context import (
    block_context,
    chain_before,
    header_at,
    qname_parts,
    resolve_at,
    span_in,
)
from plxtools.ide.describe import describe, expr_text
from plxtools.ide.host import FileState
from plxtools.ide.types import HoverResult
from plxtools.model.symbols import MemberSym, ModelSym
from plxtools.rules import suppress
from plxtools.syntax import ast
from plxtools.ide.context import symbol_of_top



def hover(st: FileState, offset: int) -> HoverResult | None:
    rule = _rule_hover(st, offset)
    if rule is not None:
        return rule
    if st.program is None:
        return None
    res = resolve_at(st, offset)
    if res is None:
        return None
    p = st.program
    context, path, line_stmt = _member_context(st, offset, res)
    text = describe(p, res.target, context, path)
    if isinstance(res.target, MemberSym):
        if line_stmt is not None and path:
            text = _own_line_value(text, st, line_stmt)
        for other in res.also:
            if isinstance(other, MemberSym) and other is not res.target and res.target.keyword == "becomes":
                owner = p.concrete(other.owner) if other.owner.anonymous else other.owner
                text += (f"\n\nspecialises `{other.name}` ({p.member_type(other).display()}) "
                         f"declared in `{owner.qname}`")
                break
    if not text:
        return None
    return HoverResult(text, res.span)


def _own_line_value(text: str, st: FileState, stmt: ast.Stmt) -> str:
    """On the line that gives the value, say so (`mass: 1000` · set on this line in `Chassis`)."""
    value = getattr(stmt, "value", None)
    if value is None:
        return text
    own = expr_text(value, st.unit)
    first, sep, rest = text.partition("\n\n")
    mark = f": {own}`** · set at line {value.span.start.line + 1} in "
    if first.startswith("**`") and mark in first:
        first = first.replace(f" · set at line {value.span.start.line + 1} in ", " · set on this line in ", 1)
    return first + sep + rest


def _member_context(st: FileState, offset: int, res):
    """For an attribute: the model whose value applies and the path from it, when we can tell."""
    if not isinstance(res.target, MemberSym):
        return None, None, None
    owners, stmt = header_at(st.tree, offset)
    if stmt is None:
        return None, None, None
    # a name in the statement's own path (left-hand side)
    path_node = getattr(stmt, "path", None)
    if isinstance(path_node, ast.QName) and path_node.span.start.offset <= offset <= path_node.span.end.offset:
        ctx = block_context(st, owners) if owners else None
        names = [p.name for p in path_node.parts]
        k = next((i for i, part in enumerate(path_node.parts)
                  if part.span.start.offset <= offset <= part.span.end.offset), len(names) - 1)
        if ctx is None:
            return None, None, None
        if ctx.outer is None:
            return None, None, None
        return ctx.outer, ctx.prefix + tuple(names[: k + 1]), stmt
    # a name in an expression: chains that start at an attribute of the outer model
    top = owners[0] if owners else stmt

    outer = symbol_of_top(st, top)
    if not isinstance(outer, ModelSym):
        return None, None, None
    chain = chain_before(st.text, res.span.end.offset)
    if not chain or any(ch in chain for ch in "()[]"):
        return outer, None, None
    names = [n for n, _a, _b in qname_parts(chain, span_in(st, 0, len(chain)))]
    if names and names[0] == "this":
        names = names[1:]
    if not names or names[0] not in st.program.all_members(outer):
        return outer, None, None
    return outer, tuple(names), None


def _rule_hover(st: FileState, offset: int) -> HoverResult | None:
    for c in st.tree.comments:
        if not (c.span.start.offset <= offset <= c.span.end.offset):
            continue
        sc = suppress.parse(c.text)
        if sc is None or sc.codes is None:
            return None
        for code, a, b in sc.codes:
            a, b = c.span.start.offset + a, c.span.start.offset + b
            if a <= offset <= b:
                from plxtools.rules.registry import get

                r = get(code)
                if r is None:
                    return HoverResult(f"unknown rule `{code}` (see `plx rule --all`)", span_in(st, a, b))
                return HoverResult(r.page(), span_in(st, a, b))
        return None
    return None
