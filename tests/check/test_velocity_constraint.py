"""A stiff velocity motor runs as a velocity constraint solved together with contacts (issue 29,
section 5; plxtools/check/mujoco/velocity_constraint.py): a cart on the ground, driven through a
gear by a 1D velocity motor, has its wheel at the input speed after ONE step and after a
reversal, stays on the ground, and its motor's effort is the constraint's force, bounded by a
symmetric effort range.  An asymmetric range keeps the servo, and says so."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("mujoco")

from plxtools.check.api import SignalValueError, load  # noqa: E402
from plxtools.cli import main  # noqa: E402

CART = (Path(__file__).parent / "models" / "driven_cart.openplx").read_text()
RATIO, RADIUS = 4.0, 0.3


def _cart(tmp_path, text=CART, dt=None):
    if dt is not None:
        (tmp_path / "plx.toml").write_text(f"[check]\ntimestep = {dt}\n")
    path = tmp_path / "cart.openplx"
    path.write_text(text)
    return load(path)


@pytest.mark.parametrize("dt", [0.001, 0.002, 0.01])
def test_the_wheel_is_at_the_input_speed_after_one_step_on_the_ground(tmp_path, dt):
    sim = _cart(tmp_path, dt=dt)
    sim.set("speed_input", 16.0)
    sim.step()
    assert sim.read("wheel_speed") == pytest.approx(16.0 / RATIO, rel=0.01)
    sim.step(1.0)
    assert sim.read("wheel_speed") == pytest.approx(16.0 / RATIO, rel=1e-4)
    x, y, z = sim.read("chassis_position")
    assert z == pytest.approx(0.35, abs=0.01)  # on its wheels: a stiff servo made it jump
    vx = sim.read("chassis_velocity")[0]
    assert vx == pytest.approx(16.0 / RATIO * RADIUS, rel=0.02)  # rolling, not slipping
    sim.set("speed_input", -16.0)
    sim.step()
    assert sim.read("wheel_speed") == pytest.approx(-16.0 / RATIO, rel=0.01)


def test_a_symmetric_effort_range_bounds_the_constraint_force(tmp_path):
    text = CART.replace("        target_speed: 16.0\n", "        target_speed: 0.0\n        min_effort: -2.0\n"
                        "        max_effort: 2.0\n")
    sim = _cart(tmp_path, text)
    sim.set("speed_input", 16.0)
    sim.step(0.2)
    assert sim.read("motor_torque") == pytest.approx(2.0, rel=1e-6)  # pushing at its limit
    assert 0.0 < sim.read("wheel_speed") < 0.5 * 16.0 / RATIO  # 2 N m cannot spin up a 300 kg cart in 0.2 s
    assert sim.read("motor_range") == (-2.0, 2.0)
    sim.set("range_input", (-1e3, 1e3))
    sim.step(0.5)
    assert sim.read("wheel_speed") == pytest.approx(16.0 / RATIO, rel=1e-3)
    # a one-sided or asymmetric range is an offset plus a friction bound: [2, 3] N m (which raised
    # SignalValueError in round 3) makes the motor push between 2 and 3 N m
    sim.set("speed_input", 0.0)
    sim.set("range_input", (2.0, 3.0))
    sim.step(0.2)
    assert sim.read("motor_range") == pytest.approx((2.0, 3.0))
    assert 2.0 - 1e-6 <= sim.read("motor_torque") <= 3.0 + 1e-6
    assert sim.read("motor_torque") == pytest.approx(2.0, rel=1e-3)  # braking to 0 it pushes as little as it may
    with pytest.raises(SignalValueError, match="min > max"):
        sim.set("range_input", (5.0, -1.0))


def test_an_asymmetric_effort_range_is_a_constraint_too(tmp_path):
    text = CART.replace("        target_speed: 16.0\n", "        target_speed: 16.0\n        min_effort: -1.0\n"
                        "        max_effort: 5000.0\n")
    sim = _cart(tmp_path, text)
    assert not [n for n in sim.prepared.compiled.notes if n.code == "A111"]
    sim.step()
    assert sim.read("wheel_speed") == pytest.approx(16.0 / RATIO, rel=0.01)  # one step, as a symmetric one
    assert sim.read("motor_range") == pytest.approx((-1.0, 5000.0))
    sim.step(0.5)
    # within 0.1 %: the constraint's softness leaves an error in proportion to its friction force,
    # here the load minus the range's middle, 2500 N m (1.2e-4 measured; 0 for a symmetric range)
    assert sim.read("wheel_speed") == pytest.approx(16.0 / RATIO, rel=1e-3)
    assert -1.0 - 1e-6 <= sim.read("motor_torque") <= 5000.0


def test_check_finds_nothing_wrong_with_the_driven_cart(tmp_path, capsys):
    path = tmp_path / "cart.openplx"
    path.write_text(CART)
    code = main(["check", str(path), "--simulate", "--duration", "2", "--output-format", "json"])
    out = json.loads(capsys.readouterr().out)
    codes = sorted({d["code"] for f in out["files"] for d in f["diagnostics"]}) if "files" in out else out
    assert code == 0, codes
    text = json.dumps(out)
    assert "A134" not in text and "A106" not in text and "A135" not in text


def test_plx_test_refuses_an_inverted_range_at_its_line(tmp_path, capsys):
    (tmp_path / "cart.openplx").write_text(CART)
    (tmp_path / "cart.plxtest.toml").write_text(
        'model = "cart.openplx"\nduration = 0.1\n\n[[input]]\nat = 0.0\nsignal = "range_input"\n'
        'value = [5.0, -1.0]\n\n[[expect]]\nat = 0.1\nof = "wheel_speed"\nabove = 0.0\n')
    code = main(["test", str(tmp_path / "cart.plxtest.toml")])
    out = capsys.readouterr().out
    assert code == 2, out
    # (before this round an inverted range in a scenario was an internal error)
    assert "cart.plxtest.toml:7:1: error A141" in out and "min > max" in out and "internal error" not in out


def test_plx_test_takes_an_asymmetric_range(tmp_path, capsys):
    (tmp_path / "cart.openplx").write_text(CART)
    (tmp_path / "cart.plxtest.toml").write_text(
        'model = "cart.openplx"\nduration = 0.5\n\n[[input]]\nat = 0.0\nsignal = "range_input"\n'
        'value = [2.0, 3.0]\n\n[[expect]]\nat = 0.5\nof = "motor_torque"\nbetween = [2.0, 3.0]\n')
    code = main(["test", str(tmp_path / "cart.plxtest.toml")])
    out = capsys.readouterr().out
    assert code == 0, out


def test_a_train_driving_two_wheels_is_at_the_input_speed_after_one_step(tmp_path):
    """Two hinges on one train: a joint per shaft coupled by velocity-level equalities, solved with
    the motor's constraint and the contacts."""
    text = (Path(__file__).parent / "models" / "driven_axle.openplx").read_text()
    sim = _cart(tmp_path, text)
    sim.set("speed_input", 16.0)
    sim.step()
    assert sim.read("wheel_speed") == pytest.approx(16.0 / RATIO, rel=0.01)
    assert sim.read("right_speed") == pytest.approx(sim.read("wheel_speed"), rel=1e-3)
    sim.step(1.0)
    assert sim.read("chassis_position")[2] == pytest.approx(0.35, abs=0.01)
    assert sim.read("chassis_velocity")[0] == pytest.approx(16.0 / RATIO * RADIUS, rel=0.02)
    sim.set("speed_input", -16.0)
    sim.step()
    assert sim.read("wheel_speed") == pytest.approx(-16.0 / RATIO, rel=0.02)
    assert sim.read("right_speed") == pytest.approx(sim.read("wheel_speed"), rel=1e-3)


