"""Inlay hints over stdio: the inherited type after an assignment's path."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import EXAMPLE_URI, example_text, open_and_wait, position

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


async def test_inlay_hints(client):
    text = example_text()
    await open_and_wait(client, EXAMPLE_URI, text)
    end = text.count("\n")
    hints = await client.text_document_inlay_hint_async(types.InlayHintParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI),
        range=types.Range(start=types.Position(line=0, character=0), end=types.Position(line=end, character=0))))
    want = position(client, text, "inertia.mass: 10", len("inertia.mass"))
    assert any(h.position == want and h.label == ": Real" and h.kind == types.InlayHintKind.Type for h in hints)


async def test_long_type_hints_are_shortened_with_the_full_type_in_the_tooltip(client):
    """Issue 40.4: VS Code cut `: Physics3D.Interactions.MateConnector` at the window's edge; the hint
    is the type's own name, the qualified one is in the tooltip."""
    uri = "untitled:inlay-long"
    text = ("Body is Physics3D.Bodies.RigidBody:\n    hub is Physics3D.Interactions.MateConnector\n"
            "Cart is Physics3D.System:\n    a is Body\n    b is Body\n"
            "    h is Physics3D.Interactions.Hinge:\n        connectors: [a.hub, b.hub]\n")
    await open_and_wait(client, uri, text)
    hints = await client.text_document_inlay_hint_async(types.InlayHintParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        range=types.Range(start=types.Position(line=0, character=0), end=types.Position(line=8, character=0))))
    want = position(client, text, "connectors: [", len("connectors"))
    (hint,) = [h for h in hints if h.position == want]
    assert hint.label == ": MateConnector[]"
    tip = hint.tooltip.value if isinstance(hint.tooltip, types.MarkupContent) else hint.tooltip
    assert "Physics3D.Interactions.MateConnector[]" in tip
    client.text_document_did_close(types.DidCloseTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri=uri)))
