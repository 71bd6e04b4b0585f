"""Code actions over stdio: a lint fix, suppress-this-rule, fix all."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import open_and_wait

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


async def test_quick_fix_and_suppress(client):
    uri = "untitled:actions"
    text = "S is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        is_dynamc: false\n"
    diags = await open_and_wait(client, uri, text)
    [d] = [x for x in diags if x.code == "N002"]
    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), range=d.range,
        context=types.CodeActionContext(diagnostics=[d])))
    titles = [a.title for a in actions]
    fix = next(a for a in actions if a.title.startswith("Fix N002"))
    assert fix.kind == types.CodeActionKind.QuickFix and fix.diagnostics[0].code == "N002"
    [edit] = fix.edit.changes[uri]
    assert edit.new_text == "is_dynamic" and edit.range == d.range
    sup = next(a for a in actions if a.title.startswith("Suppress N002"))
    [edit] = sup.edit.changes[uri]
    assert edit.new_text == "  # plx: ignore[N002]" and edit.range.start.line == 2, titles


async def test_fix_all(client):
    uri = "untitled:fixall"
    text = "S is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody  # plx: ignore[T001]\n"
    await open_and_wait(client, uri, text)
    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        range=types.Range(start=types.Position(line=0, character=0), end=types.Position(line=0, character=0)),
        context=types.CodeActionContext(diagnostics=[], only=[types.CodeActionKind.SourceFixAll])))
    [action] = actions
    assert action.kind == types.CodeActionKind.SourceFixAll
    [edit] = action.edit.changes[uri]
    assert edit.new_text == "" and edit.range.start.line == 1
