"""The renames and moves OpenPLX itself declares (its migration tool's list, kept as data in
declared_renames.toml): every one whose versions plx has indexed is a rename for --explain, is
rewritten by plx migrate and is what lint suggests, never a removal (issue 39)."""

from __future__ import annotations

import json
import tomllib

import pytest

from plxtools.model.apichanges import DECLARED, DECLARED_RENAMES, changes, declared_renames, renamed_model
from plxtools.model.apiindex import version_key, versions
from tests.bundles.conftest import fetched  # noqa: F401 - the fixture that provides old versions
from tests.conftest import plx_here

LAST = versions()[-1]


def _indexed():
    return [d for d in declared_renames() if d.kind in ("model", "attribute") and d.after in versions()]


def test_every_fact_names_where_it_comes_from():
    data = tomllib.loads(DECLARED_RENAMES.read_text(encoding="utf-8"))
    assert data["source"]["package"] == "openplx" and data["source"]["module"] == "openplx.migrations"
    facts = declared_renames()
    assert len(facts) == sum(len(v) for k, v in data.items() if k != "source")
    for d in facts:
        assert d.operation.split(":")[0].startswith(("migrations_for_", "snakecaseify_", "rename_from_brick")), d
        assert version_key(d.after) < version_key(d.to)
    # the count: 16 type and attribute renames whose both versions plx knows (13 signal and
    # drive-train types, VelocityMotor.desired_speed twice, AutomaticClutch.engagement_time) ...
    top = [d for d in _indexed() if d.kind == "model" or d.model in ("Physics3D.Interactions.VelocityMotor",
                                                                       "Physics1D.Interactions.VelocityMotor",
                                                                       "DriveTrain.AutomaticClutch")]
    assert len(top) == 16
    # ... and the attributes of the renamed signals (hinge -> source, ...)
    assert len(_indexed()) == 27


@pytest.mark.parametrize("d", _indexed(), ids=lambda d: f"{d.model + '.' if d.model else ''}{d.old}")
def test_a_declared_rename_is_a_rename_never_a_removal(d):
    cs = changes(d.after, LAST)
    if d.kind == "model":
        removed = [c for c in cs if c.kind == "model-removed" and c.model == d.old]
        renamed = [c for c in cs if c.kind in ("model-moved", "model-renamed") and c.old == d.old]
    else:
        removed = [c for c in cs if c.kind == "attr-removed" and c.model == d.model and c.attr == d.old]
        renamed = [c for c in cs if c.kind == "attr-renamed" and c.model == d.model and c.old == d.old]
    assert not removed, f"{d} is reported as a removal: {removed}"
    assert len(renamed) == 1 and renamed[0].handling == DECLARED, renamed
    assert renamed[0].detail == d.source() and d.operation.split(":")[0] in renamed[0].detail
    if d.kind == "model":
        assert renamed[0].new == d.new or version_key(renamed[0].since) > version_key(d.to)  # (moved on later)


def test_explain_names_each_declared_rename_with_its_source():
    r = plx_here("migrate", "--explain", "0.15.1", "0.16.1")
    assert r.returncode == 0, r.stderr
    text = r.stdout
    assert ("Physics3D.Signals.HingeAngularVelocityOutput -> Physics.Signals.AngularVelocity1DOutput  [0.15.2] "
            "(declared by OpenPLX: openplx.migrations.migrations_for_0_15_1, 0.15.1 -> 0.15.2)") in text
    assert ("DriveTrain.AutomaticClutch.engagement_time -> engagement_duration  [0.16.1] (declared by OpenPLX: "
            "openplx.migrations.migrations_for_0_15_22, 0.15.22 -> 0.16.0)") in text
    removed = text.split("Removed models", 1)[1].split("\n\n", 1)[0] if "Removed models" in text else ""
    for d in _indexed():
        assert d.old not in removed
    data = json.loads(plx_here("migrate", "--explain", "0.15.1", "0.16.1", "--output-format", "json").stdout)
    assert data["counts"][DECLARED] == 27


