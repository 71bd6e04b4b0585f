"""The physics monitors of `plx check --simulate` through the command line: energy that no motor
supplied (A134), speeds nothing in the scene explains (A135), the wall-clock limit (A109), the
per-body energy report, and `--trace` / `--timeout` usage."""

from __future__ import annotations

import csv
import json
import math

import pytest

from check_helpers import CASES, EXAMPLE

from tests.conftest import run_plx

pytest.importorskip("mujoco")

OVERLAP = CASES / "physics" / "overlap.openplx"
MODELS = CASES.parents[1] / "physics" / "models"


def _json(*args: str) -> tuple[int, dict]:
    r = run_plx("check", "--output-format", "json", *args)
    assert r.returncode in (0, 1), r.stderr
    return r.returncode, json.loads(r.stdout)


def test_energy_from_nowhere_is_reported_with_its_size_time_and_body():
    code, doc = _json("--simulate", "--duration", "0.3", str(OVERLAP))
    gain = [d for d in doc["diagnostics"] if d["code"] == "A134"]
    assert len(gain) == 1 and gain[0]["severity"] == "warning"
    assert "crate" in gain[0]["message"] and " J " in gain[0]["message"]
    sim = next(iter(doc["simulation"].values()))
    assert sim["findings"]["energy_gain"]["joules"] > 30  # pushed out of a 15 cm overlap
    assert sim["energy"]["max_unexplained_gain"] == pytest.approx(sim["findings"]["energy_gain"]["joules"])


def test_a_speed_nothing_explains_is_reported():
    code, doc = _json("--simulate", "--duration", "0.05", str(OVERLAP))
    fast = [d for d in doc["diagnostics"] if d["code"] == "A135"]
    assert len(fast) == 1 and "crate reached" in fast[0]["message"]
    sim = next(iter(doc["simulation"].values()))
    assert sim["findings"]["implausible_speeds"][0]["body"] == "crate"


def test_a_clean_motor_driven_scene_has_no_energy_or_speed_finding():
    code, doc = _json("--simulate", str(EXAMPLE))
    assert code == 0 and not {"A134", "A135"} & {d["code"] for d in doc["diagnostics"]}
    sim = next(iter(doc["simulation"].values()))
    assert sim["energy"]["actuator_work"] > 0 and sim["energy"]["checked"] is True
    chassis = sim["bodies"]["box_truck.chassis"]
    assert chassis["max_kinetic_energy"] > 100 and chassis["max_speed"] > 0.5  # 1000 kg at ~1.4 m/s
    assert chassis["potential_energy"] == pytest.approx(1000 * 9.80665 * 1.0, rel=0.01)  # resting ~1 m up


def test_timeout_stops_the_run_and_fails_the_file():
    r = run_plx("check", "--simulate", "--duration", "600", "--timeout", "0.05", str(EXAMPLE))
    assert r.returncode == 1
    assert "error A109" in r.stdout and "time limit (0.05 s of wall time)" in r.stdout
    assert "All checks passed" not in r.stdout


@pytest.mark.parametrize("value", ["0", "-1", "nan", "inf"])
def test_bad_timeout_is_a_usage_error(value):
    r = run_plx("check", "--simulate", "--timeout", value, str(EXAMPLE))
    assert r.returncode == 2 and "--timeout must be a positive number of seconds" in r.stderr


def test_trace_implies_simulate_and_writes_the_motion(tmp_path):
    out = tmp_path / "motion.csv"
    r = run_plx("check", "--duration", "0.5", "--trace", str(out), str(MODELS / "simple_pendulum.openplx"))
    assert r.returncode == 0, r.stdout + r.stderr
    rows = list(csv.reader(out.open()))
    head = rows[0]
    assert head[:3] == ["time", "hinge.q", "hinge.qdot"] and "bob.wz" in head
    assert len(rows) == 1 + 51  # t = 0, 0.01, ..., 0.5
    assert float(rows[1][1]) == pytest.approx(0.05)  # initial_angle
    assert not list(tmp_path.glob("*.plxtmp"))


