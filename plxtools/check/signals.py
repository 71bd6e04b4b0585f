"""Signals (``Physics.Signals`` / ``Physics3D.Signals`` inputs and outputs) on a MuJoCo run.

Two halves:

* :func:`classify` / :func:`collect` read the assembled object tree (no MuJoCo): every Input and
  Output object with its dotted path, its ``source`` (the motor, mate, spring or body it belongs to)
  and what it maps to, or why it does not map.  ``checks.py`` asks :func:`classify` whether a signal
  the user declared is simulated (A040 otherwise).
* :class:`SignalRuntime` binds those to a compiled MuJoCo model: an input writes the value it names
  (a control, an actuator force range, a spring reference, a free body's velocity, an external
  force or torque on a body: ``body_loads.py``); an output reads a joint coordinate, an actuator
  force, a body's pose, velocity or mass, or a mate connector's frame (``connector_signals.py``).
  mujoco is never imported here: the bindings only touch ``model`` / ``data`` arrays and call the
  module given to them.

Conventions: values are SI (rad, rad/s, m, m/s, N, N m).  1D joint values are in the OpenPLX sign of
the mate (``connectors[1]`` relative to ``connectors[0]``), motor values in the motor's own
coordinate (as the compiled actuator's gear makes them).  Body outputs are world-frame: position of
the body frame origin, RPY with ``R = Rz(yaw) Ry(pitch) Rx(roll)``, linear velocity of the centre of
mass and angular velocity.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

from plxtools.model import suggest
from plxtools.check.bindings import Binding, SignalValueError, Unbindable, rpy_of_mat  # noqa: F401 (rpy_of_mat, SignalValueError: read from here too)
from plxtools.check.mapped_types import CONTROLLERS, MATES
from plxtools.model.resolve import linearize

INPUT = "Physics.Signals.Input"
OUTPUT = "Physics.Signals.Output"

# source type -> source kind (most derived first)
SOURCE_KINDS = {
    **{qn: name for qn, (_kind, _dof, name) in CONTROLLERS.items()},  # check/mapped_types.py
    **MATES,
    "Physics3D.Interactions.MateConnector": "connector",
    "Physics3D.Bodies.RigidBody": "body",
    # drive trains (check/mujoco/drivetrain.py: a shaft is a hinge joint of its own, 1D motors act on it)
    "Physics1D.Interactions.RotationalVelocityMotor": "rotational_velocity_motor_1d",
    "DriveTrain.TorqueMotor": "torque_motor_1d",
    "Physics1D.Bodies.RotationalBody": "shaft",
    # brakes, clutches and differentials (check/mujoco/shaft_parts.py); the automatic ones derive from these
    "DriveTrain.ManualBrake": "brake",
    "DriveTrain.ManualClutch": "clutch",
    "DriveTrain.Differential": "differential",
    "DriveTrain.Gear": "gear",  # its torque (check/gear_torque.py); flexible and viscous gears are not simulated
}
ROT_MOTOR = SOURCE_KINDS["Physics3D.Interactions.RotationalVelocityMotor"]
LIN_MOTOR = SOURCE_KINDS["Physics3D.Interactions.LinearVelocityMotor"]
ROT_MOTOR_1D, TORQUE_MOTOR_1D = "rotational_velocity_motor_1d", "torque_motor_1d"

# (signal type, source kinds) -> quantity; the first matching row wins.  A quantity names how the
# runtime reads or writes it (see SignalRuntime._bind_*); its value kind is in VALUE_KIND.
INPUT_MAP: tuple[tuple[str, tuple[str, ...], str], ...] = (
    ("Physics.Signals.AngularVelocity1DInput", (ROT_MOTOR, ROT_MOTOR_1D), "target_speed"),
    ("Physics.Signals.LinearVelocity1DInput", (LIN_MOTOR,), "target_speed"),
    ("Physics.Signals.Torque1DInput", ("torque_motor", TORQUE_MOTOR_1D), "effort"),
    ("Physics.Signals.Force1DInput", ("force_motor",), "effort"),
    ("Physics.Signals.TorqueRangeInput", (ROT_MOTOR, ROT_MOTOR_1D), "effort_range"),
    ("Physics.Signals.ForceRangeInput", (LIN_MOTOR,), "effort_range"),
    ("Physics.Signals.AngleInput", ("torsion_spring",), "spring_rest"),
    ("Physics.Signals.Position1DInput", ("linear_spring",), "spring_rest"),
    ("Physics.Signals.FractionInput", ("brake", "clutch"), "engagement"),
    ("Physics.Signals.EngageInput", ("brake", "clutch"), "engaged"),
    ("Physics.Signals.BoolInput", ("differential",), "locked_up"),
    ("Physics3D.Signals.LinearVelocity3DInput", ("body",), "body_linear_velocity"),
    ("Physics3D.Signals.AngularVelocity3DInput", ("body",), "body_angular_velocity"),
    # an external load on a body (check/body_loads.py): the body must say it takes one
    # (`with Physics3D.Signals.Torque3DInputTrait`), the type checker holds the source to that
    ("Physics3D.Signals.Torque3DInput", ("body",), "body_torque"),
)
# inputs of no bundle type above, mapped by what their `type:` (a Physics.Signals.InputOutputType
# member, read from the bundles) says they carry: the bundles have no Force3DInput, so a project that
# pushes a body declares its own `Physics.Signals.Input` with `type: InputOutputType.Force3D`
INPUT_TYPE_MAP: tuple[tuple[str, tuple[str, ...], str], ...] = (
    ("Force3D", ("body",), "body_force"),
    ("Torque3D", ("body",), "body_torque"),
)
OUTPUT_MAP: tuple[tuple[str, tuple[str, ...], str], ...] = (
    ("Physics.Signals.AngleOutput", ("hinge", "cylindrical"), "joint_position"),
    ("Physics.Signals.AngleOutput", ("shaft",), "shaft_position"),
    ("Physics.Signals.AngularVelocity1DOutput", ("shaft",), "shaft_velocity"),
    # the bundles' own sources of these (engines, a shovel's soil) are not simulated; a shaft, hinge or
    # body given the output's trait has the value (rev/min = rad/s * 60 / 2 pi; the body's mass in MuJoCo)
    ("Physics.Signals.RpmOutput", ("shaft",), "shaft_rpm"),
    ("Physics.Signals.RpmOutput", ("hinge", "cylindrical"), "joint_rpm"),
    ("Physics.Signals.MassOutput", ("body",), "body_mass"),
    ("Physics.Signals.AngleOutput", ("torsion_spring",), "spring_rest"),
    ("Physics.Signals.Position1DOutput", ("prismatic", "cylindrical"), "joint_position"),
    ("Physics.Signals.Position1DOutput", ("linear_spring",), "spring_rest"),
    ("Physics.Signals.AngularVelocity1DOutput", ("hinge", "cylindrical"), "joint_velocity"),
    ("Physics.Signals.LinearVelocity1DOutput", ("prismatic", "cylindrical"), "joint_velocity"),
    ("Physics.Signals.AngularVelocity1DOutput", (ROT_MOTOR, ROT_MOTOR_1D), "target_speed"),
    ("Physics.Signals.LinearVelocity1DOutput", (LIN_MOTOR,), "target_speed"),
    ("Physics.Signals.Torque1DOutput", (ROT_MOTOR, "torque_motor", ROT_MOTOR_1D, TORQUE_MOTOR_1D), "actuator_effort"),
    ("Physics.Signals.Force1DOutput", (LIN_MOTOR, "force_motor"), "actuator_effort"),
    ("Physics.Signals.Torque1DOutput", ("torsion_spring",), "spring_effort"),
    ("Physics.Signals.Force1DOutput", ("linear_spring",), "spring_effort"),
    ("Physics.Signals.TorqueRangeOutput", (ROT_MOTOR, ROT_MOTOR_1D), "effort_range"),
    ("Physics.Signals.ForceRangeOutput", (LIN_MOTOR,), "effort_range"),
    ("Physics.Signals.FractionOutput", ("brake", "clutch"), "engagement"),
    ("Physics.Signals.EngagedOutput", ("brake", "clutch"), "engaged"),
    ("Physics.Signals.Torque1DOutput", ("brake", "clutch"), "part_torque"),
    ("Physics.Signals.Torque1DOutput", ("gear",), "gear_torque"),
    ("Physics.Signals.RelativeVelocity1DOutput", ("brake", "clutch"), "slip_velocity"),
    ("Physics.Signals.BoolOutput", ("differential",), "locked_up"),
    ("Physics3D.Signals.Position3DOutput", ("body",), "body_position"),
    ("Physics3D.Signals.RPYOutput", ("body",), "body_rpy"),
    ("Physics3D.Signals.LinearVelocity3DOutput", ("body",), "body_linear_velocity"),
    ("Physics3D.Signals.AngularVelocity3DOutput", ("body",), "body_angular_velocity"),
    # a mate connector's frame: its body's pose times the connector's frame in it (check/connector_signals.py)
    ("Physics3D.Signals.MateConnector.PositionOutput", ("connector",), "connector_position"),
    ("Physics3D.Signals.MateConnector.RPYOutput", ("connector",), "connector_rpy"),
    ("Physics3D.Signals.MateConnector.LinearVelocity3DOutput", ("connector",), "connector_linear_velocity"),
    ("Physics3D.Signals.MateConnector.AngularVelocity3DOutput", ("connector",), "connector_angular_velocity"),
    ("Physics3D.Signals.LinearVelocity3DOutput", ("connector",), "connector_linear_velocity"),
    ("Physics3D.Signals.AngularVelocity3DOutput", ("connector",), "connector_angular_velocity"),
    ("Physics3D.Signals.MateConnector.Acceleration3DOutput", ("connector",), "connector_acceleration"),
    ("Physics3D.Signals.MateConnector.AngularAcceleration3DOutput", ("connector",),
     "connector_angular_acceleration"),
)
# every other Input / Output type of the bundles, refused by name with the reason (a test checks that
# each signal type the installed bundles define is mapped above or listed here)
_SWITCH = ("its sources in the bundles are interactions switched on and off and the vacuum gripper: nothing can be "
           "switched during a MuJoCo run")
_GEARBOX = "its source in the bundles is DriveTrain.GearBox (the selected gear and its ratio), which is not simulated"
_REACTION = ("constraint forces of mates are not read: the bundle gives neither the point nor the frame they are "
             "measured at, and a MuJoCo tree joint has no reaction force of its own (cfrc_int also holds the "
             "child body's inertial load)")
_DURATION = ("an automatic clutch's or brake's engagement and disengagement durations are simulated with the model's "
             "values, which no signal changes or reads during a run")
REFUSED: dict[str, str] = {
    "Physics.Signals.Input": "the abstract base of inputs",
    "Physics.Signals.Output": "the abstract base of outputs",
    "Physics.Signals.ActivateInput": _SWITCH,
    "Physics.Signals.ActivatedOutput": _SWITCH,
    "Physics.Signals.IntInput": _GEARBOX,
    "Physics.Signals.IntOutput": _GEARBOX,
    "Physics.Signals.DurationInput": _DURATION,
    "Physics.Signals.DurationOutput": _DURATION,
    "Physics.Signals.EnableInteractionInput": "interactions cannot be switched on or off during a run",
    "Physics.Signals.InteractionEnabledOutput": "interactions cannot be switched on or off during a run",
    "Physics.Signals.RatioOutput": _GEARBOX,
    "Physics3D.Signals.Force3DOutput": _REACTION,
    "Physics3D.Signals.Torque3DOutput": _REACTION,
    "Physics3D.Signals.MateConnector.Output": "the abstract base of mate connector outputs",
    "DriveTrain.Signals.AutomaticClutchDisengagementDurationInput": _DURATION,
    "DriveTrain.Signals.AutomaticClutchEngagementDurationInput": _DURATION,
    "DriveTrain.Signals.AutomaticClutchDisengagementDurationOutput": _DURATION,
    "DriveTrain.Signals.AutomaticClutchEngagementDurationOutput": _DURATION,
    "DriveTrain.Signals.TorqueConverterLockUpInput": "torque converters are not simulated",
    "DriveTrain.Signals.TorqueConverterLockedUpOutput": "torque converters are not simulated",
    "DriveTrain.Signals.TorqueConverterPumpTorqueOutput": "torque converters are not simulated",
    "DriveTrain.Signals.TorqueConverterTurbineTorqueOutput": "torque converters are not simulated",
    "Robotics.Signals.RobotInput": "robot-level signals are not simulated",
    "Robotics.Signals.RobotOutput": "robot-level signals are not simulated",
    "Sensors.Signals.LidarOutput": "sensors are not simulated",
}
# signals of simulated sources that are not read, by the source's type
SOURCE_REFUSED: dict[str, str] = {
    "DriveTrain.Gear": "gear ratios are fixed in the MuJoCo model (a rigid train's gears are one coordinate)",
}
VALUE_KIND = {
    "shaft_position": "real", "shaft_velocity": "real", "shaft_rpm": "real", "joint_rpm": "real", "body_mass": "real",
    "target_speed": "real", "effort": "real", "effort_range": "vec2", "spring_rest": "real",
    "joint_position": "real", "joint_velocity": "real", "actuator_effort": "real", "spring_effort": "real",
    "body_position": "vec3", "body_rpy": "vec3", "body_linear_velocity": "vec3", "body_angular_velocity": "vec3",
    "body_force": "vec3", "body_torque": "vec3",
    "connector_position": "vec3", "connector_rpy": "vec3", "connector_linear_velocity": "vec3",
    "connector_angular_velocity": "vec3", "connector_acceleration": "vec3", "connector_angular_acceleration": "vec3",
    "engagement": "real", "engaged": "bool", "part_torque": "real", "gear_torque": "real", "slip_velocity": "real", "locked_up": "bool",
}
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)  # RpmOutput: revolutions per minute
# what a value kind looks like, for messages
KIND_TEXT = {"bool": "true or false", "real": "a number", "vec2": "two numbers [min, max]", "vec3": "three numbers [x, y, z]"}
# the components an expectation may pick from a vector output
COMPONENTS = {"vec3": ("x", "y", "z"), "vec2": ("min", "max")}
RPY_COMPONENTS = ("roll", "pitch", "yaw")
RPY_QUANTITIES = ("body_rpy", "connector_rpy")  # vec3 outputs whose components are roll, pitch, yaw


@dataclass(slots=True)
class SignalInfo:
    """One Input or Output object of the scene."""

    path: str  # dotted from the root, e.g. box_truck.front_left_motor.target_angular_velocity_input
    direction: str  # "input" | "output"
    type: str  # qualified type, e.g. Physics.Signals.AngularVelocity1DInput
    source: str | None  # path of the motor / mate / body it belongs to
    source_kind: str | None  # a SOURCE_KINDS value
    quantity: str | None  # what it maps to (None: not simulated)
    why: str = ""  # when quantity is None: why not
    enabled: bool = True  # outputs: the model's `enabled`
    location: Any = None  # plxtools.check.scene.Source of the declaration, when known
    frame: Any = None  # a connector output: its source's ConnectorFrame (check/connector_frames.py)
    relative: Any = None  # and its relative_to's (None: the world)

    @property
    def value_kind(self) -> str | None:
        return VALUE_KIND.get(self.quantity) if self.quantity else None

    @property
    def mapped(self) -> bool:
        return self.quantity is not None

    def to_dict(self) -> dict[str, Any]:
        return {"path": self.path, "direction": self.direction, "type": self.type, "source": self.source,
                "mapped": self.mapped, "quantity": self.quantity, "value": self.value_kind,
                **({"why": self.why} if not self.mapped else {})}


def _source_kind(obj: Any, kinds: Any) -> str | None:
    return kinds.first(obj, SOURCE_KINDS) if obj is not None else None


def classify(obj: Any, ev: Any, kinds: Any) -> SignalInfo | None:
    """The signal ``obj`` is (None when it is no Input or Output), and what it maps to."""
    from plxtools.check.instance import Obj

    if kinds.isa(obj, INPUT):
        direction, table = "input", INPUT_MAP
    elif kinds.isa(obj, OUTPUT):
        direction, table = "output", OUTPUT_MAP
    else:
        return None
    qn = kinds.p.concrete(obj.model).qname
    src = ev.child(obj, "source") if "source" in obj.children else None
    src = src if isinstance(src, Obj) else None
    skind = _source_kind(src, kinds)
    enabled = True
    if direction == "output":
        try:
            enabled = bool(ev.get(obj, "enabled", True))
        except Exception:  # an unevaluable flag: the check reports it; the output stays readable
            enabled = True
    info = SignalInfo(obj.display, direction, qn, src.display if src is not None else None, skind, None,
                      enabled=enabled)
    for sig_type, sources, quantity in table:
        if kinds.isa(obj, sig_type):
            if skind in sources:
                info.quantity = quantity
                return info
    if direction == "input":
        info.quantity = _by_carried_type(obj, ev, kinds, skind)
        if info.quantity is not None:
            return info
    refused = next((REFUSED[t] for t in _lineage(obj, kinds) if t in REFUSED and t not in (INPUT, OUTPUT)), None)
    if refused is None and src is not None:
        refused = next((SOURCE_REFUSED[t] for t in _lineage(src, kinds) if t in SOURCE_REFUSED), None)
    if refused is not None:
        of = f" of a {skind.replace('_', ' ')}" if skind else ""
        info.why = f"{qn}{of} is not mapped: {refused}"
    elif src is None:
        info.why = "it has no source"
    elif skind is None:
        info.why = f"its source {src.display} ({kinds.p.concrete(src.model).qname}) has no MuJoCo mapping"
    else:
        info.why = f"{_short(qn)} of a {skind.replace('_', ' ')} has no MuJoCo mapping"
    return info


IO_TYPES = "Physics.Signals.InputOutputType"


def _by_carried_type(obj: Any, ev: Any, kinds: Any, skind: str | None) -> str | None:
    """What an input of no mapped type maps to by its ``type:`` (INPUT_TYPE_MAP), the members'
    values read from the bundles' ``Physics.Signals.InputOutputType``; None when nothing fits."""
    rows = [(name, q) for name, sources, q in INPUT_TYPE_MAP if skind in sources]
    sym = kinds.sym(IO_TYPES) if rows else None
    if sym is None:
        return None
    try:
        carried = ev.get(obj, "type")
        members = ev.b.singleton(sym)
        return next((q for name, q in rows if members is not None and ev.get(members, name) == carried), None)
    except Exception:  # an unevaluable `type:` is the check's to report; the input is then not mapped
        return None


