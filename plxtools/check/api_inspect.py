"""What the Python API tells about a loaded scene besides signals: a body's geometries and their
materials, the contact model between two materials, and where a connector is in the world now.

These read the assembled scene (``plxtools.check.scene``), the same one the MuJoCo model is built
from, so what they say is what is simulated (a geometry left out of the MuJoCo model is listed with
``simulated`` False)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class MaterialInfo:
    """A geometry's material: its ``unique_name`` (None for the bundle's default) and density (kg/m^3)."""

    name: str | None
    density: float


@dataclass(frozen=True)
class GeometryInfo:
    """One geometry of a body: its dotted path, kind (box, sphere, cylinder, capsule, plane, mesh),
    material, and whether it collides and gives mass."""

    path: str
    kind: str
    material: MaterialInfo
    collides: bool
    in_mass: bool
    visual_only: bool


@dataclass(frozen=True)
class ContactModelInfo:
    """The ``SurfaceContact.Model`` of a material pair, as simulated (``friction`` None: the default)."""

    path: str
    material1: str
    material2: str
    friction: float | None
    friction_model: str
    restitution: float | None
    tangential_restitution: float | None
    enabled: bool


@dataclass(frozen=True)
class ConnectorState:
    """A mate connector's world frame now: its origin, its orientation (w, x, y, z) and rotation
    matrix (its columns the frame's axes: x the normal, z the main axis), and those two axes."""

    path: str
    body: str | None  # the rigid body it moves with (None: fixed in the world)
    position: tuple[float, float, float]
    quaternion: tuple[float, float, float, float]
    rotation: tuple[tuple[float, float, float], ...]  # 3x3, rows
    main_axis: tuple[float, float, float]
    normal: tuple[float, float, float]


def geometries(scene: Any, body_path: str) -> tuple[GeometryInfo, ...]:
    b = scene.body(body_path)
    if b is None:
        return ()
    return tuple(GeometryInfo(g.path, g.kind, MaterialInfo(g.material, float(g.density)),
                              bool(g.enable_collisions and not g.visual_only),
                              bool(g.include_in_mass and not g.visual_only), bool(g.visual_only)) for g in b.geoms)


def contact_model(scene: Any, material1: str, material2: str) -> ContactModelInfo | None:
    """The contact model of the unordered pair (the last one given, as the simulation uses), or None."""
    got = None
    for c in scene.contact_models:
        if {c.material1, c.material2} == {material1, material2}:
            got = c
    if got is None:
        return None
    return ContactModelInfo(got.path, got.material1, got.material2, got.friction, got.friction_model,
                            got.restitution, got.tangential_restitution, bool(got.enabled))


def connector_state(data: Any, path: str, placed: tuple, body: str | None) -> ConnectorState:
    """``placed`` is ``connector_signals._placed``'s (body id, rotation and origin in that body)."""
    from plxtools.check.connector_signals import _world

    r, p = _world(data, placed)
    t3 = lambda a: tuple(float(x) for x in a)  # noqa: E731
    return ConnectorState(path, body, t3(p), _quat(r), tuple(t3(row) for row in r), t3(r[:, 2]), t3(r[:, 0]))


def _quat(r: np.ndarray) -> tuple[float, float, float, float]:
    """(w, x, y, z) of a rotation matrix (Shepperd's method)."""
    t = float(np.trace(r))
    if t > 0:
        s = 2.0 * (t + 1.0) ** 0.5
        q = (0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s)
    else:
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * (1.0 + r[i, i] - r[j, j] - r[k, k]) ** 0.5
        v = [0.0, 0.0, 0.0]
        v[i] = 0.25 * s
        v[j] = (r[j, i] + r[i, j]) / s
        v[k] = (r[k, i] + r[i, k]) / s
        q = ((r[k, j] - r[j, k]) / s, *v)
    w, x, y, z = q
    if w < 0:
        w, x, y, z = -w, -x, -y, -z
    return (float(w), float(x), float(y), float(z))
