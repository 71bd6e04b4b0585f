"""Two motors, two ranges and two springs on one joint (a hinge or a prismatic) are a valid model:
``plx check --simulate`` must not report A134 (energy no motor supplied) unless the energy really
grows (issue 29, section 5).  The false A134 came from a velocity motor as stiff as 10 x inertia /
step against a range on its own joint: MuJoCo solves the joint limit from the servo's explicit force
and integrates the servo implicitly afterwards, so the joint chattered at the stop, the servo's
damping took energy out and the limit put it back (5e4 J "gained" over 2 s while the total energy
stayed put).  A range that starts violated does push the joint in with real energy: A134 stays."""

from __future__ import annotations

import contextlib
import io
import json

import pytest

pytest.importorskip("mujoco")

from plxtools.cli import main  # noqa: E402

HEAD = """\
Frame is Physics3D.Bodies.RigidBody:
    is_dynamic: false
    mount is Physics3D.Interactions.MateConnector:
        main_axis: {{0, 1, 0}}
        normal: {{1, 0, 0}}

Part is Physics3D.Bodies.RigidBody:
    inertia.mass: 4.0
    geometry is Physics3D.Geometries.Box:
        size:
            x: 0.6
            y: 0.2
            z: 0.2
        local_transform.position.x: {offset}
    socket is Physics3D.Interactions.MateConnector:
        main_axis: {{0, 1, 0}}
        normal: {{1, 0, 0}}

Crowd is Physics3D.System:
    frame is Frame:
        kinematics.local_transform.position.z: 1.0
    part is Part
    joint is Physics3D.Interactions.{mate}:
        connectors: [frame.mount, part.socket]
"""


def _motor(name: str, kind: str, linear: bool, value: float, limit: float | None) -> str:
    if kind == "velocity":
        t = "LinearVelocityMotor" if linear else "RotationalVelocityMotor"
        text = (f"    {name} is Physics3D.Interactions.{t}:\n        connectors: joint.connectors\n"
                f"        target_speed: {value}\n")
        if limit is not None:
            text += f"        max_effort: {limit}\n        min_effort: {-limit}\n"
        return text
    t, attr = ("ForceMotor", "default_force") if linear else ("TorqueMotor", "default_torque")
    return f"    {name} is Physics3D.Interactions.{t}:\n        connectors: joint.connectors\n        {attr}: {value}\n"


def _range(name: str, linear: bool, start: float, end: float) -> str:
    t = "LinearRange" if linear else "RotationalRange"
    return (f"    {name} is Physics3D.Interactions.{t}:\n        connectors: joint.connectors\n"
            f"        start: {start}\n        end: {end}\n")


def _spring(name: str, linear: bool, rest: float, stiffness: float, damping: float | None) -> str:
    t, key = ("LinearSpring", "position") if linear else ("TorsionSpring", "angle")
    text = (f"    {name} is Physics3D.Interactions.{t}:\n        connectors: joint.connectors\n        {key}: {rest}\n"
            f"        flexibility.stiffness: {stiffness}\n")
    if damping is not None:
        text += ("        dissipation becomes Physics.Interactions.Dissipation.MechanicalDamping:\n"
                 f"            damping_constant: {damping}\n")
    return text


def crowded(linear: bool, kinds: tuple[str, str], limit: float | None, damping: float | None,
            offset: float = 0.0, low: float = -1.0) -> str:
    text = HEAD.format(offset=offset, mate="Prismatic" if linear else "Hinge")
    text += _motor("first_motor", kinds[0], linear, 1.0 if kinds[0] == "velocity" else 3.0, limit)
    text += _motor("second_motor", kinds[1], linear, -2.0 if kinds[1] == "velocity" else 8.0, limit)
    text += _range("wide_stop", linear, low, 1.0) + _range("narrow_stop", linear, low - 0.1, 0.8)
    text += _spring("soft_spring", linear, 0.0, 20.0, damping) + _spring("hard_spring", linear, 0.3, 50.0, damping)
    return text


def check(tmp_path, text: str) -> tuple[int, dict]:
    path = tmp_path / "crowd.openplx"
    path.write_text(text)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(["check", str(path), "--simulate", "--duration", "2", "--output-format", "json"])
    return code, json.loads(buf.getvalue())


def _codes(report: dict) -> set[str]:
    return {d["code"] for d in report["diagnostics"]}


CASES = [  # (prismatic, motor kinds, effort limit, spring damping, centre of mass off the axis)
    (False, ("velocity", "torque"), None, None, 0.0),  # 103 J "gained" before the fix
    (False, ("velocity", "torque"), None, 2.0, 0.3),  # 428 J, with gravity on an arm
    (False, ("velocity", "velocity"), None, None, 0.3),
    (True, ("velocity", "torque"), None, None, 0.0),  # 3581 J
    (True, ("velocity", "velocity"), 5.0, 2.0, 0.0),
]


@pytest.mark.parametrize("case", CASES, ids=[
    f"{'prismatic' if c[0] else 'hinge'}-{'+'.join(c[1])}-limit{c[2]}-damping{c[3]}-offset{c[4]}" for c in CASES])
def test_motors_ranges_and_springs_on_one_joint_gain_no_energy(tmp_path, case):
    linear, kinds, limit, damping, offset = case
    _code, report = check(tmp_path, crowded(linear, kinds, limit, damping, offset))
    assert "A134" not in _codes(report), [d["message"] for d in report["diagnostics"]]


def test_a_range_that_starts_violated_pushes_with_real_energy(tmp_path):
    """The block starts at 0, 0.2 m below both ranges: the stops throw it in, a real burst of energy
    (about 1.2 kJ in the first 10 ms) that the damping then takes away again."""
    _code, report = check(tmp_path, crowded(True, ("torque", "torque"), None, None, low=0.2))
    codes = _codes(report)
    assert {"A045", "A134"} <= codes
    energy = next(iter(report["simulation"].values()))["energy"]
    assert energy["max_unexplained_gain"] > 100.0
    assert energy["max_unexplained_gain_time"] < 0.1
