"""Plain-data intermediate representation of an ASSEMBLED OpenPLX scene.

This is the contract between the scene assembler (instantiation + SNAP, which computes every
pose) and the physics backends (``mujoco_backend``).  It holds no parser or semantic objects,
only numbers, strings and source locations, so it can be built by hand in tests.

Conventions (all SI units, right-handed, Z up):

* Quaternions are ``(w, x, y, z)``.  Positions are metres.
* ``Body.world_pos``/``world_quat`` are the body frame in the world after SNAP.
* ``Geom.pos``/``quat`` are in the owning body's frame and use the **OpenPLX** convention:
  cylinders and capsules lie along their local **Y** axis (the backend rotates them to MuJoCo's
  Z).  ``Box.size`` holds the **full** edge lengths.
* Geometry owned directly by a system (static collision shapes) goes on a ``Body`` with
  ``is_dynamic=False`` whose ``path`` is the owning system's path and whose pose is the system's
  world pose.
* ``Connector.local_pos``/``main_axis``/``normal`` are in the owning body's frame.  When
  ``Connector.body`` is ``None`` (a connector owned by a system, or ``Physics3D.Interactions.World``)
  they are in **world** coordinates: the assembler composes the system transforms.
* Joint coordinates follow the OpenPLX sign convention: q is the motion of ``connectors[1]``
  relative to ``connectors[0]`` about / along the shared main axis (right-hand rule).
* ``Source`` lines and columns are 1-based (0 = unknown).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from plxtools.check.mapped_types import CONTROLLERS, GEOMS, MATES, SCENE_ONLY_GEOMS, scene_geom_kind

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]
Mat3 = tuple[Vec3, Vec3, Vec3]

ZERO3: Vec3 = (0.0, 0.0, 0.0)
IDENTITY_QUAT: Quat = (1.0, 0.0, 0.0, 0.0)
INF = math.inf

# the kinds a scene holds, from the mapped types (check/mapped_types.py)
GEOM_KINDS = (*dict.fromkeys(scene_geom_kind(shape) for shape in GEOMS.values()), *SCENE_ONLY_GEOMS)
MATE_KINDS = tuple(dict.fromkeys(MATES.values()))
CONTROLLER_KINDS = tuple(dict.fromkeys(kind for kind, _dof, _name in CONTROLLERS.values()))
DOF_KINDS = tuple(dict.fromkeys(dof for _kind, dof, _name in CONTROLLERS.values()))
FRICTION_MODELS = (
    "dry",  # DefaultDryFriction
    "dry_cone",
    "dry_box",
    "dry_scale_box",
    "dry_constant_normal_force",
    "dry_depth_scaled_constant_normal_force",
)


@dataclass(frozen=True, slots=True)
class Source:
    """Where an element comes from in the OpenPLX source (1-based; 0 means unknown)."""

    file: str
    line: int
    column: int
    end_line: int = 0
    end_column: int = 0

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


@dataclass(slots=True)
class Geom:
    """One geometry of a body.

    ``kind`` is one of :data:`GEOM_KINDS`.  Size fields by kind:

    * ``box``: ``size`` = full edge lengths (x, y, z);
    * ``sphere``: ``radius``;
    * ``cylinder``: ``radius`` and ``height`` (full length, along local Y);
    * ``capsule``: ``radius`` and ``height`` (length of the inner cylinder, along local Y);
    * ``plane``: infinite, normal = local +Z; ``size`` x/y only set the drawn extent.
      Only valid on static bodies (MuJoCo restriction);
    * ``mesh``: ``mesh_file`` (ExternalTriMeshGeometry; resolved against ``Scene.base_dir`` when
      relative) or ``mesh_vertices``/``mesh_indices`` (ConvexMesh / TriMesh), with ``mesh_scale``.
      ``convex`` is False for TriMesh / external meshes that may be concave.
    """

    path: str
    kind: str
    size: Vec3 = ZERO3
    radius: float = 0.0
    height: float = 0.0
    pos: Vec3 = ZERO3
    quat: Quat = IDENTITY_QUAT
    material: str | None = None  # Material.unique_name
    density: float = 1000.0  # material density, kg/m^3
    enable_collisions: bool = True
    include_in_mass: bool = True
    visual_only: bool = False  # Visuals.Geometries.*: rendered only, no contacts, no mass
    mesh_file: str | None = None
    mesh_scale: Vec3 = (1.0, 1.0, 1.0)
    mesh_vertices: tuple[Vec3, ...] | None = None
    mesh_indices: tuple[int, ...] | None = None
    convex: bool = True
    rgba: tuple[float, float, float, float] | None = None
    source: Source | None = None


@dataclass(slots=True)
class Body:
    """A rigid body (or a system's static geometry holder when ``is_dynamic`` is False).

    Mass properties follow AGX: ``mass > 0`` is used as given; ``mass == 0`` means computed
    from the geometries (density x volume of geoms with ``include_in_mass``).  When
    ``inertia_tensor`` is set (any diagonal element != 0) it is the full tensor about the centre
    of mass, in a CM frame aligned with the body frame.  ``cm_pos`` (body frame) overrides the
    centre of mass; ``None`` means "from the geometries".
    """

    path: str
    world_pos: Vec3 = ZERO3
    world_quat: Quat = IDENTITY_QUAT
    mass: float = 0.0
    inertia_tensor: Mat3 | None = None
    cm_pos: Vec3 | None = None
    is_dynamic: bool = True
    geoms: list[Geom] = field(default_factory=list)
    lin_vel: Vec3 = ZERO3  # initial linear velocity of the body origin, world frame
    ang_vel: Vec3 = ZERO3  # initial angular velocity, world frame
    source: Source | None = None

    @property
    def kinematic(self) -> bool:
        """A non-dynamic body with a velocity: it moves as prescribed, whatever hits it."""
        return not self.is_dynamic and any(v != 0.0 for v in (*self.lin_vel, *self.ang_vel))


@dataclass(slots=True)
class Connector:
    """A MateConnector.  ``body`` is the owning body's path, or None for a world/system connector
    (then the vectors are in world coordinates).  ``normal`` None means "not given": the backend
    picks :func:`default_normal`; the assembler should pass the one it used for SNAP."""

    path: str
    body: str | None
    local_pos: Vec3 = ZERO3
    main_axis: Vec3 = (0.0, 0.0, 1.0)
    normal: Vec3 | None = None
    source: Source | None = None


@dataclass(slots=True)
class Mate:
    """A two-body mate; ``kind`` is one of :data:`MATE_KINDS`.

    ``initial_angle`` / ``initial_position`` are the SNAP offsets already applied to the poses
    (the backend uses them as the joint reference).  ``initial_distance`` is the held distance of
    a Distance mate."""

    path: str
    kind: str
    connectors: tuple[Connector, Connector]
    initial_angle: float = 0.0
    initial_position: float = 0.0
    initial_distance: float = 0.0
    enabled: bool = True
    source: Source | None = None
    target_distance: float | None = None  # Distance: the held distance (None: initial_distance)
    # friction on the free DOF(s), (rotation, translation): a constant limit (N m or N, dry) and a
    # viscous coefficient (N m s/rad or N s/m)
    friction_limit: tuple[float, float] = (0.0, 0.0)
    viscous_friction: tuple[float, float] = (0.0, 0.0)


@dataclass(slots=True)
class Controller:
    """A 1-DOF interaction driving / limiting a mate's free DOF.

    ``kind`` in :data:`CONTROLLER_KINDS`, ``dof`` in :data:`DOF_KINDS`.  Fields used per kind:

    * ``velocity_motor``: ``target_speed``, ``gain``, ``min_effort``/``max_effort``;
    * ``torque_motor`` / ``force_motor``: ``effort`` (default_torque / default_force), clamped
      to ``min_effort``/``max_effort``;
    * ``range``: ``start``/``end`` (in the mate's q);
    * ``spring``: ``stiffness``, ``damping``, ``rest`` (TorsionSpring.angle / LinearSpring.position);
      ``damping_from`` says where the damping comes from (for the report).

    ``user_set`` names the parameters whose value the user's files decide (not a bundle default):
    changing one of those for MuJoCo is a warning, changing a bundle default an info.
    """

    path: str
    kind: str
    dof: str
    connectors: tuple[Connector, Connector]
    target_speed: float = 0.0
    effort: float = 0.0
    gain: float = 1e8
    min_effort: float = -INF
    max_effort: float = INF
    start: float | None = None
    end: float | None = None
    stiffness: float = 1e6
    damping: float = 0.0
    rest: float = 0.0
    damping_from: str = ""
    user_set: frozenset[str] = frozenset()
    enabled: bool = True
    source: Source | None = None


@dataclass(slots=True)
class ContactModel:
    """SurfaceContact.Model for the unordered material pair (material1, material2)."""

    path: str
    material1: str
    material2: str
    friction: float | None = None  # friction coefficient; None = runtime default
    friction_model: str = "dry"  # one of FRICTION_MODELS, anything else is unsupported
    restitution: float | None = None  # normal_restitution
    tangential_restitution: float | None = None
    enabled: bool = True
    source: Source | None = None


@dataclass(slots=True)
class ExcludePair:
    """Disable collisions between two bodies (expanded from CollisionGroup/DisableCollisionPair).
    ``body1 == body2`` is allowed and meaningless (a body never collides with itself)."""

    body1: str
    body2: str
    source: Source | None = None


@dataclass(slots=True)
class Unsupported:
    """Something the assembler met but the backends cannot represent (DriveTrain, Terrain...)."""

    what: str
    path: str
    source: Source | None = None
    message: str = ""


@dataclass(slots=True)
class Shaft:
    """A 1D rotational body (Physics1D.Bodies.RotationalBody, DriveTrain.Shaft): one rotational
    degree of freedom with ``inertia`` (kg m^2), starting at ``angle`` and ``velocity``."""

    path: str
    inertia: float
    angle: float = 0.0
    velocity: float = 0.0
    source: Source | None = None


@dataclass(slots=True)
class ShaftCoupling:
    """``gear``: ``a`` (input shaft) turns ``ratio`` times as fast as ``b`` (output shaft);
    ``actuator``: shaft ``a`` turns with the 3D hinge mate ``b`` (DriveTrain.HingeActuator)."""

    path: str
    kind: str  # gear | actuator
    a: str
    b: str
    ratio: float = 1.0
    source: Source | None = None


@dataclass(slots=True)
class ShaftMotor:
    """A 1D velocity motor (Physics1D.Interactions.RotationalVelocityMotor) or torque motor
    (DriveTrain.TorqueMotor) acting on ``shaft`` against the ground."""

    path: str
    kind: str  # velocity_motor | torque_motor
    shaft: str
    target_speed: float = 0.0
    effort: float = 0.0
    gain: float = 1e8
    min_effort: float = -INF
    max_effort: float = INF
    source: Source | None = None


@dataclass(slots=True)
class ShaftPart:
    """A drive-train part between shafts (check/mujoco/shaft_parts.py).  ``brake``: a friction
    torque of at most ``engagement x capacity`` against ``shafts[0]`` turning (against the ground)
    or, with two shafts, against their relative turning; ``clutch``: the same between two shafts;
    ``differential``: ``shafts`` = (drive, left, right) with ``w_left + w_right = 2 w_drive / ratio``
    (and ``w_left = w_right`` while ``locked``)."""

    path: str
    kind: str  # brake | clutch | differential
    shafts: tuple[str, ...]
    capacity: float = 0.0  # N m, at engagement 1
    engagement: float = 0.0  # the fraction engaged at the start
    ratio: float = 1.0
    locked: bool = False
    automatic: bool = False  # engaged by a boolean input, over these durations (s)
    engage_time: float = 0.0
    release_time: float = 0.0
    source: Source | None = None


@dataclass(slots=True)
class Scene:
    name: str
    bodies: list[Body] = field(default_factory=list)
    mates: list[Mate] = field(default_factory=list)
    controllers: list[Controller] = field(default_factory=list)
    contact_models: list[ContactModel] = field(default_factory=list)
    excludes: list[ExcludePair] = field(default_factory=list)
    gravity: Vec3 = (0.0, 0.0, -9.80665)
    unsupported: list[Unsupported] = field(default_factory=list)
    timestep: float = 0.002
    integrator: str = "auto"  # auto (chosen by the scene, check/mujoco/integrator.py) or a MuJoCo integrator's name
    base_dir: str | None = None  # directory of the root .openplx file (relative mesh paths)
    default_friction: float | None = None  # material pairs without a model; None = backend default
    shafts: list[Shaft] = field(default_factory=list)
    shaft_couplings: list[ShaftCoupling] = field(default_factory=list)
    shaft_motors: list[ShaftMotor] = field(default_factory=list)
    shaft_parts: list[ShaftPart] = field(default_factory=list)
    source: Source | None = None

    def body(self, path: str) -> Body | None:
        for b in self.bodies:
            if b.path == path:
                return b
        return None

    def connectors(self) -> list[Connector]:
        """All connectors referenced by mates and controllers (deduplicated by path)."""
        seen: dict[str, Connector] = {}
        for item in [*self.mates, *self.controllers]:
            for c in item.connectors:
                seen.setdefault(c.path, c)
        return list(seen.values())

    def connector_world(self, c: Connector) -> tuple[Vec3, Vec3, Vec3]:
        """World (position, main_axis, normal) of a connector; axes normalised."""
        axis = normalize(c.main_axis)
        normal = orthogonalize(c.normal if c.normal is not None else default_normal(axis), axis)
        if c.body is None:
            return c.local_pos, axis, normal
        b = self.body(c.body)
        if b is None:
            raise KeyError(f"connector {c.path}: unknown body {c.body}")
        p = quat_rotate(b.world_quat, c.local_pos)
        pos = (p[0] + b.world_pos[0], p[1] + b.world_pos[1], p[2] + b.world_pos[2])
        return pos, quat_rotate(b.world_quat, axis), quat_rotate(b.world_quat, normal)


# --- tiny pure-python helpers (no numpy needed to build or inspect a scene) -------------------


def normalize(v: Vec3) -> Vec3:
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if n == 0.0:
        return (0.0, 0.0, 0.0)
    return (v[0] / n, v[1] / n, v[2] / n)


def orthogonalize(n: Vec3, axis: Vec3) -> Vec3:
    """Gram-Schmidt: ``n`` with its ``axis`` component removed, normalised."""
    d = n[0] * axis[0] + n[1] * axis[1] + n[2] * axis[2]
    return normalize((n[0] - d * axis[0], n[1] - d * axis[1], n[2] - d * axis[2]))


def default_normal(axis: Vec3) -> Vec3:
    """Deterministic unit vector orthogonal to ``axis`` (stand-in for
    ``get_orthogonal_unit_vector``): the world axis least aligned with ``axis``, orthogonalised."""
    a = normalize(axis)
    absd = [abs(a[0]), abs(a[1]), abs(a[2])]
    i = absd.index(min(absd))
    e = [0.0, 0.0, 0.0]
    e[i] = 1.0
    return orthogonalize((e[0], e[1], e[2]), a)


def quat_rotate(q: Quat, v: Vec3) -> Vec3:
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z) or 1.0
    w, x, y, z = w / n, x / n, y / n, z / n
    # v' = v + 2 w (u x v) + 2 u x (u x v)
    cx = y * v[2] - z * v[1]
    cy = z * v[0] - x * v[2]
    cz = x * v[1] - y * v[0]
    ccx = y * cz - z * cy
    ccy = z * cx - x * cz
    ccz = x * cy - y * cx
    return (v[0] + 2 * (w * cx + ccx), v[1] + 2 * (w * cy + ccy), v[2] + 2 * (w * cz + ccz))


def quat_mul(a: Quat, b: Quat) -> Quat:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


def quat_from_axis_angle(axis: Vec3, angle: float) -> Quat:
    a = normalize(axis)
    s = math.sin(angle / 2.0)
    return (math.cos(angle / 2.0), a[0] * s, a[1] * s, a[2] * s)
