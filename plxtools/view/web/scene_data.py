"""What the preview page draws, as plain JSON: the compiled MuJoCo model's geometry, by OpenPLX path.

The page draws the model MuJoCo simulates (``Simulation.model``), not a second reading of the
file: every geom with its type, size and offset in its body's frame, the bodies' world poses from
``MjData`` (what ``plx check --simulate --trace`` writes), and around them what the text says: the
connectors and mates of the assembled scene, each element's declaration (file and line) and the
line ranges of the blocks that define it, so that a click can reveal a line and a cursor can light
an element.  Positions are metres, quaternions (w, x, y, z), lines 1-based.
"""

from __future__ import annotations

import os
from typing import Any

# mjtGeom values (MuJoCo's C enum; stable across versions)
GEOM_KINDS = {0: "plane", 2: "sphere", 3: "capsule", 4: "ellipsoid", 5: "cylinder", 6: "box", 7: "mesh"}
PLANE_EXTENT = 20.0  # half size drawn for an infinite plane (MuJoCo size 0)


def _r(x: float, nd: int = 6) -> float:
    return round(float(x), nd) + 0.0


def _src(source: Any) -> dict | None:
    if source is None or not getattr(source, "file", None) or source.line <= 0:
        return None
    return {"file": os.path.abspath(source.file), "line": source.line, "column": max(source.column, 1)}


def body_ids(sim: Any) -> list[tuple[int, str]]:
    """(MuJoCo body id, OpenPLX path) of every body the page shows, in the order poses are sent."""
    m, names = sim.model, sim.prepared.compiled.names
    out = []
    for b in range(1, m.nbody):
        path = names.path("body", m.body(b).name)
        if path is not None and sim.prepared.compiled.scene.body(path) is not None:
            out.append((b, path))
    return out


def poses(sim: Any, ids: list[tuple[int, str]]) -> list[float]:
    """x, y, z, qw, qx, qy, qz of each body of ``ids``, flat (the world pose of the body frame)."""
    sim._fresh()
    d = sim.data
    out: list[float] = []
    for b, _ in ids:
        out += [_r(v) for v in d.xpos[b]]
        out += [_r(v, 7) for v in d.xquat[b]]
    return out


def scene_json(sim: Any, generation: int) -> dict:
    """The whole scene for the page (sent on every good load)."""
    compiled = sim.prepared.compiled
    names = compiled.names
    ids = body_ids(sim)
    ranges = _ranges(sim.prepared)
    bodies = [{"path": path, "dynamic": bool(compiled.scene.body(path).is_dynamic),
               "src": _src(names.sources.get(path)), "ranges": ranges.get(path, [])} for _, path in ids]
    geoms, meshes = _geoms(sim, ids, ranges)
    connectors, cindex = _connectors(compiled.scene, ids, ranges)
    mates = [{"path": mt.path, "kind": mt.kind, "connectors": [cindex[c.path] for c in mt.connectors],
              "src": _src(mt.source), "ranges": ranges.get(mt.path, [])}
             for mt in compiled.scene.mates if all(c.path in cindex for c in mt.connectors)]
    return {"model": sim.model_name, "file": os.path.abspath(sim.path), "generation": generation,
            "timestep": sim.timestep, "bodies": bodies, "geoms": geoms, "meshes": meshes,
            "connectors": connectors, "mates": mates, "poses": poses(sim, ids), "time": _r(sim.time)}


def _geoms(sim: Any, ids: list[tuple[int, str]], ranges: dict) -> tuple[list[dict], list[dict]]:
    """Every drawable geom of the MuJoCo model in its body's frame, and the meshes they use."""
    m, names = sim.model, sim.prepared.compiled.names
    index = {b: i for i, (b, _) in enumerate(ids)}
    geoms, meshes, mesh_index = [], [], {}
    for g in range(m.ngeom):
        kind = GEOM_KINDS.get(int(m.geom_type[g]))
        bid = int(m.geom_bodyid[g])
        if kind is None or (bid != 0 and bid not in index):
            continue
        path = names.path("geom", m.geom(g).name) or m.geom(g).name
        size = [_r(v) for v in m.geom_size[g]]
        if kind == "plane":
            size = [size[0] or PLANE_EXTENT, size[1] or PLANE_EXTENT, 0.0]
        item = {"path": path, "body": index.get(bid, -1), "kind": kind, "size": size,
                "pos": [_r(v) for v in m.geom_pos[g]], "quat": [_r(v, 7) for v in m.geom_quat[g]],
                "rgba": [_r(v, 3) for v in m.geom_rgba[g]], "group": int(m.geom_group[g]),
                "src": _src(names.sources.get(path)), "ranges": ranges.get(path, [])}
        if kind == "mesh":
            mid = int(m.geom_dataid[g])
            if mid not in mesh_index:
                mesh_index[mid] = len(meshes)
                meshes.append(_mesh(m, mid))
            item["mesh"] = mesh_index[mid]
        geoms.append(item)
    return geoms, meshes


