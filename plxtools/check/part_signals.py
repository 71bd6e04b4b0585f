"""Signals of brakes, clutches and differentials (``check/mujoco/shaft_parts.py``) on a MuJoCo run.

* engagement (``FractionInput`` / ``FractionOutput``): the fraction of the torque capacity the
  part holds with; writing it sets the friction tendon's bound to fraction x capacity, from the
  step it is written at (see :func:`_remake`).  An engage input (``EngageInput``: true / false)
  of an automatic part ramps it to 1 or 0 over its engagement or disengagement duration
  (``mujoco.shaft_parts.Engagements``); engaged (``EngagedOutput``) is the state it was told (a
  manual part: engagement above 0).
* torque (``Torque1DOutput``): the torque the part passes from its first shaft to its second (a
  brake on one shaft: to the ground), the friction constraint's force of the last step, 0 when
  released or when nothing loads it.
* slip velocity (``RelativeVelocity1DOutput``): the first shaft's speed minus the second's (a brake
  on one shaft: the shaft's speed).
* a differential's lock (``BoolInput`` / ``BoolOutput``): its ``w_left = w_right`` equality is
  active.

mujoco is never imported here: the module is handed to the bindings.
"""

from __future__ import annotations

import math
from typing import Any

from plxtools.check.bindings import Binding, SignalValueError, Unbindable

PART_QUANTITIES = ("engagement", "engaged", "part_torque", "slip_velocity", "locked_up")


def bind_part(rt: Any, info: Any) -> Any:
    part = rt.compiled.parts.get(info.source or "")
    if part is None:
        raise Unbindable(f"{info.source} is not simulated (see the check notes)")
    model, q, b = rt.compiled.model, info.quantity, Binding(info)
    if q == "locked_up":
        if part.lock is None:
            raise Unbindable(f"{part.path}: its axle shafts already turn as one")
        eid = int(model.equality(part.lock).id)
        b.read = lambda m, d: bool(d.eq_active[eid])

        lock_tendon = int(model.eq_obj1id[eid])

        def write_lock(m, d, v):
            if v and not d.eq_active[eid]:  # lock the axles where they are now, not where they started
                m.eq_data[eid, 0] = float(d.ten_length[lock_tendon])
            d.eq_active[eid] = 1 if v else 0
            _remake(rt.mujoco, m, d)

        b.write = write_lock
        return b
    tid = int(model.tendon(part.tendon).id)
    friction = int(rt.mujoco.mjtConstraint.mjCNSTR_FRICTION_TENDON)
    if q in ("engagement", "engaged"):
        if q == "engagement":
            b.read = lambda m, d: rt.engagements.now[part.path]
        else:
            b.read = lambda m, d: rt.engagements.engaged[part.path]

        def refuse(v):
            if q == "engagement" and v < 0:
                return f"{info.path}: an engagement fraction is at least 0, not {v:g}"
            return None

        def write_engagement(m, d, v):
            why = refuse(v)
            if why is not None:
                raise SignalValueError(why)
            if q == "engaged":
                if not rt.engagements.engage(m, part.path, bool(v), float(d.time)):
                    return  # a ramp, from the next step on
            else:
                rt.engagements.set_fraction(m, part.path, float(v))
            _remake(rt.mujoco, m, d)

        b.read, b.write, b.refuse = b.read, write_engagement, refuse
        return b
    if q == "slip_velocity":
        adr, num = int(model.tendon_adr[tid]), int(model.tendon_num[tid])
        wraps = [(int(model.jnt_dofadr[model.wrap_objid[w]]), float(model.wrap_prm[w])) for w in range(adr, adr + num)]
        b.read = lambda m, d: math.fsum(c * float(d.qvel[dof]) for dof, c in wraps)
        return b

    def read_torque(m, d):
        return next((-float(d.efc_force[i]) for i in _rows(d, friction, tid)), 0.0)

    b.read = read_torque
    return b


def _rows(d: Any, friction: int, tid: int) -> list[int]:
    """The constraint rows of the tendon's friction now (one, or none while released)."""
    return [i for i in range(int(d.nefc)) if int(d.efc_type[i]) == friction and int(d.efc_id[i]) == tid]


def _remake(mujoco: Any, m: Any, d: Any) -> None:
    """Make this step's constraints again after a write changed them.  Inputs are written between
    ``mj_step1`` and ``mj_step2`` (mujoco.kinematic.Stepper), and ``mj_step1`` has already made the
    constraint rows with the old bound (or none for a bound of 0) and the old active equalities:
    without this the write would act one step late (measured: a half-engaged brake held the whole
    first step)."""
    mujoco.mj_fwdPosition(m, d)
    mujoco.mj_fwdVelocity(m, d)
