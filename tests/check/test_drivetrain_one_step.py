"""A velocity input on a drive train's 1D velocity motor turns the hinge that the train's hinge
actuator drives at the input speed over the gear ratios after ONE step, as AGX's velocity
constraint does (issue 29, section 5): for several shaft inertias, wheel masses, gear ratios and
time steps, through the public API (a project ``plx.toml`` sets the time step)."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from plxtools.check.api import load  # noqa: E402

TRAIN = """\
Stand is Physics3D.Bodies.RigidBody:
    is_dynamic: false
    bearing is Physics3D.Interactions.MateConnector:
        main_axis: {{1, 0, 0}}
        normal: {{0, 0, 1}}

Roller is Physics3D.Bodies.RigidBody:
    inertia.mass: {mass}
    geometry is Physics3D.Geometries.Cylinder:
        radius: 0.4
        height: 0.2
    axle is Physics3D.Interactions.MateConnector:
        main_axis: {{1, 0, 0}}
        normal: {{0, 0, 1}}

Mill is Physics3D.System:
    stand is Stand:
        kinematics.local_transform.position.z: 2.0
    roller is Roller
    motor_shaft is DriveTrain.Shaft:
        inertia.inertia: {motor_inertia}
    middle_shaft is DriveTrain.Shaft:
        inertia.inertia: {middle_inertia}
    roller_shaft is DriveTrain.Shaft:
        inertia.inertia: 0.3
    first_stage is DriveTrain.Gear:
        connectors: [motor_shaft.output, middle_shaft.input]
        ratio: {ratio1}
    second_stage is DriveTrain.Gear:
        connectors: [middle_shaft.output, roller_shaft.input]
        ratio: {ratio2}
    drive is Physics1D.Interactions.RotationalVelocityMotor:
        connectors: [motor_shaft.input]
        target_speed: 0.0
    roll is DriveTrain.HingeActuator:
        connector_1d: roller_shaft.output
        mate_3d.connectors: [stand.bearing, roller.axle]
    roller_speed is Physics.Signals.AngularVelocity1DOutput:
        source: roll.mate_3d
    motor_speed is Physics.Signals.AngularVelocity1DOutput:
        source: motor_shaft
    middle_speed is Physics.Signals.AngularVelocity1DOutput:
        source: middle_shaft
    speed_input is Physics.Signals.AngularVelocity1DInput:
        source: drive
"""

CASES = [  # (motor inertia, middle inertia, roller mass, ratio 1, ratio 2, time step)
    (0.5, 2.0, 4.0, 4.0, 1.0, 0.002),
    (0.01, 0.02, 40.0, 10.0, 5.0, 0.002),
    (20.0, 5.0, 0.5, 0.5, 2.0, 0.001),
    (1.0, 1.0, 10.0, 3.0, -2.0, 0.005),
    (0.05, 8.0, 100.0, 1.0, 1.0, 0.01),
]


def _mill(tmp_path, motor_inertia, middle_inertia, mass, ratio1, ratio2, dt):
    (tmp_path / "plx.toml").write_text(f"[check]\ntimestep = {dt}\n")
    path = tmp_path / "mill.openplx"
    path.write_text(TRAIN.format(motor_inertia=motor_inertia, middle_inertia=middle_inertia, mass=mass,
                                 ratio1=ratio1, ratio2=ratio2))
    sim = load(path)
    assert sim.timestep == pytest.approx(dt)
    return sim


@pytest.mark.parametrize("case", CASES, ids=[f"I{c[0]}-{c[1]}_m{c[2]}_r{c[3]}x{c[4]}_dt{c[5]}" for c in CASES])
def test_the_hinge_turns_at_the_input_speed_after_one_step(tmp_path, case):
    motor_inertia, middle_inertia, mass, ratio1, ratio2, dt = case
    sim = _mill(tmp_path, *case)
    target = 6.0
    sim.set("speed_input", target)
    sim.step()
    want = target / (ratio1 * ratio2)
    assert sim.read("roller_speed") == pytest.approx(want, rel=0.01)
    assert sim.read("motor_speed") == pytest.approx(target, rel=0.01)
    assert sim.read("middle_speed") == pytest.approx(target / ratio1, rel=0.01)
    sim.step(0.2)  # and it stays there
    assert sim.read("roller_speed") == pytest.approx(want, rel=1e-4)
    sim.set("speed_input", -target)  # a new input is followed at once as well: within 1 % of the change
    sim.step()
    assert abs(sim.read("roller_speed") + want) <= 0.01 * 2 * abs(want)


def test_a_rigid_train_runs_without_energy_findings(tmp_path):
    """The train's shafts turn with the hinge: no couplings to spring back, no A134."""
    from plxtools.cli import main

    _mill(tmp_path, 0.5, 2.0, 4.0, 4.0, 1.0, 0.002)
    text = (tmp_path / "mill.openplx").read_text().replace("target_speed: 0.0", "target_speed: 6.0")
    (tmp_path / "mill.openplx").write_text(text)
    code = main(["check", str(tmp_path / "mill.openplx"), "--duration", "1", "--output-format", "json"])
    assert code == 0


SPINNING = """\
Spinner is Physics3D.System:
    fast_shaft is DriveTrain.Shaft:
        inertia.inertia: 1.0
        kinematics.velocity: {fast}
    slow_shaft is DriveTrain.Shaft:
        inertia.inertia: 4.0
        kinematics.velocity: {slow}
        kinematics.angle: 0.5
    reduction is DriveTrain.Gear:
        connectors: [fast_shaft.output, slow_shaft.input]
        ratio: 2.0
    fast_speed is Physics.Signals.AngularVelocity1DOutput:
        source: fast_shaft
    slow_speed is Physics.Signals.AngularVelocity1DOutput:
        source: slow_shaft
    slow_angle is Physics.Signals.AngleOutput:
        source: slow_shaft
"""


def _spinner(tmp_path, fast, slow):
    path = tmp_path / "spinner.openplx"
    path.write_text(SPINNING.format(fast=fast, slow=slow))
    sim = load(path)
    notes = [n for n in sim.prepared.compiled.notes if n.code == "A120"]
    return sim, notes


def test_a_train_of_shafts_keeps_speeds_that_agree(tmp_path):
    sim, notes = _spinner(tmp_path, 4.0, 2.0)
    assert notes == []
    sim.step(0.1)
    assert sim.read("fast_speed") == pytest.approx(4.0)
    assert sim.read("slow_speed") == pytest.approx(2.0)
    assert sim.read("slow_angle") == pytest.approx(0.5 + 2.0 * sim.time)


def test_speeds_that_disagree_start_at_the_trains_momentum(tmp_path):
    """I f v summed over I f^2 on the fast shaft's coordinate: (1 x 1 x 6 + 4 x 0.5 x 0) / (1 + 4 x 0.25) = 3."""
    sim, notes = _spinner(tmp_path, 6.0, 0.0)
    assert [n.path for n in notes] == ["fast_shaft", "slow_shaft"]
    sim.step()
    assert sim.read("fast_speed") == pytest.approx(3.0)
    assert sim.read("slow_speed") == pytest.approx(1.5)
