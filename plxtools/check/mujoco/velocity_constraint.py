"""A velocity motor as a velocity constraint that MuJoCo solves together with contacts.

AGX's velocity motor is a constraint: the solver finds the torque, within the effort range, that
makes the joint turn at the target speed at the end of the step, in the same solve as contacts,
limits and other joints.  A MuJoCo ``<velocity>`` servo is a force ``kv (target - v)``; the implicit
integrators treat its damping only after the constraint solver, which computed contact and limit
forces for the explicit force.  So a servo stiff enough to reach the target in one step makes a
driven cart jump off the ground, and a safe one gets half way per step.

MuJoCo has one velocity-level constraint with a force bound: friction loss, which drives a
velocity to zero with at most ``frictionloss`` of force.  Applied to a fixed tendon whose length is
the driven coordinate minus a **reference coordinate** turning at the target speed, it drives the
driven coordinate to the target speed, within the effort range, in the constraint solve itself:

* the reference is a hinge of a body of its own (no geometry, no gravity effect) whose armature is
  ``REFERENCE_INERTIA`` times the inertia the motor drives, so the constraint's reaction moves it by
  a millionth of the driven side's change;
* a ``<velocity>`` actuator on the reference with ``kv = armature / h`` holds the motor's target
  speed as its control, so every input that sets a motor's target sets it.  In the constraint
  solve the reference's predicted speed at the end of the step is exactly that control (an
  explicit step of ``kv (ctrl - v) / armature`` covers the whole difference), whatever the
  integrator then does to the reference itself;
* the tendon's friction loss is the effort limit (``[-e, e]`` around the range's middle, see
  below; ``BIG_EFFORT`` when unlimited), with a direct ``solreffriction`` whose damping removes the whole speed error in one
  step, and the impedance below.

A finite gain is honoured exactly.  MuJoCo's soft constraint pushes with ``(aref - a) / R``, where
``R = (1 - d) / d * w`` (``d`` the impedance, ``w`` the tendon's inverse inertia at the initial
pose, ``tendon_invweight0``); with the damping ``1 / h`` in ``aref`` that force is
``gain (target - v_next)``, an implicit servo's force law, exactly when
``d = g h w / (g h w + 1)`` (:func:`impedance`), and it is solved with the contacts instead of
after them.  A gain whose ``d`` is 0.999 or more (the default 1e8 on any ordinary body) is rigid:
MuJoCo's largest impedance, 0.9999.  (A servo of gain 100 on a light wheel on the ground made the
cart of examples/user_bundle hop, A134.)

The motor's effort is the constraint's force on the tendon: the reference's ``qfrc_constraint``
with its sign flipped (:func:`effort`), which the signals, the motor report and the energy monitor
read instead of an actuator force.  The reference's kinetic energy is not the scene's: the energy
monitor subtracts it (:func:`reference_energy`).

Any effort range is a friction bound around a constant effort: ``[lo, hi]`` is the offset
``(lo + hi) / 2`` plus ``[-(hi - lo) / 2, (hi - lo) / 2]`` (:func:`split_range`).  The offset is a
generalized force on the driven coordinate (``qfrc_applied``, set when a run starts and when a range
input changes it), and the motor's effort is the constraint's force plus it, so an asymmetric or
one-sided range (a lift that may only push up, [-50, 300] N) keeps the velocity constraint's
exactness instead of falling back to a servo that sags under load.

What softness is left at MuJoCo's largest impedance is a speed error in proportion to the
constraint's force: the solve reaches ``aref - R f`` (``R = (1 - d) / d w``), so a rigid motor turns
``h R f`` slower than its reference.  For ordinary loads that is a millionth, but an offset far from
the load (a wide one-sided or asymmetric range: [-1, 1e5] N m, its offset 5e4) makes ``f`` large and
the error 0.5 %.  :class:`Lag` takes it out: after each step it pushes each such motor's reference
with ``(armature R + 1) f`` (``R`` and ``f`` the friction row's of the step before; the first
step's from minus the offset), which moves the reference's predicted speed, and so the motor's, ahead by
``h R f`` and by what the constraint's reaction on the reference takes off it: measured, the error of
[-1, 1e6] N m on a 20 kg arm goes from 5 % to 1e-5.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from plxtools.check.mujoco.context import BuildContext

REFERENCE_INERTIA = 1e6  # reference armature per unit of the inertia the motor drives
BIG_EFFORT = 1e9  # the friction bound of an unlimited motor (N m or N)
MAX_IMPEDANCE = 0.9999  # MuJoCo's largest: a rigid motor (the default gain)
MIN_IMPEDANCE = 0.0001  # MuJoCo's smallest
RIGID_IMPEDANCE = 0.999  # a gain that leaves less than 0.1 % of a speed error per step is rigid
SOLIMP = [MAX_IMPEDANCE, MAX_IMPEDANCE, 0.001, 0.5, 2.0]  # nearly hard (also the coupled trains' equalities)
_POINT_MASS = 1e-6  # kg: the reference body (its inertia 1e-9 kg m^2 beside the armature)


def split_range(lo: float, hi: float, span: float = 1.0) -> tuple[float, float] | None:
    """(offset, bound): the effort range ``[lo, hi]`` as a constant effort ``offset`` plus a friction
    bound ``[-bound, bound]`` around it, the same set; None when it is inverted.  A one-sided range
    ``[lo, inf)`` is ``[lo, lo + 2 S]``, ``S = span + |lo|`` (:func:`one_sided_span`): the friction
    force is what the load needs minus the offset, and the constraint's softness leaves a speed
    error in proportion to it, so the offset must not be far from the loads (measured: a 50 kg lift
    at 0.5 m/s is 1e-4 off with S = 1.3e4 N, 5 % off with S = 6e6 N)."""
    if not lo <= hi:
        return None
    lo_f, hi_f = math.isfinite(lo), math.isfinite(hi)
    if not lo_f and not hi_f:
        return 0.0, BIG_EFFORT
    if lo_f and hi_f:
        c, b = 0.5 * (lo + hi), 0.5 * (hi - lo)
        if abs(c) <= 1e-12 * max(abs(lo), abs(hi), 1.0):
            c = 0.0
        return c, min(b, BIG_EFFORT)
    span = float(span) + abs(lo if lo_f else hi)
    return (lo + span, span) if lo_f else (hi - span, span)


def one_sided_span(inertia: float, target: float, h: float, gravity: float) -> float:
    """The half-width a one-sided range is given: what stops the driven inertia's target speed in
    one step and holds it against gravity (N or N m, at least 1)."""
    return max(float(inertia) * (abs(float(target)) / h + gravity), 1.0)


def offset_dofs(model: Any, actuators: list) -> tuple[np.ndarray, np.ndarray]:
    """(dof, generalized force) of every constraint motor's effort offset (for ``qfrc_applied``)."""
    dofs, forces = [], []
    for a in actuators:
        if a.reference is not None and a.offset != 0.0:
            dofs.append(int(model.jnt_dofadr[model.joint(a.joint).id]))
            forces.append(float(a.gear) * float(a.offset))
    return np.array(dofs, dtype=int), np.array(forces, dtype=float)


