"""Migrations that work as printed (issue 39): the version a file was written for inferred from its
content on an unpinned tree, lint's hint run exactly as printed, a migrate that changes nothing
while files fail, `--bundle-path`, `.brick` files and `AGX.*` names. The models are plxtools' own."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from tests.bundles.conftest import fetched  # noqa: F401 - the fixture that provides old versions
from tests.conftest import plx_here, run_plx

ERA_017 = {
    "frame.openplx": """\
# A small 0.17-era tree written for plxtools' tests: a frame with two plates on a hinge.
Frame is Physics3D.System:
    base is Physics3D.Bodies.RigidBody:
        shape is Physics3D.Charges.Box:
            size: Math.Vec3.from_xyz(0.4, 0.4, 0.05)
        pivot is Physics3D.Charges.MateConnector:
            position: Math.Vec3.from_xyz(0, 0, 0.05)
    plate is Physics3D.Bodies.RigidBody:
        shape is Physics3D.Charges.Box:
            size: Math.Vec3.from_xyz(0.3, 0.05, 0.3)
        pivot is Physics3D.Charges.MateConnector
    joint is Physics3D.Interactions.Hinge:
        charges: [base.pivot, plate.pivot]
""",
    "wheel.openplx": """\
# A wheel on a spinning motor, 0.17-era names.
Wheel is Physics3D.System:
    hub is Physics3D.Bodies.RigidBody:
        rim is Physics3D.Charges.Cylinder:
            radius: 0.3
            height: 0.1
        axle is Physics3D.Charges.MateConnector
    ground is Physics3D.Bodies.RigidBody:
        axle is Physics3D.Charges.MateConnector
    spin is Physics3D.Interactions.RotationalVelocityMotor:
        charges: [hub.axle, ground.axle]
        target_speed: 2.0
""",
    "notes.openplx": """\
# Clean under every version: nothing to infer or migrate here.
Notes is Physics3D.System:
    block is Physics3D.Bodies.RigidBody
