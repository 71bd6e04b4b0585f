"""The server survives garbage input, unknown methods, edits to unopened documents and a failing request."""

from __future__ import annotations

import os
import sys

import pytest
import pytest_lsp
from lsprotocol import types
from pygls.exceptions import JsonRpcException
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities

from tests.lsp.conftest import (
    EXAMPLE_URI,
    accept_registrations,
    REPO,
    example_text,
    open_and_wait,
    position,
    record_diagnostics,
    wait_diagnostics,
)

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

EVERY_CLIENT = True  # its answers depend on the client's capabilities (see conftest.py)

FAULTY = "textDocument/foldingRange"  # made to fail on purpose in this module's server


@pytest_lsp.fixture(scope="module", params=["neovim", "visual-studio-code"], config=ClientServerConfig(
    server_command=[sys.executable, "-m", "plxtools", "lsp"], server_env={**os.environ, "PLX_LSP_FAULT": FAULTY}))
async def client(request, lsp_client: LanguageClient):
    accept_registrations(lsp_client)
    result = await lsp_client.initialize_session(types.InitializeParams(
        capabilities=client_capabilities(request.param), root_uri=REPO.as_uri(),
        initialization_options={"diagnosticMode": "push"}))
    lsp_client.server_capabilities = result.capabilities
    record_diagnostics(lsp_client)
    lsp_client.name = request.param
    yield
    await lsp_client.shutdown_session()


async def hover_ok(client) -> None:
    text = example_text()
    h = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI),
        position=position(client, text, "inertia.mass", 9)))
    assert h is not None and "Real" in h.contents.value


async def test_a_failing_request_gets_an_error_and_the_server_lives_on(client):
    await open_and_wait(client, EXAMPLE_URI, example_text())
    with pytest.raises(JsonRpcException, match="injected fault"):
        await client.text_document_folding_range_async(types.FoldingRangeParams(
            text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI)))
    await hover_ok(client)


async def test_unknown_methods(client):
    with pytest.raises(JsonRpcException):
        await client.protocol.send_request_async("plx/noSuchMethod", {"x": 1})
    client.protocol.notify("plx/noSuchNotification", {"x": 1})
    await hover_ok(client)


async def test_edits_to_unopened_documents(client):
    ghost = "file:///nowhere/ghost.openplx"
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=ghost, version=3),
        content_changes=[types.TextDocumentContentChangePartial(
            range=types.Range(start=types.Position(line=0, character=0), end=types.Position(line=0, character=0)),
            text="x")]))
    client.text_document_did_close(types.DidCloseTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri="file:///nowhere/never-opened.openplx")))
    got = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri="file:///nowhere/missing.openplx"),
        position=types.Position(line=0, character=0)))
    assert got is None
    # a whole-text change to an unopened document is taken as an open
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri="untitled:late", version=2),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text="A is Physics3D.System:\n    x: 1\n")]))
    diags = await wait_diagnostics(client, "untitled:late", 2)
    assert [d.code for d in diags] == ["N002"]
    await hover_ok(client)


async def test_garbage_text_and_positions(client):
    uri = "untitled:garbage"
    text = "\x00\x01 is is : : {{{ ]]] \"\"\" \n\t\tfoo:\n💥💥 becomes ((\n" * 20
    await open_and_wait(client, uri, text)
    doc = types.TextDocumentIdentifier(uri=uri)
    far = types.Position(line=10_000, character=10_000)
    for pos in (types.Position(line=0, character=3), types.Position(line=2, character=1), far):
        await client.text_document_hover_async(types.HoverParams(text_document=doc, position=pos))
        await client.text_document_completion_async(types.CompletionParams(text_document=doc, position=pos))
        await client.text_document_definition_async(types.DefinitionParams(text_document=doc, position=pos))
        await client.text_document_signature_help_async(types.SignatureHelpParams(text_document=doc, position=pos))
    await client.text_document_semantic_tokens_full_async(types.SemanticTokensParams(text_document=doc))
    await client.text_document_document_symbol_async(types.DocumentSymbolParams(text_document=doc))
    await hover_ok(client)
