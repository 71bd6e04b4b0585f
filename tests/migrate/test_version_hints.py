"""An unknown name that exists in another official version says so (issue 12 item 6)."""

from __future__ import annotations

import json

from plxtools.model.apiindex import where_defined
from tests.conftest import plx_here, run_plx


def test_a_removed_type_of_an_older_version_names_the_versions_that_have_it(tmp_path):
    f = tmp_path / "old.openplx"
    f.write_text("Scene is Physics3D.System:\n    s is Sensors.ForceTorqueSensor\n", encoding="utf-8")
    [d] = json.loads(run_plx("lint", "--output-format", "json", str(f)).stdout)
    assert d["code"] == "N001"
    have = where_defined("Sensors.ForceTorqueSensor")
    assert have and "0.19.0" not in have  # the index says it was removed before 0.19.0
    assert f"exists in OpenPLX {have[0]}-" in d["help"] and "plx migrate --explain" in d["help"]
    assert have[-1] in d["help"]


def test_a_plain_typo_gets_no_version_note(tmp_path):
    f = tmp_path / "typo.openplx"
    f.write_text("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBdy\n", encoding="utf-8")
    [d] = json.loads(run_plx("lint", "--output-format", "json", str(f)).stdout)
    assert d["code"] == "N001" and "exists in OpenPLX" not in (d["help"] or "")


OLD_STYLE = """\
Scene is Physics3D.System:
    a is Physics3D.Bodies.RigidBody:
        geometry is Physics3D.Charges.Box:  # written for 0.17
            size: {1, 1, 1}
        top is Physics3D.Charges.MateConnector
    b is Physics3D.Bodies.RigidBody:
        top is Physics3D.Charges.MateConnector
    hinge is Physics3D.Interactions.Hinge:
        charges: [a.top, b.top]
"""


def test_renamed_models_are_u001_with_a_safe_fix_and_attributes_u002_with_an_unsafe_one(tmp_path):
    f = tmp_path / "scene.openplx"
    f.write_text(OLD_STYLE, encoding="utf-8")
    diags = json.loads(run_plx("lint", "--output-format", "json", str(f)).stdout)
    assert [d["code"] for d in diags] == ["U001", "U001", "U001", "U002"], diags
    assert diags[0]["fix"]["applicability"] == "safe" and diags[3]["fix"]["applicability"] == "unsafe"
    assert "Physics3D.Geometries.Box" in diags[0]["message"] and "'connectors'" in diags[3]["message"]
    run_plx("lint", "--fix", str(f))
    assert "Physics3D.Charges" not in f.read_text(encoding="utf-8")
    assert "charges:" in f.read_text(encoding="utf-8")  # unsafe: only on request
    r = run_plx("lint", "--fix", "--unsafe-fixes", str(f))
    assert r.returncode == 0, r.stdout
    assert "connectors: [a.top, b.top]" in f.read_text(encoding="utf-8")
    assert "# written for 0.17" in f.read_text(encoding="utf-8")


def test_the_renamed_attribute_table_from_the_cache_folder_gives_the_same_hints(tmp_path, warm_cache):
    """U002's table is composed once and kept in plx's cache folder: a run that reads it, one that
    writes it and one with --no-cache report the same."""
    f = tmp_path / "scene.openplx"
    f.write_text(OLD_STYLE, encoding="utf-8")
    env = {"PLX_CACHE_DIR": str(warm_cache)}  # a warm bundle program, no renames table yet
    first = run_plx("lint", "--output-format", "json", str(f), env=env).stdout
    assert list((tmp_path / "cache" / "plxtools" / "renames").glob("*")), "the table was not kept"
    (f.parent / "scene2.openplx").write_text(OLD_STYLE, encoding="utf-8")  # not a stored result
    second = run_plx("lint", "--output-format", "json", str(f.parent / "scene2.openplx"), env=env).stdout
    uncached = plx_here("lint", "--no-cache", "--output-format", "json", str(f), env=env).stdout
    assert [d["code"] for d in json.loads(first)][-1] == "U002"
    assert second.replace("scene2.openplx", "scene.openplx") == first == uncached
