"""Controllers (motors, ranges, springs) and the initial keyframe (steps of the MjSpec build, on a :class:`BuildContext`).

Velocity motors: one with any effort range (an offset plus a friction bound) is a velocity
constraint of its gain (``mujoco.velocity_constraint``), solved with the contacts.  One with an
inverted range (an error, A024, when not suppressed) or a gain too soft for it is a servo,
``kv = min(gain, KV_STEPS * I_eff / timestep)`` with ``I_eff = 1 / dof_invweight0``;
``KV_STEPS`` is 10 for unlimited motors (a servo time constant of a tenth of a step: tight tracking)
and 1 when an effort limit is finite (MuJoCo drops the implicit damping of a saturated actuator, and
a stiffer servo then chatters bang-bang between the limits). 1000 was tried first: stable for the
BoxTruck, but light wheels driven through ground contact gained energy (a 0.15 m wheel at 3 rad/s
"drove" 158 m in 3 s instead of 1.35 m); 10 gives 1.38 m there and leaves the BoxTruck unchanged.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from plxtools.check.mapped_types import FREE_DOFS
from plxtools.check.mujoco import velocity_constraint
from plxtools.check.mujoco.context import BuildContext
from plxtools.check.mujoco.poses import quat_to_mat
from plxtools.check.mujoco.notes import ERROR, INFO, WARNING
from plxtools.check.mujoco.results import ActuatorInfo
from plxtools.check.scene import Controller, Mate
from plxtools.rules import registry

KV_STEPS = 10.0
KV_STEPS_LIMITED = 1.0
SPRING_OMEGA_H = 0.2  # spring stiffness cap: natural frequency * timestep <= 0.2
MIN_TIMESTEP = 1e-4  # s: the shortest step chosen for stiff springs (20 x shorter than the default)
BIG_FORCE = velocity_constraint.BIG_EFFORT  # N m or N: the bound of an unlimited effort, for servos and constraints


# -- controllers -----------------------------------------------------------------------------
def note_gain_clamped(ctx: BuildContext, severity: str, message: str, item: Any) -> None:
    """A111, for mate motors here and drive-train motors (mujoco.drivetrain): one home for the code."""
    ctx.note(severity, registry.VELOCITY_MOTOR_GAIN_CLAMPED, message, item)


def note_on_loop_mate(ctx: BuildContext, message: str, item: Any) -> None:
    """A124: a controller or hinge actuator on a mate that closes a loop (no joint to act on)."""
    ctx.note(WARNING, registry.CONTROLLER_ON_LOOP_MATE, message, item)


def add_controllers(ctx: BuildContext, model: Any) -> None:
    bound = bind_controllers(ctx, model)
    choose_timestep(ctx, bound)
    stopped = {joint for ctl, _m, joint, _s, _i in bound if ctl.kind == "range"}
    for ctl, mate, joint, sign, ieff in bound:
        if ctl.kind == "velocity_motor":
            add_velocity_motor(ctx, model, ctl, mate, joint, sign, ieff, joint in stopped)
        elif ctl.kind in ("torque_motor", "force_motor"):
            add_effort_motor(ctx, ctl, mate, joint, sign)
        elif ctl.kind == "range":
            add_range(ctx, ctl, joint, sign)
        elif ctl.kind == "spring":
            add_spring(ctx, ctl, joint, sign, ieff)
        else:
            ctx.invariant(registry.NOT_SIMULATED,
                f"{ctl.path}: controller kind {ctl.kind!r} unsupported; ignored",
                ctl,
            )


Binding = tuple[Controller, Mate, str, int, float]  # controller, its mate, joint, sign, effective inertia


def bind_controllers(ctx: BuildContext, model: Any) -> list[Binding]:
    """Each enabled controller with the MuJoCo joint it acts on (notes for those that act on none)."""
    mates: dict[tuple[str, str], Mate] = {}
    for m in ctx.scene.mates:
        if len(m.connectors) == 2:
            mates.setdefault((m.connectors[0].path, m.connectors[1].path), m)
    out: list[Binding] = []
    for ctl in ctx.scene.controllers:
        ctx.names.add("controller", ctl.path, ctl.source)
        if not ctl.enabled:
            ctx.disabled(f"{ctl.path} is disabled", ctl)
            continue
        if len(ctl.connectors) != 2:
            ctx.invariant(registry.CONNECTOR_COUNT, f"{ctl.path}: needs exactly 2 connectors", ctl)
            continue
        a, b = ctl.connectors[0].path, ctl.connectors[1].path
        mate, reversed_ = mates.get((a, b)), False
        if mate is None and (b, a) in mates:
            mate, reversed_ = mates[(b, a)], True
        if mate is None:
            ctx.invariant(registry.CONTROLLER_WITHOUT_MATE,
                f"{ctl.path}: no mate uses the connector pair ({a}, {b}); controller ignored",
                ctl,
            )
            continue
        joint = controller_joint(ctx, ctl, mate)
        if joint is None:
            continue
        sign = ctx.out.joint_sign[mate.path] * (-1 if reversed_ else 1)
        if reversed_:
            ctx.note(
                INFO,
                registry.CONTROLLER_REVERSED,
                f"{ctl.path} lists the connectors of {mate.path} in the opposite order: its coordinate is the negated mate coordinate",
                ctl,
            )
        jid = model.joint(joint).id
        ieff = 1.0 / max(float(model.dof_invweight0[model.jnt_dofadr[jid]]), 1e-12)
        out.append((ctl, mate, joint, sign, ieff))
    return out


def choose_timestep(ctx: BuildContext, bound: list[Binding]) -> None:
    """Shorten the time step (down to MIN_TIMESTEP) so that every spring runs with the stiffness
    the model gives it: joint stiffness is integrated explicitly and needs omega * h <= 0.2."""
    h = float(ctx.spec.option.timestep)
    need, stiffest = h, None
    for ctl, _mate, _joint, _sign, ieff in bound:
        if ctl.kind == "spring" and ctl.stiffness > 0 and math.isfinite(ctl.stiffness):
            hk = SPRING_OMEGA_H * math.sqrt(ieff / ctl.stiffness)
            if hk < need:
                need, stiffest = hk, ctl
    if stiffest is None:
        return
    new_h = max(need, MIN_TIMESTEP)
    new_h = h / math.ceil(h / new_h)  # a whole number of steps per default step keeps sampling exact
    ctx.spec.option.timestep = new_h
    ctx.note(INFO, registry.TIMESTEP_SHORTENED, f"time step shortened from {h:g} s to {new_h:.4g} s so that {stiffest.path} "
             f"(stiffness {stiffest.stiffness:g}) is simulated as stiff as the model says"
             + ("" if new_h <= need * (1 + 1e-9) else f"; the floor is {MIN_TIMESTEP:g} s"), stiffest)


def controller_joint(ctx: BuildContext, ctl: Controller, mate: Mate) -> str | None:
    if not mate.enabled:
        ctx.note(
            WARNING, registry.CONTROLLER_ON_DISABLED_MATE, f"{ctl.path}: its mate {mate.path} is disabled", ctl
        )
        return None
    joints = ctx.out.joints.get(mate.path)
    fits = FREE_DOFS.get(mate.kind, ())
    if ctl.dof not in fits:
        ctx.invariant(registry.CONTROLLER_DOF_MISMATCH,
            f"{ctl.path}: a {ctl.dof} controller cannot drive the {mate.kind} mate {mate.path}",
            ctl,
        )
        return None
    if not joints:
        note_on_loop_mate(ctx, f"{ctl.path}: {mate.path} closes a kinematic loop (equality constraint); controllers on "
                          "it are not supported", ctl)
        return None
    if mate.kind == "cylindrical":
        return joints[0] if ctl.dof == "rotational" else joints[1]
    return joints[0]


def effort_range(ctx: BuildContext, ctl: Controller, act: Any) -> None:
    lo, hi = float(ctl.min_effort), float(ctl.max_effort)
    if lo > hi:
        ctx.invariant(registry.INVERTED_LIMITS,
            f"{ctl.path}: min_effort {lo:g} > max_effort {hi:g}; effort left unlimited",
            ctl,
        )
        return
    force_range(ctx, act, lo, hi)


def force_range(ctx: BuildContext, act: Any, lo: float, hi: float) -> None:
    """An actuator's force range from an effort range ``lo <= hi`` (none when both are infinite)."""
    if math.isfinite(lo) or math.isfinite(hi):
        act.forcelimited = ctx.mj.mjtLimited.mjLIMITED_TRUE
        act.forcerange = [max(lo, -BIG_FORCE), min(hi, BIG_FORCE)]


