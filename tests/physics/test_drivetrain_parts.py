"""Brakes, clutches and differentials against their closed forms (check/mujoco/shaft_parts.py):
a brake holds any torque up to its capacity and slips beyond it, a clutch passes up to its capacity
and nothing once released, an open differential keeps w_left + w_right = 2 w_drive / ratio with
equal torques on its axles; their engage / engagement / lock inputs and outputs through the API."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from physics_cases import MODELS  # noqa: E402

from plxtools.check.api import load  # noqa: E402

W = "angular_velocity_output"


@pytest.mark.parametrize("torque", [4.0, 9.9, -9.9])
def test_a_brake_holds_a_torque_up_to_its_capacity(torque):
    sim = load(MODELS / "brake_hold.openplx")
    sim.set("drive.torque_input", torque)
    sim.step(0.5)
    assert abs(sim.read(f"shaft.{W}")) < 1e-5  # held (what creeps: the constraint's softness, 4e-7 rad/s per N m)
    assert sim.read("brake.torque_output") == pytest.approx(torque, rel=1e-6)


@pytest.mark.parametrize("torque", [12.0, -25.0])
def test_a_brake_slips_beyond_its_capacity(torque):
    sim = load(MODELS / "brake_hold.openplx")
    sim.set("drive.torque_input", torque)
    sim.step(0.5)
    excess = torque - 10.0 * (1 if torque > 0 else -1)
    assert sim.read(f"shaft.{W}") == pytest.approx(excess / 0.5 * 0.5, rel=1e-3)
    assert abs(sim.read("brake.torque_output")) == pytest.approx(10.0, rel=1e-9)
    assert sim.read("brake.slip_velocity_output") == pytest.approx(sim.read(f"shaft.{W}"), rel=1e-9)


def test_a_half_engaged_brake_holds_half_its_capacity():
    sim = load(MODELS / "brake_hold.openplx")
    sim.set("brake.engagement_fraction_input", 0.5)
    sim.set("drive.torque_input", 7.0)
    sim.step(0.5)
    assert sim.read(f"shaft.{W}") == pytest.approx((7.0 - 5.0) / 0.5 * 0.5, rel=1e-3)
    assert sim.read("brake.engagement_fraction_output") == 0.5


def test_an_automatic_brake_stops_the_shaft_when_engaged():
    sim = load(MODELS / "brake_engage.openplx")
    sim.step(0.2)
    assert sim.read(f"shaft.{W}") == pytest.approx(1.0, abs=1e-12)  # released: it turns on
    assert sim.read("brake.engaged_output") is False
    sim.set("brake.engage_input", True)
    sim.step(0.02)
    assert sim.read("brake.engaged_output") is True  # told to engage; the torque ramps up
    # the torque ramps over engagement_duration 0.1 s: 1000 t N m on 0.5 kg m^2, w = 1 - 1000 t^2 (the
    # engagement of each step is the one at its start: up to a step behind)
    assert 1 - 1000 * 0.02 ** 2 <= sim.read(f"shaft.{W}") <= 1 - 1000 * 0.018 ** 2
    assert 0 < sim.read("brake.engagement_fraction_output") < 0.21
    sim.step(0.016)  # stopped after sqrt(1e-3) = 31.6 ms
    assert abs(sim.read(f"shaft.{W}")) < 1e-9
    sim.step(1.0)
    assert sim.read("brake.engagement_fraction_output") == 1.0
    assert abs(sim.read(f"shaft.{W}")) < 1e-9
    assert sim.read("brake.engaged_output") is True
    sim.set("brake.engage_input", False)
    sim.step(0.05)
    assert sim.read("brake.engaged_output") is False
    assert sim.read("brake.engagement_fraction_output") == pytest.approx(0.5, abs=0.021)  # released over 0.1 s
    sim.step(0.06)
    assert sim.read("brake.engagement_fraction_output") == 0.0


def test_a_clutch_passes_up_to_its_capacity_then_the_load_and_nothing_released():
    sim = load(MODELS / "clutch_transmit.openplx")
    sim.set("load.torque_input", -3.0)
    sim.step(1.0)  # slipping: the output gains (20 - 3) / 2 rad/s^2
    assert sim.read(f"output_shaft.{W}") == pytest.approx(8.5, rel=1e-6)
    assert sim.read("clutch.torque_output") == pytest.approx(20.0, rel=1e-9)
    assert sim.read("clutch.engaged_output") is True
    sim.step(0.5)  # at 10 / 8.5 s it sticks: the clutch passes the load
    assert sim.read(f"output_shaft.{W}") == pytest.approx(10.0, rel=1e-5)
    assert sim.read("clutch.torque_output") == pytest.approx(3.0, rel=1e-3)
    sim.set("clutch.engage_input", False)
    sim.step(0.5)  # released: the load slows the output at 3 / 2 rad/s^2
    assert sim.read("clutch.torque_output") == 0.0
    assert sim.read("clutch.engaged_output") is False
    assert sim.read(f"output_shaft.{W}") == pytest.approx(10.0 - 1.5 * 0.5, rel=1e-3)


def test_an_overloaded_clutch_slips_at_its_capacity():
    sim = load(MODELS / "clutch_transmit.openplx")
    sim.set("load.torque_input", -25.0)
    sim.step(0.5)
    assert sim.read(f"output_shaft.{W}") == pytest.approx((20.0 - 25.0) / 2.0 * 0.5, rel=1e-6)
    assert sim.read("clutch.torque_output") == pytest.approx(20.0, rel=1e-9)
    assert sim.read("clutch.slip_velocity_output") == pytest.approx(10.0 + 1.25, rel=1e-4)


def test_a_differential_splits_the_speed_with_equal_torques():
    sim = load(MODELS / "differential_split.openplx")
    sim.step(0.1)
    w_in, w_l, w_r = (sim.read(f"{s}.{W}") for s in ("drive_shaft", "left", "right"))
    assert w_l + w_r == pytest.approx(2 * w_in / 2.0, rel=1e-6)
    assert (w_l, w_r) == pytest.approx((3.0, 1.0), rel=1e-6)  # equal torques: 1 kg m^2 x 3 = 3 kg m^2 x 1
    assert sim.read("differential.locked_up_output") is False
    sim.set("differential.lock_up_input", True)
    sim.step()
    apart = sim.read("left.angle_output") - sim.read("right.angle_output")
    assert apart == pytest.approx(0.2, rel=0.05)  # (3 - 1) rad/s for 0.1 s
    sim.step(0.5)
    # locked where they were (not pulled back to their starting angles), turning as one
    assert sim.read("left.angle_output") - sim.read("right.angle_output") == pytest.approx(apart, abs=1e-6)
    assert sim.read(f"left.{W}") == pytest.approx(sim.read(f"right.{W}"), rel=1e-4)
    assert sim.read(f"left.{W}") == pytest.approx(2.0, rel=1e-4)
    assert sim.read("differential.locked_up_output") is True


def test_a_held_drive_shaft_turns_the_axles_opposite(tmp_path):
    f = tmp_path / "held.openplx"
    f.write_text((MODELS / "differential_split.openplx").read_text().replace("target_speed: 4.0", "target_speed: 0.0")
                 + "    spin is Physics1D.Interactions.RotationalVelocityMotor:\n"
                   "        connectors: [left.output]\n        target_speed: 1.5\n")
    sim = load(f)
    sim.step(0.2)
    w1, w2 = sim.read(f"left.{W}"), sim.read(f"right.{W}")
    assert abs(w1) >= 0.1 and w1 == pytest.approx(1.5, rel=1e-6)
    assert w2 == pytest.approx(-w1, rel=1e-5)  # two rigid velocity constraints against one soft equality


_SCENARIO = """model = "brake_engage.openplx"
duration = 0.5

