"""An ideal gear multiplies torque by its ratio (input speed / output speed): a torque on the input
shaft is held on the output shaft by input torque x ratio, for reductions and overdrives, and a
free output shaft accelerates as the train's reflected inertia says."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from physics_cases import MODELS  # noqa: E402

from plxtools.check.api import load  # noqa: E402


@pytest.mark.parametrize("ratio", [4.0, 0.5, 12.5])
@pytest.mark.parametrize("torque", [3.0, -1.5])
def test_the_holding_torque_is_the_input_torque_times_the_ratio(tmp_path, ratio, torque):
    f = tmp_path / "gear_torque.openplx"
    f.write_text((MODELS / "gear_torque.openplx").read_text().replace("ratio: 4.0", f"ratio: {ratio}"))
    sim = load(f)
    sim.set("drive.torque_input", torque)
    sim.step(0.2)
    assert sim.read("output_shaft.angular_velocity_output") == pytest.approx(0.0, abs=1e-6)
    # 1e-9 in the first steps, then a ringing of the rigid velocity constraint of up to 3e-4
    assert sim.read("hold.torque_output") == pytest.approx(-torque * ratio, rel=1e-3)


def test_a_free_output_accelerates_with_the_reflected_inertia(tmp_path):
    f = tmp_path / "gear_free.openplx"
    f.write_text((MODELS / "gear_torque.openplx").read_text().replace(
        "    hold is Physics1D.Interactions.RotationalVelocityMotor:\n        connectors: [output_shaft.output]\n"
        "        target_speed: 0.0\n", ""))
    sim = load(f)
    sim.set("drive.torque_input", 3.0)
    sim.step(1.0)
    # output acceleration = input torque x ratio / (I_out + I_in ratio^2)
    assert sim.read("output_shaft.angular_velocity_output") == pytest.approx(3.0 * 4.0 / (2.0 + 0.5 * 16.0), rel=1e-6)


def _with_torque_output(text: str) -> str:
    return text.replace("        ratio: 4.0\n", "        ratio: 4.0\n        torque_output.enabled: true\n")


@pytest.mark.parametrize("ratio, torque", [(4.0, 3.0), (0.5, -1.5)])
def test_the_gear_reads_the_torque_it_passes_to_its_held_output(tmp_path, ratio, torque):
    """Its torque_output is input torque x ratio, the torque that holds the output back."""
    f = tmp_path / "gear_torque.openplx"
    f.write_text(_with_torque_output((MODELS / "gear_torque.openplx").read_text()).replace("ratio: 4.0",
                                                                                          f"ratio: {ratio}"))
    sim = load(f)
    sim.set("drive.torque_input", torque)
    sim.step(0.2)
    assert sim.read("reduction.torque_output") == pytest.approx(torque * ratio, rel=1e-3)
    assert sim.read("reduction.torque_output") == pytest.approx(-sim.read("hold.torque_output"), rel=1e-9)


def test_the_gear_torque_into_a_free_output_is_what_accelerates_it(tmp_path):
    """I_out a_out, with a_out = T ratio / (I_out + I_in ratio^2)."""
    text = _with_torque_output((MODELS / "gear_torque.openplx").read_text()).replace(
        "    hold is Physics1D.Interactions.RotationalVelocityMotor:\n        connectors: [output_shaft.output]\n"
        "        target_speed: 0.0\n", "")
    f = tmp_path / "gear_free.openplx"
    f.write_text(text)
    sim = load(f)
    sim.set("drive.torque_input", 3.0)
    sim.step(0.5)
    a_out = 3.0 * 4.0 / (2.0 + 0.5 * 16.0)
    assert sim.read("reduction.torque_output") == pytest.approx(2.0 * a_out, rel=1e-6)


def test_a_gear_whose_output_turns_a_wheel_reads_its_torque_from_the_input_side(tmp_path):
    """The output side reaches a 3D hinge (the world acts through it), so the torque is read from
    the input shaft: ratio x (T - I_in a_in); and it is what the output shaft and the wheel take,
    (I_out + I_wheel) a_out, with the wheel's inertia about its axis 1/2 m r^2."""
    text = (MODELS / "gear_train.openplx").read_text().replace(
        "    drive is Physics1D.Interactions.RotationalVelocityMotor:\n        connectors: [input_shaft.input]\n"
        "        target_speed: 8.0\n", "    drive is DriveTrain.TorqueMotor:\n        connectors: [input_shaft.input]\n")
    f = tmp_path / "gear_wheel.openplx"
    f.write_text(_with_torque_output(text))
    sim = load(f)
    sim.set("drive.torque_input", 2.0)
    sim.step(0.5)
    a_in = sim.read("input_shaft.angular_velocity_output") / sim.time
    tau = sim.read("reduction.torque_output")
    assert tau == pytest.approx(4.0 * (2.0 - 0.5 * a_in), rel=1e-6)
    i_wheel = 0.5 * 4.0 * 0.25 ** 2
    assert tau == pytest.approx((2.0 + i_wheel) * a_in / 4.0, rel=1e-3)