def add_velocity_motor(ctx: BuildContext, model: Any, ctl: Controller, mate: Mate, joint: str, sign: int, ieff: float,
                       stopped: bool = False) -> None:
    h = float(ctx.spec.option.timestep)
    if ctl.gain <= 0:
        ctx.note(
            ERROR,
            registry.INVALID_CONTROLLER_PARAMETER,
            f"{ctl.path}: gain {ctl.gain:g} must be positive; motor ignored",
            ctl,
        )
        return
    limited = math.isfinite(ctl.min_effort) or math.isfinite(ctl.max_effort)
    steps = KV_STEPS_LIMITED if limited or stopped else KV_STEPS
    cap = steps * ieff / h
    g = float(np.linalg.norm(np.asarray(ctx.spec.option.gravity, dtype=float)))
    span = velocity_constraint.one_sided_span(ieff, ctl.target_speed, h, g)
    split = velocity_constraint.split_range(float(ctl.min_effort), float(ctl.max_effort), span)
    d = velocity_constraint.impedance(ctl.gain, h, velocity_constraint.tendon_invweight(model, joint, float(sign), ieff))
    if split is not None and d is not None:
        name, ref = velocity_constraint.add(ctx, ctl.path, ctl.source, joint, float(sign), ieff, split[1], d,
                                             offset=split[0])
        ctx.out.actuators.append(ActuatorInfo(ctl.path, name, ctl.kind, mate.path, joint, float(sign),
                                              float(ctl.target_speed), velocity_constraint.honoured_gain(ctl.gain, d),
                                              float(ctl.target_speed), reference=ref,
                                              tendon=ctx.names.name("tendon", ctl.path), offset=split[0], span=span))
        return
    kv = min(float(ctl.gain), cap)
    if kv < ctl.gain:
        why = (
            "its effort range is inverted (min above max), so it cannot run as a velocity constraint; "
            "as an effort-limited servo, a larger kv would chatter between the effort limits (MuJoCo ignores the "
            "implicit damping of a saturated actuator)"
            if limited
            else "a range on the same joint: the joint limit is solved from the servo's explicit force, and a larger "
            "kv would chatter against it (gaining energy, A134)"
            if stopped
            else "integrated implicitly, nearly rigid speed tracking"
        )
        user = "gain" in ctl.user_set
        note_gain_clamped(
            ctx,
            WARNING if user else INFO,
            f"{ctl.path}: {'your' if user else 'the default'} gain {ctl.gain:g} is far too stiff for MuJoCo; "
            f"kv clamped to {kv:.4g} "
            f"(= {steps:g} x effective inertia {ieff:.4g} / timestep {h:g}; {why})",
            ctl,
        )
    name = ctx.names.add("actuator", ctl.path, ctl.source)
    act = ctx.spec.add_actuator(name=name, target=joint, trntype=ctx.mj.mjtTrn.mjTRN_JOINT)
    act.set_to_velocity(kv=kv)
    act.gear = [float(sign), 0, 0, 0, 0, 0]
    act.ctrllimited = ctx.mj.mjtLimited.mjLIMITED_FALSE
    effort_range(ctx, ctl, act)
    ctx.out.actuators.append(
        ActuatorInfo(
            ctl.path,
            name,
            ctl.kind,
            mate.path,
            joint,
            float(sign),
            float(ctl.target_speed),
            kv,
            float(ctl.target_speed),
        )
    )


