"""Where is the cursor? Statements around an offset, the type a block configures, names under the cursor.

These helpers turn a position in a (possibly half-typed) file into semantic facts, using the
checker's recorded occurrences where it resolved a name and the program's lookups elsewhere.
"""

from __future__ import annotations

from dataclasses import dataclass

from plxtools.diagnostics import Pos, Span
from plxtools.ide.host import FileState
from plxtools.model import resolve
from plxtools.model.symbols import (
    PRIMITIVES,
    UNKNOWN,
    MemberSym,
    ModelSym,
    Ty,
)
from plxtools.model.values import MethodRef, TypeObj
from plxtools.syntax import ast
from plxtools.syntax.fragments import dotted_name, fragment_tokens, matching_close

# ------------------------------------------------------------------ statements


def statement_chain(tree: ast.File, offset: int) -> list[ast.Stmt]:
    """Statements whose span holds the offset, outermost first."""
    chain: list[ast.Stmt] = []
    body = tree.statements
    while body:
        found = None
        for s in body:
            if s.span.start.offset <= offset <= s.span.end.offset:
                found = s
                # a later sibling starting at this offset wins (a header right after a block end)
        if found is None:
            break
        chain.append(found)
        body = ast.body_of(found) or []
    return chain


def header_at(tree: ast.File, offset: int) -> tuple[list[ast.Stmt], ast.Stmt | None]:
    """The enclosing block owners and the statement whose header holds the offset (if any)."""
    chain = statement_chain(tree, offset)
    for i, s in enumerate(chain):
        if s.header.start.offset <= offset <= s.header.end.offset:
            return chain[:i], s
    return chain, None


def owners_for_line(tree: ast.File, line: int, indent: int) -> list[ast.Stmt]:
    """The block owners a line at this indentation belongs to (for blank or half-typed lines).

    A line belongs to the innermost statement before it whose header is indented less and whose
    block (or its `:`) reaches down to it.
    """
    chain: list[ast.Stmt] = []
    body = tree.statements
    while body:
        last = None
        for s in body:
            if s.header.start.line < line:
                last = s
            else:
                break
        if last is None or last.header.start.column >= indent:
            break
        opens = ast.body_of(last) is not None or _ends_with_colon(tree, last)
        if not opens:
            break
        chain.append(last)
        body = ast.body_of(last) or []
    return chain


def _ends_with_colon(tree: ast.File, s: ast.Stmt) -> bool:
    toks = fragment_tokens(tree.text[s.header.start.offset:s.header.end.offset])
    return bool(toks) and toks[-1].type == "COLON"


def line_indent(line_text: str) -> int:
    return len(line_text) - len(line_text.lstrip(" \t"))


# ------------------------------------------------------------------ occurrences by span


def occ_at_span(st: FileState, span: Span, kinds: tuple[str, ...] | None = None) -> list:
    """Occurrences recorded exactly at a span."""
    cache = st._by_start
    if cache is None:
        cache = {}
        for o in st.occurrences:
            cache.setdefault(o.span.start.offset, []).append(o)
        st._by_start = cache
    return [o for o in cache.get(span.start.offset, ()) if o.span.end.offset == span.end.offset
            and (kinds is None or o.kind in kinds)]


# ------------------------------------------------------------------ the type a block configures


@dataclass(slots=True)
class BlockContext:
    """What the lines of a block configure."""

    ty: Ty  # the object's type (maybe an anonymous instance subtype)
    model_def: ModelSym | None  # the model or instance type being defined, when the block defines one
    outer: ModelSym | None  # the top-level model (the scope of names in expressions)
    prefix: tuple[str, ...] = ()  # path from the outer model to this object


def symbol_of_top(st: FileState, stmt: ast.Stmt):
    return resolve.symbol_of_top(st.unit, stmt) if st.unit is not None else None


def member_of_stmt(st: FileState, stmt: ast.Stmt) -> MemberSym | None:
    """The attribute a member statement declares or sets, as the checker resolved it."""
    if isinstance(stmt, (ast.Declaration, ast.Assignment)) and stmt.path.parts:
        kinds = ("definition",) if isinstance(stmt, ast.Declaration) else ("attribute",)
        for o in occ_at_span(st, stmt.path.parts[-1].span, kinds):
            if isinstance(o.target, MemberSym):
                return o.target
        if isinstance(stmt, ast.Declaration):
            for o in occ_at_span(st, stmt.path.parts[-1].span, ("attribute",)):
                if isinstance(o.target, MemberSym):
                    return o.target
    return None


