"""External forces and torques on bodies (issue 29, point 5) against closed-form motion, through the
Python API and `plx test`; a body's MassOutput."""

from __future__ import annotations

import json

import pytest

from plxtools.check.api import NotSimulatedError, Vec3InputSignal, load
from tests.conftest import run_plx

LOADS = "tests/signals/models/loads.openplx"
G = 9.80665
MASS = 2.0
PRINCIPAL = (0.5, 0.4, 0.3)  # the block's inertia tensor, diagonal in its frame


def test_a_constant_force_accelerates_a_free_body_at_f_over_m():
    sim = load(LOADS, "Space")
    sim.getInputSignalQueue().send(Vec3InputSignal.create([3.0, -1.0, 0.5], sim.scene().getObject("block.push")))
    sim.step(1.0)
    vx, vy, vz = sim.read("block.linear_velocity_world_output")
    assert (vx, vy, vz) == pytest.approx((3.0 / MASS, -1.0 / MASS, 0.5 / MASS), rel=1e-9)
    # the force stays until it is changed: one more second doubles the speed, and x = F t^2 / (2 m)
    # up to the semi-implicit Euler step's first-order error
    sim.step(1.0)
    assert sim.read("block.linear_velocity_world_output")[0] == pytest.approx(2 * 3.0 / MASS, rel=1e-9)
    assert sim.read("block.position_output")[0] == pytest.approx(3.0 * 4 / (2 * MASS), rel=2e-3)
    assert sim.read("block.angular_velocity_world_output") == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)


def test_two_force_inputs_on_one_body_add_up_and_a_new_value_replaces_the_old():
    sim = load(LOADS, "Space")
    sim.set("block.push", [2.0, 0.0, 0.0])
    sim.set("block.second_push", [0.0, 4.0, 0.0])
    sim.step(0.5)
    sim.set("block.push", [0.0, 0.0, 0.0])  # the first push ends; the second goes on
    sim.step(0.5)
    vx, vy, _ = sim.read("block.linear_velocity_world_output")
    assert vx == pytest.approx(2.0 * 0.5 / MASS, rel=1e-9)
    assert vy == pytest.approx(4.0 * 1.0 / MASS, rel=1e-9)


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_a_torque_about_a_principal_axis_spins_a_body_at_tau_over_i(axis):
    sim = load(LOADS, "Space")
    torque = [0.0, 0.0, 0.0]
    torque[axis] = 0.6
    sim.set("block.torque_input", torque)
    sim.step(0.5)
    w = sim.read("block.angular_velocity_world_output")
    assert w[axis] == pytest.approx(0.6 / PRINCIPAL[axis] * 0.5, rel=1e-6)
    assert [abs(c) for i, c in enumerate(w) if i != axis] == pytest.approx([0.0, 0.0], abs=1e-9)
    assert sim.read("block.linear_velocity_world_output") == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)
    # the angle turned about that axis is alpha t^2 / 2 (a principal axis: no precession)
    angle = sim.read("block.rpy_output")[axis]
    assert angle == pytest.approx(0.5 * 0.6 / PRINCIPAL[axis] * 0.25, rel=1e-2)


def test_the_torque_is_in_world_axes_whatever_the_body_turned():
    """Torque3DInput names no frame; like the bundles' 3D velocity inputs it is world-frame: a body
    first turned a quarter about z, then pushed by a torque about world x, spins about world x
    (its own y axis, moment 0.4), not about its own x."""
    sim = load(LOADS, "Space")
    sim.set("block.angular_velocity_world_input", [0.0, 0.0, 3.14159265358979 / 2])
    sim.step(1.0)
    sim.set("block.angular_velocity_world_input", [0.0, 0.0, 0.0])
    sim.step()
    sim.set("block.torque_input", [0.4, 0.0, 0.0])
    sim.step(0.25)
    wx, wy, wz = sim.read("block.angular_velocity_world_output")
    assert wx == pytest.approx(0.4 / PRINCIPAL[1] * 0.25, rel=1e-3)
    assert abs(wy) < 1e-6 and abs(wz) < 1e-6


