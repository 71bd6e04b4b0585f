"""From an assembled object tree to the plain scene IR (:mod:`plxtools.check.scene`).

Geometry, mass, controller and contact parameters are read here (once) into small records that the
static checks use too; :func:`to_scene` then builds the IR the MuJoCo backend compiles.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from plxtools.check import scene as S
from plxtools.check.assemble import Assembler, Assembly, Conn, CtrlRec, Kinds, MateRec, Node
from plxtools.check.coverage import not_simulated
from plxtools.check.evaluate import Unavailable
from plxtools.check.frames import IDENTITY, Pose, compose, from_transform, inverse, mat_to_quat_wxyz
from plxtools.check.instance import Obj
from plxtools.check.mapped_types import GEOMS, scene_geom_kind
from plxtools.check.report import Reporter, span_of
from plxtools.rules import registry
from plxtools.check import drivetrain
from plxtools.model.imports import read_obj

# The one home of A031 (missing-file): a mesh file here, a path string in check's scan_strings.


def report_missing_file(rep: Reporter, message: str, **where: Any) -> Any:
    """A031: a file the model names does not exist, placed as ``Reporter.add`` places it."""
    return rep.add(registry.MISSING_FILE, message, **where)


CONTACT_GEOM = "Physics3D.Geometries.ContactGeometry"
# descriptions the runtime turns into many objects, sizing them itself: a track link's length is
# computed from the belt's routing, so its Box has no size.x in the file (the track is A040)
RUNTIME_SIZED = ("Vehicles.Tracks.DefaultLinkDescription",)
VISUAL_GEOM = "Visuals.Geometries.Geometry"
GEOM_KINDS = GEOMS  # type -> shape (check/mapped_types.py)
SURFACE_MODEL = "Physics.Interactions.SurfaceContact.Model"
FRICTION_MODELS = {
    "Physics.Interactions.Dissipation.DryDepthScaledConstantNormalForceFriction":
        "dry_depth_scaled_constant_normal_force",
    "Physics.Interactions.Dissipation.DryConstantNormalForceFriction": "dry_constant_normal_force",
    "Physics.Interactions.Dissipation.DryScaleBoxFriction": "dry_scale_box",
    "Physics.Interactions.Dissipation.DryBoxFriction": "dry_box",
    "Physics.Interactions.Dissipation.DryConeFriction": "dry_cone",
    "Physics.Interactions.Dissipation.DefaultDryFriction": "dry",
}
COLLISION_GROUP = "Simulation.CollisionGroup"
DISABLE_PAIR = "Simulation.DisableCollisionPair"
ENVIRONMENT = "Simulation.Environment"
UNIFORM_GRAVITY = "Simulation.UniformGravitationalField"
POINT_GRAVITY = "Simulation.PointGravitationalField"
LINEAR_ELASTIC = "Physics.Interactions.Flexibility.LinearElastic"
MECH_DAMPING = "Physics.Interactions.Dissipation.MechanicalDamping"
RELAXATION_DAMPING = "Physics.Interactions.Dissipation.ConstraintRelaxationTimeDamping"
DEFAULT_DISSIPATION = "Physics.Interactions.Dissipation.DefaultDissipation"
# "The runtime decides" (DefaultDissipation): AGX damps a constraint with a relaxation time of two
# of its default 60 Hz time steps; the damping coefficient is stiffness x relaxation time.
DEFAULT_RELAXATION_TIME = 2.0 / 60.0


@dataclass(eq=False)
class GeomRec:
    obj: Obj
    node: Node  # the body (or system, for static geometry) it belongs to
    kind: str  # box | sphere | cylinder | capsule | convex_mesh | trimesh | external_mesh
    visual: bool
    pose: Pose = IDENTITY  # in the node frame
    size: np.ndarray = field(default_factory=lambda: np.zeros(3))
    radius: float = 0.0
    height: float = 0.0
    material_key: str | None = None
    material_obj: Obj | None = None
    density: float = 1000.0
    enable_collisions: bool = True
    include_in_mass: bool = True
    mesh_file: str | None = None
    bounds: np.ndarray | None = None  # an external .obj mesh's lowest and highest corner (2x3)
    mesh_scale: np.ndarray = field(default_factory=lambda: np.ones(3))
    vertices: list | None = None
    indices: list | None = None
    valid: bool = True
    failed: bool = False  # a value could not be evaluated (already reported)

    @property
    def path(self) -> str:
        return self.obj.display

    def volume(self) -> float:
        if not self.valid:
            return 0.0
        if self.kind == "box":
            return float(np.prod(self.size))
        if self.kind == "sphere":
            return 4.0 / 3.0 * math.pi * self.radius ** 3
        if self.kind == "cylinder":
            return math.pi * self.radius ** 2 * self.height
        if self.kind == "capsule":
            return math.pi * self.radius ** 2 * self.height + 4.0 / 3.0 * math.pi * self.radius ** 3
        return 1.0 if self.kind in ("convex_mesh", "trimesh", "external_mesh") else 0.0

    def half_extents(self) -> np.ndarray | None:
        """Half extents of the geometry's axis-aligned box in its own frame (None for meshes)."""
        if not self.valid:
            return None
        if self.kind == "box":
            return self.size / 2.0
        if self.kind == "sphere":
            return np.full(3, self.radius)
        if self.kind == "cylinder":
            return np.array([self.radius, self.height / 2.0, self.radius])
        if self.kind == "capsule":
            return np.array([self.radius, self.height / 2.0 + self.radius, self.radius])
        if self.vertices:
            v = np.asarray(self.vertices, dtype=float) * self.mesh_scale
            return np.max(np.abs(v), axis=0)
        if self.bounds is not None:  # an .obj file's bounds
            return np.max(np.abs(self.bounds * self.mesh_scale), axis=0)
        return None


