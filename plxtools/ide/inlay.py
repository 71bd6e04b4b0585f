"""Inlay hints: the inherited type after an assignment's path, and field names in `{...}` literals."""

from __future__ import annotations

import re

from plxtools.ide.context import member_of_stmt
from plxtools.ide.host import FileState
from plxtools.ide.types import InlayHint
from plxtools.model.symbols import Ty
from plxtools.syntax import ast


def inlay_hints(st: FileState, start: int, end: int) -> list[InlayHint]:
    p = st.program
    if p is None:
        return []
    out: list[InlayHint] = []
    for s in ast.walk_statements(st.tree.statements):
        if s.header.end.offset < start or s.header.start.offset > end:
            continue
        ty: Ty | None = None
        if isinstance(s, ast.Assignment) and s.path.parts:
            mem = member_of_stmt(st, s)
            if mem is None:
                continue
            ty = p.member_type(mem)
            if not ty.unknown:
                after = s.path.span.end
                full = ty.display()
                where = f"declared in {p.concrete(mem.owner).qname}" if mem.owner else None
                short = short_type(full)
                tip = where if short == full else f"{full}" + (f", {where}" if where else "")
                out.append(InlayHint(after.offset, after.line, after.column, f": {short}", "type", tooltip=tip))
        elif isinstance(s, ast.Declaration) and s.type is not None and s.value is not None:
            mem = member_of_stmt(st, s)
            ty = p.member_type(mem) if mem is not None else p.resolve_type_expr(s.type, st.unit)
        value = getattr(s, "value", None)
        if isinstance(value, ast.Brace) and ty is not None and ty.model is not None and not ty.array:
            fields = p.positional_fields(ty.model)
            if fields and len(fields) == len(value.items):
                for item, f in zip(value.items, fields):
                    a = item.span.start
                    out.append(InlayHint(a.offset, a.line, a.column, f"{f.name}:", "parameter", padding_right=True))
    return out


MAX_HINT = 28  # characters of a type hint; editors cut longer ones at the window's edge (VS Code)
_QUALIFIED = re.compile(r"\b(?:[A-Za-z_][A-Za-z0-9_]*\.)+([A-Za-z_][A-Za-z0-9_]*)")


def short_type(full: str) -> str:
    """A type as a hint: each qualified name by its own name (`RigidBody[]`, the bundle path is in the
    tooltip), and what is still too long cut at a `|` or with an ellipsis."""
    short = _QUALIFIED.sub(r"\1", full)
    if len(short) <= MAX_HINT:
        return short
    alts = short.split(" | ")
    if len(alts) > 1:
        return f"{alts[0]} | … ({len(alts)} types)"
    return short[:MAX_HINT - 1] + "…"
