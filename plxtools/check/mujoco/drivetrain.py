"""Drive trains on MuJoCo (a step of the MjSpec build, on a :class:`BuildContext`).

A **rigid train** is a connected set of shafts, ideal gears (``q_out = q_in / ratio``; which
connector is the input is not documented, plx takes ``connectors[0]``'s shaft, so ``ratio`` =
input speed / output speed [I]) and hinge actuators (``q_shaft = q_hinge`` in the hinge's
OpenPLX sign) that forms a tree and reaches at most one 3D hinge.  Its gears and hinge actuators
do no work and allow no slip, so the whole train has ONE degree of freedom, and plx simulates it
as one MuJoCo coordinate: the hinge's joint (or, with no hinge, the first shaft's own hinge joint),
whose ``armature`` takes every shaft's inertia times the square of its speed ratio.  A shaft of
the train has no body of its own: its angle and speed are its ratio times the joint's
(:class:`ShaftCoordinate`, read by the signals and the trace).

Why one coordinate and not a joint per shaft with equality couplings (the first mapping): MuJoCo's
implicit integrators treat a velocity servo's damping after the constraint solver, which
computed the couplings' forces for the explicit servo force; so the servo's own shaft lags while
the rest of the train follows the explicit force, and the train reached 61 % of its target speed
after one step (10 x the gain: 10 x the target).  One coordinate also makes the gears exact: no
coupling to spring back (A134) or to drift.  A train that is not rigid in this sense (a loop of
gears, two hinges, a hinge actuator on a loop-closing mate) keeps the coupled mapping: a joint per
shaft, a joint equality per gear / hinge actuator, nearly hard (impedance 0.9999) with a direct
reference (``solref = (-0.25 / h^2, -1 / h)``) that removes the whole speed error in one step and a
quarter of the angle error per step: solved with the motor's velocity constraint and the
contacts, a train driving two wheels is at its input speed after one step too (before, with a
time constant of two steps, 42 %).

A **1D velocity motor** with any effort range is a velocity constraint of its gain
(rigid with the default gain) on its shaft's coordinate (``mujoco.velocity_constraint``: a friction-loss
tendon against a reference turning at the target speed), solved together with contacts, limits and
the couplings, so the shaft is at its target speed after one step as with AGX's velocity
constraint (tests/check/test_drivetrain_one_step.py, also on a cart driven over the ground).  With
an inverted effort range it is a ``<velocity>`` servo (``gear`` = the shaft's speed ratio, so the
actuator's length, speed and force are the shaft's) of ``kv = min(gain, I / h)``, ``I`` the inertia
the shaft sees, which gets half way to a new target per step.  A **1D torque motor** is a
``<motor>`` whose control is its torque input (0 until a signal sets it).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from plxtools.check.mujoco import velocity_constraint
from plxtools.check.mujoco.context import BuildContext
from plxtools.check.mujoco.controllers import force_range, note_gain_clamped, note_on_loop_mate
from plxtools.check.mujoco.notes import INFO
from plxtools.check.mujoco.results import ActuatorInfo, ShaftCoordinate

SHAFT_BODY_MASS = 1e-6  # kg: a point (its inertia 1e-9 kg m^2 beside the armature), so the MJCF export reloads
COUPLING_ANGLE_RATE = 0.25  # a coupled train's equalities remove this share of their angle error per step
SERVO_GAIN_STEPS = 1.0  # a servo (an inverted effort range): kv = this x the inertia it drives / timestep

Edge = tuple[str, float]  # (other node, its coordinate per this node's coordinate)


def _links(ctx: BuildContext) -> dict[str, list[Edge]]:
    """The couplings as a graph over shaft and mate paths, in coordinates: a gear's output turns
    1 / ratio times as fast as its input; a hinge actuator's shaft turns with the hinge's
    MuJoCo joint times the hinge's sign."""
    links: dict[str, list[Edge]] = {}
    for c in ctx.scene.shaft_couplings:
        if c.kind == "gear":
            f = 1.0 / c.ratio
        else:
            f = float(ctx.out.joint_sign.get(c.b, 1))  # joint = sign x shaft (sign is +-1)
        links.setdefault(c.a, []).append((c.b, f))
        links.setdefault(c.b, []).append((c.a, 1.0 / f))
    return links


