"""MuJoCo backend: scenes built by hand in the assembled-scene IR, simulated, checked with numbers."""

from __future__ import annotations

import json
import math
import zlib

import numpy as np
import pytest

from plxtools.check.mujoco.backend import RenderUnavailable, compile_scene, export_mjcf, render_png, simulate
from plxtools.check.scene import (
    IDENTITY_QUAT,
    Body,
    ContactModel,
    Connector,
    Controller,
    ExcludePair,
    Geom,
    Mate,
    Scene,
    Source,
    Unsupported,
    quat_from_axis_angle,
    quat_rotate,
)

G = 9.80665
SRC = "boxtruck.openplx"

# --------------------------------------------------------------------------------------- scenes


def boxtruck(left_speed: float = 1.0, right_speed: float = 1.0) -> Scene:
    """The BoxTruck tutorial (step 10) as SNAP leaves it.

    Chassis box 3.3 x 1.7 x 1.44, 1000 kg at z = 1.1; connectors at (+-3.3*0.31, +-1.7*0.44,
    -1.44*0.48), left ones main_axis -Y, right ones +Y, normal +X.  Wheel: cylinder r 0.26,
    h 0.165 (along Y), 10 kg, connector at its origin with main_axis -Y, normal +X.  SNAP puts
    main axis on main axis and normal on normal: left wheels keep the identity orientation,
    right wheels are turned 180 deg about X."""
    ox, oy, oz = 3.3 * 0.31, 1.7 * 0.44, 1.44 * 0.48
    cz = 1.1
    chassis = Body(
        "boxTruck.chassis",
        (0.0, 0.0, cz),
        mass=1000.0,
        geoms=[Geom("boxTruck.chassis.geometry", "box", size=(3.3, 1.7, 1.44), source=Source(SRC, 8, 5))],
        source=Source(SRC, 6, 5),
    )
    ground = Body(
        "ground",
        is_dynamic=False,
        geoms=[
            Geom("ground.geometry", "box", size=(100.0, 100.0, 0.1), material="GroundMaterial", density=10.0)
        ],
        source=Source(SRC, 90, 5),
    )
    bodies, mates, controllers = [chassis], [], []
    corners = {
        "front_left": (-ox, -oy, -1.0),
        "front_right": (-ox, oy, 1.0),
        "rear_left": (ox, -oy, -1.0),
        "rear_right": (ox, oy, 1.0),
    }
    line = 40
    for name, (x, y, side) in corners.items():
        cc = Connector(
            f"boxTruck.chassis.{name}_connector", chassis.path, (x, y, -oz), (0.0, side, 0.0), (1.0, 0.0, 0.0)
        )
        q = IDENTITY_QUAT if side < 0 else (0.0, 1.0, 0.0, 0.0)
        wheel = Body(
            f"boxTruck.{name}_wheel",
            (x, y, cz - oz),
            q,
            mass=10.0,
            geoms=[
                Geom(
                    f"boxTruck.{name}_wheel.geometry",
                    "cylinder",
                    radius=0.26,
                    height=0.165,
                    material="WheelMaterial",
                )
            ],
        )
        wc = Connector(
            f"boxTruck.{name}_wheel.connector", wheel.path, (0.0, 0.0, 0.0), (0.0, -1.0, 0.0), (1.0, 0.0, 0.0)
        )
        bodies.append(wheel)
        mates.append(Mate(f"boxTruck.{name}_hinge_joint", "hinge", (cc, wc), source=Source(SRC, line, 5)))
        if name.startswith("front"):
            controllers.append(
                Controller(
                    f"boxTruck.{name}_drive_motor",
                    "velocity_motor",
                    "rotational",
                    (cc, wc),
                    target_speed=left_speed if "left" in name else right_speed,
                    source=Source(SRC, line + 30, 5),
                )
            )
        line += 3
    group = [b.path for b in bodies]
    excludes = [ExcludePair(a, b) for i, a in enumerate(group) for b in group[i:]]
    contact = ContactModel(
        "wheel_ground_friction",
        "WheelMaterial",
        "GroundMaterial",
        friction=1.0,
        friction_model="dry_constant_normal_force",
        restitution=0.0,
        tangential_restitution=0.0,
    )
    return Scene("Scene", [*bodies, ground], mates, controllers, [contact], excludes)


