"""Drive trains in the scene: the Physics1D shafts, DriveTrain gears, hinge actuators and the 1D
motors that the MuJoCo backend maps (``mj_drivetrain``).  Every other Physics1D / DriveTrain
object (engines, clutches, brakes, differentials, gear boxes, torque converters, linear bodies,
prismatic actuators) stays named as unsupported (A040) by the static checks.

Read here, once, from the instance tree; the static checks ask :func:`mapped` which objects this
module takes, so the two never disagree."""

from __future__ import annotations

import math
from typing import Any

from plxtools.check import scene as S
from plxtools.check.instance import Obj

SHAFT = "Physics1D.Bodies.RotationalBody"
GEAR = "DriveTrain.Gear"
HINGE_ACTUATOR = "DriveTrain.HingeActuator"
VELOCITY_MOTOR_1D = "Physics1D.Interactions.RotationalVelocityMotor"
TORQUE_MOTOR_1D = "DriveTrain.TorqueMotor"
MAPPED = (SHAFT, GEAR, HINGE_ACTUATOR, VELOCITY_MOTOR_1D, TORQUE_MOTOR_1D)


EXACT = frozenset({*MAPPED, "DriveTrain.Shaft"})


def mapped(kinds: Any, obj: Obj) -> bool:
    """True for the drive-train objects the MuJoCo backend simulates.  A user's model built on a
    mapped type is mapped; a bundle subtype that means more than its base (FlexibleGear,
    ViscousGear, GearBox) is not."""
    qn = kinds.p.concrete(obj.model).qname
    if qn in EXACT:
        return True
    if qn.split(".")[0] in ("DriveTrain", "Physics1D"):
        return False
    return any(kinds.isa(obj, t) for t in MAPPED)


def collect(asm: Any, col: Any, rep: Any, source: Any, mate_paths: set[str]) -> tuple[list, list, list]:
    """(shafts, couplings, motors) of the assembled tree, with A040 for drive-train objects this
    mapping cannot take (a gear on something that is not a shaft, a motor between two shafts)."""
    k, a = col.k, col.a
    shafts: dict[int, S.Shaft] = {}
    couplings: list[S.ShaftCoupling] = []
    motors: list[S.ShaftMotor] = []
    objs = [o for o in asm.owned if isinstance(o, Obj) and mapped(k, o)]
    for o in objs:
        if k.isa(o, SHAFT):
            inertia = a.real(o, "inertia.inertia", math.nan)
            if not math.isfinite(inertia) or inertia <= 0:
                rep.add("A040", f"{o.display}: a shaft needs a positive, finite inertia.inertia (got {inertia:g}); "
                        "it is not simulated", obj=o, severity="warning")
                continue
            shafts[id(o)] = S.Shaft(o.display, inertia, a.real(o, "kinematics.angle", 0.0),
                                    a.real(o, "kinematics.velocity", 0.0), source(rep, o))

    def shaft_of(conn: Any) -> S.Shaft | None:
        cur = conn.owner if isinstance(conn, Obj) else None
        while cur is not None:
            if id(cur) in shafts:
                return shafts[id(cur)]
            cur = cur.owner
        return None

    def unsupported(o: Obj, why: str) -> None:
        rep.add("A040", f"{o.display}: {why}; it is not simulated", obj=o, severity="warning")

    for o in objs:
        if k.isa(o, SHAFT) or not a.get(o, "enabled", True):
            continue
        conns = a.get(o, "connectors", []) if not k.isa(o, HINGE_ACTUATOR) else []
        conns = [c for c in conns if isinstance(c, Obj)] if isinstance(conns, (list, tuple)) else []
        if k.isa(o, GEAR):
            ends = [shaft_of(c) for c in conns]
            if len(ends) != 2 or None in ends or ends[0] is ends[1]:
                unsupported(o, "a gear needs two connectors on two different shafts")
                continue
            ratio = a.real(o, "ratio", 1.0)
            if not math.isfinite(ratio) or ratio == 0:
                unsupported(o, f"gear ratio {ratio:g} must be finite and not zero")
                continue
            couplings.append(S.ShaftCoupling(o.display, "gear", ends[0].path, ends[1].path, ratio, source(rep, o)))
        elif k.isa(o, HINGE_ACTUATOR):
            sh = shaft_of(a.get(o, "connector_1d", None))
            mate = a.get(o, "mate_3d", None)
            mate_path = mate.display if isinstance(mate, Obj) else None
            if sh is None or mate_path not in mate_paths:
                unsupported(o, "a hinge actuator needs connector_1d on a shaft and mate_3d bound to a hinge of the scene")
                continue
            couplings.append(S.ShaftCoupling(o.display, "actuator", sh.path, mate_path, 1.0, source(rep, o)))
        else:
            ends = [shaft_of(c) for c in conns]
            on = {id(e): e for e in ends if e is not None}
            if len(on) != 1:
                unsupported(o, "a 1D motor is mapped when its connectors are on exactly one shaft (it acts against "
                            "the ground)")
                continue
            sh = next(iter(on.values()))
            m = S.ShaftMotor(o.display, "velocity_motor" if k.isa(o, VELOCITY_MOTOR_1D) else "torque_motor", sh.path,
                             source=source(rep, o))
            m.min_effort = a.real(o, "min_effort", -math.inf)
            m.max_effort = a.real(o, "max_effort", math.inf)
            if m.kind == "velocity_motor":
                m.target_speed = a.real(o, "target_speed", 1.0)
            else:
                m.effort = a.real(o, "default_torque", 0.0)
            motors.append(m)
    return list(shafts.values()), couplings, motors