@dataclass(eq=False)
class ContactRec:
    obj: Obj
    m1: Obj | None
    m2: Obj | None
    key1: str | None
    key2: str | None
    enabled: bool = True
    friction: float | None = None
    friction_model: str = "dry"
    restitution: float | None = None
    tangential_restitution: float | None = None


def material_key(ev_get, mat: Obj) -> str:
    name = ev_get(mat, "unique_name", "")
    if isinstance(name, str) and name:
        return name
    return mat.display


class Collector:
    """Reads geometry, mass, controller and contact parameters from the object tree."""

    def __init__(self, asm: Assembly, asmb: Assembler, kinds: Kinds, rep: Reporter):
        self.asm = asm
        self.a = asmb
        self.ev = asmb.ev
        self.k = kinds
        self.rep = rep
        self.geoms: list[GeomRec] = []
        self.contacts: list[ContactRec] = []
        self.groups: list[Obj] = []
        self.pairs: list[Obj] = []
        self.unsupported: list[tuple[str, Obj, str]] = []

    def get(self, obj: Obj, path: str, default: Any = None) -> Any:
        return self.a.get(obj, path, default)

    def real(self, obj: Obj, path: str, default: float) -> float:
        return self.a.real(obj, path, default)

    def run(self) -> None:
        for obj in self.asm.owned:
            if self.asm.node_of(obj) is not None:
                continue
            if self.k.isa(obj, CONTACT_GEOM) or self.k.isa(obj, VISUAL_GEOM):
                if not self._runtime_sized(obj):
                    self._geom(obj)
            elif self.k.isa(obj, SURFACE_MODEL):
                self._contact(obj)
            elif self.k.isa(obj, COLLISION_GROUP):
                self.groups.append(obj)
            elif self.k.isa(obj, DISABLE_PAIR):
                self.pairs.append(obj)

    # ------------------------------------------------------------------ geometry

    def _runtime_sized(self, obj: Obj) -> bool:
        """Is the object part of a description the runtime instantiates and sizes (RUNTIME_SIZED)?"""
        cur = obj.owner
        while cur is not None:
            if any(self.k.isa(cur, q) for q in RUNTIME_SIZED):
                return True
            cur = cur.owner
        return False

    def _geom(self, obj: Obj) -> None:
        visual = not self.k.isa(obj, CONTACT_GEOM)
        kind = self.k.first(obj, GEOM_KINDS)
        node = self.a._parent_node(self.asm, obj)
        if kind is None or node is None:
            if not visual:
                self.unsupported.append((self.a.p.concrete(obj.model).qname, obj,
                                         f"geometry {obj.display} ({self.a.p.concrete(obj.model).qname}) has no "
                                         f"MuJoCo mapping and is ignored"))
            return
        g = GeomRec(obj, node, kind, visual)
        t = self.get(obj, "local_transform", None)
        if t is not None and hasattr(t, "rotation"):
            g.pose = from_transform(t)
        if kind == "box":
            self._box_size(g, obj)
        elif kind in ("sphere", "cylinder", "capsule"):
            self._round_size(g, obj, kind)
        elif kind == "external_mesh":
            self._mesh_file(g, obj, visual)
            self._mesh_scale(g, obj)
        else:
            self._mesh_vertices(g, obj, kind)
        if not visual:
            self._contact_properties(g, obj)
        self.geoms.append(g)

    def _box_size(self, g: "GeomRec", obj: Obj) -> None:
        size = self.a._vec(obj, "size", None)
        if size is None:
            g.valid, g.failed = False, True
            return
        g.size = size
        bad = [f"{a}={v:g}" for a, v in zip("xyz", size) if v <= 0]
        if bad:
            self._bad_size(g, "size", f"box {obj.display} has size {{{', '.join(f'{v:g}' for v in size)}}}: "
                           f"{', '.join(bad)} must be > 0",
                           "a Box's size has no default and is 0, 0, 0 unless assigned; "
                           "give the full edge lengths, e.g. size: {1, 1, 1}")

    def _round_size(self, g: "GeomRec", obj: Obj, kind: str) -> None:
        """A sphere's radius; a cylinder's or capsule's radius and height."""
        r = self._num(obj, "radius")
        if r is None:
            g.valid, g.failed = False, True
        else:
            g.radius = r
            if r <= 0:
                self._bad_size(g, "radius", f"{kind} {obj.display} has radius {r:g}; it must be > 0")
        if kind == "sphere":
            return
        h = self._num(obj, "height")
        if h is None:
            g.valid, g.failed = False, True
            return
        g.height = h
        if (kind == "cylinder" and h <= 0) or (kind == "capsule" and h < 0):
            need = "> 0" if kind == "cylinder" else ">= 0"
            self._bad_size(g, "height", f"{kind} {obj.display} has height {h:g}; it must be {need}")

    def _mesh_file(self, g: "GeomRec", obj: Obj, visual: bool) -> None:
        """An external mesh's file, relative to the file that names it (A031 when it is missing)."""
        p = self.get(obj, "path", None)
        if not (isinstance(p, str) and p):
            g.valid = False
            return
        stmt, unit = self.ev.where(obj, "path")
        base = os.path.dirname(os.path.abspath(unit.path)) if unit is not None else os.getcwd()
        full = p if os.path.isabs(p) else os.path.normpath(os.path.join(base, p))
        g.mesh_file = full
        if full.lower().endswith(".obj") and os.path.isfile(full):
            self._obj_bounds(g, obj, p, visual)
        if not os.path.isfile(full) and unit is not self.rep.unit:
            report_missing_file(self.rep, f"mesh file {p!r} of {obj.display} does not exist ({full})",
                                obj=obj, severity="warning" if visual else None)
        if not os.path.isfile(full):
            g.valid = False

    def _mesh_scale(self, g: "GeomRec", obj: Obj) -> None:
        scale = self.a._vec(obj, "scale", None)
        if scale is None:
            return
        g.mesh_scale = scale
        if np.any(scale <= 0):
            self._bad_size(g, "scale", f"mesh {obj.display} has scale {{{', '.join(f'{v:g}' for v in scale)}}};"
                           f" every component must be > 0")

    def _mesh_vertices(self, g: "GeomRec", obj: Obj, kind: str) -> None:
        """A convex or triangle mesh given by its vertices (and a trimesh's indices)."""
        verts = self.get(obj, "vertices", None)
        if isinstance(verts, list) and verts:
            try:
                g.vertices = [tuple(float(c) for c in np.asarray(v, dtype=float)) for v in verts]
            except (TypeError, ValueError):
                g.valid = False
        else:
            g.valid = False
            self.rep.add(registry.NON_POSITIVE_SIZE, f"mesh {obj.display} has no vertices", obj=obj)
        if kind == "trimesh":
            idx = self.get(obj, "indices", None)
            g.indices = [int(i) for i in idx] if isinstance(idx, list) else None

    def _contact_properties(self, g: "GeomRec", obj: Obj) -> None:
        """What a contact geometry adds: collisions, mass and its material."""
        g.enable_collisions = bool(self.get(obj, "enable_collisions", True))
        g.include_in_mass = bool(self.get(obj, "include_in_mass_properties", True))
        mat = self.get(obj, "material", None)
        if isinstance(mat, Obj):
            g.material_obj = mat
            g.material_key = material_key(self.get, mat)
            g.density = self.real(mat, "density", 1000.0)

    def _obj_bounds(self, g: "GeomRec", obj: Obj, written: str, visual: bool) -> None:
        """An OBJ file's bounds (model/imports.py reads it), so the geometry has extents."""

        info = read_obj(g.mesh_file)
        if info.lo is not None:
            g.bounds = np.array([info.lo, info.hi], dtype=float)
        elif info.problem:
            g.valid = False
            self.rep.add(registry.NON_POSITIVE_SIZE, f"mesh {obj.display}: {written!r} cannot be used: {info.problem}",
                         obj=obj, severity="warning" if visual else None)

    def _num(self, obj: Obj, path: str) -> float | None:
        try:
            v = self.a.value(obj, path)
        except (Unavailable, KeyError):
            return None
        try:
            f = float(v)
        except (TypeError, ValueError):
            return None
        return f if math.isfinite(f) else None

    def _bad_size(self, g: GeomRec, attr: str, message: str, help: str | None = None) -> None:
        g.valid = False
        node, unit = self.ev.where(g.obj, attr)
        self.rep.add(registry.NON_POSITIVE_SIZE, message, node=node, unit=unit, obj=g.obj, help=help)

    # ------------------------------------------------------------------ contacts

    def _contact(self, obj: Obj) -> None:
        m1 = self.get(obj, "material_1", None)
        m2 = self.get(obj, "material_2", None)
        rec = ContactRec(obj, m1 if isinstance(m1, Obj) else None, m2 if isinstance(m2, Obj) else None,
                         material_key(self.get, m1) if isinstance(m1, Obj) else None,
                         material_key(self.get, m2) if isinstance(m2, Obj) else None)
        rec.enabled = bool(self.get(obj, "enabled", True))
        fr = self.ev.child(obj, "friction")
        if isinstance(fr, Obj):
            model = self.k.first(fr, FRICTION_MODELS)
            if model is not None:
                rec.friction_model = model
                c = self.get(fr, "coefficient", None)
                rec.friction = float(c) if isinstance(c, (int, float)) else None
            elif self.a.p.concrete(fr.model).qname != "Physics.Interactions.Dissipation.DefaultFriction":
                rec.friction_model = self.a.p.concrete(fr.model).qname
        for attr, name in (("normal_restitution", "restitution"), ("tangential_restitution", "tangential_restitution")):
            v = self.get(obj, attr, None)
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                setattr(rec, name, float(v))
        self.contacts.append(rec)

    # ------------------------------------------------------------------ collision groups

    def group_bodies(self, group: Obj) -> list[Node]:
        out: list[Node] = []

        def add(n: Node | None) -> None:
            if n is not None and n.kind == "body" and n not in out:
                out.append(n)

        for item in self.get(group, "bodies", []) or []:
            if isinstance(item, Obj):
                add(self.asm.node_of(item))
        for item in self.get(group, "systems", []) or []:
            if isinstance(item, Obj):
                top = self.asm.node_of(item)
                for n in self.asm.nodes:
                    cur = n
                    while cur is not None and cur is not top:
                        cur = cur.parent
                    if cur is top and top is not None:
                        add(n)
        for item in self.get(group, "geometries", []) or []:
            if isinstance(item, Obj):
                add(self.a._parent_node(self.asm, item))
        return out

    def exclude_pairs(self) -> list[tuple[Node, Node, Obj]]:
        out = []
        for pair in self.pairs:
            g1, g2 = self.get(pair, "group1", None), self.get(pair, "group2", None)
            if not isinstance(g1, Obj) or not isinstance(g2, Obj):
                continue
            b1, b2 = self.group_bodies(g1), self.group_bodies(g2)
            for x in b1:
                for y in b2:
                    out.append((x, y, pair))
        return out


