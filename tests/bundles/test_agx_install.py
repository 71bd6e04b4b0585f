"""An AGX installation is found without configuration, used, reported, and pointed at by the
unknown-name help (issue 29, point 2). Every installation here is a fake tree built by the test."""

from __future__ import annotations

from plxtools.model.agx import find_agx
from tests.bundles.agx_fake import fake_agx
from tests.bundles.agx_fake import write as _write
from tests.conftest import run_plx

SCENE = "Scene is Physics3D.System:\n    tracks is Vehicles.TrackSystem\n"
NO_AGX = {"AGX_DIR": "", "AGX_DATA_DIR": "", "AGX_PLUGIN_PATH": "", "OPENPLX_BUNDLE_PATH": ""}


def test_agx_dir_is_found_used_and_reported(tmp_path):
    agx = tmp_path / "Algoryx" / "AGX-2.42.0.0"
    bundles = fake_agx(agx)
    scene = _write(tmp_path / "proj" / "scene.openplx", SCENE)
    env = {**NO_AGX, "AGX_DIR": str(agx)}
    r = run_plx("lint", str(scene), env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    s = run_plx("lint", str(scene), "--show-settings", env=env)
    assert f"official bundles: 0.20.1 from {bundles.resolve()}" in s.stdout, s.stdout
    assert f"AGX: AGX 2.42.0.0 at {agx.resolve()}, OpenPLX 0.20.1 (AGX_DIR)" in s.stdout, s.stdout
    # the data folder AGX's setup script exports finds the same installation
    d = run_plx("lint", str(scene), "--show-settings", env={**NO_AGX, "AGX_DATA_DIR": str(agx / "data")})
    assert f"AGX 2.42.0.0 at {agx.resolve()}, OpenPLX 0.20.1 (AGX_DATA_DIR)" in d.stdout, d.stdout
    # without it, the installed bundles, and the help says newer bundles are needed and how to get them
    lidar = _write(tmp_path / "proj" / "lidar.openplx", "Scene is Physics3D.System:\n    l is Sensors.LidarModel\n")
    n = run_plx("lint", str(lidar), env=NO_AGX)
    assert n.returncode == 1 and "N001" in n.stdout and "set AGX_DIR" in n.stdout, n.stdout


def test_config_overrides_the_installation_found(tmp_path):
    agx = tmp_path / "AGX-2.42.0.0"
    bundles = fake_agx(agx)
    other = tmp_path / "opt" / "AGX-2.43.1.0"
    fake_agx(other, openplx="0.21.0")
    proj = tmp_path / "proj"
    scene = _write(proj / "scene.openplx", SCENE)
    env = {**NO_AGX, "AGX_DIR": str(agx)}
    _write(proj / "plx.toml", f'agx-dir = "{other.as_posix()}"\n')
    s = run_plx("lint", str(scene), "--show-settings", env=env)
    assert "AGX 2.43.1.0" in s.stdout and "OpenPLX 0.21.0 (agx-dir in the configuration)" in s.stdout, s.stdout
    _write(proj / "plx.toml", 'agx-dir = ""\n')
    s = run_plx("lint", str(scene), "--show-settings", env=env)
    assert "AGX: none found" in s.stdout and "official bundles: 0.19.0" in s.stdout, s.stdout
    _write(proj / "plx.toml", 'openplx-version = "0.19.0"\n')
    s = run_plx("lint", str(scene), "--show-settings", env=env)
    assert "official bundles: 0.19.0" in s.stdout and "(found, not used" in s.stdout, s.stdout
    r = run_plx("lint", str(scene), env=env)
    assert r.returncode == 1, r.stdout
    assert "AGX 2.42.0.0's bundles (OpenPLX 0.20.1" in r.stdout and str(bundles.resolve()) in r.stdout, r.stdout


def test_a_dependency_on_agxs_version_uses_agxs_bundles(tmp_path):
    agx = tmp_path / "AGX-2.42.0.0"
    bundles = fake_agx(agx)
    bot = tmp_path / "proj" / "Bot"
    _write(bot / "config.openplx", 'config is BundleConfig:\n    name: "Bot"\n    dependencies: ["Physics3D==0.20.1", '
                                   '"Vehicles"]\n')
    _write(bot / "Drive.openplx", "Drive is Vehicles.TrackSystem\n")
    s = run_plx("lint", str(bot), "--show-settings", env={**NO_AGX, "AGX_DIR": str(agx)})
    assert f"official bundles: 0.20.1 from {bundles.resolve()} (pinned by" in s.stdout, s.stdout
    r = run_plx("lint", str(bot), env={**NO_AGX, "AGX_DIR": str(agx)})
    assert r.returncode == 0, r.stdout + r.stderr


def test_the_agx_python_package_is_found_without_importing_it(tmp_path):
    agx = tmp_path / "AGX-2.42.0.0"
    fake_agx(agx)
    # importing it would fail: plx only asks where it is
    _write(agx / "lib" / "python" / "agx" / "__init__.py", "raise ImportError('native libraries missing')\n")
    scene = _write(tmp_path / "proj" / "scene.openplx", SCENE)
    s = run_plx("lint", str(scene), "--show-settings",
                env={**NO_AGX, "PYTHONPATH": str(agx / "lib" / "python")})
    assert "OpenPLX 0.20.1 (the agx Python package)" in s.stdout, s.stdout + s.stderr


def test_the_usual_install_folders_newest_release_first(tmp_path):
    for v in ("2.9.0.0", "2.42.0.0", "2.41.1.0"):
        fake_agx(tmp_path / "Algoryx" / f"AGX-{v}", layout="share/openplx/bundles")
    (tmp_path / "Algoryx" / "AGX-2.50.0.0").mkdir()  # no bundles in it: skipped
    found = find_agx(env={}, usual=[str(tmp_path / "Algoryx" / "AGX-*")])
    assert found is not None and found.agx_version == "2.42.0.0" and found.why == "a usual install folder"
    assert found.bundles == (tmp_path / "Algoryx" / "AGX-2.42.0.0" / "share" / "openplx" / "bundles").resolve()
    assert find_agx(env={}, usual=[str(tmp_path / "nothing" / "AGX-*")]) is None
