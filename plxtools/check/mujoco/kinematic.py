"""Kinematic bodies and the one stepping path of every MuJoCo run.

A kinematic body (``is_dynamic: false`` with a velocity, or listed in the deprecated
``kinematically_controlled``) moves at its prescribed velocity whatever hits it, and what rests on
it moves with it by friction (a conveyor belt, a turntable, a lifting platform).  MuJoCo's mocap
bodies cannot do the second: contacts see a mocap body's pose but no velocity.  So a kinematic body
is a free body whose six degrees of freedom carry an armature ``KINEMATIC_INERTIA`` times what the
scene's dynamic bodies weigh (its reactions move it by about a millionth of what they move the
others), compensated for gravity, and excluded from contacts with the world, static bodies and
other kinematic bodies.  Before every step plx sets its pose and velocity to the prescribed ones,
so the contact solve sees the surface's velocity and friction drags what lies on it.

Every reader of a body's velocity (the trace, the report's top speed, scenario values, velocity
output signals, the Python API) reads MuJoCo's, which is the prescribed one (a velocity input
changes it from the next step on: :meth:`KinematicMover.set_velocity`).
:class:`Stepper` is the step that ``plx check``, ``plx test`` and ``plxtools.check.api.Simulation``
all take, so a kinematic body moves the same way in all three.  Its armature's kinetic energy is
not the scene's: :func:`kinematic_dofs` lists the degrees of freedom the energy monitor leaves out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from plxtools.check.mujoco.velocity_constraint import Lag, apply_offsets, tighten


KINEMATIC_INERTIA = 1e6  # armature per unit of what the dynamic bodies weigh (kg, kg m^2)


@dataclass(slots=True)
class KinematicMover:
    """A kinematic body moved at its prescribed velocity (world frame, about its origin)."""

    path: str
    body: int  # MuJoCo body id
    qadr: int  # its free joint's qpos address
    dadr: int  # and dof address
    p0: np.ndarray
    q0: np.ndarray
    v: np.ndarray
    w: np.ndarray
    t0: float = 0.0  # when p0, q0 were its pose (a new velocity starts from where it is)

    def pose(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        dt = t - self.t0
        angle = float(np.linalg.norm(self.w)) * dt
        if angle == 0.0:
            return self.p0 + self.v * dt, self.q0
        ax = self.w / np.linalg.norm(self.w)
        dq = np.array([math.cos(angle / 2), *(math.sin(angle / 2) * ax)])
        return self.p0 + self.v * dt, quat_mul(dq, self.q0)

    def place(self, data: Any, t: float) -> None:
        """Its pose at ``t`` and its velocity (a free joint's angular velocity is in the body frame)."""
        p, q = self.pose(t)
        data.qpos[self.qadr:self.qadr + 3] = p
        data.qpos[self.qadr + 3:self.qadr + 7] = q
        data.qvel[self.dadr:self.dadr + 3] = self.v
        data.qvel[self.dadr + 3:self.dadr + 6] = quat_to_mat(q).T @ self.w

    def set_velocity(self, t: float, v: Any = None, w: Any = None) -> None:
        """A new prescribed velocity from ``t`` on (a velocity input), continuing from its pose then."""
        self.p0, self.q0 = self.pose(t)
        self.t0 = t
        if v is not None:
            self.v = np.asarray(v, dtype=float)
        if w is not None:
            self.w = np.asarray(w, dtype=float)


def quat_to_mat(q: np.ndarray) -> np.ndarray:
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def add_kinematic_joint(ctx: Any, path: str, body: Any, mb: Any) -> None:
    """The free joint of a kinematic body (its armature is set once the masses are known)."""
    mb.add_freejoint(name=ctx.names.add("joint", path, body.source, ":kinematic"))
    mb.gravcomp = 1.0
    ctx.out.kinematic.append(path)


def exclude_kinematic_contacts(ctx: Any) -> None:
    """A kinematic body touches only dynamic bodies (as a static one): not the world, not static
    bodies, not other kinematic bodies."""
    still = [p for p, b in ctx.bodies.items() if not b.is_dynamic]
    kin = set(ctx.out.kinematic)
    for k in ctx.out.kinematic:
        kname = ctx.names.name("body", k)
        ctx.spec.add_exclude(bodyname1="world", bodyname2=kname)
        for other in still:
            if other != k and not (other in kin and other < k):
                ctx.spec.add_exclude(bodyname1=kname, bodyname2=ctx.names.name("body", other))


def set_kinematic_inertia(ctx: Any, model: Any) -> None:
    """Each kinematic body's armature: KINEMATIC_INERTIA times the dynamic bodies' masses and their
    inertias about it, so what it carries cannot slow it; and a mass where it has none (a free body
    needs one)."""
    for k in ctx.out.kinematic:
        bid = model.body(ctx.names.name("body", k)).id
        here = np.asarray(model.body_pos[bid], dtype=float)
        total = 0.0
        for p, b in ctx.bodies.items():
            if not b.is_dynamic or ctx.names.name("body", p) is None:
                continue
            d = model.body(ctx.names.name("body", p)).id
            m = float(model.body_mass[d])
            r = np.asarray(b.world_pos, dtype=float) - here
            total += m * (1.0 + float(r @ r)) + float(np.sum(model.body_inertia[d]))
        mb = ctx.mj_bodies[k]
        if float(model.body_mass[bid]) <= 1e-9:
            mb.explicitinertial = True
            mb.mass = 1e-3
            mb.inertia = [1e-6] * 3
            mb.ipos = [0.0, 0.0, 0.0]
            mb.iquat = [1.0, 0.0, 0.0, 0.0]
        for j in mb.joints:
            j.armature = KINEMATIC_INERTIA * max(total, 1e-3)
    if ctx.out.kinematic:
        # the armature is in MuJoCo's mean inertia (1.7e6 for a turntable under a 2 kg box), which
        # scales the solver's tolerance: at MuJoCo's 1e-8 Newton stopped early and a box on a turning
        # table rocked on its corners (|vz| 0.1 m/s) and slid off its radius; at 1e-10, |vz| 4e-5
        tighten(ctx.spec.option)


def kinematic_dofs(compiled: Any, model: Any) -> list[int]:
    """The degrees of freedom of the kinematic bodies' free joints."""
    out = []
    for path in compiled.kinematic:
        name = compiled.names.name("joint", path, ":kinematic")
        if name is not None:
            adr = int(model.jnt_dofadr[model.joint(name).id])
            out.extend(range(adr, adr + 6))
    return out


def quat_mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw])


