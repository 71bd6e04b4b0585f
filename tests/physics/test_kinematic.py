"""Kinematic bodies move as prescribed and every reader sees their prescribed velocity: the trace,
the report's top speed, scenario values (``plx test``), velocity output signals and the Python API,
which steps them the way ``plx check`` does.  Closed form: a body translating at v has speed v
everywhere; a body turning at w about its origin has its centre of mass, r from the axis, move at
w r on a circle (angle w t)."""

from __future__ import annotations

import contextlib
import io
import json
import math

import pytest

pytest.importorskip("mujoco")

from physics_cases import MODELS, run_model  # noqa: E402

MODEL = MODELS / "kinematic_turntable.openplx"
V, W, R = 0.5, 2.0, 0.5  # platform speed (m/s), turntable rate (rad/s), its mass's distance from the axis (m)


def test_trace_and_report_give_the_prescribed_velocity():
    run = run_model(MODEL, 1.0)
    tr = run.trace
    assert tr["platform.vx"] == pytest.approx(V, abs=1e-12)
    assert tr["platform.x"][-1] - tr["platform.x"][0] == pytest.approx(V * 1.0, abs=1e-9)
    speed = (tr["table.vx"] ** 2 + tr["table.vy"] ** 2 + tr["table.vz"] ** 2) ** 0.5
    assert speed == pytest.approx(W * R, rel=1e-9)
    assert tr["table.wz"] == pytest.approx(W, abs=1e-12)
    # the centre of mass at angle w t: its velocity is w r (-sin w t, cos w t)
    t = tr.t[-1]
    assert tr["table.vx"][-1] == pytest.approx(-W * R * math.sin(W * t), abs=1e-9)
    bodies = next(iter(run.report["simulation"].values()))["bodies"]
    assert bodies["platform"]["max_speed"] == pytest.approx(V, rel=1e-9)
    assert bodies["table"]["max_speed"] == pytest.approx(W * R, rel=1e-9)


def test_scenario_values_and_velocity_outputs(tmp_path):
    from plxtools.cli import main

    (tmp_path / "kin.openplx").write_text(MODEL.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "kin.scenario.toml").write_text(f"""model = "kin.openplx"
duration = 1.0
[[expect]]
at = 1.0
of = "platform.vx"
equals = {V}
tolerance = 1e-9
[[expect]]
at = 0.5
of = "table.speed"
equals = {W * R}
tolerance = 1e-6
[[expect]]
at = 0.5
of = "table.angular_velocity_world_output.z"
equals = {W}
tolerance = 1e-9
""", encoding="utf-8")
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(["test", str(tmp_path / "kin.scenario.toml"), "--output-format", "json"])
    out = json.loads(buf.getvalue())
    assert code == 0, out


def test_api_moves_kinematic_bodies_as_plx_check_does():
    from plxtools.check.api import load

    sim = load(MODEL)
    sim.step(1.0)
    p = sim.body("platform")
    assert p.position[0] == pytest.approx(V * 1.0, abs=1e-9)
    assert p.linear_velocity == pytest.approx((V, 0.0, 0.0), abs=1e-12)
    t = sim.body("table")
    assert t.angular_velocity == pytest.approx((0.0, 0.0, W), abs=1e-12)
    assert t.rpy[2] == pytest.approx(W * 1.0, abs=1e-9)
    assert math.hypot(*t.linear_velocity) == pytest.approx(W * R, rel=1e-9)
    assert sim.read("platform.linear_velocity_world_output") == pytest.approx((V, 0.0, 0.0), abs=1e-12)
    # the same motion as the trace of `plx check`
    tr = run_model(MODEL, 1.0).trace
    assert t.position == pytest.approx((tr["table.x"][-1], tr["table.y"][-1], tr["table.z"][-1]), abs=1e-12)


def test_velocity_inputs_drive_a_kinematic_body():
    """AGX drives kinematic bodies by velocity signals: a new velocity acts from the next step on,
    the body continuing from where it is; the outputs read it."""
    from plxtools.check.api import load

    sim = load(MODEL)
    sim.step(0.5)
    x0 = sim.body("platform").position[0]
    sim.set("platform.linear_velocity_world_input", [-1.0, 0.25, 0.0])
    sim.set("table.angular_velocity_world_input", [0.0, 0.0, -3.0])
    sim.step(1.0)
    p = sim.body("platform")
    assert p.position[0] - x0 == pytest.approx(-1.0, abs=1e-9)
    assert p.position[1] == pytest.approx(0.25, abs=1e-9)
    assert p.linear_velocity == pytest.approx((-1.0, 0.25, 0.0), abs=1e-9)
    assert sim.read("platform.linear_velocity_world_output") == pytest.approx((-1.0, 0.25, 0.0), abs=1e-9)
    t = sim.body("table")
    assert t.angular_velocity == pytest.approx((0.0, 0.0, -3.0), abs=1e-9)
    assert math.hypot(*t.linear_velocity) == pytest.approx(3.0 * R, rel=1e-9)