def _component(links: dict[str, list[Edge]], start: str) -> tuple[dict[str, float], int]:
    """Every node connected to ``start`` with its coordinate per ``start``'s, and the number of
    couplings among them (a tree has one fewer than nodes)."""
    seen, stack, edges = {start: 1.0}, [start], 0
    while stack:
        cur = stack.pop()
        for nxt, f in links.get(cur, []):
            edges += 1
            if nxt not in seen:
                seen[nxt] = seen[cur] * f
                stack.append(nxt)
    return seen, edges // 2


def plan_trains(ctx: BuildContext) -> dict[str, tuple[str | None, dict[str, float]]]:
    """For each shaft of a rigid train: (the hinge mate that carries its train, or None when the
    train's first shaft does, and every shaft of the train with its speed per carrier speed).
    Shafts of trains that are not rigid (a loop, two hinges, a hinge without a joint) are left out."""
    links = _links(ctx)
    shafts = {sh.path for sh in ctx.scene.shafts}
    plan: dict[str, tuple[str | None, dict[str, float]]] = {}
    for sh in ctx.scene.shafts:
        if sh.path in plan:
            continue
        nodes, edges = _component(links, sh.path)
        mates = [n for n in nodes if n not in shafts]
        if edges != len(nodes) - 1 or len(mates) > 1 or any(not ctx.out.joints.get(m) for m in mates):
            continue
        carrier = mates[0] if mates else sh.path
        base = nodes[carrier]
        members = {n: f / base for n, f in nodes.items() if n in shafts}  # shaft per carrier coordinate
        for n in members:
            plan[n] = (mates[0] if mates else None, members)
    return plan


def add_shafts(ctx: BuildContext) -> None:
    """A MuJoCo coordinate for every shaft: one per rigid train (the hinge's joint, or the first
    shaft's own joint, with the train's inertia as armature), one per shaft of any other train."""
    plan = plan_trains(ctx)
    done: set[str] = set()
    inertia = {s.path: float(s.inertia) for s in ctx.scene.shafts}
    objs = {s.path: s for s in ctx.scene.shafts}
    for sh in ctx.scene.shafts:
        if sh.path in done:
            continue
        mate, members = plan.get(sh.path, (None, {sh.path: 1.0}))
        done.update(members)
        armature = sum(inertia[p] * f * f for p, f in members.items())
        if mate is None:
            joint = _shaft_joint(ctx, sh, armature)
        else:
            joint = ctx.out.joints[mate][0]
            j = ctx.spec.joint(joint)
            j.armature = float(j.armature) + armature
        ctx.shaft_trains[joint] = (mate is None, [(objs[p], f) for p, f in members.items()])
        for p, f in members.items():
            ctx.out.shafts[p] = ShaftCoordinate(joint, f, rigid=sh.path in plan)
            ctx.names.sources.setdefault(p, objs[p].source)


def _shaft_joint(ctx: BuildContext, sh: Any, armature: float) -> str:
    """A body of its own with one hinge joint whose ``armature`` is the train's inertia (the
    body itself is a negligible point mass, with no geometry and no gravity effect on the joint)."""
    mj = ctx.mj
    name = ctx.names.add("body", sh.path, sh.source)
    body = ctx.spec.worldbody.add_body(name=name, pos=[0, 0, 0])
    body.mass = SHAFT_BODY_MASS
    body.inertia = [SHAFT_BODY_MASS * 1e-3] * 3
    body.explicitinertial = True
    body.ipos = [0.0, 0.0, 0.0]
    body.iquat = [1.0, 0.0, 0.0, 0.0]
    body.gravcomp = 1.0
    jn = ctx.names.add("joint", sh.path, sh.source)
    body.add_joint(name=jn, type=mj.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1], armature=armature)
    ctx.out.joints[sh.path] = [jn]
    ctx.out.joint_sign[sh.path] = 1
    return jn


