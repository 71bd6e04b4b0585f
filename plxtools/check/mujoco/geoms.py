"""Geometry, mass properties, collision filtering and contact pairs (steps of the MjSpec build, on a :class:`BuildContext`)."""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from plxtools import DOCS_BASE_URL
from plxtools.check.mujoco.context import BuildContext
from plxtools.check.mujoco.poses import Z_TO_Y_QUAT, quat_mul, quat_normalize
from plxtools.check.mujoco.notes import INFO, WARNING
from plxtools.check.mujoco.restitution import restitution_solref, slowest_exact_impact, speed_ratio_error
from plxtools.check.mujoco.results import VISUAL_GROUP
from plxtools.check.scene import GEOM_KINDS, Body, Geom
from plxtools.rules import registry

MESH_EXTENSIONS = (".stl", ".obj", ".msh")
PALETTE = [
    (0.85, 0.33, 0.25, 1.0),
    (0.25, 0.45, 0.85, 1.0),
    (0.95, 0.75, 0.2, 1.0),
    (0.35, 0.7, 0.35, 1.0),
    (0.6, 0.4, 0.75, 1.0),
    (0.2, 0.75, 0.75, 1.0),
]
STATIC_RGBA = (0.55, 0.6, 0.55, 1.0)


# -- geoms -----------------------------------------------------------------------------------
def add_geoms(ctx: BuildContext, mb: Any, body: Body) -> None:
    for g in body.geoms:
        add_geom(ctx, mb, body, g)


def geom_size_ok(ctx: BuildContext, g: Geom) -> bool:
    k = g.kind
    bad = ""
    if k == "box" and min(g.size) <= 0:
        bad = f"box size {tuple(g.size)} must be positive (full edge lengths; the default is 0,0,0)"
    elif k in ("sphere", "cylinder", "capsule") and g.radius <= 0:
        bad = f"{k} radius {g.radius} must be positive"
    elif k == "cylinder" and g.height <= 0:
        bad = f"cylinder height {g.height} must be positive"
    elif k == "capsule" and g.height < 0:
        bad = f"capsule height {g.height} must not be negative"
    elif k == "mesh" and min(g.mesh_scale) <= 0:
        bad = f"mesh scale {tuple(g.mesh_scale)} must be positive"
    if bad:
        ctx.invariant(registry.NON_POSITIVE_SIZE, f"{g.path}: {bad}; geometry skipped", g)
        return False
    return True


def add_geom(ctx: BuildContext, mb: Any, body: Body, g: Geom) -> None:
    if g.kind not in GEOM_KINDS:
        ctx.invariant(registry.NOT_SIMULATED,
            f"{g.path}: geometry kind {g.kind!r} is not supported; skipped",
            g,
        )
        return
    if not geom_size_ok(ctx, g):
        return
    name = ctx.names.add("geom", g.path, g.source)
    kw: dict[str, Any] = {"name": name, "pos": list(g.pos)}
    quat = _shape(ctx, body, g, kw)
    if quat is None:
        return
    kw["quat"] = list(quat_normalize(quat))
    collide = g.enable_collisions and not g.visual_only
    _surface(ctx, body, g, kw, collide)
    mb.add_geom(**kw)
    if collide and g.material:
        ctx.geoms_by_material.setdefault(g.material, []).append((name, body.path))