def _lineage(obj: Any, kinds: Any) -> list[str]:
    """The qualified names of an object's model and its bases, nearest first."""

    return [m.qname for m in reversed(linearize(kinds.p, kinds.p.concrete(obj.model)))]


def _short(qn: str) -> str:
    return qn.rsplit(".", 1)[-1]


def collect(owned: list, ev: Any, kinds: Any, locate: Callable[[Any], Any] | None = None,
            frame: Callable[[Any], Any] | None = None) -> list[SignalInfo]:
    """Every Input and Output among the ``owned`` objects, in declaration order.  ``frame`` gives a
    connector's frame (check/connector_frames.py) for the outputs that read one."""
    out = []
    for obj in owned:
        info = classify(obj, ev, kinds)
        if info is not None:
            if locate is not None:
                info.location = locate(obj)
            if frame is not None and info.source_kind == "connector" and info.mapped:
                _frames(info, obj, ev, frame)
            out.append(info)
    return out


def _frames(info: SignalInfo, obj: Any, ev: Any, frame: Callable[[Any], Any]) -> None:
    """The frames of a connector output's source and of its ``relative_to`` (None: the world)."""
    from plxtools.check.instance import Obj

    src = ev.child(obj, "source")
    info.frame = frame(src) if isinstance(src, Obj) else None
    rel = ev.child(obj, "relative_to") if "relative_to" in obj.children else None
    info.relative = frame(rel) if isinstance(rel, Obj) else None