SIGNALS_0151 = """\
# Signals as OpenPLX 0.15.1 wrote them (plxtools' own test model).
Rig is Physics3D.System:
    a is Physics3D.Bodies.RigidBody:
        c is Physics3D.Charges.MateConnector
    b is Physics3D.Bodies.RigidBody:
        c is Physics3D.Charges.MateConnector
    hinge is Physics3D.Interactions.Hinge:
        charges: [a.c, b.c]
    motor is Physics3D.Interactions.RotationalVelocityMotor:
        charges: hinge.charges
        desired_speed: 1.5
    speed is Physics3D.Signals.HingeAngularVelocityOutput:
        hinge: hinge
    command is Physics3D.Signals.RotationalVelocityMotorVelocityInput:
        motor: motor
    attitude is Physics3D.Signals.RigidBodyRPYOutput:
        rigid_body: a
    where_b is Physics3D.Signals.RigidBodyPositionOutput:
        rigid_body: b
"""


def test_migrate_rewrites_declared_renames_attributes_too_and_the_result_lints_clean(tmp_path, fetched):  # noqa: F811
    fetched("0.15.1")
    f = tmp_path / "rig.openplx"
    f.write_text(SIGNALS_0151, encoding="utf-8")
    assert plx_here("lint", "--openplx-version", "0.15.1", str(f)).returncode == 0
    r = plx_here("migrate", "--from", "0.15.1", "--to", LAST, str(f))
    assert r.returncode == 0, r.stderr
    text = f.read_text(encoding="utf-8")
    for old in ("HingeAngularVelocityOutput", "RotationalVelocityMotorVelocityInput", "RigidBodyRPYOutput",
                "RigidBodyPositionOutput", "desired_speed", "hinge: hinge", "motor: motor", "rigid_body:"):
        assert old not in text, (old, text)
    assert "speed is Physics.Signals.AngularVelocity1DOutput:\n        source: hinge" in text
    assert "target_speed: 1.5" in text and "source: motor" in text
    after = plx_here("lint", str(f))
    assert after.returncode == 0, after.stdout


def test_lint_suggests_the_declared_target_not_a_look_alike(tmp_path):
    f = tmp_path / "speed.openplx"
    f.write_text("Rig is Physics3D.System:\n"
                 "    speed is Physics3D.Signals.HingeAngularVelocityOutput\n", encoding="utf-8")
    [d] = json.loads(plx_here("lint", "--output-format", "json", str(f)).stdout)
    assert d["code"] == "U001", d
    assert "'Physics.Signals.AngularVelocity1DOutput'" in d["message"] and "3DOutput" not in json.dumps(d)
    assert d["fix"]["edits"][0]["content"] == "Physics.Signals.AngularVelocity1DOutput"
    found = renamed_model("Physics3D.Signals.HingeAngularVelocityOutput", "0.15.1", LAST)
    assert found is not None and found.new == "Physics.Signals.AngularVelocity1DOutput"
    assert found.handling == DECLARED


def test_a_declared_attribute_rename_is_suggested_only_where_its_model_can_be(tmp_path):
    """`motor` -> `source` is a rename of some signal models' attribute: on a rigid body `motor:`
    stays an unknown attribute (N002, with its own did-you-mean), on a velocity motor
    `desired_speed:` is U002."""
    f = tmp_path / "m.openplx"
    f.write_text("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        motor: 1\n"
                 "    m is Physics3D.Interactions.RotationalVelocityMotor:\n        desired_speed: 1\n", encoding="utf-8")
    diags = json.loads(plx_here("lint", "--output-format", "json", str(f)).stdout)
    assert [(d["code"], d["range"]["start"]["line"]) for d in diags] == [("N002", 3), ("U002", 5)], diags
    assert "'target_speed'" in diags[1]["message"] and "Physics3D.Interactions.VelocityMotor" in diags[1]["message"]