def prescribed(compiled: Any, model: Any) -> dict[int, tuple[str, np.ndarray, np.ndarray]]:
    """MuJoCo body id -> (path, linear velocity of its origin, angular velocity), world frame, of
    every kinematic body that moves (kept on ``compiled``: it depends on nothing else)."""
    got = compiled.prescribed_cache
    if got is not None and got[0] is model:
        return got[1]
    out: dict[int, tuple[str, np.ndarray, np.ndarray]] = {}
    for path in compiled.kinematic:
        b = compiled.scene.body(path)
        name = compiled.names.name("body", path)
        if b is None or name is None:
            continue
        bid = int(model.body(name).id)
        if compiled.names.name("joint", path, ":kinematic") is None:
            continue
        out[bid] = (path, np.asarray(b.lin_vel, dtype=float), np.asarray(b.ang_vel, dtype=float))
    compiled.prescribed_cache = (model, out)
    return out


def kinematic_movers(compiled: Any, model: Any, data: Any) -> list[KinematicMover]:
    """A mover per kinematic body, starting from its pose in ``data`` (the initial keyframe)."""
    out = []
    for bid, (path, v, w) in prescribed(compiled, model).items():
        jid = model.joint(compiled.names.name("joint", path, ":kinematic")).id
        qa, da = int(model.jnt_qposadr[jid]), int(model.jnt_dofadr[jid])
        out.append(KinematicMover(path, bid, qa, da, data.qpos[qa:qa + 3].copy(), data.qpos[qa + 3:qa + 7].copy(),
                                  v.copy(), w.copy()))
    return out


def body_velocity(mujoco: Any, model: Any, data: Any, compiled: Any, bid: int,
                  out: np.ndarray | None = None) -> np.ndarray:
    """(angular, linear) velocity of body ``bid``'s centre of mass, world frame, as
    ``mj_objectVelocity`` gives it (a kinematic body's free joint carries its prescribed velocity,
    set before every step)."""
    res = np.zeros(6) if out is None else out
    mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_BODY, bid, res, 0)
    return res


class Stepper:
    """One MuJoCo step as every run takes it: kinematic bodies placed at the pose and velocity they
    have at the start of the step (and again at its end), then ``mj_step1``, the caller's hook (inputs written while positions and
    velocities are current), ``mj_step2`` (with RK4 a whole ``mj_step``: MuJoCo's split step
    integrates with Euler)."""

    def __init__(self, mujoco: Any, compiled: Any, model: Any, data: Any) -> None:
        self.mujoco, self.model, self.data = mujoco, model, data
        self.movers = kinematic_movers(compiled, model, data)
        apply_offsets(model, data, compiled.actuators)  # velocity constraints' constant efforts
        from plxtools.check.mujoco.shaft_parts import Engagements

        self.engagements = Engagements.of(compiled, model)  # automatic brakes' and clutches' ramps
        self.lag = Lag(model, compiled.actuators)  # rigid motors' softness, taken out per step (with offsets)
        self.lag.start(data)
        self.h = float(model.opt.timestep)
        self.rk4 = int(model.opt.integrator) == int(mujoco.mjtIntegrator.mjINT_RK4)

    def step(self, done: int, hook: Callable[[float, Any, Any], None] | None = None) -> None:
        """Advance from step ``done`` (time ``done * h``) to the next."""
        for mv in self.movers:
            mv.place(self.data, done * self.h)
        if self.engagements.ramps:
            self.engagements.advance(self.model, done * self.h)
        if hook is None:
            self.mujoco.mj_step(self.model, self.data)
        else:
            self.mujoco.mj_step1(self.model, self.data)
            hook(done * self.h, self.model, self.data)
            if self.rk4:  # mj_step2 integrates with Euler whatever the integrator: redo the step as RK4
                self.mujoco.mj_step(self.model, self.data)
            else:
                self.mujoco.mj_step2(self.model, self.data)
        for mv in self.movers:  # what its loads moved it by (a millionth) is not its motion
            mv.place(self.data, (done + 1) * self.h)
        self.lag.apply(self.data)  # for the next step
