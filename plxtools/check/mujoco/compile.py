"""Compile an assembled :class:`~plxtools.check.scene.Scene` into a MuJoCo model via ``MjSpec``.

mujoco is imported lazily (inside functions).  Entry point: :func:`compile_scene`.  The builder
is split over ``mujoco.compile`` (tree, joints, loop closures), ``mujoco.geoms`` (geometry, mass,
collision filtering, contact pairs) and ``mujoco.controllers`` (motors, ranges, springs, keyframe).

Mapping decisions (see also the module docstring of ``mujoco_backend``):

* Kinematic tree: a spanning forest of the mate graph, where the world, system connectors and
  every static body are one node.  Tree edges are chosen Kruskal-style by preference
  prismatic/cylindrical (cannot close a loop exactly) < hinge < lock < ball, then declaration
  order.  Components touching the world hang under the static body (or the worldbody) that owns
  the parent-side connector; other components get a free joint on the body with the most tree
  mates (ties: first declared).  The remaining mates close loops with equality constraints:
  ball -> connect, lock -> weld, hinge -> two connects on the axis (+-0.1 m), prismatic /
  cylindrical loops are not enforced (warning).  Distance mates become a spatial tendon with a
  tendon-length equality (connect when the distance is 0).
* Joint ``pos``/``axis`` come from the CHILD's connector in the child frame; body poses relative to
  their parent come from the assembled world poses; ``ref`` = sign * initial offset.
* Sign: the OpenPLX coordinate is connectors[1] relative to connectors[0].  If the tree makes
  connectors[0]'s body the child the MuJoCo joint measures the opposite, so sign = -1: actuator
  gear -1, ranges / springref / ref negated.  A controller whose connectors are listed in the
  opposite order from its mate flips the sign once more.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from plxtools.check.mujoco.drivetrain import add_couplings, add_shaft_motors, add_shafts
from plxtools.check.mujoco.shaft_parts import add_shaft_parts
from plxtools.check.mujoco.context import BuildContext, CompileFailed
from plxtools.check.mujoco.controllers import add_controllers, add_keyframe
from plxtools.check.mujoco.kinematic import add_kinematic_joint, exclude_kinematic_contacts, set_kinematic_inertia
from plxtools.check.mujoco.geoms import add_contact_pairs, add_excludes, add_geoms, set_inertials, set_restitution
from plxtools.check.mujoco.integrator import choose as choose_integrator
from plxtools.check.frames import mat_to_quat_wxyz
from plxtools.check.mujoco.poses import angle_between, quat_normalize, quat_to_mat, relative_pose, unit
from plxtools.check.mujoco.notes import INFO, WARNING, BackendNote
from plxtools.check.mujoco.results import VISUAL_GROUP, ActuatorInfo, CompiledScene, MateMonitor
from plxtools.check.scene import Connector, Mate, Scene, default_normal, orthogonalize
from plxtools.rules import registry

__all__ = ["VISUAL_GROUP", "ActuatorInfo", "BackendNote", "CompiledScene", "MateMonitor", "compile_scene"]

WORLD = "<world>"
TREE_PRIORITY = {"prismatic": 0, "cylindrical": 0, "hinge": 1, "lock": 2, "ball": 3}
HINGE_LOOP_HALF_LENGTH = 0.1  # m, half distance between the two connect points of a hinge loop
ALIGN_POS_TOL = 1e-4  # m: "initially violated mate" thresholds
ALIGN_ANGLE_TOL = 1e-3  # rad
PULL_TIME_CONSTANT = 0.05  # s: equalities that pull a mate that starts apart together


def compile_scene(scene: Scene) -> CompiledScene:
    """Build the MjSpec and compile it.  Never raises for scene problems: they become notes."""
    import time

    t0 = time.perf_counter()
    ctx = BuildContext.for_scene(scene)
    try:
        build(ctx)
    except CompileFailed:
        pass
    ctx.out.compile_ms = (time.perf_counter() - t0) * 1e3
    return ctx.out


# -- helpers ---------------------------------------------------------------------------------
def node(ctx: BuildContext, c: Connector) -> str | None:
    """Graph node of a connector: WORLD for world/system/static owners, else the body path."""
    if c.body is None:
        return WORLD
    body = ctx.bodies.get(c.body)
    if body is None:
        return None
    return c.body if body.is_dynamic else WORLD


def owner_mj_name(ctx: BuildContext, c: Connector) -> str:
    if c.body is None:
        return "world"
    return ctx.names.name("body", c.body) or "world"


def local_frame(ctx: BuildContext, c: Connector) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    axis = unit(c.main_axis)
    normal = np.array(
        orthogonalize(c.normal if c.normal is not None else default_normal(tuple(axis)), tuple(axis))
    )
    return np.asarray(c.local_pos, dtype=float), axis, normal


def world_pose(ctx: BuildContext, path: str | None) -> tuple[np.ndarray, np.ndarray]:
    if path is None:
        return np.zeros(3), np.array([1.0, 0, 0, 0])
    b = ctx.bodies[path]
    return np.asarray(b.world_pos, dtype=float), quat_normalize(b.world_quat)


# -- main ------------------------------------------------------------------------------------
def build(ctx: BuildContext) -> None:
    mj, spec, scene = ctx.mj, ctx.spec, ctx.scene
    spec.modelname = ctx.names.add("model", scene.name or "scene")
    spec.compiler.degree = False
    spec.option.timestep = float(scene.timestep)
    spec.option.gravity = [float(g) for g in scene.gravity]
    spec.option.integrator = mj.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.enableflags |= int(mj.mjtEnableBit.mjENBL_ENERGY)
    spec.option.cone = mj.mjtCone.mjCONE_ELLIPTIC
    spec.option.impratio = 10.0
    spec.visual.global_.offwidth = 1280
    spec.visual.global_.offheight = 960
    spec.worldbody.add_light(
        name="plx_sun",
        pos=[0, 0, 30],
        dir=[0.3, 0.2, -1],
        castshadow=0,
        type=int(mj.mjtLightType.mjLIGHT_DIRECTIONAL),
    )

    # scene.unsupported: reported by the static checks (A040), which own it; nothing to build
    for i, body in enumerate(scene.bodies):
        if body.path in ctx.bodies:
            ctx.inconsistent(f"duplicate body path {body.path}; the second one is ignored", body)
            continue
        ctx.bodies[body.path] = body
        ctx.body_index[body.path] = i
        ctx.names.add("body", body.path, body.source)
        if body.mass < 0:
            ctx.invariant(registry.NEGATIVE_MASS,
                f"{body.path}: negative mass {body.mass}; using the geometry mass",
                body,
            )

    tree, loops, distances = classify_mates(ctx)
    parents, roots = orient(ctx, tree)
    add_static_bodies(ctx)
    add_dynamic_bodies(ctx, parents, roots)
    add_loop_closures(ctx, loops)
    add_distance_mates(ctx, distances)
    add_shafts(ctx)
    add_couplings(ctx)
    add_excludes(ctx)
    add_contact_pairs(ctx)

    # pass 1: geometry mass properties (bounded so massless bodies still compile)
    spec.compiler.boundmass = 1e-9
    spec.compiler.boundinertia = 1e-12
    model = ctx.compile("mass-properties")
    set_inertials(ctx, model)
    set_kinematic_inertia(ctx, model)
    spec.compiler.boundmass = 0.0
    spec.compiler.boundinertia = 0.0
    # pass 2: effective joint inertias for gains / stiffness caps
    model = ctx.compile("inertia")
    add_controllers(ctx, model)
    add_shaft_motors(ctx, model)
    add_keyframe(ctx, model)
    add_shaft_parts(ctx)  # after the keyframe: a differential holds the shafts' starting angles
    set_restitution(ctx)
    # pass 3: final
    ctx.out.model = ctx.compile("final")
    ctx.out.integrator, ctx.out.integrator_why = choose_integrator(mj, ctx.out.model, scene.integrator)
    spec.option.integrator = ctx.out.model.opt.integrator  # what an exported MJCF runs with too


# -- mates -> tree ---------------------------------------------------------------------------
def classify_mates(ctx: BuildContext) -> tuple[list[Mate], list[Mate], list[Mate]]:
    """(tree, loops, distances): the mates that become joints of the kinematic tree, those that
    close a loop or start apart (equality constraints), and the distance mates."""
    usable: list[tuple[int, int, Mate]] = []
    distances: list[Mate] = []
    pulled: list[Mate] = []
    # a mate that a controller drives needs its joint (actuators act on joints), so it keeps the offset
    driven = {_pair(c) for c in ctx.scene.controllers if len(c.connectors) == 2}
    for idx, m in enumerate(ctx.scene.mates):
        ctx.names.add("mate", m.path, m.source)
        if not _buildable(ctx, m):
            continue
        violated = check_alignment(ctx, m)
        c0, c1 = m.connectors
        if c0.body and c1.body:
            ctx.mated.add(frozenset((c0.body, c1.body)))
        if m.kind == "distance":
            distances.append(m)
        elif violated and m.kind in ("hinge", "ball", "lock") and _pair(m) not in driven:
            # starts apart (A016): an equality between the two connector frames pulls the parts
            # together, as a runtime does; a joint would keep the offset for ever
            ctx.violated.add(m.path)
            pulled.append(m)
        else:
            usable.append((TREE_PRIORITY[m.kind], idx, m))
    tree, loops = _spanning_tree(ctx, usable, pulled)
    ctx.out.tree_mates = [m.path for m in tree]
    ctx.out.loop_mates = [m.path for m in loops]
    return tree, loops, distances


def _buildable(ctx: BuildContext, m: Mate) -> bool:
    """Whether the mate joins two different bodies (or a body and the world) of the scene; a note
    for one that does not (the static checks own those findings)."""
    if not m.enabled:
        ctx.disabled(f"{m.path} is disabled and not simulated", m)
        return False
    if m.kind not in TREE_PRIORITY and m.kind != "distance":
        ctx.invariant(registry.NOT_SIMULATED, f"{m.path}: unknown mate kind {m.kind!r}; ignored", m)
        return False
    if len(m.connectors) != 2:
        ctx.invariant(registry.CONNECTOR_COUNT, f"{m.path}: a mate needs exactly 2 connectors", m)
        return False
    c0, c1 = m.connectors
    n0, n1 = node(ctx, c0), node(ctx, c1)
    bad = [c for c, n in ((c0, n0), (c1, n1)) if n is None]
    if bad:
        ctx.inconsistent(f"{m.path}: connector {bad[0].path} belongs to unknown body {bad[0].body}", m)
        return False
    if c0.body is not None and c0.body == c1.body:
        ctx.invariant(registry.MATE_SAME_BODY, f"{m.path}: both connectors belong to {c0.body}; ignored", m)
        return False
    if n0 == WORLD and n1 == WORLD:
        return False  # no effect; the static checks own this finding (A017)
    for c in (c0, c1):
        if float(np.linalg.norm(c.main_axis)) == 0.0:
            ctx.invariant(registry.ZERO_MAIN_AXIS, f"connector {c.path} has a zero main_axis", c)
    return True


def _spanning_tree(ctx: BuildContext, usable: list[tuple[int, int, Mate]],
                   pulled: list[Mate]) -> tuple[list[Mate], list[Mate]]:
    """(tree, loops): the usable mates in priority order join body groups (union-find) while they
    can; the rest, and the mates pulled together, close loops.  Both in the scene's order."""
    usable = sorted(usable, key=lambda t: (t[0], t[1]))
    parent: dict[str, str] = {}

    def find(x: str) -> str:
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    tree: list[Mate] = []
    loops: list[Mate] = list(pulled)
    for _, _, m in usable:
        a, b = find(node(ctx, m.connectors[0]) or WORLD), find(node(ctx, m.connectors[1]) or WORLD)
        if a != b:
            parent[a] = b
            tree.append(m)
        else:
            loops.append(m)
    order = {m.path: i for i, m in enumerate(ctx.scene.mates)}
    tree.sort(key=lambda m: order[m.path])
    loops.sort(key=lambda m: order[m.path])
    return tree, loops