def mapping_summary() -> dict[str, list[str]]:
    """The signal types mapped, by direction (docs and the closing note)."""
    return {"input": sorted({t for t, _, _ in INPUT_MAP}), "output": sorted({t for t, _, _ in OUTPUT_MAP})}


# ---------------------------------------------------------------------------------------------- runtime


def _num(x: Any) -> float | None:
    """``x`` as a float when it is a real number (not a boolean), else None."""
    if isinstance(x, bool) or type(x).__name__ == "bool_":
        return None
    if isinstance(x, (int, float)):
        return float(x)
    if type(x).__module__ == "numpy" and hasattr(x, "dtype") and getattr(x, "ndim", 1) == 0 \
            and x.dtype.kind in "iuf":
        return float(x)
    return None


def coerce(info: SignalInfo, value: Any) -> Any:
    """``value`` as the signal takes it (a float, or a tuple of floats), or SignalValueError."""
    kind = info.value_kind or "real"
    wrong = SignalValueError(f"{info.path} takes {KIND_TEXT[kind]}, not {_describe(value)}")
    if kind == "bool":
        if isinstance(value, bool) or type(value).__name__ == "bool_":
            return bool(value)
        raise wrong
    if kind == "real":
        v = _num(value)
        if v is None:
            raise wrong
        if not math.isfinite(v):
            raise SignalValueError(f"{info.path} takes a finite number, not {v}")
        return v
    if isinstance(value, (str, bytes, dict)):
        raise wrong
    try:
        items = list(value)
    except TypeError:
        raise wrong from None
    vals = tuple(_num(x) for x in items)
    if len(vals) != (3 if kind == "vec3" else 2) or any(x is None for x in vals):
        raise wrong
    if not all(math.isfinite(x) for x in vals):
        raise SignalValueError(f"{info.path} takes finite numbers, not {list(vals)}")
    if kind == "vec2" and vals[0] > vals[1]:
        raise SignalValueError(f"{info.path}: the range [{vals[0]:g}, {vals[1]:g}] has min > max")
    return vals


