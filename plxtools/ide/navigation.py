"""Go to definition / declaration / type definition, find references, rename."""

from __future__ import annotations

import os
import re

from plxtools.ide.context import resolve_at
from plxtools.ide.host import AnalysisHost, FileState
from plxtools.ide.types import FileSpan, NavTarget, RenameError, TextEdit
from plxtools.model import resolve
from plxtools.model.symbols import GlobalSym, MemberSym, MethodSym, ModelSym, Namespace
from plxtools.syntax import ast
from plxtools.diagnostics import EMPTY_SPAN, Span
from plxtools.syntax.lexer import KEYWORDS

IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


# ------------------------------------------------------------------ definitions


def target_of(program, sym) -> NavTarget | None:
    """Where a symbol is defined."""
    if isinstance(sym, ModelSym):
        if sym.anonymous:
            # an instance block: its declaration
            stmt = sym.stmt
            if isinstance(stmt, ast.Declaration) and sym.unit is not None:
                return NavTarget(sym.unit.path, stmt.path.parts[-1].span, stmt.span, sym.name)
            return None
        if sym.stmt is None or sym.unit is None:
            return None
        focus = sym.stmt.name.span if isinstance(sym.stmt, ast.TraitDef) else sym.stmt.path.span
        return NavTarget(sym.unit.path, focus, sym.stmt.span, sym.name)
    if isinstance(sym, MemberSym):
        unit = sym.owner.unit
        if unit is None:
            return None
        return NavTarget(unit.path, sym.stmt.path.parts[-1].span, sym.stmt.span, sym.name)
    if isinstance(sym, GlobalSym):
        return NavTarget(sym.unit.path, sym.stmt.path.span, sym.stmt.span, sym.name)
    if isinstance(sym, MethodSym):
        unit = sym.owner.unit
        if unit is None:
            return None
        return NavTarget(unit.path, sym.stmt.name.span, sym.stmt.span, sym.name)
    if isinstance(sym, Namespace):
        return _namespace_target(program, sym)
    return None


def _namespace_target(program, ns: Namespace) -> NavTarget | None:
    """A namespace is a folder: go to its bundle's config.openplx, or the first file directly inside it."""

    inside = sorted((u for u in program.units.values() if u.namespace.qname[: len(ns.qname)] == ns.qname),
                    key=lambda u: (len(u.namespace.qname), u.path))
    if not inside:
        return None
    u = inside[0]
    folder = os.path.dirname(u.path)
    for _ in range(len(u.namespace.qname) - len(ns.qname)):
        folder = os.path.dirname(folder)
    config = os.path.join(folder, "config.openplx")
    if len(ns.qname) == 1 and os.path.isfile(config):
        return NavTarget(config, EMPTY_SPAN, EMPTY_SPAN, ns.name)
    return NavTarget(u.path, EMPTY_SPAN, EMPTY_SPAN, ns.name)


def definition(st: FileState, offset: int) -> list[NavTarget]:
    if st.program is None:
        return []
    res = resolve_at(st, offset)
    if res is None or isinstance(res.target, str):
        return []
    t = target_of(st.program, res.target)
    return [t] if t is not None else []


def declaration(st: FileState, offset: int) -> list[NavTarget]:
    """For an attribute, where it was first declared (`is`), not where a subtype `becomes` it."""
    if st.program is None:
        return []
    res = resolve_at(st, offset)
    if res is None:
        return []
    sym = res.target
    if isinstance(sym, MemberSym):
        sym = original_declaration(st.program, sym, res.also)
    t = target_of(st.program, sym)
    return [t] if t is not None else []


def original_declaration(program, mem: MemberSym, also=()) -> MemberSym:
    """Follow `becomes` back to the `is` that introduced the attribute."""
    if mem.keyword != "becomes":
        return mem
    for other in also:
        if isinstance(other, MemberSym) and other.name == mem.name and other is not mem:
            return original_declaration(program, other)
    return resolve.introduced_by(program, mem)


