"""Values written as numbers outside their physical range are found by `plx lint` (so the editor
shows them while typing), on the value, and `plx check` does not repeat them."""

from __future__ import annotations

import json

from tests.conftest import run_plx

TEXT = """\
Wheel is Physics3D.Bodies.RigidBody:
    inertia.mass: -10
    geometry is Physics3D.Geometries.Cylinder:
        radius: -0.26
        height: (0.165)
    plate is Physics3D.Geometries.Box:
        size: {1, 0, 1}
    slab is Physics3D.Geometries.Box:
        size.z: -1
    good is Physics3D.Geometries.Box:
        size: {1, 2, 3}
    computed is Physics3D.Geometries.Sphere:
        radius: 0.5 - 1.0

Rig is Physics3D.System:
    wheel is Wheel
    grip is Physics.Interactions.SurfaceContact.Model:
        normal_restitution: 1.5
        tangential_restitution: 0
        friction becomes Physics.Interactions.Dissipation.DefaultDryFriction:
            coefficient: -0.1
"""


def test_lint_reports_literal_values_out_of_range_on_the_value(tmp_path):
    p = tmp_path / "rig.openplx"
    p.write_text(TEXT, encoding="utf-8")
    r = run_plx("lint", "--output-format", "json", str(p))
    got = {(d["code"], d["range"]["start"]["line"]) for d in json.loads(r.stdout)}
    assert {("A032", 2), ("A030", 4), ("A030", 7), ("A030", 9), ("A036", 18), ("A036", 21)} <= got
    assert not {line for code, line in got if code == "A030" and line in (5, 11, 13)}  # fine or computed
    assert r.returncode == 1


def test_check_reports_each_once_and_still_finds_the_computed_one(tmp_path):
    p = tmp_path / "rig.openplx"
    p.write_text(TEXT, encoding="utf-8")
    r = run_plx("check", "--output-format", "json", str(p))
    diags = json.loads(r.stdout)["diagnostics"]
    lines = [(d["code"], d["range"]["start"]["line"]) for d in diags if d["code"].startswith("A03")]
    assert len(lines) == len(set(lines)), lines  # no repeats of lint's findings
    assert ("A030", 13) in lines  # 0.5 - 1.0 is computed: check's evaluation finds it