def _absorbed(ctx: BuildContext, a: str, b: str) -> bool:
    """Both ends turn with one coordinate already (a rigid train): no coupling to add."""
    ca = ctx.out.shafts.get(a)
    if ca is None:
        return False
    cb = ctx.out.shafts.get(b)
    other = cb.joint if cb is not None else (ctx.out.joints.get(b) or [None])[0]
    return other == ca.joint


def add_couplings(ctx: BuildContext) -> None:
    mj = ctx.mj
    h = float(ctx.spec.option.timestep)
    for c in ctx.scene.shaft_couplings:
        if _absorbed(ctx, c.a, c.b):
            continue
        ja = ctx.out.joints.get(c.a)
        if c.kind == "gear":
            jb = ctx.out.joints.get(c.b)
            if not ja or not jb:
                continue
            first, second, coef = jb[0], ja[0], 1.0 / c.ratio  # q_out = q_in / ratio
        else:
            jm = ctx.out.joints.get(c.b)
            if not ja:
                continue
            if not jm:
                note_on_loop_mate(ctx, f"{c.path}: {c.b} closes a kinematic loop (an equality constraint); "
                                  "a hinge actuator on it is not simulated", c)
                continue
            first, second, coef = ja[0], jm[0], float(ctx.out.joint_sign.get(c.b, 1))
        e = ctx.spec.add_equality(name=ctx.names.add("equality", c.path, c.source), type=mj.mjtEq.mjEQ_JOINT)
        e.objtype = mj.mjtObj.mjOBJ_JOINT
        e.name1, e.name2 = first, second
        data = np.zeros(len(e.data))
        data[1] = coef
        e.data = data
        e.solref = [-COUPLING_ANGLE_RATE / (h * h), -1.0 / h]  # see the module docstring
        e.solimp = list(velocity_constraint.SOLIMP)


def add_shaft_motors(ctx: BuildContext, model: Any) -> None:
    for m in ctx.scene.shaft_motors:
        coord = ctx.out.shafts.get(m.shaft)
        if coord is None:
            continue
        ctx.names.add("controller", m.path, m.source)
        lo, hi = float(m.min_effort), float(m.max_effort)
        if m.kind == "velocity_motor":
            _velocity_motor(ctx, model, m, coord, lo, hi)
            continue
        name = ctx.names.add("actuator", m.path, m.source)
        act = ctx.spec.add_actuator(name=name, target=coord.joint, trntype=ctx.mj.mjtTrn.mjTRN_JOINT)
        act.gear = [coord.factor, 0, 0, 0, 0, 0]  # the actuator's length, speed and force are the shaft's
        act.ctrllimited = ctx.mj.mjtLimited.mjLIMITED_FALSE
        _effort_range(ctx, act, lo, hi)
        act.set_to_motor()
        ctrl = float(np.clip(m.effort, lo, hi)) if lo <= hi else float(m.effort)
        ctx.out.actuators.append(ActuatorInfo(m.path, name, m.kind, m.shaft, coord.joint, coord.factor, ctrl))


def _effort_range(ctx: BuildContext, act: Any, lo: float, hi: float) -> None:
    if lo <= hi:  # an inverted range is left unlimited (the static checks report it)
        force_range(ctx, act, lo, hi)