def type_definition(st: FileState, offset: int) -> list[NavTarget]:
    if st.program is None:
        return []
    res = resolve_at(st, offset)
    if res is None:
        return []
    p = st.program
    sym = res.target
    ty = None
    if isinstance(sym, MemberSym):
        ty = p.member_type(sym)
    elif isinstance(sym, GlobalSym):
        ty = sym.ty or p.resolve_type_expr(sym.stmt.type, sym.unit)
    elif isinstance(sym, MethodSym) and sym.stmt.returns is not None:
        ty = p.resolve_type_ref(sym.stmt.returns, sym.owner.unit)
    elif isinstance(sym, ModelSym):
        return [t for t in [target_of(p, sym)] if t is not None]
    if ty is None:
        return []
    out = []
    models = [a.model for a in ty.alts] if ty.alts else [ty.model]
    for m in models:
        if m is not None:
            t = target_of(p, p.concrete(m))
            if t is not None:
                out.append(t)
    return out


# ------------------------------------------------------------------ references


def search_scope(host: AnalysisHost, sym, include_official: bool = False) -> list[str]:
    """Files that may name a symbol: open buffers, every user-bundle file, and optionally the bundles."""
    p = host.program
    out: list[str] = list(host.docs)
    for path, unit in p.units.items():
        if unit.bundle is None:
            continue
        if unit.official and not include_official:
            continue
        if path not in out:
            out.append(path)
    home = _home_path(sym)
    if home is not None and home not in out:
        out.append(home)
    return out


def _home_path(sym) -> str | None:
    if isinstance(sym, (ModelSym, GlobalSym)):
        return sym.unit.path if sym.unit is not None else None
    if isinstance(sym, (MemberSym, MethodSym)):
        return sym.owner.unit.path if sym.owner.unit is not None else None
    return None


def _linked(states: list[FileState], sym) -> set[int]:
    """The symbol plus every attribute joined to it by `becomes` (same span, definition + attribute)."""
    if not isinstance(sym, MemberSym):
        return {id(sym)}
    edges: dict[int, set[int]] = {}
    for st in states:
        by_span: dict[tuple[int, int], list] = {}
        for o in st.occurrences:
            if isinstance(o.target, MemberSym):
                by_span.setdefault((o.span.start.offset, o.span.end.offset), []).append(o)
        for group in by_span.values():
            if len(group) < 2:
                continue
            ids = {id(o.target) for o in group}
            for i in ids:
                edges.setdefault(i, set()).update(ids)
    family = {id(sym)}
    stack = [id(sym)]
    while stack:
        cur = stack.pop()
        for nxt in edges.get(cur, ()):
            if nxt not in family:
                family.add(nxt)
                stack.append(nxt)
    return family


def references(host: AnalysisHost, path: str, offset: int, include_declaration: bool = True,
               include_official: bool | None = None) -> list[FileSpan]:
    st = host.state(path)
    if st is None or st.program is None:
        return []
    res = resolve_at(st, offset)
    if res is None or isinstance(res.target, str):
        return []
    sym = res.target
    official = _is_official_symbol(sym)
    if include_official is None:
        include_official = official
    states = _states(host, search_scope(host, sym, include_official))
    family = _linked(states, sym)
    out: list[FileSpan] = []
    seen: set[tuple[str, int, int]] = set()
    for fst in states:
        for o in fst.occurrences:
            if id(o.target) not in family:
                continue
            if o.kind == "definition" and not include_declaration:
                continue
            key = (fst.path, o.span.start.offset, o.span.end.offset)
            if key in seen:
                continue
            seen.add(key)
            out.append(FileSpan(fst.path, _name_span(fst, o.span, _name(sym))))
    if include_declaration:
        t = target_of(st.program, sym)
        if t is not None and not any(r.path == t.path and r.span.start.offset == t.focus.start.offset for r in out):
            out.append(FileSpan(t.path, t.focus))
    out.sort(key=lambda r: (r.path != path, r.path, r.span.start.offset))
    return out


def _states(host: AnalysisHost, paths: list[str]) -> list[FileState]:
    out = []
    for p in paths:
        try:
            st = host.state(p)
        except Exception:  # noqa: BLE001 - one unreadable file must not break the search
            st = None
        if st is not None:
            out.append(st)
    return out


def _name(sym) -> str:
    if isinstance(sym, Namespace):
        return sym.name
    return getattr(sym, "name", "")