def add_effort_motor(ctx: BuildContext, ctl: Controller, mate: Mate, joint: str, sign: int) -> None:
    name = ctx.names.add("actuator", ctl.path, ctl.source)
    act = ctx.spec.add_actuator(name=name, target=joint, trntype=ctx.mj.mjtTrn.mjTRN_JOINT)
    act.set_to_motor()
    act.gear = [float(sign), 0, 0, 0, 0, 0]
    act.ctrllimited = ctx.mj.mjtLimited.mjLIMITED_FALSE
    effort_range(ctx, ctl, act)
    lo, hi = float(ctl.min_effort), float(ctl.max_effort)
    ctrl = float(ctl.effort) if lo > hi else float(np.clip(ctl.effort, lo, hi))
    ctx.out.actuators.append(ActuatorInfo(ctl.path, name, ctl.kind, mate.path, joint, float(sign), ctrl))


def add_range(ctx: BuildContext, ctl: Controller, joint: str, sign: int) -> None:
    if ctl.start is None or ctl.end is None:
        ctx.note(ERROR, registry.INVALID_CONTROLLER_PARAMETER, f"{ctl.path}: range needs start and end", ctl)
        return
    if ctl.start > ctl.end:
        ctx.invariant(registry.INVERTED_LIMITS,
            f"{ctl.path}: start {ctl.start:g} > end {ctl.end:g}; range ignored",
            ctl,
        )
        return
    lo, hi = sorted((sign * float(ctl.start), sign * float(ctl.end)))
    if joint in ctx.joint_limits:
        plo, phi = ctx.joint_limits[joint]
        lo, hi = max(lo, plo), min(hi, phi)
        ctx.note(INFO, registry.STACKED_CONTROLLERS, f"{ctl.path}: several ranges on one DOF are intersected", ctl)
    ctx.joint_limits[joint] = [lo, hi]
    j = ctx.spec.joint(joint)
    j.limited = ctx.mj.mjtLimited.mjLIMITED_TRUE
    j.range = [lo, hi]
    # OpenPLX ranges are rigid by default: MuJoCo's stiffest stable limit (a time constant of two
    # steps, critically damped) instead of its soft default (0.02 s), which let a weight falling
    # 0.5 m onto its stop overshoot by 2 cm
    h = float(ctx.spec.option.timestep)
    j.solref_limit = [2.0 * h, 1.0]
    j.solimp_limit = [0.95, 0.99, 0.001, 0.5, 2.0]
    if math.isfinite(ctl.max_effort) or (math.isfinite(ctl.min_effort) and ctl.min_effort != 0):
        ctx.note(
            INFO,
            registry.RANGE_EFFORT_IGNORED,
            f"{ctl.path}: range effort limits are not modelled (hard MuJoCo joint limit)",
            ctl,
        )


