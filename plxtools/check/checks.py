"""Static assembly checks (codes A0xx, stage "check"), run on the assembled object tree.

Each finding is placed on the line that causes it: the assignment that gives the bad value when it
is written in the checked file, otherwise the declaration (in that file) of the object involved.
"""

from __future__ import annotations

import math
import os
import re
from itertools import combinations

import numpy as np

from plxtools import envpath
from plxtools.check.broadphase import first_overlaps
from plxtools.check import coverage, drivetrain
from plxtools.check.coverage import not_simulated
from plxtools.check.assemble import DOF_OF_MATE, Assembler, Assembly, CtrlRec, Kinds, MateRec, Node, Placement
from plxtools.check.convert import Collector, GeomRec, report_missing_file
from plxtools.check.frames import angle_between, compose
from plxtools.check.instance import Obj
from plxtools.check.report import Reporter
from plxtools.syntax import ast
from plxtools.diagnostics import Severity
from plxtools.rules import registry
from plxtools.check.signals import classify


# The codes this module raises (their home).  The MuJoCo build names them when it meets a scene these
# checks should have rejected (BuildContext.invariant); `plx check`'s summary lists the motion ones.
# found by these checks, not by the simulation: what they say about how the scene moves (or fails to)
STATIC_MOTION_CODES = frozenset({registry.MATE_WITHOUT_DYNAMIC_BODY, registry.HINGE_AXIS_OFF_CYLINDER_AXIS, registry.MIRRORED_DRIVE_MOTORS,
                                 registry.UNPLACED_BODY_OVERLAPS})

TWO_PI = 2.0 * math.pi
UNSUPPORTED_BUNDLES = {
    "Physics1D": "Physics1D (1D shafts and interactions)",
    "DriveTrain": "DriveTrain (engines, gear boxes, torque converters, limited-slip differentials, actuators)",
    "Terrain": "Terrain (deformable terrain)",
    "Sensors": "Sensors",
    "Vehicles": "Vehicles (tracks, suspensions, tyres)",
    "Robotics": "Robotics",
}
SIGNAL_NAMESPACES = ("Physics.Signals", "Physics3D.Signals")
DRY_MODELS = ("dry", "dry_cone", "dry_box", "dry_scale_box", "dry_constant_normal_force",
              "dry_depth_scaled_constant_normal_force")


