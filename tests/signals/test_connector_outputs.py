"""Outputs of mate connectors (issue 29, point 5) against hand-computed values for an arm turning
about the world z axis, through the Python API and `plx test`; RpmOutput of a hinge and a shaft."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from plxtools.check.api import NotSimulatedError, load
from tests.conftest import run_plx

ROTOR = "tests/signals/models/rotor.openplx"
G = 9.80665
# the tip connector's frame in the arm: z = main_axis (0, 1, 0), x = normal (1, 0, 0), y = z x x
TIP_AXES = np.column_stack([(1.0, 0.0, 0.0), (0.0, 0.0, -1.0), (0.0, 1.0, 0.0)])


def rz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def from_rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    return rz(yaw) @ ry @ rx


@pytest.fixture(scope="module")
def turned():
    """The rotor after 1.3 s at 2 rad/s, with the hinge's own angle and speed."""
    sim = load(ROTOR, "Rotor")
    sim.step(1.3)
    return sim, sim.read("hinge.angle_output"), sim.read("hinge.angular_velocity_output")


def test_the_arm_turns_as_driven(turned):
    _, theta, w = turned
    assert w == pytest.approx(2.0, rel=1e-6) and theta == pytest.approx(2.6, abs=0.01)


def test_position_and_orientation_of_the_tip_frame(turned):
    sim, th, _ = turned
    assert sim.read("arm.tip_position") == pytest.approx((math.cos(th), math.sin(th), 0.0), abs=1e-9)
    r = from_rpy(*sim.read("arm.tip_rpy"))
    assert r == pytest.approx(rz(th) @ TIP_AXES, abs=1e-9)


def test_velocity_and_acceleration_of_the_tip_not_of_the_centre_of_mass(turned):
    """The tip is 1 m from the axis, the centre of mass 0.5 m: v = w r, a = -w^2 r (no angular
    acceleration at a steady speed)."""
    sim, th, w = turned
    assert sim.read("arm.tip_velocity") == pytest.approx((-w * math.sin(th), w * math.cos(th), 0.0), abs=1e-9)
    assert sim.read("arm.tip_spin") == pytest.approx((0.0, 0.0, w), abs=1e-9)
    acc = sim.read("arm.tip_acceleration")
    assert acc == pytest.approx((-w * w * math.cos(th), -w * w * math.sin(th), 0.0), abs=1e-6)
    assert sim.read("arm.tip_angular_acceleration") == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    # the body's own outputs are of its centre of mass, half as far out
    assert sim.read("arm.linear_velocity_world_output") == pytest.approx(
        (-w * 0.5 * math.sin(th), w * 0.5 * math.cos(th), 0.0), abs=1e-9)


def test_relative_to_a_connector_fixed_in_the_world(turned):
    """viewpoint sits at z = 1 with x along world y and y along world -x: a point (px, py, 0) is
    (py, -px, -1) there, and a velocity (vx, vy, 0) is (vy, -vx, 0)."""
    sim, th, w = turned
    px, py = math.cos(th), math.sin(th)
    assert sim.read("seen_position") == pytest.approx((py, -px, -1.0), abs=1e-9)
    vx, vy = -w * math.sin(th), w * math.cos(th)
    assert sim.read("seen_velocity") == pytest.approx((vy, -vx, 0.0), abs=1e-9)


def test_relative_to_a_moving_connector_position_is_read_and_velocity_is_refused(turned):
    sim, _, _ = turned
    # the axle seen from the tip: 1 m back along the arm's x axis, which is the tip frame's x axis
    assert sim.read("ground_from_tip") == pytest.approx((-1.0, 0.0, 0.0), abs=1e-9)
    with pytest.raises(NotSimulatedError, match="relative_to arm.tip, which moves"):
        sim.read("ground_velocity_from_tip")


def test_a_freely_falling_connector_accelerates_at_g_and_one_at_rest_does_not():
    sim = load(ROTOR, "Falling")
    sim.step(0.2)
    assert sim.read("arm.tip_acceleration") == pytest.approx((0.0, 0.0, -G), abs=1e-6)
    v = sim.read("arm.tip_velocity")
    assert v == pytest.approx((0.0, 0.0, -G * 0.2), rel=1e-6)
    # held by the hinge against gravity, the motor told to stand still: no acceleration (an
    # accelerometer would read +g here; the output is the frame's own acceleration)
    still = load(ROTOR, "Rotor")
    still.set("motor.target_angular_velocity_input", 0.0)
    still.step(0)
    assert still.read("arm.tip_acceleration") == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)


def test_rpm_of_a_hinge_that_says_it_has_one(turned):
    sim, _, w = turned
    assert sim.read("hinge.rpm_output") == pytest.approx(w * 60 / (2 * math.pi), rel=1e-9)