def _describe(value: Any) -> str:
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, str):
        return f"the text {value!r}"
    if isinstance(value, (list, tuple)):
        return f"a list of {len(value)} item{'s' if len(value) != 1 else ''}"
    if isinstance(value, dict):
        return "a table"
    return f"{type(value).__name__} {value!r}"


def _ctrl_binding(b: Binding, aid: int) -> None:
    """A motor's target speed or effort: its actuator's control."""
    b.read = lambda m, d: float(d.ctrl[aid])

    def write_ctrl(m, d, v):
        d.ctrl[aid] = v

    b.write = write_ctrl


def _constraint_motor_binding(b: Binding, q: str, act: Any, model: Any, aid: int, offsets: dict) -> Binding:
    """A motor run as a velocity constraint (mujoco.velocity_constraint): its target speed is its
    reference's control, its effort the constraint's force plus its offset, its effort range the
    offset plus the tendon's friction bound around it (any range: ``split_range``)."""
    from plxtools.check.mujoco import velocity_constraint as vc

    offsets.setdefault(act.path, float(act.offset))
    if q == "actuator_effort":
        dof = vc.reference_dof(model, act.reference)
        b.read = lambda m, d: vc.effort(d, dof, offsets[act.path])
    elif q == "effort_range":
        tid = int(model.tendon(act.tendon).id)
        jdof = int(model.jnt_dofadr[model.joint(act.joint).id])

        def read_range(m, d):
            e, c = float(m.tendon_frictionloss[tid]), offsets[act.path]
            return (-math.inf, math.inf) if e >= vc.BIG_EFFORT else (c - e, c + e)

        def refuse(v):
            if vc.split_range(float(v[0]), float(v[1])) is None:
                return f"{b.info.path}: [{v[0]:g}, {v[1]:g}] is not a range (its minimum is above its maximum)"
            return None

        def write_range(m, d, v):
            why = refuse(v)
            if why is not None:
                raise SignalValueError(why)
            c, e = vc.split_range(float(v[0]), float(v[1]), act.span)
            d.qfrc_applied[jdof] += float(act.gear) * (c - offsets[act.path])
            m.tendon_frictionloss[tid] = e
            vc.refresh_bound(m, d, tid)  # with the offset, in this step (not from the next)
            vc.anticipate(m, d, tid, vc.reference_dof(m, act.reference), c - offsets[act.path], c)
            offsets[act.path] = c

        b.read, b.write, b.refuse = read_range, write_range, refuse
    else:
        _ctrl_binding(b, aid)
    return b


