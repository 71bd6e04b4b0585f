"""SNAP assembly: world poses compared with hand-computed values."""

from __future__ import annotations

import math

import pytest

from check_helpers import CASES, EXAMPLE, line_of


def poses(fc) -> dict[str, tuple[list, list, str]]:
    return {p: (b["position"], b["quaternion"], b["placed_by"]) for p, b in fc.assembled_bodies().items()}


def test_boxtruck_wheels_sit_on_their_hubs(check_file):
    fc = check_file(EXAMPLE)
    assert not [d for d in fc.diagnostics if d.severity.value in ("error", "warning")]
    got = poses(fc)
    assert set(got) == {"box_truck.chassis", "box_truck.front_left_wheel", "box_truck.front_right_wheel",
                        "box_truck.rear_left_wheel", "box_truck.rear_right_wheel", "ground"}
    chassis_z = 1.1
    ox, oy, oz = 3.3 * 0.31, 1.7 * 0.44, 1.44 * 0.48  # hub offsets: fractions of the box size
    assert got["box_truck.chassis"][0] == pytest.approx([0, 0, chassis_z])
    assert got["box_truck.chassis"][1] == pytest.approx([1, 0, 0, 0])
    assert got["box_truck.chassis"][2].startswith("declared transform at line "
                                                   f"{line_of(EXAMPLE, 'kinematics.local_transform.position.z')}")
    expected = {  # wheel origin = its connector = the hub; x front (-) / rear (+), y left (-) / right (+)
        "front_left": (-ox, -oy), "front_right": (-ox, oy), "rear_left": (ox, -oy), "rear_right": (ox, oy)}
    for name, (x, y) in expected.items():
        pos, quat, how = got[f"box_truck.{name}_wheel"]
        assert pos == pytest.approx([x, y, chassis_z - oz], abs=1e-12)
        assert how == f"SNAP, by mate box_truck.{name}_hinge"
        if "left" in name:  # wheel connector main_axis -Y onto hub main_axis -Y: no rotation
            assert quat == pytest.approx([1, 0, 0, 0], abs=1e-12)
        else:  # -Y onto +Y with normal X onto X: half a turn about X
            assert quat == pytest.approx([0, 1, 0, 0], abs=1e-12)
    assert got["ground"][0] == [0.0, 0.0, 0.0] and got["ground"][2].startswith("not placed")
    for m in fc.assembly.mates:  # every hinge closes exactly
        assert m.separation < 1e-12 and m.misalignment < 1e-9


def test_hinge_initial_angle_and_the_world_connector(check_file):
    fc = check_file(CASES / "world_pendulum.openplx")
    got = poses(fc)
    th = 0.5
    # pivot at z 2, axis +Y; connectors[1] is connectors[0] turned by initial_angle about the axis
    assert got["bob"][0] == pytest.approx([-math.sin(th), 0, 2 - math.cos(th)], abs=1e-12)
    assert got["bob"][1] == pytest.approx([math.cos(th / 2), 0, math.sin(th / 2), 0], abs=1e-12)
    # World: origin, main axis Z, normal X.  bob.top (main Y, normal X) is laid onto it, then turned
    # about Z: the bob's top-to-origin direction (0, -1, 0) in the connector frame, turned by 0.5 rad
    assert got["world_bob"][0] == pytest.approx([-math.sin(th), math.cos(th), 0], abs=1e-12)


def test_nested_systems_and_a_lock_between_them(check_file):
    fc = check_file(CASES / "nested_systems.openplx")
    got = poses(fc)
    s = math.sqrt(0.5)
    assert got["arm1.first"][0] == pytest.approx([0.5, 0, 1])  # arm1 at z 1, first at x 0.5 in it
    assert got["arm1.second"][0] == pytest.approx([1, 0.5, 1])  # hinged at x 1, turned 90 deg about Z
    assert got["arm1.second"][1] == pytest.approx([s, 0, 0, s])
    # arm2 has no transform: the lock moves the whole system so that arm2.first.left meets arm1's end
    assert got["arm2.first"][0] == pytest.approx([1, 1.5, 1])
    assert got["arm2.first"][1] == pytest.approx([s, 0, 0, s])
    assert got["arm2.second"][0] == pytest.approx([0.5, 2, 1])
    assert got["arm2.second"][1] == pytest.approx([0, 0, 0, 1], abs=1e-12)
    assert not [d for d in fc.diagnostics if d.code.startswith("A")]


def test_reference_body_conflicting_mates_and_enable_snap(check_file):
    path = CASES / "snap_order.openplx"
    fc = check_file(path)
    got = poses(fc)
    assert got["chain.b"][0] == pytest.approx([0, 0, 1]) and "reference_body" in got["chain.b"][2]
    assert got["chain.a"][0] == pytest.approx([-0.2, 0, 1])  # locked to b's left face
    assert got["chain.c"][0] == pytest.approx([0.7, 0, 1])  # prismatic initial_position 0.5 along +X
    assert got["loose"][0] == pytest.approx([0, 3, 1])  # enable_snap: false leaves it where it was declared
    found = {(d.code, d.span.start.line + 1): d.message for d in fc.diagnostics}
    ca = found[("A016", line_of(path, "ca is Physics3D.Interactions.Lock"))]
    assert "1.1 m apart" in ca and "chain.c: SNAP, by mate chain.bc" in ca
    tether = found[("A016", line_of(path, "tether is Physics3D.Interactions.Ball"))]
    declared = line_of(path, "local_transform.position: {0, 3, 1}")
    assert "6.001 m apart" in tether and f"loose: declared transform at line {declared}" in tether


def test_unplaced_bodies_piling_up_at_the_origin_are_reported(check_file):
    path = CASES / "precedence.openplx"
    fc = check_file(path)
    overlaps = [(d.span.start.line + 1, d.message) for d in fc.diagnostics if d.code == "A037"]
    assert [ln for ln, _ in overlaps] == [line_of(path, "    a is Base"), line_of(path, "    b is Derived"),
                                           line_of(path, "    c is Derived:"), line_of(path, "    d is OnlyTrait")]
    assert "stays at {0, 0, 0}, where it overlaps b (by 1 m)" in overlaps[0][1]
    assert poses(fc)["e"][0] == pytest.approx([1, 2, 5])
