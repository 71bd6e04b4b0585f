"""Brakes, clutches and differentials on MuJoCo (a step of the MjSpec build, after the keyframe).

A **brake** or **clutch** is dry friction between two rotating things: it sticks (no slip) while
the torque needed to keep them together is at most its capacity, ``engagement x torque_capacity``,
and slips with exactly that torque beyond it.  That is MuJoCo's friction loss on a fixed tendon
whose length is the slip angle: for a clutch, or a brake between two shafts, the first shaft's
angle minus the second's; for a brake on one shaft, that shaft's angle (it brakes against the
ground).  The friction loss is the capacity, changed at run time by the engagement inputs; a nearly
hard, direct friction constraint (as a velocity motor's, ``mujoco.velocity_constraint``) removes
the whole slip speed in one step, so a held shaft stays held and the torque through the part is
the constraint's force, solved with everything else.  Engagement 0 is a friction loss of 0: MuJoCo
then adds no constraint at all (a released clutch transmits nothing).

A **differential** is the tendon equality ``q_left + q_right - 2 q_drive / ratio = const``: one
constraint, whose one force acts equally on both axle shafts (equal torques, the open
differential) and ``-2 / ratio`` times it on the drive shaft.  ``locked_up`` adds a second one,
``q_left - q_right = const``, switched by the lock-up input (``eq_active``; the constant is set to
the axles' angle difference when the lock engages, part_signals).

A shaft's angle is ``factor x`` its MuJoCo joint's plus an offset (``mujoco.drivetrain``), so each
tendon wraps the joints with the shafts' coefficients times their factors; shafts sharing one joint
(a rigid gear train) add up.

An automatic brake or clutch engages over ``engagement_duration`` (from released to fully engaged;
from part way, the rest of it at the same rate) and releases over ``disengagement_duration``: its
engagement is a ramp in time, set before every step of a run (:class:`Engagements`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from plxtools.rules import registry
from plxtools.check.mujoco import velocity_constraint
from plxtools.check.mujoco.context import BuildContext
from plxtools.check.mujoco.drivetrain import COUPLING_ANGLE_RATE
from plxtools.check.mujoco.notes import WARNING
from plxtools.check.mujoco.results import PartInfo

_EPS = 1e-12


def _joint_coefs(ctx: BuildContext, terms: list[tuple[str, float]]) -> tuple[dict[str, float], float] | None:
    """The tendon of ``sum c x shaft angle`` over its MuJoCo joints ({joint: coefficient}) and its
    value at the start; None when a shaft has no coordinate."""
    coefs: dict[str, float] = {}
    start = 0.0
    shafts = {s.path: s for s in ctx.scene.shafts}
    for path, c in terms:
        coord = ctx.out.shafts.get(path)
        if coord is None:
            return None
        coefs[coord.joint] = coefs.get(coord.joint, 0.0) + c * coord.factor
        start += c * (float(shafts[path].angle) - coord.offset)  # = c x factor x the joint's start
    return {j: c for j, c in coefs.items() if abs(c) > _EPS}, start


def _tendon(ctx: BuildContext, part: Any, coefs: dict[str, float], suffix: str = "") -> str:
    t = ctx.spec.add_tendon(name=ctx.names.add("tendon", part.path, part.source, suffix))
    for joint, c in coefs.items():
        t.wrap_joint(joint, float(c))
    return t.name


def add_shaft_parts(ctx: BuildContext) -> None:
    ctx_parts = ctx.scene.shaft_parts
    for part in ctx_parts:
        if part.kind == "differential":
            _differential(ctx, part)
        else:
            _friction(ctx, part)


def _unsimulated(ctx: BuildContext, part: Any, why: str) -> None:
    ctx.note(WARNING, registry.NOT_SIMULATED, f"{part.path}: {why}; it is not simulated", part)


def _friction(ctx: BuildContext, part: Any) -> None:
    terms = [(part.shafts[0], 1.0)] + ([(part.shafts[1], -1.0)] if len(part.shafts) > 1 else [])
    got = _joint_coefs(ctx, terms)
    if got is None:
        return _unsimulated(ctx, part, "a shaft it acts on is not simulated")
    coefs, _ = got
    if not coefs:
        return _unsimulated(ctx, part, f"the two shafts of this {part.kind} turn as one through rigid gears, so it "
                            "can never slip")
    h = float(ctx.spec.option.timestep)
    ctx.names.add("controller", part.path, part.source)
    name = _tendon(ctx, part, coefs)
    t = ctx.spec.tendon(name)
    t.frictionloss = float(part.engagement * part.capacity)
    t.solref_friction = [-0.0, -1.0 / h]  # direct: the whole slip speed in one step (velocity_constraint)
    d = velocity_constraint.MAX_IMPEDANCE
    t.solimp_friction = [d, d, 0.001, 0.5, 2.0]
    ctx.out.parts[part.path] = PartInfo(part.path, part.kind, name, float(part.capacity), float(part.engagement),
                                        automatic=part.automatic, engage_time=float(part.engage_time),
                                        release_time=float(part.release_time))


def _equality(ctx: BuildContext, part: Any, tendon: str, value: float, suffix: str) -> str:
    mj = ctx.mj
    h = float(ctx.spec.option.timestep)
    e = ctx.spec.add_equality(name=ctx.names.add("equality", part.path, part.source, suffix),
                              type=mj.mjtEq.mjEQ_TENDON)
    e.objtype = mj.mjtObj.mjOBJ_TENDON
    e.name1 = tendon
    data = np.zeros(len(e.data))
    data[0] = value  # one tendon: its length is held at data[0]
    e.data = data
    e.solref = [-COUPLING_ANGLE_RATE / (h * h), -1.0 / h]  # as a coupled drive train's gears (mujoco.drivetrain)
    e.solimp = list(velocity_constraint.SOLIMP)
    return e.name


def _differential(ctx: BuildContext, part: Any) -> None:
    drive, left, right = part.shafts
    got = _joint_coefs(ctx, [(left, 1.0), (right, 1.0), (drive, -2.0 / part.ratio)])
    lock = _joint_coefs(ctx, [(left, 1.0), (right, -1.0)])
    if got is None or lock is None:
        return _unsimulated(ctx, part, "a shaft it connects is not simulated")
    if not got[0]:
        return _unsimulated(ctx, part, "its shafts already turn as one through rigid gears")
    ctx.names.add("controller", part.path, part.source)
    eq = _equality(ctx, part, _tendon(ctx, part, got[0]), got[1], "")
    lock_eq = None
    if lock[0]:
        lock_eq = _equality(ctx, part, _tendon(ctx, part, lock[0], ":lock"), lock[1], ":lock")
        ctx.spec.equality(lock_eq).active = bool(part.locked)
    ctx.out.parts[part.path] = PartInfo(part.path, part.kind, None, equality=eq, lock=lock_eq, locked=part.locked)


@dataclass
class Engagements:
    """The engagement of every brake and clutch of one run, and the ramps of the automatic ones
    (set by their inputs, advanced by the stepper before each step, mujoco.kinematic.Stepper)."""

    parts: dict[str, PartInfo]
    tendons: dict[str, int]
    now: dict[str, float] = field(default_factory=dict)
    engaged: dict[str, bool] = field(default_factory=dict)  # an automatic part's commanded state
    ramps: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)  # t0, f0, target, rate

    @classmethod
    def of(cls, compiled: Any, model: Any) -> "Engagements":
        parts = {p.path: p for p in compiled.parts.values() if p.tendon is not None}
        e = cls(parts, {path: int(model.tendon(p.tendon).id) for path, p in parts.items()})
        e.now = {path: p.engagement for path, p in parts.items()}
        e.engaged = {path: p.engagement > 0 for path, p in parts.items()}
        return e

    def _put(self, model: Any, path: str, f: float) -> None:
        self.now[path] = f
        model.tendon_frictionloss[self.tendons[path]] = f * self.parts[path].capacity

    def set_fraction(self, model: Any, path: str, f: float) -> None:
        """A manual engagement: at once, ending any ramp."""
        self.ramps.pop(path, None)
        self.engaged[path] = f > 0
        self._put(model, path, f)

    def engage(self, model: Any, path: str, on: bool, t: float) -> bool:
        """An automatic part told to engage (``on``) or release at time ``t``; True when the change
        is immediate (a duration of 0), False when it ramps from the next step on."""
        p, target = self.parts[path], 1.0 if on else 0.0
        self.engaged[path] = bool(on)
        duration = p.engage_time if on else p.release_time
        if duration <= 0 or self.now[path] == target:
            self.ramps.pop(path, None)
            self._put(model, path, target)
            return True
        self.ramps[path] = (t, self.now[path], target, 1.0 / duration)
        return False

    def advance(self, model: Any, t: float) -> None:
        """Each ramping part's engagement at time ``t`` (the start of the next step)."""
        for path, (t0, f0, target, rate) in list(self.ramps.items()):
            step = rate * max(t - t0, 0.0)
            f = min(f0 + step, target) if target > f0 else max(f0 - step, target)
            self._put(model, path, f)
            if f == target:
                del self.ramps[path]
