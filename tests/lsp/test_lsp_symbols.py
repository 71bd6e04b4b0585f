"""Document symbols (outline) and workspace symbols over stdio."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import EXAMPLE_URI, example_text, open_and_wait

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


EVERY_CLIENT = True  # its answers depend on the client's capabilities (see conftest.py)


async def test_document_symbols(client):
    await open_and_wait(client, EXAMPLE_URI, example_text())
    syms = await client.text_document_document_symbol_async(types.DocumentSymbolParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI)))
    names = [s.name for s in syms]
    assert "BoxTruck" in names and "Wheel" in names
    if isinstance(syms[0], types.DocumentSymbol):  # hierarchical (both bundled clients say so)
        truck = next(s for s in syms if s.name == "BoxTruck")
        assert truck.kind == types.SymbolKind.Class
        assert "front_left_hinge" in [c.name for c in truck.children]
    else:
        assert any(s.container_name == "BoxTruck" for s in syms)


async def test_workspace_symbols(client):
    got = await client.workspace_symbol_async(types.WorkspaceSymbolParams(query="RigidBody"))
    first = got[0]
    assert first.name == "RigidBody" and first.container_name == "Physics3D.Bodies"
    assert first.location.uri.endswith("/Physics3D/Bodies/RigidBody.openplx")
