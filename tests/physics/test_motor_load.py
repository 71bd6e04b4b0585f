"""A velocity motor under load either tracks its target or is warned about (A106) with the error
that was measured.  A weight lifted on a slide by a linear velocity motor: with a symmetric effort
range the motor is a velocity constraint (as AGX's) and rises at exactly its target speed, its
effort the weight; with an asymmetric range it is a servo of clamped gain kv, which sags by
F / kv under a load F (the closed form), and A106 says by how much when that is over 2 %."""

from __future__ import annotations

import re

import numpy as np
import pytest

pytest.importorskip("mujoco")

from physics_cases import G, MODELS, run_model  # noqa: E402

TARGET, LOAD = 0.5, 50.0 * G


def test_a_velocity_constraint_lifts_the_weight_at_its_target_speed():
    run = run_model(MODELS / "motor_lift.openplx", 2.0)
    tr = run.trace
    v = tr["slide.qdot"][tr.t >= 0.1]
    assert np.max(np.abs(v - TARGET)) < 1e-3 * TARGET
    codes = {d["code"] for d in run.report["diagnostics"]}
    assert not codes & {"A106", "A111", "A134"}
    sim = next(iter(run.report["simulation"].values()))
    assert next(iter(sim["motors"].values()))["mean_effort"] == pytest.approx(LOAD, rel=1e-3)


def test_a_sagging_servo_is_warned_with_its_measured_error(tmp_path):
    text = (MODELS / "motor_lift.openplx").read_text().replace("min_effort: -1000.0", "min_effort: -10.0")
    path = tmp_path / "motor_lift.openplx"
    path.write_text(text)
    run = run_model(path, 2.0)
    tr = run.trace
    v = float(np.mean(tr["slide.qdot"][tr.t >= 1.6]))
    a111 = next(d for d in run.report["diagnostics"] if d["code"] == "A111")
    assert "not symmetric" in a111["message"]
    kv = float(re.search(r"kv clamped to ([0-9.e+]+)", a111["message"]).group(1))
    assert TARGET - v == pytest.approx(LOAD / kv, rel=0.02)  # the servo's steady-state sag
    a106 = [d for d in run.report["diagnostics"] if d["code"] == "A106"]
    if abs(v - TARGET) <= 0.02 * TARGET + 0.005:
        assert not a106
    else:
        assert len(a106) == 1
        pct = float(re.search(r"\(([0-9.]+) % off\)", a106[0]["message"]).group(1))
        assert pct == pytest.approx(100 * (TARGET - v) / TARGET, rel=0.01)
        assert f"{LOAD:.4g}"[:3] in a106[0]["message"]  # the mean effort: the load