class StaticChecks:
    def __init__(self, asm: Assembly, asmb: Assembler, col: Collector, kinds: Kinds, rep: Reporter):
        self.asm = asm
        self.a = asmb
        self.ev = asmb.ev
        self.col = col
        self.k = kinds
        self.rep = rep

    def run(self) -> None:
        self.unsupported()
        self.settings_not_simulated()
        self.masses()
        self.contacts()
        self.mates()
        self.controllers()
        self.hinge_axes()
        self.mirrored_motors()
        self.overlaps()
        self.collision_pairs_without_effect()

    # ------------------------------------------------------------------ helpers

    def where(self, obj: Obj, path: str) -> tuple:
        return self.ev.where(obj, path)

    def add_at(self, code: str, message: str, obj: Obj, attr: str | None = None, **kw) -> None:
        node, unit = self.where(obj, attr) if attr else (None, None)
        self.rep.add(code, message, node=node, unit=unit, obj=obj, **kw)

    # ------------------------------------------------------------------ unsupported features

    def settings_not_simulated(self) -> None:
        """Attributes of mapped objects (mates, controllers, contact models, materials) that hold
        something the backend cannot simulate: A040 where the value is set (coverage.TABLE)."""
        seen: set[int] = set()
        objs = [m.obj for m in self.asm.mates] + [c.obj for c in self.asm.controllers] + \
            [c.obj for c in self.col.contacts] + [n.obj for n in self.asm.bodies]
        for obj in objs:
            if id(obj) in seen:
                continue
            seen.add(id(obj))
            for attr, msg, where in coverage.settings_not_simulated(self.k, self.ev, self.a.get, obj):
                node, unit = where if where else (None, None)
                not_simulated(self.rep, msg, node=node, unit=unit, obj=obj, severity="warning")
                self.col.unsupported.append((attr, obj, msg))

    def unsupported(self) -> None:
        """A040 for each element the MuJoCo backend does not simulate, once per element (not again
        for what it owns)."""
        reported = self._unsupported_owned()
        self._unmapped_interactions(reported)
        for m in self.asm.mates:
            if m.kind == "unknown":
                qn = self.a.p.concrete(m.obj.model).qname
                self._refuse(qn, m.obj, f"{m.path} ({qn}): this mate type has no MuJoCo mapping and is not simulated")
        self._contact_settings()
        self._point_gravity()

    def _refuse(self, what: str, obj: Obj, msg: str) -> None:
        not_simulated(self.rep, msg, obj=obj)
        self.col.unsupported.append((what, obj, msg))

    def _unsupported_owned(self) -> set[int]:
        """The objects of unsupported bundles, signals and types; returns the ids of those reported
        (and of the drive-train objects that are simulated with their parts)."""
        reported: set[int] = set()
        for obj in self.asm.owned[1:]:
            if any(id(o) in reported for o in _owners(obj)):
                continue
            if drivetrain.mapped(self.k, obj):  # simulated, with its parts (connectors, inertia, signals)
                reported.add(id(obj))
                continue
            qn = self.a.p.concrete(obj.model).qname
            msg = self._unsupported_text(obj, qn)
            if msg is not None:
                reported.add(id(obj))
                self._refuse(qn, obj, msg)
        return reported

    def _unsupported_text(self, obj: Obj, qn: str) -> str | None:
        ns = qn.split(".")[0]
        if ns in UNSUPPORTED_BUNDLES:
            return f"{obj.display} ({qn}): {UNSUPPORTED_BUNDLES[ns]} is not supported by the MuJoCo backend; " \
                   f"it is not simulated"
        if qn.startswith(SIGNAL_NAMESPACES) and obj.decl is not None and obj.decl[0].unit is self.rep.unit:
            return self._unmapped_signal(obj, qn)
        if qn == "Physics.KinematicLock":
            return f"{obj.display}: Physics.KinematicLock is not supported by the MuJoCo backend (the bodies " \
                   f"move independently)"
        if self.k.isa(obj, "Physics3D.Interactions.AdaptiveMateConnector"):
            return f"{obj.display}: AdaptiveMateConnector is treated as a plain MateConnector"
        return None

    def _unmapped_interactions(self, reported: set[int]) -> None:
        for obj in self.asm.other_interactions:
            if id(obj) in reported or any(id(o) in reported for o in _owners(obj)) or drivetrain.mapped(self.k, obj):
                continue
            qn = self.a.p.concrete(obj.model).qname
            if qn.split(".")[0] in UNSUPPORTED_BUNDLES:
                continue
            self._refuse(qn, obj, f"{obj.display} ({qn}): this interaction has no MuJoCo mapping and is not simulated")

    def _contact_settings(self) -> None:
        """Contact model settings MuJoCo has no counterpart for (placed where they are set)."""
        for c in self.col.contacts:
            if c.enabled and c.tangential_restitution is not None and 0 < c.tangential_restitution <= 1:
                not_simulated(self.rep, f"{c.obj.display}: tangential_restitution {c.tangential_restitution:g} is "
                              f"not simulated by the MuJoCo backend (its contacts resist sliding by friction only); "
                              f"it is ignored", **self._where_kw(c.obj, "tangential_restitution"), obj=c.obj,
                              path=c.obj.display)
            if c.enabled and c.friction_model not in DRY_MODELS:
                not_simulated(self.rep, f"{c.obj.display}: friction model {c.friction_model} is not dry friction; "
                              f"MuJoCo uses its default friction for this pair", **self._where_kw(c.obj, "friction"),
                              obj=c.obj, path=c.obj.display)

    def _point_gravity(self) -> None:
        root = self.asm.root
        if self.k.isa(root, "Simulation.Environment"):
            g = self.ev.child(root, "gravity")
            if isinstance(g, Obj) and self.k.isa(g, "Simulation.PointGravitationalField"):
                self._refuse("Simulation.PointGravitationalField", g,
                             f"{g.display}: PointGravitationalField is not supported by MuJoCo; uniform gravity "
                             f"{{0, 0, -9.80665}} is used")

    def _unmapped_signal(self, obj: Obj, qn: str) -> str | None:
        """The A040 text for a signal declared in the file that the MuJoCo run cannot map (None when
        it maps: plxtools/check/signals.py)."""

        info = classify(obj, self.ev, self.k)
        if info is not None and info.mapped:
            return None
        why = f": {info.why}" if info is not None and info.why else ""
        return f"{obj.display} ({qn}): not simulated by the MuJoCo backend{why}"

    # ------------------------------------------------------------------ mass

    def masses(self) -> None:
        geoms: dict[int, list[GeomRec]] = {}
        for g in self.col.geoms:
            geoms.setdefault(id(g.node), []).append(g)
            if not g.visual and g.include_in_mass and g.valid and g.density <= 0 and g.material_obj is not None:
                self.add_at(registry.NON_POSITIVE_DENSITY, f"material {g.material_obj.display} of {g.path} has density "
                            f"{g.density:g}; it must be > 0 for the geometry to give mass", g.material_obj,
                            "density", path=g.path)
        for n in self.asm.bodies:
            self._body_mass(n, geoms.get(id(n), []))
            self._inertia_tensor(n)

    def _body_mass(self, n: Node, geoms: list[GeomRec]) -> None:
        """A negative mass, or a dynamic body of mass 0 that no geometry gives mass to."""
        obj = n.obj
        mass = self.a.real(obj, "inertia.mass", 0.0)
        if mass < 0:
            self.add_at(registry.NEGATIVE_MASS, f"{n.path} has negative mass {mass:g}", obj, "inertia.mass",
                        help="a mass of 0 means: compute it from the geometries")
            return
        if mass != 0 or not n.is_dynamic:
            return
        contributing = [g for g in geoms if not g.visual and g.valid and g.include_in_mass
                        and g.density > 0 and g.volume() > 0]
        # a geometry that failed to evaluate or was rejected (A030, A031) is reported already
        failed = any(g.failed or not g.valid for g in geoms if not g.visual)
        if not contributing and not failed:
            self.add_at(registry.ZERO_MASS_DYNAMIC_BODY, f"dynamic body {n.path} has mass 0 and no geometry that gives it "
                        f"mass", obj, "inertia.mass",
                        help="give inertia.mass a value, or a contact geometry with a size and a material density")

    def _inertia_tensor(self, n: Node) -> None:
        t = self.a.get(n.obj, "inertia.tensor", None)
        if isinstance(t, np.ndarray) and t.shape == (3, 3) and np.any(np.diag(t) != 0):
            problem = _tensor_problem(t)
            if problem:
                self.add_at(registry.INVALID_INERTIA, f"{n.path}: inertia tensor {problem}", n.obj, "inertia.tensor",
                            help="use Physics3D.Bodies.Inertia.symmetric_tensor(diag, e01, e02, e12) with "
                            "positive principal moments")

    # ------------------------------------------------------------------ contact models

    def contacts(self) -> None:
        seen: dict[tuple, object] = {}
        for c in self.col.contacts:
            if c.key1 is None or c.key2 is None:
                continue
            key = tuple(sorted((c.key1, c.key2)))
            first = seen.get(key)
            if first is not None:
                line = self.rep.anchor(first.obj).start.line + 1
                self.rep.add(registry.DUPLICATE_CONTACT_MODEL, f"{c.obj.display} is a second SurfaceContact.Model for the material pair "
                             f"{key[0]} / {key[1]} (the first is {first.obj.display}, line {line})", obj=c.obj,
                             help="keep one contact model per pair of materials")
            else:
                seen[key] = c
            if c.friction is not None and c.friction < 0:
                fr = self.ev.child(c.obj, "friction")
                self.add_at(registry.INVALID_CONTACT_PARAMETER, f"{c.obj.display}: friction coefficient {c.friction:g} is negative",
                            fr if isinstance(fr, Obj) else c.obj, "coefficient" if isinstance(fr, Obj) else None,
                            path=c.obj.display)
            pairs = (("normal_restitution", c.restitution), ("tangential_restitution", c.tangential_restitution))
            for attr, v in pairs:
                if v is not None and not 0.0 <= v <= 1.0:
                    self.add_at(registry.INVALID_CONTACT_PARAMETER, f"{c.obj.display}: {attr} {v:g} is outside [0, 1]", c.obj, attr,
                                path=c.obj.display)

    # ------------------------------------------------------------------ mates

    def mates(self) -> None:
        for m in self.asm.mates:
            if not m.usable or not m.enabled:
                continue
            if m.kind in ("hinge", "cylindrical") and abs(m.initial_angle) > TWO_PI:
                self.add_at(registry.ANGLE_PROBABLY_DEGREES, f"{m.path}: initial_angle {m.initial_angle:g} is more than 2 pi: is it in "
                            f"degrees? Angles are radians", m.obj, "initial_angle",
                            help=f"Math.Functions.deg_to_rad({m.initial_angle:g})")
            movers = [self.asm.mover(c) for c in m.conns]
            dyn = [n.kind == "body" and n.is_dynamic for n in movers]
            if not any(dyn):
                self.rep.add(registry.MATE_WITHOUT_DYNAMIC_BODY, f"mate {m.path} joins two parts that do not move (static bodies or the "
                             f"world); it has no effect", obj=m.obj)

    # ------------------------------------------------------------------ controllers

    def controllers(self) -> None:
        for c in self.asm.controllers:
            obj = c.obj
            if len(c.conns) != 2 or any(x is None for x in c.conns):
                continue
            if c.mate is None:
                names = ", ".join(x.obj.display for x in c.conns)
                self.add_at(registry.CONTROLLER_WITHOUT_MATE, f"{c.path}: its connectors [{names}] are not the connectors of any mate, so "
                            f"it drives nothing", obj, "connectors",
                            help="use the connectors of the mate it drives, e.g. connectors: hinge.connectors")
            else:
                free = DOF_OF_MATE.get(c.mate.kind, set())
                if c.dof not in free:
                    what = "rotation" if c.dof == "rotational" else "translation"
                    self.add_at(registry.CONTROLLER_DOF_MISMATCH, f"{c.path} ({self.a.p.concrete(obj.model).name}) drives a {what}, but its "
                                f"mate {c.mate.path} is a {c.mate.kind.capitalize()}, which has no free {what}",
                                obj, "connectors")
            if c.kind == "velocity_motor" and c.dof == "rotational":
                v = self.a.real(obj, "target_speed", 0.0)
                if abs(v) > TWO_PI:
                    self.add_at(registry.ANGLE_PROBABLY_DEGREES, f"{c.path}: target_speed {v:g} rad/s is more than 2 pi: is it in degrees "
                                f"per second?", obj, "target_speed", severity=Severity.INFO,
                                help=f"Math.Functions.deg_to_rad({v:g}) if it is")  # (wheels often turn faster)
            if c.kind == "range":
                start = self.a.real(obj, "start", math.nan)
                end = self.a.real(obj, "end", math.nan)
                if math.isfinite(start) and math.isfinite(end) and start > end:
                    self.add_at(registry.INVERTED_LIMITS, f"{c.path}: range start {start:g} is greater than end {end:g}", obj, "start")
                elif math.isfinite(start) and math.isfinite(end) and c.mate is not None and c.mate.enabled:
                    self._range_start(c, start, end)
                if c.dof == "rotational" and any(math.isfinite(x) and abs(x) > TWO_PI for x in (start, end)):
                    self.add_at(registry.ANGLE_PROBABLY_DEGREES, f"{c.path}: range [{start:g}, {end:g}] goes beyond 2 pi: is it in degrees?",
                                obj, "start")
            lo = self.a.real(obj, "min_effort", -math.inf)
            hi = self.a.real(obj, "max_effort", math.inf)
            if lo > hi:
                self.add_at(registry.INVERTED_LIMITS, f"{c.path}: min_effort {lo:g} is greater than max_effort {hi:g}", obj,
                            "min_effort")

    def _range_start(self, c, start: float, end: float) -> None:
        """A range its mate starts outside of (A045): the joint limit kicks the bodies back at the
        first step, with the energy of a stiff spring compressed by the whole violation."""
        m = c.mate
        rotational = c.dof == "rotational"
        if rotational and m.kind in ("hinge", "cylindrical"):
            q, what, unit = m.initial_angle, "initial_angle", "rad"
        elif not rotational and m.kind in ("prismatic", "cylindrical"):
            q, what, unit = m.initial_position, "initial_position", "m"
        else:
            return
        tol = 1e-9 * max(1.0, abs(start), abs(end))
        if start - tol <= q <= end + tol:
            return
        node, unit_ = self.where(m.obj, what)
        if node is None:
            node, unit_ = self.where(c.obj, "start" if q < start else "end")
        self.rep.add(registry.RANGE_STARTS_VIOLATED, f"{c.path}: {m.path} starts at {what} {q:g} {unit}, outside the range [{start:g}, "
                     f"{end:g}] {unit}; the limit pushes it back at the first step with a kick that is not in the "
                     f"model", node=node, unit=unit_, obj=c.obj, path=c.path,
                     help=f"start the mate inside the range, or widen the range to include {q:g}")

    # ------------------------------------------------------------------ hinge axis vs cylinder axis

    def hinge_axes(self) -> None:
        by_node: dict[int, list[GeomRec]] = {}
        for g in self.col.geoms:
            if not g.visual and g.valid and g.kind in ("cylinder", "capsule"):
                by_node.setdefault(id(g.node), []).append(g)
        for m in self.asm.mates:
            if not m.usable or m.kind not in ("hinge", "cylindrical"):
                continue
            if not all(c.ok for c in m.conns):
                continue  # a zero or degenerate axis is reported once, as A010 / A011
            axis_w = self.asm.conn_world(m.conns[0])[0][:, 2]
            for c in m.conns:
                n = c.node
                if not getattr(n, "is_dynamic", True):
                    continue  # a static body does not turn: its cylinder (a bearing housing, a post) is no wheel
                for g in by_node.get(id(n), []):
                    gw = compose(n.world, g.pose)
                    cyl_axis = gw[0][:, 1]
                    p = self.asm.conn_world(c)[1]
                    if float(np.linalg.norm(p - gw[1])) > max(g.radius, g.height / 2.0) + 1e-9:
                        continue  # the hinge does not pass through this cylinder
                    ang = angle_between(axis_w, cyl_axis)
                    ang = min(ang, math.pi - ang)
                    if ang > math.radians(1.0):
                        node, unit = self.where(c.obj, "main_axis")
                        local_axis = c.main_axis
                        self.rep.add(registry.HINGE_AXIS_OFF_CYLINDER_AXIS, f"{m.path} turns {n.path} about an axis {math.degrees(ang):.3g} deg "
                                     f"away from the axis of its {g.kind} {g.path} (the {g.kind}'s local Y): the "
                                     f"{g.kind} would tumble instead of rolling", node=node, unit=unit, obj=c.obj,
                                     path=m.path,
                                     help=f"the connector's main_axis {_v(local_axis)} should lie along the "
                                     f"{g.kind} axis, e.g. main_axis: {{0, -1, 0}}")
                        break

    # ------------------------------------------------------------------ the BoxTruck trap

    def mirrored_motors(self) -> None:
        motors = [c for c in self.asm.controllers if c.kind == "velocity_motor" and c.dof == "rotational"
                  and c.mate is not None and c.mate.kind in ("hinge", "cylindrical")]
        for x, y in combinations(motors, 2):
            vx = self.a.real(x.obj, "target_speed", 0.0) * (-1 if x.reversed else 1)
            vy = self.a.real(y.obj, "target_speed", 0.0) * (-1 if y.reversed else 1)
            if vx == 0 or abs(vx - vy) > 1e-9 * max(1.0, abs(vx)):
                continue
            fx = self.asm.conn_world(x.mate.conns[0])
            fy = self.asm.conn_world(y.mate.conns[0])
            ax, ay = fx[0][:, 2], fy[0][:, 2]
            if float(np.dot(ax, ay)) > -0.99:
                continue
            # mirrored hubs: on opposite sides along the axis, on the same parent
            if self.asm.mover(x.mate.conns[0]) is not self.asm.mover(y.mate.conns[0]):
                continue
            d = fy[1] - fx[1]
            if float(np.dot(d, ay)) <= 0:
                continue
            d = self.rep.add(
                registry.MIRRORED_DRIVE_MOTORS, f"{x.path} and {y.path} have the same target_speed ({vx:g}) on hinges whose axes "
                f"point opposite ways ({_v(ax)} and {_v(ay)}): the two wheels are driven in opposite directions, "
                f"so the vehicle does not drive straight: it turns where it stands, and where other wheels on the "
                f"ground resist (a four-wheeled truck) the driven wheels slip and scrub against each other (motors "
                f"with an effort limit then fall short of their target: A106 with --simulate)",
                **self._where_kw(y.obj, "target_speed"), obj=y.obj,
                help=f"to drive straight, give {y.obj.name} target_speed: {-vy:g}")
            self.rep.mirrored_motors.append((x.path, y.path, d))

    # ------------------------------------------------------------------ collision groups

    def collision_pairs_without_effect(self) -> None:
        """A044 where a DisableCollisionPair changes nothing at the start: each body pair it names
        is joined by a mate (mated bodies' contacts are excluded anyway) or apart. The tutorial's
        step 8 group is such a one (issue 32.6): say so where it is declared, so the reader does not
        look for its effect in the simulation."""
        mated: set[tuple[int, int]] = set()
        for m in self.asm.mates:
            if len(m.conns) == 2 and all(c is not None for c in m.conns):
                a, b = self.asm.mover(m.conns[0]), self.asm.mover(m.conns[1])
                mated |= {(id(a), id(b)), (id(b), id(a))}
        boxes = self._collision_boxes()
        by_pair: dict[int, list] = {}
        for x, y, pair in self.col.exclude_pairs():
            if x is not y:
                by_pair.setdefault(id(pair), [pair, set()])[1].add(frozenset((id(x), id(y))))
        for pair, pairs in by_pair.values():
            joined = apart = 0
            for key in pairs:
                a, b = tuple(key)
                if (a, b) in mated:
                    joined += 1
                elif a in boxes and b in boxes and not _boxes_touch(boxes[a], boxes[b]):
                    apart += 1
                else:
                    break
            else:
                if joined:
                    self.rep.add(registry.COLLISION_PAIR_WITHOUT_EFFECT, f"{pair.display} changes nothing at the start of the simulation: "
                                 f"{joined} of its {len(pairs)} body pairs are joined by mates, whose contacts are "
                                 f"excluded anyway, and the other {apart} are apart",
                                 obj=pair, help="keep it if those bodies can come to touch as they move; "
                                 "otherwise it can go")

    def _collision_boxes(self) -> dict[int, tuple[np.ndarray, np.ndarray]]:
        """World bounding box of each body's colliding geometry at the start, by node id."""
        boxes: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        for g in self.col.geoms:
            if g.visual or not g.valid or not g.enable_collisions:
                continue
            he = g.half_extents()
            if he is None:
                continue
            w = compose(g.node.world, g.pose)
            half = np.abs(w[0]) @ he
            lo, hi = w[1] - half, w[1] + half
            cur = boxes.get(id(g.node))
            boxes[id(g.node)] = (lo, hi) if cur is None else (np.minimum(cur[0], lo), np.maximum(cur[1], hi))
        return boxes

    def _where_kw(self, obj: Obj, attr: str) -> dict:
        node, unit = self.where(obj, attr)
        return {"node": node, "unit": unit}

    # ------------------------------------------------------------------ overlaps at the origin

    def overlaps(self) -> None:
        mated: set[tuple[int, int]] = set()
        for m in self.asm.mates:
            if len(m.conns) == 2 and all(c is not None for c in m.conns):
                a, b = self.asm.mover(m.conns[0]), self.asm.mover(m.conns[1])
                mated.add((id(a), id(b)))
                mated.add((id(b), id(a)))
        excluded = {(id(x), id(y)) for x, y, _ in self.col.exclude_pairs()}
        excluded |= {(b, a) for a, b in excluded}
        boxes = self._collision_boxes()
        nodes = {id(n): n for n in self.asm.nodes}
        unplaced = {id(n) for n in self.asm.bodies  # static geometry at the origin is normal (a ground)
                    if n.placement is Placement.UNPLACED and n.is_dynamic and id(n) in boxes}
        if not unplaced:
            return
        keys = list(boxes)
        index = {k: i for i, k in enumerate(keys)}
        # sort and sweep (check/broadphase.py): linear in the boxes plus the overlapping pairs
        partner = first_overlaps(np.array([boxes[k][0] for k in keys]), np.array([boxes[k][1] for k in keys]),
                                 [k in unplaced for k in keys],
                                 lambda i, j: (keys[i], keys[j]) not in excluded and (keys[i], keys[j]) not in mated,
                                 margin=0.01)
        for n in self.asm.bodies:
            found = partner.get(index[id(n)]) if id(n) in unplaced else None
            if found is None:
                continue
            other, depth = nodes[keys[found[0]]], found[1]
            broken = [m for m in self.asm.broken if self.k.isa(m, "Physics3D.Interactions.Mate")]
            if broken:  # the cause is more likely a mate that failed than a missing transform
                help = (f"{broken[0].display} could not be built (see its error); fix that first: it "
                        f"may be the mate that places {n.path}")
            else:
                help = "give it kinematics.local_transform.position, or join it to the scene with a mate"
            self.rep.add(registry.UNPLACED_BODY_OVERLAPS, f"{n.path} has no declared transform and no mate places it, so it stays "
                         f"at {_v(n.world[1])}, where it overlaps {other.path} "
                         f"(by {depth:.3g} m)", obj=n.obj, help=help)