@pytest.mark.parametrize("gain", [0.5, 5.0, 40.0])
def test_a_finite_gain_follows_the_servo_law_step_by_step(tmp_path, gain):
    """The constraint's softness is set so that its force is gain (target - v_next), an implicit
    servo's law, solved with everything else (velocity_constraint.impedance)."""
    text = (Path(__file__).parent / "models" / "soft_motor.openplx").read_text().replace("gain: 0.5", f"gain: {gain}")
    sim = _cart(tmp_path, text)
    inertia, h, target = 0.4 * 2 * 0.2 ** 2, sim.timestep, 3.0
    sim.set("speed_in", target)
    v = 0.0
    for _ in range(25):
        sim.step()
        v = (inertia * v + h * gain * target) / (inertia + h * gain)
        assert sim.read("speed") == pytest.approx(v, rel=1e-6, abs=2e-5)


def test_the_soft_motors_of_the_user_bundle_cart_roll_it_without_hopping(capsys):
    """examples/user_bundle drives light wheels with gain 100: as a servo solved after the contacts
    it made the cart hop at the start (a false A134 of 4.8 J, the deck at 0.70 m/s); as a constraint
    it rolls at 3 rad/s x 0.15 m."""
    example = Path(__file__).parents[2] / "examples" / "user_bundle" / "cart_scene.openplx"
    code = main(["check", str(example), "--simulate", "--duration", "3", "--output-format", "json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert "A134" not in json.dumps(out["diagnostics"])
    sim = next(iter(out["simulation"].values()))
    assert sim["bodies"]["cart.deck"]["max_speed"] == pytest.approx(0.45, rel=0.02)
