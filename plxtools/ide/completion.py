"""Completion on whole and half-typed lines.

The context comes from the raw text of the line up to the cursor (a half-typed line is often an
`ErrorStmt`) and from the block structure above it (`owners_for_line`), never from the line's own
parse. Contexts:

- a type after `is` / `becomes` / `or` / `with` / `->` / a parameter's `:`, narrowed by a
  qualifier (`Physics3D.Geometries.`);
- a statement start in a block: the attributes of the object being configured that the block does
  not set yet (and after `inertia.` the attributes of `inertia`);
- a value after `:`: `true`/`false`, attributes of the outer model, const models and globals whose
  type fits; after `a.b.` the members and methods.
"""

from __future__ import annotations


from plxtools.ide.context import (
    UNKNOWN,
    BlockContext,
    MethodRef,
    TypeObj,
    block_context,
    chain_before,
    eval_chain,
    line_indent,
    owners_for_line,
    path_members,
    path_type,
)
from plxtools.ide.describe import describe, expr_text, signature
from plxtools.ide.host import FileState
from plxtools.ide.line_context import TYPE_KINDS, LineContext, classify, space_triggers, word_before
from plxtools.ide.types import CompletionItem, CompletionResult
from plxtools.model.symbols import PRIMITIVES, GlobalSym, MemberSym, MethodSym, ModelSym, Namespace, Ty
from plxtools.model.values import NsRef
from plxtools.syntax import ast
from plxtools.syntax.fragments import dotted_name, ends_in_comment_or_string, fragment_tokens

TOP_KEYWORDS = ["const", "trait", "operator", "import"]
BLOCK_KEYWORDS = ["with", "optional", "fn", "static fn"]

RANK_BEST, RANK_GOOD, RANK_OK, RANK_REST, RANK_KEYWORD = "0", "1", "2", "3", "4"


def complete(st: FileState, offset: int, trigger: str | None = None) -> CompletionResult:
    """Completion items at an offset. `trigger` is the character that made the editor ask, if any:
    a space only asks where a type or a value starts (after `is `, `becomes `, `with `, `: `...)."""
    idx = st.tree.index
    pos = idx.pos(offset)
    line = idx.line_text(pos.line)
    return complete_line(st, pos.line, line, pos.column, offset - pos.column, trigger, pos.line, offset)


def complete_line(st: FileState, line_no: int, line: str, column: int, line_start: int, trigger: str | None,
                  own_line: int, tree_offset: int) -> CompletionResult:
    """Completion on line `line_no` whose current text is `line` (the cursor at `column`, the line
    starting at offset `line_start` of the current text), against the analysis `st`.

    `st` may be of an older version of the buffer that differs only on this line (host.line_view):
    everything above the line is the same, so the blocks it belongs to are too. `own_line` is the
    line of `st`'s tree that the cursor's line replaces (-1: none, the line is new) and
    `tree_offset` a place on it in `st`'s text."""
    before = line[:column]
    word = word_before(before)
    start = line_start + column - len(word)
    j = column
    while j < len(line) and (line[j].isalnum() or line[j] == "_"):
        j += 1
    end = line_start + j
    empty = CompletionResult([], start, end)
    if trigger == " " and not space_triggers(before):
        return empty
    if st.program is None or st.unit is None or _in_comment_or_string(st, before, tree_offset):
        return empty
    head = before[: len(before) - len(word)]
    items = _dispatch(st, line_no, line, head, own_line)
    if items is None:
        return empty
    seen: set[str] = set()
    out = []
    for it in items:
        if it.label in seen:
            continue
        seen.add(it.label)
        out.append(it)
    return CompletionResult(out, start, end)


def _in_comment_or_string(st: FileState, before: str, offset: int) -> bool:
    if ends_in_comment_or_string(before):
        return True  # after a '#' or inside an open "..."
    for s in st.tree.statements:
        if s.span.start.offset <= offset <= s.span.end.offset:
            for d in ast.walk_statements([s]):
                v = getattr(d, "value", None)
                if (isinstance(v, ast.String) and v.kind == "triple"
                        and v.span.start.offset < offset < v.span.end.offset):
                    return True
            break
    return False


