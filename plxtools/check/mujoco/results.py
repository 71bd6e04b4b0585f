"""Plain result types of the MuJoCo compile step (shared by compile, simulate and render)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from plxtools.check.mujoco.notes import BackendNote, NameMap
from plxtools.check.scene import Scene

VISUAL_GROUP = 2  # MuJoCo geom group of Visuals.Geometries (rendered, no contacts, no mass)


@dataclass(slots=True)
class MateMonitor:
    """What ``simulate`` needs to measure how well a mate holds (local frames of both sides)."""

    path: str
    kind: str
    body0: str  # MuJoCo body name ("world" for world connectors)
    pos0: np.ndarray
    axis0: np.ndarray
    normal0: np.ndarray
    body1: str
    pos1: np.ndarray
    axis1: np.ndarray
    normal1: np.ndarray
    target_distance: float = 0.0
    role: str = "tree"  # tree | loop | distance | open


@dataclass(slots=True)
class ActuatorInfo:
    path: str  # controller path
    name: str  # MuJoCo actuator name
    kind: str
    mate: str
    joint: str
    gear: float
    ctrl: float
    kv: float | None = None
    target_speed: float | None = None
    # a velocity constraint (mujoco.velocity_constraint): the reference joint its actuator turns
    # and the tendon whose friction force is the motor's effort; None for a servo or a motor
    reference: str | None = None
    tendon: str | None = None
    offset: float = 0.0  # a velocity constraint's constant effort, the middle of its range (velocity_constraint)
    span: float = 1.0  # and the half-width of a one-sided range given to it (velocity_constraint.one_sided_span)


@dataclass(slots=True)
class ShaftCoordinate:
    """Where a drive-train shaft's rotation lives in the MuJoCo model: a shaft of a rigid train
    turns with the train's one joint (``mujoco.drivetrain``), ``factor`` times as fast."""

    joint: str  # MuJoCo joint the shaft turns with (its own, a hinge's, or another shaft's)
    factor: float = 1.0  # shaft speed per joint speed
    offset: float = 0.0  # shaft angle when the joint's coordinate is 0
    rigid: bool = True  # its train is this one coordinate (False: coupled to others by equalities)


@dataclass(slots=True)
class PartInfo:
    """A brake, clutch or differential in the MuJoCo model (``mujoco.shaft_parts``): its friction
    tendon (the bound is engagement x capacity) or its tendon equality, and its lock's."""

    path: str
    kind: str  # brake | clutch | differential
    tendon: str | None  # brake / clutch: the friction tendon (its length: the slip angle)
    capacity: float = 0.0
    engagement: float = 0.0  # at the start
    equality: str | None = None  # differential: w_l + w_r = 2 w_in / ratio
    lock: str | None = None  # differential: w_l = w_r, active while locked up
    locked: bool = False  # at the start
    automatic: bool = False  # engaged by a boolean input over these durations (s)
    engage_time: float = 0.0
    release_time: float = 0.0


@dataclass(slots=True)
class CompiledScene:
    scene: Scene
    spec: Any = None  # mujoco.MjSpec
    model: Any = None  # mujoco.MjModel, None when compilation failed
    notes: list[BackendNote] = field(default_factory=list)
    names: NameMap = field(default_factory=NameMap)
    joints: dict[str, list[str]] = field(default_factory=dict)  # mate path -> MuJoCo joint names
    joint_sign: dict[str, int] = field(default_factory=dict)  # mate path -> +1 / -1
    tree_mates: list[str] = field(default_factory=list)
    loop_mates: list[str] = field(default_factory=list)
    free_roots: list[str] = field(default_factory=list)  # body paths given a free joint
    kinematic: list[str] = field(default_factory=list)  # body paths moved as prescribed (free bodies set every step)
    integrator: str = "implicitfast"  # the MuJoCo integrator the scene runs with (mujoco.integrator.choose)
    integrator_why: str = ""
    prescribed_cache: Any = None  # mujoco.kinematic.prescribed: (model, body id -> prescribed velocity)
    actuators: list[ActuatorInfo] = field(default_factory=list)
    shafts: dict[str, ShaftCoordinate] = field(default_factory=dict)  # shaft path -> its coordinate
    parts: dict[str, PartInfo] = field(default_factory=dict)  # brakes, clutches, differentials by path
    monitors: list[MateMonitor] = field(default_factory=list)
    compile_ms: float = 0.0

    @property
    def ok(self) -> bool:
        return self.model is not None

    def body_name(self, path: str) -> str | None:
        return self.names.name("body", path)
