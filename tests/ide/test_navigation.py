"""Definition, declaration, type definition, references and rename; across files of a user bundle."""

from __future__ import annotations

import os
from pathlib import Path

import openplxbundles
import pytest

from plxtools.ide import (
    AnalysisHost,
    RenameError,
    declaration,
    definition,
    prepare_rename,
    references,
    rename,
    type_definition,
)
from tests.ide.conftest import Doc, write_bundle

BUNDLES = Path(openplxbundles.package_dir()).resolve()


def test_definition_of_bundle_model_jumps_to_its_file_line_1(example):
    targets = definition(example.st, example.at("Physics3D.Bodies.RigidBody", 20))
    assert len(targets) == 1
    t = targets[0]
    assert Path(t.path) == BUNDLES / "Physics3D" / "Bodies" / "RigidBody.openplx"
    assert t.focus.start.line == 0 and t.name == "RigidBody"


def test_definition_of_namespace_part(example):
    t = definition(example.st, example.at("Physics3D.Bodies.RigidBody", 1))[0]
    assert Path(t.path) == BUNDLES / "Physics3D" / "config.openplx"


def test_definition_of_local_model_and_attribute(example):
    t = definition(example.st, example.at("is Wheel", 4))[0]
    assert t.path == example.path
    assert example.text[t.focus.start.offset:t.focus.end.offset] == "Wheel"
    # `front_left_wheel.connector` -> the connector declared in Wheel
    t = definition(example.st, example.at("front_left_wheel.connector", len("front_left_wheel.") + 1))[0]
    assert t.path == example.path and t.focus.start.line == example.text.count("\n", 0, example.at("connector is"))


def test_definition_of_inherited_attribute_goes_into_the_bundle(example):
    t = definition(example.st, example.at("is_dynamic: false", 1))[0]
    assert t.path.endswith(os.path.join("Physics3D", "Bodies", "RigidBody.openplx"))


def test_declaration_follows_becomes_to_the_original(example):
    t = declaration(example.st, example.at("inertia.mass", 1))[0]
    assert t.path.endswith(os.path.join("Physics", "Bodies", "Body.openplx"))


def test_type_definition_of_attribute(example):
    t = type_definition(example.st, example.at("inertia.mass", 1))[0]
    assert t.path.endswith(os.path.join("Physics3D", "Bodies", "Inertia.openplx"))


def test_references_of_local_const(example, host):
    refs = references(host, example.path, example.at("TireMaterial", 2))
    assert len(refs) == 3  # the definition and two uses
    assert all(example.text[r.span.start.offset:r.span.end.offset] == "TireMaterial" for r in refs)
    without = references(host, example.path, example.at("TireMaterial", 2), include_declaration=False)
    assert len(without) == 2


def test_rename_refuses_official_symbols(example, host):
    with pytest.raises(RenameError, match="official bundle 'Physics3D'"):
        prepare_rename(host, example.path, example.at("RigidBody", 2))
    with pytest.raises(RenameError, match="official"):
        rename(host, example.path, example.at("is_dynamic: false", 1), "dyn")
    with pytest.raises(RenameError, match="namespace"):
        prepare_rename(host, example.path, example.at("Physics3D", 1))


def test_rename_local_model(example, host):
    span, name = prepare_rename(host, example.path, example.at("Wheel is", 1))
    assert name == "Wheel"
    edits = rename(host, example.path, example.at("Wheel is", 1), "Tyre")
    [(path, file_edits)] = edits.items()
    assert path == example.path and len(file_edits) == 5
    new = example.text
    for e in sorted(file_edits, key=lambda e: -e.start):
        new = new[:e.start] + e.text + new[e.end:]
    assert "Tyre is Physics3D.Bodies.RigidBody" in new and "front_left_wheel is Tyre" in new
    with pytest.raises(RenameError, match="not a valid"):
        rename(host, example.path, example.at("Wheel is", 1), "1bad")


@pytest.fixture
def bundle_host(tmp_path):
    root = write_bundle(tmp_path, "Garage", {
        "Parts/Tyre.openplx": "Tyre is Physics3D.Bodies.RigidBody:\n    radius is Real: 0.3\n"
                              "    with_hub becomes Physics3D.Bodies.RigidBody\n",
        "Car.openplx": "Car is Physics3D.System:\n    wheel is Parts.Tyre:\n        radius: 0.4\n"
                       "    r is Real: wheel.radius * 2\n",
    })
    h = AnalysisHost()
    return h, root


def test_cross_file_definition_references_and_rename(bundle_host):
    h, root = bundle_host
    car = str((root / "Car.openplx").resolve())
    tyre = str((root / "Parts" / "Tyre.openplx").resolve())
    doc = Doc(h, car, (root / "Car.openplx").read_text())
    st = doc.st
    assert [d.code for d in st.diagnostics if d.severity.value == "error"] == []
    t = definition(st, doc.at("Parts.Tyre", 7))[0]
    assert t.path == tyre and t.focus.start.line == 0
    t = definition(st, doc.at("wheel.radius", 7))[0]
    assert t.path == tyre and t.focus.start.line == 1
    refs = references(h, car, doc.at("radius: 0.4", 1))
    assert {r.path for r in refs} == {car, tyre} and len(refs) == 3
    edits = rename(h, car, doc.at("Parts.Tyre", 7), "Tire")
    assert set(edits) == {car, tyre}
    assert [e.text for e in edits[tyre]] == ["Tire"]
    assert Path(car).read_text()[edits[car][0].start:edits[car][0].end] == "Tyre"  # only the last part


def test_edit_in_one_bundle_file_rechecks_the_other(bundle_host):
    h, root = bundle_host
    car = str((root / "Car.openplx").resolve())
    tyre = str((root / "Parts" / "Tyre.openplx").resolve())
    doc_car = Doc(h, car, (root / "Car.openplx").read_text())
    doc_tyre = Doc(h, tyre, (root / "Parts" / "Tyre.openplx").read_text())
    assert not [d for d in doc_car.st.diagnostics if d.severity.value == "error"]
    assert h.dependents(tyre) == [car]
    h.update_document(tyre, doc_tyre.text.replace("radius is Real", "diameter is Real"), 2)
    codes = [d.code for d in h.state(car).diagnostics if d.severity.value == "error"]
    assert "N002" in codes and "N004" in codes  # `radius:` and `wheel.radius` no longer exist
    h.close_document(tyre)  # back to the disk version
    assert not [d for d in h.state(car).diagnostics if d.severity.value == "error"]