def _pair(item) -> frozenset[str]:
    return frozenset(c.path for c in item.connectors)


def check_alignment(ctx: BuildContext, m: Mate) -> bool:
    """Rule 43: both sides placed but frames do not coincide (SNAP offsets removed).  True when
    the mate starts violated."""
    (p0, a0, _), (p1, a1, _) = (world_connector(ctx, c) for c in m.connectors)
    d = p1 - p0
    if m.kind in ("prismatic", "cylindrical"):
        d = d - np.dot(d, a0) * a0
    sep = float(np.linalg.norm(d)) if m.kind != "distance" else 0.0
    ang = angle_between(a0, a1) if m.kind not in ("ball", "distance") else 0.0
    if sep > ALIGN_POS_TOL or ang > ALIGN_ANGLE_TOL:
        return True  # A016, the static check's, is the one finding: the backend runs on such a scene on purpose
    return False


def world_connector(ctx: BuildContext, c: Connector) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    p, a, n = local_frame(ctx, c)
    if c.body is None:
        return p, a, n
    bp, bq = world_pose(ctx, c.body)
    r = quat_to_mat(bq)
    return bp + r @ p, r @ a, r @ n


def orient(ctx: BuildContext, tree: list[Mate]) -> tuple[dict[str, tuple[str, Mate]], list[str]]:
    adj: dict[str, list[Mate]] = {}
    for m in tree:
        for c in m.connectors:
            adj.setdefault(node(ctx, c) or WORLD, []).append(m)
    parents: dict[str, tuple[str, Mate]] = {}
    visited = {WORLD}
    roots: list[str] = []

    def bfs(start: str) -> list[str]:
        seen_order = [start]
        queue = [start]
        while queue:
            u = queue.pop(0)
            for m in adj.get(u, []):
                for c in m.connectors:
                    v = node(ctx, c) or WORLD
                    if v not in visited:
                        visited.add(v)
                        parents[v] = (u, m)
                        queue.append(v)
                        seen_order.append(v)
        return seen_order

    bfs(WORLD)
    dynamic = [p for p, b in ctx.bodies.items() if b.is_dynamic]
    for path in dynamic:
        if path in visited:
            continue
        # collect the component without marking it, then choose its root
        comp, stack = {path}, [path]
        while stack:
            u = stack.pop()
            for m in adj.get(u, []):
                for c in m.connectors:
                    v = node(ctx, c) or WORLD
                    if v not in comp:
                        comp.add(v)
                        stack.append(v)
        root = max(comp, key=lambda p: (len(adj.get(p, [])), -ctx.body_index[p]))
        visited.add(root)
        roots.append(root)
        bfs(root)
    ctx.out.free_roots = roots
    return parents, roots


