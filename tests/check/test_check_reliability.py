"""Issue 14 (items 6-8) and issue 16 (check messages) through the real `plx check` command line:
non-finite values, JSON that is always JSON, exports that MuJoCo loads, usage errors, one message
per mistake, one rule for running the backend after errors."""

from __future__ import annotations

import json
import random
import tempfile
from pathlib import Path

import pytest

from check_helpers import BROKEN, REPO

from tests.conftest import campaign_size, run_plx as _run_plx


def run_plx(*args: str):
    """`plx` run outside the repository, so that MuJoCo's MUJOCO_LOG.TXT (written on a blow-up)
    lands in a temporary folder, not in the working tree (all paths given are absolute)."""
    return _run_plx(*args, cwd=_scratch())


def _scratch() -> Path:
    global _SCRATCH
    if _SCRATCH is None:
        _SCRATCH = Path(tempfile.mkdtemp(prefix="plx-check-tests-"))
    return _SCRATCH


_SCRATCH: Path | None = None

# a hinged link driven by a motor (the fuzzing campaign's control scene); each case replaces one value
CONTROL = """\
Link is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size: {0.1, 0.1, 0.5}
    inertia.mass: 1
    top is Physics3D.Interactions.MateConnector:
        position: {0, 0, 0.25}
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}
Scene is Physics3D.System:
    anchor is Physics3D.Interactions.MateConnector:
        position: {0, 0, 3}
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}
    link is Link:
        kinematics.initial_local_linear_velocity: {0, 0, 0}
    hinge is Physics3D.Interactions.Hinge:
        connectors: [anchor, link.top]
    motor is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: hinge.connectors
        target_speed: 1
        gain: 1e8
"""
INF, NAN = "(1e308 * 10)", "(1e308 * 10 - 1e308 * 10)"
NON_FINITE = {  # name: (text replaced, replacement, 1-based line of the error)
    "mass_nan": ("inertia.mass: 1", f"inertia.mass: {NAN}", 4),
    "size_inf": ("size: {0.1, 0.1, 0.5}", "size: {0.1, 0.1, %s}" % INF, 3),
    "size_nan": ("size: {0.1, 0.1, 0.5}", "size: {0.1, 0.1, %s}" % NAN, 3),
    "axis_inf": ("        main_axis: {0, 1, 0}\n        normal: {1, 0, 0}\nScene",
                 "        main_axis: {0, %s, 0}\n        normal: {1, 0, 0}\nScene" % INF, 7),
    "cpos_nan": ("position: {0, 0, 0.25}", "position: {0, 0, %s}" % NAN, 6),
    "vel_inf": ("velocity: {0, 0, 0}", "velocity: {%s, 0, 0}" % INF, 15),
    "vel_nan": ("velocity: {0, 0, 0}", "velocity: {%s, 0, 0}" % NAN, 15),
    "gain_inf": ("gain: 1e8", f"gain: {INF}", 21),
}


def _write(tmp_path: Path, text: str, name: str = "scene.openplx") -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def _json(*args: str):
    r = run_plx("check", "--output-format", "json", *args)
    assert "Traceback" not in r.stderr and "internal error" not in r.stderr, r.stderr
    return r, json.loads(r.stdout)


def test_control_scene_is_clean_and_simulates(tmp_path):
    r, doc = _json("--simulate", "--duration", "0.5", str(_write(tmp_path, CONTROL)))
    assert r.returncode == 0
    assert not [d for d in doc["diagnostics"] if d["severity"] == "error"]
    assert "bodies" in next(iter(doc["simulation"].values()))


@pytest.mark.parametrize("case", sorted(NON_FINITE))
def test_non_finite_value_is_an_error_at_its_line(tmp_path, case):
    old, new, line = NON_FINITE[case]
    assert old in CONTROL
    f = _write(tmp_path, CONTROL.replace(old, new, 1))
    r, doc = _json("--simulate", "--duration", "0.5", str(f))
    assert r.returncode == 1
    errors = [d for d in doc["diagnostics"] if d["severity"] == "error"]
    assert [(d["code"], d["range"]["start"]["line"]) for d in errors] == [("A041", line)], errors
    sim = next(iter(doc["simulation"].values()))
    assert "A041" in sim["skipped"]


def test_infinite_size_does_not_drop_the_geometry_silently(tmp_path):
    old, new, _ = NON_FINITE["size_inf"]
    r = run_plx("check", "--simulate", str(_write(tmp_path, CONTROL.replace(old, new, 1))))
    assert "A041" in r.stdout and "link.geometry.size is infinite" in r.stdout
    assert "All checks passed" not in r.stdout and r.returncode == 1