""",
}

HINT = re.compile(r"`(plx migrate [^`]+)`")


def _tree(tmp_path: Path, files: dict[str, str]) -> Path:
    tmp_path.mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    return tmp_path


def _run_hint(hint: str, cwd: Path):
    words = shlex.split(hint)
    assert words[:2] == ["plx", "migrate"], hint
    return plx_here(*words[1:], cwd=cwd)


def test_lints_hint_migrates_an_unpinned_0_17_tree_as_printed(tmp_path, fetched):  # noqa: F811
    fetched("0.18.10")
    root = _tree(tmp_path, ERA_017)
    lint = plx_here("lint", ".", cwd=root)
    assert lint.returncode == 1
    # the release inferred from the index is one the tree lints clean under (the index was enough)
    assert plx_here("lint", "--openplx-version", "0.18.10", ".", cwd=root).returncode == 0
    hints = {h for h in HINT.findall(lint.stdout) if "--explain" not in h}
    # no pin: plx infers the version, so the printed command needs no --from
    assert hints == {"plx migrate --to 0.19.0 frame.openplx", "plx migrate --to 0.19.0 wheel.openplx"}, lint.stdout
    for hint in sorted(hints):
        r = _run_hint(hint, root)
        assert r.returncode == 0, r.stderr
        assert "written for OpenPLX 0.18.10 (inferred from the file's content" in r.stderr
    after = plx_here("lint", ".", cwd=root)
    assert after.returncode == 0, after.stdout
    text = (root / "frame.openplx").read_text(encoding="utf-8")
    assert "connectors: [base.pivot, plate.pivot]" in text and "Physics3D.Geometries.Box" in text
    assert text.startswith("# A small 0.17-era tree")  # comments kept
    assert (root / "notes.openplx").read_text(encoding="utf-8") == ERA_017["notes.openplx"]


def test_show_settings_shows_the_inferred_version_per_file(tmp_path):
    root = _tree(tmp_path, ERA_017)
    r = plx_here("migrate", "--show-settings", "--to", "0.19.0", ".", cwd=root)
    assert r.returncode == 0, r.stderr
    lines = [ln for ln in r.stdout.splitlines() if ln.startswith("written for:")]
    assert [ln.split(":")[1].strip() for ln in lines] == ["frame.openplx", "wheel.openplx"], r.stdout
    assert all("OpenPLX 0.18.10 (inferred from the file's content" in ln for ln in lines)
    lint = plx_here("lint", "--show-settings", ".", cwd=root)  # lint shows the same inference
    assert [ln for ln in lint.stdout.splitlines() if ln.startswith("written for:")] == lines, lint.stdout


def test_a_pinned_tree_gets_a_hint_with_from_and_it_works(tmp_path, fetched):  # noqa: F811
    fetched("0.18.10")
    root = _tree(tmp_path, {"frame.openplx": ERA_017["frame.openplx"]})
    (root / "plx.toml").write_text('openplx-version = "0.19.0"\n', encoding="utf-8")
    lint = plx_here("lint", "frame.openplx", cwd=root)
    hints = {h for h in HINT.findall(lint.stdout) if "--explain" not in h}
    assert hints == {"plx migrate --from 0.18.10 --to 0.19.0 frame.openplx"}, lint.stdout
    r = _run_hint(hints.pop(), root)
    assert r.returncode == 0, r.stderr
    assert plx_here("lint", "frame.openplx", cwd=root).returncode == 0


def test_a_migrate_that_changes_nothing_while_files_fail_exits_1_and_says_why(tmp_path):
    root = _tree(tmp_path, {"typo.openplx": "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBdy\n"})
    r = plx_here("migrate", "--to", "0.19.0", "typo.openplx", cwd=root)
    assert r.returncode == 1, r.stderr
    assert "nothing was migrated, but typo.openplx still has 1 error under 0.19.0" in r.stderr
    assert "--from VERSION" in r.stderr
    assert (root / "typo.openplx").read_text(encoding="utf-8").endswith("RigidBdy\n")


def test_a_clean_tree_migrates_to_its_own_version_with_exit_0(tmp_path):
    root = _tree(tmp_path, {"notes.openplx": ERA_017["notes.openplx"]})
    r = plx_here("migrate", "--to", "0.19.0", ".", cwd=root)
    assert r.returncode == 0 and "Migrated 0 files (0 changes); 1 file unchanged." in r.stderr


def test_the_inference_reads_nothing_for_a_file_without_version_sensitive_errors():
    from plxtools.diagnostics import EMPTY_SPAN
    from plxtools.model import facts
    from plxtools.model.written_for import infer

    # (the model's facts: a type mismatch, then an unknown type)
    other = [facts.TypeMismatch(EMPTY_SPAN, "Real", "String")]
    assert infer("x is Physics3D.Charges.Box\n", other, [], "0.19.0") is None
    unknown = [facts.UnknownType(EMPTY_SPAN, "Physics3D.Charges.Box")]
    got = infer("x is Physics3D.Charges.Box\n", unknown, [], "0.19.0")
    assert got is not None and got.version == "0.18.10" and got.missing == 0 and got.missing_in_use == 1
    # migrating to 0.18.5, the file is taken as written for 0.18.5 (it fits it as well): nothing to do
    assert got.newest_fit("0.18.5") == "0.18.5" and got.newest_fit("0.19.0") == "0.18.10"
    assert got.fits[0] == "0.15.0"


def test_bundle_path_is_used_by_both_ends(tmp_path, fetched):  # noqa: F811
    fetched("0.18.10")
    shelf = tmp_path / "lib" / "Shelf"
    shelf.mkdir(parents=True)
    (shelf / "config.openplx").write_text('config:\n    name: "Shelf"\n    version: "1.0"\n'
                                          '    dependencies: ["Physics3D"]\n', encoding="utf-8")
    (shelf / "Board.openplx").write_text("Board is Physics3D.Bodies.RigidBody\n", encoding="utf-8")
    models = tmp_path / "models"
    models.mkdir()
    (models / "rack.openplx").write_text(
        "Rack is Physics3D.System:\n    board is Shelf.Board:\n        shape is Physics3D.Charges.Box\n",
        encoding="utf-8")
    without = plx_here("migrate", "--from", "0.18.10", "--to", "0.19.0", "models", cwd=tmp_path)
    assert "N001 unknown type 'Shelf.Board'" in without.stderr  # the bundle is not loaded: left for a person
    (models / "rack.openplx").write_text(
        "Rack is Physics3D.System:\n    board is Shelf.Board:\n        shape is Physics3D.Charges.Box\n",
        encoding="utf-8")
    r = plx_here("migrate", "--bundle-path", "lib", "--from", "0.18.10", "--to", "0.19.0", "models", cwd=tmp_path)
    assert r.returncode == 0 and "Shelf.Board" not in r.stderr, r.stderr
    assert "Physics3D.Geometries.Box" in (models / "rack.openplx").read_text(encoding="utf-8")
    assert plx_here("lint", "--bundle-path", "lib", "models", cwd=tmp_path).returncode == 0


BRICK = """\
# A model of before OpenPLX 0.15 (plxtools' own), with the old extension.
Old is Physics3D.System:
    body is Physics3D.Bodies.RigidBody:
        shape is Physics3D.Charges.Box:
            size: Math.Vec3.fromXYZ(1, 2, 3)
    gear is DriveTrain.Gear
