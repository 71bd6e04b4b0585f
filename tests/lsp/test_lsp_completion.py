"""Completion (and resolve) over stdio on half-typed lines."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import EXAMPLE_URI, change, example_text, open_and_wait, position, wait_diagnostics

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

VERSION = [1]


async def complete_at(client, text, needle):
    VERSION[0] += 1
    change(client, EXAMPLE_URI, VERSION[0], text)
    await wait_diagnostics(client, EXAMPLE_URI, VERSION[0])
    return await client.text_document_completion_async(types.CompletionParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI),
        position=position(client, text, needle, len(needle))))


async def test_types_under_a_namespace(client):
    await open_and_wait(client, EXAMPLE_URI, example_text(), VERSION[0])
    line = "    inertia.mass: 10\n"
    text = example_text().replace(line, line + "    geo2 is Physics3D.Geometries.\n", 1)
    res = await complete_at(client, text, "geo2 is Physics3D.Geometries.")
    labels = {i.label for i in res.items}
    assert {"Box", "Cylinder", "Sphere"} <= labels
    box = next(i for i in res.items if i.label == "Box")
    assert box.kind == types.CompletionItemKind.Class
    assert box.text_edit.new_text == "Box"


async def test_unset_attributes_on_an_empty_line_and_resolve(client):
    text = example_text().replace("    inertia.mass: 10\n", "    inertia.mass: 10\n    \n", 1)
    res = await complete_at(client, text, "    inertia.mass: 10\n    ")
    item = next(i for i in res.items if i.label == "is_dynamic")
    assert item.detail == "Bool = true"
    assert item.text_edit.new_text == "is_dynamic: "
    assert "geometry" not in {i.label for i in res.items}
    resolved = await client.completion_item_resolve_async(item)
    doc = resolved.documentation
    value = doc.value if isinstance(doc, types.MarkupContent) else doc
    assert "is_dynamic is Bool: true" in value


async def test_members_after_dot(client):
    text = example_text().replace("x: geometry.size.x * 0.31", "x: geometry.size.", 1)
    res = await complete_at(client, text, "x: geometry.size.")
    assert [i.label for i in sorted(res.items, key=lambda i: i.sort_text)][:3] == ["x", "y", "z"]
