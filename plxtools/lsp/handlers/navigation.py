"""Hover, go to definition / declaration / type definition, references, rename, and the
document's and workspace's symbols."""

from __future__ import annotations

from typing import TYPE_CHECKING

from lsprotocol import types

from plxtools import ide
from plxtools.lsp.protocol import RequestFailed
from plxtools.ide.context import resolve_at

if TYPE_CHECKING:
    from plxtools.lsp.server import PlxServer


def register(server, server_feature) -> None:
    @server_feature(types.TEXT_DOCUMENT_HOVER)
    def hover(ls: PlxServer, params: types.HoverParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        res = ide.hover(st, pos.offset(params.position))
        if res is None:
            return None
        return types.Hover(contents=ls.markup(res.markdown), range=pos.range(res.span))

    def _locations(ls: PlxServer, targets, link_support: str | None, origin=None):
        if not targets:
            return None
        if link_support and ls.cap(link_support) and origin is not None:
            out = []
            for t in targets:
                tp = ls.positions(t.path)
                out.append(types.LocationLink(target_uri=ls.uri_of(t.path), target_range=tp.range(t.full),
                                              target_selection_range=tp.range(t.focus), origin_selection_range=origin))
            return out
        return [types.Location(uri=ls.uri_of(t.path), range=ls.positions(t.path).range(t.focus)) for t in targets]

    def _nav(fn, link_cap):
        def handler(ls: PlxServer, params):
            st = ls.state(params.text_document.uri)
            if st is None:
                return None
            pos = ls.positions(st.path, st)
            offset = pos.offset(params.position)
            targets = fn(st, offset)
            origin = None

            r = resolve_at(st, offset) if targets else None
            if r is not None:
                origin = pos.range(r.span)
            return _locations(ls, targets, link_cap, origin)
        return handler

    server_feature(types.TEXT_DOCUMENT_DEFINITION)(_nav(ide.definition, "text_document.definition.link_support"))
    server_feature(types.TEXT_DOCUMENT_DECLARATION)(_nav(ide.declaration, "text_document.declaration.link_support"))
    server_feature(types.TEXT_DOCUMENT_TYPE_DEFINITION)(
        _nav(ide.type_definition, "text_document.type_definition.link_support"))

    @server_feature(types.TEXT_DOCUMENT_REFERENCES)
    def references(ls: PlxServer, params: types.ReferenceParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        refs = ide.references(ls.host, st.path, pos.offset(params.position),
                              include_declaration=params.context.include_declaration)
        return [types.Location(uri=ls.uri_of(r.path), range=ls.positions(r.path).range(r.span)) for r in refs]

    @server_feature(types.TEXT_DOCUMENT_PREPARE_RENAME)
    def prepare_rename(ls: PlxServer, params: types.PrepareRenameParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        try:
            span, name = ide.prepare_rename(ls.host, st.path, pos.offset(params.position))
        except ide.RenameError as exc:
            raise RequestFailed(str(exc)) from None
        return types.PrepareRenamePlaceholder(range=pos.range(span), placeholder=name)

    @server_feature(types.TEXT_DOCUMENT_RENAME)
    def rename(ls: PlxServer, params: types.RenameParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        try:
            edits = ide.rename(ls.host, st.path, pos.offset(params.position), params.new_name)
        except ide.RenameError as exc:
            raise RequestFailed(str(exc)) from None
        changes = {}
        for path, file_edits in edits.items():
            fp = ls.positions(path)
            changes[ls.uri_of(path)] = [types.TextEdit(range=fp.offsets_range(e.start, e.end), new_text=e.text)
                                        for e in file_edits]
        return types.WorkspaceEdit(changes=changes)


    @server_feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def document_symbol(ls: PlxServer, params: types.DocumentSymbolParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        syms = ide.document_symbols(st.tree)
        if ls.cap("text_document.document_symbol.hierarchical_document_symbol_support"):
            def conv(s):
                return types.DocumentSymbol(name=s.name, kind=SYMBOL_KIND[s.kind], range=pos.range(s.span),
                                            selection_range=pos.range(s.selection), detail=s.detail or None,
                                            children=[conv(c) for c in s.children] or None)
            return [conv(s) for s in syms]
        flat = []
        uri = params.text_document.uri

        def walk(s, container):
            flat.append(types.SymbolInformation(name=s.name, kind=SYMBOL_KIND[s.kind],
                                                location=types.Location(uri=uri, range=pos.range(s.span)),
                                                container_name=container))
            for c in s.children:
                walk(c, s.name)
        for s in syms:
            walk(s, None)
        return flat

    @server_feature(types.WORKSPACE_SYMBOL)
    def workspace_symbol(ls: PlxServer, params: types.WorkspaceSymbolParams):
        out = []
        for w in ide.workspace_symbols(ls.host, params.query):
            out.append(types.WorkspaceSymbol(name=w.name, kind=SYMBOL_KIND.get(w.kind, types.SymbolKind.Class),
                                             location=types.Location(uri=ls.uri_of(w.path),
                                                                     range=ls.positions(w.path).range(w.span)),
                                             container_name=w.container or None))
        return out


SYMBOL_KIND = {
    "model": types.SymbolKind.Class,
    "trait": types.SymbolKind.Interface,
    "const": types.SymbolKind.Constant,
    "global": types.SymbolKind.Constant,
    "attribute": types.SymbolKind.Field,
    "method": types.SymbolKind.Method,
    "operator": types.SymbolKind.Operator,
    "block": types.SymbolKind.Object,
    "import": types.SymbolKind.Module,
}