# ---------------------------------------------------------------------- scene IR


def _source(rep: Reporter, obj: Obj | None, node: Any = None, unit: Any = None) -> S.Source:
    sp = rep.locate(node, unit, obj)
    return S.Source(rep.file, sp.start.line + 1, sp.start.column + 1, sp.end.line + 1, sp.end.column + 1)


def _t3(v) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def to_scene(asm: Assembly, col: Collector, rep: Reporter, base_dir: str | None) -> S.Scene:
    """The scene IR of an assembled tree: bodies with their geometry, then mates, controllers,
    contact models, excluded pairs, gravity and what is not supported."""
    scene = S.Scene(asm.root.model.name, base_dir=base_dir, source=_source(rep, asm.root))
    scene.bodies = _bodies(asm, col, rep)
    conns = _Connectors(asm, rep, {b.path for b in scene.bodies})
    scene.mates = [_mate(col, m, conns, rep) for m in asm.mates if m.usable and m.kind != "unknown"]
    scene.controllers = [_controller(col, c, conns, rep) for c in asm.controllers
                         if len(c.conns) == 2 and all(x is not None for x in c.conns)
                         and c.mate is not None and c.mate.usable]
    scene.contact_models = [S.ContactModel(cr.obj.display, cr.key1, cr.key2, cr.friction, cr.friction_model,
                                           cr.restitution, cr.tangential_restitution, cr.enabled, _source(rep, cr.obj))
                            for cr in col.contacts if cr.key1 is not None and cr.key2 is not None]
    scene.excludes = _excludes(col, rep)

    scene.shafts, scene.shaft_couplings, scene.shaft_motors, scene.shaft_parts = drivetrain.collect(
        asm, col, rep, _source, {m.path for m in scene.mates if m.kind in ("hinge", "cylindrical")})
    gravity = _gravity(asm, col)
    if gravity is not None:
        scene.gravity = gravity
    scene.unsupported = [S.Unsupported(what, obj.display, _source(rep, obj), msg) for what, obj, msg in col.unsupported]
    return scene


