"""Definition, declaration, type definition and references over stdio."""

from __future__ import annotations

from pathlib import Path

import openplxbundles
import pytest
from lsprotocol import types

from tests.lsp.conftest import EXAMPLE_URI, example_text, open_and_wait, position

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]

BUNDLES = Path(openplxbundles.package_dir()).resolve()


def target(result):
    [loc] = result
    if isinstance(loc, types.LocationLink):
        return loc.target_uri, loc.target_selection_range
    return loc.uri, loc.range


async def test_definition_into_the_bundle(client):
    text = example_text()
    await open_and_wait(client, EXAMPLE_URI, text)
    params = types.DefinitionParams(text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI),
                                    position=position(client, text, "Physics3D.Bodies.RigidBody", 20))
    uri, rng = target(await client.text_document_definition_async(params))
    assert uri == (BUNDLES / "Physics3D" / "Bodies" / "RigidBody.openplx").as_uri()
    assert rng.start.line == 0 and rng.start.character == 0


async def test_declaration_and_type_definition(client):
    text = example_text()
    pos = position(client, text, "inertia.mass", 1)
    doc = types.TextDocumentIdentifier(uri=EXAMPLE_URI)
    uri, _ = target(await client.text_document_declaration_async(
        types.DeclarationParams(text_document=doc, position=pos)))
    assert uri.endswith("/Physics/Bodies/Body.openplx")
    uri, rng = target(await client.text_document_type_definition_async(
        types.TypeDefinitionParams(text_document=doc, position=pos)))
    assert uri.endswith("/Physics3D/Bodies/Inertia.openplx") and rng.start.line == 0


async def test_references(client):
    text = example_text()
    refs = await client.text_document_references_async(types.ReferenceParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI), position=position(client, text, "TireMaterial"),
        context=types.ReferenceContext(include_declaration=True)))
    assert len(refs) == 3 and {r.uri for r in refs} == {EXAMPLE_URI}
    assert sorted(r.range.start.line for r in refs) == [text[:text.index(s)].count("\n") for s in
                                                        ("TireMaterial is", "material_1: TireMaterial",
                                                         "material: TireMaterial")]


async def test_definition_on_nothing_is_empty(client):
    text = example_text()
    got = await client.text_document_definition_async(types.DefinitionParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI), position=position(client, text, "# A static")))
    assert not got


async def test_in_an_official_bundle_file(client):
    """An official bundle file opened in the editor: no errors, and navigation works inside the bundles."""
    from tests.lsp.conftest import open_and_wait as _open

    path = BUNDLES / "Physics3D" / "Bodies" / "RigidBody.openplx"
    text = path.read_text(encoding="utf-8")
    diags = await _open(client, path.as_uri(), text)
    assert not [d for d in diags if d.severity == types.DiagnosticSeverity.Error]
    uri, rng = target(await client.text_document_definition_async(types.DefinitionParams(
        text_document=types.TextDocumentIdentifier(uri=path.as_uri()),
        position=position(client, text, "Physics3D.Bodies.Body", len("Physics3D.Bodies.B")))))
    assert uri == (BUNDLES / "Physics3D" / "Bodies" / "Body.openplx").as_uri() and rng.start.line == 0
    h = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=path.as_uri()),
        position=position(client, text, "is_dynamic is Bool", 2)))
    assert "`Bool`" in h.contents.value and "default `true`" in h.contents.value
