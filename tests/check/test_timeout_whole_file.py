"""`plx check --timeout` bounds the file's whole check (issue 33, point 5: reproduction
check-timeout-ignored-overlapping-bodies): the initial-overlap check is linear in MuJoCo's contacts
and stops at the limit saying what it found and what is left; the static overlap check (A037) is a
sort-and-sweep broad phase."""

from __future__ import annotations

import json
import re
import time

import pytest

from tests.conftest import run_plx

pytest.importorskip("mujoco")


def _heap(n: int, spread: float = 0.0) -> str:
    """`n` unit boxes, all at the origin (spread 0: every pair overlaps) or in a row along x from
    x = 10, `spread` m apart."""
    lines = ["Scene is Physics3D.System:"]
    for i in range(n):
        lines += [f"    b{i} is Physics3D.Bodies.RigidBody:", "        inertia.mass: 1"]
        if spread:
            lines += [f"        kinematics.local_transform.position: {{{10 - i * spread}, 0, 0}}"]
        lines += ["        g is Physics3D.Geometries.Box:", "            size: {1, 1, 1}"]
    return "\n".join(lines) + "\n"


def _json(*args):
    r = run_plx("check", "--output-format", "json", *args)
    assert r.returncode in (0, 1), r.stderr
    return r.returncode, json.loads(r.stdout)


def test_300_overlapping_bodies_stop_at_the_limit(tmp_path):
    f = tmp_path / "heap.openplx"
    f.write_text(_heap(300))
    t0 = time.monotonic()
    code, doc = _json("--simulate", "--duration", "0.5", "--timeout", "4", str(f))
    elapsed = time.monotonic() - t0
    codes = [d["code"] for d in doc["diagnostics"]]
    a109 = [d["message"] for d in doc["diagnostics"] if d["code"] == "A109"]
    assert code == 1 and len(a109) == 1
    # stopped in the overlap check (saying what is left) or in the simulation (the overlaps listed)
    assert "overlapping pairs" in a109[0] or "A104" in codes, a109
    assert elapsed < 60, elapsed  # before: no result after 120 s


def test_a_limit_reached_before_the_overlaps_are_listed_says_how_many_are_left(tmp_path):
    f = tmp_path / "heap.openplx"
    f.write_text(_heap(20))
    code, doc = _json("--simulate", "--duration", "0.5", "--timeout", "0.001", str(f))
    a109 = [d["message"] for d in doc["diagnostics"] if d["code"] == "A109"]
    assert code == 1 and len(a109) == 1
    assert "the check of initial overlaps was stopped by the time limit (0.001 s of wall time) after 0 of 190 " \
           "overlapping pairs (190 not reported); the simulation did not run" in a109[0]


def test_within_the_limit_every_overlapping_pair_is_listed(tmp_path):
    f = tmp_path / "heap.openplx"
    f.write_text(_heap(6))
    code, doc = _json("--simulate", "--duration", "0.05", str(f))
    pairs = [d["message"] for d in doc["diagnostics"] if d["code"] == "A104"]
    # the report groups the pairs of one geometry: "b0.g and b1.g overlap ... (also 4 more: ...)"
    listed = sum(1 + int(m.group(1)) if (m := re.search(r"also (\d+) more", p)) else 1 for p in pairs)
    assert listed == 15 and "A109" not in [d["code"] for d in doc["diagnostics"]]


def test_static_overlaps_are_found_among_spread_bodies(tmp_path):
    """The broad phase finds what a pair loop found: the box left at the origin overlaps b19 (x = 0.5,
    by 0.5 m), b20 and b21 of the row, and is reported with the first of them in the file."""
    f = tmp_path / "row.openplx"
    f.write_text(_heap(40, spread=0.5) + "    far is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n"
                 "        g is Physics3D.Geometries.Box:\n            size: {1, 1, 1}\n")
    code, doc = _json(str(f))
    a037 = [d["message"] for d in doc["diagnostics"] if d["code"] == "A037"]
    assert a037 == ["far has no declared transform and no mate places it, so it stays at {0, 0, 0}, where it "
                    "overlaps b19 (by 0.5 m)"]