def _connectors(scene: Any, ids: list[tuple[int, str]], ranges: dict) -> tuple[list[dict], dict[str, int]]:
    """The connectors of the scene's mates and controllers, in their body's frame (world: body -1)."""
    from plxtools.check.scene import default_normal, normalize, orthogonalize

    owner_of = {p: i for i, (_, p) in enumerate(ids)}
    out, index = [], {}
    for c in scene.connectors():
        owner = owner_of.get(c.body, -1) if c.body is not None else -1
        if owner < 0 and c.body is not None:  # on a body the page does not draw: place it in the world
            pos, axis, normal = scene.connector_world(c)
        else:
            pos, axis, normal = c.local_pos, c.main_axis, c.normal
        axis = normalize(axis)
        normal = orthogonalize(normal if normal is not None else default_normal(axis), axis)
        index[c.path] = len(out)
        out.append({"path": c.path, "body": owner, "pos": [_r(v) for v in pos], "axis": [_r(v) for v in axis],
                    "normal": [_r(v) for v in normal], "src": _src(c.source), "ranges": ranges.get(c.path, [])})
    return out, index


def _mesh(m: Any, mid: int) -> dict:
    va, vn = int(m.mesh_vertadr[mid]), int(m.mesh_vertnum[mid])
    fa, fn = int(m.mesh_faceadr[mid]), int(m.mesh_facenum[mid])
    return {"vert": [_r(v, 5) for v in m.mesh_vert[va:va + vn].ravel()],
            "face": [int(i) for i in m.mesh_face[fa:fa + fn].ravel()]}


def _ranges(prepared: Any) -> dict[str, list[list]]:
    """Path -> [file, first line, last line] of every block that defines the object: its own
    declaration and the user's models it is built from (a cursor there lights it)."""
    fc = prepared.fc
    asm = fc.assembly
    program = prepared.workspace.program if prepared.workspace is not None else None
    out: dict[str, list[list]] = {}
    if asm is None or program is None:
        return out
    for o in asm.owned[1:]:
        spans = []
        template = o.decl[0] if isinstance(o.decl, tuple) and o.decl else None  # (template, scope, depth)
        node, unit = getattr(template, "stmt", None), getattr(template, "unit", None)
        if node is not None and unit is not None and not getattr(unit, "official", False):
            spans.append([os.path.abspath(unit.path), node.span.start.line + 1, node.span.end.line + 1])
        try:
            layers = [o.model, *program.ancestors(o.model)]
        except Exception:  # noqa: BLE001 - an unresolvable model has no more blocks to show
            layers = [o.model]
        for sym in layers:
            if sym.unit is None or sym.unit.official or sym.stmt is None:
                continue
            spans.append([os.path.abspath(sym.unit.path), sym.stmt.span.start.line + 1, sym.stmt.span.end.line + 1])
        uniq = []
        for s in spans:
            if s not in uniq:
                uniq.append(s)
        out[o.display] = uniq
    return out


def finding_json(d: Any) -> dict:
    """A diagnostic as the page lists it (1-based line and column; no location: line 0)."""
    span = getattr(d, "span", None)
    has_place = span is not None and bool(getattr(d, "file", ""))
    return {"file": os.path.abspath(d.file) if has_place else "", "line": span.start.line + 1 if has_place else 0,
            "column": span.start.column + 1 if has_place else 0,
            "severity": getattr(getattr(d, "severity", None), "value", "error"), "code": getattr(d, "code", ""),
            "message": getattr(d, "message", str(d))}
