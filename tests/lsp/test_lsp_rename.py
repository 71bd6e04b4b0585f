"""prepareRename and rename over stdio: within a file, across a user bundle, refused for official names."""

from __future__ import annotations

import pytest
from lsprotocol import types
from pygls.exceptions import JsonRpcException

from tests.ide.conftest import write_bundle
from tests.lsp.conftest import EXAMPLE_URI, example_text, open_and_wait, position

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


async def test_prepare_rename(client):
    assert client.server_capabilities.rename_provider.prepare_provider  # both clients support it
    text = example_text()
    await open_and_wait(client, EXAMPLE_URI, text)
    doc = types.TextDocumentIdentifier(uri=EXAMPLE_URI)
    got = await client.text_document_prepare_rename_async(types.PrepareRenameParams(
        text_document=doc, position=position(client, text, "Wheel is", 2)))
    assert got.placeholder == "Wheel"
    assert got.range.start == position(client, text, "Wheel is")
    with pytest.raises(JsonRpcException, match="official bundle"):
        await client.text_document_prepare_rename_async(types.PrepareRenameParams(
            text_document=doc, position=position(client, text, "RigidBody", 2)))


async def test_rename_in_file(client):
    text = example_text()
    edit = await client.text_document_rename_async(types.RenameParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI), position=position(client, text, "Wheel is", 1),
        new_name="Tyre"))
    assert list(edit.changes) == [EXAMPLE_URI] and len(edit.changes[EXAMPLE_URI]) == 5
    assert {e.new_text for e in edit.changes[EXAMPLE_URI]} == {"Tyre"}


async def test_rename_across_a_user_bundle(client, tmp_path_factory):
    root = write_bundle(tmp_path_factory.mktemp(f"rename-{client.name}"), f"Garage{client.name.replace('-', '')}", {
        "Parts/Tyre.openplx": "Tyre is Physics3D.Bodies.RigidBody:\n    radius is Real: 0.3\n",
        "Car.openplx": "Car is Physics3D.System:\n    wheel is Parts.Tyre:\n        radius: 0.4\n",
    })
    car = root / "Car.openplx"
    text = car.read_text()
    await open_and_wait(client, car.as_uri(), text)
    edit = await client.text_document_rename_async(types.RenameParams(
        text_document=types.TextDocumentIdentifier(uri=car.as_uri()),
        position=position(client, text, "radius: 0.4", 1), new_name="size"))
    tyre_uri = (root / "Parts" / "Tyre.openplx").resolve().as_uri()
    assert set(edit.changes) == {car.resolve().as_uri(), tyre_uri}
    [tyre_edit] = edit.changes[tyre_uri]
    assert tyre_edit.range.start.line == 1 and tyre_edit.new_text == "size"
    with pytest.raises(JsonRpcException, match="not a valid"):
        await client.text_document_rename_async(types.RenameParams(
            text_document=types.TextDocumentIdentifier(uri=car.as_uri()),
            position=position(client, text, "radius: 0.4", 1), new_name="two words"))
