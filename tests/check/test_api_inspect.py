"""The Python API tells what a third-party test asks of a loaded model besides signals: a body's
geometries with their materials (name, density), the contact model between two named materials
(friction, restitution), and a connector's pose in the world as the body carrying it moves."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

pytest.importorskip("mujoco")

from plxtools.check.api import SignalPathError, load  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
BELT = ROOT / "tests" / "physics" / "models" / "conveyor_belt.openplx"
TRUCK = ROOT / "examples" / "boxtruck" / "boxtruck.openplx"


def test_a_body_lists_its_geometries_with_their_material():
    sim = load(BELT)
    (g,) = sim.body("parcel").geometries
    assert (g.path, g.kind, g.material.name, g.material.density) == ("parcel.geometry", "box", "conveyor_parcel", 500.0)
    assert g.collides and g.in_mass and not g.visual_only
    assert sim.body("belt").geometries[0].material.density == 1000.0


def test_the_contact_model_between_two_materials_either_way_round():
    sim = load(BELT)
    cm = sim.contact_model("conveyor_belt", "conveyor_parcel")
    assert cm is not None and cm.friction == 0.5 and cm.restitution == 0.0 and cm.tangential_restitution == 0.0
    assert cm == sim.contact_model("conveyor_parcel", "conveyor_belt")
    assert sim.contact_model("conveyor_belt", "no_such_material") is None


def test_a_connector_moves_with_its_body():
    sim = load(TRUCK)
    hub = "box_truck.chassis.front_left_hub"
    c0 = sim.connector(hub)
    assert c0.body == "box_truck.chassis"
    assert c0.position == pytest.approx((-1.023, -0.748, 0.4088), abs=1e-9)
    assert c0.main_axis == pytest.approx((0.0, -1.0, 0.0), abs=1e-12)
    sim.step(1.0)
    c1, ch = sim.connector(hub), sim.body("box_truck.chassis")
    # the chassis frame carries the hub: same offset in the chassis's axes
    w, x, y, z = ch.quaternion
    assert math.isclose(w * w + x * x + y * y + z * z, 1.0, rel_tol=1e-9)
    assert c1.position != pytest.approx(c0.position, abs=1e-3)  # the truck moved
    off0 = [a - b for a, b in zip(c0.position, (0.0, 0.0, 1.1))]
    off1 = [a - b for a, b in zip(c1.position, ch.position)]
    assert math.dist(off1, [0, 0, 0]) == pytest.approx(math.dist(off0, [0, 0, 0]), rel=1e-9)


def test_a_connector_path_that_is_not_a_connector_is_refused():
    sim = load(TRUCK)
    with pytest.raises(TypeError, match="not a mate connector"):
        sim.connector("box_truck.chassis")
    with pytest.raises(SignalPathError):
        sim.connector("box_truck.chassis.front_left_hubb")


def test_moving_an_imported_model_carries_every_body_and_its_velocity():
    sim = load(TRUCK)
    wheel0 = sim.body("box_truck.front_left_wheel").position
    sim.place("box_truck", position=(5.0, 2.0, 0.0))  # the system's frame was at the origin
    assert sim.body("box_truck.chassis").position == pytest.approx((5.0, 2.0, 1.1), abs=1e-12)
    assert sim.body("box_truck.front_left_wheel").position == pytest.approx(
        (wheel0[0] + 5.0, wheel0[1] + 2.0, wheel0[2]), abs=1e-12)
    h = math.sqrt(0.5)
    sim.place("box_truck", rotation=(h, 0.0, 0.0, h))  # a quarter turn about z, about its frame's origin
    assert sim.body("box_truck.chassis").rpy[2] == pytest.approx(math.pi / 2, abs=1e-12)
    assert sim.body("box_truck.front_left_wheel").position == pytest.approx(
        (5.0 - wheel0[1], 2.0 + wheel0[0], wheel0[2]), abs=1e-12)
    sim.step(0.5)
    v = sim.body("box_truck.chassis").linear_velocity
    sim.place("box_truck", rotation=(0.0, 0.0, 0.0, 1.0))  # between steps: to a half turn, a quarter more
    assert sim.body("box_truck.chassis").linear_velocity == pytest.approx((-v[1], v[0], v[2]), abs=1e-9)


def test_moving_the_whole_scene_moves_its_static_ground_too():
    sim = load(TRUCK)
    sim.place("", position=(0.0, 0.0, 3.0))
    assert sim.body("ground").position == pytest.approx((0.0, 0.0, 3.0), abs=1e-12)
    sim.step(0.5)
    assert sim.body("box_truck.chassis").position[2] > 3.9  # it rests on the moved ground


def test_moving_the_whole_scene_carries_bodies_hung_from_its_static_ones():
    sim = load(ROOT / "tests" / "physics" / "models" / "double_pendulum.openplx")
    before = {b: sim.body(b).position for b in ("support", "upper", "lower")}
    sim.place("", position=(0.0, 0.0, 1.0))  # the support is fixed in the world; the rods hang from it
    for b, p in before.items():
        assert sim.body(b).position == pytest.approx((p[0], p[1], p[2] + 1.0), abs=1e-9)
    with pytest.raises(Exception, match="upper hangs from support, outside it"):
        sim.place("upper", position=(0.0, 0.0, 0.0))  # alone, it cannot leave its hinge