def scan_strings(tree: ast.File, rep: Reporter) -> None:
    """``@"..."`` files that do not exist, and ``$"{VAR}"`` variables that are not set (A031, A007).
    An import's missing file is lint's N006, so an import's path is only checked for unset variables."""
    base = os.path.dirname(os.path.abspath(tree.path)) if tree.path else os.getcwd()
    stack: list = list(tree.statements)
    while stack:
        node = stack.pop()
        if isinstance(node, ast.Import):
            if node.source.kind == "interp":
                _check_string(node.source, base, rep, variables_only=True)
            continue
        if isinstance(node, ast.String):
            _check_string(node, base, rep)
            continue
        if isinstance(node, list):
            stack.extend(node)
            continue
        if not isinstance(node, ast.Node):
            continue
        for name in getattr(node, "__slots__", ()):
            if name in ("span", "header"):
                continue
            v = getattr(node, name, None)
            if isinstance(v, (ast.Node, list)):
                stack.append(v)


def _check_string(s: ast.String, base: str, rep: Reporter, variables_only: bool = False) -> None:
    if s.kind == "path" and not variables_only:
        p = s.value
        full = p if os.path.isabs(p) else os.path.normpath(os.path.join(base, p))
        if p and not os.path.exists(full):
            report_missing_file(rep, f"file {p!r} does not exist (looked for {full})", span=s.span,
                            help="paths in @\"...\" are relative to the folder of the .openplx file")
    elif s.kind == "interp":
        val, unset = envpath.expand(s.value)
        for v in unset:
            rep.add(registry.ENVIRONMENT_VARIABLE_UNSET, f"environment variable {v} in {s.raw} is not set; the path cannot be resolved here",
                    span=s.span, help=f"set {v} (for AGX_DATA_DIR: install AGX), or use @\"...\" with a relative path")
        if not unset and not variables_only:
            looks_like_file = "/" in val or os.sep in val or re.search(r"\.[A-Za-z0-9]{2,4}$", val)
            if looks_like_file and not os.path.exists(val if os.path.isabs(val) else os.path.join(base, val)):
                named = envpath.shown(s.raw, val)
                report_missing_file(rep, f"file {named} does not exist", span=s.span, severity="warning",
                                    help="plx check --show-env shows the path the variables give" if named == s.raw else None)


