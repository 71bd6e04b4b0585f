"""`plx check` through the real command line: output formats, the JSON contract, exit codes,
--render and --export-mjcf."""

from __future__ import annotations

import json
import math
import zlib

import pytest

from check_helpers import BROKEN, EXAMPLE, REPO, line_of

from tests.conftest import run_plx

EX = str(EXAMPLE.relative_to(REPO))


def _png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    w = int.from_bytes(data[16:20], "big")
    h = int.from_bytes(data[20:24], "big")
    return w, h


def test_example_is_clean_in_text_form():
    r = run_plx("check", EX)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "Traceback" not in r.stderr
    # the one finding is A044, an info: its DisableCollisionPair changes nothing at the start
    before = r.stdout.split("Scene:")[0]
    assert [ln.split()[2] for ln in before.splitlines() if ": info " in ln or ": warning " in ln
            or ": error " in ln] == ["A044"], r.stdout
    assert r.stdout.strip().endswith("Found 1 info.")
    assert f"{EX}: Scene: 6 bodies (1 declared, 4 placed by SNAP, 1 at their system's origin), 4 mates, " \
           f"2 controllers" in r.stdout


def test_simulate_json_contract_export_and_render(tmp_path):
    png, xml = tmp_path / "truck.png", tmp_path / "truck.xml"
    r = run_plx("check", "--simulate", "--output-format", "json", "--render", str(png), "--export-mjcf", str(xml), EX,
                env={"MESA_SHADER_CACHE_DISABLE": "true"})
    if r.returncode == 2 and "cannot render" in r.stderr:
        pytest.skip(f"offscreen rendering unavailable: {r.stderr.strip()}")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    assert set(doc) == {"diagnostics", "assembly", "simulation"}
    for d in doc["diagnostics"]:  # lint's item shape, 1-based ranges
        assert set(d) >= {"file", "code", "severity", "message", "range"}
        assert d["severity"] == "info" and d["range"]["start"]["line"] >= 1 and d["range"]["start"]["column"] >= 1
    sim = doc["simulation"][EX]
    assert sim["duration"] == 3.0 and sim["steps"] == 1500 and sim["timestep"] == 0.002
    bodies = sim["bodies"]
    assert set(bodies) == {"box_truck.chassis", "box_truck.front_left_wheel", "box_truck.front_right_wheel",
                           "box_truck.rear_left_wheel", "box_truck.rear_right_wheel", "ground"}
    ch = bodies["box_truck.chassis"]
    assert ch["initial"] == {"position": [0.0, 0.0, 1.1], "quaternion": [1.0, 0.0, 0.0, 0.0]}
    assert len(ch["final"]["position"]) == 3 and len(ch["final"]["quaternion"]) == 4
    assert math.hypot(*ch["final"]["position"][:2]) > 0.5  # it drove
    assert abs(ch["heading_change"]) < math.radians(1)
    assert bodies["box_truck.front_right_wheel"]["initial"]["quaternion"] == pytest.approx([0, 1, 0, 0], abs=1e-9)
    assert sim["findings"]["blowup"] is None and sim["findings"]["mates_pulled_apart"] == []
    asm = doc["assembly"][EX]["bodies"]
    assert asm["box_truck.rear_left_wheel"]["position"] == pytest.approx([3.3 * 0.31, -1.7 * 0.44, 1.1 - 1.44 * 0.48])
    # --export-mjcf: MJCF text that MuJoCo accepts
    text = xml.read_text()
    assert text.lstrip().startswith("<mujoco") and 'name="box_truck.chassis"' in text
    # --render: a real PNG of the assembled scene, not a blank frame
    data = png.read_bytes()
    assert _png_size(data) == (640, 480)
    assert len(data) > 2000 and zlib.crc32(data) != 0


def test_github_annotations_and_exit_code_for_a_broken_file():
    path = BROKEN / "moved_connector.openplx"
    r = run_plx("check", "--output-format", "github", str(path.relative_to(REPO)))
    assert r.returncode == 1
    line = line_of(path, "front_left_hinge is Physics3D.Interactions.Hinge")
    (ann,) = [x for x in r.stdout.splitlines() if x.startswith("::error")]
    assert ann.startswith(f"::error file=examples/broken/moved_connector.openplx,line={line},col=5,")
    assert "title=plx A016::A016 mate box_truck.front_left_hinge" in ann
    r = run_plx("check", "--exit-zero", str(path.relative_to(REPO)))
    assert r.returncode == 0 and "A016" in r.stdout


def test_sarif_for_all_broken_files():
    # examples/broken is excluded from folder scans by the project config: name the files
    files = sorted(str(p.relative_to(REPO)) for p in BROKEN.glob("*.openplx"))
    assert len(files) == 8
    r = run_plx("check", "--output-format", "sarif", *files)
    assert r.returncode == 1, r.stderr
    doc = json.loads(r.stdout)
    assert doc["version"] == "2.1.0"
    run = doc["runs"][0]
    rules = {x["id"] for x in run["tool"]["driver"]["rules"]}
    results = {(x["ruleId"], x["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]) for x in run["results"]}
    for code, name in [("A016", "moved_connector"), ("A018", "flipped_axis"), ("A020", "wrong_motor_connectors"),
                       ("A030", "zero_box_size"), ("M007", "missing_radius"), ("A035", "duplicate_contact"),
                       ("A031", "missing_mesh"), ("A023", "mirrored_motors")]:
        assert (code, f"examples/broken/{name}.openplx") in results
        assert code in rules
    levels = {x["ruleId"]: x["level"] for x in run["results"]}
    assert levels["A016"] == "error" and levels["A018"] == "warning" and levels["A023"] == "note"


def test_text_report_with_simulation_has_a_motion_table():
    r = run_plx("check", "--simulate", "--duration", "1", str((BROKEN / "moved_connector.openplx").relative_to(REPO)))
    assert r.returncode == 1
    out = r.stdout
    assert "simulated 1.00 s in 500 steps of 0.002 s" in out
    assert "box_truck.chassis" in out and "heading" in out and "moved" in out
    assert "findings:" in out and "box_truck.front_left_hinge pulled apart: max separation" in out


def test_usage_errors_and_bad_input_exit_cleanly(tmp_path):
    r = run_plx("check", "no/such/file.openplx")
    assert r.returncode == 2 and "no such file" in r.stderr and "Traceback" not in r.stderr
    r = run_plx("check", "--model", "Nope", EX)
    assert r.returncode == 1 and "A001" in r.stdout and "no model named 'Nope'" in r.stdout
    r = run_plx("check", "--duration", "0", "--simulate", EX)
    assert r.returncode == 2 and "--duration" in r.stderr
    bad = tmp_path / "bad.openplx"
    bad.write_text("Scene is Physics3D.System:\n    box is Physics3D.Bodies.RigidBody:\n        inertia.mass: (1\n")
    r = run_plx("check", "--simulate", "--output-format", "json", str(bad))
    assert r.returncode == 1 and "Traceback" not in r.stderr
    doc = json.loads(r.stdout)
    assert doc["diagnostics"] and all(d["code"].startswith("S") for d in doc["diagnostics"])
    assert doc["simulation"][str(bad)]["skipped"] == "the file has syntax errors"
    binary = tmp_path / "mesh.openplx"
    binary.write_bytes(b"\x00\x01\x02garbage")
    r = run_plx("check", str(binary))
    assert r.returncode == 1 and "S001" in r.stdout and "Traceback" not in r.stderr
