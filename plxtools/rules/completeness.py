"""Missing assignments and unbound references in what a file's root model instantiates (M007, M008).

Library models may be incomplete; only objects that the root model (the last model in a file
outside any bundle) actually creates must have every non-optional value.
"""

from __future__ import annotations

from plxtools.diagnostics import Diagnostic, Severity, Span
from plxtools.model.program import Program
from plxtools.model.symbols import ModelSym, Ty
from plxtools.syntax import ast

REQUIRED_PRIMITIVES = {"Real", "Int", "Bool", "String"}
MAX_DEPTH = 40


def root_model(program: Program, unit) -> ModelSym | None:
    last = None
    for s in unit.tree.statements:
        if isinstance(s, ast.Declaration) and s.keyword != "becomes" and len(s.path.parts) == 1:
            sym = unit.locals.get(s.path.parts[0].name) if unit.bundle is None else unit.namespace.symbols.get(s.path.parts[0].name)
            if isinstance(sym, ModelSym) and not sym.is_trait and sym.stmt is s:
                last = sym
    return last


def _walk_assigned(body, prefix: tuple[str, ...], out: set[tuple[str, ...]]) -> None:
    for s in body:
        if isinstance(s, ast.Declaration) and s.keyword in ("is", "becomes"):
            if s.value is not None:
                out.add(prefix + tuple(p.name for p in s.path.parts))
        elif isinstance(s, ast.Assignment):
            path = prefix + tuple(p.name for p in s.path.parts)
            if s.value is not None:
                out.add(path)
            if s.body:
                _walk_assigned(s.body, path, out)


def _assigned(program: Program, model: ModelSym) -> set[tuple[str, ...]]:
    """Paths given a value anywhere in a model's chain of bases, traits and its own body."""
    out: set[tuple[str, ...]] = set()
    for m in program.ancestors(model):
        body = getattr(m.stmt, "body", None)
        if body:
            _walk_assigned(body, (), out)
    return out


def completeness_diagnostics(program: Program, unit) -> list[Diagnostic]:
    if unit.bundle is not None:
        return []
    root = root_model(program, unit)
    if root is None:
        return []
    out: list[Diagnostic] = []
    seen: set[tuple[str, str]] = set()
    memo: dict[int, set[tuple[str, ...]]] = {}

    def assigned_in(m: ModelSym) -> set[tuple[str, ...]]:
        got = memo.get(id(m))
        if got is None:
            got = memo[id(m)] = _assigned(program, m)
        return got

    def visit(ty: Ty, outer: set[tuple[str, ...]], path: str, anchor: Span, depth: int, chain: tuple) -> None:
        model = ty.model
        if model is None or depth > MAX_DEPTH or id(model) in chain:
            return
        assigned = assigned_in(model) | outer
        for t in ty.traits:
            assigned |= assigned_in(t)
        for name, mem in program.members_of(ty).items():
            mty = program.member_type(mem)
            here = (name,) in assigned or mem.value is not None
            local_anchor = anchor
            if mem.owner.unit is unit and mem.stmt.path is not None:
                local_anchor = mem.stmt.path.span
            full = f"{path}.{name}" if path else name
            if mem.reference:
                if not here and not mem.optional and (full, "ref") not in seen:
                    seen.add((full, "ref"))
                    out.append(Diagnostic(
                        "M008", f"reference '{full}' ({mty.display()}) is never bound",
                        local_anchor, Severity.ERROR, file=unit.path,
                        help=f"give it an existing object: '{name}: ...' (declared in {mem.owner.qname})"))
                continue
            if mty.unknown or mty.alts or mty.array:
                continue
            if mty.primitive is not None:
                if mty.primitive in REQUIRED_PRIMITIVES and not here and not mem.optional and (full, "val") not in seen:
                    seen.add((full, "val"))
                    out.append(Diagnostic(
                        "M007", f"missing assignment {full} ({mty.primitive}): the model is not complete",
                        local_anchor, Severity.ERROR, file=unit.path,
                        help=f"give it a value, e.g. '{name}: ...' (declared without a default in {mem.owner.qname})"))
                continue
            if mem.value is not None:
                continue  # given an existing object or a computed value
            sub = {p[1:] for p in assigned if len(p) > 1 and p[0] == name}
            visit(mty, sub, full, local_anchor, depth + 1, chain + (id(model),))

    anchor = root.stmt.path.span if isinstance(root.stmt, ast.Declaration) else root.stmt.header
    visit(Ty(root), set(), "", anchor, 0, ())
    return out
