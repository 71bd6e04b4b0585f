"""Issue 45: one ranking of suggestions (plxtools/model/suggest.py), meaning first, spelling second,
in every place plx suggests a name. One test per family, through the public surface: lint's
did-you-mean (attributes, bundles and types), `plx test` scenario keys (inputs, outputs, body
quantities) and the runtime API that controller scripts use (signals)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from plxtools.model.suggest import best, ranked
from tests.conftest import plx_here

REPO = Path(__file__).resolve().parents[2]
TRUCK = REPO / "examples" / "tutorial" / "step11-controls" / "boxtruck.openplx"


def test_meaning_before_spelling():
    motor = ["torque_range_input", "target_angular_velocity_input", "angle_output", "torque_output"]
    assert best("target_speed_input", motor) == "target_angular_velocity_input"
    body = ["rpy_output", "linear_velocity_world_output", "angular_velocity_output", "position_output"]
    assert best("velocity_output", body) == "linear_velocity_world_output"
    # an input ranks after every output, however alike its spelling
    assert ranked("torque_output", ["torque_input", "force_output"], cutoff=0.0) == ["force_output", "torque_input"]
    assert best("Physics3d", ["Physics1D", "Physics3D", "Physics"]) == "Physics3D"
    assert best("zzz", ["alpha", "beta"]) is None


@pytest.fixture
def truck(tmp_path):
    shutil.copy(TRUCK, tmp_path / "boxtruck.openplx")
    (tmp_path / "plx.toml").write_text('ignore = ["C001"]\n')
    return tmp_path


def _lint(folder: Path, old: str, new: str) -> str:
    f = folder / "boxtruck.openplx"
    f.write_text(f.read_text().replace(old, new, 1))
    return plx_here("lint", str(f), cwd=folder).stdout


def test_bundles_case_only_typo_gets_the_right_case_and_no_follow_ons(truck):
    out = _lint(truck, "Wheel is Physics3D.Bodies.RigidBody", "Wheel is Physics3d.Bodies.RigidBody")
    assert "did you mean 'Physics3D.Bodies.RigidBody'?" in out
    assert out.count(" error ") == 1, out  # no T001 on the four wheels that are built on it


def test_attributes(truck):
    out = _lint(truck, "inertia.mass: 10", "inertia.mas: 10")
    assert "error N002 'mas'" in out and "did you mean 'mass'?" in out


def test_types_in_a_namespace(truck):
    out = _lint(truck, "Physics3D.Geometries.Cylinder", "Physics3D.Geometries.cylinder")
    assert "did you mean 'Physics3D.Geometries.Cylinder'?" in out


def _scenario(folder: Path, signal: str, of: str) -> str:
    (folder / "s.scenario.toml").write_text(
        'model = "boxtruck.openplx"\nroot = "Scene"\nduration = 0.1\n\n'
        f'[[input]]\nat = 0.0\nsignal = "{signal}"\nvalue = 1.0\n\n'
        f'[[expect]]\nat = 0.05\nof = "{of}"\nbelow = 100\n')
    return plx_here("test", str(folder / "s.scenario.toml"), cwd=folder).stdout


def test_inputs_and_outputs_in_scenarios(truck):
    out = _scenario(truck, "boxTruck.front_left_drive_motor.target_speed_input",
                    "boxTruck.front_left_hinge_joint.angle_outptu")
    assert "did you mean 'boxTruck.front_left_drive_motor.target_angular_velocity_input'?" in out
    assert "did you mean 'boxTruck.front_left_hinge_joint.angle_output'?" in out


def test_body_quantities_in_scenarios(truck):
    out = _scenario(truck, "boxTruck.front_left_drive_motor.target_angular_velocity_input",
                    "boxTruck.chassis.velocity_output")
    assert "did you mean 'vx' or 'vy' or 'vz' or 'speed' (the body's linear_velocity_world_output)?" in out


def test_signals_in_the_runtime_api(truck):
    pytest.importorskip("mujoco")
    from plxtools.check.api import load

    sim = load(truck / "boxtruck.openplx")
    with pytest.raises(Exception) as err:
        sim.scene().getObject("boxTruck.front_left_drive_motor.target_speed_input")
    assert "did you mean 'boxTruck.front_left_drive_motor.target_angular_velocity_input'?" in str(err.value)
    with pytest.raises(Exception) as err:
        sim.scene().getObject("boxTruck.chassis.velocity_output")
    assert "did you mean 'boxTruck.chassis.linear_velocity_world_output'?" in str(err.value)
