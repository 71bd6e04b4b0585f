"""Which bodies a velocity input (LinearVelocity3DInput / AngularVelocity3DInput) can act on, and
the reason given when it cannot: a kinematic body that no mate touches is refused because it is
not dynamic, never because of mates it does not have (issue 29, section 5)."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from plxtools.check.api import NotSimulatedError, load  # noqa: E402

YARD = """\
Block is Physics3D.Bodies.RigidBody:
    inertia.mass: 1
    geometry is Physics3D.Geometries.Box:
        size:
            x: 0.2
            y: 0.2
            z: 0.2
    connector is Physics3D.Interactions.MateConnector:
        main_axis: {0, 0, 1}

Yard is Physics3D.System:
    conveyor is Block:
        is_dynamic: false
        kinematics.local_transform.position.x: 3
    crate is Block:
        kinematics.local_transform.position.z: 2
    door is Block:
        kinematics.local_transform.position.x: -3
    anchor is Physics3D.Interactions.MateConnector:
        position: {-3, 0, 0}
        main_axis: {0, 0, 1}
    hinge is Physics3D.Interactions.Hinge:
        connectors: [anchor, door.connector]
"""

INPUTS = ("linear_velocity_world_input", "angular_velocity_world_input")


@pytest.fixture(scope="module")
def yard(tmp_path_factory):
    path = tmp_path_factory.mktemp("yard") / "yard.openplx"
    path.write_text(YARD)
    return load(path)


@pytest.mark.parametrize("signal", INPUTS)
def test_a_kinematic_body_without_mates_is_refused_as_not_dynamic(yard, signal):
    with pytest.raises(NotSimulatedError) as exc:
        yard.set(f"conveyor.{signal}", [1.0, 0.0, 0.0])
    msg = str(exc.value)
    assert "conveyor is not dynamic and does not move" in msg
    assert "mates" not in msg


@pytest.mark.parametrize("signal", INPUTS)
def test_a_body_on_a_mate_is_refused_because_of_its_mate(yard, signal):
    with pytest.raises(NotSimulatedError, match="door is attached to other bodies by mates"):
        yard.set(f"door.{signal}", [1.0, 0.0, 0.0])


def test_a_free_body_takes_the_velocity(yard):
    yard.set("crate.linear_velocity_world_input", [1.0, 0.0, 0.0])
    yard.step()
    assert yard.body("crate").linear_velocity[0] == pytest.approx(1.0, rel=1e-6)