# -- bodies ----------------------------------------------------------------------------------
def add_static_bodies(ctx: BuildContext) -> None:
    for path, body in ctx.bodies.items():
        if body.is_dynamic:
            continue
        name = ctx.names.name("body", path)
        mb = ctx.spec.worldbody.add_body(
            name=name, pos=list(body.world_pos), quat=list(quat_normalize(body.world_quat))
        )
        ctx.mj_bodies[path] = mb
        if body.kinematic:
            add_kinematic_joint(ctx, path, body, mb)
            ctx.note(
                INFO,
                registry.KINEMATIC_BODY,
                f"{path} is kinematic: it moves with its velocity whatever hits it (a free body of effectively "
                "infinite inertia set to its prescribed pose and velocity every step, so contacts see how fast "
                "it moves and friction carries what rests on it)",
                body,
            )
        add_geoms(ctx, mb, body)
    exclude_kinematic_contacts(ctx)


def add_dynamic_bodies(ctx: BuildContext, parents: dict[str, tuple[str, Mate]], roots: list[str]) -> None:
    # breadth-first order: parents are created first
    order: list[str] = []
    children: dict[str, list[str]] = {}
    for child, (par, _) in parents.items():
        children.setdefault(par, []).append(child)
    queue = [WORLD, *roots]
    while queue:
        u = queue.pop(0)
        if u != WORLD:
            order.append(u)
        kids = sorted(children.get(u, []), key=lambda p: ctx.body_index[p])
        queue.extend(kids)
    for path in order:
        body = ctx.bodies[path]
        if path in parents:
            par, mate = parents[path]
            cc, pc = (
                (mate.connectors[1], mate.connectors[0])
                if node(ctx, mate.connectors[1]) == path
                else mate.connectors
            )
            parent_path = pc.body if par == WORLD else par
            mj_parent = ctx.mj_bodies[parent_path] if parent_path is not None else ctx.spec.worldbody
            ppos, pquat = world_pose(ctx, parent_path)
        else:
            mate = None
            mj_parent = ctx.spec.worldbody
            ppos, pquat = np.zeros(3), np.array([1.0, 0, 0, 0])
        cpos, cquat = world_pose(ctx, path)
        rpos, rquat = relative_pose(ppos, pquat, cpos, cquat)
        mb = mj_parent.add_body(name=ctx.names.name("body", path), pos=list(rpos), quat=list(rquat))
        ctx.mj_bodies[path] = mb
        if mate is None:
            mb.add_freejoint(name=ctx.names.add("joint", path, body.source, ":free"))
        else:
            add_joint(ctx, mb, mate, cc)
        add_geoms(ctx, mb, body)


