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
from plxtools.rules import registry

MAPPED = "mapped"
CHOICE = "choice"  # an object-valued attribute: only the runtime's default choice is simulated
VALUE = "value"  # a plain value: only the stated neutral value is simulated
SIGNAL = "signal"
NOTED = "noted"  # approximated or refused with a note by the static checks (A113 / A040), not here
REFUSED = "refused"  # never simulated: A040 wherever the object has it (a trait's attributes, mostly)

# The one home of A040 (unsupported-feature): every static check that finds something the MuJoCo
# backend does not simulate reports it through not_simulated(); the backend names the code when it
# meets such an element anyway (an invariant) through registry.NOT_SIMULATED.


def not_simulated(rep: Any, message: str, **where: Any) -> Any:
    """Report (A040) that ``message``'s element or setting is not simulated by the MuJoCo backend;
    ``where`` places it as ``Reporter.add`` does (obj, node, unit, severity, path, ...)."""
    return rep.add(registry.NOT_SIMULATED, message, **where)

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
    # what `friction` of a contact model or a mate holds (convert.py reads the coefficient, limit or viscosity;
    # a model that is not dry friction is named by the static checks, A040 / A113)
    "Physics.Interactions.Dissipation.DefaultDryFriction": {"coefficient": MAPPED},
    "Physics.Interactions.Dissipation.DryConstantNormalForceFriction": {"coefficient": MAPPED, "normal_force": NOTED},
    "Physics.Interactions.Dissipation.DryDepthScaledConstantNormalForceFriction": {
        "coefficient": MAPPED, "normal_force": NOTED, "depth_factor": NOTED},
    "Physics.Interactions.Dissipation.ConstantLimitFriction": {"limit": MAPPED},
    "Physics.Interactions.Dissipation.ConstantViscousSurfaceFriction": {"viscosity": MAPPED},
    "Physics.Interactions.Dissipation.AsymmetricLimitFriction": {"positive_limit": NOTED, "negative_limit": NOTED},
    "Physics.Interactions.Dissipation.MechanicalDamping": {"damping_constant": MAPPED},
    "Physics.Interactions.Dissipation.ConstraintRelaxationTimeDamping": {"relaxation_time": MAPPED},
    "Physics3D.Interactions.MateConnector": {"position": MAPPED, "main_axis": MAPPED, "normal": MAPPED},
}

# Traits a mapped object can be given, by the trait that declares the attributes: what plx does with
# them.  An attribute of a mapped object that a bundle trait (or a bundle subtype) declares and
# neither table classifies is refused too (A040), so a new bundle trait is never ignored silently;
# the coverage test lists the official traits and fails on one this table does not know.
TRAITS: dict[str, dict[str, Any]] = {
    "Physics3D.Interactions.SurfaceContact.Traits.OrientedFriction": {
        "primary_direction": REFUSED, "secondary_coefficient": REFUSED},
    "Physics3D.Interactions.SurfaceContact.Traits.GeometryOrientedFriction": {"reference_geometry": REFUSED},
    "Physics3D.Interactions.SurfaceContact.Traits.BodyOrientedFriction": {"reference_body": REFUSED},
    "Physics.Interactions.SurfaceContact.Traits.SurfaceViscosity": {"viscosity": REFUSED},
    "Physics3D.Interactions.SurfaceContact.Traits.OrientedSurfaceViscosity": {"secondary_viscosity": REFUSED},
    "Physics.GeometryMaterialOverrideTrait": {"material_override": REFUSED,
                                              "material_override_geometries_excluded": REFUSED},
}

