"""Formatting and range formatting through plx fmt's functions, over stdio."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import open_and_wait

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

OPTIONS = types.FormattingOptions(tab_size=4, insert_spaces=True)


def apply(text: str, edits) -> str:
    lines = text.split("\n")
    starts = [0]
    for ln in lines:
        starts.append(starts[-1] + len(ln) + 1)
    for e in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character), reverse=True):
        a = starts[e.range.start.line] + e.range.start.character
        b = starts[e.range.end.line] + e.range.end.character
        text = text[:a] + e.new_text + text[b:]
    return text


async def test_formatting(client):
    uri = "untitled:fmt"
    text = "A is Physics3D.Bodies.RigidBody:\n  is_dynamic:   false\n  inertia.mass: 2\n"
    await open_and_wait(client, uri, text)
    edits = await client.text_document_formatting_async(types.DocumentFormattingParams(
        text_document=types.TextDocumentIdentifier(uri=uri), options=OPTIONS))
    assert apply(text, edits) == "A is Physics3D.Bodies.RigidBody:\n    is_dynamic: false\n    inertia.mass: 2\n"


async def test_range_formatting(client):
    uri = "untitled:fmt-range"
    text = "A is Physics3D.Bodies.RigidBody:\n    is_dynamic:   false\nB is  Physics3D.System\n"
    await open_and_wait(client, uri, text)
    edits = await client.text_document_range_formatting_async(types.DocumentRangeFormattingParams(
        text_document=types.TextDocumentIdentifier(uri=uri), options=OPTIONS,
        range=types.Range(start=types.Position(line=2, character=0), end=types.Position(line=2, character=5))))
    out = apply(text, edits)
    assert "B is Physics3D.System" in out and "is_dynamic:   false" in out


async def test_formatting_a_file_with_syntax_errors_changes_nothing(client):
    uri = "untitled:fmt-broken"
    text = "A is :\n"
    await open_and_wait(client, uri, text)
    edits = await client.text_document_formatting_async(types.DocumentFormattingParams(
        text_document=types.TextDocumentIdentifier(uri=uri), options=OPTIONS))
    assert not edits