def block_context(st: FileState, owners: list[ast.Stmt]) -> BlockContext:
    """The object configured by the innermost of `owners` (outermost first)."""
    p = _program(st)
    if not owners or p is None or st.unit is None:
        return BlockContext(UNKNOWN, None, None)
    top = owners[0]
    sym = symbol_of_top(st, top)
    outer = sym if isinstance(sym, ModelSym) else None
    if isinstance(sym, ModelSym):
        ctx = BlockContext(Ty(sym), sym, outer, ())
    elif isinstance(top, ast.ErrorStmt):
        ty = _guess_error_type(st, top, BlockContext(UNKNOWN, None, None))
        outer = ty.model
        ctx = BlockContext(ty, None, outer, ())
    else:
        return BlockContext(UNKNOWN, None, None)
    for s in owners[1:]:
        ctx = _child_context(st, ctx, s)
    return ctx


def _program(st: FileState):
    return st.program


def _child_context(st: FileState, ctx: BlockContext, s: ast.Stmt) -> BlockContext:
    p = _program(st)
    if isinstance(s, ast.Declaration):
        mem = member_of_stmt(st, s) or resolve.declared_member(ctx.model_def, s)
        prefix = ctx.prefix + tuple(x.name for x in s.path.parts)
        if mem is not None and mem.stmt is s:
            ty = p.member_type(mem)
            return BlockContext(ty, mem.anon, ctx.outer, prefix)
        ty = p.resolve_type_expr(s.type, st.unit) if s.type is not None else UNKNOWN
        return BlockContext(ty, None, ctx.outer, prefix)
    if isinstance(s, ast.Assignment):
        ty = path_type(st, ctx, [x.name for x in s.path.parts])[0]
        return BlockContext(ty, None, ctx.outer, ctx.prefix + tuple(x.name for x in s.path.parts))
    if isinstance(s, ast.ErrorStmt):
        return BlockContext(_guess_error_type(st, s, ctx), None, ctx.outer, ctx.prefix)
    return BlockContext(UNKNOWN, None, ctx.outer, ctx.prefix)


def _guess_error_type(st: FileState, s: ast.ErrorStmt, ctx: BlockContext) -> Ty:
    """A header that did not parse still says what it configures often enough: `x is T...`, `x:`."""
    p = _program(st)
    toks = fragment_tokens(s.text.split("\n", 1)[0])
    i = 0
    while i < len(toks) and toks[i].type in ("CONST", "OPTIONAL"):
        i += 1
    path, i = dotted_name(toks, i)
    if not path or i >= len(toks):
        return UNKNOWN
    if toks[i].type in ("IS", "BECOMES"):
        type_path, _ = dotted_name(toks, i + 1)
        if not type_path:
            return UNKNOWN
        found = p.lookup(type_path, st.unit)
        if isinstance(found, (ModelSym, str)):
            return Ty(found)
        if toks[i].type == "BECOMES" or not found:
            return path_type(st, ctx, path)[0]
        return UNKNOWN
    if toks[i].type == "COLON":
        return path_type(st, ctx, path)[0]
    return UNKNOWN


def path_members(st: FileState, ctx: BlockContext, ty: Ty, prefix: tuple[str, ...]) -> dict[str, MemberSym]:
    """Attributes reachable on an object: its type's, plus dotted declarations made for this path."""
    return resolve.attributes(_program(st), ty, ctx.outer, prefix)


def path_type(st: FileState, ctx: BlockContext, parts: list[str]) -> tuple[Ty, MemberSym | None]:
    return resolve.path_target(_program(st), ctx.ty, ctx.outer, ctx.prefix, parts)


# ------------------------------------------------------------------ expressions


def name_value(st: FileState, outer: ModelSym | None, name: str):
    """What a bare name means in an expression (model/resolve.py decides)."""
    p = _program(st)
    return resolve.meaning(p, resolve.name_target(p, st.unit, outer, name))


def member_value(st: FileState, base, name: str):
    p = _program(st)
    return resolve.meaning(p, resolve.member_target(p, base, name))


def call_value(st: FileState, f):
    return resolve.call_result(_program(st), f)


def chain_before(text: str, end: int) -> str | None:
    """The postfix chain (`a.b(c).d[0].`) that ends at `end`, or None if there is none."""
    i = end
    depth = 0
    while i > 0:
        ch = text[i - 1]
        if depth:
            if ch in ")]":
                depth += 1
            elif ch in "([":
                depth -= 1
            elif ch == "\n":
                return None
            i -= 1
            continue
        if ch.isalnum() or ch in "_.`":
            i -= 1
        elif ch in ")]":
            depth += 1
            i -= 1
        else:
            break
    chain = text[i:end]
    return chain or None