def test_infinity_as_no_limit_is_allowed(tmp_path):
    text = CONTROL.replace("gain: 1e8", "gain: 1e8\n        max_effort: Math.INF\n        min_effort: Math.NEG_INF")
    r, doc = _json(str(_write(tmp_path, text)))
    assert r.returncode == 0 and not [d for d in doc["diagnostics"] if d["code"] == "A041"]


def test_json_replaces_non_finite_numbers_by_null_and_says_where():
    from plxtools.check.output import _finite_json

    found: list[str] = []
    out = _finite_json({"a": [1.0, float("nan")], "b": {"c": float("inf")}, "d": "x"}, "", found)
    assert out == {"a": [1.0, None], "b": {"c": None}, "d": "x"}
    assert found == ["/a/1", "/b/c"]


def test_simulation_blow_up_gives_valid_json(tmp_path):
    blow = ("Box is Physics3D.Bodies.RigidBody:\n    geometry is Physics3D.Geometries.Box:\n        size: {1, 1, 1}\n"
            "    inertia.mass: 1\n    kinematics.initial_local_linear_velocity: {1e300, 0, 0}\n"
            "Scene is Physics3D.System:\n    box is Box\n")
    r, doc = _json("--simulate", "--duration", "0.5", str(_write(tmp_path, blow)))
    assert r.returncode == 1
    assert any(d["code"] == "A101" for d in doc["diagnostics"])
    assert next(iter(doc["simulation"].values()))["findings"]["blowup"] is not None


def test_export_that_mujoco_cannot_reload_is_a_located_error(tmp_path):
    f = _write(tmp_path, "Box is Physics3D.Bodies.RigidBody:\n    geometry is Physics3D.Geometries.Box:\n"
                         "        size: {0.5, 1e30, 0.5}\n    inertia.mass: 1\nScene is Physics3D.System:\n"
                         "    box is Box\n")
    out = tmp_path / "x.xml"
    r = run_plx("check", "--export-mjcf", str(out), str(f))
    assert r.returncode == 2, r.stdout + r.stderr
    assert "A132" in r.stdout and f"{f.name}:2:5" in r.stdout
    assert not out.exists() and not list(tmp_path.glob(".plx-export-*"))


def test_exported_example_reloads(tmp_path):
    import mujoco

    out = tmp_path / "truck.xml"
    r = run_plx("check", "--export-mjcf", str(out), str(REPO / "examples" / "boxtruck" / "boxtruck.openplx"))
    assert r.returncode == 0, r.stdout + r.stderr
    assert mujoco.MjModel.from_xml_path(str(out)).nbody > 1


@pytest.mark.parametrize("value", ["inf", "nan", "0", "-1", "1e9"])
def test_impossible_duration_is_a_usage_error(tmp_path, value):
    r = run_plx("check", "--simulate", "--duration", value, str(_write(tmp_path, CONTROL)))
    assert r.returncode == 2
    assert "--duration" in r.stderr and "internal error" not in r.stderr and "All checks passed" not in r.stdout


def test_zero_main_axis_is_one_error_and_blocks_the_simulation(tmp_path):
    text = CONTROL.replace("    top is Physics3D.Interactions.MateConnector:\n        position: {0, 0, 0.25}\n"
                           "        main_axis: {0, 1, 0}",
                           "    top is Physics3D.Interactions.MateConnector:\n        position: {0, 0, 0.25}\n"
                           "        main_axis: {0, 0, 0}")
    assert text != CONTROL
    r, doc = _json("--simulate", str(_write(tmp_path, text)))
    assert [d["code"] for d in doc["diagnostics"] if d["severity"] != "info"] == ["A010"]
    assert "A010" in next(iter(doc["simulation"].values()))["skipped"]


def test_wheel_on_a_cylinder_with_a_zero_axis_has_no_off_axis_warning(tmp_path):
    text = (BROKEN / "flipped_axis.openplx").read_text(encoding="utf-8")
    r0, doc0 = _json(str(_write(tmp_path, text, "a.openplx")))
    assert any(d["code"] == "A018" for d in doc0["diagnostics"])  # the example's own finding
    assert text.count("main_axis: {0, 0, 1}") == 1  # the wheel connector of the Wheel model
    lines = [text.replace("main_axis: {0, 0, 1}", "main_axis: {0, 0, 0}")]
    r, doc = _json(str(_write(tmp_path, "\n".join(lines) + "\n", "b.openplx")))
    got = [d["code"] for d in doc["diagnostics"]]
    assert "A010" in got and "A018" not in got, got


