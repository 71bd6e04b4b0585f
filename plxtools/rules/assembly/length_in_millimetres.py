"""A dynamic body's geometry is hundreds of metres or more in size, most likely a length written in
millimetres (`x: 3300` for a 3.3 m chassis): reported at the number, with the value in metres.

## Why it matters

OpenPLX lengths are metres. A chassis 3300 m long weighs millions of tonnes, lands on wheels a
thousand times smaller and blows the simulation up; `plx check --simulate` then reports a blow-up
(A101) or an overlap of hundreds of metres somewhere else, never the number that caused it.

## Example

```openplx
Chassis is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size:
            x: 3300
            y: 1.7
            z: 1.44
```

## Use instead

```openplx
Chassis is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size:
            x: 3.3
            y: 1.7
            z: 1.44
```
"""

# The plausibility model (docs/plausibility.md). Which attributes are lengths is read from the
# bundles: the Real and Math.Vec3 attributes that a Physics3D contact geometry type declares (a
# Box's `size`, a Cylinder's `radius` and `height`...; not `scale`, a ratio, nor mesh vertices).
# A written length of a geometry on a dynamic body is suspicious when it is at least 100 m and
# either at least 1000 m (no single rigid part that moves is a kilometre long) or at least 100
# times the smallest length written for the same geometry (3300 beside 1.7: one number in
# millimetres among numbers in metres). Static bodies (`is_dynamic: false`: grounds, terrain
# tiles) are left alone, whatever their size; so is anything computed.

from __future__ import annotations

from plxtools.model.symbols import ModelSym
from plxtools.rules.blocks import declaration_blocks, written_static
from plxtools.rules.literals import literal
from plxtools.syntax import ast

GEOMETRY = ("Physics3D", "Geometries", "ContactGeometry")
SUSPICIOUS, SURELY, RATIO = 100.0, 1000.0, 100.0
_WHAT = {"x": "long", "y": "wide", "z": "high", "radius": "in radius", "height": "high", "length": "long"}


def check(facts, report) -> None:
    program, unit = facts.program, facts.unit
    base = program.lookup_outside_visibility(list(GEOMETRY))
    if unit.official or not isinstance(base, ModelSym):
        return
    for owner, body in declaration_blocks(facts.judged):
        if written_static(body):
            continue
        for g in body:
            if isinstance(g, ast.Declaration) and g.body and g.type is not None and g.keyword in ("is", "becomes"):
                ty = program.resolve_type_expr(g.type, unit)
                if ty.model is not None and not ty.array and program.is_subtype(ty.model, base):
                    _judge(program, ty.model, base, owner, g, report)


def _length_names(program, model: ModelSym, base: ModelSym) -> set[str]:
    """The geometry's own length attributes: Real or Math.Vec3 members declared below `base`."""
    out = set()
    for name, mem in program.all_members(model).items():
        owner = mem.owner
        if owner is base or not program.is_subtype(owner, base) or "scale" in name:
            continue
        ty = program.member_type(mem)
        if not ty.array and (ty.primitive == "Real" or (ty.model is not None and ty.model.qname == "Math.Vec3")):
            out.add(name)
    return out


def _written(body, names: set[str]):
    """(attribute path, value, expression) for each number the geometry's block writes for a length."""
    for s in body:
        if not isinstance(s, ast.Assignment) or not s.path.parts or s.path.parts[0].name not in names:
            continue
        key = ".".join(p.name for p in s.path.parts)
        v = literal(s.value) if s.value is not None else None
        if isinstance(v, float):
            yield key, v, s.value
        elif isinstance(v, list) and isinstance(s.value, ast.Brace):
            for axis, x, e in zip("xyz", v, s.value.items):
                yield f"{key}.{axis}", x, e
        for t in s.body or []:
            w = literal(t.value) if isinstance(t, ast.Assignment) and t.value is not None else None
            if isinstance(w, float):
                yield f"{key}." + ".".join(p.name for p in t.path.parts), w, t.value


def _judge(program, model: ModelSym, base: ModelSym, owner, geometry, report) -> None:
    sizes = [(k, v, e) for k, v, e in _written(geometry.body, _length_names(program, model, base)) if v > 0]
    if not sizes:
        return
    smallest = min(v for _k, v, _e in sizes)
    for key, v, e in sizes:
        if v >= SURELY or (v >= SUSPICIOUS and v >= RATIO * smallest):
            body = owner.path.text
            what = _WHAT.get(key.rsplit(".", 1)[-1], "in size")
            report(f"{key}: {v:g} makes {body}'s {model.name.lower()} {v:g} m {what}, on a body that moves: lengths "
                   f"are in metres", e.span,
                   help=f"if it is {v:g} mm, write {v / 1000:g}")
            return  # one per geometry: the others follow from the same unit