def _geoms(recs: list[GeomRec], rep: Reporter) -> list[S.Geom]:
    out = []
    for g in recs:
        if not g.valid:
            continue
        sg = S.Geom(g.path, scene_geom_kind(g.kind), pos=_t3(g.pose[1]),
                    quat=mat_to_quat_wxyz(g.pose[0]), visual_only=g.visual, source=_source(rep, g.obj))
        if g.kind == "box":
            sg.size = _t3(g.size)
        elif g.kind in ("sphere", "cylinder", "capsule"):
            sg.radius, sg.height = g.radius, g.height
        else:
            sg.mesh_file = g.mesh_file
            sg.mesh_scale = _t3(g.mesh_scale)
            sg.mesh_vertices = tuple(g.vertices) if g.vertices else None
            sg.mesh_indices = tuple(g.indices) if g.indices else None
            sg.convex = g.kind == "convex_mesh"
        if not g.visual:
            sg.material = g.material_key
            sg.density = g.density
            sg.enable_collisions = g.enable_collisions
            sg.include_in_mass = g.include_in_mass
        out.append(sg)
    return out


def _bodies(asm: Assembly, col: Collector, rep: Reporter) -> list[S.Body]:
    """Rigid bodies, and systems that own geometry directly (as static bodies)."""
    by_node: dict[int, list[GeomRec]] = {}
    for g in col.geoms:
        by_node.setdefault(id(g.node), []).append(g)
    out = []
    for n in asm.nodes:
        geoms = _geoms(by_node.get(id(n), []), rep)
        if n.kind == "body":
            out.append(_body(n, col, geoms, rep))
        elif geoms:
            out.append(S.Body(n.path, _t3(n.world[1]), mat_to_quat_wxyz(n.world[0]), is_dynamic=False, geoms=geoms,
                              source=_source(rep, n.obj)))
    return out


