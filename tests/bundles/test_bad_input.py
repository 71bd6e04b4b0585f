"""Bad bundle setups: one clear message naming the thing, exit 2, never a traceback."""

from __future__ import annotations

from pathlib import Path

from tests.bundles.conftest import offline_env
from tests.conftest import run_plx


def _write(p: Path, text: str) -> Path:
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text, encoding="utf-8")
    return p


def _model(tmp_path: Path) -> Path:
    return _write(tmp_path / "proj" / "m.openplx", "B is Physics3D.Bodies.RigidBody\n")


def _fails_cleanly(r, *needles: str) -> None:
    assert r.returncode == 2, (r.returncode, r.stdout, r.stderr)
    assert "Traceback" not in r.stderr and "internal error" not in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    for n in needles:
        assert n in r.stderr, (n, r.stderr)
    assert "All checks passed" not in r.stdout


def test_bundle_path_that_does_not_exist(tmp_path):
    m = _model(tmp_path)
    _fails_cleanly(run_plx("lint", str(m), "--bundle-path", str(tmp_path / "nowhere")), "nowhere", "does not exist",
                   "--bundle-path")
    _write(tmp_path / "proj" / "plx.toml", 'bundle-path = ["../agx"]\n')
    _fails_cleanly(run_plx("lint", str(m)), "agx", "does not exist", "plx.toml")
    _fails_cleanly(run_plx("check", str(m)), "agx", "does not exist")


def test_folder_with_two_bundles_of_one_name(tmp_path):
    for sub in ("a", "b"):
        _write(tmp_path / "lib" / sub / "config.openplx", 'config is BundleConfig:\n    name: "Parts"\n')
    _fails_cleanly(run_plx("lint", str(_model(tmp_path)), "--bundle-path", str(tmp_path / "lib")),
                   "two bundles are named 'Parts'", "a/config.openplx", "b/config.openplx")


def test_version_not_on_the_registry(tmp_path):
    r = run_plx("lint", str(_model(tmp_path)), "--openplx-version", "0.17.99",
                env={"PLX_CACHE_DIR": str(tmp_path / "cache")})
    # with a network: "not on the package index"; without one the network message (its own test)
    _fails_cleanly(r, "0.17.99")
    assert "not on the package index" in r.stderr or "cannot be reached" in r.stderr


def test_not_a_version(tmp_path):
    _fails_cleanly(run_plx("lint", str(_model(tmp_path)), "--openplx-version", "latest"), "'latest'", "0.17.26")
    _write(tmp_path / "proj" / "plx.toml", "openplx-version = 17\n")
    _fails_cleanly(run_plx("lint", str(tmp_path / "proj")), "plx.toml", "openplx-version")


def test_no_network(tmp_path):
    r = run_plx("lint", str(_model(tmp_path)), "--openplx-version", "0.16.3", env=offline_env(tmp_path / "cache"))
    _fails_cleanly(r, "0.16.3", "cannot be reached", "--openplx-version")
    r2 = run_plx("bundles", "install", "0.16.3", env=offline_env(tmp_path / "cache"))
    _fails_cleanly(r2, "0.16.3", "cannot be reached")


def test_corrupt_wheel_in_the_cache(tmp_path):
    cache = tmp_path / "cache"
    wheel = _write(cache / "plxtools" / "wheels" / "openplx_bundles-0.16.3-py3-none-any.whl", "not a zip file")
    r = run_plx("lint", str(_model(tmp_path)), "--openplx-version", "0.16.3", env=offline_env(cache))
    _fails_cleanly(r, str(wheel), "corrupt", "removed", "cannot be reached")
    assert not wheel.exists()  # the next run with a network fetches a fresh one
    assert not (cache / "plxtools" / "bundles" / "0.16.3").exists()  # nothing half-unpacked


def test_config_openplx_pins_a_version_plx_cannot_get(tmp_path):
    bot = tmp_path / "proj" / "MyBot"
    _write(bot / "config.openplx", 'config is BundleConfig:\n    name: "MyBot"\n'
                                   '    dependencies: ["Physics3D@0.16.3"]\n')
    _write(bot / "Arm.openplx", "Arm is Physics3D.Bodies.RigidBody\n")
    r = run_plx("lint", str(tmp_path / "proj"), env=offline_env(tmp_path / "cache"))
    _fails_cleanly(r, "0.16.3", f"{bot / 'config.openplx'}:3:20", "pinned by")


def test_lint_show_settings_with_no_bundle_error(tmp_path):
    r = run_plx("bundles")
    assert r.returncode == 2 and "install" in r.stdout
