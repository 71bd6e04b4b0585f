"""Impacts with a normal restitution, through the Python API: a ball dropped on a static floor and
two balls of any mass ratio colliding head on.  Shared by tests/physics/test_restitution.py and
bench/restitution.py (the table in docs/physics.md).

Closed form: an impact at normal speed v leaves at e v.  Measured as the rebound speed ratio:
for a drop from H, sqrt(rebound apex / H) (the apex above the floor, so what the impact cost in
position counts too); for two balls, their separation speed over their approach speed."""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

G = 9.80665
RADIUS = 0.1

_MATERIALS = """
const ImpactA is Physics.Geometries.Material:
    unique_name: "impact_a"
    density: {da}

const ImpactB is Physics.Geometries.Material:
    unique_name: "impact_b"
    density: {db}

Bounce is Physics.Interactions.SurfaceContact.Model:
    material_1: ImpactA
    material_2: ImpactB
    normal_restitution: {e}
    tangential_restitution: 0.0
    friction becomes Physics.Interactions.Dissipation.DryConeFriction:
        coefficient: 0.5
"""

DROP = _MATERIALS + """
Drop is Physics3D.System:
    floor is Physics3D.Bodies.RigidBody:
        is_dynamic: false
        kinematics.local_transform.position.z: -0.1
        geometry is Physics3D.Geometries.Box:
            size: {{4, 4, 0.2}}
            material: ImpactB
    ball is Physics3D.Bodies.RigidBody:
        kinematics.local_transform.position.z: {z}
        geometry is Physics3D.Geometries.Sphere:
            radius: 0.1
            material: ImpactA
    contact is Bounce
"""

HEAD_ON = _MATERIALS + """
HeadOn is Physics3D.System:
    a is Physics3D.Bodies.RigidBody:
        kinematics.local_transform.position.x: -0.5
        kinematics.initial_local_linear_velocity.x: {v}
        geometry is Physics3D.Geometries.Sphere:
            radius: 0.1
            material: ImpactA
    b is Physics3D.Bodies.RigidBody:
        kinematics.local_transform.position.x: 0.5
        geometry is Physics3D.Geometries.Sphere:
            radius: 0.1
            material: ImpactB
    contact is Bounce
"""


def load_text(text: str, timestep: float, folder: Path | None = None):
    from plxtools.check.api import load

    d = Path(tempfile.mkdtemp(dir=folder))
    (d / "plx.toml").write_text(f"[check]\ntimestep = {timestep!r}\n", encoding="utf-8")
    f = d / "impact.openplx"
    f.write_text(text, encoding="utf-8")
    return load(f)


def drop(e: float, height: float, timestep: float) -> dict:
    """Rebound speed ratio, deepest penetration (m) and the A137 note of a ball dropped ``height``."""
    sim = load_text(DROP.format(e=e, da=1000, db=1000, z=height + RADIUS), timestep)
    v_in = math.sqrt(2 * G * height)
    t_max = math.sqrt(2 * height / G) + 2 * e * v_in / G + 0.1
    deepest, rising, apex = 0.0, False, 0.0
    for _ in range(int(t_max / sim.timestep)):
        sim.step()
        b = sim.body("ball")
        z, vz = b.position[2] - RADIUS, b.linear_velocity[2]
        deepest = min(deepest, z)
        if vz > 0:
            rising = True
        elif rising:  # the first sample past the apex: the parabola's top through it
            apex = z + vz * vz / (2 * G)
            break
    return {"ratio": math.sqrt(max(apex, 0.0) / height), "speed": v_in, "depth": -deepest,
            "notes": _a137(sim)}


def head_on(e: float, mass_ratio: float, timestep: float, speed: float = 2.0) -> dict:
    """Separation over approach speed of a ball hitting one ``mass_ratio`` times heavier at rest."""
    sim = load_text(HEAD_ON.format(e=e, da=1000, db=1000 * mass_ratio, v=speed), timestep)
    sim.step(1.0 / speed)
    va, vb = sim.body("a").linear_velocity[0], sim.body("b").linear_velocity[0]
    return {"ratio": (vb - va) / speed, "speed": speed, "notes": _a137(sim)}


def within(e: float, ratio: float, tol: float = 0.03) -> bool:
    """The rebound speed ratio within 3 % of e (within 0.03 of 0 for e = 0: nothing to take a share of)."""
    return abs(ratio - e) <= tol * (e if e > 0 else 1.0)


def _a137(sim) -> list:
    """The backend's A137 notes on the loaded model (severity "info" or "warning", message)."""
    return [n for n in sim.prepared.compiled.notes if n.code == "A137"]
