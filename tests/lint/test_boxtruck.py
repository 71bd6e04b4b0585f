"""The example BoxTruck lints clean; each typical mistake in a copy is reported at its exact range."""

import pytest

from plxtools.rules.analysis import analyse_tree
from plxtools.config import Config
from plxtools.syntax import parse_text
from tests.conftest import REPO

BOXTRUCK = (REPO / "examples" / "boxtruck" / "boxtruck.openplx").read_text()


def lint_text(text, workspace, name="boxtruck_copy.openplx"):
    tree = parse_text(text, str(REPO / "build" / name))
    return analyse_tree(tree, Config(), workspace)


def test_example_is_clean(workspace):
    assert lint_text(BOXTRUCK, workspace) == []


CASES = [
    # (original, replacement, code, message fragment, underlined text)
    ("inertia.mass: 10", "inertia.mas: 10", "N002", "'mas' is not an attribute of Physics3D.Bodies.Inertia", "mas"),
    ("kinematics.local_transform.position.z: 1.1", "kinematics.local_transform.positon.z: 1.1", "N002",
     "'positon' is not an attribute of Math.AffineTransform", "positon"),
    ("geometry is Physics3D.Geometries.Cylinder", "geometry is Physics3D.Geometries.Cilinder", "N001",
     "unknown type 'Physics3D.Geometries.Cilinder'", "Physics3D.Geometries.Cilinder"),
    ("radius: 0.26", 'radius: "0.26"', "T001", "expected Real, found String", '"0.26"'),
    ("is_dynamic: false", "is_dynamic: 0", "T001", "expected Bool, found Int", "0"),
    ("main_axis: {0, -1, 0}\n        normal: {1, 0, 0}\n\nChassis", "main_axis: {0, -1}\n        normal: {1, 0, 0}\n\nChassis",
     "T003", "Math.Vec3 takes 3 values", "{0, -1}"),
    ("group1: own_parts", "group1: front_left_motor", "T001",
     "expected Simulation.CollisionGroup, found Physics3D.Interactions.RotationalVelocityMotor", "front_left_motor"),
    # the typo also leaves GroundPlate unused (C003), which is reported too
    ("    ground is GroundPlate", "    ground is GroundPlane", "N001+C003", "unknown type 'GroundPlane'", "GroundPlane"),
    ("x: geometry.size.x * 0.31", "x: geometry.size.w * 0.31", "N004", "Math.Vec3 has no attribute or method 'w'", "w"),
]


@pytest.mark.parametrize("old,new,code,message,underlined", CASES, ids=[c[2] + "-" + c[4] for c in CASES])
def test_mistake_is_located(workspace, old, new, code, message, underlined):
    assert BOXTRUCK.count(old) >= 1
    text = BOXTRUCK.replace(old, new, 1)
    diags = [d for d in lint_text(text, workspace) if d.severity.value != "info"]
    wanted = code.split("+")
    assert sorted(d.code for d in diags) == sorted(wanted), [d.message for d in diags]
    d = next(d for d in diags if d.code == wanted[0])
    assert message in d.message
    assert text[d.span.start.offset:d.span.end.offset] == underlined
    start = text.index(new) if new in text else None
    assert start is not None and start <= d.span.start.offset <= start + len(new)
