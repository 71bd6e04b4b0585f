"""A velocity motor under load either tracks its target or is warned about (A106) with the error
that was measured.  A weight lifted on a slide by a linear velocity motor: with any effort range
that holds the weight (symmetric, asymmetric, one-sided) the motor is a velocity constraint (as
AGX's: an offset plus a friction bound) and rises at its target speed within 0.1 %, its effort the
weight; a range that cannot hold it lets it fall at (m g - max) / m, and A106 says so."""

from __future__ import annotations

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


@pytest.mark.parametrize("lo, hi", [("-10.0", "1000.0"), ("0.0", "600.0"), ("400.0", "1000.0"),
                                    ("-Math.INF", "600.0"), ("0.0", "Math.INF"), ("480.0", "1000.0")])
def test_any_range_that_holds_the_weight_lifts_it_at_its_target_speed(tmp_path, lo, hi):
    text = (MODELS / "motor_lift.openplx").read_text().replace("min_effort: -1000.0", f"min_effort: {lo}") \
        .replace("max_effort: 1000.0", f"max_effort: {hi}")
    path = tmp_path / "motor_lift.openplx"
    path.write_text(text)
    run = run_model(path, 2.0)
    tr = run.trace
    v = tr["slide.qdot"][tr.t >= 0.5]
    assert np.max(np.abs(v - TARGET)) < 1e-3 * TARGET, (lo, hi, float(np.max(np.abs(v - TARGET))))
    codes = {d["code"] for d in run.report["diagnostics"]}
    assert not codes & {"A106", "A111", "A134"}
    sim = next(iter(run.report["simulation"].values()))
    assert next(iter(sim["motors"].values()))["mean_effort"] == pytest.approx(LOAD, rel=1e-3)


def test_a_range_too_small_for_the_weight_lets_it_fall_and_is_warned(tmp_path):
    text = (MODELS / "motor_lift.openplx").read_text().replace("min_effort: -1000.0", "min_effort: -50.0") \
        .replace("max_effort: 1000.0", "max_effort: 300.0")
    path = tmp_path / "motor_lift.openplx"
    path.write_text(text)
    run = run_model(path, 1.0)
    tr = run.trace
    a = float(np.polyfit(tr.t[tr.t >= 0.2], tr["slide.qdot"][tr.t >= 0.2], 1)[0])
    assert a == pytest.approx(-(LOAD - 300.0) / 50.0, rel=1e-3)  # it pushes its 300 N and no more
    a106 = [d for d in run.report["diagnostics"] if d["code"] == "A106"]
    assert len(a106) == 1 and "300" in a106[0]["message"]