def pendulum(theta0: float = 0.1, length: float = 1.0) -> Scene:
    """A 1 kg ball (r = 0.05) on a massless arm, hinged to the world at z = 2 about +Y."""
    pivot = (0.0, 0.0, 2.0)
    q = quat_from_axis_angle((0.0, 1.0, 0.0), theta0)
    off = quat_rotate(q, (0.0, 0.0, -length))
    bob = Body(
        "pend.bob",
        (pivot[0] + off[0], pivot[1] + off[1], pivot[2] + off[2]),
        q,
        mass=1.0,
        geoms=[Geom("pend.bob.geometry", "sphere", radius=0.05)],
    )
    world = Connector("pend.world_connector", None, pivot, (0.0, 1.0, 0.0), (1.0, 0.0, 0.0))
    top = Connector("pend.bob.top", bob.path, (0.0, 0.0, length), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0))
    return Scene("Pendulum", [bob], [Mate("pend.hinge", "hinge", (world, top), initial_angle=theta0)])


def linear_range(reverse: bool = False) -> Scene:
    """AGXUnity LinearRangeTest: a rod on a world prismatic (world main +Z normal +Y; rod connector at
    rod-local z -0.5, main -Z normal -Y), initial_position -0.25, LinearRange -0.5..0.  The rod falls
    until the range stops it with its origin at z = -1.0.  ``reverse`` lists the connectors the other
    way round (q negated: initial_position +0.25, range 0..0.5) - same physics, MuJoCo sign -1."""
    rod = Body(
        "test.rod",
        (0.0, 0.0, -0.75),
        (0.0, 1.0, 0.0, 0.0),  # 180 deg about X
        mass=1.0,
        geoms=[Geom("test.rod.geometry", "box", size=(0.05, 0.05, 1.0))],
    )
    world = Connector("test.world", None, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 1.0, 0.0))
    rc = Connector("test.rod.connector", rod.path, (0.0, 0.0, -0.5), (0.0, 0.0, -1.0), (0.0, -1.0, 0.0))
    pair = (rc, world) if reverse else (world, rc)
    init, start, end = (0.25, 0.0, 0.5) if reverse else (-0.25, -0.5, 0.0)
    mate = Mate("test.prismatic", "prismatic", pair, initial_position=init)
    rng = Controller("test.range", "range", "linear", pair, start=start, end=end, min_effort=0.0)
    return Scene("LinearRange", [rod], [mate], [rng])


def drop_box(ground_collides: bool = True) -> Scene:
    box = Body(
        "drop.box",
        (0.0, 0.0, 1.0),
        geoms=[Geom("drop.box.geometry", "box", size=(0.4, 0.4, 0.4))],
        source=Source("drop.openplx", 3, 5),
    )
    ground = Body(
        "drop.ground",
        is_dynamic=False,
        geoms=[
            Geom("drop.ground.geometry", "box", size=(10.0, 10.0, 0.1), enable_collisions=ground_collides)
        ],
    )
    return Scene("Drop", [box, ground])


def four_bar(theta: float = 0.5) -> Scene:
    """Parallelogram linkage: two 0.5 m cranks hinged to the world at x = 0 and x = 1 (z = 2),
    joined by a 1 m coupler.  Four hinges about Y: one of them must close the loop."""
    y = (0.0, 1.0, 0.0)
    q = quat_from_axis_angle(y, theta)
    s, c = math.sin(theta), math.cos(theta)
    crank_geom = {"size": (0.04, 0.04, 0.5), "pos": (0.0, 0.0, -0.25)}
    a = Body("fb.crank_a", (0.0, 0.0, 2.0), q, geoms=[Geom("fb.crank_a.geometry", "box", **crank_geom)])
    b = Body("fb.crank_b", (1.0, 0.0, 2.0), q, geoms=[Geom("fb.crank_b.geometry", "box", **crank_geom)])
    cp = Body(
        "fb.coupler",
        (0.5 - 0.5 * s, 0.0, 2.0 - 0.5 * c),
        geoms=[Geom("fb.coupler.geometry", "box", size=(1.0, 0.04, 0.04))],
    )

    def conn(path: str, body: str | None, pos: tuple[float, float, float]) -> Connector:
        return Connector(path, body, pos, y, (1.0, 0.0, 0.0))

    mates = [
        Mate(
            "fb.hinge_a",
            "hinge",
            (conn("fb.wa", None, (0.0, 0.0, 2.0)), conn("fb.crank_a.top", a.path, (0, 0, 0))),
            initial_angle=theta,
        ),
        Mate(
            "fb.hinge_ac",
            "hinge",
            (conn("fb.crank_a.bottom", a.path, (0, 0, -0.5)), conn("fb.coupler.left", cp.path, (-0.5, 0, 0))),
            initial_angle=-theta,
        ),
        Mate(
            "fb.hinge_bc",
            "hinge",
            (conn("fb.crank_b.bottom", b.path, (0, 0, -0.5)), conn("fb.coupler.right", cp.path, (0.5, 0, 0))),
            initial_angle=-theta,
        ),
        Mate(
            "fb.hinge_b",
            "hinge",
            (conn("fb.wb", None, (1.0, 0.0, 2.0)), conn("fb.crank_b.top", b.path, (0, 0, 0))),
            initial_angle=theta,
            source=Source("fb.openplx", 30, 5),
        ),
    ]
    return Scene("FourBar", [a, b, cp], mates)


