"""Default-gain velocity motors on light wheels drive at the commanded speed, not faster.

Regression: with the servo clamped at 1000 x I_eff / dt, a cart with 0.15 m wheels at 3 rad/s
gained energy through ground contact and "drove" 158 m in 3 s while `--simulate` reported
nothing wrong. The expected distance is wheel speed x radius x time.
"""

import json
import shutil

import pytest

from tests.conftest import REPO, run_plx


def test_default_gain_cart_drives_at_wheel_speed_times_radius(tmp_path):
    bundle = tmp_path / "user_bundle"
    shutil.copytree(REPO / "examples" / "user_bundle", bundle)
    cart = bundle / "Machines" / "Carts" / "MotorCart.openplx"
    text = cart.read_text()
    assert "motor_gain is Real: 100" in text
    cart.write_text(text.replace("motor_gain is Real: 100", "motor_gain is Real: 100000000"))
    r = run_plx("check", "--simulate", "--duration", "3", "--output-format", "json", "cart_scene.openplx",
                cwd=bundle)
    assert r.returncode == 0, r.stdout + r.stderr
    sim = json.loads(r.stdout)["simulation"]
    bodies = next(iter(sim.values()))["bodies"] if isinstance(sim, dict) else sim[0]["bodies"]
    deck = bodies["cart.deck"]
    dx = deck["final"]["position"][0] - deck["initial"]["position"][0]
    expected = 3.0 * 0.15 * 3.0  # rad/s x m x s
    assert abs(dx) == pytest.approx(expected, rel=0.15)
    assert deck["final"]["position"][2] == pytest.approx(deck["initial"]["position"][2], abs=0.05)
