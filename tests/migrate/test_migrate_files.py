"""`plx migrate --to VERSION PATH...` on models written by us in the 0.17 style (issue 13)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.bundles.conftest import fetched  # noqa: F401 - the fixture that provides old versions
from tests.conftest import plx_here

OLD = """\
# a pendulum written for 0.17: charges became connectors, Charges became Geometries/Interactions
Battery:
    charges is Int: 3  # our own attribute called charges: not the mate's

Link is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Charges.Box:
        size: {0.1, 0.1, 1.0}
    inertia.mass: 1
    top is Physics3D.Charges.MateConnector:  # the pivot
        position: {0, 0, 0.5}
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}

Scene is Physics3D.System:
    battery is Battery
    link is Link
    world_top is Physics3D.Charges.MateConnector:
        position: {0, 0, 2}
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}
    hinge is Physics3D.Interactions.Hinge:
        charges: [link.top, world_top]
    count is Int: battery.charges
"""

NEW = (OLD.replace("Physics3D.Charges.Box", "Physics3D.Geometries.Box")
       .replace("Physics3D.Charges.MateConnector", "Physics3D.Interactions.MateConnector")
       .replace("        charges: [link.top", "        connectors: [link.top"))


@pytest.fixture
def old_model(tmp_path, fetched):  # noqa: F811
    fetched("0.17.26")
    f = tmp_path / "pendulum.openplx"
    f.write_text(OLD, encoding="utf-8")
    assert plx_here("lint", "--openplx-version", "0.17.26", str(f)).returncode == 0
    return f


def test_migrate_rewrites_moved_models_and_renamed_attributes_and_keeps_the_rest(old_model: Path):
    r = plx_here("migrate", "--from", "0.17.26", "--to", "0.19.0", str(old_model))
    assert r.returncode == 0, r.stderr
    assert old_model.read_text(encoding="utf-8") == NEW
    assert "4 changes" in r.stderr
    lint = plx_here("lint", "--openplx-version", "0.19.0", str(old_model))
    assert lint.returncode == 0, lint.stdout
    # the input was in the formatter's style, and so is the result
    assert plx_here("fmt", "--check", str(old_model)).returncode == 0
    again = plx_here("migrate", "--from", "0.19.0", "--to", "0.19.0", "--check", str(old_model))
    assert again.returncode == 0 and "0 files (0 changes)" in again.stderr
    fmt = plx_here("fmt", "--check", str(old_model))
    assert fmt.returncode in (0, 1) and "internal error" not in fmt.stderr


def test_diff_and_check_write_nothing(old_model: Path):
    d = plx_here("migrate", "--from", "0.17.26", "--to", "0.19.0", "--diff", str(old_model))
    assert d.returncode == 0 and "+        connectors: [link.top, world_top]" in d.stdout
    c = plx_here("migrate", "--from", "0.17.26", "--to", "0.19.0", "--check", str(old_model))
    assert c.returncode == 1 and "would migrate" in c.stderr
    assert old_model.read_text(encoding="utf-8") == OLD


def test_the_from_version_defaults_to_the_projects_pin(old_model: Path):
    (old_model.parent / "plx.toml").write_text('openplx-version = "0.17.26"\n', encoding="utf-8")
    r = plx_here("migrate", "--to", "0.19.0", str(old_model))
    assert r.returncode == 0, r.stderr
    assert "0.17.26 -> 0.19.0" in r.stderr and old_model.read_text(encoding="utf-8") == NEW


def test_bad_input_is_a_message_and_the_file_is_untouched(old_model: Path, tmp_path):
    r = plx_here("migrate", "--from", "0.17.26", "--to", "9.9", str(old_model))
    assert r.returncode == 2 and "9.9" in r.stderr and "Traceback" not in r.stderr
    r = plx_here("migrate", "--from", "0.19.0", "--to", "0.17.26", str(old_model))
    assert r.returncode == 2 and "only moves forward" in r.stderr
    broken = tmp_path / "broken.openplx"
    broken.write_text("Scene is Physics3D.System:\n    x is = 1\n", encoding="utf-8")
    r = plx_here("migrate", "--from", "0.17.26", "--to", "0.19.0", str(broken))
    assert r.returncode == 2 and "syntax errors" in r.stderr
    assert broken.read_text(encoding="utf-8") == "Scene is Physics3D.System:\n    x is = 1\n"
    assert old_model.read_text(encoding="utf-8") == OLD


def test_partial_migration_applies_the_safe_renames_and_lists_the_rest(tmp_path, fetched):  # noqa: F811
    """A model removed between the versions: the safe rename is applied anyway (issue 29: refusing
    the whole file dropped the renames plx knows), and the error is shown at its line."""
    fetched("0.17.26")
    f = tmp_path / "probe.openplx"
    text = ("Probe is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n"
            "    top is Physics3D.Charges.MateConnector:\n        position: {0, 0, 0.5}\n\n"
            "Scene is Physics3D.System:\n    probe is Probe\n    sensor is Sensors.ForceTorqueSensor\n")
    f.write_text(text, encoding="utf-8")
    r = plx_here("migrate", "--from", "0.17.26", "--to", "0.19.0", str(f))
    assert r.returncode == 1, r.stderr  # something is left for a person
    assert "1 error left for a person (under 0.17.26: 0)" in r.stderr
    assert f"{f}:8:15: N001 unknown type 'Sensors.ForceTorqueSensor'" in r.stderr
    assert "exists in OpenPLX 0.17.0-0.17.26, not in 0.19.0" in r.stderr
    assert "1 file with errors left for a person" in r.stderr
    assert f.read_text(encoding="utf-8") == text.replace("Physics3D.Charges.MateConnector",
                                                         "Physics3D.Interactions.MateConnector")