# ---------------------------------------------------------------------------------------- tests


def test_boxtruck_tutorial_motors_spin_the_truck_clockwise() -> None:
    """Both motors at +1 rad/s.  q is connectors[1] (wheel) relative to connectors[0] (chassis) about
    the chassis connector's main axis: -Y on the left, +Y on the right.  The left wheel spinning about
    -Y pushes the truck towards -X (the front), the right wheel about +Y pushes towards +X: the
    two front wheels fight and the truck yaws clockwise (negative about Z) almost in place, with the
    front wheels slipping - it does not drive forward (the tutorial's own controller script sends
    -target to the right motor to drive)."""
    scene = boxtruck(1.0, 1.0)
    for mate in scene.mates:  # the hand-made SNAP result: connector frames coincide
        (p0, a0, n0), (p1, a1, n1) = (scene.connector_world(c) for c in mate.connectors)
        assert p0 == pytest.approx(p1) and a0 == pytest.approx(a1) and n0 == pytest.approx(n1)
    compiled = compile_scene(scene)
    assert compiled.ok, [n.message for n in compiled.notes]
    assert not any(n.code == "A131" for n in compiled.notes)  # SNAP result: no broken invariant
    # 6 bodies and the world, and the references of the two motors' velocity constraints
    assert compiled.model.nbody == 7 + 2 and compiled.model.njnt == 5 + 2 and compiled.model.nu == 2
    assert compiled.free_roots == ["boxTruck.chassis"]  # chassis carries 4 mates: it is the root
    assert sorted(compiled.joint_sign.values()) == [1, 1, 1, 1]  # wheels (connectors[1]) are children
    codes = {n.code for n in compiled.notes}
    assert "A113" in codes  # stiff unlimited motors are velocity constraints: no gain clamped (A111)
    assert codes <= {"A113"}  # restitution and the like are the static checks' findings
    assert compiled.model.npair == 4  # one wheel/ground pair per wheel
    assert compiled.model.nexclude == 10  # the self-disabled collision group: 5 bodies -> 10 pairs

    res = simulate(compiled, 5.0)
    assert res.ok and res.blowup is None and res.steps == 2500
    ch = res.bodies["boxTruck.chassis"]
    assert ch.initial_pos == pytest.approx([0.0, 0.0, 1.1])
    # settles ~0.1 m: wheel bottoms start 0.1488 above z 0, the ground top is at 0.05
    assert ch.final_pos[2] == pytest.approx(1.001, abs=0.005)
    assert -0.3 < ch.heading_change < -0.05  # clockwise
    # it turns, the front wheels slipping, and gets 0.73 m in 5 s (1.3 m when driving straight; 0.45 m
    # on MuJoCo's default soft contact, before normal_restitution 0 became a plastic, nearly hard one)
    assert ch.horizontal_distance < 1.0
    for m in res.motors.values():
        # the two motors fight through the ground; as velocity constraints without an effort
        # limit (as AGX's), they hold 1 rad/s and the front wheels slip
        assert m.mean_speed == pytest.approx(1.0, abs=1e-3)
    for mate in res.mates.values():
        assert mate.max_separation < 1e-6 and mate.max_misalignment < 1e-6 and not mate.pulled_apart
    assert not res.fall_through and not res.penetrations
    json.dumps(res.to_dict())  # plain data out


def test_boxtruck_drives_forward_when_right_motor_is_negated() -> None:
    """The controller script drives forward with (+v, -v): the truck rolls towards -X (the front
    connectors are at -X) at wheel radius x speed = 0.26 m/s."""
    res = simulate(boxtruck(1.0, -1.0), 5.0)
    ch = res.bodies["boxTruck.chassis"]
    assert res.ok and res.blowup is None
    # ~0.2 s to land and spin up, then 0.26 m/s
    assert ch.displacement[0] == pytest.approx(-1.25, abs=0.06)
    assert abs(ch.displacement[1]) < 0.01 and abs(ch.heading_change) < 0.01
    assert ch.path_length == pytest.approx(1.35, abs=0.1)  # includes the 0.1 m drop
    for w in ("front_left", "rear_right"):
        assert res.bodies[f"boxTruck.{w}_wheel"].final_pos[2] == pytest.approx(0.31, abs=0.005)  # 0.05 + r