def add_spring(ctx: BuildContext, ctl: Controller, joint: str, sign: int, ieff: float) -> None:
    h = float(ctx.spec.option.timestep)
    if ctl.stiffness <= 0:
        ctx.note(
            ERROR,
            registry.INVALID_CONTROLLER_PARAMETER,
            f"{ctl.path}: stiffness {ctl.stiffness:g} must be positive; spring ignored",
            ctl,
        )
        return
    if ctl.damping < 0 or not math.isfinite(ctl.damping):
        ctx.note(
            ERROR,
            registry.INVALID_CONTROLLER_PARAMETER,
            f"{ctl.path}: damping ({ctl.damping_from or ctl.damping}) must be a finite number >= 0; spring ignored",
            ctl,
        )
        return
    cap = ieff * (SPRING_OMEGA_H / h) ** 2
    k = min(float(ctl.stiffness), cap)
    if k < ctl.stiffness:
        ctx.note(
            WARNING,
            registry.SPRING_STIFFNESS_CLAMPED,
            f"{ctl.path}: stiffness {ctl.stiffness:g} would be unstable even at the shortest time step {h:g} s; "
            f"simulated with {k:.4g} "
            f"(natural frequency x timestep <= {SPRING_OMEGA_H:g} for effective inertia {ieff:.4g})",
            ctl,
        )
    j = ctx.spec.joint(joint)
    n = ctx.spring_count.get(joint, 0)
    if n:
        ctx.note(
            INFO,
            registry.STACKED_CONTROLLERS,
            f"{ctl.path}: several springs on one DOF act as one: stiffness and damping summed, rest at the "
            f"stiffness-weighted mean of their rests (the same force and, up to a constant, the same energy)",
            ctl,
        )
    ctx.spring_count[joint] = n + 1
    stiffness = [float(v) for v in j.stiffness]  # [linear, polynomial terms...] in MuJoCo 4
    damping = [float(v) for v in j.damping]
    k_before = stiffness[0] if n else 0.0
    rest = sign * float(ctl.rest)
    if n and k_before + k > 0:  # k1 (q - r1) + k2 (q - r2) = (k1 + k2) (q - (k1 r1 + k2 r2) / (k1 + k2))
        rest = (k_before * float(j.springref) + k * rest) / (k_before + k)
    stiffness[0] = k_before + k
    damping[0] = damping[0] + float(ctl.damping)  # on top of the mate's viscous friction
    j.stiffness = stiffness
    j.damping = damping
    j.springref = rest