def _shape(ctx: BuildContext, body: Body, g: Geom, kw: dict[str, Any]) -> Any:
    """The MuJoCo geom type and size of ``g`` into ``kw``; returns its orientation (MuJoCo's
    cylinders and capsules lie along Z, OpenPLX's along Y), or None when the geometry is skipped."""
    mj = ctx.mj
    quat = quat_normalize(g.quat)
    if g.kind == "box":
        kw.update(type=mj.mjtGeom.mjGEOM_BOX, size=[s / 2.0 for s in g.size])
    elif g.kind == "sphere" or (g.kind == "capsule" and g.height == 0):
        kw.update(type=mj.mjtGeom.mjGEOM_SPHERE, size=[g.radius, 0, 0])
    elif g.kind in ("cylinder", "capsule"):
        kind = mj.mjtGeom.mjGEOM_CYLINDER if g.kind == "cylinder" else mj.mjtGeom.mjGEOM_CAPSULE
        kw.update(type=kind, size=[g.radius, g.height / 2.0, 0])
        quat = quat_mul(quat, Z_TO_Y_QUAT)
    elif g.kind == "plane":
        if body.is_dynamic or body.kinematic:  # a kinematic body is a free MuJoCo body (mujoco.kinematic)
            ctx.note(WARNING, registry.PLANE_ON_DYNAMIC_BODY, f"{g.path}: planes can only be static in MuJoCo; skipped", g)
            return None
        kw.update(type=mj.mjtGeom.mjGEOM_PLANE, size=[g.size[0] / 2.0, g.size[1] / 2.0, 1.0])
    elif g.kind == "mesh":
        mesh = add_mesh(ctx, g)
        if mesh is None:
            return None
        kw.update(type=mj.mjtGeom.mjGEOM_MESH, meshname=mesh)
    return quat


def _surface(ctx: BuildContext, body: Body, g: Geom, kw: dict[str, Any], collide: bool) -> None:
    """Whether ``g`` collides and gives mass, its colour and its friction, into ``kw``."""
    kw["contype"] = 1 if collide else 0
    kw["conaffinity"] = 1 if collide else 0
    in_mass = g.include_in_mass and not g.visual_only
    kw["density"] = float(g.density) if in_mass else 0.0
    if in_mass and g.density <= 0:
        kw["density"] = 0.0  # gives no mass; the static checks own this finding (A038)
    if g.visual_only:
        kw["group"] = VISUAL_GROUP
    if g.rgba is not None:
        kw["rgba"] = list(g.rgba)
    elif not body.is_dynamic:
        kw["rgba"] = list(STATIC_RGBA)
    else:
        kw["rgba"] = list(PALETTE[ctx.body_index[body.path] % len(PALETTE)])
    if ctx.scene.default_friction is not None:
        kw["friction"] = [float(ctx.scene.default_friction), 0.005, 0.0001]


def add_mesh(ctx: BuildContext, g: Geom) -> str | None:
    name = ctx.names.add("mesh", g.path, g.source)
    kw: dict[str, Any] = {"name": name, "scale": list(g.mesh_scale)}
    if g.mesh_file:
        f = g.mesh_file
        if not os.path.isabs(f) and ctx.scene.base_dir:
            f = os.path.join(ctx.scene.base_dir, f)
        if not os.path.isfile(f):
            ctx.invariant(registry.MISSING_FILE, f"{g.path}: mesh file not found: {f}; geometry skipped", g
            )
            return None
        if not f.lower().endswith(MESH_EXTENSIONS):
            ctx.note(
                WARNING,
                registry.MESH_FORMAT_UNSUPPORTED,
                f"{g.path}: MuJoCo reads only {', '.join(MESH_EXTENSIONS)} meshes, not {f}; skipped",
                g,
            )
            return None
        kw["file"] = os.path.abspath(f)
    elif g.mesh_vertices:
        kw["uservert"] = [float(x) for v in g.mesh_vertices for x in v]
        if g.mesh_indices:
            kw["userface"] = [int(i) for i in g.mesh_indices]
    else:
        ctx.invariant(registry.NON_POSITIVE_SIZE, f"{g.path}: mesh has neither a file nor vertices; skipped", g)
        return None
    if g.visual_only:
        # a visual never changes the physics: no mass from it (its geom has density 0), its
        # volume is not needed (a flat mesh is fine as a shell), and one MuJoCo cannot load is
        # left out with a note instead of failing the whole scene
        kw["inertia"] = ctx.mj.mjtMeshInertia.mjMESH_INERTIA_SHELL
        problem = visual_mesh_problem(ctx.mj, kw)
        if problem is not None:
            ctx.note(INFO, registry.VISUAL_MESH_SKIPPED, f"{g.path}: visual mesh left out of the MuJoCo scene ({problem}); "
                     f"it has no effect on the physics", g)
            return None
    elif not g.convex and g.enable_collisions:
        ctx.note(
            INFO, registry.CONCAVE_MESH_HULL, f"{g.path}: MuJoCo collides with the convex hull of this mesh", g
        )
    ctx.spec.add_mesh(**kw)
    return name


