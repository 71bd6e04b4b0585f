"""`plx test` expectations on what the Python API tells besides signals (a geometry's material, the
contact model of two materials, a connector's world frame) and ``[[place]]`` moving a body between
steps, as ``sim.place`` does: each passes when right, fails with what it measured when wrong, and a
wrong key or path is an A141 error at its line."""

from __future__ import annotations

import json

import pytest

from tests.conftest import plx_here

pytest.importorskip("mujoco")

# a 0.2 m crate dropped from 0.3 m onto a floor whose top is at z = 0.1; it rests at z = 0.2, its
# lid (a connector 0.1 m above its centre) at z = 0.3; a flap hangs from a fixed post by a hinge
YARD = """\
const CrateMaterial is Physics.Geometries.Material:
    unique_name: "crate_wood"
    density: 600

const FloorMaterial is Physics.Geometries.Material:
    unique_name: "floor_concrete"
    density: 2400

CrateOnFloor is Physics.Interactions.SurfaceContact.Model:
    material_1: CrateMaterial
    material_2: FloorMaterial
    normal_restitution: 0.0
    tangential_restitution: 0.0
    friction becomes Physics.Interactions.Dissipation.DryConeFriction:
        coefficient: 0.4

Yard is Physics3D.System:
    floor is Physics3D.Bodies.RigidBody:
        is_dynamic: false
        geometry is Physics3D.Geometries.Box:
            size: {4, 4, 0.2}
            material: FloorMaterial
    crate is Physics3D.Bodies.RigidBody:
        kinematics.local_transform.position.z: 0.3
        geometry is Physics3D.Geometries.Box:
            size: {0.2, 0.2, 0.2}
            material: CrateMaterial
        lid is Physics3D.Interactions.MateConnector:
            position: {0, 0, 0.1}
            main_axis: {0, 0, 1}
    post is Physics3D.Bodies.RigidBody:
        is_dynamic: false
        kinematics.local_transform.position: {1.5, 0, 1.0}
        pivot is Physics3D.Interactions.MateConnector:
            main_axis: {0, 1, 0}
            normal: {1, 0, 0}
    flap is Physics3D.Bodies.RigidBody:
        kinematics.local_transform.position: {1.5, 0, 0.7}
        geometry is Physics3D.Geometries.Box:
            size: {0.05, 0.05, 0.5}
            enable_collisions: false
        top is Physics3D.Interactions.MateConnector:
            position: {0, 0, 0.3}
            main_axis: {0, 1, 0}
            normal: {1, 0, 0}
    swing is Physics3D.Interactions.Hinge:
        connectors: [post.pivot, flap.top]
    contact is CrateOnFloor
"""


def _expect(of: str, at: float, check: str) -> str:
    return f'[[expect]]\nat = {at}\nof = "{of}"\n{check}\n'


def _files(tmp_path, **scenarios: str):
    (tmp_path / "yard.openplx").write_text(YARD, encoding="utf-8")
    for name, body in scenarios.items():
        (tmp_path / f"{name}.scenario.toml").write_text('model = "yard.openplx"\nduration = 1.0\n' + body,
                                                        encoding="utf-8")


RIGHT = "".join([
    _expect("crate.geometry.material.density", 0.0, "equals = 600\ntolerance = 1e-9"),
    _expect("floor.geometry.material.density", 1.0, "above = 2000"),
    _expect("contact_model(floor_concrete, crate_wood).friction", 1.0, "equals = 0.4\ntolerance = 1e-9"),
    _expect("contact_model(crate_wood, floor_concrete).restitution", 1.0, "abs_below = 1e-9"),
    _expect("crate.lid.position.z", 0.0, "equals = 0.4\ntolerance = 1e-9"),  # where it was assembled
    _expect("crate.lid.position.z", 0.45, "equals = 0.3\ntolerance = 2e-3"),  # landed
    _expect("crate.lid.main_axis.z", 0.45, "above = 0.999"),
    # moved at 0.5 s: measured at once where it was put, and it falls from there onto the floor
    "[[place]]\nat = 0.5\npath = \"crate\"\nposition = [1.0, 0.5, 0.6]\nrotation = [0.7071068, 0, 0, 0.7071068]\n",
    _expect("crate.x", 0.5, "equals = 1.0\ntolerance = 1e-6"),
    _expect("crate.lid.position.z", 0.5, "equals = 0.7\ntolerance = 1e-6"),
    _expect("crate.yaw", 0.5, "equals = 90\ntolerance = 1e-3\nunit = \"deg\""),
    _expect("crate.y", 1.0, "equals = 0.5\ntolerance = 1e-3"),
    _expect("crate.z", 1.0, "between = [0.19, 0.205]"),  # on the floor again (0.4 m below where put)
])


# the whole yard lifted by 1 m before the first step: the fixed post with it, the flap still hanging from it
ROOT_LIFTED = "".join([
    "[[place]]\npath = \"\"\nposition = [0, 0, 1]\n",
    _expect("floor.z", 0.0, "equals = 1.0\ntolerance = 1e-9"),
    _expect("crate.lid.position.z", 0.0, "equals = 1.4\ntolerance = 1e-9"),
    _expect("flap.z", 0.0, "equals = 1.7\ntolerance = 1e-6"),
    _expect("flap.z", 1.0, "equals = 1.7\ntolerance = 1e-3"),
    _expect("crate.z", 1.0, "between = [1.19, 1.205]"),
])


