"""Settings from initializationOptions and workspace/configuration (select / ignore rules)."""

from __future__ import annotations

import sys

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities

from tests.lsp.conftest import (REPO, accept_registrations, change, open_and_wait, record_diagnostics,
                                 wait_diagnostics)

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

EVERY_CLIENT = True  # its answers depend on the client's capabilities (see conftest.py)

TEXT = "a_scene is Physics3D.System:\n    is_dynamc: 1\n"


@pytest_lsp.fixture(scope="module", params=["neovim", "visual-studio-code"],
                    config=ClientServerConfig(server_command=[sys.executable, "-m", "plxtools", "lsp"]))
async def client(request, lsp_client: LanguageClient):
    accept_registrations(lsp_client)
    result = await lsp_client.initialize_session(types.InitializeParams(
        capabilities=client_capabilities(request.param), root_uri=REPO.as_uri(),
        initialization_options={"ignore": ["C001"], "diagnosticMode": "push"}))
    lsp_client.server_capabilities = result.capabilities
    record_diagnostics(lsp_client)
    yield
    await lsp_client.shutdown_session()


async def test_initialization_options_ignore(client):
    diags = await open_and_wait(client, "untitled:settings", TEXT)
    assert [d.code for d in diags] == ["N002"]  # C001 (a_scene is not PascalCase) is ignored


async def test_workspace_configuration_select(client):
    # its own document: under xdist this test may run in another process than the one above
    uri = "untitled:settings-select"
    assert [d.code for d in await open_and_wait(client, uri, TEXT)] == ["N002"]
    client.mark = len(client.published)  # before the new settings: a check already under way may use them
    client.set_configuration({"select": ["C"], "ignore": []}, section="openplx")
    client.workspace_did_change_configuration(types.DidChangeConfigurationParams(settings=None))
    try:
        diags = await wait_diagnostics(client, uri, 1)
        assert [d.code for d in diags] == ["C001"]
        change(client, uri, 2, TEXT + "\n")
        assert [d.code for d in await wait_diagnostics(client, uri, 2)] == ["C001"]
    finally:
        client.set_configuration({}, section="openplx")
        client.workspace_did_change_configuration(types.DidChangeConfigurationParams(settings=None))
