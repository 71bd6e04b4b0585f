"""Semantic tokens (full) over stdio: decoded with the server's legend."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import EXAMPLE_URI, example_text, open_and_wait

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


async def test_semantic_tokens(client):
    text = example_text()
    await open_and_wait(client, EXAMPLE_URI, text)
    res = await client.text_document_semantic_tokens_full_async(types.SemanticTokensParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI)))
    legend = client.server_capabilities.semantic_tokens_provider.legend
    lines = text.split("\n")
    line = col = 0
    found = {}
    data = res.data
    for i in range(0, len(data), 5):
        dl, dc, length, typ, _mods = data[i:i + 5]
        line += dl
        col = col + dc if dl == 0 else dc
        found.setdefault(lines[line][col:col + length], set()).add(legend.token_types[typ])
    assert "class" in found["RigidBody"] and "namespace" in found["Physics3D"]
    assert "property" in found["is_dynamic"] and "keyword" in found["becomes"]