def _body(n: Node, col: Collector, geoms: list[S.Geom], rep: Reporter) -> S.Body:
    a, obj = col.a, n.obj
    mass = a.real(obj, "inertia.mass", 0.0)
    tensor = None
    t = a.get(obj, "inertia.tensor", None)
    if isinstance(t, np.ndarray) and t.shape == (3, 3) and np.all(np.isfinite(t)) and np.any(np.diag(t) != 0):
        tensor = tuple(tuple(float(x) for x in row) for row in t)
    cm = None
    cmo = col.ev.child(obj, "kinematics.local_cm_transform")
    if isinstance(cmo, Obj) and cmo.explicit:
        tr = a.get(obj, "kinematics.local_cm_transform", None)
        if tr is not None and hasattr(tr, "position"):
            cm = _t3(tr.position)
    pw = n.parent.world if n.parent is not None else IDENTITY
    lv = a._vec(obj, "kinematics.initial_local_linear_velocity", np.zeros(3))
    av = a._vec(obj, "kinematics.initial_local_angular_velocity", np.zeros(3))
    return S.Body(n.path, _t3(n.world[1]), mat_to_quat_wxyz(n.world[0]), mass=mass, inertia_tensor=tensor, cm_pos=cm,
                  is_dynamic=n.is_dynamic, geoms=geoms, lin_vel=_t3(pw[0] @ lv), ang_vel=_t3(pw[0] @ av),
                  source=_source(rep, obj))


