"""The real `plx lsp` as a subprocess over stdio, driven by pytest-lsp with real editors' capabilities.

One server per test module and client (Neovim 0.11: UTF-8 positions, no document links; VS Code
1.65: UTF-16, hierarchical symbols, link support), shared by the module's tests.

Most modules test what the server does, which does not depend on the client: they run with VS Code
only. A module whose answers do depend on it (positions in non-ASCII text, link and symbol
capabilities) says `EVERY_CLIENT = True` and runs with both; `PLX_ALL_CLIENTS=1` runs every module
with both (a stage of .ci/run).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
EXAMPLE_URI = EXAMPLE.as_uri()
CLIENTS = ["neovim", "visual-studio-code"]
SERVER = ClientServerConfig(server_command=[sys.executable, "-m", "plxtools", "lsp"])


def pytest_collection_modifyitems(config, items):
    """Leave out the Neovim run of a server test whose module did not ask for every client."""
    if os.environ.get("PLX_ALL_CLIENTS") == "1":
        return
    here = Path(__file__).resolve().parent
    keep, drop = [], []
    for item in items:
        spec = getattr(item, "callspec", None)
        one_client = (spec is not None and Path(item.path).resolve().parent == here
                      and any(isinstance(v, str) and v == "neovim" for v in spec.params.values())
                      and not getattr(item.module, "EVERY_CLIENT", False))
        (drop if one_client else keep).append(item)
    if drop:
        config.hook.pytest_deselected(items=drop)
        items[:] = keep


def example_text() -> str:
    return EXAMPLE.read_text(encoding="utf-8")


@pytest_lsp.fixture(scope="module", params=CLIENTS, config=SERVER)
async def client(request, lsp_client: LanguageClient):
    accept_registrations(lsp_client)
    result = await lsp_client.initialize_session(types.InitializeParams(
        capabilities=client_capabilities(request.param),
        root_uri=REPO.as_uri(),
        initialization_options={"diagnosticMode": "push"},
    ))
    lsp_client.name = request.param
    lsp_client.server_capabilities = result.capabilities
    record_diagnostics(lsp_client)
    yield
    await lsp_client.shutdown_session()


def accept_registrations(client: LanguageClient) -> None:
    """Answer client/registerCapability and client/unregisterCapability as editors do (pytest-lsp's
    client has no handler for them)."""
    client.registrations = []

    @client.feature(types.CLIENT_REGISTER_CAPABILITY)
    def _register(params: types.RegistrationParams) -> None:
        client.registrations.extend(params.registrations)

    @client.feature(types.CLIENT_UNREGISTER_CAPABILITY)
    def _unregister(params: types.UnregistrationParams) -> None:
        gone = {u.id for u in params.unregisterations}
        client.registrations[:] = [r for r in client.registrations if r.id not in gone]


def record_diagnostics(client: LanguageClient) -> None:
    """Keep every publishDiagnostics (pytest-lsp's waiting future sees only one at a time)."""
    client.published = []
    client.mark = 0
    original = client.protocol._handle_notification

    def spy(method, params):
        if method == types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS:
            client.published.append(params)
        return original(method, params)

    client.protocol._handle_notification = spy


def encoding_of(client: LanguageClient) -> str:
    enc = client.server_capabilities.position_encoding
    return str(enc.value if hasattr(enc, "value") else enc or "utf-16")


def position(client: LanguageClient, text: str, needle: str, delta: int = 0, nth: int = 0) -> types.Position:
    """The LSP position of `needle` (+delta code points) in the client's negotiated encoding."""
    at = -1
    for _ in range(nth + 1):
        at = text.index(needle, at + 1)
    at += delta
    line = text.count("\n", 0, at)
    col_text = text[text.rfind("\n", 0, at) + 1:at]
    enc = encoding_of(client)
    if enc == "utf-8":
        ch = len(col_text.encode("utf-8"))
    elif enc == "utf-32":
        ch = len(col_text)
    else:
        ch = len(col_text.encode("utf-16-le")) // 2
    return types.Position(line=line, character=ch)


async def open_and_wait(client: LanguageClient, uri: str, text: str, version: int = 1) -> list[types.Diagnostic]:
    """Open a document and wait for the diagnostics of exactly this version."""
    client.mark = len(client.published)
    client.text_document_did_open(types.DidOpenTextDocumentParams(text_document=types.TextDocumentItem(
        uri=uri, language_id="openplx", version=version, text=text)))
    return await wait_diagnostics(client, uri, version)


async def wait_diagnostics(client: LanguageClient, uri: str, version: int | None = None, timeout: float = 20):
    """The first diagnostics for `uri` (and `version`) published since the last open/change/close sent."""
    import asyncio

    start = client.mark
    loop = asyncio.get_running_loop()
    deadline = loop.time() + timeout
    while loop.time() < deadline:
        for params in client.published[start:]:
            if params.uri == uri and (version is None or params.version == version):
                client.mark = client.published.index(params) + 1
                return list(params.diagnostics)
        await asyncio.sleep(0.005)
    raise TimeoutError(f"no diagnostics for {uri} version {version}")


def change(client: LanguageClient, uri: str, version: int, text: str) -> None:
    client.mark = len(client.published)
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))


def close(client: LanguageClient, uri: str) -> None:
    client.mark = len(client.published)
    client.text_document_did_close(types.DidCloseTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri=uri)))
