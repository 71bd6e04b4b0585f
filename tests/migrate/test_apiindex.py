"""The stored API index: coverage, content checked against real bundle sources, deterministic bytes."""

import gzip
import importlib.util
import json
from pathlib import Path

import pytest

from plxtools.model import apiindex
from plxtools.model.apiindex import UnknownVersion, load, spans, versions, where_defined
from tests.conftest import REPO, bundle_root


def _script():
    spec = importlib.util.spec_from_file_location("build_api_index", REPO / "scripts" / "build_api_index.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_every_released_version_from_0_15_0_to_0_19_0_is_indexed():
    vs = versions()
    assert vs[0] == "0.15.0" and vs[-1] == "0.19.0"
    for v in ("0.15.22", "0.16.10", "0.17.26", "0.17.33", "0.18.10", "0.18.11"):
        assert v in vs
    assert len(vs) == 81  # every openplx-bundles release on the registry when the index was built
    assert sum(p.stat().st_size for p in apiindex.DATA.glob("*.json.gz")) < 3_000_000


def test_index_records_what_the_bundle_sources_say():
    idx = load("0.19.0")
    box = idx.models["Physics3D.Geometries.Box"]
    assert box["k"] == "m" and box["f"] == "Physics3D/Geometries/Box.openplx"
    src = (bundle_root() / box["f"]).read_text().splitlines()
    assert src[box["l"] - 1].startswith("Box is ")
    size = idx.all_attrs("Physics3D.Geometries.Box")["size"]
    assert size[0] == "Math.Vec3"
    assert src[size[2] - 1].strip().startswith("size is Math.Vec3")
    # inherited attributes come through bases
    assert idx.declaring("Physics3D.Interactions.Hinge", "connectors") is not None
    assert "Physics.Interactions.Interaction" in idx.ancestors("Physics3D.Interactions.Hinge")
    old = load("0.18.10")
    assert old.all_attrs("Physics.Interactions.Interaction")["charges"][0] == "Physics.Charges.Charge[]"
    assert "connectors" not in old.all_attrs("Physics.Interactions.Interaction")
    assert old.models["Math.Vec3"]["fn"]["cross"] == "fn cross(rhs: Math.Vec3) -> Math.Vec3"
    assert "kinematically_controlled" in idx.models["Physics3D.System"]["dep"]


def test_installed_bundles_reindex_to_the_stored_bytes(tmp_path):
    """Regenerating 0.19.0 from the installed openplx-bundles gives the committed file, byte for byte."""
    mod = _script()
    data = mod.index_folder(bundle_root(), "0.19.0")
    first = mod.write_index(data, tmp_path / "a").read_bytes()
    assert first == mod.write_index(data, tmp_path / "b").read_bytes()
    assert first == (apiindex.DATA / "0.19.0.json.gz").read_bytes()  # written by another run, from the wheel
    assert json.loads(gzip.decompress(first))["models"] == load("0.19.0").models


def test_where_defined_names_the_versions_that_have_a_name():
    charges_box = where_defined("Physics3D.Charges.Box")
    geometries_box = where_defined("Physics3D.Geometries.Box")
    assert charges_box and geometries_box
    assert charges_box[-1] == "0.18.10" and geometries_box[0] == "0.18.11"
    assert not set(charges_box) & set(geometries_box)
    for v in charges_box:
        assert "Physics3D.Charges.Box" in load(v).models
    # attributes, inherited ones included
    charges = where_defined("Physics3D.Interactions.Hinge.charges")
    assert charges[-1] == "0.18.10" and where_defined("Physics3D.Interactions.Hinge.connectors")[0] == "0.18.11"
    assert where_defined("No.Such.Model") == []
    assert spans(geometries_box) == "0.18.11-0.19.0"


def test_unknown_version_is_a_clear_error():
    with pytest.raises(UnknownVersion, match="0.15.0 to 0.19.0"):
        load("0.20.1")


def test_names_summary_matches_the_version_files():
    """names.json.gz (what where_defined reads) is exactly what the version files say."""
    with gzip.open(apiindex.NAMES, "rb") as fh:
        stored = json.loads(fh.read())
    assert stored == apiindex.build_names(), "run `python scripts/build_api_index.py --names-only`"
    for q in ("Physics3D.Charges.Box", "Physics.Interactions.Interaction.charges", "Terrain.Shovel.tooth_direction"):
        direct = [v for v in versions() if q in load(v).models
                  or (q.rpartition(".")[0] in load(v).models and q.rpartition(".")[2] in load(v).all_attrs(q.rpartition(".")[0]))]
        assert where_defined(q) == direct and direct