def add_joint(ctx: BuildContext, mb: Any, m: Mate, cc: Connector) -> None:
    mj = ctx.mj
    sign = 1 if cc is m.connectors[1] else -1
    pos, axis, _ = local_frame(ctx, cc)
    ctx.out.joint_sign[m.path] = sign
    names: list[str] = []
    # a cylindrical mate is a hinge and a slide on the same axis
    for kinds, jtype, suffix, offset in (
        (("hinge", "cylindrical"), mj.mjtJoint.mjJNT_HINGE, ":rot", m.initial_angle),
        (("prismatic", "cylindrical"), mj.mjtJoint.mjJNT_SLIDE, ":slide", m.initial_position),
    ):
        if m.kind in kinds:
            n = ctx.names.add("joint", m.path, m.source, suffix if m.kind == "cylindrical" else "")
            k = 0 if jtype == mj.mjtJoint.mjJNT_HINGE else 1  # friction of the rotation / the translation
            mb.add_joint(name=n, type=jtype, pos=list(pos), axis=list(axis), ref=sign * float(offset),
                         frictionloss=float(m.friction_limit[k]), damping=[float(m.viscous_friction[k])])
            names.append(n)
    if m.kind == "ball":
        n = ctx.names.add("joint", m.path, m.source)
        mb.add_joint(name=n, type=mj.mjtJoint.mjJNT_BALL, pos=list(pos))
        names.append(n)
    ctx.out.joints[m.path] = names
    add_monitor(ctx, m, "tree")


