"""Semantic tokens, folding ranges, document links and inlay hints."""

from __future__ import annotations

from typing import TYPE_CHECKING

from lsprotocol import types

from plxtools import ide
from pygls.uris import from_fs_path
from plxtools.ide.tokens import encode

if TYPE_CHECKING:
    from plxtools.lsp.server import PlxServer


def register(server, server_feature) -> None:
    @server_feature(types.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL,
                    types.SemanticTokensLegend(token_types=ide.TOKEN_TYPES, token_modifiers=ide.TOKEN_MODIFIERS))
    def semantic_tokens(ls: PlxServer, params: types.SemanticTokensParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)

        return types.SemanticTokens(data=encode(ide.semantic_tokens(st), pos.length))

    @server_feature(types.TEXT_DOCUMENT_FOLDING_RANGE)
    def folding_range(ls: PlxServer, params: types.FoldingRangeParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        kinds = {"comment": types.FoldingRangeKind.Comment, "region": types.FoldingRangeKind.Region}
        return [types.FoldingRange(start_line=f.start_line, end_line=f.end_line, kind=kinds.get(f.kind))
                for f in ide.folding_ranges(st.tree)]

    @server_feature(types.TEXT_DOCUMENT_DOCUMENT_LINK)
    def document_link(ls: PlxServer, params: types.DocumentLinkParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        tooltips = ls.cap("text_document.document_link.tooltip_support")
        return [types.DocumentLink(range=pos.range(link.span), target=from_fs_path(link.target),
                                   tooltip=link.tooltip if tooltips else None)
                for link in ide.document_links(st.tree, st.path)]

    @server_feature(types.TEXT_DOCUMENT_INLAY_HINT)
    def inlay_hint(ls: PlxServer, params: types.InlayHintParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        start, end = pos.offset(params.range.start), pos.offset(params.range.end)
        kinds = {"type": types.InlayHintKind.Type, "parameter": types.InlayHintKind.Parameter}
        return [types.InlayHint(position=pos.position(h.line, h.column), label=h.label, kind=kinds[h.kind],
                                tooltip=h.tooltip, padding_left=h.padding_left or None, padding_right=h.padding_right or None)
                for h in ide.inlay_hints(st, start, end)]

    return server
