"""`inertia.mass: 0` written on a dynamic body: 0 means 'from the geometries', so the body gets its
geometries' volume times their density; the message says how much when the file decides it.

## How it decides

A mass of 0 is the bundles' way of saying "compute it from the geometries" (volume times the
material's density, 1000 kg/m^3 unless a material says otherwise), so a hand-written 0 does not
make a body light or massless: it gets the mass of its geometries, which can be far from what was
meant (a 0.26 m wheel of the default material weighs 35 kg). The message says what mass it will
get when the file decides it (a Box, Cylinder, Sphere or Capsule with written sizes and a material
whose density is written); otherwise how it is computed. A static body (`is_dynamic: false`) has
no mass to speak of and is left alone.

## Why it matters

The author almost always meant something else: a placeholder to fill later, a massless link (which
a dynamic body cannot be), or the mass of another body. The simulation silently uses the
geometry's mass instead.

## Example

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Cylinder:
        radius: 0.26
        height: 0.165
    inertia.mass: 0
```

## Use instead

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Cylinder:
        radius: 0.26
        height: 0.165
    inertia.mass: 10
```
"""

from __future__ import annotations

import math

from plxtools.rules.blocks import declaration_blocks, written_static
from plxtools.rules.literals import literal
from plxtools.syntax import ast

MASS = "Physics3D.Bodies.Inertia.mass"
DEFAULT_DENSITY = 1000.0  # Physics.Geometries.Material.density's default in the bundles


def check(facts, report) -> None:
    tree = facts.tree
    target = None
    consts = facts.table_by_name("const densities", lambda: _const_densities(tree))
    for owner, body in declaration_blocks(facts.judged):
        if written_static(body):
            continue
        for stmt, value in _mass_values(body):
            if literal(value) != 0.0:
                continue
            target = target if target is not None else {(o.span.start.offset, o.span.end.offset): o.target
                                                        for o in facts.occurrences if o.kind in ("attribute", "definition")}
            last = stmt.path.parts[-1]
            if getattr(target.get((last.span.start.offset, last.span.end.offset)), "qname", None) != MASS:
                continue
            _report(report, owner, body, value, consts)


def _mass_values(body):
    for s in body:
        if isinstance(s, ast.Assignment):
            names = [p.name for p in s.path.parts]
            if names == ["inertia", "mass"] and s.value is not None:
                yield s, s.value
            elif names == ["inertia"] and s.body:
                for t in s.body:
                    if isinstance(t, ast.Assignment) and [p.name for p in t.path.parts] == ["mass"] and t.value:
                        yield t, t.value


def _const_densities(tree) -> dict[str, float]:
    out = {}
    for s in tree.statements:
        if isinstance(s, ast.Declaration) and s.const and s.body:
            for t in s.body:
                if isinstance(t, ast.Assignment) and [p.name for p in t.path.parts] == ["density"]:
                    v = literal(t.value) if t.value is not None else None
                    if isinstance(v, float):
                        out[s.path.parts[-1].name] = v
    return out


def _written_sizes(geometry: ast.Declaration) -> dict[str, float]:
    """The geometry's sizes written as numbers: `radius`, `size.x` (from `size: {..}`, `size.x: ..`
    or a `size:` block)."""
    vals: dict[str, float] = {}
    for s in geometry.body or []:
        if not isinstance(s, ast.Assignment):
            continue
        names = [p.name for p in s.path.parts]
        v = literal(s.value) if s.value is not None else None
        if isinstance(v, float):
            vals[".".join(names)] = v
        elif isinstance(v, list) and names == ["size"]:
            vals.update(zip(("size.x", "size.y", "size.z"), v))
        for t in s.body or []:
            w = literal(t.value) if isinstance(t, ast.Assignment) and t.value is not None else None
            if isinstance(w, float):
                vals[".".join(names + [p.name for p in t.path.parts])] = w
    return vals


def _volume(geometry: ast.Declaration) -> tuple[float, str] | None:
    kind = geometry.type.alternatives[0].name.parts[-1].name if geometry.type and geometry.type.alternatives else ""
    vals = _written_sizes(geometry)
    r, h = vals.get("radius"), vals.get("height")
    box = [vals.get(k) for k in ("size.x", "size.y", "size.z")]
    if kind == "Box" and None not in box:
        return box[0] * box[1] * box[2], "box {:g} x {:g} x {:g} m".format(*box)
    if kind in ("Cylinder", "Capsule") and r is not None and h is not None:
        ends = 4 / 3 * math.pi * r ** 3 if kind == "Capsule" else 0.0
        return math.pi * r * r * h + ends, f"{kind.lower()} r {r:g} m, h {h:g} m"
    if kind == "Sphere" and r is not None:
        return 4 / 3 * math.pi * r ** 3, f"sphere r {r:g} m"
    return None


def _density(geometry: ast.Declaration, consts: dict[str, float]) -> float | None:
    for s in geometry.body or []:
        if isinstance(s, ast.Assignment) and [p.name for p in s.path.parts] == ["material"]:
            name = s.value.ident.name if isinstance(s.value, ast.Name) else None
            return consts.get(name) if name else None
    return DEFAULT_DENSITY


def _report(report, owner, body, value, consts) -> None:
    geoms = [s for s in body if isinstance(s, ast.Declaration) and s.keyword in ("is", "becomes") and s.body
             and s.path.parts[-1].name == "geometry"]
    what = "the mass of its geometries (their volume times their material's density, 1000 kg/m^3 by default)"
    if len(geoms) == 1:
        vol, rho = _volume(geoms[0]), _density(geoms[0], consts)
        if vol is not None and rho is not None:
            what = f"{vol[0] * rho:.4g} kg, the mass of its geometry ({vol[1]}, {rho:g} kg/m^3)"
    name = owner.path.text
    report(f"inertia.mass: 0 does not make {name} massless: a dynamic body's mass 0 means 'from the geometries', "
           f"so it gets {what}", value.span,
           help="write the mass it should have in kg, or delete the line to say 'from the geometries' on purpose")
