"""Outputs of mate connectors (``Physics3D.Signals.MateConnector.*``) read from a MuJoCo run.

A connector is a frame fixed in the body it moves with (or in the world).  Its frame in that body
is taken from the MuJoCo model at its initial keyframe (the assembled pose), so a body that MuJoCo
places anywhere keeps the connector where the assembly put it.  Then, at any time:

* position: the body's pose times that frame's origin; RPY of the frame's rotation
  (``R = Rz(yaw) Ry(pitch) Rx(roll)``, as the body outputs);
* linear velocity of the frame's origin, ``v_com + w x r`` (``r`` from the centre of mass), and
  the body's angular velocity ``w``;
* acceleration of the origin, ``a_com + alpha x r + w x (w x r)``, and angular acceleration
  ``alpha``: ``a_com`` and ``alpha`` are MuJoCo's (``mj_objectAcceleration`` after
  ``mj_forward`` and ``mj_rnePostConstraint``: the acceleration the state has under the forces and
  inputs in force at that time), with gravity taken out (MuJoCo reports an accelerometer's proper
  acceleration; the output is the frame's acceleration).  A kinematic body moves at a constant
  prescribed velocity: its points only have the centripetal part.

``relative_to`` (default ``Physics3D.Interactions.World``): position and RPY are the source's pose in
that connector's frame.  A velocity or an acceleration relative to a connector fixed in the world
is the world value in that frame's axes; relative to a moving connector the bundles do not say
whether the frame's own motion counts, so such an output is not read (the reason is given).

mujoco is never imported here: the module is handed to the bindings.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from plxtools.check.bindings import Binding, Unbindable, rpy_of_mat
from plxtools.check.mujoco.kinematic import body_velocity
from plxtools.check.mujoco.kinematic import prescribed

CONNECTOR_QUANTITIES = ("connector_position", "connector_rpy", "connector_linear_velocity",
                        "connector_angular_velocity", "connector_acceleration", "connector_angular_acceleration")
_MOTION = CONNECTOR_QUANTITIES[2:]


def _placed(rt: Any, frame: Any) -> tuple[int | None, np.ndarray, np.ndarray]:
    """(MuJoCo body id or None for the world, rotation and origin of the frame in that body)."""
    r0, p0 = frame.pose()
    if frame.body is None:
        return None, r0, p0
    sb = rt.compiled.scene.body(frame.body)
    if sb is None:
        raise Unbindable(f"the body {frame.body} that {frame.path} moves with is not simulated")
    bid = rt.body_id(frame.body)
    d0 = rt.initial_data()
    rb = np.asarray(d0.xmat[bid]).reshape(3, 3)
    return bid, rb.T @ r0, rb.T @ (p0 - np.asarray(d0.xpos[bid]))


def _world(d: Any, placed: tuple) -> tuple[np.ndarray, np.ndarray]:
    bid, r, p = placed
    if bid is None:
        return r, p
    rb = np.asarray(d.xmat[bid]).reshape(3, 3)
    return rb @ r, np.asarray(d.xpos[bid]) + rb @ p


def _moves(rt: Any, placed: tuple, path: str) -> bool:
    """Whether a placed frame moves: on a dynamic body, or on a kinematic one with a velocity."""
    if placed[0] is None:
        return False
    b = rt.compiled.scene.body(path)
    return b is None or b.is_dynamic or b.kinematic


def _velocity(rt: Any, m: Any, d: Any, bid: int, point: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    res = body_velocity(rt.mujoco, m, d, rt.compiled, bid)
    w = res[:3].copy()
    return w, res[3:] + np.cross(w, point - np.asarray(d.xipos[bid]))


def _acceleration(rt: Any, m: Any, d: Any, bid: int, point: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    kin = prescribed(rt.compiled, m).get(bid)
    if kin is not None:  # constant prescribed velocity: no angular acceleration, only the centripetal part
        w = kin[2]
        return np.zeros(3), np.cross(w, np.cross(w, point - np.asarray(d.xpos[bid])))
    mj = rt.mujoco
    mj.mj_forward(m, d)
    mj.mj_rnePostConstraint(m, d)
    res = np.zeros(6)
    mj.mj_objectAcceleration(m, d, mj.mjtObj.mjOBJ_BODY, bid, res, 0)
    alpha, a_com = res[:3], res[3:] + np.asarray(m.opt.gravity)
    w, _ = _velocity(rt, m, d, bid, point)
    r = point - np.asarray(d.xipos[bid])
    return alpha, a_com + np.cross(alpha, r) + np.cross(w, np.cross(w, r))


def _t3(v: Any) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def bind_connector(rt: Any, info: Any) -> Any:
    """The Binding of a connector output (``rt`` is the SignalRuntime)."""
    q = info.quantity
    if info.frame is None:
        raise Unbindable(f"the frame of its connector {info.source} is undefined (see the check's findings)")
    src = _placed(rt, info.frame)
    rel = _placed(rt, info.relative) if info.relative is not None else (None, np.eye(3), np.zeros(3))
    if q in _MOTION and _moves(rt, rel, info.relative.body if info.relative is not None else ""):
        raise Unbindable(f"it is relative_to {info.relative.path}, which moves: the bundles do not say whether "
                         f"the motion of that frame counts in a relative velocity or acceleration (position and "
                         f"RPY relative to a moving connector are read)")

    def pose(m: Any, d: Any) -> tuple[np.ndarray, np.ndarray]:
        r, p = _world(d, src)
        rr, pr = _world(d, rel)
        return rr.T @ r, rr.T @ (p - pr)

    def motion(m: Any, d: Any) -> tuple[np.ndarray, np.ndarray]:
        """(angular, linear) of the source frame, world axes, or zeros when it is fixed in the world."""
        bid = src[0]
        if bid is None:
            return np.zeros(3), np.zeros(3)
        point = _world(d, src)[1]
        if q in ("connector_linear_velocity", "connector_angular_velocity"):
            return _velocity(rt, m, d, bid, point)
        return _acceleration(rt, m, d, bid, point)

    if q == "connector_position":
        return Binding(info, read=lambda m, d: _t3(pose(m, d)[1]))
    if q == "connector_rpy":
        return Binding(info, read=lambda m, d: rpy_of_mat(pose(m, d)[0].reshape(-1)))
    angular = q in ("connector_angular_velocity", "connector_angular_acceleration")

    def read_motion(m: Any, d: Any) -> tuple[float, float, float]:
        rr = _world(d, rel)[0]
        return _t3(rr.T @ motion(m, d)[0 if angular else 1])

    return Binding(info, read=read_motion)
