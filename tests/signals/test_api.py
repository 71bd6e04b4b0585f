"""The Python API (plxtools.check.api) against closed-form results, and its errors."""

from __future__ import annotations

import math

import pytest

from plxtools.check.api import (
    Input,
    ModelError,
    NotSimulatedError,
    RealInputSignal,
    RealRangeInputSignal,
    SignalPathError,
    SignalValueError,
    Vec3InputSignal,
    load,
)
from tests.conftest import run_plx
from tests.signals.helpers import boxtruck_copy

RIG = "tests/signals/models/rig.openplx"
ARM_INERTIA = 1.0 * (1.0 ** 2 + 0.1 ** 2) / 12  # box 1 x 0.1 x 0.1 m, 1 kg, about its z axis


@pytest.fixture(scope="module")
def rig():
    return load(RIG)


def test_torque_input_and_hinge_outputs_match_closed_form():
    sim = load(RIG)
    scene = sim.scene()
    sim.getInputSignalQueue().send(RealInputSignal.create(2.0, scene.getObject("motor.torque_input")))
    assert sim.step(0.5) == pytest.approx(0.5)
    alpha = 2.0 / ARM_INERTIA
    assert sim.read("hinge.angular_velocity_output") == pytest.approx(alpha * 0.5, rel=1e-6)
    assert sim.read("hinge.angle_output") == pytest.approx(0.5 * alpha * 0.25, rel=2e-2)  # Euler steps
    assert sim.read("my_angle") == sim.read("hinge.angle_output")  # a signal declared in the file
    assert sim.read("motor.torque_output") == pytest.approx(2.0)
    assert sim.read("arm.rpy_output")[2] == pytest.approx(sim.read("hinge.angle_output"))


def test_body_velocity_input_and_outputs_of_a_free_body():
    sim = load(RIG)
    scene = sim.scene()
    sim.getInputSignalQueue().send(Vec3InputSignal.create([1.0, 0.0, 0.0],
                                                          scene.getObject("ball.linear_velocity_world_input")))
    sim.step(0.5)
    x, y, z = sim.read("ball.position_output")
    assert x == pytest.approx(0.5) and y == pytest.approx(0.0)
    assert z == pytest.approx(5 - 0.5 * 9.80665 * 0.25, abs=0.02)
    vx, _, vz = sim.read("ball.linear_velocity_world_output")
    assert vx == pytest.approx(1.0) and vz == pytest.approx(-9.80665 * 0.5, rel=1e-6)
    state = sim.body("ball")
    assert state.position == sim.read("ball.position_output")


def test_an_input_acts_from_the_next_step_on(rig):
    sim = load(RIG)
    sim.set("motor.torque_input", 1.0)
    assert sim.read("motor.torque_output") == 0.0  # queued, not yet applied
    sim.step()
    assert sim.read("hinge.angular_velocity_output") == pytest.approx(sim.timestep / ARM_INERTIA, rel=1e-6)


def test_boxtruck_controller_as_in_the_tutorial_matches_the_scenario(tmp_path):
    """The same inputs through the API and through plx test give the same chassis position."""
    import json

    sim = load("examples/boxtruck/boxtruck.openplx")
    scene = sim.scene()
    left = scene.getObject("box_truck.front_left_motor.target_angular_velocity_input")
    right = scene.getObject("box_truck.front_right_motor.target_angular_velocity_input")
    queue = sim.getInputSignalQueue()
    queue.send(RealInputSignal.create(3.0, left))
    queue.send(RealInputSignal.create(-3.0, right))
    sim.step(2.0)
    x_api = sim.read("box_truck.chassis.position_output")[0]
    doc = json.loads(run_plx("test", "examples/boxtruck", "--output-format", "json").stdout)
    x_scenario = next(e for e in doc["scenarios"][0]["expectations"] if e["line"] == 22)["measured"]
    assert x_api == pytest.approx(x_scenario, abs=1e-3)
    assert -1.7 < x_api < -1.3


def test_torque_range_input_limits_the_motor():
    sim = load("examples/boxtruck/boxtruck.openplx")
    scene = sim.scene()
    rng = scene.getObject("box_truck.front_left_motor.torque_range_input")
    sim.getInputSignalQueue().send(RealRangeInputSignal.create([-5.0, 5.0], rng))
    sim.set("box_truck.front_left_motor.target_angular_velocity_input", 50.0)
    sim.step(0.2)
    assert sim.read("box_truck.front_left_motor.torque_range_output") == (-5.0, 5.0)
    assert abs(sim.read("box_truck.front_left_motor.torque_output")) <= 5.0 + 1e-9


