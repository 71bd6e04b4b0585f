"""Signature help for fn calls over stdio."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import open_and_wait, position

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


async def test_signature_help(client):
    uri = "untitled:sig"
    text = "S is Physics3D.System:\n    q is Math.Quat: Math.Quat.angle_axis(Math.PI / 4, \n"
    await open_and_wait(client, uri, text)
    res = await client.text_document_signature_help_async(types.SignatureHelpParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=position(client, text, "Math.PI / 4, ", len("Math.PI / 4, "))))
    sig = res.signatures[res.active_signature]
    assert sig.label.startswith("static fn angle_axis(")
    assert res.active_parameter == 1
    label = sig.parameters[1].label
    shown = sig.label[label[0]:label[1]] if isinstance(label, (list, tuple)) else label
    assert shown.startswith("axis") or ":" in shown


@pytest.mark.parametrize("text", ["", "S is Physics3D.System:\n    v is Math.Vec3: Math.Vec3.from_xyz("])
async def test_signature_help_at_the_start_of_a_file(client, text):
    """Issue 32.10: at offset 0 nothing precedes the cursor. An empty buffer crashed with an
    IndexError, and a file ending in an open call showed that call's signature at its start."""
    uri = f"untitled:sig-start-{len(text)}"
    await open_and_wait(client, uri, text)
    res = await client.text_document_signature_help_async(types.SignatureHelpParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=types.Position(line=0, character=0)))
    assert res is None