def _velocity_motor(ctx: BuildContext, model: Any, m: Any, coord: ShaftCoordinate, lo: float, hi: float) -> None:
    """A velocity constraint (mujoco.velocity_constraint) of the motor's gain when the effort range
    is a range (any, or none); otherwise a servo of gain ``min(gain, inertia / h)``."""
    h = float(ctx.spec.option.timestep)
    joint, ratio = coord.joint, coord.factor
    ieff = _joint_inertia(model, joint) / (ratio * ratio) if coord.rigid else chain_inertia(ctx, model, m.shaft)
    cap = SERVO_GAIN_STEPS * ieff / h
    g = float(np.linalg.norm(np.asarray(ctx.spec.option.gravity, dtype=float)))
    span = velocity_constraint.one_sided_span(ieff, m.target_speed, h, g)
    split = velocity_constraint.split_range(lo, hi, span)
    target = float(m.target_speed)
    d = velocity_constraint.impedance(m.gain, h, velocity_constraint.tendon_invweight(model, joint, ratio, ieff))
    if split is not None and d is not None:
        name, ref = velocity_constraint.add(ctx, m.path, m.source, joint, ratio, ieff, split[1], d, offset=split[0])
        ctx.out.actuators.append(ActuatorInfo(m.path, name, m.kind, m.shaft, joint, ratio, target,
                                              velocity_constraint.honoured_gain(m.gain, d), target,
                                              reference=ref, tendon=ctx.names.name("tendon", m.path),
                                              offset=split[0], span=span))
        return
    kv = min(float(m.gain), cap)
    if kv < m.gain:
        note_gain_clamped(ctx, INFO, f"{m.path}: the default gain {m.gain:g} is far too stiff for a MuJoCo servo; kv "
                          f"clamped to {kv:.4g} (= the inertia it drives through the drive train, {ieff:.4g}, / "
                          f"timestep {h:g}): its effort range [{lo:g}, {hi:g}] is inverted, so it cannot be "
                          "solved as a velocity constraint; integrated implicitly, half way to its target speed "
                          "per step", m)
    name = ctx.names.add("actuator", m.path, m.source)
    act = ctx.spec.add_actuator(name=name, target=joint, trntype=ctx.mj.mjtTrn.mjTRN_JOINT)
    act.gear = [ratio, 0, 0, 0, 0, 0]  # the actuator's length, speed and force are the shaft's
    act.ctrllimited = ctx.mj.mjtLimited.mjLIMITED_FALSE
    _effort_range(ctx, act, lo, hi)
    act.set_to_velocity(kv=kv)
    ctx.out.actuators.append(ActuatorInfo(m.path, name, m.kind, m.shaft, joint, ratio, target, kv, target))


def _joint_inertia(model: Any, joint: str) -> float:
    """A joint's effective inertia (``1 / dof_invweight0``: its armature and what hangs on it)."""
    jid = model.joint(joint).id
    return 1.0 / max(float(model.dof_invweight0[model.jnt_dofadr[jid]]), 1e-12)


def chain_inertia(ctx: BuildContext, model: Any, shaft: str) -> float:
    """The inertia a motor on ``shaft`` of a coupled train drives: every coordinate the gears and
    hinge actuators couple to it, each with its own effective inertia (which includes what hangs
    on a hinge) times the square of its speed ratio to the shaft."""
    links: dict[str, list[tuple[str, float]]] = {}
    for c in ctx.scene.shaft_couplings:
        f = 1.0 / c.ratio if c.kind == "gear" and c.ratio else 1.0  # b turns f times as fast as a
        links.setdefault(c.a, []).append((c.b, f))
        links.setdefault(c.b, []).append((c.a, 1.0 / f if f else 0.0))
    seen, stack, total = {shaft: 1.0}, [shaft], 0.0
    while stack:
        cur = stack.pop()
        for nxt, f in links.get(cur, []):
            if nxt not in seen:
                seen[nxt] = seen[cur] * f
                stack.append(nxt)
    for path, factor in seen.items():
        joints = ctx.out.joints.get(path)
        if not joints:
            continue
        total += factor * factor * _joint_inertia(model, joints[0])
    return total