def apply_offsets(model: Any, data: Any, actuators: list) -> None:
    """Set the effort offsets of a fresh run (MuJoCo keeps ``qfrc_applied`` between steps)."""
    dofs, forces = offset_dofs(model, actuators)
    for dof, f in zip(dofs, forces):
        data.qfrc_applied[dof] += f


def impedance(gain: float, h: float, invweight: float) -> float | None:
    """The constraint impedance that makes a motor of ``gain`` push with exactly
    ``gain (target - v_next)``, as an implicit servo would, but solved with the contacts (see the
    module docstring); capped at MAX_IMPEDANCE (rigid).  None when the gain is so soft that MuJoCo's
    smallest impedance would be stiffer (then a servo, which is harmless that soft)."""
    x = float(gain) * h * invweight
    if not math.isfinite(x):
        return MAX_IMPEDANCE
    d = x / (x + 1.0)
    if d < MIN_IMPEDANCE:
        return None
    return d if d < RIGID_IMPEDANCE else MAX_IMPEDANCE


def honoured_gain(gain: float, d: float) -> float | None:
    """The gain a velocity constraint of impedance ``d`` follows, or None when it is rigid."""
    return None if d >= MAX_IMPEDANCE else float(gain)


def tendon_invweight(model: Any, joint: str, gear: float, inertia: float) -> float:
    """The tendon's inverse inertia at the initial pose, as MuJoCo computes it
    (``tendon_invweight0``): the joint's ``dof_invweight0`` times gear squared, plus the reference's."""
    dof = int(model.jnt_dofadr[model.joint(joint).id])
    return gear * gear * float(model.dof_invweight0[dof]) + 1.0 / reference_armature(inertia)


