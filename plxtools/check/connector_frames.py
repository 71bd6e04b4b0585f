"""Where a mate connector is, for the signals that read it (``Physics3D.Signals.MateConnector.*``).

The assembler only builds frames for the connectors that mates and controllers use; an output may
read any connector (one on a body that nothing is mated to, or ``relative_to`` another one), so its
frame is computed here from the same attributes the assembler reads (``position``, ``main_axis``,
``normal``; a ``RedirectedMateConnector`` moves with its ``redirected_parent``) and the placed
nodes of the assembly.  No MuJoCo here: the runtime (``check/connector_signals.py``) turns the
world frame at assembly into a frame fixed in the MuJoCo body the connector moves with.

The frame's axes follow the MateConnector's own definition: z is ``main_axis``, x is ``normal``
(its part orthogonal to ``main_axis``) and y = z x x.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from plxtools.check.frames import compose, orthogonal_unit
from plxtools.check.scene import default_normal

REDIRECTED = "Physics3D.Interactions.RedirectedMateConnector"


@dataclass(frozen=True, slots=True)
class ConnectorFrame:
    """A connector's world frame at assembly, and the rigid body it moves with (None: fixed in the world)."""

    path: str
    body: str | None
    rotation: tuple  # 3x3, rows, world
    position: tuple  # 3, world

    def pose(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array(self.rotation, dtype=float), np.array(self.position, dtype=float)


def _vec(ev: Any, obj: Any, attr: str, default: np.ndarray | None) -> np.ndarray | None:
    try:
        v = np.asarray(ev.get(obj, attr), dtype=float)
    except Exception:  # an unevaluable attribute: the check reports it where it is written
        return default
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        return default
    return v


def _local_frame(ev: Any, obj: Any) -> tuple[np.ndarray, np.ndarray] | None:
    """(R, p) of the connector in its owner's frame, or None when its axes are degenerate."""

    pos = _vec(ev, obj, "position", np.zeros(3))
    axis = _vec(ev, obj, "main_axis", np.array([0.0, 0.0, 1.0]))
    n = float(np.linalg.norm(axis))
    if n < 1e-9:
        return None
    z = axis / n
    normal = _vec(ev, obj, "normal", None)
    x = orthogonal_unit(normal, z) if normal is not None else None
    if x is None:
        x = np.array(default_normal(tuple(float(c) for c in z)))
    return np.column_stack([x, np.cross(z, x), z]), pos


def connector_frame(asm: Any, ev: Any, kinds: Any, obj: Any) -> ConnectorFrame | None:
    """The frame of connector ``obj`` (None when its axes are degenerate: the check reports that).
    A connector that belongs to no placed node (the ``World`` constant) is given in world coordinates."""
    local = _local_frame(ev, obj)
    if local is None:
        return None
    owner = asm.owner_node(obj)
    world = compose(owner.world, local) if owner is not None and owner.world is not None else local
    mover = owner
    if kinds.isa(obj, REDIRECTED):
        try:
            parent = ev.get(obj, "redirected_parent")
        except Exception:
            parent = None
        node = asm.node_of(parent) if parent is not None and not isinstance(parent, (str, float, int)) else None
        if node is not None:
            mover = node
    body = mover.path if mover is not None and mover.kind == "body" else None
    return ConnectorFrame(obj.display, body, tuple(tuple(float(c) for c in row) for row in world[0]),
                          tuple(float(c) for c in world[1]))
