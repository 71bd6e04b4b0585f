"""Renames of redeclared attributes come from the bundles of both versions, in every bundle
(issue 29, point 4): a `becomes` redeclaration follows the rename its base made, whether the
subtype redeclares the new name or drops the redeclaration (Physics1D in 0.18.11)."""

from __future__ import annotations

import pytest

from plxtools.model.apichanges import changes
from plxtools.model.apiindex import load
from tests.bundles.conftest import fetched  # noqa: F401 - the fixture
from tests.conftest import run_plx

FROM, TO = "0.17.26", "0.19.0"


def _redeclared_renames(from_v: str, to_v: str) -> list[tuple[str, str, str]]:
    """(model, old attribute, new attribute) for every rename of an attribute the model redeclares."""
    old = load(from_v)
    out = []
    for c in changes(from_v, to_v):
        if c.kind != "attr-renamed" or c.model not in old.models:
            continue
        own = old.models[c.model].get("a", {}).get(c.attr)
        if own is not None and "b" in own[1]:
            out.append((c.model, c.old, c.new))
    return out


REDECLARED = _redeclared_renames(FROM, TO)


def test_the_redeclarations_of_every_bundle_are_found():
    bundles = {m.split(".")[0] for m, _a, _b in REDECLARED}
    assert {"Physics1D", "Physics3D"} <= bundles, REDECLARED
    assert ("Physics1D.Interactions.VelocityMotor", "charges", "connectors") in REDECLARED


@pytest.mark.parametrize(("model", "old", "new"), REDECLARED, ids=[f"{m}.{a}" for m, a, _n in REDECLARED])
def test_each_redeclared_attribute_is_renamed(tmp_path, fetched, model, old, new):  # noqa: F811
    fetched(FROM)
    f = tmp_path / "use.openplx"
    f.write_text(f"Use is {model}:\n    {old}: []\n", encoding="utf-8")
    r = run_plx("migrate", "--from", FROM, "--to", TO, "--diff", str(f))
    assert r.returncode in (0, 1), r.stderr
    assert f"-    {old}: []" in r.stdout and f"+    {new}: []" in r.stdout, r.stdout + r.stderr


DRIVE = """\
Drive is Physics3D.System:
    motor_shaft is DriveTrain.Shaft:
        inertia.inertia: 0.5
    wheel_shaft is DriveTrain.Shaft:
        inertia.inertia: 2
    gear is DriveTrain.Gear:
        ratio: 3
        charges: [motor_shaft.output, wheel_shaft.input]
    brake is DriveTrain.ManualBrake:
        initial_engagement_fraction: 0
        torque_capacity: 100
        min_relative_slip_ratio: 0.01
        charges: [wheel_shaft.output]
    motor is Physics1D.Interactions.RotationalVelocityMotor:
        charges: [motor_shaft.input]
        target_speed: 1
    base is Physics3D.Bodies.RigidBody:
        inertia.mass: 1
        top is Physics3D.Charges.MateConnector
    lock is Physics3D.Interactions.Lock:
        charges: [base.top, world_top]
    world_top is Physics3D.Charges.MateConnector
    sensor is Sensors.ForceTorqueSensor
"""


def test_a_drive_train_file_is_migrated_with_what_needs_a_person_listed(tmp_path, fetched):  # noqa: F811
    """Physics1D and Physics3D redeclarations and a type move in one file with a removed model:
    every rename is applied; the removed model is listed at its line."""
    fetched(FROM)
    f = tmp_path / "drive.openplx"
    f.write_text(DRIVE, encoding="utf-8")
    before = run_plx("lint", "--openplx-version", FROM, str(f))
    assert before.returncode == 0, before.stdout
    r = run_plx("migrate", "--from", FROM, "--to", TO, str(f))
    assert r.returncode == 1, r.stderr
    text = f.read_text(encoding="utf-8")
    assert "charges" not in text and text.count("connectors: [") == 4, text
    assert "Physics3D.Interactions.MateConnector" in text and "Charges" not in text
    assert f"{f}:23:15: N001 unknown type 'Sensors.ForceTorqueSensor'" in r.stderr, r.stderr
    after = run_plx("lint", "--openplx-version", TO, str(f))
    assert "1 error" in after.stdout.splitlines()[-1] and "ForceTorqueSensor" in after.stdout, after.stdout
