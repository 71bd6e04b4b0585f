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