def _dispatch(st: FileState, line_no: int, line: str, head: str, own_line: int):
    lc = classify(head)
    if lc is None:
        return None
    if lc.kind in TYPE_KINDS:
        return _type_items(st, line_no, line, lc)
    if lc.kind == "annotation":
        names = sorted(st.known_annotations or {"doc"})
        return [CompletionItem(n, "keyword", "annotation", insert_text=f"{n}: ",
                               sort_text=(RANK_BEST if n == "doc" else RANK_GOOD) + n) for n in names]
    if lc.kind == "value":
        return _value_items(st, line_no, line, lc, head)
    return _statement_items(st, line_no, lc.indent, lc.qual, own_line)


# ------------------------------------------------------------------ blocks


def _context(st: FileState, line_no: int, indent: int) -> tuple[list[ast.Stmt], BlockContext]:
    owners = owners_for_line(st.tree, line_no, indent)
    return owners, block_context(st, owners)


def _qualifier(q: str) -> list[str]:
    return [p.strip("`") for p in q.split(".") if p]


def _statement_items(st: FileState, line_no: int, indent_text: str, qual: str, own_line: int):
    indent = len(indent_text.expandtabs(4))
    owners, ctx = _context(st, line_no, indent)
    if not owners:
        if qual:
            return []
        return [CompletionItem(k, "keyword", sort_text=RANK_KEYWORD + k) for k in TOP_KEYWORDS]
    parts = _qualifier(qual)
    if parts:
        ty, _mem = path_type(st, ctx, parts)
        if ty.unknown:
            return []
        mems = path_members(st, ctx, ty, ctx.prefix + tuple(parts))
        return [_attribute_item(st, m, ctx.outer, set_names=set(), rank=RANK_GOOD) for m in mems.values()]
    if ctx.ty.unknown:
        return [CompletionItem(k, "keyword", sort_text=RANK_KEYWORD + k) for k in BLOCK_KEYWORDS]
    mems = path_members(st, ctx, ctx.ty, ctx.prefix)
    already = _names_set_in_block(owners[-1], own_line)
    items = []
    for mem in mems.values():
        if mem.name in already:
            continue
        items.append(_attribute_item(st, mem, ctx.outer, already, None, insert_value=True))
    items += [CompletionItem(k, "keyword", sort_text=RANK_KEYWORD + k) for k in BLOCK_KEYWORDS]
    return items


def _names_set_in_block(owner: ast.Stmt, line_no: int) -> set[str]:
    out = set()
    for s in ast.body_of(owner) or ():
        if s.header.start.line == line_no:
            continue
        if isinstance(s, (ast.Declaration, ast.Assignment)) and s.path.parts and len(s.path.parts) == 1:
            out.add(s.path.parts[0].name)
    return out


def _required(p, mem: MemberSym) -> bool:
    if mem.optional or mem.value is not None:
        return False
    ty = p.member_type(mem)
    return mem.reference or (ty.primitive in ("Real", "Int", "Bool", "String") and not ty.array)


def _attribute_item(st: FileState, mem: MemberSym, outer, set_names, rank=None, insert_value=False) -> CompletionItem:
    p = st.program
    ty = p.member_type(mem)
    owner = p.concrete(mem.owner) if mem.owner.anonymous else mem.owner
    default = expr_text(mem.value, mem.owner.unit) if mem.value is not None else ""
    detail = ty.display() + (f" = {default}" if default else "")
    if mem.optional:
        detail += " (optional)"
    if rank is None:
        if _required(p, mem):
            rank = RANK_BEST
        elif owner.unit is not None and not owner.unit.official:
            rank = RANK_GOOD
        else:
            rank = RANK_OK
    insert = None
    if insert_value and (ty.primitive is not None or ty.array or mem.reference or ty.unknown):
        insert = f"{mem.name}: "
    deprecated = bool(mem.owner.deprecated.get(mem.name))
    return CompletionItem(mem.name, "attribute", detail, None, insert, sort_text=rank + mem.name,
                          key=("member", mem, outer), label_detail=f" {ty.display()}",
                          label_description=owner.name + (" · required" if rank == RANK_BEST else ""),
                          deprecated=deprecated)


