"""Moving a loaded model's root, or any system or free body in it, to a new world pose before or
between steps, as an OpenPLX runtime places an imported model (``setPosition`` / ``setRotation``).

The object's current frame (a body's own; a system's as assembled, moved by every earlier
placement) is carried to the new pose by one rigid transform, applied to every body under the
object's path: a free body's joint position and orientation, its linear velocity turned with it
(its angular velocity is in its own frame and stays), and a kinematic body's prescribed path.  A
body under that path that hangs from something outside it (a mate to the world or to another
model) cannot be carried rigidly, so the placement is refused, naming it."""

from __future__ import annotations

from typing import Any

import numpy as np

from plxtools.check.api_errors import NotSimulatedError
from plxtools.check.mujoco.kinematic import quat_mul, quat_to_mat


def mat_to_quat(r: np.ndarray) -> np.ndarray:
    from plxtools.check.api_inspect import _quat

    return np.array(_quat(r))


def current_frame(sim: Any, path: str) -> tuple[np.ndarray, np.ndarray]:
    """(rotation, origin) of the object at ``path`` now (a body's MuJoCo frame; a system's tracked one)."""
    p = sim.prepared
    if path in sim.frames:
        return sim.frames[path]
    if path in p.bodies:
        name = p.compiled.names.name("body", path)
        bid = sim.model.body(name).id
        return np.asarray(sim.data.xmat[bid]).reshape(3, 3).copy(), np.asarray(sim.data.xpos[bid]).copy()
    asm = p.fc.assembly
    node = next((n for n in asm.nodes if n.path == path), None) if path else None
    if node is not None and node.world is not None:
        return np.asarray(node.world[0], dtype=float), np.asarray(node.world[1], dtype=float)
    return np.eye(3), np.zeros(3)  # the root model: the world frame


def place(sim: Any, path: str, position: Any = None, rotation: Any = None) -> None:
    """Move the object at ``path`` so that its frame is at ``position`` with orientation
    ``rotation`` (w, x, y, z); an omitted one keeps its current value."""
    r0, p0 = current_frame(sim, path)
    r1 = r0 if rotation is None else quat_to_mat(_unit_quat(rotation))
    p1 = p0 if position is None else _vec3(position, "position")
    rt = r1 @ r0.T
    pt = p1 - rt @ p0
    qt = mat_to_quat(rt)
    under = [b for b in sim.prepared.bodies if not path or b == path or b.startswith(path + ".")]
    kin = {mv.path: mv for mv in sim._stepper.movers}
    roots, still = _carried(sim, path, under, kin)
    m, d = sim.model, sim.data
    for bid in still:  # the model is this simulation's own: its static bodies move with it
        m.body_pos[bid] = rt @ m.body_pos[bid] + pt
        m.body_quat[bid] = quat_mul(qt, m.body_quat[bid])
    for root in sorted(roots):
        jid = int(m.body_jntadr[root])
        qa, da = int(m.jnt_qposadr[jid]), int(m.jnt_dofadr[jid])
        d.qpos[qa:qa + 3] = rt @ d.qpos[qa:qa + 3] + pt
        d.qpos[qa + 3:qa + 7] = quat_mul(qt, d.qpos[qa + 3:qa + 7])
        d.qvel[da:da + 3] = rt @ d.qvel[da:da + 3]
    for mv in (kin[b] for b in under if b in kin):
        now = sim.time
        pos, q = mv.pose(now)
        mv.p0, mv.q0, mv.t0 = rt @ pos + pt, quat_mul(qt, q), now
        mv.v, mv.w = rt @ mv.v, rt @ mv.w
        mv.place(d, now)
    sim.frames[path] = (r1, p1)
    for other in list(sim.frames):  # a system inside the moved one moved with it
        if other != path and (not path or other.startswith(path + ".")):
            ro, po = sim.frames[other]
            sim.frames[other] = (rt @ ro, rt @ po + pt)


def _carried(sim: Any, path: str, under: list[str], kin: dict) -> tuple[set[int], list[int]]:
    """(free root body ids, static body ids) that carry the bodies under ``path``; refused when
    one hangs from a body outside it."""
    p, m = sim.prepared, sim.model
    names = p.compiled.names
    roots: set[int] = set()
    still: list[int] = []
    for b in under:
        name = names.name("body", b)
        if name is None or b in kin:
            continue
        bid = int(m.body(name).id)
        if int(m.body_jntnum[bid]) == 0 and int(m.body_parentid[bid]) == 0:  # a static body: fixed in the world
            still.append(bid)
            continue
        root = int(m.body_rootid[bid])
        rpath = names.path("body", m.body(root).name)
        inside = not path or rpath == path or rpath.startswith(path + ".")
        if inside and int(m.body_jntnum[root]) == 0:  # hangs from a static body moved with it
            continue
        if rpath not in p.compiled.free_roots or not inside:
            raise NotSimulatedError(f"cannot move {path or 'the root model'}: {b} hangs from "
                                    f"{rpath or 'the world'}, outside it (a mate to the world or to another model)")
        roots.add(root)
    return roots, still


def _unit_quat(q: Any) -> np.ndarray:
    a = np.asarray(q, dtype=float)
    if a.shape != (4,) or not np.all(np.isfinite(a)) or np.linalg.norm(a) < 1e-12:
        raise ValueError(f"a rotation is a quaternion (w, x, y, z), not {q!r}")
    return a / np.linalg.norm(a)


def _vec3(v: Any, what: str) -> np.ndarray:
    a = np.asarray(v, dtype=float)
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise ValueError(f"a {what} is three finite numbers (x, y, z), not {v!r}")
    return a