def test_unknown_paths_say_what_was_meant(rig):
    scene = rig.scene()
    with pytest.raises(SignalPathError) as exc:
        scene.getObject("motor.torque_inptu")
    assert str(exc.value) == f"{RIG} has no object 'motor.torque_inptu'; did you mean 'motor.torque_input'?"
    assert exc.value.suggestion == "motor.torque_input"
    with pytest.raises(SignalPathError, match="did you mean 'ball'"):
        rig.body("bal")
    assert isinstance(scene.getObject("motor.torque_input"), Input)
    assert scene.getObject("hinge").type == "Physics3D.Interactions.Hinge"


def test_values_of_the_wrong_kind_and_unmapped_signals(rig):
    scene = rig.scene()
    queue = rig.getInputSignalQueue()
    torque = scene.getObject("motor.torque_input")
    with pytest.raises(SignalValueError, match="motor.torque_input takes a number, not the text 'x'"):
        queue.send(RealInputSignal.create("x", torque))
    with pytest.raises(SignalValueError, match="takes a finite number"):
        queue.send(RealInputSignal.create(math.nan, torque))
    with pytest.raises(SignalValueError, match="send a Vec3InputSignal, not a RealInputSignal"):
        queue.send(RealInputSignal.create(1.0, scene.getObject("ball.linear_velocity_world_input")))
    with pytest.raises(TypeError, match="the target must be an Input"):
        RealInputSignal.create(1.0, scene.getObject("hinge.angle_output"))
    with pytest.raises(NotSimulatedError, match="my_force is not simulated: Physics3D.Signals.Force3DOutput of a hinge is not mapped: constraint forces"):
        rig.read("my_force")
    with pytest.raises(NotSimulatedError, match="arm is attached to other bodies by mates"):
        rig.set("arm.linear_velocity_world_input", [1, 0, 0])
    with pytest.raises(ValueError, match="duration in seconds >= 0"):
        rig.step(-1)


def test_a_model_that_cannot_be_simulated_is_a_model_error(tmp_path):
    boxtruck_copy(tmp_path)
    with pytest.raises(ModelError, match="no such file"):
        load(tmp_path / "nothing.openplx")
    with pytest.raises(ModelError) as exc:
        load(tmp_path / "boxtruck.openplx", model="Truck")
    assert "no model named 'Truck'" in str(exc.value)
    assert exc.value.diagnostics[0].code == "A001"


def test_check_names_only_the_signals_it_does_not_map():
    r = run_plx("check", RIG)
    # (a message over 200 characters continues on indented lines: rules/reporters.fit)
    a040 = [ln for ln in r.stdout.replace("\n    ", " ").splitlines() if " A040 " in ln]
    assert len(a040) == 1 and a040[0].startswith(
        f"{RIG}:30:5: warning A040 my_force (Physics3D.Signals.Force3DOutput): not simulated by "
        f"the MuJoCo backend: Physics3D.Signals.Force3DOutput of a hinge is not mapped: "
        f"constraint forces of mates are not read: the bundle gives neither the point nor the frame"), r.stdout


def test_prepare_checks_an_editors_unsaved_text_instead_of_the_file(tmp_path):
    """What `plx view --web` does with the text VS Code sends: the text is checked, the disk is not
    read for it (nor written), and a broken text gives located findings, not a scene."""
    from plxtools.check.api import ModelError, prepare

    model = tmp_path / "box.openplx"
    written = ("Scene is Physics3D.System:\n    box is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n"
               "        geometry is Physics3D.Geometries.Box:\n            size: {1, 1, 1}\n")
    model.write_text(written)
    p = prepare(model, text=written.replace("{1, 1, 1}", "{3, 1, 1}"))
    assert p.compiled.scene.body("box").geoms[0].size == (3.0, 1.0, 1.0)
    assert prepare(model).compiled.scene.body("box").geoms[0].size == (1.0, 1.0, 1.0)
    assert model.read_text() == written
    with pytest.raises(ModelError) as exc:
        prepare(model, text=written.replace("inertia.mass: 1", "inertia.mass: heavy"))
    bad = [d for d in exc.value.diagnostics if d.code == "N003"]
    assert bad and bad[0].span.start.line == 2 and bad[0].file == str(model)
