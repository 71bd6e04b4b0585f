"""Drive trains in the scene: the Physics1D shafts, DriveTrain gears, hinge actuators, 1D motors,
brakes, clutches and differentials that the MuJoCo backend maps (``mujoco.drivetrain``,
``mujoco.shaft_parts``).  Every other Physics1D / DriveTrain object (engines, gear boxes, torque
converters, limited-slip differentials, linear bodies, prismatic actuators) stays named as
unsupported (A040) by the static checks.

Read here, once, from the instance tree; the static checks ask :func:`mapped` which objects this
module takes, so the two never disagree."""

from __future__ import annotations

import math
from typing import Any

from plxtools.check import scene as S
from plxtools.check.coverage import not_simulated
from plxtools.check.instance import Obj

SHAFT = "Physics1D.Bodies.RotationalBody"
GEAR = "DriveTrain.Gear"
HINGE_ACTUATOR = "DriveTrain.HingeActuator"
VELOCITY_MOTOR_1D = "Physics1D.Interactions.RotationalVelocityMotor"
TORQUE_MOTOR_1D = "DriveTrain.TorqueMotor"
BRAKE = "DriveTrain.ManualBrake"
CLUTCH = "DriveTrain.ManualClutch"
AUTOMATIC = ("DriveTrain.AutomaticBrake", "DriveTrain.AutomaticClutch")  # engaged by a boolean, not a fraction
DIFFERENTIAL = "DriveTrain.Differential"
PARTS = (BRAKE, CLUTCH, DIFFERENTIAL)
MAPPED = (SHAFT, GEAR, HINGE_ACTUATOR, VELOCITY_MOTOR_1D, TORQUE_MOTOR_1D, *PARTS)


EXACT = frozenset({*MAPPED, *AUTOMATIC, "DriveTrain.Shaft"})


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


def collect(asm: Any, col: Any, rep: Any, source: Any, mate_paths: set[str]) -> tuple[list, list, list, list]:
    """(shafts, couplings, motors, parts) of the assembled tree, with A040 for drive-train objects
    this mapping cannot take (a gear on something that is not a shaft, a motor between two shafts)."""
    d = _DriveTrain(col.k, col.a, rep, source)
    objs = [o for o in asm.owned if isinstance(o, Obj) and mapped(col.k, o)]
    for o in objs:
        if col.k.isa(o, SHAFT):
            d.shaft(o)
    couplings: list[S.ShaftCoupling] = []
    motors: list[S.ShaftMotor] = []
    parts: list[S.ShaftPart] = []
    for o in objs:
        if col.k.isa(o, SHAFT) or not col.a.get(o, "enabled", True):
            continue
        if col.k.isa(o, GEAR):
            couplings.extend(d.gear(o))
        elif col.k.isa(o, HINGE_ACTUATOR):
            couplings.extend(d.hinge_actuator(o, mate_paths))
        elif col.k.isa(o, DIFFERENTIAL):
            parts.extend(d.differential(o))
        elif col.k.isa(o, BRAKE) or col.k.isa(o, CLUTCH):
            parts.extend(d.friction_part(o, "brake" if col.k.isa(o, BRAKE) else "clutch"))
        else:
            motors.extend(d.motor(o))
    return list(d.shafts.values()), couplings, motors, parts


