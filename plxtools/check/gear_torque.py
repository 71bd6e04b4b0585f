"""A gear's ``torque_output``: the torque an ideal gear passes to its output shaft.

A rigid drive train is one MuJoCo coordinate (``mujoco.drivetrain``): its gears are ratios in the
shafts' speeds, with no constraint and so no force to read.  The torque through a gear is what the
shafts on one side of it need that their own loads do not give: cut the train at the gear, and on
the side without the train's hinge (the rest of the world acts through the hinge), the power
balance ``sum I_s f_s^2 q'' = sum T_s f_s + tau f_cut`` over its shafts (``f_s`` a shaft's speed per
joint speed, ``T_s`` the torques of the motors, brakes, clutches and differentials on it) gives the
gear's torque on its shaft on that side; on the output side that is the output torque, on the input
side the output torque is ``ratio`` times the input shaft's torque into the gear, minus sign (an
ideal gear passes the power).  Positive: the gear drives its output shaft forward.  Measured: an
input torque of 3 N m through a 2.5:1 gear into a held output shaft reads 7.5 N m (the holding
motor's torque), and into a free 1 kg m^2 output shaft ``I_out a_out`` (tests/physics/test_gear_torque.py).
"""

from __future__ import annotations

import math
from typing import Any

from plxtools.check.bindings import Binding, Unbindable


def _side(scene: Any, start: str, gear: str) -> set[str]:
    """Every shaft or hinge reached from ``start`` over the couplings other than ``gear``, and over
    differentials (their shafts turn in one coordinate too when the train is rigid)."""
    links: dict[str, list[str]] = {}
    for c in scene.shaft_couplings:
        if c.path != gear:
            links.setdefault(c.a, []).append(c.b)
            links.setdefault(c.b, []).append(c.a)
    seen, stack = {start}, [start]
    while stack:
        for nxt in links.get(stack.pop(), []):
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return seen


def bind_gear_torque(rt: Any, info: Any) -> Binding:
    c, scene = rt.compiled, rt.compiled.scene
    gear = next((g for g in scene.shaft_couplings if g.kind == "gear" and g.path == info.source), None)
    if gear is None:
        raise Unbindable(f"the gear {info.source} is not simulated (see the check notes)")
    ca, cb = c.shafts.get(gear.a), c.shafts.get(gear.b)
    if ca is None or cb is None or not (ca.rigid and cb.rigid) or ca.joint != cb.joint:
        raise Unbindable(f"{gear.path} is a gear of a train that is not one coordinate (a loop, or two hinges)")
    shafts = {s.path: s for s in scene.shafts}
    out_side = _side(scene, gear.b, gear.path)
    on_output = all(n in shafts for n in out_side)  # no hinge: the world does not act through it
    side = out_side if on_output else _side(scene, gear.a, gear.path)
    if not all(n in shafts for n in side):
        raise Unbindable(f"{gear.path}: both sides of it reach a 3D hinge")
    for p in scene.shaft_parts:
        if p.kind == "differential" and any(s in side for s in p.shafts):
            raise Unbindable(f"{gear.path}: a differential ({p.path}) on the side its torque is read from")
    model = c.model
    dof = int(model.jnt_dofadr[model.joint(ca.joint).id])
    factor = {s: c.shafts[s].factor for s in side}
    inertia = math.fsum(float(shafts[s].inertia) * factor[s] ** 2 for s in side)
    torques = _torque_readers(rt, side, factor)
    cut = factor[gear.b] if on_output else factor[gear.a]
    ratio = float(gear.ratio)

    def read(m: Any, d: Any) -> float:
        loads = math.fsum(t(m, d) for t in torques)
        tau = (inertia * float(d.qacc[dof]) - loads) / cut  # the gear's torque on the side's shaft
        return tau if on_output else -ratio * tau

    b = Binding(info)
    b.read = read
    return b


def _torque_readers(rt: Any, side: set[str], factor: dict[str, float]) -> list:
    """Readers of each load's power per joint speed (``T_s f_s``) on the shafts of ``side``."""
    from plxtools.check.mujoco import velocity_constraint as vc

    c, model = rt.compiled, rt.compiled.model
    out = []
    for a in c.actuators:
        if a.mate not in side:
            continue
        f = factor[a.mate]
        if a.reference is not None:
            rdof, path, off = vc.reference_dof(model, a.reference), a.path, float(a.offset)
            out.append(lambda m, d, rdof=rdof, path=path, off=off, f=f: vc.effort(d, rdof, rt.offsets.get(path, off)) * f)
        else:
            aid = int(model.actuator(a.name).id)
            out.append(lambda m, d, aid=aid, f=f: float(d.actuator_force[aid]) * f)
    friction = int(rt.mujoco.mjtConstraint.mjCNSTR_FRICTION_TENDON)
    for p in c.scene.shaft_parts:
        part = c.parts.get(p.path)
        if part is None or part.tendon is None:
            continue
        tid = int(model.tendon(part.tendon).id)
        signs = [(1.0 if i == 0 else -1.0, s) for i, s in enumerate(p.shafts)]
        coeff = math.fsum(sg * factor[s] for sg, s in signs if s in side)
        if coeff:
            # the tendon is the first shaft's angle minus the second's: its force acts on them with +1, -1
            out.append(lambda m, d, tid=tid, coeff=coeff: coeff * _tendon_force(d, friction, tid))
    return out


def _tendon_force(d: Any, friction: int, tid: int) -> float:
    n = int(d.nefc)
    for i in range(n):
        if int(d.efc_type[i]) == friction and int(d.efc_id[i]) == tid:
            return float(d.efc_force[i])
    return 0.0
