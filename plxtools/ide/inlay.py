"""Inlay hints: the inherited type after an assignment's path, and field names in `{...}` literals."""

from __future__ import annotations

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
                out.append(InlayHint(after.offset, after.line, after.column, f": {ty.display()}", "type",
                                     tooltip=f"declared in {p.concrete(mem.owner).qname}" if mem.owner else None))
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