# -- initial state ---------------------------------------------------------------------------
def _joint_velocities(ctx: BuildContext, model: Any, path: str, body: Any, v: np.ndarray, w: np.ndarray,
                      qvel: np.ndarray) -> None:
    """A body attached by a mate starts with the part of its initial velocity (relative to its
    parent body's) that its joint can take: the rotation about a hinge axis, the translation along
    a slide, any rotation of a ball.  What is left over is an info (A120)."""
    mj = ctx.mj
    data = mj.MjData(model)
    mj.mj_kinematics(model, data)
    bid = model.body(ctx.names.name("body", path)).id
    parent_path = ctx.names.path("body", model.body(int(model.body_parentid[bid])).name)
    parent = ctx.bodies.get(parent_path) if parent_path else None
    pv = np.asarray(parent.lin_vel, dtype=float) if parent is not None and parent.is_dynamic else np.zeros(3)
    pw = np.asarray(parent.ang_vel, dtype=float) if parent is not None and parent.is_dynamic else np.zeros(3)
    x = np.array(data.xpos[bid])
    pid = int(model.body_parentid[bid])
    dv, dw = v - pv - np.cross(pw, x - np.array(data.xpos[pid])), w - pw  # relative to the parent's motion
    left_v, left_w = dv.copy(), dw.copy()
    for j in range(int(model.body_jntadr[bid]), int(model.body_jntadr[bid] + model.body_jntnum[bid])):
        adr, axis = int(model.jnt_dofadr[j]), np.array(data.xaxis[j])
        if model.jnt_type[j] == mj.mjtJoint.mjJNT_HINGE:
            qvel[adr] = float(dw @ axis)
            left_w = left_w - float(dw @ axis) * axis
            # turning about the hinge moves the body's origin too: that part of its velocity is taken
            left_v = left_v - np.cross(float(dw @ axis) * axis, x - np.array(data.xanchor[j]))
        elif model.jnt_type[j] == mj.mjtJoint.mjJNT_SLIDE:
            qvel[adr] = float(dv @ axis)
            left_v = left_v - float(dv @ axis) * axis
        elif model.jnt_type[j] == mj.mjtJoint.mjJNT_BALL:
            r = np.array(data.xmat[bid]).reshape(3, 3)
            qvel[adr:adr + 3] = r.T @ dw  # a ball joint's velocity is in the body frame
            left_v = left_v - np.cross(left_w, x - np.array(data.xanchor[j]))
            left_w = np.zeros(3)
    scale = max(float(np.linalg.norm(dv)), float(np.linalg.norm(dw)), 1e-12)
    if max(float(np.linalg.norm(left_v)), float(np.linalg.norm(left_w))) > 1e-6 * scale:
        ctx.note(INFO, registry.INITIAL_VELOCITY_IGNORED, f"{path}: the part of its initial velocity that its mate does not allow is ignored "
                 f"(it starts with the joint speed that the velocity gives; left out, beyond what that joint speed "
                 f"moves: linear {_fmt(left_v)} m/s, angular {_fmt(left_w)} rad/s)", body)


