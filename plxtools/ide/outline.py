"""Document outline, workspace symbols, folding ranges and document links: structure, little semantics."""

from __future__ import annotations

import os

from plxtools.diagnostics import Span
from plxtools.ide.host import AnalysisHost
from plxtools.ide.types import DocumentLink, FoldingRange, SymbolInfo, WorkspaceSymbolInfo
from plxtools.model.symbols import GlobalSym, ModelSym
from plxtools.syntax import ast


def _type_text(t: ast.TypeExpr | None) -> str:
    if t is None:
        return ""
    s = " or ".join(r.name.text + ("[]" if r.array else "") for r in t.alternatives)
    if t.traits:
        s += " with " + ", ".join(q.text for q in t.traits)
    return s


def document_symbols(tree: ast.File) -> list[SymbolInfo]:
    return [s for s in (_symbol(stmt, top=True) for stmt in tree.statements) if s is not None]


def _symbol(stmt: ast.Stmt, top: bool) -> SymbolInfo | None:
    """The outline entry of a statement and its block, by statement kind (`_SYMBOL_KINDS`)."""
    children = []
    for child in ast.body_of(stmt) or ():
        sym = _symbol(child, top=False)
        if sym is not None:
            children.append(sym)
    make = _SYMBOL_KINDS.get(type(stmt))
    return make(stmt, top, children) if make is not None else None


def _trait_symbol(stmt: ast.TraitDef, top: bool, children: list) -> SymbolInfo:
    return SymbolInfo(stmt.name.name, "trait", stmt.span, stmt.name.span,
                      f"is {stmt.base.text}" if stmt.base else "", children)


def _declaration_kind(stmt: ast.Declaration, top: bool) -> str:
    if not top:
        return "attribute"
    if stmt.keyword == "is" and stmt.value is not None and stmt.body is None:
        return "global"
    return "const" if stmt.const else "model"


def _declaration_symbol(stmt: ast.Declaration, top: bool, children: list) -> SymbolInfo:
    detail = _type_text(stmt.type)
    if stmt.keyword == "becomes":
        detail = "becomes " + detail
    return SymbolInfo(stmt.path.text, _declaration_kind(stmt, top), stmt.span, stmt.path.span, detail, children)


def _method_symbol(stmt: ast.Method, top: bool, children: list) -> SymbolInfo:
    params = ", ".join(f"{p.name.name}: {p.type.name.text}" for p in stmt.params)
    ret = f" -> {stmt.returns.name.text}" if stmt.returns else ""
    return SymbolInfo(stmt.name.name, "method", stmt.span, stmt.name.span,
                      f"{'static ' if stmt.static else ''}fn ({params}){ret}")


def _operator_symbol(stmt: ast.OperatorDecl, top: bool, children: list) -> SymbolInfo:
    params = ", ".join(p.type.name.text for p in stmt.params)
    return SymbolInfo(f"operator {stmt.op}", "operator", stmt.span, stmt.header, f"({params})")


def _assignment_symbol(stmt: ast.Assignment, top: bool, children: list) -> SymbolInfo | None:
    if not stmt.body:
        return None
    return SymbolInfo(stmt.path.text, "block", stmt.span, stmt.path.span, "", children)


def _import_symbol(stmt: ast.Import, top: bool, children: list) -> SymbolInfo:
    name = stmt.alias.text if stmt.alias is not None else stmt.source.value
    return SymbolInfo(name, "import", stmt.span, stmt.header, stmt.source.raw)


def _error_symbol(stmt: ast.ErrorStmt, top: bool, children: list) -> SymbolInfo | None:
    if not children:
        return None
    return SymbolInfo(stmt.text.strip().split("\n")[0][:40] or "?", "block", stmt.span, stmt.header, "", children)


_SYMBOL_KINDS = {
    ast.TraitDef: _trait_symbol, ast.Declaration: _declaration_symbol, ast.Method: _method_symbol,
    ast.OperatorDecl: _operator_symbol, ast.Assignment: _assignment_symbol, ast.Import: _import_symbol,
    ast.ErrorStmt: _error_symbol,
}


def _matches(query: str, name: str) -> bool:
    """Case-insensitive subsequence match (`rbody` finds RigidBody)."""
    if not query:
        return True
    q = query.lower()
    n = name.lower()
    if q in n:
        return True
    i = 0
    for ch in n:
        if i < len(q) and ch == q[i]:
            i += 1
    return i == len(q)


