"""The integrator and time step: chosen by the scene (RK4 for conservative, contact-free scenes),
set by `--integrator` / `--timestep` or the config's `[check]` table, and an energy drift of a
conservative scene beyond the stated tolerance (1 % of its energy scale) reported as A134."""

from __future__ import annotations

import contextlib
import io
import json
import shutil

import pytest

pytest.importorskip("mujoco")

from physics_cases import G, MODELS  # noqa: E402

PENDULUM = MODELS / "double_pendulum.openplx"
BOUNCE = MODELS / "bouncing_ball.openplx"


def _check(path, *extra):
    from plxtools.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["check", str(path), "--simulate", "--output-format", "json", *extra])
    if code == 2:
        return code, None, err.getvalue()
    doc = json.loads(out.getvalue())
    return code, doc, err.getvalue()


def _sim(doc):
    return next(iter(doc["simulation"].values()))


def test_auto_chooses_rk4_only_for_a_conservative_contact_free_scene():
    _, pend, _ = _check(PENDULUM, "--duration", "10")
    _, ball, _ = _check(BOUNCE, "--duration", "0.5")
    assert _sim(pend)["integrator"] == "rk4"
    assert _sim(ball)["integrator"] == "implicitfast"
    # 2 m g L is the energy scale of the swing: RK4 keeps it to far below a millionth
    assert _sim(pend)["energy"]["max_drift"] < 1e-6 * 2 * 1.0 * G * 1.0
    assert "A134" not in {d["code"] for d in pend["diagnostics"]}


def test_a_drifting_conservative_scene_is_reported_with_its_drift():
    code, doc, _ = _check(PENDULUM, "--duration", "10", "--integrator", "implicitfast")
    sim = _sim(doc)
    assert sim["integrator"] == "implicitfast"
    energy = sim["energy"]
    scale = energy["max_kinetic"] + abs(energy["actuator_work"])
    assert energy["max_drift"] > 0.01 * scale  # the first-order integrator does drift here
    a134 = [d for d in doc["diagnostics"] if d["code"] == "A134"]
    assert len(a134) == 1 and "drifted" in a134[0]["message"] and "rk4" in a134[0]["message"]
    assert f"{energy['max_drift']:.4g} J" in a134[0]["message"]


def test_flag_and_config_set_integrator_and_timestep(tmp_path):
    shutil.copy(PENDULUM, tmp_path / "pendulum.openplx")
    path = tmp_path / "pendulum.openplx"
    _, doc, _ = _check(path, "--duration", "0.2", "--integrator", "euler", "--timestep", "0.001")
    assert (_sim(doc)["integrator"], _sim(doc)["timestep"], _sim(doc)["steps"]) == ("euler", 0.001, 200)
    project = tmp_path / "project"  # a folder of its own: configs are read once per folder and process
    project.mkdir()
    shutil.copy(PENDULUM, project / "pendulum.openplx")
    path = project / "pendulum.openplx"
    (project / "plx.toml").write_text('[check]\nintegrator = "implicit"\ntimestep = 0.0005\n', encoding="utf-8")
    _, doc, _ = _check(path, "--duration", "0.2")
    assert (_sim(doc)["integrator"], _sim(doc)["timestep"], _sim(doc)["steps"]) == ("implicit", 0.0005, 400)
    _, doc, _ = _check(path, "--duration", "0.2", "--integrator", "rk4")  # the flag wins
    assert (_sim(doc)["integrator"], _sim(doc)["timestep"]) == ("rk4", 0.0005)


def test_bad_integrator_settings_are_usage_errors(tmp_path):
    shutil.copy(PENDULUM, tmp_path / "pendulum.openplx")
    code, _, err = _check(tmp_path / "pendulum.openplx", "--timestep", "0")
    assert code == 2 and "--timestep" in err and "Traceback" not in err
    (tmp_path / "bad").mkdir()
    shutil.copy(PENDULUM, tmp_path / "bad" / "pendulum.openplx")
    (tmp_path / "bad" / "plx.toml").write_text('[check]\nintegrator = "verlet"\n', encoding="utf-8")
    code, _, err = _check(tmp_path / "bad" / "pendulum.openplx")
    assert code == 2 and "check.integrator" in err and "verlet" in err and "Traceback" not in err


def test_the_python_api_runs_with_the_same_integrator(tmp_path):
    from plxtools.check.api import load

    sim = load(PENDULUM)
    import mujoco

    assert int(sim.model.opt.integrator) == int(mujoco.mjtIntegrator.mjINT_RK4)
    e0 = float(sim.data.energy.sum()) if sim.data.energy.any() else None
    sim.step(2.0)
    mujoco.mj_forward(sim.model, sim.data)
    assert e0 is not None and float(sim.data.energy.sum()) == pytest.approx(e0, abs=1e-5)