def test_material_contact_model_connector_and_place_keys_pass_when_right(tmp_path):
    _files(tmp_path, right=RIGHT, root=ROOT_LIFTED)
    r = plx_here("test", ".", "--output-format", "json", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    by_name = {sc["name"]: sc for sc in json.loads(r.stdout)["scenarios"]}
    right, root = by_name["right"], by_name["root"]
    assert right["status"] == root["status"] == "passed"
    assert len(right["expectations"]) == 12 and len(root["expectations"]) == 5
    assert all(e["passed"] and e["evaluated"] for e in right["expectations"] + root["expectations"])


def test_each_key_fails_with_what_it_measured_at_its_line(tmp_path):
    _files(tmp_path, wrong="".join([
        _expect("crate.geometry.material.density", 0.0, "below = 500"),  # line 3
        _expect("contact_model(crate_wood, floor_concrete).friction", 1.0, "above = 0.5"),  # line 7
        _expect("crate.lid.position.z", 1.0, "above = 0.35"),  # line 11: the crate has landed
        "[[place]]\nat = 0.5\npath = \"crate\"\nposition = [1.0, 0.5, 0.6]\n",
        _expect("crate.x", 1.0, "below = 0.5"),  # line 19: it was moved to x = 1
    ]))
    r = plx_here("test", ".", cwd=tmp_path)
    assert r.returncode == 1, r.stdout + r.stderr
    lines = {ln.split(": error ")[0]: ln for ln in r.stdout.splitlines() if ": error A140 " in ln}
    assert set(lines) == {f"wrong.scenario.toml:{n}:1" for n in (3, 7, 11, 19)}, r.stdout
    assert lines["wrong.scenario.toml:3:1"].endswith("expected below 500, measured 600")
    assert lines["wrong.scenario.toml:7:1"].endswith("expected above 0.5, measured 0.4")
    assert 0.29 < float(lines["wrong.scenario.toml:11:1"].rsplit(" ", 1)[1]) < 0.31
    assert 0.99 < float(lines["wrong.scenario.toml:19:1"].rsplit(" ", 1)[1]) < 1.01


def test_bad_keys_and_paths_are_errors_at_their_line(tmp_path):
    _files(tmp_path, paths="".join([
        _expect("crate.geometri.material.density", 0.0, "below = 500"),  # line 3
        _expect("contact_model(crate_wood, steel).friction", 1.0, "above = 0.5"),  # line 7
        _expect("contact_model(crate_wood, floor_concrete).frictoin", 1.0, "above = 0.5"),  # line 11
        _expect("crate.lid.position", 1.0, "above = 0.35"),  # line 15
        _expect("crate.lid.position.z", 1.0, "above = 0.35\nunit = \"deg\""),  # unit at line 22
        "[[place]]\nat = 0.5\npath = \"crat\"\nposition = [1, 2, 3]\n",  # path at line 26
    ]), keys="".join([
        "[[place]]\nat = 0.5\npath = \"crate\"\npositoin = [1, 2, 3]\n",  # line 6
        "[[place]]\nat = 0.5\npath = \"crate\"\nrotation = [0, 0, 0, 0]\n",  # line 11
        _expect("crate.x", 1.0, "below = 0.5"),
    ]), refused="".join([
        "[[place]]\nat = 0.2\npath = \"flap\"\nposition = [0, 0, 2]\n",  # line 5: it hangs from the post
        _expect("crate.x", 1.0, "below = 0.5"),
    ]))
    r = plx_here("test", ".", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    got = {ln.split(": error A141 ")[0]: ln.split(": error A141 ")[1] for ln in r.stdout.splitlines()
           if ": error A141 " in ln}
    assert got == {
        "paths.scenario.toml:5:1": "the scene has no simulated geometry 'crate.geometri'; "
                                   "did you mean 'crate.geometry'?",
        "paths.scenario.toml:9:1": "the scene has no contact model between crate_wood and steel "
                                   "(materials with one: crate_wood, floor_concrete)",
        "paths.scenario.toml:13:1": "a contact model has no value 'frictoin'; use one of friction, restitution, "
                                    "tangential_restitution; did you mean 'friction'?",
        "paths.scenario.toml:17:1": "name a vector and a component of the connector crate.lid: "
                                    "crate.lid.position.x, crate.lid.main_axis.x, crate.lid.normal.x (or .y, .z)",
        "paths.scenario.toml:23:1": "crate.lid.position.z is not an angle; it takes no unit",
        "paths.scenario.toml:26:1": "the model has no object 'crat' to place; did you mean 'crate'?",
        "keys.scenario.toml:6:1": "unknown key 'positoin' in [[place]]; did you mean 'position'?",
        "keys.scenario.toml:3:1": "[[place]] moves nothing: add position = [x, y, z] and/or rotation = [w, x, y, z]",
        "keys.scenario.toml:10:1": "rotation = [0, 0, 0, 0] is no rotation: give a quaternion [w, x, y, z]",
        "refused.scenario.toml:5:1": "cannot move flap: flap hangs from post, outside it "
                                     "(a mate to the world or to another model)",
    }, r.stdout
    assert "Traceback" not in r.stdout + r.stderr