def reference_armature(inertia: float) -> float:
    return REFERENCE_INERTIA * max(float(inertia), 1e-9)


def add(ctx: BuildContext, path: str, source: Any, joint: str, gear: float, inertia: float, bound: float,
        d: float = MAX_IMPEDANCE, offset: float = 0.0) -> tuple[str, str]:
    """The reference, its actuator and the friction tendon for a motor at ``path`` on ``joint``
    (``gear`` = the motor's coordinate per joint coordinate; ``inertia`` = what the motor drives,
    in its own coordinate; ``d`` the impedance, from :func:`impedance`; ``offset`` its range's
    middle, see :func:`tighten`).  Returns (actuator name, reference joint name)."""
    mj, spec = ctx.mj, ctx.spec
    if offset:
        tighten(spec.option)
    h = float(spec.option.timestep)
    armature = reference_armature(inertia)
    body = spec.worldbody.add_body(name=ctx.names.add("body", path, source, ":reference"), pos=[0, 0, 0])
    body.mass = _POINT_MASS
    body.inertia = [_POINT_MASS * 1e-3] * 3
    body.explicitinertial = True
    body.ipos = [0.0, 0.0, 0.0]
    body.iquat = [1.0, 0.0, 0.0, 0.0]
    body.gravcomp = 1.0
    ref = ctx.names.add("joint", path, source, ":reference")
    body.add_joint(name=ref, type=mj.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1], armature=armature)
    tendon = spec.add_tendon(name=ctx.names.add("tendon", path, source))
    tendon.wrap_joint(joint, float(gear))
    tendon.wrap_joint(ref, -1.0)
    tendon.frictionloss = float(bound)
    # direct reference: MuJoCo divides the damping by the impedance, so -d / h gives b = 1 / h, the
    # servo law of a finite gain; a rigid motor keeps b = 1 / (d h), which settles without the
    # faint two-step ringing (1e-3 N m) that b = 1 / h leaves at the largest impedance
    tendon.solref_friction = [-0.0, -(d if d < MAX_IMPEDANCE else 1.0) / h]
    tendon.solimp_friction = [d, d, 0.001, 0.5, 2.0]
    name = ctx.names.add("actuator", path, source)
    act = spec.add_actuator(name=name, target=ref, trntype=mj.mjtTrn.mjTRN_JOINT)
    act.set_to_velocity(kv=armature / h)
    act.ctrllimited = mj.mjtLimited.mjLIMITED_FALSE
    return name, ref


class Lag:
    """The softness of the rigid motors with an effort offset taken out step by step (module
    docstring).  Motors without one (a symmetric range, none) are left as they were: their error is
    ``h R f`` of an ordinary load, about a millionth, and the scenes that have only such motors (the
    BoxTruck) step bit for bit as before.  ``offsets`` is the run's offsets now, by motor path (the
    signal runtime's, so a range input turns it on or off; ``SignalRuntime.attach_movers``)."""

    def __init__(self, model: Any, actuators: list) -> None:
        self.refs: dict[int, tuple[int, float, str, float]] = {}  # tendon id: ref dof, armature, path, offset
        for a in actuators:
            if a.reference is None or a.tendon is None:
                continue
            tid = int(model.tendon(a.tendon).id)
            if float(model.tendon_solimp_fri[tid][0]) < MAX_IMPEDANCE:
                continue  # a finite gain: its softness is the gain's force law, kept
            dof = reference_dof(model, a.reference)
            self.refs[tid] = (dof, float(model.dof_armature[dof]), a.path, float(a.offset))
        self.dofs = np.array([r[0] for r in self.refs.values()], dtype=int)
        self.offsets: dict[str, float] = {}
        self.model = model

    @property
    def active(self) -> bool:
        """Whether a motor has an offset now (a run without one steps as MuJoCo's own loop)."""
        return any(self.offsets.get(path, off) for _d, _a, path, off in self.refs.values())

    def start(self, data: Any) -> None:
        """The first step's push, before any solve: the friction force then is about minus the
        offset (the load unknown, and small beside an offset that matters), with MuJoCo's ``R``
        from the tendon's inverse inertia at the initial pose."""
        d = MAX_IMPEDANCE
        for tid, (dof, arm, _path, off) in self.refs.items():
            if off:
                r = (1.0 - d) / d * float(self.model.tendon_invweight0[tid])
                data.qfrc_applied[dof] = -(arm * r + 1.0) * off

    def apply(self, data: Any) -> None:
        """After a step, for the next: each reference with an offset pushed by ``(armature R + 1) f``
        of its motor's row in the solve just made (a step's own, not one ``mj_forward`` redid
        between steps, so a run read between its steps steps as one that is not).  At its effort
        limit too: the row's force is then the limit, and the push the shift that force needs."""
        if not self.refs:
            return
        data.qfrc_applied[self.dofs] = 0.0
        if not self.active:  # the BoxTruck's motors: nothing to look up, step after step
            return
        n = int(data.nefc)
        if not n:
            return
        rows = np.nonzero(data.efc_type[:n] == FRICTION_TENDON)[0]
        for row in rows:
            got = self.refs.get(int(data.efc_id[row]))
            if got is not None and self.offsets.get(got[2], got[3]):
                data.qfrc_applied[got[0]] = (got[1] * float(data.efc_R[row]) + 1.0) * float(data.efc_force[row])


