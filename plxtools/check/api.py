"""A Python API over `plx check`'s MuJoCo run that mirrors the OpenPLX runtime's signal API.

The tutorial's AGX controller::

    result = application().loadOpenPlxFile("boxtruck.openplx", root())
    scene = result.scene()
    speed_in = scene.getObject("boxTruck.front_left_drive_motor.target_angular_velocity_input")
    result.getInputSignalQueue().send(RealInputSignal.create(3.0, speed_in))

runs headless against plx with other imports::

    from plxtools.check.api import RealInputSignal, load

    result = load("boxtruck.openplx")
    scene = result.scene()
    speed_in = scene.getObject("box_truck.front_left_motor.target_angular_velocity_input")
    result.getInputSignalQueue().send(RealInputSignal.create(3.0, speed_in))
    result.step(2.0)                                    # seconds of simulated time
    x, y, z = result.read("box_truck.chassis.position_output")

A sent signal acts from the next step on (as the runtime's input queue does).  Every name has a
snake_case twin (``get_object``, ``input_queue``).  Errors are exceptions with a one-line message:
:class:`ModelError` (the file cannot be simulated; ``.diagnostics`` has the located findings),
:class:`SignalPathError` (an unknown path, with a did-you-mean), :class:`SignalValueError` (a value
of the wrong kind) and :class:`NotSimulatedError` (a signal the MuJoCo backend does not map).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plxtools.check.api_errors import ModelError, NotSimulatedError, PlxApiError, SignalPathError
from plxtools.check.api_inspect import (
    ConnectorState,
    ContactModelInfo,
    GeometryInfo,
    MaterialInfo,
    connector_state,
    contact_model,
    geometries,
)
from plxtools.check.signals import (
    COMPONENTS,
    RPY_COMPONENTS,
    RPY_QUANTITIES,
    SignalInfo,
    SignalRuntime,
    SignalValueError,
    coerce,
    collect,
    did_you_mean,
)
from plxtools.check.scenecounts import scene_counts
from plxtools.check.scenecounts import scene_paths
from plxtools.check.signals import KIND_TEXT
from plxtools.check.signals import rpy_of_mat
from plxtools.config import ConfigError, config_for
from plxtools.diagnostics import Severity
from plxtools.discovery import UsageError
from plxtools.model.workspace import workspace_for_cli

MATE_CONNECTOR = "Physics3D.Interactions.MateConnector"

__all__ = [
    "BoolInputSignal", "ConnectorState", "ContactModelInfo", "GeometryInfo", "IntInputSignal", "Input",
    "MaterialInfo", "ModelError", "NotSimulatedError", "Output",
    "RealInputSignal", "RealRangeInputSignal", "SceneObject", "SignalPathError", "SignalValueError",
    "Simulation", "Vec3InputSignal", "load",
]


# ----------------------------------------------------------------------------- scene objects


@dataclass(frozen=True)
class SceneObject:
    """Any object of the loaded scene, by dotted path (``type`` is its qualified OpenPLX type)."""

    path: str
    type: str

    def getName(self) -> str:  # noqa: N802 - the runtime's spelling
        return self.path


@dataclass(frozen=True)
class Input(SceneObject):
    """A ``Physics.Signals.Input`` of the scene."""

    info: SignalInfo = field(compare=False, repr=False, default=None)  # type: ignore[assignment]


@dataclass(frozen=True)
class Output(SceneObject):
    """A ``Physics.Signals.Output`` of the scene."""

    info: SignalInfo = field(compare=False, repr=False, default=None)  # type: ignore[assignment]


class _InputSignal:
    kind = "real"
    type_name = "RealInputSignal"

    def __init__(self, value: Any, target: Input):
        self.value = value
        self.target = target

    @classmethod
    def create(cls, value: Any, target: Input) -> "_InputSignal":
        if not isinstance(target, Input):
            got = f"the output {target.path}" if isinstance(target, Output) else \
                f"{target.path} ({target.type})" if isinstance(target, SceneObject) else repr(target)
            raise TypeError(f"{cls.type_name}.create: the target must be an Input from scene.getObject(), "
                            f"not {got}")
        return cls(value, target)

    def __repr__(self) -> str:
        return f"{self.type_name}({self.value!r} -> {self.target.path})"


class RealInputSignal(_InputSignal):
    """One number for an Input (a motor's target speed or torque, a spring's rest angle...)."""


class RealRangeInputSignal(_InputSignal):
    """A [min, max] pair for a range Input (a motor's torque or force range)."""

    kind, type_name = "vec2", "RealRangeInputSignal"


class Vec3InputSignal(_InputSignal):
    """Three numbers for a 3D Input (a body's linear or angular velocity)."""

    kind, type_name = "vec3", "Vec3InputSignal"


class BoolInputSignal(_InputSignal):
    kind, type_name = "bool", "BoolInputSignal"


class IntInputSignal(_InputSignal):
    kind, type_name = "int", "IntInputSignal"


_SIGNAL_FOR_KIND = {"bool": "BoolInputSignal", "real": "RealInputSignal", "vec2": "RealRangeInputSignal", "vec3": "Vec3InputSignal"}


# ----------------------------------------------------------------------------- loading


@dataclass
class Prepared:
    """A model file checked, assembled and compiled, with its signals (what load and plx test share)."""

    path: str
    model: str
    fc: Any  # plxtools.check.pipeline.FileCheck
    compiled: Any  # CompiledScene
    signals: list[SignalInfo]
    objects: dict[str, str]  # every owned object: path -> qualified type
    bodies: list[str]  # rigid body paths
    workspace: Any = None  # the Workspace the file was checked in (which user bundles it could read)


def prepare(path: str | Path, model: str | None = None, *, bundle_path: list[str] | tuple = (),
            openplx_version: str | None = None, text: str | None = None) -> Prepared:
    """Check, assemble and compile ``path`` (raises ModelError when it cannot be simulated).

    ``text``: the file's unsaved content (an editor's buffer), used instead of what is on disk."""
    from plxtools.check.mujoco import backend as mjb
    from plxtools.check.connector_frames import connector_frame
    from plxtools.check.convert import _source
    from plxtools.check.pipeline import analyse, blocking_reason

    p = Path(path)
    if not p.is_file():
        raise ModelError(f"{p}: no such file")
    try:
        ws = workspace_for_cli(list(bundle_path), [p], openplx_version=openplx_version)
        cfg = config_for(p)
    except (UsageError, ConfigError, ValueError) as exc:
        raise ModelError(f"{p}: {exc}") from None
    fc = analyse(p, ws, cfg, model=model, text=text)
    errors = [d for d in fc.diagnostics if d.severity == Severity.ERROR]
    if fc.scene is None or fc.assembly is None:
        raise ModelError(_why(fc, errors), sorted(fc.diagnostics, key=lambda d: -d.severity.rank))
    reason = blocking_reason(fc)
    if reason is not None:
        raise ModelError(f"{p}: cannot simulate {fc.model}: {reason}" + _first(errors), errors)
    compiled = mjb.compile_scene(fc.scene)
    if not compiled.ok:
        msgs = "; ".join(n.message for n in compiled.notes if n.severity == "error")
        raise ModelError(f"{p}: MuJoCo cannot compile {fc.model}: {msgs}")
    program = ws.program
    ev = fc.evaluator  # the assembly's own: its values are already evaluated
    ev.report = lambda *a: None  # the file's diagnostics are final; reading signals adds none
    owned = fc.assembly.owned[1:]
    signals = collect(owned, ev, fc.kinds, lambda o: _source(fc.rep, o),
                      lambda o: connector_frame(fc.assembly, ev, fc.kinds, o))
    objects = {o.display: program.concrete(o.model).qname for o in owned}
    bodies = [n.path for n in fc.assembly.bodies]
    return Prepared(str(p), fc.model or "", fc, compiled, signals, objects, bodies, ws)


def _first(errors: list) -> str:
    if not errors:
        return ""
    d = errors[0]
    more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
    return f"; first: {d.file}:{d.span.start.line + 1}:{d.span.start.column + 1}: {d.code} {d.message}{more}"


def _why(fc: Any, errors: list) -> str:
    return f"{fc.path}: cannot load a scene: {fc.skipped or 'no scene'}" + _first(errors)


def load(path: str | Path, model: str | None = None, *, bundle_path: list[str] | tuple = (),
         openplx_version: str | None = None) -> "Simulation":
    """Load ``path`` (its last model, or ``model``) into a simulation at t = 0.

    ``bundle_path`` and ``openplx_version`` are the CLI's ``--bundle-path`` / ``--openplx-version``;
    the file's plx.toml / pyproject.toml applies as for ``plx check``."""
    return Simulation(prepare(path, model, bundle_path=bundle_path, openplx_version=openplx_version))


# ----------------------------------------------------------------------------- the simulation


class InputSignalQueue:
    """Signals sent here act from the next step on, in the order sent."""

    def __init__(self, sim: "Simulation"):
        self._sim = sim

    def send(self, signal: _InputSignal) -> None:
        self._sim.send(signal)


class Scene:
    """The loaded scene's objects by dotted path (the root model's own path is empty)."""

    def __init__(self, sim: "Simulation"):
        self._sim = sim

    def getObject(self, path: str) -> SceneObject:  # noqa: N802 - the runtime's spelling
        return self._sim.get_object(path)

    get_object = getObject

    def inputs(self) -> list[Input]:
        return [self._sim.get_object(i.path) for i in self._sim.prepared.signals if i.direction == "input"]

    def outputs(self) -> list[Output]:
        return [self._sim.get_object(i.path) for i in self._sim.prepared.signals if i.direction == "output"]

    def bodies(self) -> list[str]:
        """The dotted paths of the assembled scene's rigid bodies (what the run simulates)."""

        return scene_paths(self._sim.prepared.compiled.scene)["bodies"]

    def mates(self) -> list[str]:
        """The dotted paths of the assembled scene's mates."""

        return scene_paths(self._sim.prepared.compiled.scene)["mates"]

    def counts(self) -> dict[str, int]:
        """How many bodies, mates, controllers and drive-train parts, in all and per kind
        (`{"bodies": 3, "mates": 2, "mates.hinge": 2, ...}`)."""

        return scene_counts(self._sim.prepared.compiled.scene)


@dataclass(frozen=True)
class BodyState:
    """A rigid body's world state: frame origin, orientation, centre-of-mass and angular velocity."""

    path: str
    position: tuple[float, float, float]
    quaternion: tuple[float, float, float, float]  # w, x, y, z
    rpy: tuple[float, float, float]  # roll, pitch, yaw (rad), R = Rz(yaw) Ry(pitch) Rx(roll)
    linear_velocity: tuple[float, float, float]
    angular_velocity: tuple[float, float, float]
    geometries: tuple[GeometryInfo, ...] = ()  # with their materials (plxtools.check.api_inspect)


class Simulation:
    """A MuJoCo run of a loaded model that you step yourself (see the module docstring)."""

    def __init__(self, prepared: Prepared):
        import mujoco

        from plxtools.check.mujoco.kinematic import Stepper

        self.prepared = prepared
        self.path = prepared.path
        self.model_name = prepared.model
        self._mj = mujoco
        c = prepared.compiled
        self.model = c.model
        self.data = mujoco.MjData(self.model)
        mujoco.mj_resetDataKeyframe(self.model, self.data, self.model.key("initial").id)
        mujoco.mj_forward(self.model, self.data)
        self.runtime = SignalRuntime.bind(mujoco, c, prepared.signals)
        self._stepper = Stepper(mujoco, c, self.model, self.data)  # the step plx check and plx test take
        # velocity inputs of kinematic bodies, brakes and clutches, range inputs' offsets
        self.runtime.attach_movers(self._stepper.movers, self._stepper.engagements, self._stepper.lag)
        self.timestep = float(self.model.opt.timestep)
        self.steps = 0
        self._pending: list[tuple[str, Any]] = []
        self.sent: dict[str, Any] = {}  # input path -> the last value sent (what `plx view` shows)
        self._stale = False
        self._scene = Scene(self)
        self.frames: dict = {}  # systems moved by place(): their frame now (plxtools.check.api_place)
        self._queue = InputSignalQueue(self)

    # -- the runtime's names ------------------------------------------------------------------

    def scene(self) -> Scene:
        return self._scene

    def getInputSignalQueue(self) -> InputSignalQueue:  # noqa: N802
        return self._queue

    input_queue = getInputSignalQueue

    @property
    def time(self) -> float:
        return self.steps * self.timestep

    @property
    def diagnostics(self) -> list:
        """The check's findings on the model (warnings and mapping notes; errors stop :func:`load`)."""
        return list(self.prepared.fc.diagnostics)

    # -- objects --------------------------------------------------------------------------------

    def get_object(self, path: str) -> SceneObject:
        if not isinstance(path, str):
            raise TypeError(f"an object path is a dotted string, not {type(path).__name__}")
        p = self.prepared
        info = next((i for i in p.signals if i.path == path), None)
        if info is not None:
            cls = Input if info.direction == "input" else Output
            return cls(info.path, info.type, info)
        if path in p.objects:
            return SceneObject(path, p.objects[path])
        raise unknown_path(path, list(p.objects), "object", p.path)

    getObject = get_object  # noqa: N815

    def _signal(self, target: Any, direction: str) -> SignalInfo:
        if isinstance(target, str):
            target = self.get_object(target)
        cls = Input if direction == "input" else Output
        if not isinstance(target, cls):
            what = target.path if isinstance(target, SceneObject) else repr(target)
            raise TypeError(f"{what} is not an {direction} signal")
        if target.path not in self.runtime.bindings:
            raise NotSimulatedError(self.runtime.unbound.get(target.path, f"{target.path} is not simulated"))
        return target.info

    # -- inputs ---------------------------------------------------------------------------------

    def send(self, signal: _InputSignal) -> None:
        """Queue ``signal``; it acts from the next step on."""
        if not isinstance(signal, _InputSignal):
            raise TypeError(f"send() takes an input signal (RealInputSignal.create(value, input)), "
                            f"not {type(signal).__name__}")
        info = self._signal(signal.target, "input")
        want = info.value_kind or "real"
        if signal.kind != want:
            raise SignalValueError(f"{info.path} takes {_kind_text(want)}: send a {_SIGNAL_FOR_KIND[want]}, "
                                   f"not a {signal.type_name}")
        self._send_later(info.path, coerce(info, signal.value))

    def set(self, input_path: str | Input, value: Any) -> None:
        """``send`` of the signal class that fits the input (a number, [min, max] or [x, y, z])."""
        info = self._signal(input_path, "input")
        self._send_later(info.path, coerce(info, value))

    def _send_later(self, path: str, value: Any) -> None:
        """Written at the next step; a value this model cannot take is refused now, where it was sent."""
        why = self.runtime.refusal(path, value)
        if why is not None:
            raise SignalValueError(why)
        self._pending.append((path, value))
        self.sent[path] = value

    # -- stepping -------------------------------------------------------------------------------

    def step(self, duration: float | None = None) -> float:
        """Advance one step, or ``duration`` seconds (rounded to whole steps); returns the time."""
        if duration is None:
            n = 1
        else:
            if isinstance(duration, bool) or not isinstance(duration, (int, float)) or not math.isfinite(duration) \
                    or duration < 0:
                raise ValueError(f"step() takes a duration in seconds >= 0, not {duration!r}")
            n = int(round(duration / self.timestep))
        for _ in range(n):
            self._stepper.step(self.steps, self._hook)
            self.steps += 1
            self._stale = True
        if n == 0:
            self._apply_pending()
        return self.time

    def _hook(self, t: float, m: Any, d: Any) -> None:
        self._apply_pending()

    def _apply_pending(self) -> None:
        for path, value in self._pending:
            self.runtime.write(path, value, self.model, self.data)
        self._pending.clear()

    def _fresh(self) -> None:
        if self._stale:
            self._mj.mj_forward(self.model, self.data)
            self._stale = False

    # -- outputs --------------------------------------------------------------------------------

    def read(self, output: str | Output) -> Any:
        """The current value of an output: a float, or a tuple for vector outputs."""
        info = self._signal(output, "output")
        self._fresh()
        return self.runtime.read(info.path, self.model, self.data)

    def body(self, path: str) -> BodyState:
        """The world state of a rigid body."""
        from plxtools.check.mujoco.kinematic import body_velocity

        if path not in self.prepared.bodies:
            raise unknown_path(path, self.prepared.bodies, "body", self.path)
        name = self.prepared.compiled.names.name("body", path)
        if name is None:
            raise NotSimulatedError(f"the body {path} is not simulated")
        self._fresh()
        mj, m, d = self._mj, self.model, self.data
        bid = m.body(name).id
        v = body_velocity(mj, m, d, self.prepared.compiled, bid)
        t3 = lambda a: tuple(float(x) for x in a)  # noqa: E731
        return BodyState(path, t3(d.xpos[bid]), t3(d.xquat[bid]), rpy_of_mat(d.xmat[bid]), t3(v[3:]), t3(v[:3]),
                         geometries(self.prepared.compiled.scene, path))

    def place(self, path: str = "", position: Any = None, rotation: Any = None) -> None:
        """Move the root model (``""``), a system or a free body so that its frame is at
        ``position`` (x, y, z) with orientation ``rotation`` (w, x, y, z), before or between steps;
        everything under it moves with it, velocities turned with it (``plxtools.check.api_place``)."""
        from plxtools.check.api_place import place

        if not isinstance(path, str):
            raise TypeError(f"a path is a dotted string, not {type(path).__name__}")
        if path and path not in self.prepared.objects:
            raise unknown_path(path, list(self.prepared.objects), "object", self.path)
        self._fresh()
        place(self, path, position, rotation)
        self._stale = True

    def contact_model(self, material1: str, material2: str) -> ContactModelInfo | None:
        """The contact model between two materials (their ``unique_name``), as simulated: friction
        coefficient and model, normal and tangential restitution; None when the scene has none."""
        return contact_model(self.prepared.compiled.scene, material1, material2)

    def connector(self, path: str) -> ConnectorState:
        """A mate connector's world frame now (origin, orientation, main axis, normal)."""
        from plxtools.check.connector_frames import connector_frame
        from plxtools.check.connector_signals import _placed
        from plxtools.check.signals import Unbindable

        p = self.prepared
        qtype = p.objects.get(path)
        if qtype is None:
            raise unknown_path(path, [o for o, t in p.objects.items() if t.endswith("MateConnector")], "connector",
                               p.path)
        obj = next((o for o in p.fc.assembly.owned if o.display == path), None)
        if obj is None or not p.fc.kinds.isa(obj, MATE_CONNECTOR):
            raise TypeError(f"{path} is a {qtype}, not a mate connector")
        frame = connector_frame(p.fc.assembly, p.fc.evaluator, p.fc.kinds, obj)
        if frame is None:
            raise NotSimulatedError(f"{path} has a degenerate frame (see the check's findings)")
        try:
            placed = _placed(self.runtime, frame)
        except Unbindable as exc:
            raise NotSimulatedError(f"{path}: {exc}") from None
        self._fresh()
        return connector_state(self.data, path, placed, frame.body)


def _kind_text(kind: str) -> str:
    return KIND_TEXT.get(kind, kind)


def unknown_path(path: str, candidates: list[str], what: str, file: str) -> SignalPathError:
    hint = did_you_mean(path, candidates)
    msg = f"{file} has no {what} '{path}'"
    if hint:
        msg += f"; did you mean '{hint}'?"
    return SignalPathError(msg, hint)


# subjects of expectations: "<body>.x" and friends, on the body's own outputs
BODY_QUANTITIES = {
    "x": ("position_output", 0), "y": ("position_output", 1), "z": ("position_output", 2),
    "roll": ("rpy_output", 0), "pitch": ("rpy_output", 1), "yaw": ("rpy_output", 2),
    "vx": ("linear_velocity_world_output", 0), "vy": ("linear_velocity_world_output", 1),
    "vz": ("linear_velocity_world_output", 2), "speed": ("linear_velocity_world_output", None),
}
ANGULAR_OUTPUTS = ("AngleOutput", "AngularVelocity1DOutput", "RPYOutput", "AngularVelocity3DOutput")


def component_index(info: SignalInfo, comp: str) -> int | None:
    """The index of a component name (x/y/z, roll/pitch/yaw, min/max) in the output's value."""
    names = COMPONENTS.get(info.value_kind or "", ())
    if comp in names:
        return names.index(comp)
    if info.quantity in RPY_QUANTITIES and comp in RPY_COMPONENTS:
        return RPY_COMPONENTS.index(comp)
    return None