class _DriveTrain:
    """The drive-train elements found so far (the shafts, by object id) and how to map the others:
    each mapping returns the scene element, or nothing after saying why (A040)."""

    def __init__(self, kinds: Any, asmb: Any, rep: Any, source: Any):
        self.k, self.a, self.rep, self.source = kinds, asmb, rep, source
        self.shafts: dict[int, S.Shaft] = {}

    def unsupported(self, o: Obj, why: str) -> list:
        not_simulated(self.rep, f"{o.display}: {why}; it is not simulated", obj=o, severity="warning")
        return []

    def shaft(self, o: Obj) -> None:
        inertia = self.a.real(o, "inertia.inertia", math.nan)
        if not math.isfinite(inertia) or inertia <= 0:
            not_simulated(self.rep, f"{o.display}: a shaft needs a positive, finite inertia.inertia (got "
                          f"{inertia:g}); it is not simulated", obj=o, severity="warning")
            return
        self.shafts[id(o)] = S.Shaft(o.display, inertia, self.a.real(o, "kinematics.angle", 0.0),
                                     self.a.real(o, "kinematics.velocity", 0.0), self.source(self.rep, o))

    def shaft_of(self, conn: Any) -> S.Shaft | None:
        cur = conn.owner if isinstance(conn, Obj) else None
        while cur is not None:
            if id(cur) in self.shafts:
                return self.shafts[id(cur)]
            cur = cur.owner
        return None

    def connectors(self, o: Obj) -> list[Obj]:
        conns = self.a.get(o, "connectors", [])
        return [c for c in conns if isinstance(c, Obj)] if isinstance(conns, (list, tuple)) else []

    def gear(self, o: Obj) -> list[S.ShaftCoupling]:
        ends = [self.shaft_of(c) for c in self.connectors(o)]
        if len(ends) != 2 or None in ends or ends[0] is ends[1]:
            return self.unsupported(o, "a gear needs two connectors on two different shafts")
        ratio = self.a.real(o, "ratio", 1.0)
        if not math.isfinite(ratio) or ratio == 0:
            return self.unsupported(o, f"gear ratio {ratio:g} must be finite and not zero")
        return [S.ShaftCoupling(o.display, "gear", ends[0].path, ends[1].path, ratio, self.source(self.rep, o))]

    def hinge_actuator(self, o: Obj, mate_paths: set[str]) -> list[S.ShaftCoupling]:
        sh = self.shaft_of(self.a.get(o, "connector_1d", None))
        mate = self.a.get(o, "mate_3d", None)
        mate_path = mate.display if isinstance(mate, Obj) else None
        if sh is None or mate_path not in mate_paths:
            return self.unsupported(o, "a hinge actuator needs connector_1d on a shaft and mate_3d bound to a hinge "
                                    "of the scene")
        return [S.ShaftCoupling(o.display, "actuator", sh.path, mate_path, 1.0, self.source(self.rep, o))]

    def motor(self, o: Obj) -> list[S.ShaftMotor]:
        """A 1D velocity or torque motor, mapped when it acts between one shaft and the ground."""
        ends = [self.shaft_of(c) for c in self.connectors(o)]
        on = {id(e): e for e in ends if e is not None}
        if len(on) != 1:
            return self.unsupported(o, "a 1D motor is mapped when its connectors are on exactly one shaft (it acts "
                                    "against the ground)")
        sh = next(iter(on.values()))
        velocity = self.k.isa(o, VELOCITY_MOTOR_1D)
        m = S.ShaftMotor(o.display, "velocity_motor" if velocity else "torque_motor", sh.path,
                         source=self.source(self.rep, o))
        m.min_effort = self.a.real(o, "min_effort", -math.inf)
        m.max_effort = self.a.real(o, "max_effort", math.inf)
        if velocity:
            m.target_speed = self.a.real(o, "target_speed", 1.0)
        else:
            m.effort = self.a.real(o, "default_torque", 0.0)
        return [m]

    def friction_part(self, o: Obj, kind: str) -> list[S.ShaftPart]:
        """A brake (against the ground on one shaft, or between two) or a clutch (between two
        shafts): a friction torque of at most engagement x torque_capacity.  An automatic one
        starts fully engaged or released (``initially_engaged``), a manual one at
        ``initial_engagement_fraction``."""
        ends = [self.shaft_of(c) for c in self.connectors(o)]
        on = list({id(e): e for e in ends if e is not None}.values())
        if None in ends or not ends or len(on) > 2 or (kind == "clutch" and len(on) != 2):
            need = "two connectors on two different shafts" if kind == "clutch" else \
                "its connectors on one shaft (braking it against the ground) or on two shafts"
            return self.unsupported(o, f"a {kind} needs {need}")
        capacity = self.a.real(o, "torque_capacity", math.nan)
        if not math.isfinite(capacity) or capacity < 0:
            return self.unsupported(o, f"a {kind} needs a finite torque_capacity >= 0 (got {capacity:g})")
        automatic = any(self.k.isa(o, t) for t in AUTOMATIC)
        times = (0.0, 0.0)
        if automatic:
            engagement = 1.0 if self.a.get(o, "initially_engaged", False) is True else 0.0
            times = (self.a.real(o, "engagement_duration", 0.0), self.a.real(o, "disengagement_duration", 0.0))
            if not all(math.isfinite(t) and t >= 0 for t in times):
                return self.unsupported(o, f"an automatic {kind} needs finite engagement and disengagement durations "
                                        f">= 0 (got {times[0]:g}, {times[1]:g})")
        else:
            engagement = self.a.real(o, "initial_engagement_fraction", math.nan)
            if not math.isfinite(engagement):
                return self.unsupported(o, f"a {kind} needs a finite initial_engagement_fraction (got {engagement:g})")
        return [S.ShaftPart(o.display, kind, tuple(e.path for e in on), capacity, max(engagement, 0.0),
                            automatic=automatic, engage_time=times[0], release_time=times[1],
                            source=self.source(self.rep, o))]

    def differential(self, o: Obj) -> list[S.ShaftPart]:
        """An open differential: connectors (drive, left, right) on three different shafts."""
        ends = [self.shaft_of(c) for c in self.connectors(o)]
        if len(ends) != 3 or None in ends or len({id(e) for e in ends}) != 3:
            return self.unsupported(o, "a differential needs three connectors (drive shaft, left and right axle "
                                    "shafts) on three different shafts")
        ratio = self.a.real(o, "gear_ratio", 1.0)
        if not math.isfinite(ratio) or ratio == 0:
            return self.unsupported(o, f"differential gear_ratio {ratio:g} must be finite and not zero")
        locked = self.a.get(o, "locked_up", False) is True
        return [S.ShaftPart(o.display, "differential", tuple(e.path for e in ends), ratio=ratio, locked=locked,
                            source=self.source(self.rep, o))]