def _fmt(v: np.ndarray) -> str:
    return "(" + ", ".join(f"{x:.3g}" for x in v) + ")"


def _train_state(ctx: BuildContext, model: Any, joint: str, own: bool, members: list[tuple[Any, float]],
                 qpos: np.ndarray, qvel: np.ndarray) -> None:
    """A drive train's coordinate at the start, and each shaft's angle on it (mujoco.drivetrain).

    A train carried by its first shaft starts at that shaft's angle, turning at the speed that
    keeps the train's angular momentum (sum of I f v over sum of I f^2: the shafts' own speed when
    they agree); a train carried by a hinge starts with the hinge.  A shaft whose own initial
    speed is not the one its train starts with is an info (A120)."""
    jid = model.joint(joint).id
    qa, da = int(model.jnt_qposadr[jid]), int(model.jnt_dofadr[jid])
    if own:
        qpos[qa] = float(members[0][0].angle)
        weight = sum(float(s.inertia) * f * f for s, f in members)
        qvel[da] = sum(float(s.inertia) * f * float(s.velocity) for s, f in members) / weight
    q0, v0 = float(qpos[qa]), float(qvel[da])
    for s, f in members:
        ctx.out.shafts[s.path].offset = float(s.angle) - f * q0
        v = float(s.velocity)
        if abs(v - f * v0) > 1e-9 * max(abs(v), abs(f * v0), 1.0):
            ctx.note(INFO, registry.INITIAL_VELOCITY_IGNORED, f"{s.path}: its initial velocity {v:g} rad/s is not the {f * v0:.4g} rad/s "
                     "its drive train starts with (the gears and hinge actuators let the train turn only as one; "
                     "it starts at the train's speed)", s)


def add_keyframe(ctx: BuildContext, model: Any) -> None:
    qvel = np.zeros(model.nv)
    roots = set(ctx.out.free_roots)
    for path, body in ctx.bodies.items():
        kinematic = ctx.names.name("joint", path, ":kinematic")
        if not body.is_dynamic and kinematic is None:
            continue
        v, w = np.asarray(body.lin_vel, dtype=float), np.asarray(body.ang_vel, dtype=float)
        if kinematic is not None or path in roots:
            jid = model.joint(kinematic or ctx.names.name("joint", path, ":free")).id
            adr = model.jnt_dofadr[jid]
            r = quat_to_mat(body.world_quat)
            qvel[adr : adr + 3] = v
            qvel[adr + 3 : adr + 6] = r.T @ w  # free-joint angular velocity is in the body frame
        elif np.any(v != 0) or np.any(w != 0):
            _joint_velocities(ctx, model, path, body, v, w, qvel)
    qpos = np.array(model.qpos0)
    for jn, (own, members) in ctx.shaft_trains.items():
        _train_state(ctx, model, jn, own, members, qpos, qvel)
    ctrl = [a.ctrl for a in ctx.out.actuators]  # actuators compile in the order they were added
    ctx.spec.add_key(name="initial", qpos=list(qpos), qvel=list(qvel), ctrl=ctrl)