def visual_mesh_problem(mj: Any, kw: dict[str, Any]) -> str | None:
    """Why MuJoCo cannot load this visual mesh (compiled alone, on a static geom), or None."""
    spec = mj.MjSpec()
    mesh_kw = {k: v for k, v in kw.items() if k != "name"}
    spec.add_mesh(name="probe", **mesh_kw)
    spec.worldbody.add_geom(type=mj.mjtGeom.mjGEOM_MESH, meshname="probe", contype=0, conaffinity=0, density=0.0)
    try:
        spec.compile()
    except Exception as exc:  # MuJoCo raises ValueError with its compiler's message
        text = str(exc).replace("Error: ", "").splitlines()[0].strip()
        return text.split(" Element name")[0].rstrip(". ") or type(exc).__name__
    return None


def add_excludes(ctx: BuildContext) -> None:
    pairs: list[tuple[str, str, Any]] = []
    for ex in ctx.scene.excludes:
        pairs.append((ex.body1, ex.body2, ex))
    for m in ctx.scene.mates:
        c0, c1 = m.connectors if len(m.connectors) == 2 else (None, None)
        if m.enabled and c0 is not None and c1 is not None and c0.body and c1.body:
            pairs.append((c0.body, c1.body, None))
    done: set[frozenset[str]] = set()
    for a, b, item in pairs:
        if a == b:
            continue
        ba, bb = ctx.bodies.get(a), ctx.bodies.get(b)
        if ba is None or bb is None:
            if item is not None:
                ctx.inconsistent(f"collision exclusion names an unknown body: {a if ba is None else b}", item,
                                 path=a if ba is None else b)
            continue
        key = frozenset((a, b))
        ctx.excluded.add(key)
        if key in done or (not ba.is_dynamic and not bb.is_dynamic):
            continue
        done.add(key)
        ctx.spec.add_exclude(bodyname1=ctx.names.name("body", a), bodyname2=ctx.names.name("body", b))


def add_contact_pairs(ctx: BuildContext) -> None:
    seen: dict[frozenset[str], str] = {}
    for cm in ctx.scene.contact_models:
        ctx.names.add("contact", cm.path, cm.source)
        if not cm.enabled:
            ctx.disabled(f"{cm.path} is disabled", cm)
            continue
        key = frozenset((cm.material1, cm.material2))
        if key in seen:
            ctx.invariant(registry.DUPLICATE_CONTACT_MODEL,
                f"{cm.path}: material pair already has contact model {seen[key]}; ignored",
                cm,
            )
            continue
        seen[key] = cm.path
        mu = (
            cm.friction
            if cm.friction is not None
            else (ctx.scene.default_friction if ctx.scene.default_friction is not None else 1.0)
        )
        if mu < 0:
            ctx.invariant(registry.INVALID_CONTACT_PARAMETER, f"{cm.path}: friction coefficient {mu} < 0; using 0", cm
            )
            mu = 0.0
        if cm.friction_model not in ("dry", "dry_cone"):
            if cm.friction_model.startswith("dry"):
                ctx.note(
                    INFO,
                    registry.FRICTION_MODEL_APPROXIMATED,
                    f"{cm.path}: {cm.friction_model} friction approximated by MuJoCo's Coulomb cone with mu={mu:g}",
                    cm,
                )
            # other models: Coulomb mu is used; the static checks own that finding (A040)
        bouncy = cm.restitution is not None and 0.0 <= cm.restitution <= 1.0
        g1 = ctx.geoms_by_material.get(cm.material1, [])
        g2 = ctx.geoms_by_material.get(cm.material2, [])
        if not g1 or not g2:
            missing = cm.material1 if not g1 else cm.material2
            ctx.note(
                INFO,
                registry.CONTACT_MODEL_UNUSED,
                f"{cm.path}: no colliding geometry uses material {missing}",
                cm,
            )
        made: set[frozenset[str]] = set()
        for n1, b1 in g1:
            for n2, b2 in g2:
                k = frozenset((n1, n2))
                if n1 == n2 or k in made or b1 == b2 or frozenset((b1, b2)) in ctx.excluded:
                    continue
                if not ctx.bodies[b1].is_dynamic and not ctx.bodies[b2].is_dynamic:
                    continue
                made.add(k)
                pair = ctx.spec.add_pair(
                    name=ctx.names.add("pair", cm.path, cm.source, f":{len(made)}"),
                    geomname1=n1,
                    geomname2=n2,
                    condim=3,
                    friction=[mu, mu, 0.005, 0.0001, 0.0001],
                )
                _remember_pair(ctx, pair, cm.restitution if bouncy else None, (b1, b2))
        if bouncy and made and cm.restitution > 0.0:  # e = 0 stops an impact exactly: nothing to note
            ctx.bouncy_models.append(cm)