def test_trace_into_a_missing_folder_is_exit_2(tmp_path):
    r = run_plx("check", "--trace", str(tmp_path / "nope" / "m.csv"), str(MODELS / "simple_pendulum.openplx"))
    assert r.returncode == 2 and "cannot write" in r.stderr and "Traceback" not in r.stderr


def test_stiff_spring_shortens_the_time_step_instead_of_clamping():
    code, doc = _json("--simulate", "--duration", "0.2", str(MODELS / "stiff_torsion_spring.openplx"))
    codes = {d["code"]: d for d in doc["diagnostics"]}
    assert "A133" in codes and "A112" not in codes
    sim = next(iter(doc["simulation"].values()))
    assert sim["timestep"] == pytest.approx(0.002 / 18)


def test_kinematic_body_is_noted_and_moves():
    code, doc = _json("--simulate", "--duration", "1", str(MODELS / "kinematic_bodies.openplx"))
    notes = [d for d in doc["diagnostics"] if d["code"] == "A121"]
    assert len(notes) == 1 and notes[0]["severity"] == "info" and "platform" in notes[0]["message"]
    sim = next(iter(doc["simulation"].values()))
    assert sim["bodies"]["platform"]["final"]["position"][0] == pytest.approx(0.5)
    assert sim["energy"]["checked"] is False


def test_redirected_connector_moves_with_its_redirected_parent_in_static_checks_and_simulation():
    code, doc = _json("--simulate", "--duration", "1", str(CASES / "physics" / "redirected_pendulum.openplx"))
    assert code == 0 and "A017" not in {d["code"] for d in doc["diagnostics"]}
    arm = next(iter(doc["simulation"].values()))["bodies"]["arm"]
    assert arm["final"]["position"][0] < 0  # swung down through the vertical to the other side


def test_a_mate_that_starts_apart_is_pulled_together():
    code, doc = _json("--simulate", str(CASES / "physics" / "pulled_together.openplx"))
    codes = [d["code"] for d in doc["diagnostics"]]
    assert codes.count("A016") == 1 and "A131" not in codes and "A103" not in codes  # one finding, no plx bug
    mate = next(iter(doc["simulation"].values()))["mates"]["joint"]
    assert mate["role"] == "pulled" and mate["initial_separation"] == pytest.approx(0.3)
    assert mate["final_separation"] < 0.002 and not mate["pulled_apart"]


def test_body_report_agrees_with_the_trace_sample_by_sample(tmp_path):
    """The monitors see the samples in batches (hundreds at a time); the path length they report
    is what adding up the traced positions one sample after the other gives, across the batches'
    boundaries (6 s = 601 samples; the JSON report has 6 decimals, one sample more or less would
    change the length by about 1e-3)."""
    out = tmp_path / "motion.csv"
    code, doc = _json("--duration", "6", "--trace", str(out), str(EXAMPLE))
    rows = list(csv.reader(out.open()))
    head, data = rows[0], [[float(x) for x in r] for r in rows[1:]]
    assert len(data) == 601
    body = "box_truck.chassis"
    ix, iy, iz = (head.index(f"{body}.{c}") for c in "xyz")
    length = 0.0
    for prev, cur in zip(data, data[1:]):
        dx, dy, dz = cur[ix] - prev[ix], cur[iy] - prev[iy], cur[iz] - prev[iz]
        length += math.sqrt(dx * dx + dy * dy + dz * dz)
    rep = next(iter(doc["simulation"].values()))["bodies"][body]
    assert length > 1.0 and rep["path_length"] == pytest.approx(length, rel=1e-5)
    final = rep["final"]["position"]
    assert final == pytest.approx([data[-1][ix], data[-1][iy], data[-1][iz]], abs=1e-6)