def _name_span(st: FileState, span, name: str):
    """A qualified occurrence (`A.B.Name`) narrowed to its last part."""
    text = st.text[span.start.offset:span.end.offset]
    if "." not in text:
        return span
    for cand in (f"`{name}`", name):
        if text.endswith(cand):
            idx = st.tree.index
            a = span.end.offset - len(cand)
            return Span(idx.pos(a), span.end)
    return span


def _is_official_symbol(sym) -> bool:
    if isinstance(sym, Namespace):
        return True
    home = None
    if isinstance(sym, (ModelSym, GlobalSym)):
        home = sym.unit
    elif isinstance(sym, (MemberSym, MethodSym)):
        home = sym.owner.unit
    return bool(home is not None and home.official)


# ------------------------------------------------------------------ rename


def prepare_rename(host: AnalysisHost, path: str, offset: int):
    """The span of the name to rename, or a RenameError saying why it cannot be renamed."""
    st = host.state(path)
    if st is None or st.program is None:
        raise RenameError("nothing to rename here")
    res = resolve_at(st, offset)
    if res is None:
        raise RenameError("no symbol here: put the cursor on a model, trait, attribute or global name")
    sym = res.target
    _check_renamable(sym)
    span = _name_span(st, res.span, _name(sym))
    return span, _name(sym)


def _check_renamable(sym) -> None:
    if isinstance(sym, str):
        raise RenameError(f"'{sym}' is a primitive type of the language and cannot be renamed")
    if isinstance(sym, Namespace):
        raise RenameError(f"'{sym.dotted}' is a namespace (a folder); rename the folder instead")
    if isinstance(sym, ModelSym) and sym.anonymous:
        raise RenameError("this is an instance block, not a named model")
    if _is_official_symbol(sym):
        home = sym.unit if isinstance(sym, (ModelSym, GlobalSym)) else sym.owner.unit
        raise RenameError(f"'{_name(sym)}' is defined in the official bundle '{home.bundle}' "
                          f"({os.path.basename(home.path)}); official bundles cannot be renamed")


def rename(host: AnalysisHost, path: str, offset: int, new_name: str) -> dict[str, list[TextEdit]]:
    """Edits per file renaming the symbol at the offset everywhere it is named."""
    st = host.state(path)
    if st is None or st.program is None:
        raise RenameError("nothing to rename here")
    res = resolve_at(st, offset)
    if res is None:
        raise RenameError("no symbol here: put the cursor on a model, trait, attribute or global name")
    sym = res.target
    _check_renamable(sym)
    bare = new_name.strip("`")
    if not IDENT.match(new_name) and not (new_name.startswith("`") and new_name.endswith("`") and bare):
        raise RenameError(f"'{new_name}' is not a valid OpenPLX name")

    if new_name in KEYWORDS:
        raise RenameError(f"'{new_name}' is a keyword")
    old = _name(sym)
    # a family of attributes joined by `becomes` is renamed together, so refuse if any is official
    states = _states(host, search_scope(host, sym, include_official=False))
    family = _linked(states, sym)
    out: dict[str, list[TextEdit]] = {}
    for fst in states:
        for o in fst.occurrences:
            if id(o.target) not in family:
                continue
            if _is_official_symbol(o.target):
                raise RenameError(f"'{old}' also specialises an attribute of the official bundles "
                                  f"({o.target.owner.qname}); it cannot be renamed")
            span = _name_span(fst, o.span, old)
            text = fst.text[span.start.offset:span.end.offset]
            if text.strip("`") != old:
                continue
            edits = out.setdefault(fst.path, [])
            if not any(e.start == span.start.offset for e in edits):
                edits.append(TextEdit(span.start.offset, span.end.offset, new_name))
    t = target_of(st.program, sym)
    if t is not None:
        edits = out.setdefault(t.path, [])
        if not any(e.start == t.focus.start.offset for e in edits):
            home_text = host.text_of(t.path) or ""
            if home_text[t.focus.start.offset:t.focus.end.offset].strip("`") == old:
                edits.append(TextEdit(t.focus.start.offset, t.focus.end.offset, new_name))
    for edits in out.values():
        edits.sort(key=lambda e: e.start)
    return out
