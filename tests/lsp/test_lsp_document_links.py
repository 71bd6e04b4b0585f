"""Document links for @"..." paths over stdio (tooltips only for clients that support them)."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import open_and_wait

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


EVERY_CLIENT = True  # its answers depend on the client's capabilities (see conftest.py)


async def test_document_links(client, tmp_path_factory):
    folder = tmp_path_factory.mktemp(f"links-{client.name}")
    (folder / "mesh.obj").write_text("")
    f = folder / "scene.openplx"
    text = 'S is Physics3D.System:\n    mesh is String: @"mesh.obj"\n'
    f.write_text(text)
    await open_and_wait(client, f.as_uri(), text)
    links = await client.text_document_document_link_async(types.DocumentLinkParams(
        text_document=types.TextDocumentIdentifier(uri=f.as_uri())))
    [link] = links
    assert link.target == (folder / "mesh.obj").resolve().as_uri()
    assert link.range.start == types.Position(line=1, character=text.split("\n")[1].index("mesh.obj"))