@dataclass
class SignalRuntime:
    """The scene's signals bound to a compiled MuJoCo model.  ``unbound`` says, for each signal that
    cannot act on this model, why (not simulated, its motor was dropped, its mate closes a loop...)."""

    mujoco: Any
    compiled: Any  # CompiledScene
    infos: dict[str, SignalInfo]
    bindings: dict[str, Binding] = field(default_factory=dict)
    unbound: dict[str, str] = field(default_factory=dict)
    loads: dict[tuple[int, int], dict] = field(default_factory=dict)  # body loads (check/body_loads.py)
    movers: dict[str, Any] = field(default_factory=dict)  # kinematic bodies of the run (attach_movers)
    offsets: dict[str, float] = field(default_factory=dict)  # constraint motors' effort offsets now, by path
    engagements: Any = None  # the run's brakes and clutches (mujoco.shaft_parts.Engagements, attach_movers)
    _initial: Any = None

    @classmethod
    def bind(cls, mujoco: Any, compiled: Any, infos: list[SignalInfo]) -> "SignalRuntime":
        rt = cls(mujoco, compiled, {i.path: i for i in infos})
        model = compiled.model
        acts = {a.path: (a, model.actuator(a.name).id) for a in compiled.actuators}
        for info in infos:
            if not info.mapped:
                rt.unbound[info.path] = f"{info.path} is not simulated: {info.why}"
                continue
            try:
                b = rt._binding(info, acts)
            except Unbindable as exc:
                rt.unbound[info.path] = f"{info.path} cannot act on the MuJoCo model: {exc}"
                continue
            rt.bindings[info.path] = b
        return rt

    # -- helpers over the compiled model --------------------------------------------------------

    def _joint(self, mate_path: str, dof: str) -> tuple[int, int, int]:
        """(qpos address, dof address, sign) of a mate's joint for a rotational / linear DOF."""
        c, model = self.compiled, self.compiled.model
        names = c.joints.get(mate_path)
        if not names:
            if mate_path in c.loop_mates:
                raise Unbindable(f"{mate_path} closes a kinematic loop (an equality constraint, no joint)")
            raise Unbindable(f"{mate_path} is not simulated (see the check notes)")
        name = names[0]
        if len(names) > 1:
            name = next((n for n in names if n.endswith(":rot" if dof == "rotational" else ":slide")), names[0])
        jid = model.joint(name).id
        return int(model.jnt_qposadr[jid]), int(model.jnt_dofadr[jid]), int(c.joint_sign[mate_path])

    def _controller_joint(self, ctl_path: str) -> tuple[int, int, int]:
        scene = self.compiled.scene
        ctl = next((x for x in scene.controllers if x.path == ctl_path), None)
        if ctl is None or not ctl.enabled:
            raise Unbindable(f"{ctl_path} is not simulated (see the check notes)")
        pair = (ctl.connectors[0].path, ctl.connectors[1].path)
        for m in scene.mates:
            key = (m.connectors[0].path, m.connectors[1].path)
            if key == pair or key == pair[::-1]:
                qadr, dadr, sign = self._joint(m.path, ctl.dof)
                return qadr, dadr, sign * (-1 if key != pair else 1)
        raise Unbindable(f"no mate of {ctl_path} is simulated")

    def _body(self, path: str) -> int:
        name = self.compiled.names.name("body", path)
        if name is None:
            raise Unbindable(f"the body {path} is not simulated")
        return int(self.compiled.model.body(name).id)

    body_id = _body

    def initial_data(self) -> Any:
        """MuJoCo data at the model's initial keyframe, positions computed (where the assembly put
        everything); made once."""
        if self._initial is None:
            mj, model = self.mujoco, self.compiled.model
            d = mj.MjData(model)
            mj.mj_resetDataKeyframe(model, d, model.key("initial").id)
            mj.mj_kinematics(model, d)
            self._initial = d
        return self._initial

    def _bind_actuator(self, info: SignalInfo, acts: dict) -> Binding:
        """A motor's control, effort or effort range (the compiled actuator's ``ctrl`` / force)."""
        q, src, b = info.quantity, info.source or "", Binding(info)
        if src not in acts:
            raise Unbindable(f"its motor {src} is not simulated (see the check notes)")
        act, aid = acts[src]
        if act.reference is not None:
            return _constraint_motor_binding(b, q, act, self.compiled.model, aid, self.offsets)
        if q == "actuator_effort":
            b.read = lambda m, d: float(d.actuator_force[aid])
        elif q == "effort_range":
            def read_range(m, d):
                if m.actuator_forcelimited[aid]:
                    return (float(m.actuator_forcerange[aid][0]), float(m.actuator_forcerange[aid][1]))
                return (-math.inf, math.inf)

            def write_range(m, d, v):
                m.actuator_forcelimited[aid] = 1
                m.actuator_forcerange[aid] = [v[0], v[1]]

            b.read, b.write = read_range, write_range
        else:
            _ctrl_binding(b, aid)
        return b

    def _binding(self, info: SignalInfo, acts: dict) -> Binding:  # noqa: C901 - one table of small cases
        q, src, mj = info.quantity, info.source or "", self.mujoco
        elsewhere = _bound_elsewhere(q)
        if elsewhere is not None:
            return elsewhere(self, info)
        if q in ("target_speed", "effort", "actuator_effort", "effort_range"):
            return self._bind_actuator(info, acts)
        b = Binding(info)
        if q in ("shaft_position", "shaft_velocity", "shaft_rpm"):
            coord = self.compiled.shafts.get(src)  # a shaft turns with its drive train's joint (mujoco.drivetrain)
            if coord is None:
                raise Unbindable(f"the shaft {src} is not simulated (see the check notes)")
            jid = self.compiled.model.joint(coord.joint).id
            qadr, dadr = int(self.compiled.model.jnt_qposadr[jid]), int(self.compiled.model.jnt_dofadr[jid])
            f, off = coord.factor, coord.offset
            if q == "shaft_position":
                b.read = lambda m, d: f * float(d.qpos[qadr]) + off
            else:
                scale = f * (RPM_PER_RAD_S if q == "shaft_rpm" else 1.0)
                b.read = lambda m, d: scale * float(d.qvel[dadr])
            return b
        if q in ("joint_position", "joint_velocity", "joint_rpm"):
            rotational = q == "joint_rpm" or info.type.endswith(("AngleOutput", "AngularVelocity1DOutput"))
            qadr, dadr, sign = self._joint(src, "rotational" if rotational else "linear")
            if q == "joint_position":
                b.read = lambda m, d: sign * float(d.qpos[qadr])
            else:
                scale = sign * (RPM_PER_RAD_S if q == "joint_rpm" else 1.0)
                b.read = lambda m, d: scale * float(d.qvel[dadr])
            return b
        if q in ("spring_rest", "spring_effort"):
            qadr, dadr, sign = self._controller_joint(src)
            if q == "spring_effort":
                b.read = lambda m, d: sign * float(d.qfrc_spring[dadr])
            else:
                b.read = lambda m, d: sign * float(m.qpos_spring[qadr])

                def write_rest(m, d, v):
                    m.qpos_spring[qadr] = sign * v

                b.write = write_rest
            return b
        bid = self._body(src)
        if q == "body_position":
            b.read = lambda m, d: tuple(float(x) for x in d.xpos[bid])
        elif q == "body_rpy":
            b.read = lambda m, d: rpy_of_mat(d.xmat[bid])
        elif q in ("body_linear_velocity", "body_angular_velocity"):
            lin = q == "body_linear_velocity"

            compiled = self.compiled

            def read_vel(m, d):
                from plxtools.check.mujoco.kinematic import body_velocity  # a kinematic body's is prescribed

                res = body_velocity(mj, m, d, compiled, bid)
                return tuple(float(x) for x in (res[3:] if lin else res[:3]))

            b.read = read_vel
            if info.direction == "input":
                b.write = self._velocity_input(src, lin, bid)
        else:  # pragma: no cover - the tables and this function are kept in step by tests
            raise Unbindable(f"quantity {q} has no binding")
        return b

    def _velocity_input(self, src: str, lin: bool, bid: int) -> Any:
        """The write of a body's velocity input: a free body's joint speed, a kinematic body's
        prescribed velocity; refused (Unbindable) for a static or mated body."""
        jname = self.compiled.names.name("joint", src, ":free")
        sb = self.compiled.scene.body(src)
        if sb is not None and self.compiled.names.name("joint", src, ":kinematic") is not None:
            return self._kinematic_velocity(src, lin)
        if sb is not None and not sb.is_dynamic:
            raise Unbindable(f"{src} is not dynamic and does not move (is_dynamic: false without a velocity): "
                              f"plx simulates it as static, so no input can move it; give it an initial "
                              f"velocity (kinematics.initial_local_linear_velocity or _angular_velocity) to "
                              f"make it a kinematic body that velocity inputs drive")
        if src not in self.compiled.free_roots or jname is None:
            raise Unbindable(f"{src} is attached to other bodies by mates (only a free body's velocity "
                              f"can be set)")
        dadr = int(self.compiled.model.jnt_dofadr[self.compiled.model.joint(jname).id])

        def write_vel(m, d, v):
            import numpy as np

            if lin:
                d.qvel[dadr:dadr + 3] = v
            else:
                r = np.asarray(d.xmat[bid]).reshape(3, 3)
                d.qvel[dadr + 3:dadr + 6] = r.T @ np.asarray(v)  # free-joint angular velocity: body frame

        return write_vel

    def _kinematic_velocity(self, src: str, lin: bool) -> Any:
        """The write of a kinematic body's velocity input: its new prescribed velocity (world frame)
        from this step on, continuing from where it is (AGX drives kinematic bodies by velocity)."""

        def write(m, d, v):
            mover = self.movers.get(src)
            if mover is None:  # pragma: no cover - every run that writes inputs attaches its stepper
                raise RuntimeError(f"{src}: no kinematic mover attached to this run")
            if lin:
                mover.set_velocity(float(d.time), v=v)
            else:
                mover.set_velocity(float(d.time), w=v)
            mover.place(d, float(d.time))

        return write

    def attach_movers(self, movers: list, engagements: Any = None, lag: Any = None) -> None:
        """The kinematic bodies' movers of the run this runtime writes to (see mujoco.kinematic), its
        brakes' and clutches' engagements (mujoco.shaft_parts), and its motors' softness correction,
        which reads the effort offsets the range inputs set (mujoco.velocity_constraint.Lag)."""
        self.movers = {mv.path: mv for mv in movers}
        self.engagements = engagements
        if lag is not None:
            lag.offsets = self.offsets

    # -- use --------------------------------------------------------------------------------------

    def write(self, path: str, value: Any, model: Any, data: Any) -> None:
        b = self.bindings[path]
        assert b.write is not None
        b.write(model, data, value)

    def refusal(self, path: str, value: Any) -> str | None:
        """Why ``value`` cannot be written to ``path`` on this model (checked before a run), or None."""
        b = self.bindings.get(path)
        return b.refuse(value) if b is not None and b.refuse is not None else None

    def read(self, path: str, model: Any, data: Any) -> Any:
        b = self.bindings[path]
        assert b.read is not None
        return b.read(model, data)


