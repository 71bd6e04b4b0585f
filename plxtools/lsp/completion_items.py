"""A completion answer as plain LSP JSON: one shape for the server's handler and for the answer
given before pygls and lsprotocol have loaded (early.py), so the two cannot drift apart.

No pygls or lsprotocol here: this runs in the server's first tenth of a second.
"""

from __future__ import annotations

from dataclasses import dataclass

# LSP's CompletionItemKind numbers for the kinds `ide.complete` gives
KIND = {"model": 7, "trait": 8, "constant": 21, "namespace": 9, "attribute": 5, "method": 2, "keyword": 14,
        "value": 12, "type": 25}
DEPRECATED = 1  # CompletionItemTag.Deprecated


@dataclass(frozen=True)
class ItemOptions:
    """What the client said it supports (completionItem capabilities)."""

    lazy_documentation: bool = False  # resolveSupport lists "documentation": sent on completionItem/resolve
    label_details: bool = False
    tags: bool = False
    markdown: bool = False  # documentationFormat lists markdown


def options_from(completion_item: dict | None) -> ItemOptions:
    """ItemOptions from the raw `textDocument.completion.completionItem` capabilities."""
    got = completion_item if isinstance(completion_item, dict) else {}
    resolve = got.get("resolveSupport")
    props = resolve.get("properties") if isinstance(resolve, dict) else None
    formats = got.get("documentationFormat")
    return ItemOptions(lazy_documentation="documentation" in (props if isinstance(props, list) else []),
                       label_details=bool(got.get("labelDetailsSupport")),
                       tags=bool(got.get("tagSupport")),
                       markdown="markdown" in (formats if isinstance(formats, list) else []))


def documentation(text: str, markdown: bool):
    if markdown:
        return {"kind": "markdown", "value": text}
    return text.replace("```openplx\n", "").replace("```\n", "").replace("```", "")


def completion_list(res, rng: dict, opts: ItemOptions, keys: list, documentation_of) -> dict:
    """`res` (an `ide.complete` result) as a CompletionList; `rng` the LSP range each item replaces.
    `keys` receives the items' keys (an item's `data.k` indexes it, for completionItem/resolve);
    `documentation_of(key)` is the item's documentation, asked for only when it is not resolved lazily."""
    items = []
    for it in res.items:
        item = {"label": it.label}
        kind = KIND.get(it.kind)
        if kind is not None:
            item["kind"] = kind
        if it.detail:
            item["detail"] = it.detail
        if it.sort_text is not None:
            item["sortText"] = it.sort_text
        if it.filter_text is not None:
            item["filterText"] = it.filter_text
        item["textEdit"] = {"range": rng, "newText": it.insert_text or it.label}
        if opts.label_details and (it.label_detail or it.label_description):
            details = {}
            if it.label_detail is not None:
                details["detail"] = it.label_detail
            if it.label_description is not None:
                details["description"] = it.label_description
            item["labelDetails"] = details
        if it.deprecated and opts.tags:
            item["tags"] = [DEPRECATED]
        if it.key is not None:
            keys.append(it.key)
            item["data"] = {"k": len(keys) - 1}
            if not opts.lazy_documentation:
                doc = documentation_of(it.key)
                if doc:
                    item["documentation"] = documentation(doc, opts.markdown)
        items.append(item)
    return {"isIncomplete": bool(res.is_incomplete), "items": items}


def lsp_range(positions, start: int, end: int) -> dict:
    (l0, c0), (l1, c1) = positions.line_character(start), positions.line_character(end)
    return {"start": {"line": l0, "character": c0}, "end": {"line": l1, "character": c1}}