OFFSET_TOLERANCE = 1e-10  # the solver's tolerance in a scene with an effort offset (tighten)
FRICTION_TENDON = 2  # mujoco.mjtConstraint.mjCNSTR_FRICTION_TENDON (this module imports no mujoco)


def refresh_bound(model: Any, data: Any, tid: int) -> None:
    """A tendon's new friction bound in the step under way too: the rows of a step are made in
    ``mj_step1``, before the inputs are written, and would keep the old bound for one step."""
    n = int(data.nefc)
    if not n:
        return
    bound = float(model.tendon_frictionloss[tid])
    rows = np.nonzero((data.efc_type[:n] == FRICTION_TENDON) & (data.efc_id[:n] == tid))[0]
    data.efc_frictionloss[rows] = bound
    # the solver reads the rows' copies sorted by island (made in mj_step1 too)
    rows = np.nonzero((data.iefc_type[:n] == FRICTION_TENDON) & (data.iefc_id[:n] == tid))[0]
    data.iefc_frictionloss[rows] = bound


def tighten(option: Any) -> None:
    """The solver's tolerance for a scene with an effort offset: the constraint then carries a
    force as large as the offset (5e5 N m for [-1, 1e6]), and at MuJoCo's default tolerance (1e-8 of
    the cost) Newton accepted a solve 7 N m off, a 0.7 % speed error for a step; at 1e-10 it is
    exact, one iteration a step (measured on a 20 kg arm, tests/physics/test_motor_wide_range.py).
    Scenes without one keep MuJoCo's default."""
    option.tolerance = min(float(option.tolerance), OFFSET_TOLERANCE)


def anticipate(model: Any, data: Any, tid: int, ref_dof: int, change: float, new_offset: float) -> None:
    """A rigid motor whose offset changed by ``change`` in the step under way: its friction force
    changes by minus that (the load stays), so :class:`Lag`'s push is moved now, not a step late."""
    if not change:
        return
    tighten(model.opt)
    if float(model.tendon_solimp_fri[tid][0]) < MAX_IMPEDANCE or not new_offset:
        return
    n = int(data.nefc)
    rows = np.nonzero((data.efc_type[:n] == FRICTION_TENDON) & (data.efc_id[:n] == tid))[0]
    for row in rows:
        data.qfrc_applied[ref_dof] -= (float(model.dof_armature[ref_dof]) * float(data.efc_R[row]) + 1.0) * change


def reference_dof(model: Any, ref_joint: str) -> int:
    return int(model.jnt_dofadr[model.joint(ref_joint).id])


def effort(data: Any, ref_dof: int, offset: float = 0.0) -> float:
    """The motor's effort now: the constraint's force on its tendon (the reference takes minus it)
    plus its constant offset."""
    return -float(data.qfrc_constraint[ref_dof]) + offset


def reference_energy(model: Any, qvel: np.ndarray, ref_dofs: np.ndarray) -> np.ndarray | float:
    """Kinetic energy of the references (to take out of MuJoCo's total); ``qvel`` one row or many."""
    if not len(ref_dofs):
        return 0.0
    arm = np.asarray(model.dof_armature)[ref_dofs]
    v = np.asarray(qvel)[..., ref_dofs]
    return 0.5 * (v * v * arm).sum(axis=-1)


def bound_of(model: Any, tendon_name: str) -> float:
    return float(model.tendon_frictionloss[model.tendon(tendon_name).id])
