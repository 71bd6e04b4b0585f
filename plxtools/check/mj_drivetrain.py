"""Drive trains on MuJoCo (a step of the MjSpec build, on a :class:`BuildContext`).

* A **shaft** is a body of its own with one hinge joint whose ``armature`` is the shaft's
  inertia (the body itself is a negligible point mass, with no geometry and no gravity effect
  on the joint), so its rotation is a MuJoCo coordinate like any mate's.
* A **gear** is a joint equality ``q_out = q_in / ratio`` (an ideal gear: no slip, no
  flexibility, no loss: the constraint does no work), as stiff as MuJoCo allows (time constant
  of two steps).  Which connector is the input is not documented; plx takes ``connectors[0]``'s
  shaft as the input, so ``ratio`` = input speed / output speed [I].
* A **hinge actuator** is a joint equality ``q_shaft = q_hinge`` (in the hinge's OpenPLX sign).
* A **1D velocity motor** is a ``<velocity>`` actuator on its shaft's joint with
  ``kv = I_chain / h``, where ``I_chain`` is the inertia it drives through the gears and hinge
  actuators (each coupled coordinate's effective inertia times its speed ratio squared): integrated
  implicitly, the servo alone would reach its target in about one step; the soft couplings (time
  constant 2 steps) pass it on, so the driven hinge is within 10 % of its target speed after two
  steps and within 1 % after about 15 (measured on the 4:1 gear train of tests/physics).  A gain
  on the shaft's own inertia (the first version) took 0.1 s to 0.5 s under a heavy load; a servo
  ten times stiffer than I_chain / h yanks the chain, the couplings spring back and the run gains
  energy that no motor supplied (A134: 57 J in that gear train).  A **1D torque motor** a ``<motor>`` whose control is its torque input (0 until
  a signal sets it).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from plxtools.check.mj_context import BuildContext
from plxtools.check.mj_notes import INFO, WARNING
from plxtools.check.mj_types import ActuatorInfo

SHAFT_BODY_MASS = 1e-6  # kg: a point (its inertia 1e-9 kg m^2 beside the armature), so the MJCF export reloads
SERVO_GAIN_STEPS = 1.0  # 1D velocity motor: kv = this x the inertia it drives / timestep


def add_shafts(ctx: BuildContext) -> None:
    mj = ctx.mj
    for sh in ctx.scene.shafts:
        name = ctx.names.add("body", sh.path, sh.source)
        body = ctx.spec.worldbody.add_body(name=name, pos=[0, 0, 0])
        body.mass = SHAFT_BODY_MASS
        body.inertia = [SHAFT_BODY_MASS * 1e-3] * 3
        body.explicitinertial = True
        body.ipos = [0.0, 0.0, 0.0]
        body.iquat = [1.0, 0.0, 0.0, 0.0]
        body.gravcomp = 1.0
        jn = ctx.names.add("joint", sh.path, sh.source)
        body.add_joint(name=jn, type=mj.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1], armature=float(sh.inertia))
        ctx.out.joints[sh.path] = [jn]
        ctx.out.joint_sign[sh.path] = 1
        ctx.shaft_init[jn] = (float(sh.angle), float(sh.velocity))


def add_couplings(ctx: BuildContext) -> None:
    mj = ctx.mj
    h = float(ctx.spec.option.timestep)
    for c in ctx.scene.shaft_couplings:
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
                ctx.note(WARNING, "A124", f"{c.path}: {c.b} closes a kinematic loop (an equality constraint); "
                         "a hinge actuator on it is not simulated", c)
                continue
            first, second, coef = ja[0], jm[0], float(ctx.out.joint_sign.get(c.b, 1))
        e = ctx.spec.add_equality(name=ctx.names.add("equality", c.path, c.source), type=mj.mjtEq.mjEQ_JOINT)
        e.objtype = mj.mjtObj.mjOBJ_JOINT
        e.name1, e.name2 = first, second
        data = np.zeros(len(e.data))
        data[1] = coef
        e.data = data
        e.solref = [2.0 * h, 1.0]


def add_shaft_motors(ctx: BuildContext, model: Any) -> None:
    h = float(ctx.spec.option.timestep)
    for m in ctx.scene.shaft_motors:
        joints = ctx.out.joints.get(m.shaft)
        if not joints:
            continue
        joint = joints[0]
        ctx.names.add("controller", m.path, m.source)
        name = ctx.names.add("actuator", m.path, m.source)
        act = ctx.spec.add_actuator(name=name, target=joint, trntype=ctx.mj.mjtTrn.mjTRN_JOINT)
        act.gear = [1.0, 0, 0, 0, 0, 0]
        act.ctrllimited = ctx.mj.mjtLimited.mjLIMITED_FALSE
        lo, hi = float(m.min_effort), float(m.max_effort)
        limited = lo <= hi and (math.isfinite(lo) or math.isfinite(hi))
        if limited:
            act.forcelimited = ctx.mj.mjtLimited.mjLIMITED_TRUE
            act.forcerange = [max(lo, -1e9), min(hi, 1e9)]
        if m.kind == "velocity_motor":
            ieff = chain_inertia(ctx, model, m.shaft)
            kv = min(float(m.gain), SERVO_GAIN_STEPS * ieff / h)
            if kv < m.gain:
                ctx.note(INFO, "A111", f"{m.path}: the default gain {m.gain:g} is far too stiff for MuJoCo; kv "
                         f"clamped to {kv:.4g} (= {SERVO_GAIN_STEPS:g} x the inertia it drives through the drive "
                         f"train, {ieff:.4g}, / timestep {h:g}: integrated implicitly, the driven hinge is at its "
                         f"target speed within a few steps)", m)
            act.set_to_velocity(kv=kv)
            ctx.out.actuators.append(ActuatorInfo(m.path, name, m.kind, m.shaft, joint, 1.0, float(m.target_speed),
                                                  kv, float(m.target_speed)))
        else:
            act.set_to_motor()
            ctrl = float(np.clip(m.effort, lo, hi)) if lo <= hi else float(m.effort)
            ctx.out.actuators.append(ActuatorInfo(m.path, name, m.kind, m.shaft, joint, 1.0, ctrl))


def chain_inertia(ctx: BuildContext, model: Any, shaft: str) -> float:
    """The inertia a motor on ``shaft`` drives: every coordinate the gears and hinge actuators
    couple to it, each with its own effective inertia (``1 / dof_invweight0``, which includes
    what hangs on a hinge) times the square of its speed ratio to the shaft."""
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
        jid = model.joint(joints[0]).id
        inv = float(model.dof_invweight0[model.jnt_dofadr[jid]])
        total += factor * factor / max(inv, 1e-12)
    return total
