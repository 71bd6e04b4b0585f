"""Plugin imports in the editor, over stdio: the imported name is an ordinary model of the file, so
definition, hover, references and diagnostics come from the shared model (the import line is its
definition)."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.conftest import CASES
from tests.lsp.conftest import close, open_and_wait, position

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

SCENE = CASES / "check" / "imports" / "scene.openplx"


def _target(result):
    [loc] = result
    if isinstance(loc, types.LocationLink):
        return loc.target_uri, loc.target_selection_range
    return loc.uri, loc.range


async def test_definition_and_hover_lead_to_the_import_line(client):
    uri, text = SCENE.as_uri(), SCENE.read_text(encoding="utf-8")
    diags = await open_and_wait(client, uri, text)
    assert not [d for d in diags if d.severity == types.DiagnosticSeverity.Error], diags
    doc = types.TextDocumentIdentifier(uri=uri)
    # `pendulum is Pendulum` -> `import @"inverted_pendulum.agx" as Pendulum` (line 0, the alias)
    got, rng = _target(await client.text_document_definition_async(types.DefinitionParams(
        text_document=doc, position=position(client, text, "is Pendulum:", 4))))
    assert got == uri and rng.start == position(client, text, "Pendulum\n")
    # a dotted alias: `arm is robots.arm` -> `as robots.arm` on line 1
    got, rng = _target(await client.text_document_definition_async(types.DefinitionParams(
        text_document=doc, position=position(client, text, "is robots.arm\n", len("is robots.a")))))
    assert got == uri and rng.start.line == 1
    h = await client.text_document_hover_async(types.HoverParams(
        text_document=doc, position=position(client, text, "is Rock:", 4)))
    assert h is not None
    assert "Rock is Visuals.Geometries.ExternalTriMeshGeometry" in h.contents.value
    assert "*import* · this file · `scene.openplx:3`" in h.contents.value
    assert "imported from @\"rock.obj\": a mesh file" in h.contents.value
    close(client, uri)


async def test_missing_import_diagnostic_and_references(client, tmp_path_factory):
    folder = tmp_path_factory.mktemp("imports")
    path = folder / "scene.openplx"
    text = ('import @"gone.agx"\n\nScene is Physics3D.System:\n    a is gone:\n        Body.mass: 1\n'
            '    b is gone\n')
    path.write_text(text, encoding="utf-8")
    uri = path.as_uri()
    diags = await open_and_wait(client, uri, text)
    assert [(d.code, d.range.start.line, d.range.start.character) for d in diags] == [("N006", 0, 7)]
    refs = await client.text_document_references_async(types.ReferenceParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=position(client, text, "is gone:", 4),
        context=types.ReferenceContext(include_declaration=True)))
    assert sorted(r.range.start.line for r in refs) == [0, 3, 5]
    close(client, uri)