def eval_chain(st: FileState, outer: ModelSym | None, chain: str):
    """Type a postfix chain of names, member accesses, calls and indexes (without the last `.x`)."""
    toks = fragment_tokens(chain)
    if not toks or toks[0].type not in ("NAME", "TICKNAME", "THIS"):
        return None
    if toks[0].type == "THIS":
        cur = Ty(outer) if outer is not None else None
    else:
        cur = name_value(st, outer, str(toks[0]))
    k = 1
    while k < len(toks) and cur is not None:
        kind = toks[k].type
        if kind == "DOT":
            if k + 1 >= len(toks) or toks[k + 1].type not in ("NAME", "TICKNAME"):
                return None
            cur = member_value(st, cur, str(toks[k + 1]))
            k += 2
        elif kind in ("LPAR", "LSQB"):
            close = matching_close(toks, k)
            if close < 0:
                return None
            if kind == "LPAR":
                cur = call_value(st, cur)
            else:
                cur = cur.element() if isinstance(cur, Ty) and cur.array else None
            k = close + 1
        else:
            return None
    return cur


# ------------------------------------------------------------------ names under the cursor


@dataclass(slots=True)
class Resolved:
    target: object  # ModelSym | MemberSym | GlobalSym | MethodSym | Namespace | str (primitive)
    span: Span  # the name under the cursor
    kind: str  # the occurrence kind: "definition" | "type" | "attribute" | "name"
    also: list  # other targets recorded at the same place (e.g. the attribute a `becomes` specialises)


def qname_parts(text: str, span: Span) -> list[tuple[str, int, int]]:
    """The parts of a dotted name in the text, with their offsets."""
    out = []
    s = text[span.start.offset:span.end.offset]
    i = 0
    base = span.start.offset
    while i < len(s):
        if s[i] == "`":
            j = s.find("`", i + 1)
            j = len(s) - 1 if j < 0 else j
            out.append((s[i + 1:j], base + i, base + j + 1))
            i = j + 1
        elif s[i].isalnum() or s[i] == "_":
            j = i
            while j < len(s) and (s[j].isalnum() or s[j] == "_"):
                j += 1
            out.append((s[i:j], base + i, base + j))
            i = j
        else:
            i += 1
    return out


def span_in(st: FileState, start: int, end: int) -> Span:
    idx = st.tree.index
    return Span(idx.pos(start), idx.pos(end))


def resolve_at(st: FileState, offset: int) -> Resolved | None:
    """The symbol named at an offset (a name's end counts as on the name)."""
    hits = st.occurrences_at(offset)
    if not hits:
        return _primitive_at(st, offset)
    best = hits[0]
    also = [o.target for o in hits[1:] if o.span == best.span and o.target is not best.target]
    span = best.span
    target = best.target
    # a dotted type name is recorded once; narrow it to the part under the cursor
    if best.kind in ("type", "definition") and span.end.offset - span.start.offset > 0:
        parts = qname_parts(st.text, span)
        if len(parts) > 1:
            p = _program(st)
            for k, (_name, a, b) in enumerate(parts):
                if a <= offset <= b:
                    span = span_in(st, a, b)
                    if k < len(parts) - 1:
                        found = p.lookup([x[0] for x in parts[: k + 1]], st.unit)
                        if found is not None:
                            target = found
                            also = []
                    break
    return Resolved(target, span, best.kind, also)


def _primitive_at(st: FileState, offset: int) -> Resolved | None:
    """Primitive type names are not recorded as occurrences; find them in the header's types."""
    _owners, stmt = header_at(st.tree, offset)
    if stmt is None:
        return None
    refs = []
    t = getattr(stmt, "type", None)
    if isinstance(t, ast.TypeExpr):
        refs.extend(t.alternatives)
    if isinstance(stmt, (ast.Method, ast.OperatorDecl)):
        refs.extend(p.type for p in stmt.params)
        if stmt.returns is not None:
            refs.append(stmt.returns)
    for ref in refs:
        sp = ref.name.span
        if sp.start.offset <= offset <= sp.end.offset and ref.name.text in PRIMITIVES:
            return Resolved(ref.name.text, sp, "type", [])
    return None


def word_at(text: str, offset: int) -> tuple[int, int]:
    """The identifier around an offset (start, end); empty when the offset is not on one."""
    a = offset
    while a > 0 and (text[a - 1].isalnum() or text[a - 1] == "_"):
        a -= 1
    b = offset
    while b < len(text) and (text[b].isalnum() or text[b] == "_"):
        b += 1
    return a, b


def pos_of(st: FileState, offset: int) -> Pos:
    return st.tree.index.pos(offset)


PRIMITIVE_NAMES = sorted(PRIMITIVES - {"BundleConfig"})
