"""Diagnostics over stdio: the example is clean, a typo gives one located diagnostic, versions match."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import EXAMPLE_URI, change, close, example_text, open_and_wait, position, wait_diagnostics

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


async def test_example_is_clean(client):
    diags = await open_and_wait(client, EXAMPLE_URI, example_text())
    assert [d for d in diags if d.severity in (types.DiagnosticSeverity.Error, types.DiagnosticSeverity.Warning)] == []
    close(client, EXAMPLE_URI)


async def test_typo_gives_one_located_diagnostic(client):
    text = example_text()
    await open_and_wait(client, EXAMPLE_URI, text)
    bad = text.replace("    is_dynamic: false", "    is_dynamc: false", 1)
    change(client, EXAMPLE_URI, 2, bad)
    diags = await wait_diagnostics(client, EXAMPLE_URI, 2)
    errors = [d for d in diags if d.severity == types.DiagnosticSeverity.Error]
    assert len(errors) == 1
    d = errors[0]
    assert d.code == "N002" and d.source == "plx"
    assert "is_dynamc" in d.message
    start = position(client, bad, "is_dynamc")
    assert d.range.start == start
    assert d.range.end.character - d.range.start.character == len("is_dynamc")
    assert d.data["fix"]["edits"]  # the "did you mean" fix travels with the diagnostic
    close(client, EXAMPLE_URI)


async def test_untitled_buffer(client):
    uri = "untitled:Untitled-1"
    diags = await open_and_wait(client, uri, "Scene is Physics3D.System:\n    grvity: 1\n")
    assert [d.code for d in diags] == ["N002"]
    assert diags[0].range.start.line == 1
    close(client, uri)


async def test_burst_of_edits_ends_with_the_last_version(client):
    uri = "untitled:burst"
    await open_and_wait(client, uri, "Scene is Physics3D.System\n")
    start = len(client.published)
    for v in range(2, 7):
        change(client, uri, v, "Scene is Physics3D.System:\n" + "    x: 1\n" * v)
    # no fixed delay: versions the server saw before the next edit arrived may be checked, but each
    # publication is for the version it was computed on, in order, and the burst ends with version 6
    diags = await wait_diagnostics(client, uri, 6)
    assert len(diags) == 6  # one N002 per `x: 1` line of version 6
    mine = [p for p in client.published[start:] if p.uri == uri]
    assert [p.version for p in mine] == sorted({p.version for p in mine})
    for p in mine:
        assert len(p.diagnostics) == p.version


async def test_bundle_file_change_rechecks_dependents(client, tmp_path_factory):
    from tests.ide.conftest import write_bundle

    root = write_bundle(tmp_path_factory.mktemp(f"deps-{client.name}"), f"Depot{client.name.replace('-', '')}", {
        "Parts/Tyre.openplx": "Tyre is Physics3D.Bodies.RigidBody:\n    radius is Real: 0.3\n",
        "Car.openplx": "Car is Physics3D.System:\n    wheel is Parts.Tyre:\n        radius: 0.4\n",
    })
    car, tyre = (root / "Car.openplx").resolve(), (root / "Parts" / "Tyre.openplx").resolve()
    assert await open_and_wait(client, car.as_uri(), car.read_text()) == []
    await open_and_wait(client, tyre.as_uri(), tyre.read_text())
    change(client, tyre.as_uri(), 2, tyre.read_text().replace("radius", "diameter"))
    diags = await wait_diagnostics(client, car.as_uri())  # Car was not edited, but depends on Tyre
    assert [d.code for d in diags] == ["N002"]
    close(client, tyre.as_uri())  # back to the disk version: Car is fine again
    assert await wait_diagnostics(client, car.as_uri()) == []
