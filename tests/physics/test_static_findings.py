"""The smaller findings of round 3: a range that starts violated is found before any simulation
(A045), A120 names only the part of an initial velocity a mate really leaves out, and A018 (hinge
axis off a cylinder's axis) only speaks about a body the hinge turns, a wheel, not about a disc that
only sits on a hinged body."""

from __future__ import annotations

import contextlib
import io
import json

import pytest

pytest.importorskip("mujoco")

from physics_cases import MODELS  # noqa: E402


def _check(path, *extra):
    from plxtools.cli import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        code = main(["check", str(path), "--output-format", "json", *extra])
    return code, json.loads(out.getvalue())


def _line(path, needle: str) -> int:
    return next(i for i, t in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if needle in t)


def test_a_range_that_starts_violated_is_found_statically(tmp_path):
    text = (MODELS / "hinge_range.openplx").read_text(encoding="utf-8")
    path = tmp_path / "violated.openplx"
    path.write_text(text.replace("        start: -0.4\n        end: 1.0", "        start: -0.4\n        end: 0.4"),
                    encoding="utf-8")
    _, doc = _check(path)  # no --simulate: static
    a045 = [d for d in doc["diagnostics"] if d["code"] == "A045"]
    assert len(a045) == 1 and "initial_angle 1" in a045[0]["message"] and "[-0.4, 0.4]" in a045[0]["message"]
    assert a045[0]["range"]["start"]["line"] == _line(path, "initial_angle: 1.0")
    _, ok = _check(MODELS / "hinge_range.openplx")  # the same mate starting on the range's end: fine
    assert not [d for d in ok["diagnostics"] if d["code"] == "A045"]


SWING = """Support is Physics3D.Bodies.RigidBody:
    is_dynamic: false
    post is Physics3D.Geometries.Cylinder:
        radius: 0.05
        height: 0.3
        local_transform.rotation: Math.Quat.angle_axis(Math.PI / 2, {1, 0, 0})
    pivot is Physics3D.Interactions.MateConnector:
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}

Rod is Physics3D.Bodies.RigidBody:
    inertia.mass: 1.0
    geometry is Physics3D.Geometries.Box:
        size: {0.02, 0.02, 1.0}
    disc is Physics3D.Geometries.Cylinder:
        radius: 0.2
        height: 0.02
        local_transform.position: {0, 0, -0.5}
        local_transform.rotation: Math.Quat.angle_axis(Math.PI / 2, {1, 0, 0})
    top_end is Physics3D.Interactions.MateConnector:
        position: {0, 0, 0.5}
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}

Swing is Physics3D.System:
    support is Support:
        kinematics.local_transform.position.z: 2.0
    rod is Rod:
        kinematics.initial_local_angular_velocity: {0, 2, 0}
        kinematics.initial_local_linear_velocity: VELOCITY
    hinge is Physics3D.Interactions.Hinge:
        connectors: [support.pivot, rod.top_end]
"""


def test_a120_only_names_what_the_mate_really_leaves_out(tmp_path):
    # turning at 2 rad/s about a hinge 0.5 m above its centre, the rod's centre moves at (-1, 0, 0) m/s
    path = tmp_path / "swing.openplx"
    path.write_text(SWING.replace("VELOCITY", "{-1, 0, 0}"), encoding="utf-8")
    _, doc = _check(path, "--simulate", "--duration", "0.05")
    assert not [d for d in doc["diagnostics"] if d["code"] == "A120"], doc["diagnostics"]
    path.write_text(SWING.replace("VELOCITY", "{-1, 0, 0.5}"), encoding="utf-8")
    _, doc = _check(path, "--simulate", "--duration", "0.05")
    a120 = [d for d in doc["diagnostics"] if d["code"] == "A120"]
    assert len(a120) == 1 and "linear (0, 0, 0.5)" in a120[0]["message"]


def test_a018_is_not_about_a_static_post_or_a_disc_far_from_the_hinge(tmp_path):
    # the support's post stands along Z through the hinge but does not turn; the rod's disc hangs
    # 1 m below the hinge: neither is a wheel
    path = tmp_path / "swing.openplx"
    path.write_text(SWING.replace("VELOCITY", "{-1, 0, 0}"), encoding="utf-8")
    _, doc = _check(path)
    assert not [d for d in doc["diagnostics"] if d["code"] == "A018"], doc["diagnostics"]
    # the same hinge through a dynamic wheel whose axis is off the hinge axis is the wheel mistake
    wheel = SWING.replace("VELOCITY", "{-1, 0, 0}").replace(
        "        local_transform.position: {0, 0, -0.5}\n", "        local_transform.position: {0, 0, 0.5}\n")
    path.write_text(wheel, encoding="utf-8")
    _, doc = _check(path)
    assert [d for d in doc["diagnostics"] if d["code"] == "A018"], doc["diagnostics"]
