"""A rigid velocity motor keeps its target within 0.1 % under load for any effort range, however
wide and lopsided, and when an effort-range input changes it between steps.

Closed form: a 20 kg, 1 m arm on a horizontal hinge turned upward at 0.3 rad/s by a velocity motor
needs at most m g L / 2 = 98 N m; any range that holds that keeps the arm at 0.3 rad/s.  A range
like [-1, 1e6] N m is an offset of 5e5 N m plus a friction bound of 5e5 around it
(mujoco.velocity_constraint): the constraint then pushes back with almost 5e5, and before the
softness taken out step by step (``Lag``) it ran 5 % slow; a range input took effect in the bound one
step after its offset, a kick of 15 rad/s."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

TARGET = 0.3

ARM = """
Arm is Physics3D.System:
    post is Physics3D.Bodies.RigidBody:
        is_dynamic: false
        pin is Physics3D.Interactions.MateConnector:
            main_axis: {{1, 0, 0}}
            normal: {{0, 0, 1}}
    arm is Physics3D.Bodies.RigidBody:
        inertia.mass: 20.0
        geometry is Physics3D.Geometries.Box:
            size: {{0.1, 1.0, 0.1}}
        kinematics.local_transform.position: {{0, 0.5, 0}}
        pin is Physics3D.Interactions.MateConnector:
            position: {{0, -0.5, 0}}
            main_axis: {{1, 0, 0}}
            normal: {{0, 0, 1}}
    hinge is Physics3D.Interactions.Hinge:
        connectors: [post.pin, arm.pin]
        angle_output.enabled: true
    motor is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: hinge.connectors
        target_speed: {w}
        min_effort: {lo}
        max_effort: {hi}
        torque_output.enabled: true
"""


def _arm(tmp_path, lo: str, hi: str):
    from plxtools.check.api import load

    f = tmp_path / "arm.openplx"
    f.write_text(ARM.format(w=TARGET, lo=lo, hi=hi), encoding="utf-8")
    return load(f)


def _speed_errors(sim, seconds: float) -> tuple[float, float]:
    """(largest relative speed error, the motor's torque at the end) over ``seconds``, measured
    as the hinge angle's change per step (its angle output)."""
    worst, before = 0.0, sim.read("hinge.angle_output")
    for _ in range(int(seconds / sim.timestep)):
        sim.step()
        now = sim.read("hinge.angle_output")
        worst = max(worst, abs(abs(now - before) / sim.timestep - TARGET) / TARGET)
        before = now
    return worst, abs(sim.read("motor.torque_output"))


@pytest.mark.parametrize("lo, hi", [("-1.0", "1000000.0"), ("-1000000.0", "150.0"), ("-150.0", "130.0")])
def test_any_range_that_holds_the_arm_keeps_it_on_target(tmp_path, lo, hi):
    sim = _arm(tmp_path, lo, hi)
    sim.step(0.3)  # [-150, 130] takes 0.07 s to reach its speed: 32 N m to spare
    worst, torque = _speed_errors(sim, 1.0)
    assert worst < 1e-3, (lo, hi, worst)
    assert 60.0 < torque < 99.0  # the arm's weight moment, m g L / 2 cos(angle), is what it pushes


@pytest.mark.parametrize("new", [[50.0, 1e6], [-1e6, 120.0]])
def test_a_range_input_keeps_the_motor_on_target_from_the_next_step(tmp_path, new):
    sim = _arm(tmp_path, "-500.0", "500.0")
    sim.step(0.1)
    sim.set("motor.torque_range_input", new)
    worst, _ = _speed_errors(sim, 0.5)
    assert worst < 1e-3, (new, worst)


def test_a_range_too_narrow_for_the_load_is_not_compensated_into_a_runaway(tmp_path):
    """At its limit the motor pushes its limit and no more (the softness correction stays off)."""
    sim = _arm(tmp_path, "-500.0", "500.0")
    sim.step(0.1)
    sim.set("motor.torque_range_input", [-1.0, 60.0])  # less than the 98 N m the arm's weight needs
    sim.step(0.05)
    assert sim.read("motor.torque_output") == pytest.approx(60.0, rel=1e-6)
    a0 = sim.read("hinge.angle_output")
    sim.step(0.1)
    assert sim.read("hinge.angle_output") < a0  # it falls back


SHAFT = """
Spindle is Physics3D.System:
    shaft is DriveTrain.Shaft:
        inertia.inertia: 0.4
    engine is Physics1D.Interactions.RotationalVelocityMotor:
        connectors: [shaft.input]
        target_speed: 3.0
        min_effort: {lo}
        max_effort: {hi}
        torque_output.enabled: true
    load is DriveTrain.TorqueMotor:
        connectors: [shaft.output]
"""


@pytest.mark.parametrize("lo, hi", [("-1.0", "1000000.0"), ("-1000000.0", "50.0")])
def test_a_drive_train_motor_with_a_lopsided_range_holds_its_shaft_on_target(tmp_path, lo, hi):
    """A 0.4 kg m^2 shaft at 3 rad/s against a 20 N m load: the motor pushes 20 N m, on target
    (before: 8.4 % off, h R f with f = 5e5 N m on a light shaft; and the first step's overshoot,
    which a range that can hardly brake cannot take back, made it cycle)."""
    from plxtools.check.api import load

    f = tmp_path / "spindle.openplx"
    f.write_text(SHAFT.format(lo=lo, hi=hi), encoding="utf-8")
    sim = load(f)
    sim.set("load.torque_input", -20.0)
    sim.step(0.1)  # with at most 50 N m it takes 0.04 s to reach its speed
    worst = 0.0
    for _ in range(int(0.5 / sim.timestep)):
        sim.step()
        worst = max(worst, abs(sim.read("shaft.angular_velocity_output") - 3.0) / 3.0)
    assert worst < 1e-3
    assert sim.read("engine.torque_output") == pytest.approx(20.0, rel=1e-6)