def test_motion_warnings_are_in_the_simulation_findings():
    f = str((BROKEN / "mirrored_motors.openplx").resolve())
    r = run_plx("check", "--simulate", "--duration", "0.5", f)
    assert "findings: none" not in r.stdout and "A023 (line" in r.stdout
    _, doc = _json("--simulate", "--duration", "0.5", f)
    motion = next(iter(doc["simulation"].values()))["findings"]["motion_diagnostics"]
    assert "A023" in {m["code"] for m in motion}


def test_backend_notes_are_registered_rule_codes(tmp_path):
    """One naming scheme: everything the backend says is a registered A1xx code."""
    from plxtools.rules.registry import get

    _, doc = _json("--simulate", "--duration", "0.5", str(REPO / "examples" / "boxtruck" / "boxtruck.openplx"))
    backend = [d for d in doc["diagnostics"] if d["code"].startswith("A1")]
    assert backend and all(get(d["code"]) is not None for d in backend)


def test_a_missing_value_is_reported_once(tmp_path):
    """Lint's M007 owns a missing value; check does not add its own A004 for it."""
    text = ("Wheel is Physics3D.Bodies.RigidBody:\n    r is Real\n    geometry is Physics3D.Geometries.Cylinder:\n"
            "        radius: r\n        height: 0.2\nScene is Physics3D.System:\n    w is Wheel\n")
    _, doc = _json(str(_write(tmp_path, text)))
    got = [d["code"] for d in doc["diagnostics"]]
    assert "A004" not in got and any(c.startswith("M") for c in got), got


# ---------------------------------------------------------------------------------------- fuzzing

_ABSURD = ["(1e308 * 10)", "(1e308 * 10 - 1e308 * 10)", "-(1e308 * 10)", "0", "-1", "1e-300", "1e300", "1e30",
           "1e-12", "1" + "0" * 400]
_TARGETS = ["inertia.mass: 1", "size: {0.1, 0.1, 0.5}", "position: {0, 0, 0.25}", "velocity: {0, 0, 0}",
            "gain: 1e8", "target_speed: 1", "position: {0, 0, 3}"]


def mutate(rng: random.Random) -> str:
    """The control scene with one to three values replaced by absurd ones (whole lines are replaced,
    so a replaced value is never edited again as text)."""
    lines = CONTROL.splitlines()
    for _ in range(rng.randint(1, 3)):
        target = rng.choice(_TARGETS)
        found = [i for i, x in enumerate(lines) if x.strip() == target or x.strip().endswith(target)]
        if not found:
            continue  # already replaced
        i = found[0]
        indent, text = lines[i][: len(lines[i]) - len(lines[i].lstrip())], lines[i].strip()
        key, _, val = text.rpartition(": ")
        if val.startswith("{"):
            parts = val.strip("{}").split(", ")
            parts[rng.randrange(3)] = rng.choice(_ABSURD)
            val = "{" + ", ".join(parts) + "}"
        else:
            val = rng.choice(_ABSURD)
        lines[i] = f"{indent}{key}: {val}"
    return "\n".join(lines) + "\n"


def check_one(path: Path, export: Path) -> None:
    """The properties every bad scene must keep: a documented exit code, a JSON document, no
    internal error, "All checks passed" only without errors, and an export only if it loads."""
    r = run_plx("check", "--simulate", "--duration", "0.2", "--output-format", "json", "--export-mjcf",
                str(export), str(path))
    assert r.returncode in (0, 1, 2), r.stderr
    assert "internal error" not in r.stderr and "Traceback" not in r.stderr, r.stderr
    doc = json.loads(r.stdout)
    errors = [d for d in doc["diagnostics"] if d["severity"] == "error"]
    if r.returncode == 0:
        assert not errors
    if export.exists():
        import mujoco

        mujoco.MjModel.from_xml_path(str(export))
        export.unlink()
    elif r.returncode != 2:
        raise AssertionError("no export written, yet exit code %d" % r.returncode)


@pytest.mark.parametrize("seed", range(campaign_size(4)))
def test_fuzz_bad_scenes(tmp_path, seed):
    rng = random.Random(seed)
    f = _write(tmp_path, mutate(rng))
    check_one(f, tmp_path / "out.xml")