def add_monitor(ctx: BuildContext, m: Mate, role: str) -> None:
    c0, c1 = m.connectors
    p0, a0, n0 = monitor_frame(ctx, c0)
    p1, a1, n1 = monitor_frame(ctx, c1)
    ctx.out.monitors.append(
        MateMonitor(
            m.path,
            m.kind,
            owner_mj_name(ctx, c0),
            p0,
            a0,
            n0,
            owner_mj_name(ctx, c1),
            p1,
            a1,
            n1,
            float(m.initial_distance),
            role,
        )
    )


def monitor_frame(ctx: BuildContext, c: Connector) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return local_frame(ctx, c)


# -- loops, distances, filtering, friction ----------------------------------------------------
def add_loop_closures(ctx: BuildContext, loops: list[Mate]) -> None:
    mj = ctx.mj
    for m in loops:
        c0, c1 = m.connectors
        b0, b1 = owner_mj_name(ctx, c0), owner_mj_name(ctx, c1)
        p0, a0, _ = local_frame(ctx, c0)
        p1 = local_frame(ctx, c1)[0]
        if m.path in ctx.violated:
            pull_together(ctx, m)
            add_monitor(ctx, m, "pulled")
            continue
        if m.kind == "ball":
            connect(ctx, m.path, "", b0, b1, p0, m)
        elif m.kind == "hinge":
            connect(ctx, m.path, ":a", b0, b1, p0 + HINGE_LOOP_HALF_LENGTH * a0, m)
            connect(ctx, m.path, ":b", b0, b1, p0 - HINGE_LOOP_HALF_LENGTH * a0, m)
            ctx.note(
                INFO,
                registry.LOOP_CLOSURE,
                f"{m.path} closes a kinematic loop: two connect equalities on its axis (free rotation kept)",
                m,
            )
        elif m.kind == "lock":
            e = ctx.spec.add_equality(
                name=ctx.names.add("equality", m.path, m.source), type=mj.mjtEq.mjEQ_WELD
            )
            e.objtype = mj.mjtObj.mjOBJ_BODY
            e.name1, e.name2 = b0, b1
            data = np.zeros(len(e.data))
            data[0:3] = p1  # anchor in body2; relpose zeros -> taken from the assembled pose
            data[10] = 1.0
            e.data = data
            ctx.note(INFO, registry.LOOP_CLOSURE, f"{m.path} closes a kinematic loop: weld equality", m)
        else:
            ctx.note(
                WARNING,
                registry.LOOP_CLOSURE_UNSUPPORTED,
                f"{m.path}: a loop-closing {m.kind} mate cannot be expressed in MuJoCo; it is NOT enforced",
                m,
            )
            add_monitor(ctx, m, "open")
            continue
        if m.kind == "ball":
            ctx.note(INFO, registry.LOOP_CLOSURE, f"{m.path} closes a kinematic loop: connect equality", m)
        add_monitor(ctx, m, "loop")


