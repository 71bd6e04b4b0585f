"""What the assembled scene holds, by kind: the bodies, mates and drive-train parts a run simulates.

Real projects' tests assert on these after assembly ("the loaded scene has 12 bodies and 11 hinges"),
so the Python API (`Simulation.scene().counts()`) and scenario files (`of = "scene.mates.hinge"`)
read them from the assembled scene (check/scene.py), the same one the MuJoCo model is built from.
"""

from __future__ import annotations

from typing import Any

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
            kind = getattr(x, "kind", None)
            if isinstance(kind, str) and kind:
                out[f"{g}.{kind}"] = out.get(f"{g}.{kind}", 0) + 1
    return out
