"""`plx migrate` between an AGX installation's bundles and openplx-bundles releases (issue 29,
points 1 and 3). Every installation is a fake tree built here: a real release's bundles copied
into an AGX-x.y.z.w folder, relabelled or changed the way a newer OpenPLX might change them."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.bundles.agx_fake import agx_copy_of, write
from tests.bundles.conftest import fetched  # noqa: F401 - the fixture that provides old versions
from tests.conftest import bundle_root, run_plx
from tests.migrate.test_migrate_files import NEW, OLD

NO_AGX = {"AGX_DIR": "", "AGX_DATA_DIR": "", "AGX_PLUGIN_PATH": "", "OPENPLX_BUNDLE_PATH": ""}
OLD_HOME = "Physics3D.Interactions.Toughness.HingeThresholdFracture"
NEW_HOME = "Physics3D.Interactions.Fracture.HingeThresholdFracture"
USES_FRACTURE = f"Scene is Physics3D.System:\n    fracture is {OLD_HOME}\n"


def newer_agx(root: Path) -> Path:
    """AGX 2.42 with OpenPLX 0.20.1: the 0.19.0 bundles relabelled, one model moved to another
    namespace (Toughness -> Fracture), as a newer OpenPLX might do."""
    bundles = agx_copy_of(bundle_root(), root)
    for cfg in bundles.glob("*/config.openplx"):
        cfg.write_text(cfg.read_text(encoding="utf-8").replace("0.19.0", "0.20.1"), encoding="utf-8")
    old = bundles / "Physics3D" / "Interactions" / "Toughness" / "HingeThresholdFracture.openplx"
    text = old.read_text(encoding="utf-8").replace(
        "HingeThresholdFracture is DefaultHingeToughness:",
        "HingeThresholdFracture is Physics3D.Interactions.Toughness.DefaultHingeToughness:")
    write(bundles / "Physics3D" / "Interactions" / "Fracture" / "HingeThresholdFracture.openplx", text)
    old.unlink()
    return bundles


@pytest.fixture(scope="module")
def agx_242(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("opt") / "AGX-2.42.0.0"
    newer_agx(root)
    return root


def test_a_release_migrates_to_the_agx_bundles(tmp_path, agx_242):
    env = {**NO_AGX, "AGX_DIR": str(agx_242)}
    f = write(tmp_path / "proj" / "scene.openplx", USES_FRACTURE)
    write(tmp_path / "proj" / "plx.toml", 'openplx-version = "0.19.0"\n')
    s = run_plx("migrate", "--to", "0.20.1", "--show-settings", str(f), env=env)
    assert s.returncode == 0, s.stderr
    assert f"migrate from: OpenPLX 0.19.0 (openplx-version in {tmp_path / 'proj' / 'plx.toml'})" in s.stdout, s.stdout
    assert "(found, not used" in s.stdout
    assert (f"migrate to: OpenPLX 0.20.1 (--to; AGX 2.42.0.0 at {agx_242.resolve()}, OpenPLX 0.20.1 (AGX_DIR))"
            in s.stdout), s.stdout
    assert "(in use: its bundles are the official bundles)" in s.stdout
    assert f.read_text(encoding="utf-8") == USES_FRACTURE  # --show-settings migrates nothing
    r = run_plx("migrate", "--to", "0.20.1", str(f), env=env)
    assert r.returncode == 0, r.stderr
    assert "(1 change, 0.19.0 -> 0.20.1 (AGX 2.42.0.0))" in r.stderr, r.stderr
    assert f.read_text(encoding="utf-8") == USES_FRACTURE.replace(OLD_HOME, NEW_HOME)
    lint = run_plx("lint", "--openplx-version", "0.20.1", str(f), env=env)
    assert lint.returncode == 0, lint.stdout + lint.stderr


def test_the_agx_bundles_in_use_migrate_to_a_release(tmp_path, fetched):  # noqa: F811
    """AGX 2.38 shipping OpenPLX 0.17.26: with AGX_DIR set, lint uses its bundles, so migrate starts
    from them without --from and reaches the 0.19.0 release."""
    agx = tmp_path / "AGX-2.38.0.0"
    agx_copy_of(fetched("0.17.26"), agx)
    env = {**NO_AGX, "AGX_DIR": str(agx)}
    f = write(tmp_path / "proj" / "pendulum.openplx", OLD)
    lint = run_plx("lint", str(f), env=env)
    assert lint.returncode == 0, lint.stdout  # the old names are fine under AGX's bundles
    r = run_plx("migrate", "--to", "0.19.0", str(f), env=env)
    assert r.returncode == 0, r.stderr
    assert "(4 changes, 0.17.26 (AGX 2.38.0.0) -> 0.19.0)" in r.stderr, r.stderr
    assert f.read_text(encoding="utf-8") == NEW
    assert run_plx("lint", "--openplx-version", "0.19.0", str(f), env=env).returncode == 0


def test_going_back_or_to_a_version_nobody_has_is_a_message_that_says_what_to_pass(tmp_path, agx_242):
    env = {**NO_AGX, "AGX_DIR": str(agx_242)}
    text = "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n"
    f = write(tmp_path / "scene.openplx", text)
    back = run_plx("migrate", "--to", "0.19.0", str(f), env=env)
    assert back.returncode == 2 and "Traceback" not in back.stderr, back.stderr
    assert back.stderr.startswith(f"plx migrate: {f}: written for OpenPLX 0.20.1 (AGX 2.42.0.0 at {agx_242.resolve()}")
    assert "only moves forward): pass --to 0.20.1 or newer, or --from VERSION" in back.stderr
    later = run_plx("migrate", "--to", "0.21.0", str(f), env=env)
    assert later.returncode == 2 and later.stderr.count("\n") == 1, later.stderr
    assert f"the AGX installation found, AGX 2.42.0.0 at {agx_242.resolve()} (AGX_DIR), has OpenPLX 0.20.1" \
        in later.stderr
    none = run_plx("migrate", "--from", "0.19.0", "--to", "0.20.1", str(f), env=NO_AGX)
    assert none.returncode == 2 and "no AGX installation found: set AGX_DIR" in none.stderr, none.stderr
    assert f.read_text(encoding="utf-8") == text
    # the same file, from 0.19.0 to AGX's 0.20.1: nothing to change, and said so
    same = run_plx("migrate", "--from", "0.19.0", "--to", "0.20.1", "--check", str(f), env=env)
    assert same.returncode == 0 and "0 files (0 changes); 1 file unchanged" in same.stderr, same.stderr


@pytest.mark.parametrize("command", [("lint",), ("check",), ("migrate", "--to", "0.20.1")])
def test_show_settings_names_the_agx_installation_and_the_openplx_version(tmp_path, agx_242, command):
    f = write(tmp_path / "scene.openplx", "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n")
    s = run_plx(*command, "--show-settings", str(f), env={**NO_AGX, "AGX_DIR": str(agx_242)})
    assert s.returncode == 0, s.stderr
    bundles = (agx_242 / "data" / "openplx").resolve()
    assert f"official bundles: 0.20.1 from {bundles} (" in s.stdout, s.stdout
    assert (f"AGX: AGX 2.42.0.0 at {agx_242.resolve()}, OpenPLX 0.20.1 (AGX_DIR) (in use: its bundles are the "
            "official bundles)") in s.stdout, s.stdout
    without = [("0.19.0" if a == "0.20.1" else a) for a in command]  # migrate: to what plx can load then
    n = run_plx(*without, "--show-settings", str(f), env=NO_AGX)
    assert "official bundles: 0.19.0 from" in n.stdout and "AGX: none found (AGX_DIR" in n.stdout, n.stdout + n.stderr


def test_the_live_index_of_a_release_copy_equals_the_stored_one(tmp_path):
    """The run-time index of bundles in no release is built by the same code as the stored index:
    AGX's copy of 0.19.0 indexed now equals plx's stored 0.19.0."""
    from plxtools.model.apiindex import load
    from plxtools.model.apiindex.build import index_folder

    copy = tmp_path / "copy"
    shutil.copytree(bundle_root(), copy, ignore=shutil.ignore_patterns("__pycache__", "*.py"))
    assert index_folder(copy, "0.19.0")["models"] == load("0.19.0").models


def test_agx_dir_in_the_config_is_the_installation_migrate_uses(tmp_path, agx_242):
    proj = tmp_path / "proj"
    f = write(proj / "scene.openplx", USES_FRACTURE)
    write(proj / "plx.toml", f'openplx-version = "0.19.0"\nagx-dir = "{agx_242.as_posix()}"\n')
    r = run_plx("migrate", "--to", "0.20.1", str(f), env=NO_AGX)
    assert r.returncode == 0, r.stderr
    assert f.read_text(encoding="utf-8") == USES_FRACTURE.replace(OLD_HOME, NEW_HOME)


def test_explain_lists_the_changes_up_to_the_agx_bundles(agx_242):
    env = {**NO_AGX, "AGX_DIR": str(agx_242)}
    r = run_plx("migrate", "--explain", "0.19.0", "0.20.1", env=env)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("OpenPLX API changes from 0.19.0 to 0.20.1 (AGX 2.42.0.0)"), r.stdout
    assert f"{OLD_HOME} -> {NEW_HOME}  [0.20.1]" in r.stdout
    back = run_plx("migrate", "--explain", "0.20.1", "0.19.0", env=env)
    assert back.returncode == 2 and "forward only" in back.stderr and back.stderr.count("\n") == 1
    none = run_plx("migrate", "--explain", "0.19.0", "0.20.1", env=NO_AGX)
    assert none.returncode == 2 and "no AGX installation found" in none.stderr


def _official_line(text: str) -> str:
    return next(line.strip() for line in text.splitlines() if line.strip().startswith("official bundles:"))


@pytest.mark.parametrize("setup", ["agx", "config", "pin", "nothing"])
def test_migrate_starts_from_the_bundles_lint_uses(tmp_path, agx_242, setup):
    """One rule: the source end of `plx migrate` is the bundle set `plx lint` reports for the same
    files, whatever chooses it (an AGX installation, the config, a dependency's version, nothing)."""
    proj = tmp_path / "proj"
    write(proj / "scene.openplx", "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n")
    env = {**NO_AGX, "AGX_DIR": str(agx_242)} if setup != "nothing" else NO_AGX
    if setup == "config":
        write(proj / "plx.toml", 'openplx-version = "0.19.0"\n')
    if setup == "pin":
        write(proj / "Bot" / "config.openplx",
              'config is BundleConfig:\n    name: "Bot"\n    dependencies: ["Physics3D==0.20.1"]\n')
    lint = run_plx("lint", "--show-settings", str(proj), env=env)
    mig = run_plx("migrate", "--to", "0.19.0" if setup == "nothing" else "0.20.1", "--show-settings", str(proj), env=env)
    assert lint.returncode == 0 and mig.returncode == 0, lint.stderr + mig.stderr
    assert _official_line(mig.stdout.split("migrate to:")[0]) == _official_line(lint.stdout), mig.stdout + lint.stdout
