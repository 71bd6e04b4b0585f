"""Kinematic bodies and the one stepping path of every MuJoCo run.

A kinematic body (``is_dynamic: false`` with a velocity, or listed in the deprecated
``kinematically_controlled``) is a MuJoCo mocap body: MuJoCo moves nothing itself, so plx places it
before every step at its prescribed pose.  MuJoCo gives a mocap body no velocity (it has no
degrees of freedom), so every reader of a body's velocity (the trace, the report's top speed,
scenario values, velocity output signals, the Python API) asks :func:`body_velocity`, which knows
the prescribed one.  :class:`Stepper` is the step that ``plx check``, ``plx test`` and
``plxtools.check.api.Simulation`` all take, so a kinematic body moves the same way in all three.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np


@dataclass(slots=True)
class KinematicMover:
    """A kinematic body moved at its constant prescribed velocity (world frame, about its origin)."""

    path: str
    body: int  # MuJoCo body id
    mocap: int
    p0: np.ndarray
    q0: np.ndarray
    v: np.ndarray
    w: np.ndarray

    def place(self, data: Any, t: float) -> None:
        data.mocap_pos[self.mocap] = self.p0 + self.v * t
        angle = float(np.linalg.norm(self.w)) * t
        if angle == 0.0:
            data.mocap_quat[self.mocap] = self.q0
            return
        ax = self.w / np.linalg.norm(self.w)
        dq = np.array([math.cos(angle / 2), *(math.sin(angle / 2) * ax)])
        data.mocap_quat[self.mocap] = quat_mul(dq, self.q0)


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
        if int(model.body_mocapid[bid]) < 0:
            continue
        out[bid] = (path, np.asarray(b.lin_vel, dtype=float), np.asarray(b.ang_vel, dtype=float))
    compiled.prescribed_cache = (model, out)
    return out


def kinematic_movers(compiled: Any, model: Any, data: Any) -> list[KinematicMover]:
    """A mover per kinematic body, starting from its pose in ``data`` (the initial keyframe)."""
    out = []
    for bid, (path, v, w) in prescribed(compiled, model).items():
        mid = int(model.body_mocapid[bid])
        out.append(KinematicMover(path, bid, mid, data.mocap_pos[mid].copy(), data.mocap_quat[mid].copy(), v, w))
    return out


def body_velocity(mujoco: Any, model: Any, data: Any, compiled: Any, bid: int,
                  out: np.ndarray | None = None) -> np.ndarray:
    """(angular, linear) velocity of body ``bid``'s centre of mass, world frame, as
    ``mj_objectVelocity`` gives it for a dynamic body, and the prescribed motion for a kinematic
    one (MuJoCo reports zero there)."""
    res = np.zeros(6) if out is None else out
    kin = prescribed(compiled, model).get(bid)
    if kin is None:
        mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_BODY, bid, res, 0)
        return res
    _, v, w = kin
    res[:3] = w
    res[3:] = v + np.cross(w, np.asarray(data.xipos[bid]) - np.asarray(data.xpos[bid]))
    return res


class Stepper:
    """One MuJoCo step as every run takes it: kinematic bodies placed at the pose they have at the
    end of the step, then ``mj_step1``, the caller's hook (inputs written while positions and
    velocities are current), ``mj_step2`` (with RK4 a whole ``mj_step``: MuJoCo's split step
    integrates with Euler)."""

    def __init__(self, mujoco: Any, compiled: Any, model: Any, data: Any) -> None:
        self.mujoco, self.model, self.data = mujoco, model, data
        self.movers = kinematic_movers(compiled, model, data)
        self.h = float(model.opt.timestep)
        self.rk4 = int(model.opt.integrator) == int(mujoco.mjtIntegrator.mjINT_RK4)

    def step(self, done: int, hook: Callable[[float, Any, Any], None] | None = None) -> None:
        """Advance from step ``done`` (time ``done * h``) to the next."""
        for mv in self.movers:
            mv.place(self.data, (done + 1) * self.h)
        if hook is None:
            self.mujoco.mj_step(self.model, self.data)
            return
        self.mujoco.mj_step1(self.model, self.data)
        hook(done * self.h, self.model, self.data)
        if self.rk4:  # mj_step2 integrates with Euler whatever the integrator: redo the step as RK4
            self.mujoco.mj_step(self.model, self.data)
        else:
            self.mujoco.mj_step2(self.model, self.data)