# ------------------------------------------------------------------ types


def _type_items(st: FileState, line_no: int, line: str, lc: LineContext):
    p = st.program
    kind = lc.kind
    parts = _qualifier(lc.qual)
    want = {"with": "trait", "trait_base": "trait"}.get(kind, "any")
    top_level = kind == "is" and not lc.indent
    if kind == "is" and top_level:
        want = "model"
    subtype_of = None
    if kind == "becomes":
        indent = line_indent(line)
        owners, ctx = _context(st, line_no, indent)
        old, _mem = path_type(st, ctx, _qualifier(lc.target + "."))
        if old.model is not None and not old.array:
            subtype_of = p.concrete(old.model)
    prims = kind in ("is", "or", "param", "operator_param", "returns") and not parts
    if parts:
        scope = p.lookup(parts, st.unit)
        if not isinstance(scope, Namespace):
            return []
        return _namespace_type_items(st, scope, want, subtype_of, qualify=False)
    items: list[CompletionItem] = []
    if prims:
        for name in sorted(PRIMITIVES - {"BundleConfig"}):
            items.append(CompletionItem(name, "type", "primitive type", sort_text=RANK_GOOD + name,
                                        key=("primitive", name)))
    # names visible without a qualifier: this file's (or namespace chain's) symbols, then bundles
    for sym in _local_symbols(st):
        if isinstance(sym, ModelSym) and _type_fits(p, sym, want, subtype_of):
            items.append(_model_item(st, sym, sym.name, RANK_BEST))
    if subtype_of is not None:
        # the useful answers for `becomes`: every subtype, fully qualified
        for sym in _all_models(p):
            if sym.unit is not None and _visible(st, sym) and _type_fits(p, sym, want, subtype_of):
                items.append(_model_item(st, sym, sym.qname, RANK_GOOD))
    for ns in _visible_roots(st):
        if _ns_has(p, ns, want, subtype_of):
            items.append(_ns_item(ns, RANK_OK))
    return items


def _namespace_type_items(st: FileState, ns: Namespace, want: str, subtype_of, qualify: bool):
    p = st.program
    items = []
    for name, sym in ns.symbols.items():
        if isinstance(sym, ModelSym) and _type_fits(p, sym, want, subtype_of):
            items.append(_model_item(st, sym, name, RANK_BEST))
    for name, child in ns.children.items():
        if _ns_has(p, child, want, subtype_of):
            items.append(_ns_item(child, RANK_GOOD))
    return items


def _type_fits(p, sym: ModelSym, want: str, subtype_of) -> bool:
    if want == "trait" and not sym.is_trait:
        return False
    if want == "model" and sym.is_trait:
        return False
    if subtype_of is not None:
        return sym is not subtype_of and not sym.is_trait and p.is_subtype(sym, subtype_of)
    return True


_NS_CACHE: dict[tuple, bool] = {}


def _ns_has(p, ns: Namespace, want: str, subtype_of) -> bool:
    key = (id(p), id(ns), want, id(subtype_of) if subtype_of is not None else None, len(ns.symbols))
    got = _NS_CACHE.get(key)
    if got is None:
        got = False
        stack = [ns]
        while stack and not got:
            cur = stack.pop()
            for sym in cur.symbols.values():
                if isinstance(sym, ModelSym) and _type_fits(p, sym, want, subtype_of):
                    got = True
                    break
            stack.extend(cur.children.values())
        if len(_NS_CACHE) > 4096:
            _NS_CACHE.clear()
        _NS_CACHE[key] = got
    return got


def _all_models(p):
    stack = [p.root]
    while stack:
        ns = stack.pop()
        for sym in ns.symbols.values():
            if isinstance(sym, ModelSym):
                yield sym
        stack.extend(ns.children.values())