def test_connector_typo_gives_no_ground_plane_advice(tmp_path):
    """A typo in a hinge's connector leaves a wheel unplaced: the advice points at the hinge, and the
    static ground (where it should be) gets no warning of its own."""
    text = (REPO / "examples" / "boxtruck" / "boxtruck.openplx").read_text(encoding="utf-8")
    assert "connectors: [chassis.front_left_hub," in text
    f = _write(tmp_path, text.replace("connectors: [chassis.front_left_hub,", "connectors: [chassis.front_left_hb,"))
    _, doc = _json(str(f))
    a037 = [d for d in doc["diagnostics"] if d["code"] == "A037"]
    assert len(a037) == 1 and "front_left_wheel" in a037[0]["message"], a037
    assert "front_left_hinge could not be built" in a037[0]["help"]
    assert any(d["code"] == "N004" for d in doc["diagnostics"])


MISSING_CONST = """\
Steel is Physics.Geometries.Material:
    density: 7800
Box is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size: {1, 1, 1}
        material: Steel
Scene is Physics3D.System:
    box is Box
"""


def test_model_used_as_a_value_is_one_error(tmp_path):
    """Lint's T001 owns it; check does not add "not to a TypeObj value"."""
    r = run_plx("check", str(_write(tmp_path, MISSING_CONST)))
    assert r.stdout.count(" T001 ") == 1 and "A005" not in r.stdout and "TypeObj" not in r.stdout, r.stdout


def test_model_used_as_a_value_names_const_when_check_reports_it(check_text, monkeypatch):
    """Where check is the one to report it, the message names the user's concept, not a class."""
    from plxtools.rules import registry

    # no code owns another (the registry's `owns`): check makes A005 and it stands beside T001
    monkeypatch.setattr(registry, "owned_by", lambda codes: frozenset())
    fc = check_text(MISSING_CONST)
    [d] = [d for d in fc.diagnostics if d.code == "A005"]
    assert "'Steel' is a model, not an object" in d.message and "TypeObj" not in d.message
    assert "const Steel is" in d.help and "material is Steel" in d.help


def test_integer_beyond_float_range_is_a_located_error(tmp_path):
    big = "1" + "0" * 400
    f = _write(tmp_path, CONTROL.replace("inertia.mass: 1", f"inertia.mass: {big}").replace("gain: 1e8", f"gain: {big}"))
    r, doc = _json("--simulate", str(f))
    assert r.returncode == 1
    assert [(d["code"], d["range"]["start"]["line"]) for d in doc["diagnostics"] if d["severity"] == "error"] == [
        ("A041", 4), ("A041", 21)]


def test_internal_error_never_ends_in_all_checks_passed():
    import io

    from plxtools.check.output import render_text
    from plxtools.check.pipeline import FileCheck, Skip

    out = io.StringIO()
    render_text([FileCheck("a.openplx", skip=Skip.INTERNAL, internal_error="boom")], [], out, simulate=True)
    text = out.getvalue()
    assert "All checks passed" not in text and "could not be checked (internal error)" in text


def test_a_blow_up_leaves_no_mujoco_log_in_the_users_folder(tmp_path):
    """MuJoCo's default handler appends its warnings to MUJOCO_LOG.TXT in the current folder."""
    blow = ("Box is Physics3D.Bodies.RigidBody:\n    geometry is Physics3D.Geometries.Box:\n        size: {1, 1, 1}\n"
            "    inertia.mass: 1\n    kinematics.initial_local_linear_velocity: {1e300, 0, 0}\n"
            "Scene is Physics3D.System:\n    box is Box\n")
    f = _write(tmp_path, blow)
    r = _run_plx("check", "--simulate", "--duration", "0.5", str(f), cwd=tmp_path)
    assert r.returncode == 1 and "A101" in r.stdout, r.stdout + r.stderr
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()


def test_model_option_changes_the_root_the_lint_rules_judge(tmp_path):
    """`--model Test` instantiates Test, so a value missing only in the last model is not reported."""
    f = _write(tmp_path, "Wheel is Physics3D.Bodies.RigidBody:\n    radius is Real\n    inertia.mass: 10\n\n"
                         "Test is Physics3D.System:\n    w is Wheel:\n        radius: 0.3\n\n"
                         "Scene is Physics3D.System:\n    w is Wheel\n")
    default = json.loads(_run_plx("check", "--output-format", "json", str(f), cwd=tmp_path).stdout)
    assert "M007" in [d["code"] for d in default["diagnostics"]]
    chosen = _run_plx("check", "--model", "Test", "--output-format", "json", str(f), cwd=tmp_path)
    codes = [d["code"] for d in json.loads(chosen.stdout)["diagnostics"]]
    assert "M007" not in codes and "C007" not in codes, chosen.stdout
    assert chosen.returncode == 0