def _owners(obj: Obj):
    cur = obj.owner
    while cur is not None:
        yield cur
        cur = cur.owner


def _tensor_problem(t: np.ndarray) -> str | None:
    if not np.all(np.isfinite(t)):
        return "has non-finite entries"
    if float(np.max(np.abs(t - t.T))) > 1e-9 * max(1.0, float(np.max(np.abs(t)))):
        return "is not symmetric"
    try:
        ev = np.linalg.eigvalsh(t)
    except np.linalg.LinAlgError:
        return "cannot be diagonalised"
    if float(np.min(ev)) <= 0:
        return f"is not positive definite (principal moments {', '.join(f'{x:.4g}' for x in ev)})"
    a, b, c = sorted(float(x) for x in ev)
    if a + b < c * (1 - 1e-9):
        return f"breaks the triangle inequality (principal moments {a:.4g} + {b:.4g} < {c:.4g})"
    return None


def _v(a) -> str:
    return "{" + ", ".join(f"{float(x):.4g}" for x in a) + "}"


__all__ = ["StaticChecks", "scan_strings", "MateRec", "CtrlRec", "Node"]


def _boxes_touch(a, b, margin: float = 0.01) -> bool:
    return bool(np.all(a[0] - margin <= b[1]) and np.all(b[0] - margin <= a[1]))