# what the backend does instead of a refused trait, for the message
TRAIT_INSTEAD = {
    "OrientedFriction": "friction is isotropic, with the friction model's coefficient in every direction",
    "GeometryOrientedFriction": "friction is isotropic, with the friction model's coefficient in every direction",
    "BodyOrientedFriction": "friction is isotropic, with the friction model's coefficient in every direction",
    "SurfaceViscosity": "contacts have no viscous friction term",
    "OrientedSurfaceViscosity": "contacts have no viscous friction term",
    "GeometryMaterialOverrideTrait": "each geometry keeps its own material",
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
    """``Type.attribute`` of every member of a table type that the table does not classify, and
    ``Trait.attribute`` of every official non-signal trait's own attribute that :data:`TRAITS` does
    not classify (each would be refused by the catch-all, but a new trait should be looked at)."""
    out = []
    for qn, attrs in TABLE.items():
        sym = program.lookup_outside_visibility(qn.split("."))
        if sym is None:
            continue
        for name in program.all_members(sym):
            if name not in attrs and not is_signal(name):
                out.append(f"{qn}.{name}")
    for trait in official_traits(program):
        if trait.qname.startswith(_NOT_ON_MAPPED):
            continue
        known = TRAITS.get(trait.qname, {})
        for name, mem in program.all_members(trait).items():
            if mem.owner is trait and name not in known and not is_signal(name):
                out.append(f"{trait.qname}.{name}")
    return out


# traits that only apply to objects the backend does not map at all (they are refused whole, A040)
_NOT_ON_MAPPED = ("Vehicles.", "Robotics.", "Sensors.", "DriveTrain.", "Physics.Optics.", "Math.",
                  "Physics.Signals.", "Physics3D.Signals.", "Physics1D.", "Terrain.")


def official_traits(program: Any) -> list[Any]:
    """Every trait the official bundles declare."""
    out, stack = [], [program.root]
    while stack:
        ns = stack.pop()
        stack.extend(ns.children.values())
        for sym in ns.symbols.values():
            unit = getattr(sym, "unit", None)
            if getattr(sym, "is_trait", False) and unit is not None and unit.official:
                out.append(sym)
    return sorted(out, key=lambda t: t.qname)


def _trait_status(program: Any, mem: Any) -> tuple[Any, str | None]:
    """(status, trait name) of a member that a bundle trait or subtype adds to a mapped object."""
    owner = mem.owner
    for t in [owner, *program.ancestors(owner)]:
        st = TRAITS.get(getattr(t, "qname", ""), {}).get(mem.name)
        if st is not None:
            return st, owner.qname
    return REFUSED, owner.qname


def _members(program: Any, obj: Any) -> dict[str, Any]:
    out = dict(program.all_members(obj.model))
    for t in getattr(obj, "traits", ()) or ():
        for name, mem in program.all_members(t).items():
            out.setdefault(name, mem)
    return out


def settings_not_simulated(kinds: Any, ev: Any, get: Any, obj: Any, _depth: int = 0) -> list[tuple[str, str, Any]]:
    """(attribute, message, (statement, unit) or None) for each attribute of ``obj`` that holds
    something the backend does not simulate, whether the user's file or a bundle default put it
    there; the statement is the one that chose it, when known.  An attribute that a bundle trait
    or bundle subtype adds and the tables do not map is refused too (it would otherwise be ignored),
    and so are those of the objects a mapped attribute holds (a contact model's friction model)."""
    hits = _most_specific(kinds, obj)
    if not hits:
        return []
    qn, attrs = hits[0]  # the most specific table type decides (the table has no type and its subtype both)
    out = _table_settings(kinds, ev, get, obj, attrs)
    refused = _refused_traits(kinds.p, ev, obj, qn, attrs)
    if refused is not None:
        out.append(refused)
    if _depth < 2:
        out.extend(_held_settings(kinds, ev, get, obj, attrs, _depth))
    return out


def _table_settings(kinds: Any, ev: Any, get: Any, obj: Any, attrs: dict[str, Any]) -> list[tuple[str, str, Any]]:
    """The CHOICE attributes holding another than the runtime's choice and the VALUE attributes
    holding another than their neutral value."""
    out = []
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
    return out


def _refused_traits(program: Any, ev: Any, obj: Any, qn: str, attrs: dict[str, Any]) -> tuple[str, str, Any] | None:
    """One finding per object for the bundle attributes the table does not map that its traits
    (or a bundle subtype) add: the traits (most derived first) and the attributes they add."""
    refused: dict[str, list[str]] = {}
    for name, mem in _members(program, obj).items():
        if name in attrs or is_signal(name):
            continue
        unit = getattr(mem.owner, "unit", None)
        if unit is None or not unit.official:
            continue  # the user's own attributes on their subtype: not the runtime's business
        status, trait = _trait_status(program, mem)
        if status == REFUSED:
            refused.setdefault(trait or qn, []).append(name)
    if not refused:
        return None
    owners = sorted(refused, key=lambda q: -len(q.split(".")[-1]))
    names = [n for q in owners for n in refused[q]]
    shorts = [q.rsplit(".", 1)[-1] for q in owners]
    instead = next((TRAIT_INSTEAD[x] for x in shorts if x in TRAIT_INSTEAD), "left out")
    return (names[0], f"{obj.display} has {' / '.join(shorts)} ({', '.join(names)}), which the MuJoCo "
                      f"backend does not simulate; {instead}",
            _declared_where(obj) or _set_where(ev, obj, names))


def _held_settings(kinds: Any, ev: Any, get: Any, obj: Any, attrs: dict[str, Any],
                   depth: int) -> list[tuple[str, str, Any]]:
    """The settings not simulated of the objects that ``obj``'s MAPPED attributes hold (a contact
    model's friction model), named by their path from ``obj``."""
    out = []
    for name, status in attrs.items():
        if status != MAPPED:
            continue
        child = ev.child(obj, name)
        if child is not None and hasattr(child, "model") and _most_specific(kinds, child):
            for attr, msg, where in settings_not_simulated(kinds, ev, get, child, depth + 1):
                out.append((f"{name}.{attr}", msg, where if where is not None else _set_where(ev, obj, [name])))
    return out


def _most_specific(kinds: Any, obj: Any) -> list[tuple[str, dict[str, Any]]]:
    """The table entries ``obj`` is an instance of, most specific first (a subtype before its base)."""
    hits = [(qn, attrs) for qn, attrs in TABLE.items() if kinds.isa(obj, qn)]
    if len(hits) > 1:
        syms = {qn: kinds.sym(qn) for qn, _ in hits}
        hits.sort(key=lambda h: -len(kinds.p.ancestors(syms[h[0]])) if syms[h[0]] is not None else 0)
    return hits


def _declared_where(obj: Any) -> Any:
    """The statement that declares ``obj`` (where its traits are given), if known."""
    decl = getattr(obj, "decl", None)
    return (decl[0].stmt, decl[0].unit) if decl else None


def _set_where(ev: Any, obj: Any, names: list[str]) -> Any:
    """The statement that sets the first of ``names`` on ``obj``, else the one that declares ``obj``."""
    for n in names:
        node, unit = ev.where(obj, n)
        if node is not None:
            return node, unit
    decl = getattr(obj, "decl", None)
    return (decl[0].stmt, decl[0].unit) if decl else None
