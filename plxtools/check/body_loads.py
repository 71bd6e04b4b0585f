"""External forces and torques on rigid bodies, as signal inputs act on a MuJoCo run.

An input that carries a 3D force or torque (``Physics3D.Signals.Torque3DInput``, or any
``Physics.Signals.Input`` whose ``type:`` is ``InputOutputType.Force3D`` / ``Torque3D``) and whose
source is a dynamic rigid body pushes that body.  What the bundles say, and what follows from it:

* The bundles' 3D inputs that name a frame (``LinearVelocity3DInput``, ``AngularVelocity3DInput``)
  are "in the world coordinate system"; ``Torque3DInput`` names none, so its vector is taken in
  world coordinates like theirs.
* A force input names no point of application, so the force acts at the body's centre of mass
  (no torque from it); a torque is a free vector and has no point.
* An input holds its value until the next one (as every input here does), so the load is MuJoCo's
  ``xfrc_applied`` row of the body, which MuJoCo keeps between steps.  Several inputs on one body
  add up: each keeps its own latest value and the row holds their sum.

mujoco is never imported here: the bindings only touch ``data`` arrays.
"""

from __future__ import annotations

from typing import Any

from plxtools.check.bindings import Binding, Unbindable

LOAD_QUANTITIES = ("body_force", "body_torque")


def bind_load(rt: Any, info: Any) -> Any:
    """The Binding of a force or torque input (``rt`` is the SignalRuntime)."""
    src = info.source or ""
    bid = rt.body_id(src)
    sb = rt.compiled.scene.body(src)
    if sb is not None and not sb.is_dynamic:
        raise Unbindable(f"{src} is not dynamic (is_dynamic: false or kinematically controlled): its motion is "
                         f"prescribed, so a force or torque on it changes nothing")
    first = 0 if info.quantity == "body_force" else 3
    shared: dict[str, tuple[float, float, float]] = rt.loads.setdefault((bid, first), {})
    shared.setdefault(info.path, (0.0, 0.0, 0.0))

    def write(m: Any, d: Any, v: Any) -> None:
        shared[info.path] = tuple(v)
        d.xfrc_applied[bid, first:first + 3] = [sum(x[i] for x in shared.values()) for i in range(3)]

    def read(m: Any, d: Any) -> tuple[float, float, float]:
        return shared[info.path]

    return Binding(info, read=read, write=write)


def bind_mass(rt: Any, info: Any) -> Any:
    """``MassOutput`` of a body: the mass MuJoCo simulates it with (its ``inertia.mass``, or its
    geometry's).  A body whose motion is prescribed needs none in MuJoCo (no force moves it): its
    declared ``inertia.mass`` is given when it has one."""
    src = info.source or ""
    bid = rt.body_id(src)
    sb = rt.compiled.scene.body(src)
    declared = float(sb.mass) if sb is not None and not sb.is_dynamic and sb.mass > 0 else None
    return Binding(info, read=lambda m, d: declared if declared is not None else float(m.body_mass[bid]))
