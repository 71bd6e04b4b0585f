"""Every signal type the bundles define is mapped onto the MuJoCo run or refused by name, and
docs/testing.md lists them all (issue 29, point 5); drive-train signals and the scene's counts
through the Python API and `plx test`."""

from __future__ import annotations

from pathlib import Path

import pytest

from plxtools.check.signals import INPUT_MAP, OUTPUT_MAP, REFUSED, coverage_table
from tests.conftest import REPO, run_plx


def bundle_signal_types() -> dict[str, str]:
    """Every model of the installed bundles that is a Physics.Signals.Input or Output: name -> direction."""
    from plxtools.model import resolve
    from plxtools.model.versions import resolve_bundle_set
    from plxtools.model.workspace import workspace_for_set

    ws = workspace_for_set(resolve_bundle_set([], discover=False, use_config=False, use_env=False))
    p = ws.program
    unit = next(iter(p.units.values()))
    base = {"input": p.lookup(["Physics", "Signals", "Input"], unit),
            "output": p.lookup(["Physics", "Signals", "Output"], unit)}

    def walk(ns):
        yield from ns.symbols.values()
        for c in ns.children.values():
            yield from walk(c)

    out = {}
    for s in walk(p.root):
        if getattr(s, "kind", None) != "model" or s.is_trait:
            continue
        for direction, b in base.items():
            if resolve.is_subtype(p, s, b):
                out[s.qname] = direction
    return out


TYPES = bundle_signal_types()


def test_the_bundles_define_both_directions():
    assert len([t for t, d in TYPES.items() if d == "input"]) >= 20
    assert len([t for t, d in TYPES.items() if d == "output"]) >= 35
    assert "DriveTrain.Signals.TorqueConverterPumpTorqueOutput" in TYPES


@pytest.mark.parametrize("qname", sorted(TYPES))
def test_every_signal_type_is_mapped_or_refused_by_name(qname):
    mapped = {t for t, _s, _q in INPUT_MAP + OUTPUT_MAP}
    assert qname in mapped or qname in REFUSED, f"{qname} is neither mapped nor refused"
    assert not (qname in mapped and qname in REFUSED)


def test_the_docs_table_is_current():
    text = (REPO / "docs" / "testing.md").read_text(encoding="utf-8")
    assert coverage_table(TYPES) in text, "docs/testing.md: paste plxtools.check.signals.coverage_table(...) again"


DRIVE = """\
Drive is Physics3D.System:
    motor_shaft is DriveTrain.Shaft:
        inertia.inertia: 0.5
    wheel_shaft is DriveTrain.Shaft:
        inertia.inertia: 2
    gear is DriveTrain.Gear:
        ratio: 4
        connectors: [motor_shaft.output, wheel_shaft.input]
    motor is Physics1D.Interactions.RotationalVelocityMotor:
        connectors: [motor_shaft.input]
        target_speed: 0
"""


def test_drive_train_signals_through_the_api(tmp_path):
    from plxtools.check.api import NotSimulatedError, load

    f = tmp_path / "drive.openplx"
    f.write_text(DRIVE, encoding="utf-8")
    sim = load(f)
    sim.set("motor.target_angular_velocity_input", 8.0)
    sim.step(1.0)
    assert sim.read("motor_shaft.angular_velocity_output") == pytest.approx(8.0, abs=0.05)
    assert sim.read("wheel_shaft.angular_velocity_output") == pytest.approx(2.0, abs=0.02)  # ratio 4
    assert sim.read("motor.target_angular_velocity_output") == 8.0
    assert abs(sim.read("motor.torque_output")) < 1.0  # steady speed, no load
    with pytest.raises(NotSimulatedError, match="FractionOutput of a gear is not mapped: gear ratios"):
        sim.read("gear.ratio_output")
    counts = sim.scene().counts()
    assert counts["shafts"] == 2 and counts["shaft_couplings.gear"] == 1 and counts["bodies"] == 0, counts


SCENE = """\
Link is Physics3D.Bodies.RigidBody:
    inertia.mass: 1
    top is Physics3D.Interactions.MateConnector:
        position: {0, 0, 0.5}
        main_axis: {1, 0, 0}
    bottom is Physics3D.Interactions.MateConnector:
        position: {0, 0, -0.5}
        main_axis: {1, 0, 0}

Scene is Physics3D.System:
    a is Link
    b is Link
    world_top is Physics3D.Interactions.MateConnector:
        position: {0, 0, 2}
        main_axis: {1, 0, 0}
    h1 is Physics3D.Interactions.Hinge:
        connectors: [a.top, world_top]
    h2 is Physics3D.Interactions.Hinge:
        connectors: [b.top, a.bottom]
"""


def test_scene_bodies_mates_and_counts_in_the_api_and_a_scenario(tmp_path):
    from plxtools.check.api import load

    f = tmp_path / "chain.openplx"
    f.write_text(SCENE, encoding="utf-8")
    sc = load(f).scene()
    assert sc.bodies() == ["a", "b"] and sc.mates() == ["h1", "h2"]
    assert sc.counts()["mates.hinge"] == 2 and sc.counts()["bodies"] == 2
    scen = tmp_path / "chain.scenario.toml"
    scen.write_text('model = "chain.openplx"\nduration = 0.1\n\n[[expect]]\nat = 0\nof = "scene.bodies"\n'
                    'equals = 2\ntolerance = 0\n\n[[expect]]\nat = 0\nof = "scene.mates.hinge"\nequals = 2\n'
                    'tolerance = 0\n\n[[expect]]\nat = 0\nof = "scene.mates.prismatic"\nequals = 0\ntolerance = 0\n',
                    encoding="utf-8")
    r = run_plx("test", str(scen))
    assert r.returncode == 0 and "3 expectations" in r.stdout, r.stdout + r.stderr
    bad = Path(str(scen).replace("chain.", "typo."))
    bad.write_text(scen.read_text().replace("scene.bodies", "scene.bodys"), encoding="utf-8")
    r = run_plx("test", str(bad))
    assert r.returncode == 2 and "did you mean 'scene.bodies'" in r.stdout, r.stdout


def test_a_count_of_a_kind_no_mapping_has_is_an_error_not_zero(tmp_path):
    """`scene.controllers.velocity_motor` (a motor's kind, not its name) or a misspelt mate kind is a
    located error with the kinds there are, never a silent count of 0."""
    (tmp_path / "chain.openplx").write_text(SCENE, encoding="utf-8")
    for of, hint in [("scene.controllers.velocity_motor", "scene.controllers.linear_velocity_motor"),
                     ("scene.mates.hinges", "scene.mates.hinge")]:
        scen = tmp_path / "kind.scenario.toml"
        scen.write_text(f'model = "chain.openplx"\nduration = 0.1\n\n[[expect]]\nat = 0\nof = "{of}"\n'
                        'equals = 0\ntolerance = 0\n', encoding="utf-8")
        r = run_plx("test", str(scen))
        assert r.returncode == 2, r.stdout + r.stderr
        assert "kind.scenario.toml:6:" in r.stdout and "are counted as" in r.stdout, r.stdout
        assert f"did you mean '{hint}'" in r.stdout or "kinds: " in r.stdout, r.stdout
