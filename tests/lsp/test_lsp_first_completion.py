"""Issue 40.1: completion asked for right after opening a file, before its first check, returns
real items: the bundles' types after `is`, the enclosing model's unset attributes on an empty line.
Each test starts its own server (the first one with an empty cache: the bundles are parsed while the
request waits), so the request meets the bundles' loader; with Neovim's capabilities as well as VS
Code's (Neovim does not ask again after an empty answer)."""

from __future__ import annotations

import atexit
import os
import shutil
import sys
import tempfile

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities

from tests.lsp.conftest import REPO, accept_registrations, position, record_diagnostics

EVERY_CLIENT = True
pytestmark = [pytest.mark.asyncio(loop_scope="function"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

COLD = tempfile.mkdtemp(prefix="plx-first-completion-")  # an empty plx cache for these servers
atexit.register(shutil.rmtree, COLD, True)
SERVER = ClientServerConfig(server_command=[sys.executable, "-m", "plxtools", "lsp"],
                            server_env={**os.environ, "PLX_CACHE_DIR": COLD})

TEXT = """\
Wheel is Physics3D.Bodies.RigidBody:
    inertia.mass: 12
    geometry is Physics3D.Geometries.Cylinder:
        radius: 0.3
        height: 0.2
    hub is Physics3D.Geometries.

Cart is Physics3D.System:
    left is Wheel
    
"""


@pytest_lsp.fixture(params=["neovim", "visual-studio-code"], config=SERVER)
async def fresh(request, lsp_client: LanguageClient):
    """A server per test, initialized but not yet past loading the bundles."""
    accept_registrations(lsp_client)
    result = await lsp_client.initialize_session(types.InitializeParams(
        capabilities=client_capabilities(request.param), root_uri=REPO.as_uri(),
        initialization_options={"diagnosticMode": "push"}))
    lsp_client.name = request.param
    lsp_client.server_capabilities = result.capabilities
    record_diagnostics(lsp_client)
    yield
    await lsp_client.shutdown_session()


def _open(client: LanguageClient, uri: str) -> None:
    client.text_document_did_open(types.DidOpenTextDocumentParams(text_document=types.TextDocumentItem(
        uri=uri, language_id="openplx", version=1, text=TEXT)))


async def _complete(client: LanguageClient, uri: str, needle: str):
    got = await client.text_document_completion_async(types.CompletionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=position(client, TEXT, needle, len(needle))))
    return got.items if isinstance(got, types.CompletionList) else got


async def test_bundle_types_right_after_opening(fresh, tmp_path):
    uri = (tmp_path / "cart.openplx").as_uri()
    _open(fresh, uri)
    items = await _complete(fresh, uri, "hub is Physics3D.Geometries.")
    labels = {i.label for i in items}
    assert {"Box", "Cylinder", "Sphere"} <= labels, labels


async def test_model_attributes_right_after_opening(fresh, tmp_path):
    uri = (tmp_path / "cart.openplx").as_uri()
    _open(fresh, uri)
    items = await _complete(fresh, uri, "    left is Wheel\n    ")
    labels = {i.label for i in items}
    # what a Physics3D.System declares and Cart does not set yet, not a fixed list
    assert "left" not in labels
    assert {"local_transform", "kinematically_controlled"} <= labels, labels
    # and the first check still runs, on the same text
    import asyncio

    for _ in range(2000):
        if any(p.uri == uri for p in fresh.published):
            break
        await asyncio.sleep(0.01)
    assert any(p.uri == uri for p in fresh.published)
