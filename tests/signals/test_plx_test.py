"""`plx test` end to end: the example scenario passes, a wrong motor sign fails it with located
messages, every output format is well formed, and bad scenarios are located errors (exit 2)."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest

from tests.conftest import plx_here
from tests.signals.helpers import boxtruck_copy, scenario

DRIVE = """
duration = 2.0
[[input]]
at = 0.0
signal = "box_truck.front_left_motor.target_angular_velocity_input"
value = 3.0
[[expect]]
at = 2.0
of = "box_truck.chassis.x"
below = -1.0
"""


def test_example_scenario_drives_forward_and_backward_and_passes():
    r = plx_here("test", "examples/boxtruck")
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.splitlines()[0] == "examples/boxtruck/drive.scenario.toml::drive PASSED " \
                                       "(5 expectations, 4.00 s simulated)"
    assert r.stdout.rstrip().endswith("s") and "1 passed in " in r.stdout


def test_a_wrong_motor_sign_fails_with_the_scenario_line_expected_and_measured(tmp_path):
    boxtruck_copy(tmp_path, wrong_sign=True)
    r = plx_here("test", ".", cwd=tmp_path)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "drive.scenario.toml::drive FAILED" in r.stdout
    line = next(ln for ln in r.stdout.splitlines() if ln.startswith("drive.scenario.toml:22:1: error A140"))
    assert "box_truck.chassis.x at t=2.000 s: expected between -1.7 and -1.3, measured " in line
    measured = float(line.rsplit("measured ", 1)[1])
    assert abs(measured) < 1.0  # the truck turns and drifts (0.75 m) instead of driving 1.5 m
    assert "Traceback" not in r.stderr


def test_json_reports_every_expectation_with_measured_values():
    r = plx_here("test", "examples/boxtruck/drive.scenario.toml", "--output-format", "json")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["summary"]["passed"] == 1 and doc["summary"]["failed"] == 0
    (sc,) = doc["scenarios"]
    assert sc["status"] == "passed" and sc["model"] == "Scene" and sc["steps"] == 2000
    exps = {e["line"]: e for e in sc["expectations"]}
    assert -1.7 < exps[22]["measured"] < -1.3 and exps[22]["time"] == pytest.approx(2.0)
    assert exps[27]["unit"] == "deg" and abs(exps[27]["measured"]) < 2
    assert all(e["passed"] and e["evaluated"] for e in sc["expectations"])


def test_junit_github_and_sarif_name_the_failing_line(tmp_path):
    boxtruck_copy(tmp_path, wrong_sign=True)
    junit = plx_here("test", ".", "--output-format", "junit", cwd=tmp_path)
    assert junit.returncode == 1
    root = ET.fromstring(junit.stdout)
    case = root.find("testsuite/testcase")
    assert root.get("failures") == "1" and case.get("name") == "drive"
    assert "drive.scenario.toml:22:1: A140" in case.find("failure").text
    gh = plx_here("test", ".", "--output-format", "github", cwd=tmp_path)
    assert any(ln.startswith("::error file=drive.scenario.toml,line=22,") and "A140" in ln
               for ln in gh.stdout.splitlines()), gh.stdout
    sarif = json.loads(plx_here("test", ".", "--output-format", "sarif", cwd=tmp_path).stdout)
    results = sarif["runs"][0]["results"]
    assert {r["ruleId"] for r in results} == {"A140"}
    assert results[0]["locations"][0]["physicalLocation"]["region"]["startLine"] == 22


BAD = [
    ("unknown signal with did-you-mean",
     DRIVE.replace("target_angular_velocity_input", "target_angular_velocty_input"), 6,
     "has no input 'box_truck.front_left_motor.target_angular_velocty_input'; did you mean "
     "'box_truck.front_left_motor.target_angular_velocity_input'?"),
    ("value of the wrong kind", DRIVE.replace("value = 3.0", 'value = "fast"'), 7,
     "box_truck.front_left_motor.target_angular_velocity_input takes a number, not the text 'fast'"),
    ("vector for a number", DRIVE.replace("value = 3.0", "value = [1, 2, 3]"), 7,
     "takes a number, not a list of 3 items"),
    ("time after the run", DRIVE.replace("at = 2.0", "at = 2.5"), 9,
     "at = 2.5 s is after the end of the run (duration = 2 s)"),
    ("time before the run", DRIVE.replace("at = 0.0", "at = -1"), 5, "at = -1 is before the run starts"),
    ("root model not in the file", 'root = "Truck"\n' + DRIVE, 2,
     "boxtruck.openplx: no model named 'Truck'; this file defines"),
    ("unknown expectation subject", DRIVE.replace('"box_truck.chassis.x"', '"box_truck.chasis.x"'), 10,
     "has no output or body quantity 'box_truck.chasis.x'; did you mean 'box_truck.chassis.x'?"),
    ("unknown key", DRIVE.replace("below =", "belw ="), 11, "unknown key 'belw' in [[expect]]; did you mean 'below'?"),
    ("TOML syntax", DRIVE.replace("value = 3.0", "value = = 3"), 7, "invalid TOML"),
    ("input that is not simulated",
     DRIVE.replace("front_left_motor.target_angular_velocity_input", "front_left_hinge.enable_interaction_input"), 6,
     "box_truck.front_left_hinge.enable_interaction_input is not simulated: "
     "Physics.Signals.EnableInteractionInput of a hinge is not mapped: interactions cannot be switched"),
    ("output that is not simulated", DRIVE.replace('"box_truck.chassis.x"',
                                                   '"box_truck.front_left_hinge.force_output.x"'), 10,
     "box_truck.front_left_hinge.force_output is not simulated: Physics3D.Signals.Force3DOutput of a hinge is not "
     "mapped: constraint forces"),
    ("vector output without a component", DRIVE.replace('"box_truck.chassis.x"', '"box_truck.chassis.position_output"'),
     10, "is three numbers [x, y, z]: name one component (box_truck.chassis.position_output.x"),
    ("degrees on a length", DRIVE.replace("below = -1.0", 'below = -1.0\nunit = "deg"'), 12,
     "unit = \"deg\" but box_truck.chassis.x is not an angle"),
    ("equals without tolerance", DRIVE.replace("below = -1.0", "equals = -1.5"), 11, "equals needs a tolerance"),
]


@pytest.mark.parametrize("body,line,message", [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_bad_scenarios_are_located_errors_with_exit_2(tmp_path, body, line, message):
    boxtruck_copy(tmp_path)
    (tmp_path / "drive.scenario.toml").unlink()
    scenario(tmp_path, body)
    r = plx_here("test", "case.scenario.toml", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    assert "case.scenario.toml::case ERROR" in r.stdout
    errs = [ln for ln in r.stdout.splitlines() if " error A141 " in ln]
    assert errs and errs[0].startswith(f"case.scenario.toml:{line}:"), r.stdout
    assert message in errs[0], errs[0]
    assert "Traceback" not in r.stdout + r.stderr


def test_a_missing_model_file_and_missing_paths(tmp_path):
    (tmp_path / "x.scenario.toml").write_text('model = "nope.openplx"\n', encoding="utf-8")
    r = plx_here("test", ".", cwd=tmp_path)
    assert r.returncode == 2 and "x.scenario.toml:1:1: error A141 model file 'nope.openplx' not found" in r.stdout
    r = plx_here("test", "does-not-exist", cwd=tmp_path)
    assert r.returncode == 2 and "does-not-exist: no such file or folder" in r.stderr
    (tmp_path / "x.scenario.toml").unlink()
    r = plx_here("test", ".", cwd=tmp_path)
    assert r.returncode == 2 and "no scenario files" in r.stderr


def test_a_model_with_errors_fails_the_scenario_with_its_first_error(tmp_path):
    boxtruck_copy(tmp_path)
    model = tmp_path / "boxtruck.openplx"
    model.write_text(model.read_text().replace("inertia.mass: 1000", "inertia.mass: -1000"), encoding="utf-8")
    r = plx_here("test", "drive.scenario.toml", cwd=tmp_path)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "drive.scenario.toml:7:1: error A142 drive: the model cannot be simulated" in r.stdout


def test_pytest_collects_scenario_files(tmp_path):
    import subprocess
    import sys

    boxtruck_copy(tmp_path)
    ok = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "drive.scenario.toml"],
                        cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert ok.returncode == 0 and "1 passed" in ok.stdout, ok.stdout + ok.stderr
    boxtruck_copy(tmp_path, wrong_sign=True)
    bad = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "drive.scenario.toml"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert bad.returncode == 1, bad.stdout
    assert "drive.scenario.toml:22:1: A140 box_truck.chassis.x at t=2.000 s: expected between -1.7 and -1.3" \
        in bad.stdout
