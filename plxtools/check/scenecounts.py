"""What the assembled scene holds, by kind: the bodies, mates and drive-train parts a run simulates.

Real projects' tests assert on these after assembly ("the loaded scene has 12 bodies and 11 hinges"),
so the Python API (`Simulation.scene().counts()`) and scenario files (`of = "scene.mates.hinge"`)
read them from the assembled scene (check/scene.py), the same one the MuJoCo model is built from.
"""

from __future__ import annotations

from typing import Any

from plxtools.check.mapped_types import controller_name

# the lists of check.scene.Scene counted, by the name a scenario or the API uses
GROUPS = ("bodies", "mates", "controllers", "shafts", "shaft_couplings", "shaft_motors")
PREFIX = "scene."


def scene_paths(scene: Any) -> dict[str, list[str]]:
    """The dotted paths of each group's objects, in assembly order."""
    return {g: [x.path for x in getattr(scene, g, ())] for g in GROUPS}


def scene_counts(scene: Any) -> dict[str, int]:
    """`bodies`, `mates`, ... and per kind `mates.hinge`, `controllers.rotational_velocity_motor`, ..."""
    out: dict[str, int] = {}
    for g in GROUPS:
        items = list(getattr(scene, g, ()))
        out[g] = len(items)
        for x in items:
            kind = _counted_kind(x)
            if isinstance(kind, str) and kind:
                out[f"{g}.{kind}"] = out.get(f"{g}.{kind}", 0) + 1
    return out


def _counted_kind(x: Any) -> str | None:
    """The kind an item is counted under: a controller by its own name (a rotational and a linear
    velocity motor are ``rotational_velocity_motor`` and ``linear_velocity_motor``, as signals call
    them), anything else by its scene kind."""
    kind = getattr(x, "kind", None)
    dof = getattr(x, "dof", None)
    if isinstance(kind, str) and isinstance(dof, str):
        return controller_name(kind, dof) or kind
    return kind