class _Connectors:
    """Scene connectors, one per connector object, in the frame of the body they move with (a
    redirected connector: its ``redirected_parent``), or in world coordinates."""

    def __init__(self, asm: Assembly, rep: Reporter, body_paths: set[str]):
        self.asm, self.rep, self.body_paths = asm, rep, body_paths
        self.made: dict[int, S.Connector] = {}

    def get(self, c: Conn) -> S.Connector:
        sc = self.made.get(id(c.obj))
        if sc is None:
            sc = self.made[id(c.obj)] = self._make(c)
        return sc

    def _make(self, c: Conn) -> S.Connector:
        src = _source(self.rep, c.obj)
        owner: Node = c.node
        attach = self.asm.node_of(c.redirected_parent) if c.redirected_parent is not None else None
        if attach is None:
            attach = owner if owner.kind == "body" else None
        frame_world = compose(owner.world, c.frame)
        if attach is None or attach.path not in self.body_paths:
            return S.Connector(c.obj.display, None, _t3(frame_world[1]), _t3(frame_world[0][:, 2]),
                               _t3(frame_world[0][:, 0]), src)
        local = compose(inverse(attach.world), frame_world)
        return S.Connector(c.obj.display, attach.path, _t3(local[1]), _t3(local[0][:, 2]), _t3(local[0][:, 0]), src)


CONSTANT_LIMIT_FRICTION = "Physics.Interactions.Dissipation.ConstantLimitFriction"
VISCOUS_FRICTION = "Physics.Interactions.Dissipation.ConstantViscousSurfaceFriction"
MATE_FRICTION = {"hinge": (("friction", 0),), "prismatic": (("friction", 1),),
                 "cylindrical": (("friction_rotational", 0), ("friction_translational", 1))}


def _mate(col: Collector, m: MateRec, conns: _Connectors, rep: Reporter) -> S.Mate:
    sm = S.Mate(m.path, m.kind, (conns.get(m.conns[0]), conns.get(m.conns[1])), m.initial_angle,
                m.initial_position, m.initial_distance, m.enabled, _source(rep, m.obj))
    if m.kind == "distance":
        sm.target_distance = col.a.real(m.obj, "target_distance", m.initial_distance)
    limit, viscous = [0.0, 0.0], [0.0, 0.0]
    for attr, k in MATE_FRICTION.get(m.kind, ()):
        fr = col.ev.child(m.obj, attr)
        if not isinstance(fr, Obj):
            continue
        if col.k.isa(fr, CONSTANT_LIMIT_FRICTION):
            limit[k] = col.a.real(fr, "limit", 0.0)
        elif col.k.isa(fr, VISCOUS_FRICTION):
            viscous[k] = col.a.real(fr, "viscosity", 0.0)
        elif fr.model.qname.rsplit(".", 1)[-1] != "DefaultFriction":
            node, unit = (fr.decl[0].stmt, fr.decl[0].unit) if fr.decl else (None, None)
            not_simulated(rep, f"{m.path}.{attr} is {fr.model.qname}, which the MuJoCo backend does not simulate on "
                          "a joint (ConstantLimitFriction and ConstantViscousSurfaceFriction are); the joint turns "
                          "freely", node=node, unit=unit, obj=m.obj, severity="warning")
    for k in (0, 1):
        if not (math.isfinite(limit[k]) and limit[k] >= 0) or not (math.isfinite(viscous[k]) and viscous[k] >= 0):
            node, unit = col.ev.where(m.obj, MATE_FRICTION[m.kind][0][0])
            rep.add(registry.INVALID_CONTACT_PARAMETER, f"{m.path}: joint friction must be a finite number >= 0 (limit {limit[k]:g}, viscosity "
                    f"{viscous[k]:g}); it is left out", node=node, unit=unit, obj=m.obj)
            limit[k] = viscous[k] = 0.0
    sm.friction_limit, sm.viscous_friction = (limit[0], limit[1]), (viscous[0], viscous[1])
    return sm