def test_a_force_cancelling_gravity_keeps_a_body_still_in_a_scenario(tmp_path):
    """Through `plx test`: the block hovers for 2 s under a push of m g, and the energy monitor does
    not take the push's work for energy that nothing supplied (no A134)."""
    scen = tmp_path / "hover.scenario.toml"
    scen.write_text(
        f'model = "{(__import__("pathlib").Path(LOADS).resolve())}"\nroot = "Hover"\nduration = 2.0\n\n'
        f'[[input]]\nat = 0\nsignal = "block.push"\nvalue = [0, 0, {MASS * G}]\n\n'
        '[[expect]]\nduring = [0, 2]\nof = "block.z"\nequals = 3\ntolerance = 1e-9\n\n'
        '[[expect]]\nat = 2\nof = "block.speed"\nbelow = 1e-9\n\n'
        '[[expect]]\nat = 0\nof = "block.mass_output"\nequals = 2\ntolerance = 0\n', encoding="utf-8")
    r = run_plx("test", str(scen), "--output-format", "json")
    doc = json.loads(r.stdout)
    assert r.returncode == 0, r.stdout + r.stderr
    codes = {d["code"] for s in doc["scenarios"] for d in s.get("diagnostics", [])}
    assert "A134" not in codes and "A140" not in codes, doc
    # and without the push it falls: the expectation fails at its first step
    scen.write_text(scen.read_text().replace(f"value = [0, 0, {MASS * G}]", "value = [0, 0, 0]"), encoding="utf-8")
    r = run_plx("test", str(scen))
    assert r.returncode == 1 and "block.z" in r.stdout, r.stdout


def test_the_api_and_a_scenario_agree_on_a_pushed_body(tmp_path):
    sim = load(LOADS, "Space")
    sim.set("block.push", [1.0, 0.0, 0.0])
    sim.set("block.torque_input", [0.0, 0.0, 0.3])
    sim.step(1.0)
    x, yaw = sim.read("block.position_output")[0], sim.read("block.rpy_output")[2]
    scen = tmp_path / "push.scenario.toml"
    scen.write_text(
        f'model = "{(__import__("pathlib").Path(LOADS).resolve())}"\nroot = "Space"\nduration = 1.0\n\n'
        '[[input]]\nsignal = "block.push"\nvalue = [1, 0, 0]\n\n'
        '[[input]]\nsignal = "block.torque_input"\nvalue = [0, 0, 0.3]\n\n'
        f'[[expect]]\nat = 1\nof = "block.x"\nequals = {x!r}\ntolerance = 1e-9\n\n'
        f'[[expect]]\nat = 1\nof = "block.yaw"\nequals = {yaw!r}\ntolerance = 1e-9\n', encoding="utf-8")
    r = run_plx("test", str(scen))
    assert r.returncode == 0, r.stdout + r.stderr
    assert x == pytest.approx(1.0 / (2 * MASS), rel=2e-3) and yaw == pytest.approx(0.5 * 0.3 / PRINCIPAL[2], rel=2e-3)


def test_a_load_on_a_body_whose_motion_is_prescribed_is_refused_with_the_reason():
    sim = load(LOADS, "Hover")
    with pytest.raises(NotSimulatedError, match="platform is not dynamic.*prescribed"):
        sim.set("platform.push", [1.0, 0.0, 0.0])
    assert sim.read("platform.mass_output") == pytest.approx(MASS)


def test_a_body_without_the_trait_cannot_take_a_torque_input(tmp_path):
    """The bundles let a Torque3DInput act only on what says it takes one: the type checker holds a
    plain RigidBody source to that (T001), so no input is silently dropped."""
    f = tmp_path / "bare.openplx"
    f.write_text("Scene is Physics3D.System:\n    body is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n"
                 "    spin is Physics3D.Signals.Torque3DInput:\n        source: body\n", encoding="utf-8")
    r = run_plx("lint", str(f))
    assert r.returncode == 1 and "T001" in r.stdout and "Torque3DInputTrait" in r.stdout, r.stdout


def test_check_counts_the_loads_as_simulated():
    """`plx check` names no A040 for the force, torque and mass signals of the model."""
    r = run_plx("check", LOADS)
    assert r.returncode == 0 and " A040 " not in r.stdout, r.stdout


def test_a_torque_input_on_a_connector_is_named_as_not_simulated(tmp_path):
    f = tmp_path / "twist.openplx"
    f.write_text("TwistPoint is Physics3D.Interactions.MateConnector:\n    with Physics3D.Signals.Torque3DInputTrait\n\n"
                 "Scene is Physics3D.System:\n    body is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n"
                 "        point is TwistPoint\n    twist is Physics3D.Signals.Torque3DInput:\n"
                 "        source: body.point\n", encoding="utf-8")
    r = run_plx("check", str(f))
    a040 = [ln for ln in r.stdout.splitlines() if " A040 " in ln]
    assert len(a040) == 1 and "twist" in a040[0] and "Torque3DInput of a connector has no MuJoCo mapping" in a040[0], \
        r.stdout
