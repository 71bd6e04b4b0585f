"""Hover over stdio, in each client's position encoding."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import EXAMPLE_URI, close, example_text, open_and_wait, position

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


EVERY_CLIENT = True  # its answers depend on the client's capabilities (see conftest.py)


async def hover(client, uri, text, needle, delta=0, nth=0):
    return await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=position(client, text, needle, delta, nth)))


async def test_hover_attribute_and_type(client):
    text = example_text()
    await open_and_wait(client, EXAMPLE_URI, text)
    h = await hover(client, EXAMPLE_URI, text, "inertia.mass: 10", len("inertia.") + 1)
    assert h.contents.kind == types.MarkupKind.Markdown
    assert "`Real`" in h.contents.value and "default `0.0`" in h.contents.value
    assert h.range.start == position(client, text, "inertia.mass: 10", len("inertia."))
    h = await hover(client, EXAMPLE_URI, text, "Physics3D.Bodies.RigidBody", 20)
    assert "Physics3D.Bodies.RigidBody is Physics3D.Bodies.Body" in h.contents.value
    assert await hover(client, EXAMPLE_URI, text, "# A static plate") is None
    close(client, EXAMPLE_URI)


async def test_hover_after_non_ascii_text_on_the_line(client):
    # names after a 4-byte character: UTF-8 (Neovim) and UTF-16 (VS Code) columns differ
    uri = "untitled:hover-utf"
    text = ("S is Physics3D.System:\n    `😀é` is Real: 2\n"
            "    y is Math.Vec3: {`😀é`, `😀é` * 2, Math.PI}\n")
    await open_and_wait(client, uri, text)
    h = await hover(client, uri, text, "Math.PI", len("Math.") + 1)
    assert h is not None and "PI is Real" in h.contents.value
    assert h.range.start == position(client, text, "PI}")
    h = await hover(client, uri, text, "`😀é` * 2", 2)
    assert h is not None and "`Real`" in h.contents.value
    close(client, uri)


async def test_hover_shows_the_value_that_applies_and_who_sets_it(client):
    """Issue 32.9: on `inertia.mass: 1000` the hover said only `default 0.0`. It shows the value
    written there and the model that sets it; in a model below it, the value it inherits."""
    uri = "untitled:hover-value"
    text = ("Chassis is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1000\n\n"
            "Heavy is Chassis:\n    is_dynamic: true\n\n"
            "Scene is Physics3D.System:\n    truck is Heavy:\n        inertia.mass: 1500\n")
    await open_and_wait(client, uri, text)
    h = await hover(client, uri, text, "inertia.mass: 1000", len("inertia.") + 1)
    # issue 40.4: the first line is the value in force and where it is set, the default after it
    first = h.contents.value.split("\n\n")[0]
    assert first == "**`mass: 1000`** · set on this line in `Chassis`", h.contents.value
    assert "default `0.0`" in h.contents.value  # the declared default is still shown, as the default
    h = await hover(client, uri, text, "inertia.mass: 1500", len("inertia.") + 1)
    assert h.contents.value.startswith("**`mass: 1500`** · set on this line in `Scene`"), h.contents.value
    h = await hover(client, uri, text, "is_dynamic: true", 1)
    assert h.contents.value.startswith("**`is_dynamic: true`** · set on this line in `Heavy`"), h.contents.value
    close(client, uri)