def pull_together(ctx: BuildContext, m: Mate) -> None:
    """A mate that starts apart becomes equalities between sites on the two connector frames (a
    site pair keeps both points, where a body anchor would be re-measured from the start pose):
    one connect for a ball, two on the axis for a hinge (rotation about it stays free), a weld of
    the two frames for a lock."""
    mj = ctx.mj
    c0, c1 = m.connectors
    frames = [local_frame(ctx, c) for c in (c0, c1)]
    owners = [ctx.mj_bodies.get(c.body) if c.body is not None and c.body in ctx.mj_bodies else ctx.spec.worldbody
              for c in (c0, c1)]
    offsets = {"ball": [("", 0.0)], "lock": [("", 0.0)],
               "hinge": [(":a", HINGE_LOOP_HALF_LENGTH), (":b", -HINGE_LOOP_HALF_LENGTH)]}[m.kind]
    for suffix, off in offsets:
        names = []
        for k, (owner, (p, a, n)) in enumerate(zip(owners, frames)):
            quat = mat_to_quat_wxyz(np.column_stack([n, np.cross(a, n), a]))
            site = owner.add_site(name=ctx.names.add("site", m.path, m.source, f"{suffix}:pull{k}"),
                                  pos=list(p + off * a), quat=list(quat))
            names.append(site.name)
        kind = mj.mjtEq.mjEQ_WELD if m.kind == "lock" else mj.mjtEq.mjEQ_CONNECT
        e = ctx.spec.add_equality(name=ctx.names.add("equality", m.path, m.source, suffix), type=kind)
        e.objtype = mj.mjtObj.mjOBJ_SITE
        e.name1, e.name2 = names
        # closes the gap within about 0.2 s without flinging the part: MuJoCo's default (0.02 s)
        # threw a 2 kg lamp pulled in from 0.3 m around at 400 rad/s
        e.solref = [PULL_TIME_CONSTANT, 1.0]
        if m.kind == "lock":
            data = np.zeros(len(e.data))
            data[10] = 1.0
            e.data = data
    ctx.note(INFO, registry.LOOP_CLOSURE, f"{m.path} starts apart (A016); an equality constraint between its connector frames "
             "pulls the two parts together, as a runtime does", m)


def connect(ctx: BuildContext, path: str, suffix: str, b0: str, b1: str, anchor: np.ndarray, m: Mate) -> None:
    mj = ctx.mj
    e = ctx.spec.add_equality(
        name=ctx.names.add("equality", path, m.source, suffix), type=mj.mjtEq.mjEQ_CONNECT
    )
    e.objtype = mj.mjtObj.mjOBJ_BODY
    e.name1, e.name2 = b0, b1
    data = np.zeros(len(e.data))
    data[0:3] = anchor
    data[10] = 1.0
    e.data = data


def add_distance_mates(ctx: BuildContext, mates: list[Mate]) -> None:
    mj = ctx.mj
    for m in mates:
        c0, c1 = m.connectors
        (w0, _, _), (w1, _, _) = world_connector(ctx, c0), world_connector(ctx, c1)
        length0 = float(np.linalg.norm(w1 - w0))
        target = float(m.initial_distance if m.target_distance is None else m.target_distance)
        if target < 1e-6 and length0 < 1e-6:
            connect(ctx, 
                m.path, "", owner_mj_name(ctx, c0), owner_mj_name(ctx, c1), local_frame(ctx, c0)[0], m
            )
            ctx.note(
                WARNING,
                registry.DISTANCE_MATE_APPROXIMATED,
                f"{m.path}: Distance mate with zero distance approximated as a ball (connect) constraint",
                m,
            )
            add_monitor(ctx, m, "distance")
            continue
        sites = []
        for c, suffix in ((c0, ":site0"), (c1, ":site1")):
            owner = ctx.mj_bodies.get(c.body) if c.body is not None else ctx.spec.worldbody
            s = owner.add_site(
                name=ctx.names.add("site", m.path, m.source, suffix), pos=list(local_frame(ctx, c)[0])
            )
            sites.append(s.name)
        t = ctx.spec.add_tendon(name=ctx.names.add("tendon", m.path, m.source))
        t.wrap_site(sites[0])
        t.wrap_site(sites[1])
        e = ctx.spec.add_equality(
            name=ctx.names.add("equality", m.path, m.source), type=mj.mjtEq.mjEQ_TENDON
        )
        e.objtype = mj.mjtObj.mjOBJ_TENDON
        e.name1 = t.name
        data = np.zeros(len(e.data))
        data[0] = target - length0  # MuJoCo holds length - length(qpos0) at data[0]
        e.data = data
        ctx.note(
            WARNING,
            registry.DISTANCE_MATE_APPROXIMATED,
            f"{m.path}: Distance mate approximated by a tendon-length equality (target {target:g} m)",
            m,
        )
        add_monitor(ctx, m, "distance")