def _visible(st: FileState, sym) -> bool:
    vis = st.program.visible(st.unit)
    ns = getattr(sym, "namespace", None)
    if vis is None or ns is None or not ns.qname:
        return True
    return ns.qname[0] in vis


def _local_symbols(st: FileState):
    unit = st.unit
    if unit.bundle is None:
        yield from unit.locals.values()
        return
    ns = unit.namespace
    seen = set()
    while ns is not None and ns.qname:
        for name, sym in ns.symbols.items():
            if name not in seen:
                seen.add(name)
                yield sym
        ns = ns.parent


def _visible_roots(st: FileState) -> list[Namespace]:
    p = st.program
    vis = p.visible(st.unit)
    out = [ns for name, ns in sorted(p.root.children.items()) if vis is None or name in vis]
    if st.unit.bundle is not None:
        # namespaces of the file's own bundle are reachable relative to its namespace chain
        ns = st.unit.namespace
        while ns is not None and ns.qname:
            out.extend(c for c in ns.children.values() if c not in out)
            ns = ns.parent
    return out


def _model_item(st: FileState, sym: ModelSym, label: str, rank: str) -> CompletionItem:
    kind = "trait" if sym.is_trait else ("constant" if sym.const else "model")
    doc_first = (sym.doc or "").strip().split("\n", 1)[0][:80]
    return CompletionItem(label, kind, sym.qname, None, sort_text=rank + label,
                          key=("symbol", sym), label_description=doc_first or None)


def _ns_item(ns: Namespace, rank: str) -> CompletionItem:
    return CompletionItem(ns.name, "namespace", f"namespace {ns.dotted}", None, sort_text=rank + ns.name,
                          key=("symbol", ns))


# ------------------------------------------------------------------ values


def _value_items(st: FileState, line_no: int, line: str, lc: LineContext, head: str):
    p = st.program
    indent = line_indent(line)
    owners, ctx = _context(st, line_no, indent)
    value_text = lc.value
    # after a dot: members of whatever the chain before it is
    if value_text.rstrip().endswith(".") and value_text.strip() != ".":
        chain = chain_before(head, len(head) - 1)
        if not chain:
            return []
        outer = ctx.outer
        base = eval_chain(st, outer, chain)
        return _member_items(st, base, _expected_type(st, ctx, lc, value_text))
    expected = _expected_type(st, ctx, lc, value_text)
    items: list[CompletionItem] = []
    outer = ctx.outer
    if expected.primitive == "Bool" and not expected.array:
        items += [CompletionItem(v, "value", "Bool", sort_text=RANK_BEST + v) for v in ("true", "false")]
    else:
        items += [CompletionItem(v, "value", "Bool", sort_text=RANK_REST + v) for v in ("true", "false")]
    if outer is not None:
        items.append(CompletionItem("this", "value", outer.qname, sort_text=RANK_REST + "this"))
        items += _own_member_items(st, outer, expected)
        items += _nested_fits(st, outer, expected)
    # globals and const models in scope, and const-model members that fit (enum-like tables)
    for sym in _local_symbols(st):
        items.extend(_global_items(st, sym, sym.name, expected))
    for sym in _all_models(p):
        if sym.const and sym.unit is not None and sym.unit is not st.unit and _visible(st, sym):
            if _fits(p, Ty(sym), expected) == "exact":
                items.append(_model_item(st, sym, sym.qname, RANK_GOOD))
            elif expected.primitive in ("Int", "Real", "String") and not expected.array and \
                    sym.namespace is not None and _near(st, sym):
                for mem in p.all_members(sym).values():
                    if _fits(p, p.member_type(mem), expected) == "exact":
                        label = f"{sym.qname}.{mem.name}"
                        items.append(CompletionItem(label, "constant", p.member_type(mem).display(),
                                                    sort_text=RANK_OK + label, key=("member", mem, sym)))
    for ns in _visible_roots(st):
        items.append(_ns_item(ns, RANK_REST))
    return items