def workspace_symbols(host: AnalysisHost, query: str, limit: int = 300) -> list[WorkspaceSymbolInfo]:
    p = host.program
    if p is None:
        return []
    out: list[tuple[int, WorkspaceSymbolInfo]] = []
    q = query.strip()
    # open buffers first (their own names, loose files included), then every namespace
    seen: set[int] = set()
    for path in list(host.docs):
        st = host.state(path)
        if st is None or st.unit is None:
            continue
        table = st.unit.locals if st.unit.bundle is None else st.unit.namespace.symbols
        for sym in table.values():
            if getattr(sym, "unit", None) is st.unit and _matches(q, sym.name):
                seen.add(id(sym))
                out.append((0, _ws_symbol(sym)))
    stack = [p.root]
    while stack:
        ns = stack.pop()
        for sym in ns.symbols.values():
            if id(sym) in seen or not _matches(q, sym.name):
                continue
            rank = 1 if sym.unit is not None and not sym.unit.official else 2
            out.append((rank, _ws_symbol(sym)))
        stack.extend(ns.children.values())
    ql = q.lower()
    out.sort(key=lambda r: (r[0], not r[1].name.lower().startswith(ql), len(r[1].name), r[1].name))
    return [w for _r, w in out[:limit]]


def _ws_symbol(sym) -> WorkspaceSymbolInfo:
    if isinstance(sym, ModelSym):
        kind = "trait" if sym.is_trait else ("const" if sym.const else "model")
        stmt = sym.stmt
        span = stmt.name.span if isinstance(stmt, ast.TraitDef) else stmt.path.span
    else:
        kind = "global"
        span = sym.stmt.path.span
    container = sym.namespace.dotted if sym.namespace is not None else ""
    assert isinstance(sym, (ModelSym, GlobalSym))
    return WorkspaceSymbolInfo(sym.name, kind, sym.unit.path, span, container)


# ------------------------------------------------------------------ folding


def folding_ranges(tree: ast.File) -> list[FoldingRange]:
    out: list[FoldingRange] = []
    for s in ast.walk_statements(tree.statements):
        a = s.header.start.line
        b = s.span.end.line
        if b > a:
            out.append(FoldingRange(a, b))
        elif s.header.end.line > a:
            out.append(FoldingRange(a, s.header.end.line))
    # runs of own-line comments
    run: list[int] = []
    for c in tree.comments:
        if not c.own_line:
            continue
        line = c.span.start.line
        if run and line == run[-1] + 1:
            run.append(line)
            continue
        if len(run) >= 2:
            out.append(FoldingRange(run[0], run[-1], "comment"))
        run = [line]
    if len(run) >= 2:
        out.append(FoldingRange(run[0], run[-1], "comment"))
    # multi-line strings that are not already a statement's whole range
    for s in ast.walk_statements(tree.statements):
        v = getattr(s, "value", None)
        if isinstance(v, ast.String) and v.span.end.line > v.span.start.line:
            if not any(f.start_line == v.span.start.line for f in out):
                out.append(FoldingRange(v.span.start.line, v.span.end.line))
    out.sort(key=lambda f: (f.start_line, f.end_line))
    return out


# ------------------------------------------------------------------ links


def iter_exprs(stmt: ast.Stmt):
    """Every expression node of one statement (not its block)."""
    roots = []
    for name in ("value", "source"):
        v = getattr(stmt, name, None)
        if isinstance(v, ast.Node):
            roots.append(v)
    stack = roots
    while stack:
        e = stack.pop()
        yield e
        for attr in ("obj", "func", "index", "operand", "left", "right", "inner"):
            v = getattr(e, attr, None)
            if isinstance(v, ast.Node) and not isinstance(v, ast.Ident):
                stack.append(v)
        for attr in ("args", "items"):
            v = getattr(e, attr, None)
            if isinstance(v, list):
                stack.extend(x for x in v if isinstance(x, ast.Node))


def document_links(tree: ast.File, path: str) -> list[DocumentLink]:
    """`@"..."` strings are paths relative to the file: link them (only for files on disk)."""
    if not os.path.isabs(path):
        return []
    folder = os.path.dirname(path)
    out = []
    for s in ast.walk_statements(tree.statements):
        for e in iter_exprs(s):
            if isinstance(e, ast.String) and e.kind == "path" and e.value:
                target = os.path.normpath(os.path.join(folder, e.value))
                exists = os.path.exists(target)
                tip = target if exists else f"{target} (does not exist)"
                # the link covers the text between the quotes
                start = e.span.start
                inner = Span(type(start)(start.offset + 2, start.line, start.column + 2),
                             type(start)(start.offset + 2 + len(e.value), start.line,
                                         start.column + 2 + len(e.value)))
                out.append(DocumentLink(inner, target, tip))
    return out