def _bound_elsewhere(quantity: str | None) -> Callable[[SignalRuntime, SignalInfo], Binding] | None:
    """The binder of a quantity kept in a module of its own (connector outputs, loads on bodies)."""
    from plxtools.check import body_loads, connector_signals, part_signals

    if quantity in connector_signals.CONNECTOR_QUANTITIES:
        return connector_signals.bind_connector
    if quantity in part_signals.PART_QUANTITIES:
        return part_signals.bind_part
    if quantity in body_loads.LOAD_QUANTITIES:
        return body_loads.bind_load
    if quantity == "gear_torque":
        from plxtools.check.gear_torque import bind_gear_torque

        return bind_gear_torque
    return body_loads.bind_mass if quantity == "body_mass" else None


# ---------------------------------------------------------------------------------------------- names


def did_you_mean(name: str, candidates: list[str]) -> str | None:
    """The candidate to offer for ``name`` (model/suggest.py's ranking: meaning, then spelling; a
    candidate with the same last part when nothing else is close), or None."""
    import difflib

    if not candidates:
        return None
    last = name.rsplit(".", 1)[-1]
    close = suggest.best(name, candidates, cutoff=0.6)
    if close:
        return close
    same_tail = [c for c in candidates if c.rsplit(".", 1)[-1] == last]
    if same_tail:
        return difflib.get_close_matches(name, same_tail, n=1, cutoff=0.0)[0]
    return None


def coverage_table(types: dict[str, str]) -> str:
    """The Markdown table of docs/testing.md: every signal type (qualified name -> "input" | "output",
    from the bundles) with what it maps to on the MuJoCo run, or why it is refused."""
    kinds_of = {v: f"{k.split('.', 1)[0]} {k.rsplit('.', 1)[-1]}" for k, v in SOURCE_KINDS.items()}
    rows = ["| signal type | direction | on the MuJoCo run |", "|---|---|---|"]
    for qn in sorted(types):
        table = INPUT_MAP if types[qn] == "input" else OUTPUT_MAP
        mapped = [f"{', '.join(kinds_of[k] for k in sources)}: {quantity.replace('_', ' ')}"
                  for t, sources, quantity in table if t == qn]
        what = "; ".join(mapped) if mapped else f"refused: {REFUSED.get(qn, 'not mapped')}"
        rows.append(f"| `{qn}` | {types[qn]} | {what} |")
    return "\n".join(rows) + "\n"