def _own_member_items(st: FileState, outer: ModelSym, expected: Ty) -> list[CompletionItem]:
    """The enclosing model's attributes, those that fit first; none that cannot lead to a fit."""
    p = st.program
    items = []
    for mem in p.all_members(outer).values():
        ty = p.member_type(mem)
        fits = _fits(p, ty, expected)
        if fits == "no" and not _leads_to(p, ty, expected):
            continue  # a Vec3 or a signal where a connector is wanted: nothing in it fits either
        items.append(_attribute_item(st, mem, outer, set(), RANK_BEST if fits == "exact" else RANK_OK))
    return items


def _nested_fits(st: FileState, outer: ModelSym, expected: Ty) -> list[CompletionItem]:
    """`chassis.left_hub` for a connector: an attribute's attribute whose type fits a model type that
    is expected (the connectors of a joint sit on the bodies it joins), ranked first."""
    p = st.program
    if expected.unknown or expected.model is None or expected.array:
        return []
    out = []
    for mem in p.all_members(outer).values():
        ty = p.member_type(mem)
        if ty.unknown or ty.model is None or ty.array or ty.alts:
            continue
        for sub in p.members_of(ty).values():
            if _fits(p, p.member_type(sub), expected) == "exact":
                label = f"{mem.name}.{sub.name}"
                out.append(CompletionItem(label, "attribute", p.member_type(sub).display(), None,
                                          sort_text=RANK_BEST + label, key=("member", sub, None)))
    return out


def _leads_to(p, ty: Ty, expected: Ty, depth: int = 2) -> bool:
    """Whether something that fits a model-typed `expected` is `ty` or one of its attributes, `depth`
    levels down (`chassis.hub`); always True for a primitive or unknown expectation (`a.x * 2`
    reaches a Real from anything), so only model-typed slots are narrowed."""
    if expected.unknown or expected.model is None or ty.unknown:
        return True
    if _fits(p, ty, expected) != "no":
        return True
    if expected.array and _leads_to(p, ty, expected.element(), depth):
        return True  # `connectors: ` before its `[`: what goes inside counts
    if depth == 0 or ty.model is None or ty.array or ty.alts:
        return False
    return any(_leads_to(p, p.member_type(sub), expected, depth - 1) for sub in p.members_of(ty).values())


def _near(st: FileState, sym: ModelSym) -> bool:
    """Const tables from the file's own bundle (or, for loose files, the file itself)."""
    return st.unit.bundle is not None and sym.unit is not None and sym.unit.bundle == st.unit.bundle


def _fits(p, ty: Ty, expected: Ty) -> str:
    if expected.unknown or ty.unknown:
        return "unknown"
    return "exact" if p.assignable(ty, expected) == "ok" else "no"


def _global_items(st: FileState, sym, label: str, expected: Ty):
    p = st.program
    if isinstance(sym, GlobalSym):
        ty = sym.ty or p.resolve_type_expr(sym.stmt.type, sym.unit)
        rank = RANK_BEST if _fits(p, ty, expected) == "exact" else RANK_OK
        return [CompletionItem(label, "constant", ty.display(), sort_text=rank + label, key=("symbol", sym))]
    if isinstance(sym, ModelSym):
        if sym.const:
            rank = RANK_BEST if _fits(p, Ty(sym), expected) == "exact" else RANK_OK
            return [_model_item(st, sym, label, rank)]
        if p.all_methods(sym) and any(mm.static for mm in p.all_methods(sym).values()):
            return [_model_item(st, sym, label, RANK_REST)]
    return []


