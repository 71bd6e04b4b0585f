"""The server follows the file system (issue 33, point 8: reproduction
lsp-stale-after-config-or-import-change): a config change that keeps the bundle set (an ignore
added) and an imported file created or deleted update the open documents' diagnostics after
`workspace/didChangeWatchedFiles`, without an edit; the imported files are registered as watched."""

from __future__ import annotations

import pytest
from lsprotocol import types
from pytest_lsp import client_capabilities

from tests.lsp.conftest import close, open_and_wait, wait_diagnostics

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

SCENE = ("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n"
         "    c is Real: undefined_name\n")
IMPORTS = 'import @"m.obj" as M\n\nScene is Physics3D.System:\n    v is M\n'
MESH = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


async def _after_event(client, uri, path, kind):
    client.mark = len(client.published)
    client.workspace_did_change_watched_files(types.DidChangeWatchedFilesParams(
        changes=[types.FileEvent(uri=path.as_uri(), type=kind)]))
    return [d.code for d in await wait_diagnostics(client, uri)]


async def test_a_config_change_with_the_same_bundle_set_is_applied(client, tmp_path):
    toml = tmp_path / "plx.toml"
    toml.write_text("exclude = []\n")
    scene = tmp_path / "scene.openplx"
    scene.write_text(SCENE)
    uri = scene.as_uri()
    assert [d.code for d in await open_and_wait(client, uri, SCENE)] == ["N003"]
    toml.write_text('ignore = ["N003"]\nexclude = []\n')
    assert await _after_event(client, uri, toml, types.FileChangeType.Changed) == []
    toml.write_text("exclude = []\n")
    assert await _after_event(client, uri, toml, types.FileChangeType.Changed) == ["N003"]
    close(client, uri)


async def test_an_imported_file_created_or_deleted_updates_the_import_error(client, tmp_path):
    doc = tmp_path / "imp.openplx"
    doc.write_text(IMPORTS)
    uri = doc.as_uri()
    mesh = tmp_path / "m.obj"
    assert "N006" in [d.code for d in await open_and_wait(client, uri, IMPORTS)]
    mesh.write_text(MESH)
    assert "N006" not in await _after_event(client, uri, mesh, types.FileChangeType.Created)
    mesh.unlink()
    assert "N006" in await _after_event(client, uri, mesh, types.FileChangeType.Deleted)
    caps = client_capabilities(client.name).workspace.did_change_watched_files
    if not (caps and caps.dynamic_registration):
        return  # this editor watches what it wants: the events above are what counts
    current = [r for r in client.registrations if r.id.startswith("plx-imported-files")]
    assert current, client.registrations
    watched = [w["globPattern"] for w in current[-1].register_options["watchers"]]
    assert {"baseUri": tmp_path.as_uri(), "pattern": "m.obj"} in watched or str(mesh) in watched, watched
    close(client, uri)
