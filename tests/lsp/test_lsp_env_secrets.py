"""The language server names `$"{VAR}"` strings as written, in diagnostics and hovers: the value
of an environment variable is not shown (issue 33, point 4)."""

from __future__ import annotations

import os

import pytest
from lsprotocol import types

from tests.lsp.conftest import close, open_and_wait, position

SECRET = "ghp_NOTSHOWN42"
os.environ["PLX_TEST_LSP_TOKEN"] = SECRET  # before this module's server starts: it inherits it

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

TEXT = """\
import $"{PLX_TEST_LSP_TOKEN}/history.obj" as History
Scene is Physics3D.System:
    b is Physics3D.Bodies.RigidBody:
        inertia.mass: 1
        visual is Visuals.Geometries.ExternalTriMeshGeometry:
            path: $"{PLX_TEST_LSP_TOKEN}.obj"
    h is History
"""


async def test_diagnostics_and_hovers_do_not_show_the_value(client, tmp_path):
    uri = (tmp_path / "leak.openplx").as_uri()
    (tmp_path / "leak.openplx").write_text(TEXT)
    diags = await open_and_wait(client, uri, TEXT)
    assert any(d.code == "N006" for d in diags)
    assert not [d for d in diags if SECRET in d.message]
    shown = []
    for needle, delta in (('$"{PLX_TEST_LSP_TOKEN}/', 3), ("History", 2), ('$"{PLX_TEST_LSP_TOKEN}.obj', 4),
                          ("is History", 5), ("path:", 1)):
        h = await client.text_document_hover_async(types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=uri), position=position(client, TEXT, needle, delta)))
        if h is not None:
            shown.append(h.contents.value)
    assert shown and not [s for s in shown if SECRET in s]
    close(client, uri)
