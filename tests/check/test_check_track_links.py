"""Vehicles track link descriptions: the runtime computes each link's length (the Box's size.x) from
the belt's routing, so check does not call the link a zero-size box (A030); the track itself is named
as unsupported (A040)."""

from __future__ import annotations

import json

from tests.conftest import CASES, REPO, run_plx

TRACK = CASES / "check" / "vehicles" / "track.openplx"


def _diags(path):
    r = run_plx("check", "--output-format", "json", str(path))
    assert "Traceback" not in r.stderr, r.stderr
    return r, json.loads(r.stdout)["diagnostics"]


def test_track_link_box_is_not_zero_size():
    r, diags = _diags(TRACK.relative_to(REPO))
    assert r.returncode == 0, r.stdout
    assert not [d for d in diags if d["code"] == "A030"]
    track = [d for d in diags if d["code"] == "A040" and d["message"].startswith("track (Vehicles.Tracks.System)")]
    assert len(track) == 1 and track[0]["range"]["start"]["line"] == 17


def test_a_zero_size_box_outside_a_link_description_is_still_reported(tmp_path):
    text = TRACK.read_text(encoding="utf-8") + (
        "    crate is Physics3D.Bodies.RigidBody:\n"
        "        inertia.mass: 1\n"
        "        kinematics.local_transform.position.z: 2\n"
        "        shape is Physics3D.Geometries.Box:\n"
        "            size.y: 1\n")
    src = tmp_path / "track.openplx"
    src.write_text(text, encoding="utf-8")
    r, diags = _diags(src)
    a030 = [d for d in diags if d["code"] == "A030"]
    assert len(a030) == 1 and "crate.shape has size {0, 1, 0}" in a030[0]["message"], a030
