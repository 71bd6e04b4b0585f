"""A velocity motor under load either tracks its target or is warned about (A106) with the error
that was measured: a weight lifted by an effort-limited linear motor (closed form of the sag of a
velocity servo of gain kv under a load F: F / kv)."""

from __future__ import annotations

import re

import numpy as np
import pytest

pytest.importorskip("mujoco")

from physics_cases import G, MODELS, run_model  # noqa: E402


def test_a_sagging_motor_is_warned_with_its_measured_error():
    run = run_model(MODELS / "motor_lift.openplx", 2.0)
    tr = run.trace
    v = float(np.mean(tr["slide.qdot"][tr.t >= 1.6]))
    target, load = 0.5, 50.0 * G
    a111 = next(d for d in run.report["diagnostics"] if d["code"] == "A111")
    kv = float(re.search(r"kv clamped to ([0-9.e+]+)", a111["message"]).group(1))
    assert target - v == pytest.approx(load / kv, rel=0.02)  # the servo's steady-state sag
    a106 = [d for d in run.report["diagnostics"] if d["code"] == "A106"]
    if abs(v - target) <= 0.02 * target + 0.005:
        assert not a106
    else:
        assert len(a106) == 1
        pct = float(re.search(r"\(([0-9.]+) % off\)", a106[0]["message"]).group(1))
        assert pct == pytest.approx(100 * (target - v) / target, rel=0.01)
        assert f"{load:.4g}"[:3] in a106[0]["message"]  # the mean effort: the load
