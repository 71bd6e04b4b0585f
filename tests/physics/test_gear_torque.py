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