def _remember_pair(ctx: BuildContext, pair: Any, restitution: float | None, bodies: tuple[str, str]) -> None:
    """A pair whose softness set_restitution sets: one with a restitution, one touching a kinematic body."""
    if restitution is not None:
        ctx.bouncy_pairs.append((pair, float(restitution)))
    if any(b in ctx.out.kinematic for b in bodies):
        ctx.carrier_pairs.append(pair)


FRICTION_SOLREF = (0.02, 1.0)  # MuJoCo's default contact softness, kept for friction
MIN_CHECKED_IMPACT = 1.0  # m/s: a drop of 5 cm; slower impacts are not promised the 3 %


def set_restitution(ctx: BuildContext) -> None:
    """The contact velocity targets of pairs with a normal restitution, for the final time step (a
    stiff spring may have shortened it after the pairs were made), and what each one promises (A137)."""
    h = float(ctx.spec.option.timestep)
    for pair, e in ctx.bouncy_pairs:
        pair.solref, pair.solimp = restitution_solref(e, h)
        pair.solreffriction = list(FRICTION_SOLREF)  # 0 would give the friction rows the impact's target
    for pair in ctx.carrier_pairs:
        # what a kinematic body carries: MuJoCo's default friction (a time constant of 0.02 s) lets
        # a load creep at its acceleration x 0.01 s (a box on a table at 1.5 rad/s slid outward at
        # 1.35 cm/s, 6 % of its radius in 3 s); the slip removed in one step creeps at a h
        pair.solreffriction = [-0.0, -1.0 / h]
    g = float(np.linalg.norm(np.asarray(ctx.spec.option.gravity, dtype=float)))
    for cm in ctx.bouncy_models:
        e = float(cm.restitution)
        slow = slowest_exact_impact(e, h, g)
        said = (f"{cm.path}: normal_restitution {e:g}: each impact leaves at {e:g} x its normal speed "
                f"(MuJoCo contact with the velocity target -{e:g} v in the step it begins; see {DOCS_BASE_URL}physics/)")
        if slow <= MIN_CHECKED_IMPACT:
            ctx.note(INFO, registry.RESTITUTION_APPROXIMATED, said, cm)
            continue
        err = 100.0 * speed_ratio_error(e, h, g, MIN_CHECKED_IMPACT)
        ctx.note(WARNING, registry.RESTITUTION_APPROXIMATED, f"{said}; but the impact is resolved at the depth the {h:g} s step finds it "
                 f"(up to v h), so an impact slower than {slow:.2g} m/s may rebound more than 3 % short of "
                 f"{e:g} in speed (at 1 m/s by up to {err:.0f} %): a shorter time step (--timestep) lowers that", cm)