def test_pendulum_period_matches_analytic_value() -> None:
    theta0, length = 0.1, 1.0
    compiled = compile_scene(pendulum(theta0, length))
    assert compiled.ok and compiled.free_roots == []  # hangs from the world, no free joint
    res = simulate(compiled, 4.2, sample_dt=0.002, record=True)
    t = np.array(res.trace["time"])
    q = np.array(res.trace["joints"]["pend.hinge"])
    assert q[0] == pytest.approx(theta0)  # joint ref = initial_angle: q starts at the SNAP offset
    # downward zero crossings -> period
    idx = np.where((q[:-1] > 0) & (q[1:] <= 0))[0]
    tc = t[idx] + (t[idx + 1] - t[idx]) * q[idx] / (q[idx] - q[idx + 1])
    period = float(np.mean(np.diff(tc)))
    i_cm = 0.4 * 1.0 * 0.05**2
    analytic = 2 * math.pi * math.sqrt((i_cm + length**2) / (G * length)) * (1 + theta0**2 / 16)
    assert period == pytest.approx(analytic, rel=5e-3)
    assert res.mates["pend.hinge"].max_separation < 1e-9


@pytest.mark.parametrize("reverse", [False, True])
def test_prismatic_range_stops_at_the_limit(reverse: bool) -> None:
    compiled = compile_scene(linear_range(reverse))
    assert compiled.ok
    assert compiled.joint_sign["test.prismatic"] == (-1 if reverse else 1)
    res = simulate(compiled, 1.5, record=True)
    rod = res.bodies["test.rod"]
    assert rod.initial_pos[2] == pytest.approx(-0.75)
    assert rod.final_pos[2] == pytest.approx(-1.0, abs=2e-3)
    q = res.trace["joints"]["test.prismatic"]
    assert q[0] == pytest.approx(0.25 if reverse else -0.25)
    assert q[-1] == pytest.approx(0.5 if reverse else -0.5, abs=2e-3)
    assert not res.joint_limit_violations


def test_box_rests_on_static_ground() -> None:
    res = simulate(drop_box(True), 2.0)
    box = res.bodies["drop.box"]
    assert res.ok and not res.fall_through
    assert box.final_pos[2] == pytest.approx(0.05 + 0.2, abs=3e-3)  # ground top + half height
    assert res.bodies["drop.ground"].final_pos == [0.0, 0.0, 0.0]


def test_initial_penetration_is_reported() -> None:
    scene = drop_box(True)
    scene.bodies[0].world_pos = (0.0, 0.0, 0.2)  # bottom at 0.0, ground top at 0.05
    res = simulate(scene, 0.2)
    assert len(res.penetrations) == 1  # one entry per geometry pair, deepest contact
    p = res.penetrations[0]
    assert {p["geom1"], p["geom2"]} == {"drop.ground.geometry", "drop.box.geometry"}
    assert p["depth"] == pytest.approx(0.05, abs=1e-6) and p["contacts"] == 4
    assert any(n.code == "A104" for n in res.notes)


def test_initial_velocities_and_heading() -> None:
    """Free root: linear velocity in world, angular velocity given in world (stored body-local)."""
    q = quat_from_axis_angle((0.0, 0.0, 1.0), math.pi / 2)
    box = Body(
        "v.box",
        (0.0, 0.0, 0.0),
        q,
        geoms=[Geom("v.box.g", "box", size=(0.3, 0.2, 0.1))],
        lin_vel=(1.0, 0.5, 0.0),
        ang_vel=(0.0, 0.0, 0.8),
    )
    res = simulate(Scene("Vel", [box], gravity=(0.0, 0.0, 0.0)), 2.0)
    b = res.bodies["v.box"]
    assert b.displacement == pytest.approx([2.0, 1.0, 0.0], abs=1e-9)
    assert b.heading_change == pytest.approx(1.6, abs=1e-6)
    assert b.max_speed == pytest.approx(math.hypot(1.0, 0.5), rel=1e-6)


