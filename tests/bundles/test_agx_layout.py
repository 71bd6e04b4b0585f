"""Where an AGX installation keeps its OpenPLX bundles (issue 29, point 2): the documented places
first (`<AGX_DIR>/openplxbundles`, `data/openplx/agxBundle`), the search as the fallback. Every
installation here is a fake tree built by the test."""

from __future__ import annotations

import shutil

from plxtools.model.agx import find_agx
from tests.bundles.agx_fake import documented_agx, write
from tests.conftest import bundle_root, run_plx

NO_AGX = {"AGX_DIR": "", "AGX_DATA_DIR": "", "AGX_PLUGIN_PATH": "", "OPENPLX_BUNDLE_PATH": ""}
USES_AGX = "Scene is Physics3D.System:\n    cable is AGX.Cable\n    tracks is Vehicles.TrackSystem\n"


def test_the_documented_folders_come_before_the_search(tmp_path):
    root = tmp_path / "AGX-2.42.0.0"
    bundles = documented_agx(root)
    # a decoy the search would meet first: another copy of the bundles, one level deep, sorted first
    for name in ("Math", "Physics"):
        shutil.copytree(bundle_root() / name, root / "aaa" / name, ignore=shutil.ignore_patterns("__pycache__"))
    found = find_agx(env={"AGX_DIR": str(root)}, usual=[])
    assert found is not None and found.bundles == bundles.resolve(), found
    assert found.openplx_version == "0.20.1" and found.agx_bundle == (root / "data" / "openplx" / "agxBundle").resolve()


def test_each_variable_of_the_setup_script_finds_the_same_installation(tmp_path):
    root = tmp_path / "AGX-2.42.0.0"
    bundles = documented_agx(root)
    for var, value in (("AGX_DIR", root), ("AGX_DATA_DIR", root / "data"), ("AGX_PLUGIN_PATH", root / "bin" / "plugins")):
        found = find_agx(env={var: str(value)}, usual=[])
        assert found is not None and found.root == root.resolve() and found.bundles == bundles.resolve(), (var, found)
        assert found.why == var and found.agx_bundle is not None


def test_the_agx_bundle_is_loaded_with_the_official_ones_and_reported(tmp_path):
    root = tmp_path / "AGX-2.42.0.0"
    bundles = documented_agx(root)
    scene = write(tmp_path / "proj" / "scene.openplx", USES_AGX)
    env = {**NO_AGX, "AGX_DATA_DIR": str(root / "data")}
    r = run_plx("lint", str(scene), env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    s = run_plx("lint", str(scene), "--show-settings", env=env)
    assert f"official bundles: 0.20.1 from {bundles.resolve()}" in s.stdout, s.stdout
    agx_bundle = (root / "data" / "openplx" / "agxBundle").resolve()
    assert f"bundle folder: {agx_bundle} (AGX's own bundle; AGX 2.42.0.0 at {root.resolve()}" in s.stdout, s.stdout
    # the installation found but not used: no AGX bundle either, and AGX.Cable is unknown
    write(tmp_path / "proj" / "plx.toml", 'openplx-version = "0.19.0"\n')
    n = run_plx("lint", str(scene), "--show-settings", env=env)
    assert str(agx_bundle) not in n.stdout.split("bundle  ")[0] and "(found, not used" in n.stdout, n.stdout


def test_usual_folders_match_every_spelling_of_the_release_folder(tmp_path):
    """Older Linux packages install into /opt/Algoryx/AgX-x.y.z.w, Windows ones into agx-x.y.z.w."""
    base = tmp_path / "Algoryx"
    documented_agx(base / "AgX-2.25.0.1", openplx="0.15.0")
    documented_agx(base / "agx-2.21.0.0", openplx="0.15.0")
    found = find_agx(env={}, usual=[str(base / "AGX-*")])
    assert found is not None and found.agx_version == "2.25.0.1", found
    documented_agx(base / "AGX-2.42.2.1")
    assert find_agx(env={}, usual=[str(base / "AGX-*")]).agx_version == "2.42.2.1"