"""


def test_a_brick_file_gets_the_renames_before_0_15_then_the_migration_and_its_extension(tmp_path,
                                                                                    fetched):  # noqa: F811
    fetched("0.15.0")
    (tmp_path / "sub").mkdir()
    old = tmp_path / "sub" / "old.brick"
    old.write_text(BRICK, encoding="utf-8")
    r = plx_here("migrate", "--to", "0.19.0", ".", cwd=tmp_path)  # found in the folder
    assert r.returncode == 0, r.stderr
    assert "migrated sub/old.brick (3 changes, before 0.15 -> 0.19.0, as old.openplx)" in r.stderr
    # 0.13.2 renamed DriveTrain.Gear, but 0.15 has one again: a person decides
    assert "'DriveTrain.Gear' is written here" in r.stderr and "check which one is meant" in r.stderr
    new = tmp_path / "sub" / "old.openplx"
    assert not old.exists() and new.is_file()
    text = new.read_text(encoding="utf-8")
    assert "Math.Vec3.from_xyz(1, 2, 3)" in text and "Physics3D.Geometries.Box" in text
    assert "gear is DriveTrain.Gear" in text and text.startswith("# A model of before OpenPLX 0.15")
    assert plx_here("lint", str(new)).returncode == 0


def test_a_brick_file_whose_openplx_name_is_taken_is_refused_with_a_located_line(tmp_path, fetched):  # noqa: F811
    fetched("0.15.0")
    (tmp_path / "old.brick").write_text(BRICK, encoding="utf-8")
    (tmp_path / "old.openplx").write_text("Other is Physics3D.System\n", encoding="utf-8")
    r = plx_here("migrate", "--to", "0.19.0", "old.brick", cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    assert re.search(r"^old\.brick:1:1: not migrated: old\.openplx already exists", r.stderr, re.M), r.stderr
    assert (tmp_path / "old.brick").read_text(encoding="utf-8") == BRICK
    assert (tmp_path / "old.openplx").read_text(encoding="utf-8") == "Other is Physics3D.System\n"


@pytest.mark.parametrize("env", [{"AGX_DIR": "", "AGX_DATA_DIR": "", "AGX_PLUGIN_PATH": ""}])
def test_agx_names_say_where_agxs_bundle_comes_from(tmp_path, env):
    f = tmp_path / "a.openplx"
    f.write_text("Scene is Physics3D.System:\n    t is AGX.Something\n", encoding="utf-8")
    (tmp_path / "plx.toml").write_text('agx-dir = ""\n', encoding="utf-8")
    r = plx_here("lint", str(f), env=env)
    assert "N001" in r.stdout and "ships with an AGX installation" in r.stdout and "--bundle-path" in r.stdout


def test_an_inferred_release_that_cannot_be_fetched_stops_the_run_before_any_write(tmp_path, warm_cache):
    from tests.bundles.conftest import offline_env

    root = _tree(tmp_path / "tree", ERA_017)
    # a warm 0.19.0 program, no other release in the cache, and no network
    r = run_plx("migrate", "--to", "0.19.0", ".", cwd=root, env={**offline_env(warm_cache), "PIP_NO_INDEX": "1"})
    assert r.returncode == 2, r.stderr
    assert "frame.openplx: written for OpenPLX 0.18.10" in r.stderr and "whose bundles plx cannot load" in r.stderr
    assert "pass --from VERSION" in r.stderr
    assert all((root / n).read_text(encoding="utf-8") == t for n, t in ERA_017.items())
