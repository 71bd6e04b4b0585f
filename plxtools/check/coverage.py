"""What the MuJoCo backend does with every attribute the bundles declare on the objects it maps
(bodies, mates, motors, ranges, springs, contact models, materials): each is MAPPED (with the
meaning and unit the bundle documents), NEUTRAL unless it holds something else than the runtime's
default (then it is named as unsupported, A040, where it is set), or OUTPUT/INPUT (signals, see
``signals.py``).

The attribute names come from the bundles; this table only says what plx does with them.  A
test walks the members of each type in the loaded bundle program and fails on one this table
does not classify, so a new bundle version cannot add an attribute that plx silently ignores."""

from __future__ import annotations

from typing import Any

MAPPED = "mapped"
CHOICE = "choice"  # an object-valued attribute: only the runtime's default choice is simulated
VALUE = "value"  # a plain value: only the stated neutral value is simulated
SIGNAL = "signal"

_MATE_COMMON = {"connectors": MAPPED, "enabled": MAPPED, "enable_snap": MAPPED, "flexibility": CHOICE,
                "dissipation": CHOICE, "toughness": CHOICE, "clearance": CHOICE}
_CTRL_COMMON = {"connectors": MAPPED, "enabled": MAPPED, "min_effort": MAPPED, "max_effort": MAPPED}

# type -> attribute -> status; VALUE entries give the neutral value
TABLE: dict[str, dict[str, Any]] = {
    "Physics3D.Bodies.RigidBody": {"inertia": MAPPED, "kinematics": MAPPED, "is_dynamic": MAPPED},
    "Physics3D.Interactions.Hinge": {**_MATE_COMMON, "initial_angle": MAPPED, "friction": MAPPED},
    "Physics3D.Interactions.Prismatic": {**_MATE_COMMON, "initial_position": MAPPED, "friction": MAPPED},
    "Physics3D.Interactions.Cylindrical": {**_MATE_COMMON, "initial_angle": MAPPED, "initial_position": MAPPED,
                                           "friction_translational": MAPPED, "friction_rotational": MAPPED},
    "Physics3D.Interactions.Ball": dict(_MATE_COMMON),
    "Physics3D.Interactions.Lock": dict(_MATE_COMMON),
    "Physics3D.Interactions.Distance": {**_MATE_COMMON, "initial_distance": MAPPED, "target_distance": MAPPED},
    "Physics3D.Interactions.RotationalVelocityMotor": {**_CTRL_COMMON, "gain": MAPPED, "target_speed": MAPPED,
                                                       "zero_speed_as_spring": (VALUE, False),
                                                       "zero_speed_spring_flexibility": MAPPED,
                                                       "zero_speed_spring_dissipation": MAPPED},
    "Physics3D.Interactions.LinearVelocityMotor": {**_CTRL_COMMON, "gain": MAPPED, "target_speed": MAPPED,
                                                   "zero_speed_as_spring": (VALUE, False),
                                                   "zero_speed_spring_flexibility": MAPPED,
                                                   "zero_speed_spring_dissipation": MAPPED},
    "Physics3D.Interactions.TorqueMotor": {**_CTRL_COMMON, "default_torque": MAPPED},
    "Physics3D.Interactions.ForceMotor": {**_CTRL_COMMON, "default_force": MAPPED},
    "Physics3D.Interactions.RotationalRange": {**_CTRL_COMMON, "flexibility": CHOICE, "dissipation": CHOICE,
                                               "start": MAPPED, "end": MAPPED},
    "Physics3D.Interactions.LinearRange": {**_CTRL_COMMON, "flexibility": CHOICE, "dissipation": CHOICE,
                                           "start": MAPPED, "end": MAPPED},
    "Physics3D.Interactions.TorsionSpring": {**_CTRL_COMMON, "flexibility": MAPPED, "dissipation": MAPPED,
                                             "angle": MAPPED},
    "Physics3D.Interactions.LinearSpring": {**_CTRL_COMMON, "flexibility": MAPPED, "dissipation": MAPPED,
                                            "position": MAPPED},
    "Physics.Interactions.SurfaceContact.Model": {"material_1": MAPPED, "material_2": MAPPED, "enabled": MAPPED,
                                                  "friction": MAPPED, "adhesion": CHOICE,
                                                  "normal_flexibility": CHOICE, "dissipation": CHOICE,
                                                  "clearance": CHOICE, "normal_restitution": MAPPED,
                                                  "tangential_restitution": MAPPED},
    "Physics.Geometries.Material": {"unique_name": MAPPED, "density": MAPPED},
    "Physics3D.Interactions.MateConnector": {"position": MAPPED, "main_axis": MAPPED, "normal": MAPPED},
}

# what the MuJoCo backend does instead, for the message
INSTEAD = {
    "flexibility": "simulated rigid",
    "dissipation": "simulated without that damping",
    "toughness": "simulated unbreakable",
    "clearance": "simulated without clearance",
    "adhesion": "simulated without adhesion",
    "normal_flexibility": "contacts keep MuJoCo's default stiffness",
    "zero_speed_as_spring": "a velocity motor at speed 0 holds like a stiff damper, not a spring",
}

# the bundles' names for "the runtime decides" and for the ideal element
_NEUTRAL_CHOICES = ("Default", "Rigid", "Unbreakable")
# a range's "rigid" flexibility and its default dissipation are what MuJoCo's hard limit does


def is_signal(name: str) -> bool:
    return name.endswith(("_input", "_output"))


def neutral_choice(qname: str) -> bool:
    return qname.rsplit(".", 1)[-1].startswith(_NEUTRAL_CHOICES)


def unclassified(program: Any) -> list[str]:
    """``Type.attribute`` of every member of a table type that the table does not classify."""
    out = []
    for qn, attrs in TABLE.items():
        sym = program.lookup_outside_visibility(qn.split("."))
        if sym is None:
            continue
        for name in program.all_members(sym):
            if name not in attrs and not is_signal(name):
                out.append(f"{qn}.{name}")
    return out


def settings_not_simulated(kinds: Any, ev: Any, get: Any, obj: Any) -> list[tuple[str, str, Any]]:
    """(attribute, message, (statement, unit) or None) for each attribute of ``obj`` that holds
    something the backend does not simulate, whether the user's file or a bundle default put it
    there; the statement is the one that chose it, when known."""
    out = []
    for qn, attrs in TABLE.items():
        if not kinds.isa(obj, qn):
            continue
        for name, status in attrs.items():
            if status == CHOICE:
                child = ev.child(obj, name)
                cq = kinds.p.concrete(child.model).qname if hasattr(child, "model") else None
                if cq is not None and not neutral_choice(cq):
                    decl = getattr(child, "decl", None)
                    where = (decl[0].stmt, decl[0].unit) if decl else None
                    out.append((name, f"{obj.display}.{name} is {cq}, which the MuJoCo backend does not simulate; "
                                      f"{INSTEAD.get(name, 'left out')}", where))
            elif isinstance(status, tuple) and status[0] == VALUE:
                v = get(obj, name, status[1])
                if v != status[1]:
                    out.append((name, f"{obj.display}.{name}: {v!r} is not simulated by the MuJoCo backend; "
                                      f"{INSTEAD.get(name, 'the default is used')}", ev.where(obj, name)))
        break  # the most specific table type decides (the table has no type and its subtype both)
    return out