[[input]]
at = 0.2
signal = "brake.engage_input"
value = true

[[expect]]
at = 0.19
of = "shaft.angular_velocity_output"
equals = 1.0
tolerance = 1e-9

[[expect]]
at = 0.3
of = "shaft.angular_velocity_output"
abs_below = 1e-6

[[expect]]
at = 0.3
of = "brake.engaged_output"
equals = {engaged}
tolerance = 0
"""


@pytest.mark.parametrize("engaged, code", [(1, 0), (0, 1)])
def test_plx_test_engages_a_brake_and_reads_engaged(tmp_path, engaged, code):
    from tests.conftest import run_plx

    (tmp_path / "brake_engage.openplx").write_text((MODELS / "brake_engage.openplx").read_text())
    (tmp_path / "brake.scenario.toml").write_text(_SCENARIO.format(engaged=engaged))
    r = run_plx("test", str(tmp_path / "brake.scenario.toml"))
    assert r.returncode == code, r.stdout + r.stderr
    if code:  # the wrong expectation fails on the engaged output, measured true (1)
        assert "brake.engaged_output at t=0.300 s: expected 0 +- 0, measured 1" in r.stdout


def test_an_engage_input_takes_a_boolean_signal():
    from plxtools.check.api import BoolInputSignal, RealInputSignal, SignalValueError

    sim = load(MODELS / "brake_engage.openplx")
    engage = sim.getObject("brake.engage_input")
    with pytest.raises(SignalValueError, match="takes true or false"):
        sim.set("brake.engage_input", 1)
    with pytest.raises(SignalValueError, match="BoolInputSignal"):
        sim.send(RealInputSignal.create(1.0, engage))
    sim.send(BoolInputSignal.create(True, engage))
    sim.step(0.1)
    assert sim.read("brake.engaged_output") is True
    assert abs(sim.read(f"shaft.{W}")) < 1e-9


@pytest.mark.parametrize("torque", [0.5, 3.0])
def test_a_brake_on_a_geared_wheel_train(tmp_path, torque):
    """A 1 N m brake on the input shaft of gear_train.openplx (4:1 gear, a hinge actuator turning a
    4 kg wheel of radius 0.25 m): the train is one coordinate, the brake a tendon on it. It holds
    0.5 N m; under 3 N m the input accelerates at (3 - 1) / (0.5 + (2 + 0.125) / 16)."""
    f = tmp_path / "geared_brake.openplx"
    f.write_text((MODELS / "gear_train.openplx").read_text().replace(
        "    drive is Physics1D.Interactions.RotationalVelocityMotor:\n        connectors: [input_shaft.input]\n"
        "        target_speed: 8.0\n",
        "    drive is DriveTrain.TorqueMotor:\n        connectors: [input_shaft.input]\n"
        "    brake is DriveTrain.ManualBrake:\n        connectors: [input_shaft.output]\n        torque_capacity: 1.0\n"
        "        initial_engagement_fraction: 1.0\n        min_relative_slip_ratio: 0.0\n"))
    sim = load(f)
    sim.set("drive.torque_input", torque)
    sim.step(0.5)
    w = sim.read(f"input_shaft.{W}")
    if torque < 1.0:
        assert abs(w) < 1e-5 and sim.read("brake.torque_output") == pytest.approx(torque, rel=1e-6)
    else:
        assert w == pytest.approx((torque - 1.0) / (0.5 + (2.0 + 0.125) / 16) * 0.5, rel=1e-6)
        assert sim.read(f"wheel_drive.mate_3d.{W}") == pytest.approx(w / 4.0, rel=1e-6)
