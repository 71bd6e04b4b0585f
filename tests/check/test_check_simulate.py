"""--simulate in process: the BoxTruck drives, broken assemblies show up in the motion, and the
exported MJCF reproduces the assembly on its own."""

from __future__ import annotations

import math

import numpy as np
import pytest

from check_helpers import BROKEN, EXAMPLE, line_of

mujoco = pytest.importorskip("mujoco")


def test_boxtruck_drives_straight(check_file):
    fc = check_file(EXAMPLE, simulate=True, duration=3.0)
    s = fc.simulation
    assert s.ok and s.blowup is None and s.steps == 1500 and s.simulated_time == pytest.approx(3.0)
    ch = s.bodies["box_truck.chassis"]
    # front-wheel drive at 1 rad/s on 0.26 m wheels: ~0.26 m/s after landing (the wheels start 0.1 m up)
    assert ch.horizontal_distance > 0.5
    assert ch.displacement[0] == pytest.approx(-0.73, abs=0.06)  # towards -X: the front hubs are at -X
    assert abs(ch.displacement[1]) < 0.01
    assert abs(ch.heading_change) < math.radians(1)
    assert ch.final_pos[2] == pytest.approx(1.001, abs=0.005)  # settled on the plate (top at z 0.05)
    for m in s.motors.values():
        assert abs(abs(m.mean_speed) - 1.0) < 0.02  # both motors hold 1 rad/s (right one in -1 about +Y)
    assert not s.fall_through and not s.penetrations and not any(m.pulled_apart for m in s.mates.values())
    # clean: only the approximation notes of the MuJoCo mapping (info)
    assert {d.code for d in fc.diagnostics} == {"A044", "A113"}
    assert all(d.severity.value == "info" for d in fc.diagnostics)


def test_mirrored_motors_turn_instead_of_driving(check_file):
    fc = check_file(BROKEN / "mirrored_motors.openplx", simulate=True, duration=3.0)
    ch = fc.simulation.bodies["box_truck.chassis"]
    assert ch.horizontal_distance < 0.55  # it does not get far (0.42 m in 3 s; 0.78 m driving straight) ...
    assert ch.heading_change < -math.radians(0.1)  # ... it turns clockwise, front wheels slipping


def test_violated_mate_is_pulled_together_in_the_simulation(check_file):
    path = BROKEN / "moved_connector.openplx"
    fc = check_file(path, simulate=True, duration=3.0)
    codes = {(d.code, d.span.start.line + 1) for d in fc.diagnostics}
    hinge_line = line_of(path, "front_left_hinge is Physics3D.Interactions.Hinge")
    assert ("A016", hinge_line) in codes  # static: the frames do not meet
    assert ("A103", hinge_line) in codes  # simulated: the hinge came apart
    rep = fc.simulation.mates["box_truck.front_left_hinge"]
    assert rep.pulled_apart and rep.initial_separation == pytest.approx(0.5912, abs=1e-4)
    # the backend's own "initially violated" note repeats A016 and is dropped
    assert sum(1 for d in fc.diagnostics if d.code == "A016") == 1


def test_exported_mjcf_loads_alone_and_matches_the_assembly(check_file, tmp_path):
    from plxtools.check.mujoco.backend import export_mjcf

    fc = check_file(EXAMPLE)
    from plxtools.check.pipeline import run_backend

    run_backend(fc, simulate=False, duration=1.0)
    xml = tmp_path / "truck.xml"
    export_mjcf(fc.compiled, str(xml))
    model = mujoco.MjModel.from_xml_path(str(xml))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assembled = fc.assembled_bodies()
    # world + the six bodies + the references of the two motors' velocity constraints
    refs = [a for a in fc.compiled.actuators if a.reference is not None]
    assert len(refs) == 2 and model.nbody == 1 + len(assembled) + len(refs)
    for path, b in assembled.items():
        i = model.body(path).id
        assert data.xpos[i] == pytest.approx(b["position"], abs=1e-9), path
        q = np.array(b["quaternion"])
        assert abs(float(np.dot(data.xquat[i], q))) == pytest.approx(1.0, abs=1e-9), path  # same rotation
    # two motors; four hinges + the chassis' free joint + the two references
    assert model.nu == 2 and model.njnt == 5 + len(refs) and model.ntendon == len(refs)