def test_connector_outputs_in_a_scenario(tmp_path):
    """Through `plx test`: the expectations are read between the steps, where the acceleration is
    computed for the state of that time (the same values as the API's)."""
    sim = load(ROTOR, "Rotor")
    sim.step(0.5)
    ax, vy, yaw = sim.read("arm.tip_acceleration")[0], sim.read("arm.tip_velocity")[1], sim.read("arm.tip_rpy")[2]
    scen = tmp_path / "rotor.scenario.toml"
    scen.write_text(
        f'model = "{Path(ROTOR).resolve()}"\nroot = "Rotor"\nduration = 0.5\n\n'
        f'[[expect]]\nat = 0.5\nof = "arm.tip_acceleration.x"\nequals = {ax!r}\ntolerance = 1e-9\n\n'
        f'[[expect]]\nat = 0.5\nof = "arm.tip_velocity.y"\nequals = {vy!r}\ntolerance = 1e-9\n\n'
        f'[[expect]]\nat = 0.5\nof = "arm.tip_rpy.yaw"\nequals = {yaw!r}\ntolerance = 1e-9\n\n'
        '[[expect]]\nat = 0.5\nof = "hinge.rpm_output"\nbetween = [19, 19.2]\n', encoding="utf-8")
    r = run_plx("test", str(scen))
    assert r.returncode == 0 and "4 expectations" in r.stdout, r.stdout + r.stderr
    assert ax == pytest.approx(-4.0 * math.cos(1.0), abs=0.05)  # theta = 2 rad/s * 0.5 s
    bad = tmp_path / "relative.scenario.toml"
    bad.write_text(f'model = "{Path(ROTOR).resolve()}"\nroot = "Rotor"\nduration = 0.5\n\n'
                   '[[expect]]\nat = 0.5\nof = "ground_velocity_from_tip.x"\nequals = 0\ntolerance = 1\n',
                   encoding="utf-8")
    r = run_plx("test", str(bad))
    assert r.returncode == 2 and "relative_to arm.tip, which moves" in r.stdout, r.stdout


DRIVE = """\
CountedShaft is DriveTrain.Shaft:
    with Physics.Signals.RpmOutputTrait
    rpm_output is Physics.Signals.RpmOutput:
        source: this

Drive is Physics3D.System:
    motor_shaft is CountedShaft:
        inertia.inertia: 0.5
    wheel_shaft is CountedShaft:
        inertia.inertia: 2
    gear is DriveTrain.Gear:
        ratio: 4
        connectors: [motor_shaft.output, wheel_shaft.input]
    motor is Physics1D.Interactions.RotationalVelocityMotor:
        connectors: [motor_shaft.input]
        target_speed: 0
"""


def test_rpm_of_shafts_that_say_they_have_one(tmp_path):
    f = tmp_path / "drive.openplx"
    f.write_text(DRIVE, encoding="utf-8")
    sim = load(f)
    sim.set("motor.target_angular_velocity_input", 2 * math.pi)  # one revolution a second
    sim.step(1.0)
    assert sim.read("motor_shaft.rpm_output") == pytest.approx(60.0, rel=0.01)
    assert sim.read("wheel_shaft.rpm_output") == pytest.approx(15.0, rel=0.01)  # ratio 4
    assert sim.read("wheel_shaft.rpm_output") == pytest.approx(
        sim.read("wheel_shaft.angular_velocity_output") * 60 / (2 * math.pi), rel=1e-12)


def test_connectors_on_a_kinematic_body_and_in_the_world():
    """A rim 2 m out on a table turned at a prescribed 1.5 rad/s: the circle, v = 3 m/s tangential,
    a = 4.5 m/s^2 inwards (MuJoCo gives a moved body no velocity or acceleration of its own); a
    connector of the system stays where it is."""
    sim = load("tests/signals/models/turntable.openplx")
    sim.step(1.0)
    a = 1.5 * sim.time
    assert sim.read("table.rim_position") == pytest.approx((2 * math.cos(a), 2 * math.sin(a), 0.0), abs=1e-9)
    assert sim.read("table.rim_velocity") == pytest.approx((-3 * math.sin(a), 3 * math.cos(a), 0.0), abs=1e-9)
    assert sim.read("table.rim_acceleration") == pytest.approx((-4.5 * math.cos(a), -4.5 * math.sin(a), 0.0),
                                                               abs=1e-9)
    assert sim.read("mark_position") == (0.0, 3.0, 0.0)
    with pytest.raises(NotSimulatedError, match="relative_to table.rim, which moves"):
        sim.read("mark_velocity")
