"""SNAP: compute the initial world pose of every system and body from declared transforms and mates.

Decisions (spec D.5, D.6):

* **Nodes** are the owned systems (``Physics3D.System``) and rigid bodies below the root.  A node's
  pose is relative to the nearest enclosing node.  The root is at the world origin.
* **Declared transform**: a node whose ``local_transform`` (systems) or
  ``kinematics.local_transform`` (bodies) has any value routed into it from outside its own type:
  an assignment to the transform or to any part of it (``kinematics.local_transform.position.z:
  1.1``), anywhere in the chain of models and blocks that configure the node.  Such nodes are never
  moved by SNAP.
* **Connector frame**: z = main_axis normalised; x = normal with its main_axis component removed,
  normalised; y = z x x.  A connector belongs to the nearest enclosing node; a const connector
  (``Physics3D.Interactions.World``) or one on the root is fixed to the world.
* **Mates** are taken in declaration order (depth first over the owned tree).  Each sweep places,
  for the first mate that can fire, the *highest* undeclared node on the path from the mate's
  closest common ancestor system down to the owner of its unplaced connector, so that
  ``F(connectors[1]) = F(connectors[0]) * Offset`` with ``Offset = Rz(initial_angle) *
  Tz(initial_position)`` (hinge / prismatic / cylindrical; ``Tz(initial_distance)`` for a Distance).
  A sweep first fires only mates with exactly one unplaced node on that path; then mates that need
  lower unplaced nodes on the path (those keep identity); then, when nothing can fire, it forces
  the common system's ``reference_body`` (or else the nodes above ``connectors[0]``) to identity.
  ``enable_snap: false`` and disabled mates take no part.
* Nodes still unplaced at the end keep identity in their parent.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from plxtools.check.evaluate import Evaluator, Unavailable, report_non_finite
from plxtools.check.frames import (IDENTITY, Pose, angle_between, compose, from_transform, inverse, orthogonal_unit,
                                   rot_z, rotation_angle)
from plxtools.check.instance import Obj, walk_owned
from plxtools.check.mapped_types import CONTROLLERS, FREE_DOFS, MATES
from plxtools.check.report import Reporter
from plxtools.model.program import Program
from plxtools.rules import registry


# The codes this module raises (their home); the MuJoCo build names them when a hand-built scene
# breaks what the assembler guarantees, the pipeline knows A016's scene is as written.

SYSTEM = "Physics3D.System"
RIGID_BODY = "Physics3D.Bodies.RigidBody"
BODY3D = "Physics3D.Bodies.Body"
MATE = "Physics3D.Interactions.Mate"
CONNECTOR = "Physics3D.Interactions.MateConnector"
REDIRECTED = "Physics3D.Interactions.RedirectedMateConnector"
ADAPTIVE = "Physics3D.Interactions.AdaptiveMateConnector"
I1DOF = "Physics.Interactions.Interaction1DOF"
INTERACTION = "Physics.Interactions.Interaction"

# the mapped types (check/mapped_types.py), as the assembler reads them
MATE_KINDS = MATES
CONTROLLER_KINDS = {qn: (kind, dof) for qn, (kind, dof, _name) in CONTROLLERS.items()}  # type -> (kind, dof)
DOF_OF_MATE = {kind: set(dofs) for kind, dofs in FREE_DOFS.items()}
# attributes where an infinity means "no limit" (Math.INF, Math.NEG_INF in the bundles); NaN is never allowed
MAY_BE_INFINITE = frozenset({"min_effort", "max_effort", "start", "end"})
POS_TOL = 1e-4  # m
ANGLE_TOL = 1e-3  # rad


class Kinds:
    """Subtype tests against bundle types by qualified name, cached."""

    def __init__(self, program: Program):
        self.p = program
        self._syms: dict[str, Any] = {}
        self._cache: dict[tuple, bool] = {}

    def sym(self, qname: str):
        if qname not in self._syms:
            self._syms[qname] = self.p.lookup_outside_visibility(qname.split("."))
        return self._syms[qname]

    def isa(self, obj: Obj, qname: str) -> bool:
        key = (id(obj.model), qname) if not obj.traits else (id(obj.model), tuple(id(t) for t in obj.traits), qname)
        hit = self._cache.get(key)
        if hit is None:
            sym = self.sym(qname)
            hit = sym is not None and self.p.is_subtype(obj.model, sym, tuple(obj.traits))
            self._cache[key] = hit
        return hit

    def first(self, obj: Obj, table: dict) -> Any:
        """The value of the first qualified name in ``table`` that ``obj`` is a subtype of, most
        derived first (tables list leaf types)."""
        for qn, v in table.items():
            if self.isa(obj, qn):
                return v
        return None

    def root_namespace(self, obj: Obj) -> str:
        m = self.p.concrete(obj.model)
        return m.qname.split(".")[0]


class Placement(enum.Enum):
    """How SNAP gave a node its pose (state, read by the checks and reports; text only for display)."""

    PENDING = "pending"
    ROOT = "root"
    DECLARED = "declared"  # a declared transform; ``via`` = " at line N" or ""
    SNAP = "snap"  # moved so that mate ``via`` holds
    MOVED_WITH = "moved_with"  # identity, carried by node ``via`` that mate ``via2`` placed
    REFERENCE_BODY = "reference_body"  # identity as the reference_body of system ``via``
    FORCED = "forced"  # identity so that SNAP can go on from mate ``via``
    UNPLACED = "unplaced"  # nothing places it: identity in its parent


@dataclass(eq=False)
class Node:
    obj: Obj
    kind: str  # "system" | "body"
    parent: "Node | None"
    index: int
    local: Pose | None = None
    explicit: bool = False
    explicit_where: tuple = (None, None)  # (stmt, unit) of the declaring statement
    placement: Placement = Placement.PENDING
    via: str = ""  # the mate, system or line the placement names
    via2: str = ""
    world: Pose | None = None
    is_dynamic: bool = True

    @property
    def path(self) -> str:
        return self.obj.display

    def place(self, how: Placement, via: str = "", via2: str = "") -> None:
        self.placement, self.via, self.via2 = how, via, via2

    @property
    def placed_by(self) -> str:
        """Display text of the placement (reports, JSON); never parsed."""
        p = self.placement
        if p is Placement.ROOT:
            return "root (world origin)"
        if p is Placement.DECLARED:
            return "declared transform" + self.via
        if p is Placement.SNAP:
            return f"SNAP, by mate {self.via}"
        if p is Placement.MOVED_WITH:
            return f"identity, moved with {self.via} (placed by {self.via2})"
        if p is Placement.REFERENCE_BODY:
            return f"identity: reference_body of {self.via}, placed first"
        if p is Placement.FORCED:
            return f"identity: forced so that SNAP can go on from mate {self.via}"
        if p is Placement.UNPLACED:
            return "not placed: no declared transform and no mate fixes it (identity)"
        return ""


@dataclass(eq=False)
class Conn:
    obj: Obj
    node: Node  # the node whose frame the connector is given in
    frame: Pose  # connector frame in the node's frame
    main_axis: np.ndarray  # as given (owner frame)
    normal: np.ndarray  # as used (orthogonalised, unit)
    ok: bool = True
    redirected_parent: Obj | None = None


@dataclass(eq=False)
class MateRec:
    obj: Obj
    kind: str  # scene kind or "unknown"
    conns: list  # list[Conn | None]
    enabled: bool = True
    snap: bool = True
    initial_angle: float = 0.0
    initial_position: float = 0.0
    initial_distance: float = 0.0
    usable: bool = True  # two distinct, valid connectors on different owners
    placed: str = ""  # which node this mate placed (SNAP), if any
    separation: float = 0.0
    misalignment: float = 0.0

    @property
    def path(self) -> str:
        return self.obj.display

    def offset(self) -> Pose:
        r = rot_z(self.initial_angle) if self.kind in ("hinge", "cylindrical") else np.eye(3)
        dz = 0.0
        if self.kind in ("prismatic", "cylindrical"):
            dz = self.initial_position
        elif self.kind == "distance":
            dz = self.initial_distance
        return r, np.array([0.0, 0.0, dz])


@dataclass(eq=False)
class CtrlRec:
    obj: Obj
    kind: str
    dof: str
    conns: list
    mate: MateRec | None = None
    reversed: bool = False

    @property
    def path(self) -> str:
        return self.obj.display


@dataclass(eq=False)
class Assembly:
    root: Obj
    root_node: Node
    nodes: list[Node] = field(default_factory=list)
    by_obj: dict[int, Node] = field(default_factory=dict)
    mates: list[MateRec] = field(default_factory=list)
    controllers: list[CtrlRec] = field(default_factory=list)
    conns: dict[int, Conn] = field(default_factory=dict)
    owned: list[Obj] = field(default_factory=list)
    other_interactions: list[Obj] = field(default_factory=list)
    broken: list[Obj] = field(default_factory=list)  # mates / controllers whose connectors failed to evaluate

    def mover(self, c: Conn) -> Node:
        """The node a connector moves with: its ``redirected_parent``'s (a RedirectedMateConnector
        is given in its owner's frame but attached to another body), else its owner's."""
        if c.redirected_parent is not None:
            n = self.node_of(c.redirected_parent)
            if n is not None:
                return n
        return c.node

    def node_of(self, obj: Obj) -> Node | None:
        return self.by_obj.get(id(obj))

    def owner_node(self, obj: Obj) -> Node | None:
        """The nearest placed node that owns ``obj`` (None: it belongs to no node, like ``World``)."""
        cur = obj.owner
        while cur is not None:
            n = self.node_of(cur)
            if n is not None:
                return n
            cur = cur.owner
        return None

    def conn_world(self, c: Conn) -> Pose:
        return compose(c.node.world, c.frame)

    @property
    def bodies(self) -> list[Node]:
        return [n for n in self.nodes if n.kind == "body"]


def _where_text(rep: Reporter, node_unit: tuple) -> str:
    stmt, unit = node_unit
    if stmt is not None and unit is rep.unit:
        return f" at line {stmt.header.start.line + 1}"
    return ""


class Assembler:
    def __init__(self, program: Program, ev: Evaluator, rep: Reporter, kinds: Kinds):
        self.p = program
        self.ev = ev
        self.rep = rep
        self.k = kinds
        self._non_finite_seen: set[tuple[int, str]] = set()

    # ------------------------------------------------------------------ helpers

    def value(self, obj: Obj, path: str) -> Any:
        """``ev.get`` for everything assembly reads: a non-finite number (``1e308 * 10``, ``inf - inf``)
        is an error at its source line (A041) and the value is then unavailable, so no NaN or inf
        reaches SNAP, the scene or MuJoCo.  Infinity stays allowed where it means "no limit"."""
        v = self.ev.get(obj, path)
        if v is None or isinstance(v, (Obj, str, bool)):
            return v
        bad = _non_finite(v)
        if bad is not None and not (bad == "infinite" and path.rsplit(".", 1)[-1] in MAY_BE_INFINITE):
            key = (id(obj), path)
            if key not in self._non_finite_seen:
                self._non_finite_seen.add(key)
                node, unit = self.ev.where(obj, path)
                report_non_finite(self.rep, f"{obj.display}.{path} is {bad}; a value must be a finite number",
                                  node=node, unit=unit, obj=obj,
                                  help="check the expression for an overflow (a result beyond 1.8e308) or inf - inf")
            raise Unavailable(f"{obj.display}.{path} is {bad}")
        return v

    def get(self, obj: Obj, path: str, default: Any = None) -> Any:
        try:
            return self.value(obj, path)
        except Unavailable:
            return default
        except KeyError:
            return default

    def real(self, obj: Obj, path: str, default: float) -> float:
        v = self.get(obj, path, default)
        try:
            return float(v)
        except (TypeError, ValueError):
            return default

    # ------------------------------------------------------------------ build

    def run(self, root: Obj) -> Assembly:
        owned = list(walk_owned(root))
        root_kind = "body" if self.k.isa(root, RIGID_BODY) else "system"
        root_node = Node(root, root_kind, None, 0, IDENTITY, True, (None, None), Placement.ROOT)
        asm = Assembly(root, root_node, owned=owned)
        asm.nodes.append(root_node)
        asm.by_obj[id(root)] = root_node
        mates: list[Obj] = []
        ctrls: list[Obj] = []
        for obj in owned[1:]:
            kind = None
            if self.k.isa(obj, SYSTEM):
                kind = "system"
            elif self.k.isa(obj, RIGID_BODY):
                kind = "body"
            if kind is not None:
                parent = self._parent_node(asm, obj)
                node = Node(obj, kind, parent, len(asm.nodes))
                asm.nodes.append(node)
                asm.by_obj[id(obj)] = node
                if kind == "body" and parent is not None and parent.kind != "system":
                    self.rep.add(registry.BODY_NOT_IN_SYSTEM, f"rigid body {obj.display} is owned by {obj.owner.display}, which is not "
                                 f"a Physics3D.System; bodies must sit directly in a system", obj=obj,
                                 help="move the body into the system and join it with a mate (Lock)")
                elif kind == "body" and obj.owner is not None and asm.node_of(obj.owner) is None \
                        and obj.owner is not root:
                    self.rep.add(registry.BODY_NOT_IN_SYSTEM, f"rigid body {obj.display} is owned by {obj.owner.display}, which is not "
                                 f"a Physics3D.System; bodies must sit directly in a system", obj=obj)
                continue
            if self.k.isa(obj, MATE):
                mates.append(obj)
            elif self.k.isa(obj, I1DOF) and self.k.first(obj, {k: True for k in CONTROLLER_KINDS}):
                ctrls.append(obj)
            elif self.k.isa(obj, INTERACTION):
                asm.other_interactions.append(obj)
        for node in asm.nodes[1:]:
            self._declared(node)
        self._kinematically_controlled(asm)
        for m in mates:
            asm.mates.append(self._mate(asm, m))
        for c in ctrls:
            asm.controllers.append(self._controller(asm, c))
        self._snap(asm)
        self._world(asm)
        self._violations(asm)
        return asm

    def _parent_node(self, asm: Assembly, obj: Obj) -> Node | None:
        n = asm.owner_node(obj)
        return n if n is not None else asm.root_node

    def _kinematically_controlled(self, asm: Assembly) -> None:
        """``System.kinematically_controlled: [bodies]`` (deprecated in 0.19, still honoured by AGX's
        importers) makes those bodies kinematic, as ``is_dynamic: false`` does."""
        for node in asm.nodes:
            if node.kind != "system":
                continue
            listed = self.get(node.obj, "kinematically_controlled", None)
            if not isinstance(listed, (list, tuple)):
                continue
            for item in listed:
                target = asm.node_of(item) if isinstance(item, Obj) else None
                if target is not None and target.kind == "body":
                    target.is_dynamic = False

    def _declared(self, node: Node) -> None:
        obj = node.obj
        path = "local_transform" if node.kind == "system" else "kinematics.local_transform"
        lt = self.ev.child(obj, path)
        if node.kind == "body":
            node.is_dynamic = bool(self.get(obj, "is_dynamic", True))
        if isinstance(lt, Obj) and lt.struct is not None and lt.explicit:
            node.explicit = True
            node.explicit_where = self.ev.where(obj, path)
            try:
                t = self.value(obj, path)
                node.local = from_transform(t)
            except (Unavailable, KeyError, AttributeError):
                node.local = IDENTITY
            node.place(Placement.DECLARED, _where_text(self.rep, node.explicit_where))
            if not np.all(np.isfinite(node.local[1])):
                node.local = IDENTITY

    # ------------------------------------------------------------------ connectors, mates

    def connector(self, asm: Assembly, obj: Obj) -> Conn | None:
        c = asm.conns.get(id(obj))
        if c is not None:
            return c
        if not self.k.isa(obj, CONNECTOR):
            self.rep.add(registry.CONNECTOR_COUNT, f"{obj.display} is not a Physics3D.Interactions.MateConnector", obj=obj)
            return None
        node = self._parent_node(asm, obj) if obj.owner is not None else asm.root_node
        if node is None:
            node = asm.root_node
        pos = self._vec(obj, "position", np.zeros(3))
        axis = self._vec(obj, "main_axis", np.array([0.0, 0.0, 1.0]))
        normal = self._vec(obj, "normal", None)
        ok = True
        n_axis = float(np.linalg.norm(axis))
        if n_axis < 1e-9:
            node_, unit_ = self.ev.where(obj, "main_axis")
            self.rep.add(registry.ZERO_MAIN_AXIS, f"connector {obj.display} has a zero main_axis", node=node_, unit=unit_, obj=obj,
                         help="give the axis the joint turns about or slides along, e.g. main_axis: {0, 0, 1}")
            z = np.array([0.0, 0.0, 1.0])
            ok = False
        else:
            z = axis / n_axis
        x = None
        if normal is not None and ok:
            nn = float(np.linalg.norm(normal))
            x = orthogonal_unit(normal, z)
            if x is None:
                node_, unit_ = self.ev.where(obj, "normal")
                what = "zero" if nn < 1e-9 else ("parallel" if float(np.dot(normal, z)) > 0 else "antiparallel") \
                    + " to its main_axis"
                self.rep.add(registry.DEGENERATE_NORMAL, f"connector {obj.display}: normal {_v(normal)} is {what}, so the frame "
                             f"about the main axis is undefined", node=node_, unit=unit_, obj=obj,
                             help="give a normal orthogonal to main_axis")
                ok = False
            elif abs(float(np.dot(normal / nn, z))) > 1e-6:
                node_, unit_ = self.ev.where(obj, "normal")
                self.rep.add(registry.NORMAL_NOT_ORTHOGONAL, f"connector {obj.display}: normal {_v(normal)} is not orthogonal to "
                             f"main_axis {_v(axis)}; only its orthogonal part {_v(x)} counts",
                             node=node_, unit=unit_, obj=obj)
        if x is None:
            from plxtools.check.scene import default_normal

            x = np.array(default_normal(tuple(float(v) for v in z)))
        y = np.cross(z, x)
        frame = (np.column_stack([x, y, z]), pos)
        redirected = None
        if self.k.isa(obj, REDIRECTED):
            rp = self.get(obj, "redirected_parent", None)
            if isinstance(rp, Obj):
                redirected = rp
        c = Conn(obj, node, frame, axis, x, ok, redirected)
        asm.conns[id(obj)] = c
        return c

    def _vec(self, obj: Obj, path: str, default):
        try:
            v = self.value(obj, path)
        except (Unavailable, KeyError):
            return default
        try:
            arr = np.asarray(v, dtype=float)
        except (TypeError, ValueError):
            return default
        if arr.shape != (3,) or not np.all(np.isfinite(arr)):
            return default
        return arr

    def _connector_list(self, asm: Assembly, obj: Obj, what: str) -> list | None:
        try:
            lst = self.ev.get(obj, "connectors")
        except Unavailable:
            asm.broken.append(obj)
            return None
        except KeyError:
            lst = None
        if not isinstance(lst, list):
            return None
        if len(lst) != 2:
            node_, unit_ = self.ev.where(obj, "connectors")
            self.rep.add(registry.CONNECTOR_COUNT, f"{what} {obj.display} has {len(lst)} connector{'s' if len(lst) != 1 else ''}; "
                         f"it needs exactly 2", node=node_, unit=unit_, obj=obj,
                         help="connectors: [a.connector, b.connector]")
            return None
        out = []
        for item in lst:
            if not isinstance(item, Obj):
                node_, unit_ = self.ev.where(obj, "connectors")
                self.rep.add(registry.CONNECTOR_COUNT, f"{what} {obj.display}: a connector is not an object", node=node_, unit=unit_,
                             obj=obj)
                return None
            out.append(self.connector(asm, item))
        return out

    def _mate(self, asm: Assembly, obj: Obj) -> MateRec:
        kind = self.k.first(obj, MATE_KINDS) or "unknown"
        rec = MateRec(obj, kind, [])
        rec.enabled = bool(self.get(obj, "enabled", True))
        rec.snap = bool(self.get(obj, "enable_snap", True))
        if kind in ("hinge", "cylindrical"):
            rec.initial_angle = self.real(obj, "initial_angle", 0.0)
        if kind in ("prismatic", "cylindrical"):
            rec.initial_position = self.real(obj, "initial_position", 0.0)
        if kind == "distance":
            rec.initial_distance = self.real(obj, "initial_distance", 0.0)
        conns = self._connector_list(asm, obj, "mate")
        if conns is None or any(c is None for c in conns):
            rec.usable = False
            rec.conns = conns or []
            return rec
        rec.conns = conns
        c0, c1 = conns
        node_, unit_ = self.ev.where(obj, "connectors")
        if c0.obj is c1.obj:
            self.rep.add(registry.MATE_SAME_CONNECTOR, f"mate {obj.display} joins connector {c0.obj.display} to itself",
                         node=node_, unit=unit_, obj=obj, help="list the two connectors of the two parts it joins")
            rec.usable = False
        elif asm.mover(c0) is asm.mover(c1) and (asm.mover(c0).kind == "body" or asm.mover(c0) is asm.root_node or
                                                 (c0.redirected_parent is None and c1.redirected_parent is None)):
            where = asm.mover(c0).path if asm.mover(c0).kind == "body" else "the world (no body)"
            self.rep.add(registry.MATE_SAME_BODY, f"mate {obj.display}: both connectors belong to {where}, so it joins nothing",
                         node=node_, unit=unit_, obj=obj,
                         help="one connector must belong to each of the two bodies the mate joins")
            rec.usable = False
        if not c0.ok or not c1.ok:
            rec.usable = rec.usable and True  # degenerate frames are reported; SNAP uses a fallback frame
        return rec

    def _controller(self, asm: Assembly, obj: Obj) -> CtrlRec:
        kind, dof = self.k.first(obj, CONTROLLER_KINDS)
        conns = self._connector_list(asm, obj, "controller")
        rec = CtrlRec(obj, kind, dof, conns or [])
        if not conns or any(c is None for c in conns):
            return rec
        a, b = conns[0].obj, conns[1].obj
        for m in asm.mates:
            if len(m.conns) == 2 and m.conns[0] is not None and m.conns[1] is not None:
                if m.conns[0].obj is a and m.conns[1].obj is b:
                    rec.mate = m
                    break
                if m.conns[0].obj is b and m.conns[1].obj is a:
                    rec.mate, rec.reversed = m, True
                    break
        return rec

    # ------------------------------------------------------------------ SNAP

    @staticmethod
    def _chain(node: Node, top: Node) -> list[Node] | None:
        """Nodes from below ``top`` down to ``node`` (top excluded), or None if top is not above."""
        out = []
        cur: Node | None = node
        while cur is not top:
            if cur is None:
                return None
            out.append(cur)
            cur = cur.parent
        out.reverse()
        return out

    @staticmethod
    def _rel(chain: list[Node]) -> Pose | None:
        pose = IDENTITY
        for n in chain:
            if n.local is None:
                return None
            pose = compose(pose, n.local)
        return pose

    @staticmethod
    def _common_system(a: Node, b: Node) -> Node:
        seen = set()
        cur: Node | None = a
        while cur is not None:
            seen.add(id(cur))
            cur = cur.parent
        cur = b
        while cur is not None and id(cur) not in seen:
            cur = cur.parent
        lca = cur
        while lca is not None and lca.kind != "system" and lca.parent is not None:
            lca = lca.parent
        return lca

    def _snap(self, asm: Assembly) -> None:
        todo = [m for m in asm.mates if m.usable and m.enabled and m.snap and m.kind != "unknown"]
        info: dict[int, tuple] = {}
        for m in todo:
            c0, c1 = m.conns
            top = self._common_system(c0.node, c1.node)
            if top is None:
                continue
            info[id(m)] = (top, self._chain(c0.node, top), self._chain(c1.node, top))
        done: set[int] = set()
        guard = 0
        while guard < 10 * (len(todo) + len(asm.nodes)) + 10:
            guard += 1
            if self._snap_one(todo, done, info):
                continue
            forced = self._force(asm, todo, done, info)
            if not forced:
                break
        for n in asm.nodes:
            if n.local is None:
                n.local = IDENTITY
                n.place(Placement.UNPLACED)

    def _snap_one(self, todo: list[MateRec], done: set[int], info: dict[int, tuple]) -> bool:
        """Place the free side of one mate whose other side is placed: first a mate whose free
        chain has one unplaced node (strict), then any.  False when no mate could be placed."""
        for strict in (True, False):
            for m in todo:
                if self._snap_mate(m, strict, done, info):
                    return True
        return False

    def _snap_mate(self, m: MateRec, strict: bool, done: set[int], info: dict[int, tuple]) -> bool:
        if id(m) in done or id(m) not in info:
            return False
        top, ch0, ch1 = info[id(m)]
        r0, r1 = self._rel(ch0), self._rel(ch1)
        if r0 is not None and r1 is not None:
            done.add(id(m))
            return False
        if r0 is None and r1 is None:
            return False
        k = 0 if r0 is not None else 1
        u_chain = ch1 if k == 0 else ch0
        free = [n for n in u_chain if n.local is None]
        if strict and len(free) > 1:
            return False
        self._place(m, k, top, ch0, ch1, free)
        done.add(id(m))
        return True

    def _place(self, m: MateRec, k: int, top: Node, ch0: list, ch1: list, free: list) -> None:
        c_known, c_unknown = m.conns[k], m.conns[1 - k]
        ch_known, ch_unknown = (ch0, ch1) if k == 0 else (ch1, ch0)
        movable = free[0]
        for n in free[1:]:
            n.local = IDENTITY
            n.place(Placement.MOVED_WITH, movable.path, m.path)
        f_known = compose(self._rel(ch_known), c_known.frame)
        off = m.offset()
        f_target = compose(f_known, off) if k == 0 else compose(f_known, inverse(off))
        i = ch_unknown.index(movable)
        x_parent = self._rel(ch_unknown[:i])
        below = self._rel(ch_unknown[i + 1:])
        y = compose(below, c_unknown.frame)
        movable.local = compose(compose(inverse(x_parent), f_target), inverse(y))
        movable.place(Placement.SNAP, m.path)
        m.placed = movable.path

    def _force(self, asm: Assembly, todo: list, done: set, info: dict) -> bool:
        for m in todo:
            if id(m) in done or id(m) not in info:
                continue
            top, ch0, ch1 = info[id(m)]
            if self._rel(ch0) is not None or self._rel(ch1) is not None:
                continue
            ref = None
            if top.kind == "system":
                rb = self.get(top.obj, "reference_body", None)
                if isinstance(rb, Obj):
                    ref = asm.node_of(rb)
            if ref is not None and ref.local is None:
                chain = self._chain(ref, top) or [ref]
                for n in chain:
                    if n.local is None:
                        n.local = IDENTITY
                        n.place(Placement.REFERENCE_BODY, top.path)
                return True
            for ch in (ch0, ch1):
                free = [n for n in ch if n.local is None]
                if free:
                    for n in free:
                        n.local = IDENTITY
                        n.place(Placement.FORCED, m.path)
                    return True
        return False

    def _world(self, asm: Assembly) -> None:
        for n in asm.nodes:  # parents come before children (walk order)
            if n.parent is None:
                n.world = n.local if n.local is not None else IDENTITY
            else:
                pw = n.parent.world if n.parent.world is not None else IDENTITY
                n.world = compose(pw, n.local if n.local is not None else IDENTITY)

    # ------------------------------------------------------------------ checks after SNAP

    def _violations(self, asm: Assembly) -> None:
        for m in asm.mates:
            if not m.usable or not m.enabled or m.kind == "unknown":
                continue
            c0, c1 = m.conns
            f0 = compose(asm.conn_world(c0), m.offset())
            f1 = asm.conn_world(c1)
            d = f1[1] - f0[1]
            z0 = f0[0][:, 2]
            if m.kind in ("prismatic", "cylindrical"):
                d = d - float(np.dot(d, z0)) * z0
            sep = float(np.linalg.norm(d))
            if m.kind == "distance":
                sep = abs(float(np.linalg.norm(f1[1] - asm.conn_world(c0)[1])) - m.initial_distance)
            ang = 0.0
            if m.kind in ("hinge", "cylindrical"):
                ang = angle_between(z0, f1[0][:, 2])
            elif m.kind in ("prismatic", "lock"):
                ang = rotation_angle(f0[0].T @ f1[0])
            m.separation, m.misalignment = sep, ang
            if sep <= POS_TOL and ang <= ANGLE_TOL:
                continue
            parts = []
            if sep > POS_TOL:
                parts.append(f"{sep:.4g} m apart")
            if ang > ANGLE_TOL:
                parts.append(f"main axes {math.degrees(ang):.3g} deg apart" if m.kind in ("hinge", "cylindrical")
                             else f"frames turned {math.degrees(ang):.3g} deg")
            sides = []
            for c in (c0, c1):
                n = c.node
                if n is asm.root_node:
                    sides.append(f"{c.obj.display}: fixed to the world")
                else:
                    sides.append(f"{n.path}: {n.placed_by}")
            why = "; ".join(sides)
            self.rep.add(registry.MATE_NOT_COINCIDENT, f"mate {m.path}: its connectors do not coincide after assembly ({', '.join(parts)}); "
                         f"{why}", obj=m.obj,
                         help="SNAP moves only bodies and systems without a declared transform; remove the "
                         "explicit local_transform of one side, or fix the connector positions and axes")


_FLOAT_MAX = int(np.finfo(float).max)


def _non_finite(v: Any, depth: int = 0) -> str | None:
    """"NaN", "infinite" or None: the first non-finite number inside a value (numbers, arrays, lists,
    and value types such as a Transform that hold them)."""
    if depth > 8 or isinstance(v, (bool, str, Obj)) or v is None:
        return None
    if isinstance(v, int):
        return None if abs(v) <= _FLOAT_MAX else "too large for a number (beyond 1.8e308)"
    if isinstance(v, float):
        return None if math.isfinite(v) else ("NaN" if math.isnan(v) else "infinite")
    if isinstance(v, np.ndarray):
        if v.dtype.kind == "O":
            return _non_finite(v.tolist(), depth + 1)
        if v.dtype.kind != "f" or bool(np.all(np.isfinite(v))):
            return None
        return "NaN" if bool(np.any(np.isnan(v))) else "infinite"
    if isinstance(v, np.floating):
        return _non_finite(float(v), depth + 1)
    if isinstance(v, (list, tuple)):
        for x in v:
            bad = _non_finite(x, depth + 1)
            if bad is not None:
                return bad
        return None
    for attr in ("position", "rotation"):
        if hasattr(v, attr):
            bad = _non_finite(getattr(v, attr), depth + 1)
            if bad is not None:
                return bad
    return None


def _v(a) -> str:
    return "{" + ", ".join(f"{float(x):.4g}" for x in a) + "}"