@pytest.mark.parametrize(
    ("mate_order", "motor_order", "sign", "spin"),
    [("wd", "wd", 1, 1.0), ("dw", "dw", -1, -1.0), ("wd", "dw", 1, -1.0)],
)
def test_motor_sign_follows_connector_order(
    mate_order: str, motor_order: str, sign: int, spin: float
) -> None:
    """q = connectors[1] relative to connectors[0] about the main axis (+Z here), whichever body
    MuJoCo makes the child; a motor listing the mate's connectors reversed drives -q."""
    base = Body(
        "m.base", (0.0, 0.0, 0.5), is_dynamic=False, geoms=[Geom("m.base.g", "box", size=(0.4, 0.4, 0.2))]
    )
    disc = Body(
        "m.disc",
        (0.0, 0.0, 1.0),
        geoms=[
            Geom(
                "m.disc.g",
                "cylinder",
                radius=0.3,
                height=0.05,
                quat=quat_from_axis_angle((1.0, 0.0, 0.0), math.pi / 2),
            )
        ],
    )
    cw = Connector("m.base.c", base.path, (0.0, 0.0, 0.5), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    cd = Connector("m.disc.c", disc.path, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    order = {"wd": (cw, cd), "dw": (cd, cw)}
    scene = Scene(
        "Disc",
        [base, disc],
        [Mate("m.hinge", "hinge", order[mate_order])],
        [
            Controller(
                "m.motor",
                "velocity_motor",
                "rotational",
                order[motor_order],
                target_speed=1.0,
                max_effort=50.0,
                min_effort=-50.0,
            )
        ],
    )
    compiled = compile_scene(scene)
    assert compiled.ok and compiled.joint_sign["m.hinge"] == sign
    assert compiled.model.body_parentid[compiled.model.body("m.disc").id] == compiled.model.body("m.base").id
    # a stiff motor with a symmetric range is a velocity constraint: the range is its tendon's friction bound
    assert compiled.model.tendon_frictionloss[0] == pytest.approx(50.0)
    assert ("A122" in {n.code for n in compiled.notes}) == (mate_order != motor_order)
    res = simulate(compiled, 1.0, record=True)
    # 50 N m on I = 0.636 kg m^2: 1 rad/s after ~13 ms, then 1 rad/s (the constraint at its bound, then holding)
    assert compiled.actuators[0].kv is None and compiled.actuators[0].reference is not None
    assert res.bodies["m.disc"].heading_change == pytest.approx(spin * 0.994, abs=0.003)
    assert res.motors["m.motor"].mean_speed == pytest.approx(1.0, abs=1e-6)  # in the motor's own q
    q = res.trace["joints"]["m.hinge"]
    assert q[-1] == pytest.approx(spin * 0.994 * (1.0 if mate_order == "wd" else -1.0), abs=0.003)


def test_box_falls_through_ground_without_collisions() -> None:
    res = simulate(drop_box(False), 1.0)
    assert not res.ok
    assert [f["body"] for f in res.fall_through] == ["drop.box"]
    # free fall from z 1.0 to below the ground top (0.05 - 0.01 margin): t = sqrt(2*0.96/g) = 0.44 s
    assert res.fall_through[0]["time"] == pytest.approx(math.sqrt(2 * 0.96 / G), abs=0.015)
    note = next(n for n in res.notes if n.code == "A102")
    assert note.severity == "error" and note.source == Source("drop.openplx", 3, 5)


def test_blowup_is_detected_and_timed() -> None:
    """An honest failure: a 1 kg box whose torque motor applies 1e9 N m about a free hinge."""
    box = Body("spin.box", (0.0, 0.0, 1.0), geoms=[Geom("spin.box.geometry", "box", size=(0.2, 0.2, 0.2))])
    w = Connector("spin.w", None, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    bc = Connector("spin.box.c", box.path, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    scene = Scene(
        "Spin",
        [box],
        [Mate("spin.hinge", "hinge", (w, bc))],
        [Controller("spin.motor", "torque_motor", "rotational", (w, bc), effort=1e9)],
    )
    res = simulate(scene, 1.0)
    assert not res.ok and res.blowup is not None
    assert 0.0 < res.blowup["time"] <= 0.05
    assert any(n.code == "A101" and n.severity == "error" for n in res.notes)


def test_loop_closing_hinge_becomes_equality() -> None:
    compiled = compile_scene(four_bar(0.5))
    assert compiled.ok
    assert compiled.loop_mates == ["fb.hinge_b"]
    assert compiled.tree_mates == ["fb.hinge_a", "fb.hinge_ac", "fb.hinge_bc"]
    m = compiled.model
    assert m.njnt == 3 and m.neq == 2  # hinge loop -> two connect equalities on the axis
    import mujoco

    assert all(m.eq_type[i] == mujoco.mjtEq.mjEQ_CONNECT for i in range(m.neq))
    assert any(n.code == "A114" and n.path == "fb.hinge_b" for n in compiled.notes)
    res = simulate(compiled, 2.0)
    assert res.ok and res.blowup is None
    loop = res.mates["fb.hinge_b"]
    assert loop.role == "loop" and loop.max_separation < 2e-3 and not loop.pulled_apart
    # a parallelogram keeps the coupler level while it swings
    coupler = res.bodies["fb.coupler"]
    qw = coupler.final_quat[0]
    assert abs(qw) > math.cos(0.01 / 2)  # rotated by < 0.01 rad
    assert coupler.path_length > 0.5  # and it did swing


def test_exported_mjcf_reloads_with_same_initial_poses(tmp_path) -> None:
    import mujoco

    compiled = compile_scene(boxtruck())
    path = tmp_path / "boxtruck.xml"
    xml = export_mjcf(compiled, str(path))
    assert path.read_text() == xml and 'name="initial"' in xml and 'ctrl="1 1"' in xml
    m2 = mujoco.MjModel.from_xml_string(xml)
    m1 = compiled.model
    assert (m2.nbody, m2.njnt, m2.nu, m2.npair, m2.nexclude) == (
        m1.nbody,
        m1.njnt,
        m1.nu,
        m1.npair,
        m1.nexclude,
    )
    d1, d2 = mujoco.MjData(m1), mujoco.MjData(m2)
    mujoco.mj_resetDataKeyframe(m1, d1, 0)
    mujoco.mj_resetDataKeyframe(m2, d2, 0)
    mujoco.mj_forward(m1, d1)
    mujoco.mj_forward(m2, d2)
    np.testing.assert_allclose(d2.xpos, d1.xpos, atol=1e-9)
    np.testing.assert_allclose(np.abs(d2.xquat), np.abs(d1.xquat), atol=1e-9)
    np.testing.assert_allclose(d2.ctrl, [1.0, 1.0])
    np.testing.assert_allclose(m2.body_mass, m1.body_mass, rtol=1e-9)
    np.testing.assert_allclose(m2.actuator_gear[:, 0], m1.actuator_gear[:, 0])
    wheel = m1.body("boxTruck.front_right_wheel").id
    np.testing.assert_allclose(d1.xpos[wheel], [-1.023, 0.748, 1.1 - 0.6912], atol=1e-12)
    assert m1.body_mass[wheel] == pytest.approx(10.0)
    assert m1.body_mass[m1.body("boxTruck.chassis").id] == pytest.approx(1000.0)


def test_unsupported_and_invalid_features_become_notes(tmp_path) -> None:
    src = Source("bad.openplx", 12, 5, 12, 30)
    a = Body("bad.a", (0.0, 0.0, 1.0), mass=2.0, geoms=[Geom("bad.a.geometry", "box", size=(0.2, 0.2, 0.2))])
    b = Body(
        "bad.b",
        (1.0, 0.0, 1.0),
        geoms=[
            Geom("bad.b.geometry", "sphere", radius=0.1),
            Geom("bad.b.visual", "mesh", mesh_file="missing.obj", visual_only=True, source=src),
            Geom("bad.b.flat", "box", size=(0.0, 0.0, 0.0)),
        ],
    )
    ca = Connector("bad.a.c", a.path, (0.5, 0.0, 0.0))
    cb = Connector("bad.b.c", b.path, (-0.5, 0.0, 0.0))
    cz = Connector("bad.a.z", a.path, (0.0, 0.0, 0.0))
    scene = Scene(
        "Bad",
        [a, b],
        [
            Mate("bad.distance", "distance", (ca, cb), initial_distance=0.0),
            Mate("bad.slider", "prismatic", (cz, cb)),
        ],
        [
            Controller("bad.motor", "velocity_motor", "rotational", (cz, cb), target_speed=1.0),
            Controller("bad.orphan", "torque_motor", "rotational", (ca, cz), source=src),
        ],
        [ContactModel("bad.contact", "m1", "m2", friction=0.5, restitution=0.5)],
        unsupported=[Unsupported("DriveTrain.Gear", "bad.gear", src)],
        base_dir=str(tmp_path),
    )
    compiled = compile_scene(scene)
    assert compiled.ok  # problems are reported, not fatal
    by_path = {n.path: n for n in compiled.notes if n.code == "A131"}
    # what the static checks own reaches the backend only as a broken invariant (A131), naming the owner
    assert "A021" in by_path["bad.motor"].message and "A020" in by_path["bad.orphan"].message
    assert "A030" in by_path["bad.b.flat"].message and by_path["bad.b.flat"].severity == "error"
    assert "A031" in by_path["bad.b.visual"].message and by_path["bad.b.visual"].source == src
    # a mate that starts apart (A016) is a scene the backend runs on purpose (built as written): no A131
    assert "bad.slider" not in by_path
    assert by_path["bad.orphan"].source == src
    codes = {n.code for n in compiled.notes}
    assert "A116" in codes  # the distance mate approximation is the backend's own finding
    assert not any(n.path == "bad.gear" for n in compiled.notes)  # the static checks own A040
    assert {n.code for n in compiled.notes if n.path == "bad.contact"} <= {"A128"}  # no geometry: no pair, no A137
    res = simulate(compiled, 0.5)
    assert res.blowup is None
    assert json.loads(json.dumps(res.to_dict()))["notes"]


def test_mujoco_compile_error_points_at_openplx_element(tmp_path) -> None:
    bad_mesh = tmp_path / "broken.stl"
    bad_mesh.write_text("this is not an stl file")
    src = Source("mesh.openplx", 7, 9)
    body = Body(
        "m.body",
        (0.0, 0.0, 1.0),
        mass=1.0,
        geoms=[Geom("m.body.shape", "mesh", mesh_file="broken.stl", source=src)],
    )
    compiled = compile_scene(Scene("Mesh", [body], base_dir=str(tmp_path)))
    assert not compiled.ok
    err = next(n for n in compiled.notes if n.code == "A110")
    assert err.path == "m.body.shape" and err.source == src
    res = simulate(compiled, 1.0)
    assert not res.ok and res.steps == 0


def test_mesh_geometry_from_file_and_vertices(tmp_path) -> None:
    obj = tmp_path / "tet.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    verts = ((0.0, 0.0, 0.0), (0.2, 0.0, 0.0), (0.0, 0.2, 0.0), (0.0, 0.0, 0.2))
    body = Body(
        "m.body",
        (0.0, 0.0, 0.5),
        geoms=[
            Geom("m.body.file", "mesh", mesh_file="tet.obj", mesh_scale=(0.3, 0.3, 0.3), convex=False),
            Geom("m.body.hull", "mesh", mesh_vertices=verts, pos=(0.5, 0.0, 0.0)),
        ],
    )
    ground = Body("m.ground", is_dynamic=False, geoms=[Geom("m.ground.plane", "plane", size=(4.0, 4.0, 0.0))])
    compiled = compile_scene(Scene("Mesh", [body, ground], base_dir=str(tmp_path)))
    assert compiled.ok, [n.message for n in compiled.notes]
    assert compiled.model.nmesh == 2
    assert any(n.code == "A117" for n in compiled.notes)
    # density 1000: tetrahedra of edge 0.3 and 0.2 -> (0.027 + 0.008) / 6 m^3
    assert compiled.model.body("m.body").mass[0] == pytest.approx(1000 * (0.027 + 0.008) / 6, rel=1e-6)
    res = simulate(compiled, 1.0)
    assert res.ok and res.bodies["m.body"].final_pos[2] < 0.1  # landed on the plane


def test_render_png_writes_a_real_image(tmp_path) -> None:
    path = tmp_path / "truck.png"
    try:
        info = render_png(boxtruck(), str(path), 320, 240)
    except RenderUnavailable as err:
        pytest.skip(f"offscreen rendering unavailable: {err}")
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 1000
    # decode our own PNG (8-bit RGB, filter 0 rows) and check the pixels vary
    idat = b""
    pos = 8
    while pos < len(data):
        n = int.from_bytes(data[pos : pos + 4], "big")
        tag = data[pos + 4 : pos + 8]
        if tag == b"IDAT":
            idat += data[pos + 8 : pos + 8 + n]
        pos += 12 + n
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(240, 1 + 320 * 3)
    pix = raw[:, 1:].reshape(240, 320, 3)
    assert len(np.unique(pix.reshape(-1, 3), axis=0)) > 20
    assert info["distinct_colours"] > 20
    assert pix.std() > 10


def test_linear_spring_equilibrium_time_step_and_stiffness_clamp() -> None:
    """1 kg on a vertical prismatic (q = body along +Z), spring rest 0, damping 20: rests at -m g / k.
    The default stiffness 1e6 shortens the time step (A133) and is simulated as given; 1e10 is
    beyond even the shortest step (1e-4 s) and is clamped to I_eff (0.2 / 1e-4)^2 = 4e6 (A112, a warning)."""
    m = Body("s.m", (0.0, 0.0, 1.0), mass=1.0, geoms=[Geom("s.m.g", "box", size=(0.1, 0.1, 0.1))])
    w = Connector("s.w", None, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    mc = Connector("s.m.c", m.path, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    for k, k_used, h, codes in ((100.0, 100.0, 0.002, set()), (1e6, 1e6, 0.002 / 10, {"A133"}),
                                (1e10, 4e6, 1e-4, {"A133", "A112"})):
        spring = Controller("s.spring", "spring", "linear", (w, mc), stiffness=k, damping=20.0)
        compiled = compile_scene(Scene("Spring", [m], [Mate("s.p", "prismatic", (w, mc))], [spring]))
        assert compiled.model.jnt_stiffness[0] == pytest.approx(k_used)
        assert compiled.model.opt.timestep == pytest.approx(h)
        assert {n.code for n in compiled.notes} & {"A112", "A133"} == codes
        assert all(n.severity == "warning" for n in compiled.notes if n.code == "A112")
        res = simulate(compiled, 3.0, record=True)
        assert res.trace["joints"]["s.p"][-1] == pytest.approx(-G / k_used, rel=1e-4)


def test_distance_mate_holds_rope_length() -> None:
    bob = Body("r.bob", (0.6, 0.0, 1.2), mass=1.0, geoms=[Geom("r.bob.g", "sphere", radius=0.05)])
    rope = Mate(
        "r.rope",
        "distance",
        (Connector("r.w", None, (0.0, 0.0, 2.0)), Connector("r.bob.c", bob.path)),
        initial_distance=1.0,
    )
    compiled = compile_scene(Scene("Rope", [bob], [rope]))
    assert compiled.model.ntendon == 1 and compiled.model.neq == 1
    res = simulate(compiled, 3.0)
    rep = res.mates["r.rope"]
    assert rep.role == "distance" and rep.initial_separation < 1e-12
    assert rep.max_separation < 5e-3 and not rep.pulled_apart  # |length - 1 m|, soft equality
    assert res.bodies["r.bob"].min_z == pytest.approx(1.0, abs=5e-3)  # swings through the bottom


def test_mass_properties_follow_agx_rules() -> None:
    sphere = [Geom("g", "sphere", radius=0.1)]
    scene = Scene(
        "Mass",
        [
            Body("a", (0.0, 0.0, 1.0)),  # no mass, no geometry
            Body(
                "b", (1.0, 0.0, 1.0), mass=3.0, geoms=[Geom("b.g", "box", size=(0.2, 0.4, 0.6))]
            ),  # scaled shape
            Body(
                "c",
                (2.0, 0.0, 1.0),
                mass=2.0,
                inertia_tensor=((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 5.0)),
                geoms=sphere,
            ),
            Body("d", (3.0, 0.0, 1.0), geoms=[Geom("d.g", "box", size=(0.1, 0.1, 0.1), density=500.0)]),
        ],
    )
    compiled = compile_scene(scene)
    m = compiled.model
    notes = {n.path: n.message for n in compiled.notes if n.code == "A131"}
    assert set(notes) == {"a", "c"} and "A033" in notes["a"] and "A034" in notes["c"]
    assert m.body("a").mass[0] == pytest.approx(1.0)
    assert m.body("b").mass[0] == pytest.approx(3.0)
    # box inertia with the given mass: m/12 (y^2+z^2, x^2+z^2, x^2+y^2)
    assert sorted(m.body("b").inertia) == pytest.approx(sorted([3.0 / 12 * v for v in (0.52, 0.40, 0.20)]))
    assert m.body("c").inertia == pytest.approx([0.4 * 2.0 * 0.01] * 3)  # tensor rejected -> sphere
    assert m.body("d").mass[0] == pytest.approx(0.5)  # density 500 x 1e-3 m^3


def test_a_plane_on_a_moving_body_is_skipped_with_a127(tmp_path) -> None:
    """A127: no bundle geometry becomes a plane, but a scene built through the Python API may hold one;
    MuJoCo planes cannot move, so on a dynamic body it is left out, said, and the rest still runs."""
    body = Body("m.raft", (0.0, 0.0, 1.0), geoms=[Geom("m.raft.deck", "plane", size=(2.0, 2.0, 0.0)),
                                                  Geom("m.raft.hull", "box", size=(0.5, 0.5, 0.1))])
    compiled = compile_scene(Scene("Raft", [body], base_dir=str(tmp_path)))
    notes = [n for n in compiled.notes if n.code == "A127"]
    assert compiled.ok and len(notes) == 1 and "m.raft.deck" in notes[0].message, compiled.notes
    assert compiled.model.ngeom == 1  # the box alone
    assert simulate(compiled, 0.1).bodies["m.raft"].final_pos[2] < 1.0  # it falls: still simulated
