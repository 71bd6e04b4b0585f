"""Visual-only meshes never change or block the physics: a body with visual meshes (a closed cube,
a flat square, a single triangle) moves exactly as the same body without them, the run is not
refused, and a mesh MuJoCo cannot load is left out with a note (A138)."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from physics_cases import run_model  # noqa: E402

CUBE = "\n".join(f"v {x} {y} {z}" for x in (0, 1) for y in (0, 1) for z in (0, 1)) + "\n" + \
    "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n"
FLAT = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"
TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"

VISUALS = """    cube_visual is Visuals.Geometries.ExternalTriMeshGeometry:
        path: @"cube.obj"
        local_transform.position: {2, 0, 0}
    flat_visual is Visuals.Geometries.ExternalTriMeshGeometry:
        path: @"flat.obj"
    triangle_visual is Visuals.Geometries.ExternalTriMeshGeometry:
        path: @"triangle.obj"
"""

MODEL = """Crate is Physics3D.Bodies.RigidBody:
VISUALS    geometry is Physics3D.Geometries.Box:
        size: {0.4, 0.2, 0.2}

Ground is Physics3D.Bodies.RigidBody:
    is_dynamic: false
    geometry is Physics3D.Geometries.Box:
        size: {6, 6, 0.2}

Drop is Physics3D.System:
    ground is Ground:
        kinematics.local_transform.position.z: -0.1
    crate is Crate:
        kinematics.local_transform.position.z: 1.0
        kinematics.initial_local_angular_velocity: {0.3, 1.0, 0}
"""


def _write(folder, with_visuals: bool):
    folder.mkdir()
    for name, text in (("cube.obj", CUBE), ("flat.obj", FLAT), ("triangle.obj", TRIANGLE)):
        (folder / name).write_text(text, encoding="utf-8")
    path = folder / "drop.openplx"
    path.write_text(MODEL.replace("VISUALS", VISUALS if with_visuals else ""), encoding="utf-8")
    return path


def test_visual_meshes_do_not_change_or_block_the_motion(tmp_path):
    bare = run_model(_write(tmp_path / "bare", False), 1.5)
    dressed = run_model(_write(tmp_path / "dressed", True), 1.5)
    assert dressed.exit_code == 0, dressed.report["diagnostics"]
    assert not any(d["severity"] == "error" for d in dressed.report["diagnostics"])
    notes = [d for d in dressed.report["diagnostics"] if d["code"] == "A138"]
    assert len(notes) == 1 and "triangle_visual" in notes[0]["message"] and "4 vertices" in notes[0]["message"]
    assert set(bare.trace) == set(dressed.trace)
    for col in bare.trace:
        assert dressed.trace[col] == pytest.approx(bare.trace[col], abs=0.0), col
    a = next(iter(bare.report["simulation"].values()))["bodies"]["crate"]
    b = next(iter(dressed.report["simulation"].values()))["bodies"]["crate"]
    assert b["max_kinetic_energy"] == a["max_kinetic_energy"]