def test_velocity_input_on_a_static_body_says_how_to_drive_it(tmp_path):
    from plxtools.check.api import NotSimulatedError, load

    f = tmp_path / "still.openplx"
    f.write_text(MODEL.read_text(encoding="utf-8").replace("kinematics.initial_local_linear_velocity: {0.5, 0, 0}",
                                                           "kinematics.initial_local_linear_velocity: {0, 0, 0}"))
    sim = load(f)
    with pytest.raises(NotSimulatedError) as exc:
        sim.set("platform.linear_velocity_world_input", [1.0, 0.0, 0.0])
    assert "not dynamic and does not move" in str(exc.value) and "initial velocity" in str(exc.value)
    assert "mates" not in str(exc.value)


def test_a_scenario_drives_a_kinematic_body_by_its_velocity_input(tmp_path):
    from plxtools.cli import main

    (tmp_path / "kin.openplx").write_text(MODEL.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "drive.scenario.toml").write_text("""model = "kin.openplx"
duration = 1.0
[[input]]
at = 0.5
signal = "platform.linear_velocity_world_input"
value = [0.0, 0.0, 0.2]
[[expect]]
at = 1.0
of = "platform.vz"
equals = 0.2
tolerance = 1e-9
[[expect]]
at = 1.0
of = "platform.z"
equals = 0.6
tolerance = 0.003
""", encoding="utf-8")
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(["test", str(tmp_path / "drive.scenario.toml"), "--output-format", "json"])
    assert code == 0, buf.getvalue()


def test_a_plane_on_a_kinematic_body_is_left_out_with_a127():
    """MuJoCo allows planes only on static bodies, and a kinematic body is a free one."""
    from plxtools.check.mujoco.backend import compile_scene
    from plxtools.check.scene import Body, Geom, Scene

    deck = Body("deck", (0.0, 0.0, 0.0), is_dynamic=False, lin_vel=(0.5, 0.0, 0.0),
                geoms=[Geom("deck.plane", "plane", size=(4.0, 4.0, 0.0)), Geom("deck.slab", "box", size=(1, 1, 0.1))])
    compiled = compile_scene(Scene("Deck", [deck]))
    assert compiled.ok, [n.message for n in compiled.notes]
    assert [n.code for n in compiled.notes if n.path == "deck.plane"] == ["A127"]


TURNING = """
const PuckMaterial is Physics.Geometries.Material:
    unique_name: "turning_puck"
    density: 600

const PlateMaterial is Physics.Geometries.Material:
    unique_name: "turning_plate"
    density: 1000

PuckOnPlate is Physics.Interactions.SurfaceContact.Model:
    material_1: PuckMaterial
    material_2: PlateMaterial
    normal_restitution: 0.0
    tangential_restitution: 0.0
    friction becomes Physics.Interactions.Dissipation.DryConeFriction:
        coefficient: 0.7

Turning is Physics3D.System:
    plate is Physics3D.Bodies.RigidBody:
        is_dynamic: false
        kinematics.initial_local_angular_velocity: {0, 0, 1.5}
        geometry is Physics3D.Geometries.Box:
            size: {2, 2, 0.1}
            material: PlateMaterial
    puck is Physics3D.Bodies.RigidBody:
        kinematics.local_transform.position: {0, 0.6, 0.1}
        geometry is Physics3D.Geometries.Box:
            size: {0.2, 0.2, 0.1}
            material: PuckMaterial
    contact is PuckOnPlate
"""


def test_a_box_on_a_turning_table_keeps_its_radius(tmp_path):
    """mu g = 6.9 m/s^2 > w^2 r = 1.35: after the slip the box turns with the table at w on its
    circle.  It rocked on its corners and slid 8.7 % outward in 3 s (the table's armature in MuJoCo's
    mean inertia loosened the solver's tolerance; the friction's default softness let it creep at
    w^2 r x 0.01 s); now it creeps at w^2 r h: 1.3 % in 3 s."""
    from plxtools.check.api import load

    f = tmp_path / "turning.openplx"
    f.write_text(TURNING, encoding="utf-8")
    sim = load(f)
    sim.step(0.3)
    worst_vz = 0.0
    for _ in range(int(2.7 / sim.timestep)):
        sim.step()
        worst_vz = max(worst_vz, abs(sim.body("puck").linear_velocity[2]))
    b = sim.body("puck")
    r = math.hypot(b.position[0], b.position[1])
    assert r == pytest.approx(0.6, rel=0.02)
    rate = (b.position[0] * b.linear_velocity[1] - b.position[1] * b.linear_velocity[0]) / (r * r)
    assert rate == pytest.approx(1.5, rel=1e-3)
    assert b.angular_velocity[2] == pytest.approx(1.5, rel=1e-3)
    assert worst_vz < 1e-3  # it rests on the table (before: 0.1 m/s)