def _controller(col: Collector, c: CtrlRec, conns: _Connectors, rep: Reporter) -> S.Controller:
    a, obj = col.a, c.obj
    sc = S.Controller(c.path, c.kind, c.dof, (conns.get(c.conns[0]), conns.get(c.conns[1])), source=_source(rep, obj))
    sc.enabled = bool(a.get(obj, "enabled", True))
    sc.min_effort = a.real(obj, "min_effort", -math.inf)
    sc.max_effort = a.real(obj, "max_effort", math.inf)
    if c.kind == "velocity_motor":
        sc.target_speed = a.real(obj, "target_speed", 0.0)
        sc.gain = a.real(obj, "gain", 1e8)
    elif c.kind == "torque_motor":
        sc.effort = a.real(obj, "default_torque", 0.0)
    elif c.kind == "force_motor":
        sc.effort = a.real(obj, "default_force", 0.0)
    elif c.kind == "range":
        sc.start = a.real(obj, "start", math.nan)
        sc.end = a.real(obj, "end", math.nan)
        if not math.isfinite(sc.start) or not math.isfinite(sc.end):
            sc.start = sc.end = None
    elif c.kind == "spring":
        sc.rest = a.real(obj, "angle" if c.dof == "rotational" else "position", 0.0)
        fl = col.ev.child(obj, "flexibility")
        if isinstance(fl, Obj) and col.k.isa(fl, LINEAR_ELASTIC):
            sc.stiffness = a.real(fl, "stiffness", 1e6)
        _spring_damping(col, obj, sc, rep)
    sc.user_set = frozenset(n for n in ("gain", "flexibility.stiffness", "target_speed")
                            if _user_set(col, obj, n))
    return sc


def _user_set(col: Collector, obj: Obj, path: str) -> bool:
    """True when the value at ``path`` is decided by a statement outside the official bundles."""
    _, unit = col.ev.where(obj, path)
    return unit is not None and not getattr(unit, "official", False)


def _spring_damping(col: Collector, obj: Obj, sc: S.Controller, rep: Reporter) -> None:
    """The damping coefficient a spring's ``dissipation`` stands for (N s/m or N m s/rad)."""
    ds = col.ev.child(obj, "dissipation")
    k = sc.stiffness
    if not isinstance(ds, Obj):
        sc.damping, sc.damping_from = 0.0, "no dissipation"
    elif col.k.isa(ds, MECH_DAMPING):
        sc.damping = col.a.real(ds, "damping_constant", 0.0)
        sc.damping_from = "MechanicalDamping.damping_constant"
    elif col.k.isa(ds, RELAXATION_DAMPING):
        tau = col.a.real(ds, "relaxation_time", 0.0)
        sc.damping = k * tau if math.isfinite(tau) and tau > 0 else -1.0
        sc.damping_from = f"relaxation time {tau:g} s x stiffness {k:g}"
    elif col.k.isa(ds, "Physics.Interactions.Dissipation.DefaultFriction"):
        sc.damping, sc.damping_from = 0.0, "none (friction on a spring is not simulated)"
        not_simulated(rep, f"{obj.display}: {ds.model.qname} on a spring is not simulated by the MuJoCo "
                      "backend (no damping used)", obj=ds, severity="warning")
    else:  # DefaultDissipation: the runtime's choice
        sc.damping = k * DEFAULT_RELAXATION_TIME
        sc.damping_from = (f"default dissipation: AGX's relaxation time {DEFAULT_RELAXATION_TIME:.4g} s x "
                           f"stiffness {k:g}")


def _excludes(col: Collector, rep: Reporter) -> list[S.ExcludePair]:
    out = []
    seen: set[tuple[str, str]] = set()
    for x, y, pair in col.exclude_pairs():
        key = tuple(sorted((x.path, y.path)))
        if key not in seen:
            seen.add(key)
            out.append(S.ExcludePair(x.path, y.path, _source(rep, pair)))
    return out


def _gravity(asm: Assembly, col: Collector) -> tuple[float, float, float] | None:
    """The uniform gravity of a Simulation.Environment root, or None (the scene's default)."""
    if not col.k.isa(asm.root, ENVIRONMENT):
        return None
    g = col.ev.child(asm.root, "gravity")
    if isinstance(g, Obj) and col.k.isa(g, UNIFORM_GRAVITY):
        vec = col.a._vec(g, "vector", None)
        if vec is not None:
            return _t3(vec)
    return None


__all__ = ["Collector", "ContactRec", "GeomRec", "to_scene", "span_of", "MateRec", "CtrlRec"]
