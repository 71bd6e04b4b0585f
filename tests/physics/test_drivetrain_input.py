"""A drive train's velocity motor turns the hinge that its hinge actuator drives at the motor's
speed divided by the gear ratio after one step (as the real runtime does), and the run gains no
energy (no A134).  More inertias, ratios and time steps: tests/check/test_drivetrain_one_step.py."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from physics_cases import MODELS, run_model  # noqa: E402

GEARS = MODELS / "gear_train.openplx"
RATIO = 4.0


def _hinge_speed(sim, mate: str) -> float:
    c, m, d = sim.prepared.compiled, sim.model, sim.data
    j = m.joint(c.joints[mate][0])
    return c.joint_sign[mate] * float(d.qvel[m.jnt_dofadr[j.id]])


def test_the_motor_speed_reaches_the_driven_hinge_after_one_step():
    """From rest, the 1D motor's target (8 rad/s) is a step input: the hinge behind the 4:1 gear
    must turn at 2 rad/s after one step (the motor's own signal input is mapped by signals.py;
    this is the same step through the stepping path every run takes)."""
    from plxtools.check.api import load

    sim = load(GEARS)
    want = 8.0 / RATIO
    speeds = []
    for _ in range(25):
        sim.step()
        speeds.append(_hinge_speed(sim, "wheel_drive.mate_3d"))
    assert all(abs(v - want) <= 0.01 * want for v in speeds)  # from the first step on: within 1 %
    assert speeds[-1] == pytest.approx(want, rel=1e-6)  # 50 ms: at the target


def test_the_gear_train_gains_no_energy():
    run = run_model(GEARS, 2.0)
    assert "A134" not in run.codes, run.report["diagnostics"]