def _expected_type(st: FileState, ctx: BlockContext, lc: LineContext, value_text: str) -> Ty:
    p = st.program
    path = _qualifier(lc.target + ".")
    decl = fragment_tokens(lc.decl)
    if decl and decl[0].type in ("IS", "BECOMES"):
        # `is T[] with A`: the declared type's name, from the lexer's tokens
        names, after = dotted_name(decl, 1)
        arr = after + 1 < len(decl) and decl[after].type == "LSQB" and decl[after + 1].type == "RSQB"
        found = p.lookup(names, st.unit) if names else None
        ty = Ty(found, arr) if isinstance(found, (ModelSym, str)) else UNKNOWN
    else:
        ty, _mem = path_type(st, ctx, path)
    # inside brackets: the element, or the field of a {...} literal
    opened = _open_brackets(value_text)
    for br, commas in opened:
        if ty.unknown:
            break
        if br == "[":
            ty = ty.element() if ty.array else UNKNOWN
        elif br == "{":
            fields = p.positional_fields(ty.model) if ty.model is not None and not ty.array else None
            ty = p.member_type(fields[commas]) if fields and commas < len(fields) else UNKNOWN
        else:
            ty = UNKNOWN
    return ty


def _open_brackets(s: str) -> list[tuple[str, int]]:
    stack: list[list] = []
    in_str = False
    for ch in s:
        if ch == '"':
            in_str = not in_str
        elif in_str:
            continue
        elif ch in "([{":
            stack.append([ch, 0])
        elif ch in ")]}":
            if stack:
                stack.pop()
        elif ch == "," and stack:
            stack[-1][1] += 1
    return [(b, c) for b, c in stack]


def _member_items(st: FileState, base, expected: Ty = UNKNOWN) -> list[CompletionItem]:
    """After `a.b.`: what the chain's value holds; where the slot wants a model type (a joint's
    `connectors: [a.`), what fits it first and what cannot lead to it left out."""
    p = st.program
    items: list[CompletionItem] = []
    if isinstance(base, NsRef):
        base = base.ns
    if isinstance(base, Namespace):
        for name, sym in sorted(base.symbols.items()):
            if isinstance(sym, GlobalSym):
                items.extend(_global_items(st, sym, name, UNKNOWN))
            elif isinstance(sym, ModelSym):
                items.append(_model_item(st, sym, name, RANK_GOOD if sym.const else RANK_OK))
        for name, child in sorted(base.children.items()):
            items.append(_ns_item(child, RANK_REST))
        return items
    if isinstance(base, TypeObj) and isinstance(base.sym, ModelSym):
        for meth in p.all_methods(base.sym).values():
            if meth.static:
                items.append(_method_item(meth, RANK_BEST))
        return items
    if isinstance(base, Ty) and base.model is not None and not base.array and not base.alts:
        items += _value_member_items(st, base, expected)
        const = base.model.const
        for meth in p.methods_of(base).values():
            if meth.stmt.returns is None:
                continue  # cannot be used in an expression
            if meth.static and not const:
                continue
            items.append(_method_item(meth, RANK_GOOD))
        return items
    if isinstance(base, MethodRef):
        return []
    return items


def _value_member_items(st: FileState, base: Ty, expected: Ty) -> list[CompletionItem]:
    """The attributes of a value after its dot; for a model-typed slot, what fits it first."""
    p = st.program
    narrowed = not expected.unknown and expected.model is not None
    items = []
    for mem in p.members_of(base).values():
        ty = p.member_type(mem)
        if narrowed and not _leads_to(p, ty, expected):
            continue
        fits = narrowed and _fits(p, ty, expected) == "exact"
        items.append(_attribute_item(st, mem, None, set(), RANK_BEST if fits or not narrowed else RANK_GOOD))
    return items


def _method_item(meth: MethodSym, rank: str) -> CompletionItem:
    ret = meth.stmt.returns.name.text if meth.stmt.returns is not None else ""
    return CompletionItem(meth.name, "method", signature(meth), None, insert_text=None,
                          sort_text=rank + meth.name, key=("symbol", meth), label_detail="(…)",
                          label_description=ret or None)


# ------------------------------------------------------------------ documentation on resolve


def completion_documentation(program, key) -> str | None:
    if not key:
        return None
    kind = key[0]
    if kind == "member":
        _k, mem, outer = key
        return describe(program, mem, outer if isinstance(outer, ModelSym) else None)
    if kind == "symbol":
        return describe(program, key[1])
    if kind == "primitive":
        return describe(program, key[1])
    return None