# -- mass properties -------------------------------------------------------------------------
def set_inertials(ctx: BuildContext, model: Any) -> None:
    for path, body in ctx.bodies.items():
        if not body.is_dynamic:
            continue
        name = ctx.names.name("body", path)
        bid = model.body(name).id
        m0 = float(model.body_mass[bid])
        geom_mass = m0 if m0 > 1e-8 else 0.0
        inertia0 = np.array(model.body_inertia[bid])
        iquat0 = np.array(model.body_iquat[bid])
        ipos0 = np.array(model.body_ipos[bid])
        mb = ctx.mj_bodies[path]
        mass = float(body.mass) if body.mass > 0 else 0.0
        tensor = valid_tensor(ctx, body)
        cm = np.asarray(body.cm_pos, dtype=float) if body.cm_pos is not None else None
        if tensor is None and mass == 0.0 and cm is None:
            if geom_mass == 0.0:
                ctx.invariant(registry.ZERO_MASS_DYNAMIC_BODY,
                    f"{path}: dynamic body with mass 0 and no mass-contributing geometry; simulated with 1 kg",
                    body,
                )
                fallback_inertial(ctx, mb, body, 1.0, model, bid)
            continue  # MuJoCo computes from the geoms, same as AGX
        if mass == 0.0:
            mass = geom_mass
            if mass == 0.0:
                ctx.invariant(registry.ZERO_MASS_DYNAMIC_BODY,
                    f"{path}: dynamic body with mass 0 and no mass-contributing geometry; simulated with 1 kg",
                    body,
                )
                mass = 1.0
        mb.explicitinertial = True
        mb.mass = mass
        if tensor is not None:
            mb.fullinertia = [
                tensor[0, 0],
                tensor[1, 1],
                tensor[2, 2],
                tensor[0, 1],
                tensor[0, 2],
                tensor[1, 2],
            ]
            mb.ipos = list(cm if cm is not None else (ipos0 if geom_mass > 0 else np.zeros(3)))
            mb.iquat = [1.0, 0, 0, 0]
        elif geom_mass > 0:
            # inertia shape from the geometry, scaled to the given mass (AGX behaviour)
            mb.inertia = list(inertia0 * (mass / geom_mass))
            mb.iquat = list(iquat0)
            mb.ipos = list(cm if cm is not None else ipos0)
        else:
            ctx.note(
                WARNING,
                registry.MASS_WITHOUT_GEOMETRY,
                f"{path}: mass {mass:g} kg given but no geometry to shape the inertia; using a 0.1 m solid sphere",
                body,
            )
            fallback_inertial(ctx, mb, body, mass, model, bid)
            if cm is not None:
                mb.ipos = list(cm)


def fallback_inertial(ctx: BuildContext, mb: Any, body: Body, mass: float, model: Any, bid: int) -> None:
    i = 0.4 * mass * 0.1**2
    mb.explicitinertial = True
    mb.mass = mass
    mb.inertia = [i, i, i]
    mb.iquat = [1.0, 0, 0, 0]
    mb.ipos = [0.0, 0.0, 0.0]


def valid_tensor(ctx: BuildContext, body: Body) -> np.ndarray | None:
    if body.inertia_tensor is None:
        return None
    t = np.asarray(body.inertia_tensor, dtype=float).reshape(3, 3)
    if not np.any(np.diag(t) != 0):
        return None  # AGX: tensor counts as set only when a diagonal element is non-zero
    problem = ""
    if not np.allclose(t, t.T, rtol=1e-9, atol=1e-12):
        problem = "is not symmetric"
    else:
        ev = np.linalg.eigvalsh(t)
        if ev.min() <= 0:
            problem = f"is not positive definite (eigenvalues {[round(float(x), 6) for x in ev]})"
        else:
            a, b, c = sorted(float(x) for x in ev)
            if a + b < c * (1 - 1e-9):
                problem = f"breaks the triangle inequality (principal moments {[round(x, 6) for x in (a, b, c)]})"
    if problem:
        ctx.invariant(registry.INVALID_INERTIA,
            f"{body.path}: inertia tensor {problem}; computed from geometry instead",
            body,
        )
        return None
    return t
