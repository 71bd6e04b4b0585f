"""One mistake, one message (issue 16): the cause is reported, what only follows from it is not,
and a value missing in a model used four times is reported once, naming the instances."""

from __future__ import annotations

import json
from pathlib import Path

from tests.conftest import run_plx

WHEEL = """\
Wheel is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Cylinder:
{geometry}
    inertia.mass: 10

Truck is Physics3D.System:
    front_left is Wheel
    front_right is Wheel
    rear_left is Wheel
    rear_right is Wheel
"""


def _lint(tmp_path: Path, geometry: str, *extra: str) -> list[tuple[str, int, str]]:
    f = tmp_path / "truck.openplx"
    f.write_text(WHEEL.format(geometry=geometry), encoding="utf-8")
    r = run_plx("lint", "--output-format", "json", *extra, str(f))
    return [(d["code"], d["range"]["start"]["line"], d["message"]) for d in json.loads(r.stdout)]


def test_a_misspelt_attribute_in_a_model_used_four_times_is_one_diagnostic(tmp_path):
    got = _lint(tmp_path, "        raduis: 0.4\n        height: 0.3")
    assert [(c, ln) for c, ln, _ in got] == [("N002", 3)], got


def test_a_misspelling_does_not_hide_another_missing_value(tmp_path):
    got = _lint(tmp_path, "        raduis: 0.4")
    assert [c for c, _, _ in got] == ["M007", "N002"], got
    assert "height" in got[0][2] and "4 instances" in got[0][2]


def test_an_empty_block_is_reported_alone(tmp_path):
    got = _lint(tmp_path, "")
    assert [c for c, _, _ in got] == ["S010"], got


def test_a_value_missing_in_every_instance_is_reported_once_naming_them(tmp_path):
    got = _lint(tmp_path, "        height: 0.3")
    assert len(got) == 1 and got[0][:2] == ("M007", 2), got
    msg = got[0][2]
    assert msg.startswith("missing assignment geometry.radius (Real) in 4 instances")
    assert "front_left, front_right, rear_left, rear_right" in msg


def test_check_does_not_repeat_what_follows_from_the_typo(tmp_path):
    f = tmp_path / "truck.openplx"
    f.write_text(WHEEL.format(geometry="        raduis: 0.4\n        height: 0.3"), encoding="utf-8")
    r = run_plx("check", "--output-format", "json", str(f))
    assert [d["code"] for d in json.loads(r.stdout)["diagnostics"]] == ["N002"], r.stdout


def test_a_block_whose_first_line_is_three_spaces_short_is_flagged_on_that_line(tmp_path):
    p = tmp_path / "wheel.openplx"
    p.write_text("Wheel is Physics3D.Bodies.RigidBody:\n"
                 "    inertia.mass: 10\n"
                 "    connector is Physics3D.Interactions.MateConnector:\n"
                 "     main_axis: {0, -1, 0}\n"
                 "        normal: {1, 0, 0}\n", encoding="utf-8")
    r = run_plx("lint", "--output-format", "json", str(p))
    items = [(d["code"], d["range"]["start"]["line"]) for d in json.loads(r.stdout)]
    assert items == [("C006", 4)], r.stdout  # the short line itself, not the correct line after it
    assert "indent it 8 spaces" in r.stdout
    fixed = run_plx("fmt", "-", stdin=p.read_text(encoding="utf-8")).stdout
    assert "        main_axis: {0, -1, 0}\n        normal: {1, 0, 0}\n" in fixed  # fmt agrees with the help
